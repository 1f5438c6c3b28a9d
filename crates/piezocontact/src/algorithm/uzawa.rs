//! Uzawa block relaxation for the augmented Lagrangian, Algorithm 2 (with friction) and
//! Algorithm 4 (without), \[P\] (6.9)–(6.12), (6.16), as restated in model §7.
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

use super::inner::{
    DIVERGENCE, InnerMethod, InnerResult, Progress, Setup, Step, Stop, StopContext,
};
use crate::assembly::NodalBlock;
use crate::contact::law::{coulomb, stop_complementarity};
use crate::contact::{ContactModel, ContactState, ContactSurface, NodeStatus};
use crate::dofs::{CONSTRAINED, DofMap};
use crate::error::Result;
use crate::linalg::LinearSolver;
use crate::system::CoupledSystem;

/// What the Uzawa method reads from `solver.*`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Parameters {
    /// r > 0: the augmented Lagrangian parameter [stress/length] (paper: 0.25 E).
    pub r: f64,
    /// ε of (6.12)/(6.16) [-] (paper: 1e−4).
    pub eps: f64,
    /// ε_fp of the fixed-point rules (6.13)/(6.15) [-] (paper: 1e−4).
    pub eps_fp: f64,
    /// Cap on Uzawa iterations per outer step.
    pub max_inner: usize,
}

/// The augmented Lagrangian Uzawa block relaxation as an inner method: every outer step
/// starts cold, with the contact terms lagged at x_n by the outer loop.
#[derive(Clone, Debug)]
pub struct Uzawa {
    parameters: Parameters,
    /// r M on the Γ3 nodes, added to B̌.
    blocks: Vec<NodalBlock>,
}

impl Uzawa {
    /// The method with `parameters`.
    pub fn new(parameters: Parameters) -> Self {
        Self { parameters, blocks: Vec::new() }
    }
}

impl InnerMethod for Uzawa {
    fn name(&self) -> &'static str {
        "uzawa"
    }

    fn fresh(&self) -> Box<dyn InnerMethod> {
        Box::new(Self::new(self.parameters))
    }

    fn lags_contact(&self) -> bool {
        true
    }

    fn complementarity_constant(&self) -> f64 {
        self.parameters.r
    }

    fn outer_tolerance(&self) -> f64 {
        self.parameters.eps_fp
    }

    fn prepare(&mut self, setup: Setup, solver: Box<dyn LinearSolver>) -> Result<CoupledSystem> {
        let friction = setup.model.friction.is_some();
        self.blocks = step1_blocks(setup.surface, self.parameters.r, friction);
        CoupledSystem::new(setup.problem, setup.dofs, &setup.surface.nodes, solver)
    }

    fn blocks(&self) -> &[NodalBlock] {
        &self.blocks
    }

    fn solve(&mut self, step: &Step, system: &mut CoupledSystem) -> Result<InnerResult> {
        let base = lagged_loads(system.dofs(), step.surface, step.model, step.previous);
        let Parameters { r, eps, max_inner, .. } = self.parameters;
        Loop { step, base: &base, r, eps, max_inner }.run(system)
    }

    fn stop_context(&self, outer_step: usize, friction: bool) -> StopContext {
        let Parameters { r, eps, max_inner, .. } = self.parameters;
        let algorithm = if friction { 2 } else { 4 };
        let hint = format!(
            "r too small or too large for this problem: try solver.r = {:.4e} or {:.4e} (now {r:.4e}; the paper uses 0.25 E)",
            2.0 * r,
            0.5 * r,
        );
        StopContext {
            what: format!("the Uzawa loop (Algorithm {algorithm}) of outer step {outer_step}"),
            tolerance: eps,
            cap_hint: format!("raise solver.max_inner (now {max_inner}), or {hint}"),
            hint,
        }
    }
}

/// The multipliers with Uzawa's auxiliary displacements on the Γ3 nodes.
#[derive(Clone, Debug)]
struct Iterate {
    /// λ_c, λ_f.
    multipliers: ContactState,
    /// p_c: auxiliary normal displacement [length].
    p_c: Vec<f64>,
    /// p_f: auxiliary tangential displacement [length].
    p_f: Vec<[f64; 3]>,
    /// What the friction law said of each node in the last Step 3 (at λ = 0 before one;
    /// [`NodeStatus::Contact`] without friction).
    status: Vec<NodeStatus>,
}

/// One Uzawa loop: the outer step's data and the method's parameters.
struct Loop<'a> {
    /// The outer step.
    step: &'a Step<'a>,
    /// f_{1,n} − f̌ on the free DOFs: the lagged −j̃1(x_n) − ľ(x_n).
    base: &'a [f64],
    /// r > 0 [stress/length].
    r: f64,
    /// ε of (6.12).
    eps: f64,
    /// Cap on iterations.
    max_inner: usize,
}

impl Loop<'_> {
    /// Runs the loop with the factorised `system`, starting cold.
    pub fn run(&self, system: &mut CoupledSystem) -> Result<InnerResult> {
        let step = self.step;
        let n3 = step.surface.len();
        let friction = step.model.friction.is_some();
        let at_rest = |i: usize| coulomb([0.0; 3], step.friction_bound[i]).1;
        let mut state = Iterate {
            multipliers: ContactState::cold(n3),
            p_c: vec![0.0; n3],
            p_f: vec![[0.0; 3]; n3],
            status: (0..n3)
                .map(|i| if friction { at_rest(i) } else { NodeStatus::Contact })
                .collect(),
        };
        let mut x = vec![0.0; system.dofs().n_total()];
        let mut history: Vec<f64> = Vec::new();
        let mut smallest = f64::INFINITY;
        let done = |x, state: Iterate, iterations, history, stop| InnerResult {
            x,
            state: state.multipliers,
            iterations,
            history,
            status: state.status,
            stop,
        };
        for k in 0..self.max_inner {
            if let Some(signal) = crate::interrupt::requested() {
                return Ok(done(x, state, k, history, Stop::Interrupted(signal)));
            }
            let rhs = self.right_hand_side(system.dofs(), &state);
            let x_new = match system.solve(Some(&rhs)) {
                Ok(x_new) => x_new,
                Err(e) => {
                    return Ok(done(x, state, k + 1, history, Stop::of_failed_solve(e)));
                }
            };
            let dofs = system.dofs();
            let (next, mut num, mut den) = self.update(dofs, &x_new, &state);
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

    /// Steps 2 and 3 at every Γ3 node from x_{k+1} = `x_new`: p_c, λ_c, and with friction
    /// p_f, λ_f and the node's status; with the Γ3 part of the criterion (6.12), its numerator
    /// and denominator.
    fn update(&self, dofs: &DofMap, x_new: &[f64], state: &Iterate) -> (Iterate, f64, f64) {
        let (step, r, surface) = (self.step, self.r, self.step.surface);
        let friction = step.model.friction.is_some();
        let mut next = state.clone();
        let (mut num, mut den) = (0.0, 0.0);
        for i in 0..surface.len() {
            let (u_nu, u_tau) = surface.split(dofs, x_new, i);
            let w = surface.weight[i];
            let (lambda, next_lambda) = (&state.multipliers, &mut next.multipliers);
            let rho = step.model.compliance.stop(surface.gap[i]);
            next.p_c[i] = (u_nu + lambda.lambda_c[i] / r).min(rho);
            next_lambda.lambda_c[i] =
                stop_complementarity(lambda.lambda_c[i], r, u_nu, rho).projected;
            if friction {
                let z = [0, 1, 2].map(|c| lambda.lambda_f[i][c] + r * u_tau[c]);
                (next_lambda.lambda_f[i], next.status[i]) = coulomb(z, step.friction_bound[i]);
                next.p_f[i] = [0, 1, 2].map(|c| (z[c] - next_lambda.lambda_f[i][c]) / r);
            }
            num += w
                * ((next.p_c[i] - state.p_c[i]).powi(2)
                    + squared_distance(&next.p_f[i], &state.p_f[i]));
            den += w * (next.p_c[i].powi(2) + squared_distance(&next.p_f[i], &[0.0; 3]));
        }
        (next, num, den)
    }

    /// The Step 1 right-hand side beyond f̌: base + Σ_i w_i [(r p_c − λ_c) ν_i + (r p_f − λ_f)].
    fn right_hand_side(&self, dofs: &DofMap, state: &Iterate) -> Vec<f64> {
        let (surface, r) = (self.step.surface, self.r);
        let lambda = &state.multipliers;
        let mut rhs = self.base.to_vec();
        for i in 0..surface.len() {
            let w = surface.weight[i];
            let normal = w * (r * state.p_c[i] - lambda.lambda_c[i]);
            let force = std::array::from_fn(|c| {
                normal * surface.normal[i][c] + w * (r * state.p_f[i][c] - lambda.lambda_f[i][c])
            });
            dofs.add_at_node(surface.nodes[i], &force, &mut rhs);
        }
        rhs
    }
}

fn squared_distance(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    (0..3).map(|c| (a[c] - b[c]).powi(2)).sum()
}

/// r M on the Γ3 nodes: r w_i I with friction (Algorithm 2), r w_i ν_i ν_iᵀ without (Algorithm 4).
fn step1_blocks(surface: &ContactSurface, r: f64, friction: bool) -> Vec<NodalBlock> {
    (0..surface.len())
        .map(|i| {
            let (w, n) = (surface.weight[i], surface.normal[i]);
            let mut block = [[0.0; 3]; 3];
            for a in 0..surface.dim() {
                for b in 0..surface.dim() {
                    let identity = if a == b && friction { 1.0 } else { 0.0 };
                    block[a][b] = r * w * if friction { identity } else { n[a] * n[b] };
                }
            }
            block
        })
        .collect()
}

/// −j̃1(x_n, ·) − ľ(x_n, ·) on the free DOFs (nodal quadrature on Γ3): −w h_ν p_ν ν on the u
/// rows; + w ψ φ_L on the ϕ row (PV2 only).
fn lagged_loads(
    dofs: &DofMap,
    surface: &ContactSurface,
    model: &ContactModel,
    x: &[f64],
) -> Vec<f64> {
    let mut base = vec![0.0; dofs.n_free()];
    for i in 0..surface.len() {
        let (u_nu, _) = surface.split(dofs, x, i);
        let phi = surface.phi(dofs, x, i);
        let (w, node) = (surface.weight[i], surface.nodes[i]);
        let pressure = model.pressure(u_nu, phi, surface.gap[i]);
        let force = surface.normal[i].map(|n| -w * pressure * n);
        dofs.add_at_node(node, &force, &mut base);
        if model.conduction.is_some() {
            let k = dofs.free_index(dofs.phi(node));
            if k != CONSTRAINED {
                base[k] += w * model.flux(u_nu, phi, surface.gap[i]);
            }
        }
    }
    base
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::assembly::{Linearisation, secant_moduli};
    use crate::linalg::default_solver;
    use crate::testing::{Fixture, PAPER_71, PAPER_72};

    const COARSE: [&str; 3] = ["mesh.nx=24", "mesh.ny=4", "material.law=\"linear\""];

    #[test]
    fn step_1_adds_r_m_on_the_contact_nodes() {
        for (text, friction) in [(PAPER_71, false), (PAPER_72, true)] {
            let fixture = Fixture::new(text, &COARSE);
            let surface = &fixture.surface;
            let blocks = step1_blocks(surface, 3.0, friction);
            assert_eq!(blocks.len(), surface.len());
            for (i, block) in blocks.iter().enumerate() {
                let (w, n) = (surface.weight[i], surface.normal[i]);
                for a in 0..3 {
                    for b in 0..3 {
                        // Algorithm 2: r w I on u; Algorithm 4: r w ν νᵀ.
                        let identity = if a == b && a < 2 { 1.0 } else { 0.0 };
                        let expected = 3.0 * w * if friction { identity } else { n[a] * n[b] };
                        assert_eq!(block[a][b], expected, "node {i} ({a}, {b})");
                    }
                }
            }
        }
    }

    /// One Uzawa loop of PV2 to ε = 1e−12, with the friction bound s_n given: at its end the
    /// multipliers obey Steps 2–3 — λ_c ≥ 0 with complementarity and no penetration beyond
    /// the stop, ‖λ_f‖ ≤ s_n — and a second call, cold like the first, repeats it exactly.
    #[test]
    fn a_loop_ends_on_the_contact_and_friction_laws_and_starts_cold() {
        let mut overrides = COARSE.to_vec();
        overrides.extend(["solver.eps=1e-12", "solver.max_inner=100000"]);
        let fixture = Fixture::new(PAPER_72, &overrides);
        let (problem, model) = (fixture.problem(), fixture.model());
        let parameters = Parameters { r: 14.67755, eps: 1e-12, eps_fp: 1e-12, max_inner: 100_000 };
        let mut uzawa = Uzawa::new(parameters);
        let mut system = uzawa.prepare(fixture.setup(), default_solver()).unwrap();
        let zero = vec![0.0; system.dofs().n_total()];
        let moduli = secant_moduli(problem, system.dofs(), &zero).unwrap();
        let moduli = Linearisation::secant(moduli);
        system.factorize_linearised(problem, &moduli, uzawa.blocks()).unwrap();
        let s_n = vec![0.05; fixture.surface.len()];
        let step = fixture.step(&zero, &s_n, &moduli);
        let first = uzawa.solve(&step, &mut system).unwrap();
        assert!(matches!(first.stop, Stop::Converged) && *first.history.last().unwrap() < 1e-12);
        let dofs = system.dofs();
        let (mut touching, mut slipping) = (0, 0);
        for i in 0..fixture.surface.len() {
            let (u_nu, _) = fixture.surface.split(dofs, &first.x, i);
            let rho = model.compliance.stop(fixture.surface.gap[i]);
            let lambda_c = first.state.lambda_c[i];
            assert!(lambda_c >= 0.0 && u_nu - rho < 1e-9, "node {i}: {lambda_c}, {u_nu}");
            assert!(lambda_c * (rho - u_nu).max(0.0) < 1e-9 * lambda_c.max(1.0), "node {i}");
            let traction = first.state.lambda_f[i].iter().map(|v| v * v).sum::<f64>().sqrt();
            assert!(traction <= 0.05 * (1.0 + 1e-12), "node {i}: ‖λ_f‖ = {traction}");
            touching += usize::from(lambda_c > 0.0);
            slipping += usize::from(traction > 0.05 * (1.0 - 1e-9));
        }
        assert!(touching > 3 && slipping > 0, "{touching} touching, {slipping} slipping");
        let sigma_nu = first.state.normal_stress(dofs, &fixture.surface, model, &first.x);
        assert!(sigma_nu.iter().all(|s| *s <= 0.0), "the foundation only pushes");
        let again = uzawa.solve(&step, &mut system).unwrap();
        assert_eq!((again.x, again.history), (first.x, first.history));
    }

    /// The lagged loads are the compliance pressure on the u rows and the conduction flux on
    /// the ϕ rows of the Γ3 nodes, and nothing elsewhere.
    #[test]
    fn the_lagged_loads_sit_on_the_contact_rows() {
        let fixture =
            Fixture::new(PAPER_72, &[COARSE.as_slice(), &["contact.penetration=0.1"]].concat());
        let (problem, model, surface) = (fixture.problem(), fixture.model(), &fixture.surface);
        let dofs = DofMap::new(problem).unwrap();
        // Every Γ3 node 0.05 past the gap, ϕ = 40 against ϕ0 = 32.
        let mut x = vec![0.0; dofs.n_total()];
        for i in 0..surface.len() {
            let node = surface.nodes[i];
            for c in 0..2 {
                x[dofs.u(node, c)] = (surface.gap[i] + 0.05) * surface.normal[i][c];
            }
            x[dofs.phi(node)] = 40.0;
        }
        let base = lagged_loads(&dofs, surface, model, &x);
        let mut expected = vec![0.0; dofs.n_free()];
        for i in 0..surface.len() {
            let (w, node) = (surface.weight[i], surface.nodes[i]);
            // h_ν(8) p_ν(0.05) and ψ(0.05) φ_L(8) of the case's laws.
            let pressure = 1.0 * (1.0 + 8.0 / 128.0) * 0.05;
            let flux = model.conduction.as_ref().unwrap().ke * 0.05 * 8.0;
            for c in 0..2 {
                let k = dofs.free_index(dofs.u(node, c));
                if k != CONSTRAINED {
                    expected[k] -= w * pressure * surface.normal[i][c];
                }
            }
            let k = dofs.free_index(dofs.phi(node));
            if k != CONSTRAINED {
                expected[k] += w * flux;
            }
        }
        let error = base.iter().zip(&expected).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        assert!(error < 1e-14, "{error}");
        assert!(base.iter().filter(|v| **v != 0.0).count() > surface.len());
    }
}
