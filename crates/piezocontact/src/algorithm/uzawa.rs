//! Uzawa block relaxation for the augmented Lagrangian, Algorithm 2 (with friction) and
//! Algorithm 4 (without), [P] (6.9)–(6.12), (6.16), as restated in SPEC §7.
//!
//! ```text
//! Step 1  (B̌(x_n) + r M) x^{k+1} = f_{1,n} + Σ_i w_i [(r p_c − λ_c) ν_i + (r p_f − λ_f)]
//! Step 2  p_c = min(u_ν + λ_c/r, ρ);   z = λ_f + r u_τ,  p_f = (1 − s/‖z‖) z/r if ‖z‖ > s, else 0
//! Step 3  λ_c = max(0, λ_c + r(u_ν − ρ));   λ_f = P_{B(0,s)}(z)
//! stop    (‖Δx‖² + ‖Δp_c‖² + ‖Δp_f‖²) / (‖x‖² + ‖p_c‖² + ‖p_f‖²) < ε²          (6.12)
//! ```
//!
//! The matrix of Step 1 was factorised by the caller; every iteration is one solve plus
//! O(|Γ3|) work. Every call starts cold (p = λ = 0, x⁰ = 0), as SPEC §7 requires.

use super::Settings;
use crate::assembly::MassNorm;
use crate::contact::ContactSurface;
use crate::contact::law::{NormalCompliance, project_ball};
use crate::dofs::{CONSTRAINED, DofMap};
use crate::error::Result;
use crate::problem::Problem;
use crate::solver::CoupledSystem;

/// Multipliers and auxiliary variables on the Γ3 nodes.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ContactState {
    /// λ_c: contact pressure of the rigid stop [stress].
    pub lambda_c: Vec<f64>,
    /// λ_f: friction traction (σ_τ = −λ_f) [stress], 3 components (d used).
    pub lambda_f: Vec<[f64; 3]>,
    /// p_c: auxiliary normal displacement [length].
    pub p_c: Vec<f64>,
    /// p_f: auxiliary tangential displacement [length].
    pub p_f: Vec<[f64; 3]>,
}

impl ContactState {
    /// p = λ = 0 on `n` nodes.
    pub fn cold(n: usize) -> Self {
        Self {
            lambda_c: vec![0.0; n],
            lambda_f: vec![[0.0; 3]; n],
            p_c: vec![0.0; n],
            p_f: vec![[0.0; 3]; n],
        }
    }
}

/// Why a loop stopped.
#[derive(Clone, Debug)]
pub enum Stop {
    /// The stopping rule held.
    Converged,
    /// The iteration cap was reached.
    Cap,
    /// The criterion grew by a factor [`DIVERGENCE`] over its smallest value.
    Diverged,
    /// A solve produced NaN or infinity, or a criterion was not finite.
    NotFinite(String),
}

/// A criterion this many times its smallest value so far means divergence.
pub const DIVERGENCE: f64 = 1e3;

/// What one Uzawa loop produced.
#[derive(Clone, Debug)]
pub struct UzawaResult {
    /// The last finite x^k (global vector).
    pub x: Vec<f64>,
    /// The multipliers and auxiliary variables with it.
    pub state: ContactState,
    /// Iterations done.
    pub iterations: usize,
    /// The criterion of (6.12) (square root of the ratio) at each iteration.
    pub history: Vec<f64>,
    /// Why the loop stopped.
    pub stop: Stop,
}

/// Everything the loop reads.
pub struct Uzawa<'a> {
    /// The problem.
    pub problem: &'a Problem,
    /// Its DOF map (the system's).
    pub dofs: &'a DofMap,
    /// The L2(Ω) norm of (6.12).
    pub mass: &'a MassNorm,
    /// Γ3.
    pub surface: &'a ContactSurface,
    /// The normal law (for ρ = g_a + g_p).
    pub compliance: &'a NormalCompliance,
    /// s_n on the Γ3 nodes for Algorithm 2, `None` for Algorithm 4 (no friction terms).
    pub friction_bound: Option<&'a [f64]>,
    /// f_{1,n} − f̌ on the free DOFs: the lagged −j̃1(x_n) − ľ(x_n).
    pub base: &'a [f64],
    /// r, ε, the cap.
    pub settings: &'a Settings,
}

impl Uzawa<'_> {
    /// Runs the loop with the factorised `system`, starting cold.
    pub fn run(&self, system: &mut CoupledSystem) -> Result<UzawaResult> {
        let (surface, r) = (self.surface, self.settings.r);
        let rho = self.compliance.stop();
        let dofs = self.dofs;
        let mut state = ContactState::cold(surface.len());
        let mut x = vec![0.0; dofs.n_total()];
        let mut history: Vec<f64> = Vec::new();
        let mut smallest = f64::INFINITY;
        for k in 0..self.settings.max_inner {
            let x_new = match system.solve(Some(&self.right_hand_side(dofs, &state))) {
                Ok(x_new) => x_new,
                Err(e) => {
                    return Ok(UzawaResult {
                        x,
                        state,
                        iterations: k + 1,
                        history,
                        stop: Stop::NotFinite(e.to_string()),
                    });
                }
            };
            let mut next = state.clone();
            let (mut num, mut den) = (0.0, 0.0);
            for i in 0..surface.len() {
                let (u_nu, u_tau) = surface.split(dofs, &x_new, i);
                let w = surface.weight[i];
                next.p_c[i] = (u_nu + state.lambda_c[i] / r).min(rho);
                next.lambda_c[i] = (state.lambda_c[i] + r * (u_nu - rho)).max(0.0);
                if let Some(s) = self.friction_bound {
                    let z = [0, 1, 2].map(|c| state.lambda_f[i][c] + r * u_tau[c]);
                    next.lambda_f[i] = project_ball(z, s[i]);
                    next.p_f[i] = [0, 1, 2].map(|c| (z[c] - next.lambda_f[i][c]) / r);
                }
                num += w
                    * ((next.p_c[i] - state.p_c[i]).powi(2)
                        + squared_distance(&next.p_f[i], &state.p_f[i]));
                den += w * (next.p_c[i].powi(2) + squared_distance(&next.p_f[i], &[0.0; 3]));
            }
            let difference: Vec<f64> = x_new.iter().zip(&x).map(|(a, b)| a - b).collect();
            num += self.mass.squared(self.problem, dofs, &difference);
            den += self.mass.squared(self.problem, dofs, &x_new);
            let criterion = if den > 0.0 { (num / den).sqrt() } else { 0.0 };
            history.push(criterion);
            if !criterion.is_finite() {
                let cause = format!("the criterion (6.12) is {criterion}");
                return Ok(UzawaResult {
                    x,
                    state,
                    iterations: k + 1,
                    history,
                    stop: Stop::NotFinite(cause),
                });
            }
            x = x_new;
            state = next;
            smallest = smallest.min(criterion);
            let stop = if criterion < self.settings.eps {
                Some(Stop::Converged)
            } else if criterion > DIVERGENCE * smallest {
                Some(Stop::Diverged)
            } else {
                None
            };
            if let Some(stop) = stop {
                return Ok(UzawaResult { x, state, iterations: k + 1, history, stop });
            }
        }
        Ok(UzawaResult { x, state, iterations: self.settings.max_inner, history, stop: Stop::Cap })
    }

    /// The Step 1 right-hand side beyond f̌: base + Σ_i w_i [(r p_c − λ_c) ν_i + (r p_f − λ_f)].
    fn right_hand_side(&self, dofs: &DofMap, state: &ContactState) -> Vec<f64> {
        let (surface, r) = (self.surface, self.settings.r);
        let mut rhs = self.base.to_vec();
        for i in 0..surface.len() {
            let w = surface.weight[i];
            let normal = w * (r * state.p_c[i] - state.lambda_c[i]);
            for c in 0..surface.dim() {
                let k = dofs.free_index(dofs.u(surface.nodes[i], c));
                if k != CONSTRAINED {
                    rhs[k] += normal * surface.normal[i][c]
                        + w * (r * state.p_f[i][c] - state.lambda_f[i][c]);
                }
            }
        }
        rhs
    }
}

fn squared_distance(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    (0..3).map(|c| (a[c] - b[c]).powi(2)).sum()
}
