//! Friction on the Γ3 nodes (model §4): µ_i per node, the regularisation R of the normal
//! stress, and the friction bound of (2.7),
//!
//! ```text
//! s_i = µ_i |(R σ_ν)_i|
//! ```
//!
//! µ_i is the case's µ, or the mean of the µ of the contact parts node i belongs to.

use super::law::Friction;
use super::mollifier::Mollifier;
use super::surface::ContactSurface;
use crate::error::Result;
use crate::problem::Problem;

/// µ_i and R on the nodes of a Γ3: what the friction bound s = µ|Rσ_ν| reads.
pub struct NodalFriction {
    /// µ_i on each Γ3 node [-].
    pub mu: Vec<f64>,
    /// R.
    pub mollifier: Mollifier,
}

impl NodalFriction {
    /// µ_i and R of `friction` on `surface`.
    pub fn new(problem: &Problem, surface: &ContactSurface, friction: &Friction) -> Result<Self> {
        Ok(Self {
            mu: nodal_mu(problem, surface, friction),
            mollifier: Mollifier::new(problem, surface, friction.regularization)?,
        })
    }

    /// R σ_ν on the Γ3 nodes \[stress\].
    pub fn regularised(&self, sigma_nu: &[f64]) -> Vec<f64> {
        self.mollifier.apply(sigma_nu)
    }

    /// s_i = µ_i |(R σ_ν)_i| at node i, from (R σ_ν)_i \[stress\].
    pub fn node_bound(&self, i: usize, r_sigma_nu: f64) -> f64 {
        self.mu[i] * r_sigma_nu.abs()
    }

    /// The friction bound s on the Γ3 nodes from σ_ν \[stress\].
    pub fn bound(&self, sigma_nu: &[f64]) -> Vec<f64> {
        let r_sigma = self.regularised(sigma_nu);
        (0..r_sigma.len()).map(|i| self.node_bound(i, r_sigma[i])).collect()
    }
}

/// µ on each Γ3 node: the case's µ, or the mean of the µ of the parts a node belongs to.
fn nodal_mu(problem: &Problem, surface: &ContactSurface, friction: &Friction) -> Vec<f64> {
    let mut sum = vec![0.0; surface.len()];
    let mut count = vec![0usize; surface.len()];
    let index: std::collections::HashMap<usize, usize> =
        surface.nodes.iter().enumerate().map(|(i, &n)| (n, i)).collect();
    for &(part, mu) in &friction.mu_parts {
        let mut nodes: Vec<usize> = problem.mesh.part_facets(part).flatten().copied().collect();
        nodes.sort_unstable();
        nodes.dedup();
        for i in nodes.iter().filter_map(|n| index.get(n)) {
            sum[*i] += mu;
            count[*i] += 1;
        }
    }
    (0..surface.len())
        .map(|i| if count[i] > 0 { sum[i] / count[i] as f64 } else { friction.mu })
        .collect()
}
