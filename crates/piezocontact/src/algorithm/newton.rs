//! The exact contact solver (model §11): a semismooth Newton method on the problem condensed
//! onto the Γ3 unknowns.
//!
//! Every nonlinearity but Hencky's lives on the Γ3 nodes. With the Γ3 unknowns x_c (u and ϕ
//! of each Γ3 node) ordered last, the trailing block of the LDLᵀ factor of B̌ is the LDLᵀ of
//! the Schur complement S = K_cc − K_ci K_ii⁻¹ K_ic, read off the factor once per
//! factorisation. The u unknowns of node i are turned into its local coordinates
//! (u_ν, u_τ) = Q_i u, and S with them. One solve without contact forces gives x̂ and the
//! condensed load g = S x̂_c; the discrete problem on Γ3 is then, with r = S x_c − g the
//! contact forces on the Γ3 rows (r_ν = w σ_ν, r_τ = −w λ_f, r_ϕ = w ψ φ_L):
//!
//! ```text
//! λ_c = −σ_ν − h_ν(ϕ − ϕ0) p_ν(u_ν − g_a)
//! E_n = λ_c − max(0, λ_c + c_i (u_ν − ρ))                     (contact, every node)
//! E_t = λ_f − P_{B(0,s)}(λ_f + c_i u_τ),  s = µ |R σ_ν|       (Coulomb, PV2; PV1: λ_f)
//! E_ϕ = r_ϕ − w ψ(u_ν − g_a) φ_L(ϕ − ϕ0)                       (conduction, PV2; PV1: r_ϕ)
//! ```
//!
//! All of it is semismooth in x_c. Each Newton step solves J δ = −E with a generalised
//! Jacobian J: on a node in contact (λ_c + c(u_ν − ρ) > 0) the normal row is
//! −c δu_ν = −E_n, on a sticking node (‖λ_f + c u_τ‖ < s) the tangential rows are
//! −c δu_τ = −E_t; these fix their unknowns, and the dense LU runs on the others only. On
//! slipping nodes the derivative of the projection uses λ_f / max(s, ‖λ_f‖) in place of its
//! direction (Hüeber, Stadler and Wohlmuth's relaxation: exact at a slip solution, a descent
//! direction elsewhere), and a backtracking line search on ‖E‖ (each equation scaled by the
//! stiffness it sees) keeps the iteration from cycling. The constant c_i = (r/E)·S_νν,i/w_i
//! scales the case's r by the stiffness that node i sees; the answer does not depend on it.
//! The iteration stops when the sets no longer change and the step is at round-off; one solve
//! with the contact forces then recovers the interior.

use super::{ContactState, InnerResult, Progress, Step, Stop};
use crate::contact::ContactSurface;
use crate::dofs::{CONSTRAINED, DofMap};
use crate::error::{Error, Result};
use crate::linalg::DenseMatrix;
use crate::solver::CoupledSystem;

/// A relative Newton step below this, with unchanged sets, is round-off.
pub const STEP_TOLERANCE: f64 = 1e-12;
/// A relative Newton step below this ends the iteration whatever the sets do.
const STEP_FLOOR: f64 = 1e-15;
/// Halvings of the line search.
const HALVINGS: usize = 8;
/// Condensed problems solved in one outer step, at most (each after a factorisation).
const MAX_ROUNDS: usize = 10;

/// The Γ3 unknowns kept by the condensation, in the order of the Schur complement.
#[derive(Clone, Debug)]
pub struct Condensed {
    /// Free indices of the condensed unknowns.
    pub free: Vec<usize>,
    /// Global indices of the condensed unknowns.
    global: Vec<usize>,
    /// Per Γ3 node: the positions of its u components in the condensed vector (in local
    /// coordinates during the iteration: normal first, then tangents).
    u: Vec<[usize; 3]>,
    /// Per Γ3 node: its ϕ.
    phi: Vec<Phi>,
    /// Per Γ3 node: whether it is condensed. A node whose normal misses the foundation (an
    /// infinite gap) cannot touch it, and stays with the interior, as do the nodes left out
    /// of a Γ3 too large to condense whole.
    kept: Vec<bool>,
    /// Whether ϕ of the nodes is condensed.
    with_phi: bool,
}

/// ϕ of a Γ3 node in the condensed problem.
#[derive(Clone, Copy, Debug)]
enum Phi {
    /// An unknown, at this position of the condensed vector.
    Unknown(usize),
    /// Prescribed (the node is on Γa): its global index.
    Prescribed(usize),
    /// Not condensed: without penetration (g_p = 0) the laws that read ϕ, p_ν and ψ at
    /// u_ν − g_a, vanish on every admissible state, and ϕ stays with the interior.
    Interior,
}

impl Condensed {
    /// The Γ3 nodes within the foundation's reach, at most `max_nodes` of them: all when
    /// they are that few, else the `max_nodes` nearest to the foundation (smallest gap; the
    /// first of equal ones), which [`Condensed::grown`] corrects. A node's u is condensed, and its ϕ when
    /// `with_phi` (the laws that read ϕ can act: a penetration g_p > 0); a prescribed ϕ (a
    /// Γ3 node on Γa) is not an unknown.
    pub fn new(dofs: &DofMap, surface: &ContactSurface, with_phi: bool, max_nodes: usize) -> Self {
        let gap = &surface.gap;
        let mut reach: Vec<usize> = (0..surface.len()).filter(|&i| gap[i].is_finite()).collect();
        if reach.len() > max_nodes {
            reach.sort_by(|&a, &b| gap[a].total_cmp(&gap[b]).then(a.cmp(&b)));
            reach.truncate(max_nodes);
        }
        let mut kept = vec![false; surface.len()];
        reach.into_iter().for_each(|i| kept[i] = true);
        Self::with_nodes(dofs, surface, with_phi, kept)
    }

    /// The unknowns of the `kept` nodes.
    fn with_nodes(
        dofs: &DofMap,
        surface: &ContactSurface,
        with_phi: bool,
        kept: Vec<bool>,
    ) -> Self {
        let mut this = Self {
            free: Vec::new(),
            global: Vec::new(),
            u: Vec::new(),
            phi: Vec::new(),
            kept: Vec::new(),
            with_phi,
        };
        let push = |this: &mut Self, g: usize| {
            this.free.push(dofs.free_index(g));
            this.global.push(g);
            this.free.len() - 1
        };
        for (i, &node) in surface.nodes.iter().enumerate() {
            if !kept[i] {
                this.u.push([usize::MAX; 3]);
                this.phi.push(Phi::Interior);
                continue;
            }
            let mut u = [0; 3];
            for (k, slot) in u.iter_mut().enumerate().take(surface.dim()) {
                *slot = push(&mut this, dofs.u(node, k));
            }
            this.u.push(u);
            let g = dofs.phi(node);
            let phi = if !with_phi {
                Phi::Interior
            } else if dofs.free_index(g) == CONSTRAINED {
                Phi::Prescribed(g)
            } else {
                Phi::Unknown(push(&mut this, g))
            };
            this.phi.push(phi);
        }
        this.kept = kept;
        this
    }

    /// The active-set check of the nodes left out (model §11): at the solution `x` of the
    /// condensed problem, a left-out node carries no contact force, which is its law only
    /// while u_ν ≤ g_a. `None` when every left-out node is there. Else the condensation
    /// with those that pass it added, and with them the left-out nodes as near to touching
    /// (u_ν − g_a above minus the largest excess e), deepest first. When that would exceed
    /// `max_nodes`, condensed nodes clear of the foundation make room, the clearest first;
    /// an error when none can.
    pub fn grown(
        &self,
        dofs: &DofMap,
        surface: &ContactSurface,
        x: &[f64],
        max_nodes: usize,
    ) -> Result<Option<Self>> {
        let excess = |i: usize| {
            let nu = surface.frame(i)[0];
            let u_nu: f64 =
                (0..surface.dim()).map(|k| nu[k] * x[dofs.u(surface.nodes[i], k)]).sum();
            u_nu - surface.gap[i]
        };
        let reach = |i: &usize| surface.gap[*i].is_finite();
        let ranked = |kept: bool| {
            let mut nodes: Vec<(usize, f64)> = (0..surface.len())
                .filter(|i| reach(i) && self.kept[*i] == kept)
                .map(|i| (i, excess(i)))
                .collect();
            nodes.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
            nodes
        };
        let mut left_out = ranked(false);
        let touching = left_out.iter().filter(|(_, v)| *v > 0.0).count();
        if touching == 0 {
            return Ok(None);
        }
        let largest = left_out[0].1;
        left_out.retain(|(_, v)| *v > -largest);
        let mut kept = self.kept.clone();
        let count = self.node_count();
        let short = (count + left_out.len()).saturating_sub(max_nodes);
        let clear = ranked(true).into_iter().rev().take_while(|(_, v)| *v < 0.0).take(short);
        clear.for_each(|(i, _)| kept[i] = false);
        let room = max_nodes - kept.iter().filter(|k| **k).count();
        if room == 0 {
            return Err(Error::Input(format!(
                "the contact zone is larger than solver.max_condensed = {max_nodes} nodes: with that many Γ3 nodes condensed and touching, {touching} more still touch the foundation; raise solver.max_condensed to at least {} (its dense matrices grow as its square), or use solver.method = \"uzawa\"",
                count + touching
            )));
        }
        left_out.into_iter().take(room).for_each(|(i, _)| kept[i] = true);
        Ok(Some(Self::with_nodes(dofs, surface, self.with_phi, kept)))
    }

    /// Number of condensed Γ3 nodes.
    pub fn node_count(&self) -> usize {
        self.kept.iter().filter(|k| **k).count()
    }

    /// Checks that the dense work of the condensation — the Schur complement, its factor
    /// block and the Newton systems, about 5 dense m × m matrices — fits in `available`
    /// bytes.
    pub fn check_memory(&self, available: f64) -> Result<()> {
        let m = self.len() as f64;
        let bytes = 5.0 * 8.0 * m * m;
        if bytes > available {
            return Err(Error::Input(format!(
                "the exact solver condenses {} unknowns of Γ3 into dense matrices of about {:.1} GiB, more than the {:.1} GiB available; use solver.method = \"uzawa\", or name a smaller contact part (boundary.contact)",
                self.len(),
                bytes / 2f64.powi(30),
                available / 2f64.powi(30)
            )));
        }
        Ok(())
    }

    /// Number of condensed unknowns.
    pub fn len(&self) -> usize {
        self.free.len()
    }

    /// Whether there is none.
    pub fn is_empty(&self) -> bool {
        self.free.is_empty()
    }
}

/// One semismooth Newton solve of the condensed problem of an outer step.
pub struct Newton<'a> {
    /// The outer step.
    pub step: &'a Step<'a>,
    /// The Γ3 unknowns, last in the factorisation's ordering.
    pub condensed: &'a Condensed,
    /// r/E: the complementarity constant relative to the local stiffness [-].
    pub c_factor: f64,
    /// Cap on Newton steps.
    pub max_iterations: usize,
}

/// The condensed problem in local coordinates.
struct Local<'a> {
    newton: &'a Newton<'a>,
    /// Q S Qᵀ.
    schur: DenseMatrix,
    /// Q g.
    load: Vec<f64>,
    /// Per node: Q_i (rows ν, τ1, τ2).
    frames: Vec<[[f64; 3]; 3]>,
    /// Per node: c_i [stress/length].
    c: Vec<f64>,
    /// Per condensed unknown: the scale of its equation in the merit function.
    scale: Vec<f64>,
    /// The global vector of the solve without contact (for prescribed ϕ).
    x_hat: Vec<f64>,
}

/// E and the sets at an iterate.
struct Evaluation {
    /// E, the residual of the condensed equations.
    residual: Vec<f64>,
    /// Per node: 0 separated, 1 in contact; + 2 when sticking.
    sets: Vec<u8>,
    /// Per condensed unknown: whether its equation fixes it (contact normal, stick tangent).
    fixed: Vec<bool>,
    /// λ_c, λ_f (local tangential components).
    multipliers: ContactState,
    /// r = S x_c − g in local coordinates.
    forces: Vec<f64>,
    /// σ_ν per node and R σ_ν.
    sigma_nu: Vec<f64>,
    r_sigma: Vec<f64>,
}

/// What the exact solver reads from `solver.*`.
#[derive(Clone, Copy, Debug)]
pub struct Parameters {
    /// r/E: the complementarity constant relative to the local stiffness [-].
    pub c_factor: f64,
    /// Cap on Newton steps per condensed problem.
    pub max_iterations: usize,
    /// The most Γ3 nodes condensed.
    pub max_condensed: usize,
}

/// Solves an outer step with the factorised `system` (ordered with `condensed` last),
/// growing the condensation until no node left out touches (model §11). Each growth orders
/// the new condensed unknowns last, factorises B̌ with the moduli `g` again, and restarts
/// Newton from the last solution; the steps and histories of all rounds are summed.
pub fn solve(
    step: &Step,
    parameters: Parameters,
    condensed: &mut Condensed,
    system: &mut CoupledSystem,
    g: &[f64],
) -> Result<InnerResult> {
    let Parameters { c_factor, max_iterations, max_condensed } = parameters;
    let mut result = Newton { step, condensed, c_factor, max_iterations }.run(system)?;
    let mut rounds = 1;
    while matches!(result.stop, Stop::Converged)
        && let Some(grown) =
            condensed.grown(system.dofs(), step.surface, &result.x, max_condensed)?
    {
        if rounds == MAX_ROUNDS {
            return Err(Error::Input(format!(
                "the exact solver's condensation of Γ3 did not settle in {MAX_ROUNDS} factorisations (solver.max_condensed = {max_condensed} nodes, {} condensed): raise solver.max_condensed, or use solver.method = \"uzawa\"",
                condensed.node_count()
            )));
        }
        rounds += 1;
        grown.check_memory(crate::limits::available_memory())?;
        *condensed = grown;
        system.put_last(&condensed.free)?;
        system.factorize(step.problem, g, &[])?;
        let warm = Step { start: &result.x, ..*step };
        let next = Newton { step: &warm, condensed, c_factor, max_iterations }.run(system)?;
        let history = [std::mem::take(&mut result.history), next.history].concat();
        result = InnerResult { iterations: result.iterations + next.iterations, history, ..next };
    }
    Ok(result)
}

impl Newton<'_> {
    /// Solves the condensed problem with the factorised `system` (ordered with the condensed
    /// unknowns last) and recovers the whole solution.
    pub fn run(&self, system: &mut CoupledSystem) -> Result<InnerResult> {
        let cond = self.condensed;
        let x_hat = system.solve(None)?;
        let local = Local::new(self, system.schur_complement(cond.len())?, x_hat);
        let warm = self.step.start.iter().any(|v| *v != 0.0);
        let mut y = local.gather(if warm { self.step.start } else { &local.x_hat });
        let mut history = Vec::new();
        let mut previous_sets: Option<Vec<u8>> = None;
        let (mut stop, mut iterations) = (Stop::Cap, self.max_iterations);
        for k in 0..self.max_iterations {
            let eval = local.evaluate(&y);
            let delta = match local.newton_step(&y, &eval) {
                Ok(delta) => delta,
                Err(e) => {
                    (stop, iterations) = (Stop::NotFinite(e.to_string()), k + 1);
                    break;
                }
            };
            let alpha = local.line_search(&y, &delta, local.merit(&eval));
            y.iter_mut().zip(&delta).for_each(|(a, d)| *a += alpha * d);
            let size = y.iter().fold(0.0_f64, |a, v| a.max(v.abs())).max(f64::MIN_POSITIVE);
            let criterion = alpha * delta.iter().fold(0.0_f64, |a, v| a.max(v.abs())) / size;
            history.push(criterion);
            let tolerance = STEP_TOLERANCE;
            (self.step.progress)(Progress::Inner { iteration: k + 1, criterion, tolerance });
            if !criterion.is_finite() {
                (stop, iterations) =
                    (Stop::NotFinite(format!("the Newton step is {criterion}")), k + 1);
                break;
            }
            let settled = alpha == 1.0 && previous_sets.as_ref() == Some(&eval.sets);
            previous_sets = Some(eval.sets);
            if (settled && criterion <= STEP_TOLERANCE) || criterion <= STEP_FLOOR {
                (stop, iterations) = (Stop::Converged, k + 1);
                break;
            }
        }
        let eval = local.evaluate(&y);
        let mut forces = vec![0.0; system.dofs().n_free()];
        for (k, f) in local.to_global(&eval.forces).into_iter().enumerate() {
            forces[cond.free[k]] = f;
        }
        let x = system.solve(Some(&forces))?;
        let mut state = eval.multipliers;
        // Off the active set the law is λ_c = 0, held to round-off by the Newton equations.
        for (i, set) in eval.sets.iter().enumerate() {
            if set & 1 == 0 || !cond.kept[i] {
                state.lambda_c[i] = 0.0;
            }
        }
        if self.step.friction.is_none() {
            // Frictionless: σ_τ = 0 by the law; the tangential rows hold it to round-off.
            state.lambda_f.iter_mut().for_each(|l| *l = [0.0; 3]);
        }
        for (i, frame) in local.frames.iter().enumerate() {
            // λ_f from local tangential components to global ones.
            let tangential = state.lambda_f[i];
            state.lambda_f[i] =
                [0, 1, 2].map(|k| (1..3).map(|a| frame[a][k] * tangential[a - 1]).sum());
        }
        Ok(InnerResult { x, state, iterations, history, stop })
    }
}

impl<'a> Local<'a> {
    /// Turns S and the load into local coordinates and sets the constants.
    fn new(newton: &'a Newton<'a>, mut schur: DenseMatrix, x_hat: Vec<f64>) -> Self {
        let (cond, surface) = (newton.condensed, newton.step.surface);
        let dim = surface.dim();
        let frames: Vec<[[f64; 3]; 3]> = (0..surface.len()).map(|i| surface.frame(i)).collect();
        let m = cond.len();
        // S ← Q S Qᵀ, node block by node block: columns, then rows.
        for (i, q) in frames.iter().enumerate().filter(|(i, _)| cond.kept[*i]) {
            let idx = &cond.u[i][..dim];
            for r in 0..m {
                let old: Vec<f64> = idx.iter().map(|&k| schur.get(r, k)).collect();
                for (a, &k) in idx.iter().enumerate() {
                    schur.set(r, k, (0..dim).map(|b| q[a][b] * old[b]).sum());
                }
            }
            for col in 0..m {
                let old: Vec<f64> = idx.iter().map(|&k| schur.get(k, col)).collect();
                for (a, &k) in idx.iter().enumerate() {
                    schur.set(k, col, (0..dim).map(|b| q[a][b] * old[b]).sum());
                }
            }
        }
        let mut this = Self {
            newton,
            schur,
            load: Vec::new(),
            frames,
            c: Vec::new(),
            scale: Vec::new(),
            x_hat,
        };
        this.load = this.schur.mul(&this.gather(&this.x_hat));
        this.c = (0..surface.len())
            .map(|i| {
                let k = cond.u[i][0];
                if !cond.kept[i] {
                    return 0.0;
                }
                newton.c_factor * this.schur.get(k, k).abs() / surface.weight[i]
            })
            .collect();
        this.scale = (0..m)
            .map(|k| 1.0 / this.schur.get(k, k).abs().sqrt().max(f64::MIN_POSITIVE))
            .collect();
        for (i, u) in cond.u.iter().enumerate().filter(|(i, _)| cond.kept[*i]) {
            u[..dim].iter().for_each(|&k| this.scale[k] *= surface.weight[i]);
        }
        this
    }

    /// The condensed entries of a global vector, in local coordinates.
    fn gather(&self, x: &[f64]) -> Vec<f64> {
        let cond = self.newton.condensed;
        let mut y: Vec<f64> = cond.global.iter().map(|&g| x[g]).collect();
        let dim = self.newton.step.surface.dim();
        for (i, q) in self.frames.iter().enumerate().filter(|(i, _)| cond.kept[*i]) {
            let idx = &cond.u[i][..dim];
            let u: Vec<f64> = idx.iter().map(|&k| y[k]).collect();
            for (a, &k) in idx.iter().enumerate() {
                y[k] = (0..dim).map(|b| q[a][b] * u[b]).sum();
            }
        }
        y
    }

    /// A condensed vector from local to global coordinates.
    fn to_global(&self, local: &[f64]) -> Vec<f64> {
        let cond = self.newton.condensed;
        let dim = self.newton.step.surface.dim();
        let mut v = local.to_vec();
        for (i, q) in self.frames.iter().enumerate().filter(|(i, _)| cond.kept[*i]) {
            let idx = &cond.u[i][..dim];
            for (b, &k) in idx.iter().enumerate() {
                v[k] = idx.iter().enumerate().map(|(a, &l)| q[a][b] * local[l]).sum();
            }
        }
        v
    }

    /// ϕ at node i, or `None` when the laws that read it are off.
    fn phi(&self, y: &[f64], i: usize) -> Option<f64> {
        match self.newton.condensed.phi[i] {
            Phi::Unknown(p) => Some(y[p]),
            Phi::Prescribed(global) => Some(self.x_hat[global]),
            Phi::Interior => None,
        }
    }

    /// The compliance pressure h_ν p_ν at node i (0 with the laws off).
    fn pressure(&self, u_nu: f64, phi: Option<f64>, i: usize) -> f64 {
        let (step, gap) = (self.newton.step, self.newton.step.surface.gap[i]);
        phi.map_or(0.0, |phi| step.compliance.pressure(u_nu, phi, gap))
    }

    /// ‖scaled E‖².
    fn merit(&self, eval: &Evaluation) -> f64 {
        eval.residual.iter().zip(&self.scale).map(|(r, s)| (r * s).powi(2)).sum()
    }

    /// E, the sets and the multipliers at the condensed iterate y (local coordinates).
    fn evaluate(&self, y: &[f64]) -> Evaluation {
        let (step, cond) = (self.newton.step, self.newton.condensed);
        let (surface, law) = (step.surface, step.compliance);
        let (n3, dim) = (surface.len(), surface.dim());
        let mut forces = self.schur.mul(y);
        forces.iter_mut().zip(&self.load).for_each(|(r, g)| *r -= g);
        let sigma_nu: Vec<f64> = (0..n3)
            .map(|i| if cond.kept[i] { forces[cond.u[i][0]] / surface.weight[i] } else { 0.0 })
            .collect();
        let r_sigma = step.friction.map_or_else(|| sigma_nu.clone(), |(_, r)| r.apply(&sigma_nu));
        let mut eval = Evaluation {
            residual: vec![0.0; y.len()],
            sets: vec![0; n3],
            fixed: vec![false; y.len()],
            multipliers: ContactState::cold(n3),
            forces,
            sigma_nu,
            r_sigma,
        };
        for i in (0..n3).filter(|&i| cond.kept[i]) {
            let (w, u, c) = (surface.weight[i], cond.u[i], self.c[i]);
            let (u_nu, phi) = (y[u[0]], self.phi(y, i));
            let (gap, rho) = (surface.gap[i], law.stop(surface.gap[i]));
            let lambda_c = -eval.sigma_nu[i] - self.pressure(u_nu, phi, i);
            eval.multipliers.lambda_c[i] = lambda_c;
            if lambda_c + c * (u_nu - rho) > 0.0 {
                eval.residual[u[0]] = -c * (u_nu - rho);
                eval.fixed[u[0]] = true;
                eval.sets[i] = 1;
            } else {
                eval.residual[u[0]] = lambda_c;
            }
            let lambda_f: Vec<f64> = (1..dim).map(|a| -eval.forces[u[a]] / w).collect();
            (0..dim - 1).for_each(|a| eval.multipliers.lambda_f[i][a] = lambda_f[a]);
            match step.friction {
                None => (1..dim).for_each(|a| eval.residual[u[a]] = lambda_f[a - 1]),
                Some((mu, _)) => {
                    let s = mu[i] * eval.r_sigma[i].abs();
                    let z: Vec<f64> = (1..dim).map(|a| lambda_f[a - 1] + c * y[u[a]]).collect();
                    let norm = z.iter().map(|v| v * v).sum::<f64>().sqrt();
                    if norm < s {
                        eval.sets[i] += 2;
                        for a in 1..dim {
                            eval.residual[u[a]] = -c * y[u[a]];
                            eval.fixed[u[a]] = true;
                        }
                    } else {
                        for a in 1..dim {
                            let direction = if norm > 0.0 { z[a - 1] / norm } else { 0.0 };
                            eval.residual[u[a]] = lambda_f[a - 1] - s * direction;
                        }
                    }
                }
            }
            if let (Phi::Unknown(p), Some(phi)) = (cond.phi[i], phi) {
                eval.residual[p] = eval.forces[p];
                if let Some(conduction) = step.conduction {
                    eval.residual[p] -= w * conduction.flux(u_nu, phi, gap);
                }
            }
        }
        eval
    }

    /// The Newton step δ at y: the fixed unknowns from their own rows, the others from the
    /// dense system of the remaining rows.
    fn newton_step(&self, y: &[f64], eval: &Evaluation) -> Result<Vec<f64>> {
        let (step, cond) = (self.newton.step, self.newton.condensed);
        let dim = step.surface.dim();
        let m = y.len();
        let mut delta = vec![0.0; m];
        let mut node_of = vec![0; m];
        for (i, u) in cond.u.iter().enumerate().filter(|(i, _)| cond.kept[*i]) {
            u[..dim].iter().for_each(|&k| node_of[k] = i);
            if let Phi::Unknown(p) = cond.phi[i] {
                node_of[p] = i;
            }
            for &k in &u[..dim] {
                if eval.fixed[k] {
                    // −c δ = −E.
                    delta[k] = eval.residual[k] / self.c[i];
                }
            }
        }
        let free: Vec<usize> = (0..m).filter(|&k| !eval.fixed[k]).collect();
        let mut reduced = DenseMatrix::zeros(free.len());
        let mut rhs = vec![0.0; free.len()];
        let mut gradient = vec![0.0; m];
        for (column, &k) in free.iter().enumerate() {
            gradient.iter_mut().for_each(|g| *g = 0.0);
            self.gradient(y, eval, node_of[k], k, &mut gradient);
            let fixed_part: f64 =
                (0..m).filter(|&v| eval.fixed[v]).map(|v| gradient[v] * delta[v]).sum();
            rhs[column] = -eval.residual[k] - fixed_part;
            let out = reduced.col_mut(column);
            free.iter().zip(out.iter_mut()).for_each(|(&v, o)| *o = gradient[v]);
        }
        let solved = reduced.solve_transposed(&rhs)?;
        free.iter().zip(solved).for_each(|(&k, d)| delta[k] = d);
        Ok(delta)
    }

    /// The gradient of the equation of unknown k (node i) with respect to y, added to `out`.
    fn gradient(&self, y: &[f64], eval: &Evaluation, i: usize, k: usize, out: &mut [f64]) {
        let (step, cond) = (self.newton.step, self.newton.condensed);
        let (surface, law) = (step.surface, step.compliance);
        let (w, u, c, dim) = (surface.weight[i], cond.u[i], self.c[i], surface.dim());
        let (u_nu, phi) = (y[u[0]], self.phi(y, i));
        let phi_position = match cond.phi[i] {
            Phi::Unknown(p) => Some(p),
            _ => None,
        };
        let add = |out: &mut [f64], column: usize, factor: f64| {
            out.iter_mut().zip(self.schur.col(column)).for_each(|(o, s)| *o += factor * s);
        };
        if let (true, Some(phi)) = (Some(k) == phi_position, phi) {
            add(out, k, 1.0);
            if let Some(conduction) = step.conduction {
                let (d_u, d_phi) = conduction.flux_derivative(u_nu, phi, surface.gap[i]);
                out[u[0]] -= w * d_u;
                out[k] -= w * d_phi;
            }
            return;
        }
        if k == u[0] {
            // Not in contact: E_n = λ_c = −σ_ν − q.
            let derivative = |phi| law.pressure_derivative(u_nu, phi, surface.gap[i]);
            let (dq_du, dq_dphi) = phi.map_or((0.0, 0.0), derivative);
            add(out, u[0], -1.0 / w);
            out[u[0]] -= dq_du;
            if let Some(p) = phi_position {
                out[p] -= dq_dphi;
            }
            return;
        }
        // A tangential equation, component a = k's place among the tangents.
        let a = (1..dim).find(|&a| u[a] == k).unwrap_or(1);
        let Some((mu, mollifier)) = step.friction else {
            add(out, k, -1.0 / w); // E_t = λ_f = −r_τ / w.
            return;
        };
        // Slip: E_t = λ_f − s ẑ, ∂E_t = ∂λ_f − (s/‖z‖)(I − λ̃ẑᵀ)(∂λ_f + c ∂u_τ) − ẑ ∂s.
        let lambda_f: Vec<f64> = (1..dim).map(|b| eval.multipliers.lambda_f[i][b - 1]).collect();
        let z: Vec<f64> = (1..dim).map(|b| lambda_f[b - 1] + c * y[u[b]]).collect();
        let norm = z.iter().map(|v| v * v).sum::<f64>().sqrt();
        let s = mu[i] * eval.r_sigma[i].abs();
        let z_hat: Vec<f64> = z.iter().map(|v| if norm > 0.0 { v / norm } else { 0.0 }).collect();
        let lambda_norm = lambda_f.iter().map(|v| v * v).sum::<f64>().sqrt();
        let bound = s.max(lambda_norm).max(f64::MIN_POSITIVE);
        let ratio = if norm > 0.0 { s / norm } else { 0.0 };
        for b in 1..dim {
            // Coefficient of ∂z_b in row a of (s/‖z‖)(I − λ̃ẑᵀ).
            let identity = if a == b { 1.0 } else { 0.0 };
            let coefficient = ratio * (identity - lambda_f[a - 1] / bound * z_hat[b - 1]);
            // ∂λ_f,b = −S_{τb,·} / w.
            add(out, u[b], -(identity - coefficient) / w);
            out[u[b]] -= coefficient * c;
        }
        if s > 0.0 {
            let sign = mu[i] * eval.r_sigma[i].signum() * z_hat[a - 1];
            for (j, weight) in mollifier.row(i).into_iter().filter(|(j, _)| cond.kept[*j]) {
                // ∂σ_ν,j = S_{ν_j,·} / w_j.
                add(out, cond.u[j][0], -sign * weight / surface.weight[j]);
            }
        }
    }

    /// The step length: the first of 1, ½, ¼, … (2⁻⁸ at the least) that decreases ‖scaled
    /// E‖² enough (Armijo), else the full step.
    fn line_search(&self, y: &[f64], delta: &[f64], current: f64) -> f64 {
        let mut alpha = 1.0;
        for _ in 0..=HALVINGS {
            let trial: Vec<f64> = y.iter().zip(delta).map(|(a, d)| a + alpha * d).collect();
            if self.merit(&self.evaluate(&trial)) <= (1.0 - 1e-4 * alpha) * current {
                return alpha;
            }
            alpha *= 0.5;
        }
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_condensed_problem_too_large_for_memory_is_refused() {
        let many = Condensed {
            free: vec![0; 30_000],
            global: Vec::new(),
            u: Vec::new(),
            phi: Vec::new(),
            kept: Vec::new(),
            with_phi: false,
        };
        assert!(many.check_memory(64.0 * 2f64.powi(30)).is_ok());
        let e = many.check_memory(16.0 * 2f64.powi(30)).unwrap_err().to_string();
        assert!(
            e.contains("30000 unknowns") && e.contains("33.5 GiB") && e.contains("uzawa"),
            "{e}"
        );
    }
}
