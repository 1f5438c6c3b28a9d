//! Contact laws on Γ3, \[P\] (2.5)–(2.8) and Section 7, with the gap/penetration reading of
//! model §9. Every constant is a parameter; the paper's forms are the provided choice.

/// Normal compliance with finite penetration, (2.5):
///
/// ```text
/// u_ν ≤ g_a + g_p,   σ_ν + h_ν(ϕ − ϕ0) p_ν(u_ν − g_a) ≤ 0,   complementarity,
/// p_ν(s) = 0 (s < 0), s (0 ≤ s ≤ n_ν), n_ν (s > n_ν)
/// h_ν(s) = c_ν α_ν (|s| > S), c_ν (1 + (α_ν − 1)|s|/S) otherwise     (S = 128 in [P])
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormalCompliance {
    /// g_a: the gap, where compliance and conduction start (the paper's ρ) \[length\]; with a
    /// foundation surface, the offset added to the distance along ν_i (model §12).
    pub gap: f64,
    /// g_p ≥ 0: penetration before the rigid stop at u_ν = g_a + g_p \[length\].
    pub penetration: f64,
    /// c_ν > 0 [stress/length].
    pub c_nu: f64,
    /// α_ν > 1 [-].
    pub alpha_nu: f64,
    /// n_ν > 0: saturation of p_ν \[length\].
    pub n_nu: f64,
    /// S: the potential difference at which h_ν saturates (128 in \[P\]) \[potential\].
    pub h_nu_range: f64,
}

impl NormalCompliance {
    /// The rigid stop g_a,i + g_p at a node of gap g_a,i (the ρ of Algorithms 2 and 4)
    /// \[length\].
    pub fn stop(&self, gap: f64) -> f64 {
        gap + self.penetration
    }

    /// p_ν(s) \[length\].
    pub fn p_nu(&self, s: f64) -> f64 {
        s.clamp(0.0, self.n_nu)
    }

    /// h_ν(s) [stress/length], s = ϕ − ϕ0.
    pub fn h_nu(&self, s: f64) -> f64 {
        if s.abs() > self.h_nu_range {
            self.c_nu * self.alpha_nu
        } else {
            self.c_nu * (1.0 + (self.alpha_nu - 1.0) * s.abs() / self.h_nu_range)
        }
    }

    /// The compliance pressure h_ν(t) p_ν(s) \[stress\] at s = u_ν − g_a,i, t = ϕ − ϕ0
    /// ([`super::ContactModel::arguments`]).
    pub fn pressure(&self, s: f64, t: f64) -> f64 {
        self.h_nu(t) * self.p_nu(s)
    }

    /// A generalised derivative of the pressure: (∂/∂s, ∂/∂t) = (∂/∂u_ν, ∂/∂ϕ)
    /// [stress/length, stress/potential]. The pieces' one-sided derivatives at the kinks are
    /// taken from the side where the function is not constant.
    pub fn pressure_derivative(&self, s: f64, t: f64) -> (f64, f64) {
        let dp = if (0.0..=self.n_nu).contains(&s) { 1.0 } else { 0.0 };
        let dh = if t.abs() <= self.h_nu_range {
            self.c_nu * (self.alpha_nu - 1.0) / self.h_nu_range * t.signum()
        } else {
            0.0
        };
        (self.h_nu(t) * dp, dh * self.p_nu(s))
    }
}

/// Conductive foundation, (2.7)–(2.8): D·ν = ψ(u_ν − g_a) φ_L(ϕ − ϕ0),
/// ψ = k_e ψ0, ψ0(s) = 0 (s < 0), δ s (0 ≤ s ≤ 1/δ), 1 (s > 1/δ), φ_L = clamp(·, −L, L).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Conduction {
    /// k_e ≥ 0 [charge/(potential·length^d)].
    pub ke: f64,
    /// δ > 0 [1/length].
    pub delta: f64,
    /// L > 0 \[potential\].
    pub truncation: f64,
}

impl Conduction {
    /// ψ(s) = k_e ψ0(s).
    pub fn psi(&self, s: f64) -> f64 {
        self.ke * (self.delta * s).clamp(0.0, 1.0)
    }

    /// φ_L(s) \[potential\].
    pub fn phi_l(&self, s: f64) -> f64 {
        s.clamp(-self.truncation, self.truncation)
    }

    /// The normal charge flux ψ(s) φ_L(t) [charge/length^(d−1)] at s = u_ν − g_a,i,
    /// t = ϕ − ϕ0.
    pub fn flux(&self, s: f64, t: f64) -> f64 {
        self.psi(s) * self.phi_l(t)
    }

    /// A generalised derivative of the flux: (∂/∂s, ∂/∂t) = (∂/∂u_ν, ∂/∂ϕ).
    pub fn flux_derivative(&self, s: f64, t: f64) -> (f64, f64) {
        let dpsi = if (0.0..=1.0 / self.delta).contains(&s) { self.ke * self.delta } else { 0.0 };
        let dphi_l = if t.abs() <= self.truncation { 1.0 } else { 0.0 };
        (dpsi * self.phi_l(t), self.psi(s) * dphi_l)
    }
}

/// The regularisation operator R of the friction bound µ|Rσ_ν| (2.7).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Regularization {
    /// R = identity: local Coulomb friction.
    Identity,
    /// A mollifier average of σ_ν over the Γ3 nodes within `radius` \[length\], weighted by
    /// w_j (1 − (r/a)²)² — nonlocal Coulomb friction.
    Mollifier {
        /// a > 0 \[length\].
        radius: f64,
    },
}

/// Regularised Coulomb friction, (2.7).
#[derive(Clone, Debug, PartialEq)]
pub struct Friction {
    /// µ ≥ 0 on Γ3 [-].
    pub mu: f64,
    /// µ on particular Γ3 parts (mesh part index, µ); a node shared by several parts takes
    /// their mean.
    pub mu_parts: Vec<(usize, f64)>,
    /// R.
    pub regularization: Regularization,
    /// What the slip is measured from on a loading path (model §14).
    pub path: FrictionPath,
}

/// What the friction law's slip is measured from on a loading path (model §14).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum FrictionPath {
    /// The paper's static law at every step: u_τ, from the reference configuration.
    #[default]
    Static,
    /// Quasistatic Coulomb: u_τ − u_τ^{k−1}, the tangential displacement since the previous
    /// step (from rest at the first: the static law).
    Incremental,
}

/// State of a Γ3 node at a solution, as the laws decide it.
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

    /// The status of a node with normal stress σ_ν \[stress\] whose friction law said
    /// `friction` ([`coulomb`]'s status; `None` without friction): separated where σ_ν ≥ 0,
    /// else in contact (PV1) or sticking or slipping as the friction law says (PV2).
    pub fn at(sigma_nu: f64, friction: Option<NodeStatus>) -> Self {
        match friction {
            _ if sigma_nu >= 0.0 => Self::Separated,
            None => Self::Contact,
            Some(status) => status,
        }
    }
}

/// The rigid stop's complementarity at a node, \[P\] (2.5) written as a projection with a
/// constant c > 0 (model §10):
///
/// ```text
/// λ_c ≥ 0,  u_ν ≤ ρ,  λ_c (u_ν − ρ) = 0   ⇔   λ_c = max(0, λ_c + c(u_ν − ρ))
/// ```
///
/// Step 3 of Algorithms 2 and 4 with c = r, the exact solver's E_n, and the KKT residual's
/// contact part.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StopComplementarity {
    /// c(u_ν − ρ) \[stress\].
    pub overlap: f64,
    /// max(0, λ_c + c(u_ν − ρ)) \[stress\].
    pub projected: f64,
    /// Whether λ_c + c(u_ν − ρ) > 0: the stop holds the node (u_ν = ρ at a solution).
    pub at_stop: bool,
}

/// [`StopComplementarity`] of a node with multiplier λ_c \[stress\], normal displacement u_ν
/// and stop ρ \[length\], with the constant c [stress/length].
pub fn stop_complementarity(lambda_c: f64, c: f64, u_nu: f64, rho: f64) -> StopComplementarity {
    let overlap = c * (u_nu - rho);
    let sum = lambda_c + overlap;
    StopComplementarity { overlap, projected: sum.max(0.0), at_stop: sum > 0.0 }
}

/// The Coulomb law at a node written as a projection on the ball of radius s (model §10),
/// with z = λ_f + c u_τ (Steps 2–3 of Algorithm 2 with c = r):
///
/// ```text
/// λ_f = P_{B(0,s)}(z) = z (‖z‖ ≤ s),  s z/‖z‖ (‖z‖ > s);    stick where ‖z‖ < s, else slip
/// ```
///
/// Returns P(z), any dimension, and the node's status ([`NodeStatus::Stick`] or
/// [`NodeStatus::Slip`]).
pub fn coulomb<const D: usize>(z: [f64; D], s: f64) -> ([f64; D], NodeStatus) {
    let norm = z.iter().map(|v| v * v).sum::<f64>().sqrt();
    let status = if norm < s { NodeStatus::Stick } else { NodeStatus::Slip };
    let projected = if norm > s { z.map(|v| v * s / norm) } else { z };
    (projected, status)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A compliance law with every constant set.
    fn law() -> NormalCompliance {
        NormalCompliance {
            gap: 0.5,
            penetration: 0.1,
            c_nu: 2.0,
            alpha_nu: 3.0,
            n_nu: 0.2,
            h_nu_range: 128.0,
        }
    }

    #[test]
    fn paper_functions() {
        let law = law();
        assert_eq!(law.stop(law.gap), 0.6);
        assert_eq!((law.p_nu(-1.0), law.p_nu(0.1), law.p_nu(5.0)), (0.0, 0.1, 0.2));
        assert_eq!(law.h_nu(0.0), 2.0);
        assert_eq!(law.h_nu(-64.0), 2.0 * (1.0 + 2.0 * 0.5));
        assert_eq!(law.h_nu(500.0), 6.0);
        // h_ν(0) p_ν(0.55 − 0.5) = 2 × 0.05.
        assert!((law.pressure(0.55 - law.gap, 0.0) - 0.1).abs() < 1e-15);
        let c = Conduction { ke: 2.0, delta: 4.0, truncation: 10.0 };
        assert_eq!((c.psi(-1.0), c.psi(0.125), c.psi(1.0)), (0.0, 1.0, 2.0));
        assert_eq!((c.phi_l(-20.0), c.phi_l(3.0), c.phi_l(20.0)), (-10.0, 3.0, 10.0));
    }

    #[test]
    fn derivatives_match_difference_quotients_away_from_kinks() {
        let law = law();
        let c = Conduction { ke: 2.0, delta: 4.0, truncation: 10.0 };
        let h = 1e-7;
        // (s, t) = (u_ν − g_a, ϕ − ϕ0) with g_a = 0.5, ϕ0 = 32.
        for (u, phi) in [(0.55, 40.0), (0.6, 20.0), (0.3, 0.0), (0.9, 500.0), (0.52, 35.0)] {
            let (s, t) = (u - 0.5, phi - 32.0);
            let (du, dphi) = law.pressure_derivative(s, t);
            let fd_u = (law.pressure(s + h, t) - law.pressure(s - h, t)) / (2.0 * h);
            let fd_phi = (law.pressure(s, t + h) - law.pressure(s, t - h)) / (2.0 * h);
            assert!((du - fd_u).abs() < 1e-6 && (dphi - fd_phi).abs() < 1e-6, "{u}, {phi}");
            let (du, dphi) = c.flux_derivative(s, t);
            let fd_u = (c.flux(s + h, t) - c.flux(s - h, t)) / (2.0 * h);
            let fd_phi = (c.flux(s, t + h) - c.flux(s, t - h)) / (2.0 * h);
            assert!((du - fd_u).abs() < 1e-5 && (dphi - fd_phi).abs() < 1e-6, "{u}, {phi}");
        }
    }

    #[test]
    fn ball_projection() {
        assert_eq!(coulomb([3.0, 4.0], 10.0), ([3.0, 4.0], NodeStatus::Stick));
        let (p, status) = coulomb([3.0, 4.0], 1.0);
        assert!((p[0] - 0.6).abs() < 1e-15 && (p[1] - 0.8).abs() < 1e-15);
        assert_eq!(status, NodeStatus::Slip);
        assert_eq!(coulomb([-2.0], 0.5), ([-0.5], NodeStatus::Slip));
        assert_eq!(coulomb([1.0, 1.0, 1.0], 0.0), ([0.0; 3], NodeStatus::Slip));
        // On the ball's boundary the node slips, and z is its own projection.
        assert_eq!(coulomb([3.0, 4.0], 5.0), ([3.0, 4.0], NodeStatus::Slip));
        // Without a bound a node at rest slips; with one it sticks.
        assert_eq!(coulomb([0.0; 2], 0.0).1, NodeStatus::Slip);
        assert_eq!(coulomb([0.0; 2], 1e-300).1, NodeStatus::Stick);
    }

    #[test]
    fn stop_complementarity_is_max_of_zero_and_the_shifted_multiplier() {
        // Held by the stop: λ_c + c(u_ν − ρ) = 2 + 10 (0.5 − 0.6) = 1 > 0.
        let held = stop_complementarity(2.0, 10.0, 0.5, 0.6);
        assert!((held.overlap + 1.0).abs() < 1e-15 && (held.projected - 1.0).abs() < 1e-15);
        assert!(held.at_stop);
        // Off the stop: 0.5 + 10 (0.5 − 0.6) < 0, so λ_c = 0 by the law.
        let free = stop_complementarity(0.5, 10.0, 0.5, 0.6);
        assert_eq!((free.projected, free.at_stop), (0.0, false));
    }

    #[test]
    fn the_status_is_separated_without_a_compressive_stress() {
        assert_eq!(NodeStatus::at(0.0, Some(NodeStatus::Stick)), NodeStatus::Separated);
        assert_eq!(NodeStatus::at(-1.0, None), NodeStatus::Contact);
        assert_eq!(NodeStatus::at(-1.0, Some(NodeStatus::Slip)), NodeStatus::Slip);
        assert_eq!(NodeStatus::Slip.name(), "slip");
    }
}
