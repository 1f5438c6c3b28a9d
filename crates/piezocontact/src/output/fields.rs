//! The contact fields of `solution.vtu`: each Γ3 node's status, pressure, friction traction
//! and gap, from the Γ3 table.

use super::vtu::Field;
use crate::contact::{ContactSurface, NodeStatus};
use crate::mesh::Mesh;
use crate::report::Row;

/// The contact fields of solution.vtu at every node (0 off Γ3).
pub struct ContactFields {
    /// 1 separated, 2 contact or stick, 3 slip.
    status: Vec<f64>,
    /// −σ_ν [stress].
    pressure: Vec<f64>,
    /// σ_τ, 3 components [stress].
    traction: Vec<f64>,
    /// The gap [length].
    gap: Vec<f64>,
}

impl ContactFields {
    /// The fields of `solution` with its Γ3 `rows`.
    pub fn new(mesh: &Mesh, surface: &ContactSurface, rows: &[Row]) -> Self {
        let n = mesh.n_nodes();
        let (mut status, mut pressure, mut gap) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        let mut traction = vec![0.0; 3 * n];
        for (row, &node) in rows.iter().zip(&surface.nodes) {
            status[node] = match row.status {
                NodeStatus::Separated => 1.0,
                NodeStatus::Contact | NodeStatus::Stick => 2.0,
                NodeStatus::Slip => 3.0,
            };
            pressure[node] = -row.sigma_nu;
            gap[node] = row.gap;
            traction[3 * node..3 * node + 3].copy_from_slice(&row.friction_traction);
        }
        Self { status, pressure, traction, gap }
    }

    /// As point fields of a .vtu file.
    pub fn fields(&self) -> [Field<'_>; 4] {
        [
            Field { name: "contact_status", components: 1, values: &self.status },
            Field { name: "contact_pressure", components: 1, values: &self.pressure },
            Field { name: "friction_traction", components: 3, values: &self.traction },
            Field { name: "gap", components: 1, values: &self.gap },
        ]
    }
}
