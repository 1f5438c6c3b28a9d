//! The fixed-point iterations of [P] Section 6 around the Uzawa loop:
//! Algorithm 1 (PV2: friction and conduction, inner Algorithm 2) and Algorithm 3 (PV1,
//! inner Algorithm 4), as restated in model §7.
//!
//! ```text
//! x_0 = 0, s_0 = 0
//! step n:  g_n = g(‖ε^D(u_n)‖²) per element;  factor B̌(x_n) + r M   (only when g_n changed)
//!          f_{1,n} = f̌ − j̃1(x_n, ·) − ľ(x_n, ·)          (PV1: f̌ − j̃1(x_n, ·))
//!          x_{n+1} = Uzawa(f_{1,n}, s_n)                   (cold start)
//!          s_{n+1} = µ |R σ_ν(x_{n+1})|,  σ_ν = −(λ_c + h_ν(ϕ−ϕ0) p_ν(u_ν − g_a))
//! stop:    ‖s_{n+1} − s_n‖ / ‖s_{n+1}‖ < ε_fp   (6.13, PV2 with s ≢ 0)
//!          ‖x_{n+1} − x_n‖ / ‖x_{n+1}‖ < ε_fp   (6.15, PV1; PV2 when s ≡ 0; and also
//!                                                  whenever the Hencky secant is active)
//! ```
//!
//! The reported number of outer iterations is n + 1 at the stop, as Table 2 counts.
//! Hitting an iteration cap is not a silent stop: the result carries
//! [`Error::NotConverged`] naming the loop and its last criterion. A growing criterion
//! ([`Error::Diverged`]), a singular matrix or a NaN ([`Error::NumericalFailure`]) stop the run
//! the same way, keeping the last finite iterate.

pub mod newton;
pub mod residual;
pub mod uzawa;

use crate::assembly::{MassNorm, NodalBlock, secant_moduli};
use crate::contact::law::{Conduction, Friction, NormalCompliance, Regularization};
use crate::contact::{ContactSurface, Foundation};
use crate::dofs::{CONSTRAINED, DofMap};
use crate::error::{Error, Result};
use crate::problem::Problem;
use crate::solver::{CoupledSystem, Timings};
use kiddo::{ImmutableKdTree, SquaredEuclidean};
use newton::Condensed;
use residual::{Balance, KktResidual};
use uzawa::Uzawa;

/// The method that solves the contact problem of one outer step (model §7).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Method {
    /// The augmented Lagrangian Uzawa block relaxation, Algorithms 2 and 4, started cold.
    Uzawa {
        /// r > 0: augmented Lagrangian parameter [stress/length] (paper: 0.25 E).
        r: f64,
        /// ε of (6.12)/(6.16) (paper: 1e−4).
        eps: f64,
        /// Cap on Uzawa iterations per outer step.
        max_inner: usize,
    },
    /// The exact solver: semismooth Newton on the problem condensed onto Γ3 (model §11).
    Newton {
        /// r > 0 [stress/length]: the constant of the KKT residual; the Newton method uses
        /// c_i = (r/E)·S_νν,i/w_i, r scaled by the stiffness of Γ3 node i. The answer does
        /// not depend on it.
        r: f64,
        /// The run stops when the KKT residual is at most this [-].
        tol: f64,
        /// Cap on Newton steps per outer step.
        max_inner: usize,
        /// The most Γ3 nodes condensed into the dense problem. A Γ3 with more nodes within
        /// the foundation's reach starts from the nodes nearest to it, and trades clear
        /// nodes for left-out nodes that turn out to touch (model §11).
        max_condensed: usize,
    },
}

impl Method {
    /// The name a case file uses for it (`solver.method`).
    pub fn name(&self) -> &'static str {
        match self {
            Self::Uzawa { .. } => "uzawa",
            Self::Newton { .. } => "newton",
        }
    }

    /// Whether the method solves the discrete problem itself — contact, friction with
    /// s = µ|Rσ_ν(x)|, compliance and conduction at the solution, not lagged — so that the outer
    /// loop only updates Hencky's secant moduli.
    pub fn is_exact(&self) -> bool {
        matches!(self, Self::Newton { .. })
    }

    /// The constant c > 0 of the complementarity functions λ − max(0, λ + c(u_ν − ρ)) and
    /// λ_f − P_s(λ_f + c u_τ) by which the KKT residual measures the contact and friction
    /// conditions [stress/length].
    pub fn complementarity_constant(&self) -> f64 {
        match self {
            Self::Uzawa { r, .. } => *r,
            Self::Newton { r, .. } => *r,
        }
    }
}

/// Parameters of the outer fixed point and the inner method.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// The inner method.
    pub method: Method,
    /// ε_fp of (6.13)/(6.15) (paper: 1e−4).
    pub eps_fp: f64,
    /// Cap on fixed-point iterations.
    pub max_outer: usize,
}

/// The multipliers on the Γ3 nodes.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ContactState {
    /// λ_c: contact pressure of the rigid stop [stress].
    pub lambda_c: Vec<f64>,
    /// λ_f: friction traction (σ_τ = −λ_f) [stress], 3 components (d used).
    pub lambda_f: Vec<[f64; 3]>,
}

impl ContactState {
    /// λ = 0 on `n` nodes.
    pub fn cold(n: usize) -> Self {
        Self { lambda_c: vec![0.0; n], lambda_f: vec![[0.0; 3]; n] }
    }
}

/// Why an inner loop stopped.
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

/// What the inner method produced in one outer step.
#[derive(Clone, Debug)]
pub struct InnerResult {
    /// The last finite iterate x (global vector).
    pub x: Vec<f64>,
    /// The multipliers with it.
    pub state: ContactState,
    /// Iterations done.
    pub iterations: usize,
    /// The method's criterion at each iteration.
    pub history: Vec<f64>,
    /// Why the loop stopped.
    pub stop: Stop,
}

/// The data of one outer step that the inner method reads.
pub struct Step<'a> {
    /// The problem.
    pub problem: &'a Problem,
    /// The L2(Ω) norm of the stopping rules.
    pub mass: &'a MassNorm,
    /// Γ3.
    pub surface: &'a ContactSurface,
    /// The normal law (for the rigid stop ρ = g_a + g_p).
    pub compliance: &'a NormalCompliance,
    /// s_n on the Γ3 nodes with friction (PV2), `None` without.
    pub friction_bound: Option<&'a [f64]>,
    /// f_{1,n} − f̌ on the free DOFs: the lagged −j̃1(x_n) − ľ(x_n).
    pub base: &'a [f64],
    /// µ per Γ3 node and R, with friction (PV2).
    pub friction: Option<(&'a [f64], &'a Mollifier)>,
    /// The conduction law, with a conductive foundation (PV2).
    pub conduction: Option<&'a Conduction>,
    /// The previous outer iterate x_n (global; zero at the first step).
    pub start: &'a [f64],
    /// Told of every inner iteration.
    pub progress: &'a dyn Fn(Progress),
}

/// What a running solve reports to the observer of [`solve_contact_with`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Progress {
    /// Outer step `step` (from 1) of at most `max` starts.
    Outer {
        /// The step.
        step: usize,
        /// solver.max_outer.
        max: usize,
    },
    /// An iteration of the inner method ended.
    Inner {
        /// The iteration (from 1) within the outer step.
        iteration: usize,
        /// Its stopping criterion: Uzawa's (6.12)/(6.16), or Newton's relative step.
        criterion: f64,
        /// The value the criterion must fall below.
        tolerance: f64,
    },
}

/// The nodal blocks that `method` adds to B̌ on the Γ3 nodes.
fn method_blocks(method: &Method, surface: &ContactSurface, friction: bool) -> Vec<NodalBlock> {
    match method {
        Method::Uzawa { r, .. } => step1_blocks(surface, *r, friction),
        Method::Newton { .. } => Vec::new(),
    }
}

/// Runs `method` on one outer step with the `system` factorised with the moduli `g`.
fn run_inner(
    method: &Method,
    step: &Step,
    condensed: &mut Condensed,
    system: &mut CoupledSystem,
    g: &[f64],
) -> Result<InnerResult> {
    match *method {
        Method::Uzawa { r, eps, max_inner } => Uzawa { step, r, eps, max_inner }.run(system),
        Method::Newton { r, max_inner, max_condensed, .. } => {
            let c_factor = r / step.problem.material.elasticity.young();
            let parameters =
                newton::Parameters { c_factor, max_iterations: max_inner, max_condensed };
            newton::solve(step, parameters, condensed, system, g)
        }
    }
}

/// The error for an inner loop that stopped without converging: the one place where stops
/// become errors, with a hint on the method's parameters.
fn inner_failure(method: &Method, inner: &InnerResult, pv2: bool, step: usize) -> Option<Error> {
    let (what, tolerance, cap_hint, hint) = match *method {
        Method::Uzawa { r, eps, max_inner } => {
            let algorithm = if pv2 { 2 } else { 4 };
            let hint = format!(
                "r too small or too large for this problem: try solver.r = {:.4e} or {:.4e} (now {r:.4e}; the paper uses 0.25 E)",
                2.0 * r,
                0.5 * r,
            );
            let what = format!("the Uzawa loop (Algorithm {algorithm}) of outer step {step}");
            (what, eps, format!("raise solver.max_inner (now {max_inner}), or {hint}"), hint)
        }
        Method::Newton { max_inner, .. } => {
            let hint = "the active set cycles or the Jacobian is singular: check that Γ3 can \
                        touch the foundation only where the body is held, and report the case \
                        if it persists"
                .to_string();
            let what = format!("the semismooth Newton method of outer step {step}");
            let cap = format!("raise solver.max_inner (now {max_inner}); {hint}");
            (what, newton::STEP_TOLERANCE, cap, hint)
        }
    };
    let history = tail(&inner.history);
    let iteration = inner.iterations;
    match &inner.stop {
        Stop::Converged => None,
        Stop::Cap => Some(Error::NotConverged {
            what,
            iterations: iteration,
            criterion: inner.history.last().copied().unwrap_or(f64::NAN),
            tolerance,
            history,
            hint: cap_hint,
        }),
        Stop::Diverged => Some(Error::Diverged { what, iteration, history, hint }),
        Stop::NotFinite(cause) => {
            Some(Error::NumericalFailure { what, iteration, cause: cause.clone(), hint })
        }
    }
}

/// The contact model: normal compliance, and for PV2 friction and conduction.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactModel {
    /// p_ν, h_ν, the gap and the stop.
    pub compliance: NormalCompliance,
    /// `None`: PV1 (frictionless, nonconductive). `Some`: PV2.
    pub pv2: Option<(Friction, Conduction)>,
    /// The foundation's surface, which sets the gap of every Γ3 node (model §12).
    pub foundation: Foundation,
}

impl ContactModel {
    /// "PV1" or "PV2".
    pub fn name(&self) -> &'static str {
        if self.pv2.is_some() { "PV2" } else { "PV1" }
    }
}

/// The result of Algorithm 1 or 3.
#[derive(Clone, Debug)]
pub struct ContactSolution {
    /// x = (u, ϕ), global vector.
    pub x: Vec<f64>,
    /// The DOF numbering of `x`.
    pub dofs: DofMap,
    /// Γ3 and its nodal geometry.
    pub surface: ContactSurface,
    /// The multipliers of the last inner solve.
    pub state: ContactState,
    /// s_n: the friction bound used in the last inner solve [stress].
    pub s_used: Vec<f64>,
    /// s_{n+1} = µ|Rσ_ν(x_{n+1})|: the friction bound of the last outer step [stress].
    pub s: Vec<f64>,
    /// σ_ν on the Γ3 nodes [stress].
    pub sigma_nu: Vec<f64>,
    /// Whether both loops met their stopping rules.
    pub converged: bool,
    /// Why not, if not.
    pub failure: Option<Error>,
    /// Outer iterations, counted as Table 2 counts them.
    pub outer_iterations: usize,
    /// Inner iterations of each outer step.
    pub inner_iterations: Vec<usize>,
    /// The outer criterion at each step.
    pub outer_history: Vec<f64>,
    /// The inner criterion at each iteration of each outer step.
    pub inner_history: Vec<Vec<f64>>,
    /// Time spent in each phase.
    pub timings: Timings,
    /// The Γ3 nodes in the exact solver's dense problem at the end (0 for Uzawa).
    pub condensed_nodes: usize,
    /// The residual of the discrete KKT conditions at `x` (model §10).
    pub kkt: KktResidual,
    /// The global force balance at `x`.
    pub balance: Balance,
}

/// Solves PV1 (Algorithm 3 around the inner method) or PV2 (Algorithm 1 around it).
pub fn solve_contact(
    problem: &Problem,
    model: &ContactModel,
    settings: &Settings,
) -> Result<ContactSolution> {
    solve_contact_with(problem, model, settings, &|_| {})
}

/// [`solve_contact`], telling `progress` of each outer step and inner iteration.
pub fn solve_contact_with(
    problem: &Problem,
    model: &ContactModel,
    settings: &Settings,
    progress: &dyn Fn(Progress),
) -> Result<ContactSolution> {
    let dofs = DofMap::new(problem)?;
    let surface = ContactSurface::new(problem, &dofs)?.with_gaps(
        problem,
        &model.foundation,
        model.compliance.gap,
    );
    let max_condensed = match settings.method {
        Method::Newton { max_condensed, .. } => max_condensed,
        Method::Uzawa { .. } => usize::MAX,
    };
    let with_phi = model.compliance.penetration > 0.0;
    let mut condensed = Condensed::new(&dofs, &surface, with_phi, max_condensed);
    let exact = settings.method.is_exact();
    if exact {
        condensed.check_memory(crate::limits::available_memory())?;
    }
    let blocks = method_blocks(&settings.method, &surface, model.pv2.is_some());
    let mut system = if exact {
        CoupledSystem::with_last(problem, dofs, &condensed.free)?
    } else {
        CoupledSystem::new(problem, dofs, &surface.nodes)?
    };
    let mass = MassNorm::new(problem)?;
    let mollifier = Mollifier::new(problem, &surface, model)?;
    let mu = model
        .pv2
        .as_ref()
        .map_or_else(Vec::new, |(friction, _)| nodal_mu(problem, &surface, friction));
    let n3 = surface.len();
    let mut solution = ContactSolution {
        kkt: KktResidual::default(),
        balance: Balance::default(),
        condensed_nodes: 0,
        x: vec![0.0; system.dofs().n_total()],
        dofs: DofMap::default(),
        surface: surface.clone(),
        state: ContactState::cold(n3),
        s_used: vec![0.0; n3],
        s: vec![0.0; n3],
        sigma_nu: vec![0.0; n3],
        converged: false,
        failure: None,
        outer_iterations: 0,
        inner_iterations: Vec::new(),
        outer_history: Vec::new(),
        inner_history: Vec::new(),
        timings: Timings::default(),
    };
    let mut g = secant_moduli(problem, system.dofs(), &solution.x)?;
    let mut factorised_with: Option<Vec<f64>> = None;
    for n in 0..settings.max_outer {
        progress(Progress::Outer { step: n + 1, max: settings.max_outer });
        if factorised_with.as_ref() != Some(&g) {
            if let Err(e) = system.factorize(problem, &g, &blocks) {
                solution.failure = Some(Error::NumericalFailure {
                    what: format!("the factorisation of B̌(x_n) in outer step {}", n + 1),
                    iteration: n + 1,
                    cause: e.to_string(),
                    hint: "a singular matrix means the body is not held (Γ1, Γa) or a material \
                           constant is not physical"
                        .into(),
                });
                break;
            }
            factorised_with = Some(g.clone());
        }
        let base = if exact {
            vec![0.0; system.dofs().n_free()]
        } else {
            lagged_loads(system.dofs(), &surface, model, &solution.x)
        };
        let s_n = solution.s.clone();
        let step = Step {
            problem,
            mass: &mass,
            surface: &surface,
            compliance: &model.compliance,
            friction_bound: model.pv2.as_ref().map(|_| s_n.as_slice()),
            base: &base,
            friction: model.pv2.as_ref().map(|_| (mu.as_slice(), &mollifier)),
            conduction: model.pv2.as_ref().map(|(_, conduction)| conduction),
            start: &solution.x,
            progress,
        };
        let inner = run_inner(&settings.method, &step, &mut condensed, &mut system, &g)?;
        solution.inner_iterations.push(inner.iterations);
        solution.inner_history.push(inner.history.clone());
        solution.outer_iterations = n + 1;
        let failure = inner_failure(&settings.method, &inner, model.pv2.is_some(), n + 1);
        let dofs = system.dofs();
        let x_previous = std::mem::replace(&mut solution.x, inner.x);
        solution.state = inner.state;
        solution.s_used = s_n;
        solution.sigma_nu = normal_stress(dofs, &surface, model, &solution.x, &solution.state);
        solution.s = match &model.pv2 {
            Some(_) => mollifier
                .apply(&solution.sigma_nu)
                .iter()
                .zip(&mu)
                .map(|(sn, mu)| mu * sn.abs())
                .collect(),
            None => vec![0.0; n3],
        };
        if exact {
            solution.s_used = solution.s.clone();
        }
        if failure.is_some() {
            solution.failure = failure;
            break;
        }
        let g_next = secant_moduli(problem, dofs, &solution.x)?;
        let x_criterion = relative_change(problem, dofs, &mass, &solution.x, &x_previous);
        if let Method::Newton { tol, .. } = settings.method {
            // Exact inner solves: the outer loop is the secant iteration of Hencky's law,
            // done when the moduli at the solution are those it was solved with.
            let criterion = if g_next == g { 0.0 } else { x_criterion };
            solution.outer_history.push(criterion);
            g = g_next;
            if criterion <= tol {
                solution.converged = true;
                break;
            }
            continue;
        }
        let s_norm: f64 = (0..n3).map(|i| surface.weight[i] * solution.s[i].powi(2)).sum();
        let criterion = if model.pv2.is_some() && s_norm > 0.0 {
            let ds: f64 = (0..n3)
                .map(|i| surface.weight[i] * (solution.s[i] - solution.s_used[i]).powi(2))
                .sum();
            let s_criterion = (ds / s_norm).sqrt();
            if g_next != g { s_criterion.max(x_criterion) } else { s_criterion }
        } else {
            x_criterion
        };
        solution.outer_history.push(criterion);
        g = g_next;
        if criterion < settings.eps_fp {
            solution.converged = true;
            break;
        }
        if let Some(failure) = outer_failure(model, &solution) {
            solution.failure = Some(failure);
            break;
        }
    }
    if !solution.converged && solution.failure.is_none() {
        solution.failure = Some(Error::NotConverged {
            what: format!(
                "the fixed-point loop (Algorithm {})",
                if model.pv2.is_some() { 1 } else { 3 }
            ),
            iterations: solution.outer_iterations,
            criterion: solution.outer_history.last().copied().unwrap_or(f64::NAN),
            tolerance: settings.eps_fp,
            history: tail(&solution.outer_history),
            hint: format!(
                "raise solver.max_outer (now {}); a criterion that stalls means the lagged contact \
                 terms (h_ν, ψ) are too strong for the fixed point",
                settings.max_outer
            ),
        });
    }
    solution.timings = system.timings();
    solution.condensed_nodes = if exact { condensed.node_count() } else { 0 };
    solution.dofs = system.into_dofs();
    (solution.kkt, solution.balance) = residual::assess(problem, model, settings, &solution)?;
    if let Method::Newton { tol, .. } = settings.method
        && solution.converged
        && (solution.kkt.max > tol || solution.kkt.max.is_nan())
    {
        solution.converged = false;
        solution.failure = Some(Error::NotConverged {
            what: "the exact solver".into(),
            iterations: solution.outer_iterations,
            criterion: solution.kkt.max,
            tolerance: tol,
            history: tail(&solution.outer_history),
            hint: "the KKT residual stays above solver.tol: round-off of an ill-conditioned \
                   problem, or a tolerance below what double precision reaches here"
                .into(),
        });
    }
    Ok(solution)
}

/// The last values of a criterion history, for messages.
fn tail(history: &[f64]) -> String {
    let start = history.len().saturating_sub(5);
    let values: Vec<String> = history[start..].iter().map(|v| format!("{v:.3e}")).collect();
    values.join(", ")
}

/// A non-finite outer criterion or friction bound, or a growing outer criterion.
fn outer_failure(model: &ContactModel, solution: &ContactSolution) -> Option<Error> {
    let n = solution.outer_iterations;
    let what =
        format!("the fixed-point loop (Algorithm {})", if model.pv2.is_some() { 1 } else { 3 });
    let last = *solution.outer_history.last()?;
    let hint = "the lagged contact terms are too strong for the fixed point: reduce \
                conductivity.ke, contact.c_nu or contact.penetration";
    if !last.is_finite() || solution.s.iter().any(|v| !v.is_finite()) {
        let cause = "the criterion or the friction bound s is not finite".into();
        return Some(Error::NumericalFailure { what, iteration: n, cause, hint: hint.into() });
    }
    let smallest = solution.outer_history.iter().copied().fold(f64::INFINITY, f64::min);
    (n >= 3 && last > DIVERGENCE * smallest).then(|| Error::Diverged {
        what,
        iteration: n,
        history: tail(&solution.outer_history),
        hint: hint.into(),
    })
}

/// µ on each Γ3 node: the case's µ, or the mean of the µ of the parts a node belongs to.
fn nodal_mu(problem: &Problem, surface: &ContactSurface, friction: &Friction) -> Vec<f64> {
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

impl ContactSolution {
    /// The status of Γ3 node i: separated when σ_ν = 0; in PV2 slip when λ_f is on the
    /// friction bound s_n of the last Uzawa loop (to a relative 1e−9), stick otherwise.
    pub fn status(&self, i: usize, pv2: bool) -> NodeStatus {
        if self.sigma_nu[i] >= 0.0 {
            return NodeStatus::Separated;
        }
        if !pv2 {
            return NodeStatus::Contact;
        }
        let traction = self.state.lambda_f[i].iter().map(|v| v * v).sum::<f64>().sqrt();
        if traction >= self.s_used[i] * (1.0 - 1e-9) { NodeStatus::Slip } else { NodeStatus::Stick }
    }
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
        let pressure = model.compliance.pressure(u_nu, phi, surface.gap[i]);
        for c in 0..surface.dim() {
            let k = dofs.free_index(dofs.u(node, c));
            if k != CONSTRAINED {
                base[k] -= w * pressure * surface.normal[i][c];
            }
        }
        if let Some((_, conduction)) = &model.pv2 {
            let k = dofs.free_index(dofs.phi(node));
            if k != CONSTRAINED {
                base[k] += w * conduction.flux(u_nu, phi, surface.gap[i]);
            }
        }
    }
    base
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
            -(state.lambda_c[i] + model.compliance.pressure(u_nu, phi, surface.gap[i]))
        })
        .collect()
}

/// ‖a − b‖ / ‖a‖ in the L2(Ω) norm of (6.15).
fn relative_change(problem: &Problem, dofs: &DofMap, mass: &MassNorm, a: &[f64], b: &[f64]) -> f64 {
    let difference: Vec<f64> = a.iter().zip(b).map(|(p, q)| p - q).collect();
    let norm = mass.squared(problem, dofs, a);
    if norm > 0.0 { (mass.squared(problem, dofs, &difference) / norm).sqrt() } else { 0.0 }
}

/// The regularisation R of the friction bound as a sparse averaging operator on the Γ3 nodes.
pub struct Mollifier {
    /// For each node, (j, weight) with weights summing to 1; empty for R = identity.
    rows: Vec<Vec<(usize, f64)>>,
}

impl Mollifier {
    fn new(problem: &Problem, surface: &ContactSurface, model: &ContactModel) -> Result<Self> {
        let Some((Friction { regularization: Regularization::Mollifier { radius }, .. }, _)) =
            &model.pv2
        else {
            return Ok(Self { rows: Vec::new() });
        };
        // Neighbourhoods by radius queries in a k-d tree of the Γ3 nodes, not all pairs.
        let points: Vec<[f64; 3]> =
            (0..surface.len()).map(|i| surface.position3(problem, i)).collect();
        let tree = ImmutableKdTree::new_from_slice(&points).map_err(|e| {
            Error::Input(format!("friction.regularization: the k-d tree of the Γ3 nodes: {e:?}"))
        })?;
        let rows = points
            .iter()
            .map(|xi| {
                let mut row: Vec<(usize, f64)> = tree
                    .query(xi)
                    .within::<SquaredEuclidean<f64>>(radius * radius)
                    .unsorted()
                    .execute()
                    .into_iter()
                    .filter_map(|found| {
                        let (j, t) = (found.item as usize, found.distance / (radius * radius));
                        (t < 1.0).then(|| (j, surface.weight[j] * (1.0 - t).powi(2)))
                    })
                    .collect();
                row.sort_by_key(|&(j, _)| j);
                let total: f64 = row.iter().map(|(_, w)| w).sum();
                row.iter_mut().for_each(|(_, w)| *w /= total);
                row
            })
            .collect();
        Ok(Self { rows })
    }

    /// R σ_ν on the Γ3 nodes.
    pub fn apply(&self, sigma_nu: &[f64]) -> Vec<f64> {
        if self.rows.is_empty() {
            return sigma_nu.to_vec();
        }
        self.rows.iter().map(|row| row.iter().map(|&(j, w)| w * sigma_nu[j]).sum()).collect()
    }

    /// Row i of R: (j, R_ij).
    pub fn row(&self, i: usize) -> Vec<(usize, f64)> {
        self.rows.get(i).cloned().unwrap_or_else(|| vec![(i, 1.0)])
    }
}
