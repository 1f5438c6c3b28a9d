//! The regularisation R of the friction bound µ|Rσ_ν| (2.7) on the Γ3 nodes (model §4).

use super::law::Regularization;
use super::surface::ContactSurface;
use crate::error::{Error, Result};
use crate::problem::Problem;
use kiddo::{ImmutableKdTree, SquaredEuclidean};

/// The regularisation R of the friction bound as a sparse averaging operator on the Γ3 nodes.
pub struct Mollifier {
    /// For each node, (j, weight) with weights summing to 1; empty for R = identity.
    rows: Vec<Vec<(usize, f64)>>,
}

impl Mollifier {
    /// R on `surface`: identity, or the mollifier of its radius.
    pub fn new(
        problem: &Problem,
        surface: &ContactSurface,
        regularization: Regularization,
    ) -> Result<Self> {
        let Regularization::Mollifier { radius } = regularization else {
            return Ok(Self { rows: Vec::new() });
        };
        // Neighbourhoods by radius queries in a k-d tree of the Γ3 nodes, not all pairs.
        let points: Vec<[f64; 3]> =
            (0..surface.len()).map(|i| surface.position3(problem, i)).collect();
        let tree = ImmutableKdTree::new_from_slice(&points).map_err(|e| {
            Error::Input(format!("friction.regularization: the k-d tree of the Γ3 nodes: {e:?}"))
        })?;
        let rows = points
            .iter()
            .map(|xi| {
                let mut row: Vec<(usize, f64)> = tree
                    .query(xi)
                    .within::<SquaredEuclidean<f64>>(radius * radius)
                    .unsorted()
                    .execute()
                    .into_iter()
                    .filter_map(|found| {
                        let (j, t) = (found.item as usize, found.distance / (radius * radius));
                        (t < 1.0).then(|| (j, surface.weight[j] * (1.0 - t).powi(2)))
                    })
                    .collect();
                row.sort_by_key(|&(j, _)| j);
                let total: f64 = row.iter().map(|(_, w)| w).sum();
                row.iter_mut().for_each(|(_, w)| *w /= total);
                row
            })
            .collect();
        Ok(Self { rows })
    }

    /// R σ_ν on the Γ3 nodes.
    pub fn apply(&self, sigma_nu: &[f64]) -> Vec<f64> {
        if self.rows.is_empty() {
            return sigma_nu.to_vec();
        }
        self.rows.iter().map(|row| row.iter().map(|&(j, w)| w * sigma_nu[j]).sum()).collect()
    }

    /// Row i of R: (j, R_ij).
    pub fn row(&self, i: usize) -> Vec<(usize, f64)> {
        self.rows.get(i).cloned().unwrap_or_else(|| vec![(i, 1.0)])
    }
}
