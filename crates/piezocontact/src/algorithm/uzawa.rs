//! Uzawa block relaxation for the augmented Lagrangian, Algorithm 2 (with friction) and
//! Algorithm 4 (without), [P] (6.9)–(6.12), (6.16), as restated in model §7.
//!
//! ```text
//! Step 1  (B̌(x_n) + r M) x^{k+1} = f_{1,n} + Σ_i w_i [(r p_c − λ_c) ν_i + (r p_f − λ_f)]
//! Step 2  p_c = min(u_ν + λ_c/r, ρ);   z = λ_f + r u_τ,  p_f = (1 − s/‖z‖) z/r if ‖z‖ > s, else 0
//! Step 3  λ_c = max(0, λ_c + r(u_ν − ρ));   λ_f = P_{B(0,s)}(z)
//! stop    (‖Δx‖² + ‖Δp_c‖² + ‖Δp_f‖²) / (‖x‖² + ‖p_c‖² + ‖p_f‖²) < ε²          (6.12)
//! ```
//!
//! The matrix of Step 1 was factorised by the caller; every iteration is one solve plus
//! O(|Γ3|) work. Every call starts cold (p = λ = 0, x⁰ = 0), as model §7 requires.

use super::{ContactState, DIVERGENCE, InnerResult, Progress, Step, Stop};
use crate::contact::law::project_ball;
use crate::dofs::{CONSTRAINED, DofMap};
use crate::error::Result;
use crate::solver::CoupledSystem;

/// The multipliers with Uzawa's auxiliary displacements on the Γ3 nodes.
#[derive(Clone, Debug)]
struct Iterate {
    /// λ_c, λ_f.
    multipliers: ContactState,
    /// p_c: auxiliary normal displacement [length].
    p_c: Vec<f64>,
    /// p_f: auxiliary tangential displacement [length].
    p_f: Vec<[f64; 3]>,
}

/// One Uzawa loop: the outer step's data and the method's parameters.
pub struct Uzawa<'a> {
    /// The outer step.
    pub step: &'a Step<'a>,
    /// r > 0 [stress/length].
    pub r: f64,
    /// ε of (6.12).
    pub eps: f64,
    /// Cap on iterations.
    pub max_inner: usize,
}

impl Uzawa<'_> {
    /// Runs the loop with the factorised `system`, starting cold.
    pub fn run(&self, system: &mut CoupledSystem) -> Result<InnerResult> {
        let (step, r) = (self.step, self.r);
        let surface = step.surface;
        let n3 = surface.len();
        let mut state = Iterate {
            multipliers: ContactState::cold(n3),
            p_c: vec![0.0; n3],
            p_f: vec![[0.0; 3]; n3],
        };
        let mut x = vec![0.0; system.dofs().n_total()];
        let mut history: Vec<f64> = Vec::new();
        let mut smallest = f64::INFINITY;
        let done = |x, state: Iterate, iterations, history, stop| InnerResult {
            x,
            state: state.multipliers,
            iterations,
            history,
            stop,
        };
        for k in 0..self.max_inner {
            let rhs = self.right_hand_side(system.dofs(), &state);
            let x_new = match system.solve(Some(&rhs)) {
                Ok(x_new) => x_new,
                Err(e) => {
                    return Ok(done(x, state, k + 1, history, Stop::NotFinite(e.to_string())));
                }
            };
            let dofs = system.dofs();
            let mut next = state.clone();
            let (mut num, mut den) = (0.0, 0.0);
            for i in 0..surface.len() {
                let (u_nu, u_tau) = surface.split(dofs, &x_new, i);
                let w = surface.weight[i];
                let (lambda, next_lambda) = (&state.multipliers, &mut next.multipliers);
                let rho = step.compliance.stop(surface.gap[i]);
                next.p_c[i] = (u_nu + lambda.lambda_c[i] / r).min(rho);
                next_lambda.lambda_c[i] = (lambda.lambda_c[i] + r * (u_nu - rho)).max(0.0);
                if let Some(s) = step.friction_bound {
                    let z = [0, 1, 2].map(|c| lambda.lambda_f[i][c] + r * u_tau[c]);
                    next_lambda.lambda_f[i] = project_ball(z, s[i]);
                    next.p_f[i] = [0, 1, 2].map(|c| (z[c] - next_lambda.lambda_f[i][c]) / r);
                }
                num += w
                    * ((next.p_c[i] - state.p_c[i]).powi(2)
                        + squared_distance(&next.p_f[i], &state.p_f[i]));
                den += w * (next.p_c[i].powi(2) + squared_distance(&next.p_f[i], &[0.0; 3]));
            }
            let difference: Vec<f64> = x_new.iter().zip(&x).map(|(a, b)| a - b).collect();
            num += step.mass.squared(step.problem, dofs, &difference);
            den += step.mass.squared(step.problem, dofs, &x_new);
            let criterion = if den > 0.0 { (num / den).sqrt() } else { 0.0 };
            history.push(criterion);
            (step.progress)(Progress::Inner { iteration: k + 1, criterion, tolerance: self.eps });
            if !criterion.is_finite() {
                let cause = format!("the criterion (6.12) is {criterion}");
                return Ok(done(x, state, k + 1, history, Stop::NotFinite(cause)));
            }
            x = x_new;
            state = next;
            smallest = smallest.min(criterion);
            let stop = if criterion < self.eps {
                Some(Stop::Converged)
            } else if criterion > DIVERGENCE * smallest {
                Some(Stop::Diverged)
            } else {
                None
            };
            if let Some(stop) = stop {
                return Ok(done(x, state, k + 1, history, stop));
            }
        }
        Ok(done(x, state, self.max_inner, history, Stop::Cap))
    }

    /// The Step 1 right-hand side beyond f̌: base + Σ_i w_i [(r p_c − λ_c) ν_i + (r p_f − λ_f)].
    fn right_hand_side(&self, dofs: &DofMap, state: &Iterate) -> Vec<f64> {
        let (surface, r) = (self.step.surface, self.r);
        let lambda = &state.multipliers;
        let mut rhs = self.step.base.to_vec();
        for i in 0..surface.len() {
            let w = surface.weight[i];
            let normal = w * (r * state.p_c[i] - lambda.lambda_c[i]);
            for c in 0..surface.dim() {
                let k = dofs.free_index(dofs.u(surface.nodes[i], c));
                if k != CONSTRAINED {
                    rhs[k] += normal * surface.normal[i][c]
                        + w * (r * state.p_f[i][c] - lambda.lambda_f[i][c]);
                }
            }
        }
        rhs
    }
}

fn squared_distance(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    (0..3).map(|c| (a[c] - b[c]).powi(2)).sum()
}
