//! The contact model on Γ3 (model §4, §6): the laws of PV1 and PV2, the multipliers and the
//! statuses of the nodes, the normal stress σ_ν and the friction bound s = µ|Rσ_ν|.

use super::ContactSurface;
use super::foundation::Foundation;
use super::law::{Conduction, Friction, NormalCompliance};
use super::mollifier::Mollifier;
use crate::dofs::DofMap;
use crate::problem::Problem;

/// The contact model: normal compliance, and for PV2 friction and conduction.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactModel {
    /// p_ν, h_ν, the gap and the stop.
    pub compliance: NormalCompliance,
    /// `None`: PV1 (frictionless, nonconductive). `Some`: PV2.
    pub pv2: Option<(Friction, Conduction)>,
    /// The foundation's surface, which sets the gap of every Γ3 node (model §12).
    pub foundation: Foundation,
    /// ϕ0: the potential of the foundation \[potential\], which h_ν and φ_L read.
    pub phi0: f64,
}

impl ContactModel {
    /// The arguments of the laws at a node of gap g_a,i: (s, t) = (u_ν − g_a,i, ϕ − ϕ0)
    /// [length, potential].
    pub fn arguments(&self, u_nu: f64, phi: f64, gap: f64) -> (f64, f64) {
        (u_nu - gap, phi - self.phi0)
    }

    /// The compliance pressure h_ν(ϕ − ϕ0) p_ν(u_ν − g_a,i) \[stress\].
    pub fn pressure(&self, u_nu: f64, phi: f64, gap: f64) -> f64 {
        let (s, t) = self.arguments(u_nu, phi, gap);
        self.compliance.pressure(s, t)
    }

    /// (∂/∂u_ν, ∂/∂ϕ) of [`ContactModel::pressure`].
    pub fn pressure_derivative(&self, u_nu: f64, phi: f64, gap: f64) -> (f64, f64) {
        let (s, t) = self.arguments(u_nu, phi, gap);
        self.compliance.pressure_derivative(s, t)
    }

    /// The conduction flux ψ(u_ν − g_a,i) φ_L(ϕ − ϕ0) [charge/length^(d−1)]; 0 without
    /// conduction (PV1).
    pub fn flux(&self, u_nu: f64, phi: f64, gap: f64) -> f64 {
        let (s, t) = self.arguments(u_nu, phi, gap);
        self.pv2.as_ref().map_or(0.0, |(_, conduction)| conduction.flux(s, t))
    }

    /// (∂/∂u_ν, ∂/∂ϕ) of [`ContactModel::flux`].
    pub fn flux_derivative(&self, u_nu: f64, phi: f64, gap: f64) -> (f64, f64) {
        let (s, t) = self.arguments(u_nu, phi, gap);
        self.pv2.as_ref().map_or((0.0, 0.0), |(_, conduction)| conduction.flux_derivative(s, t))
    }

    /// "PV1" or "PV2".
    pub fn name(&self) -> &'static str {
        if self.pv2.is_some() { "PV2" } else { "PV1" }
    }
}

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
}

/// State of a Γ3 node at the solution.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NodeStatus {
    /// σ_ν = 0: no contact force.
    Separated,
    /// σ_ν < 0 in PV1.
    Contact,
    /// PV2, σ_ν < 0 and ‖λ_f‖ < s: u_τ = 0.
    Stick,
    /// PV2, σ_ν < 0 and ‖λ_f‖ = s.
    Slip,
}

impl NodeStatus {
    /// The name used in outputs.
    pub fn name(self) -> &'static str {
        match self {
            Self::Separated => "separated",
            Self::Contact => "contact",
            Self::Stick => "stick",
            Self::Slip => "slip",
        }
    }
}

/// σ_ν = −(λ_c + h_ν(ϕ − ϕ0) p_ν(u_ν − g_a)) on the Γ3 nodes (model §6).
pub fn normal_stress(
    dofs: &DofMap,
    surface: &ContactSurface,
    model: &ContactModel,
    x: &[f64],
    state: &ContactState,
) -> Vec<f64> {
    (0..surface.len())
        .map(|i| {
            let (u_nu, _) = surface.split(dofs, x, i);
            let phi = surface.phi(dofs, x, i);
            -(state.lambda_c[i] + model.pressure(u_nu, phi, surface.gap[i]))
        })
        .collect()
}

/// σ_ν at (x, λ) ([`normal_stress`]) and the friction bound s of `friction` (µ per node and
/// R; [`friction_bound`]), 0 without friction, on the Γ3 nodes \[stress\]: what an outer step
/// records, and what the exact solver's active-set check reads.
pub fn stress_and_bound(
    (dofs, surface): (&DofMap, &ContactSurface),
    model: &ContactModel,
    friction: Option<(&[f64], &Mollifier)>,
    x: &[f64],
    state: &ContactState,
) -> (Vec<f64>, Vec<f64>) {
    let sigma_nu = normal_stress(dofs, surface, model, x, state);
    let s = match friction {
        Some((mu, mollifier)) => friction_bound(mu, mollifier, &sigma_nu),
        None => vec![0.0; surface.len()],
    };
    (sigma_nu, s)
}

/// The friction bound s = µ |R σ_ν| on the Γ3 nodes \[stress\], (2.7): `mu` per node and the
/// regularisation R of σ_ν.
pub fn friction_bound(mu: &[f64], mollifier: &Mollifier, sigma_nu: &[f64]) -> Vec<f64> {
    mollifier
        .apply(sigma_nu)
        .iter()
        .zip(mu)
        .map(|(r_sigma, mu)| node_bound(*mu, *r_sigma))
        .collect()
}

/// s = µ |R σ_ν| at one node, from µ and (R σ_ν)_i \[stress\].
pub fn node_bound(mu: f64, r_sigma_nu: f64) -> f64 {
    mu * r_sigma_nu.abs()
}

/// µ on each Γ3 node: the case's µ, or the mean of the µ of the parts a node belongs to.
pub fn nodal_mu(problem: &Problem, surface: &ContactSurface, friction: &Friction) -> Vec<f64> {
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
