//! The data of a static piezoelectric problem (\[P\] (2.1)–(2.4)): mesh, material, boundary
//! roles and loads. [`Problem::new`] checks the roles once.

use crate::error::{Error, Result};
use crate::material::Material;
use crate::mesh::Mesh;
use std::sync::Arc;

/// A vector field x ↦ v(x) with d components (loads, prescribed displacements).
pub type VectorField = Arc<dyn Fn(&[f64]) -> Vec<f64> + Send + Sync>;
/// A scalar field x ↦ s(x).
pub type ScalarField = Arc<dyn Fn(&[f64]) -> f64 + Send + Sync>;

/// A constant vector field.
pub fn constant_vector(v: Vec<f64>) -> VectorField {
    Arc::new(move |_| v.clone())
}

/// A constant scalar field.
pub fn constant_scalar(s: f64) -> ScalarField {
    Arc::new(move |_| s)
}

/// Boundary roles of \[P\] (2.4), each a list of mesh part indices. Parts with no role are
/// traction free and charge free (natural conditions).
#[derive(Clone, Default)]
pub struct Boundary {
    /// Γ1: u = u_D (0 in the model).
    pub clamped: Vec<usize>,
    /// Γa: ϕ = ϕ_D (0 in the model).
    pub grounded: Vec<usize>,
    /// Γ3: the contact surface.
    pub contact: Vec<usize>,
    /// Γ2 with its traction density f2 \[stress\].
    pub traction: Vec<(usize, VectorField)>,
    /// Γb with its surface charge density q2 [charge/length^(d−1)].
    pub charge: Vec<(usize, ScalarField)>,
    /// Prescribed displacement on Γ1 \[length\]; `None` is the model's u = 0. Used by
    /// verification problems (patch tests, manufactured solutions).
    pub clamped_value: Option<VectorField>,
    /// Prescribed potential on Γa \[potential\]; `None` is the model's ϕ = 0.
    pub grounded_value: Option<ScalarField>,
}

/// Body loads of (2.1).
#[derive(Clone, Default)]
pub struct BodyLoads {
    /// f0: body force density [stress/length].
    pub f0: Option<VectorField>,
    /// q0: volume charge density [charge/length^d].
    pub q0: Option<ScalarField>,
}

/// A checked problem.
#[derive(Clone)]
pub struct Problem {
    /// The mesh.
    pub mesh: Mesh,
    /// The material.
    pub material: Material,
    /// Boundary roles and data.
    pub boundary: Boundary,
    /// Body loads.
    pub loads: BodyLoads,
}

impl Problem {
    /// Checks that Γ1 and Γa have positive measure (else the system is singular: Korn's and
    /// Friedrichs' inequalities (2.9) need them), and that Γ3 shares no facet with Γ1 ∪ Γ2 ∪
    /// Γa ∪ Γb, nor Γa with Γb, nor Γ1 with Γ2.
    pub fn new(
        mesh: Mesh,
        material: Material,
        boundary: Boundary,
        loads: BodyLoads,
    ) -> Result<Self> {
        if material.dim != mesh.dim() {
            return Err(Error::InvalidParameter {
                name: "material dimension".into(),
                value: material.dim.to_string(),
                requirement: format!("must equal the mesh dimension {}", mesh.dim()),
            });
        }
        let problem = Self { mesh, material, boundary, loads };
        problem.check_roles()?;
        Ok(problem)
    }

    fn check_roles(&self) -> Result<()> {
        let b = &self.boundary;
        let measure =
            |parts: &[usize]| parts.iter().map(|&p| self.mesh.part_measure(p)).sum::<f64>();
        if measure(&b.clamped) <= 0.0 {
            return Err(Error::EmptyRole {
                role: "Γ1 (clamped)",
                why: "the displacement must be fixed on a part of positive measure, or the body \
                      can move freely and the system is singular; name at least one non-empty \
                      boundary part as clamped",
            });
        }
        if measure(&b.grounded) <= 0.0 {
            return Err(Error::EmptyRole {
                role: "Γa (grounded)",
                why: "the potential must be fixed on a part of positive measure, or it is only \
                      known up to a constant and the system is singular; name at least one \
                      non-empty boundary part as grounded",
            });
        }
        self.check_pieces()?;
        let traction: Vec<usize> = b.traction.iter().map(|(p, _)| *p).collect();
        let charge: Vec<usize> = b.charge.iter().map(|(p, _)| *p).collect();
        let roles: [(&'static str, &[usize]); 6] = [
            ("Γ1 (clamped)", &b.clamped),
            ("Γ2 (traction)", &traction),
            ("Γ3 (contact)", &b.contact),
            ("Γa (grounded)", &b.grounded),
            ("Γb (charge)", &charge),
            ("Γ3 (contact)", &b.contact),
        ];
        // Pairs that must be disjoint: (Γ1, Γ2), (Γ3, all others), (Γa, Γb).
        for (i, j) in [(0, 1), (2, 0), (2, 1), (2, 3), (2, 4), (3, 4)] {
            self.check_disjoint(roles[i], roles[j])?;
        }
        self.check_contact_parts_apart()
    }

    /// Checks that no two parts of Γ3 (nor one part named twice) share a facet: the facet
    /// would count twice in the nodes' weights, and every contact stress would be halved.
    fn check_contact_parts_apart(&self) -> Result<()> {
        match self.mesh.facet_shared_within(&self.boundary.contact) {
            Some((first, second, nodes)) => Err(Error::Input(format!(
                "boundary parts '{first}' and '{second}' of Γ3 (contact) share the facet with \
                 nodes {nodes:?}: a facet of Γ3 must belong to one contact part (it would count \
                 twice); name each facet in one part only"
            ))),
            None => Ok(()),
        }
    }

    /// Checks that every connected piece of the body touches Γ1 and Γa: a piece that does
    /// not can move freely (or float electrically), and the system is singular.
    fn check_pieces(&self) -> Result<()> {
        let pieces = self.mesh.pieces();
        let b = &self.boundary;
        for (role, key, parts) in [
            ("Γ1 (clamped)", "boundary.clamped", &b.clamped),
            ("Γa (grounded)", "boundary.grounded", &b.grounded),
        ] {
            let mut held = vec![false; pieces.cells.len()];
            for node in self.part_nodes(parts) {
                held[pieces.of_node[node]] = true;
            }
            let loose: Vec<String> = (0..held.len())
                .filter(|&k| !held[k] && pieces.cells[k] > 0)
                .map(|k| {
                    let (lo, hi) = &pieces.boxes[k];
                    format!(
                        "piece {} ({} elements, bounding box {lo:?}–{hi:?})",
                        k + 1,
                        pieces.cells[k]
                    )
                })
                .collect();
            if !loose.is_empty() {
                let count = pieces.cells.iter().filter(|c| **c > 0).count();
                return Err(Error::Input(format!(
                    "the body has {count} connected pieces and {} of them touch no {role} part: {}; such a piece is not held, and the system is singular: add a boundary part on it to {key}, or remove it from the mesh",
                    loose.len(),
                    loose.join("; ")
                )));
            }
        }
        Ok(())
    }

    fn check_disjoint(
        &self,
        (first_role, first): (&'static str, &[usize]),
        (second_role, second): (&'static str, &[usize]),
    ) -> Result<()> {
        match self.mesh.shared_facet(first, second) {
            Some((first, second, nodes)) => {
                Err(Error::RoleConflict { first, first_role, second, second_role, nodes })
            }
            None => Ok(()),
        }
    }

    /// Nodes of the facets of the given parts, sorted and without repetition.
    pub fn part_nodes(&self, parts: &[usize]) -> Vec<usize> {
        let mut nodes: Vec<usize> =
            parts.iter().flat_map(|&p| self.mesh.part_facets(p).flatten().copied()).collect();
        nodes.sort_unstable();
        nodes.dedup();
        nodes
    }
}
