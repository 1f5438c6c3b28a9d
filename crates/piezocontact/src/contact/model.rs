//! The contact model on Γ3 (model §4, §6): the laws of PV1 and PV2 and where the foundation
//! is.

use super::foundation::Foundation;
use super::law::{Conduction, Friction, NormalCompliance};

/// The contact model: normal compliance, and for PV2 friction and conduction.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactModel {
    /// p_ν, h_ν, the gap and the stop.
    pub compliance: NormalCompliance,
    /// Regularised Coulomb friction (PV2); `None`: frictionless (PV1).
    pub friction: Option<Friction>,
    /// The conductive foundation (PV2); `None`: nonconductive (PV1).
    pub conduction: Option<Conduction>,
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
        self.conduction.as_ref().map_or(0.0, |conduction| conduction.flux(s, t))
    }

    /// (∂/∂u_ν, ∂/∂ϕ) of [`ContactModel::flux`].
    pub fn flux_derivative(&self, u_nu: f64, phi: f64, gap: f64) -> (f64, f64) {
        let (s, t) = self.arguments(u_nu, phi, gap);
        self.conduction.as_ref().map_or((0.0, 0.0), |conduction| conduction.flux_derivative(s, t))
    }

    /// Whether this is PV2 (friction and conduction), solved by Algorithm 1, rather than PV1
    /// (Algorithm 3).
    pub fn is_pv2(&self) -> bool {
        self.friction.is_some() || self.conduction.is_some()
    }

    /// "PV1" or "PV2".
    pub fn name(&self) -> &'static str {
        if self.is_pv2() { "PV2" } else { "PV1" }
    }
}
