//! The multipliers on the Γ3 nodes and the normal stress they give (model §6).

use super::model::ContactModel;
use super::surface::ContactSurface;
use crate::dofs::DofMap;

/// The multipliers on the Γ3 nodes.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ContactState {
    /// λ_c: contact pressure of the rigid stop \[stress\].
    pub lambda_c: Vec<f64>,
    /// λ_f: friction traction (σ_τ = −λ_f) \[stress\], 3 components (d used).
    pub lambda_f: Vec<[f64; 3]>,
}

impl ContactState {
    /// λ = 0 on `n` nodes.
    pub fn cold(n: usize) -> Self {
        Self { lambda_c: vec![0.0; n], lambda_f: vec![[0.0; 3]; n] }
    }

    /// σ_ν = −(λ_c + h_ν(ϕ − ϕ0) p_ν(u_ν − g_a)) on the Γ3 nodes at x (model §6) \[stress\].
    pub fn normal_stress(
        &self,
        dofs: &DofMap,
        surface: &ContactSurface,
        model: &ContactModel,
        x: &[f64],
    ) -> Vec<f64> {
        (0..surface.len())
            .map(|i| {
                let (u_nu, _) = surface.split(dofs, x, i);
                let phi = surface.phi(dofs, x, i);
                -(self.lambda_c[i] + model.pressure(u_nu, phi, surface.gap[i]))
            })
            .collect()
    }
}
