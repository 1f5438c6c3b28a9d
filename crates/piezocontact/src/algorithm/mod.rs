//! The outer fixed point of \[P\] Section 6 — Algorithm 1 (PV2) and Algorithm 3 (PV1) — around
//! an inner method (model §7): the paper's Uzawa block relaxation ([`uzawa`], Algorithms 2
//! and 4) or the exact solver ([`newton`], model §11). The outer loop knows no method: it
//! asks an [`InnerMethod`] to set up the coupled system with the caller's linear solver, to
//! solve each outer step, and to say how its stops read; adding a method touches the method's
//! own module and the case's `solver.method` table.
//!
//! One outer step n: linearise Hencky's law at x_n — the secant moduli of the paper's fixed
//! point when the method lags the contact terms, the consistent tangent (a Newton iteration on
//! the law) when it solves them exactly (model §13) — and factorise B̌(x_n) (only when the
//! linearisation changed); solve the contact problem of the step; compute σ_ν and the
//! friction bound s_{n+1} = µ|Rσ_ν(x_{n+1})| ([`crate::contact::model`]); stop on the criteria
//! (6.13)/(6.15) when the method lags the contact terms, or when the linearisation no longer
//! changes (or the step is below the tolerance) when it does not. The reported number of outer iterations is n + 1 at the stop, as Table 2 counts.
//! Hitting an iteration cap is not a silent stop: the result carries
//! [`Error::NotConverged`] naming the loop and its last criterion. A growing criterion
//! ([`Error::Diverged`]), a singular matrix or a NaN ([`Error::NumericalFailure`]) stop the run
//! the same way, keeping the last finite iterate.

pub mod condensed;
pub mod newton;
pub mod residual;
pub mod uzawa;

use crate::assembly::{Beyond, Linearisation, MassNorm, NodalBlock, secant_moduli};
use crate::contact::law::FrictionPath;
use crate::contact::model::{nodal_mu, stress_and_bound};
use crate::contact::{ContactModel, ContactState, ContactSurface, Mollifier, NodeStatus};
use crate::dofs::DofMap;
use crate::error::{Error, Result};
use crate::linalg::{LinearSolver, SolverStats, default_solver};
use crate::problem::Problem;
use crate::solver::{CoupledSystem, Timings};
use residual::{Balance, KktResidual};

/// What the outer loop asks of an inner method.
pub trait InnerMethod: std::fmt::Debug + Send + Sync {
    /// The name a case file uses for it (`solver.method`).
    fn name(&self) -> &'static str;
    /// The same method and parameters with no state, for a new solve.
    fn fresh(&self) -> Box<dyn InnerMethod>;
    /// Whether the outer loop lags the contact terms — the friction bound s, the compliance
    /// h_ν p_ν and the conduction ψ φ_L at x_n — as Algorithms 1 and 3 do, with Hencky's
    /// secant (true), or the method solves them at the solution, so that the outer loop only
    /// iterates on Hencky's law, by Newton with its consistent tangent (false).
    fn lags_contact(&self) -> bool;
    /// The constant c > 0 [stress/length] of the complementarity functions by which the KKT
    /// residual measures the contact and friction conditions (model §10).
    fn complementarity_constant(&self) -> f64;
    /// The outer loop stops when its criterion is below this [-].
    fn outer_tolerance(&self) -> f64;
    /// Sets the method up for a solve and builds the coupled system with the caller's
    /// `solver`; refuses a solver that lacks a capability the method needs.
    fn prepare(&mut self, setup: Setup, solver: Box<dyn LinearSolver>) -> Result<CoupledSystem>;
    /// The nodal blocks that the method adds to B̌ on the Γ3 nodes.
    fn blocks(&self) -> &[NodalBlock];
    /// Told before the outer loop factorises `system` (first, and whenever Hencky's
    /// linearisation has changed): the method may order its unknowns anew.
    fn before_factorisation(&mut self, system: &mut CoupledSystem) -> Result<()> {
        let _ = system;
        Ok(())
    }
    /// Solves the contact problem of one outer step with the factorised `system`.
    fn solve(&mut self, step: &Step, system: &mut CoupledSystem) -> Result<InnerResult>;
    /// How a stop of outer step `outer_step` reads in an error.
    fn stop_context(&self, outer_step: usize, pv2: bool) -> StopContext;
    /// A final check of the solution's KKT residual, `None` when it is accepted.
    fn accept(&self, kkt: &KktResidual, outer_history: &[f64]) -> Option<Error> {
        let _ = (kkt, outer_history);
        None
    }
    /// The Γ3 nodes in the method's condensed problem at the end (0 without one).
    fn condensed_nodes(&self) -> usize {
        0
    }
    /// The bytes of the method's dense matrices for its condensed problem (0 without one).
    fn dense_bytes(&self) -> f64 {
        0.0
    }
    /// The time spent on the method's condensed problem outside the system's counted phases
    /// ([`crate::solver::Timings::dense`]), over every step so far \[s\].
    fn dense_seconds(&self) -> f64 {
        0.0
    }
}

/// Parameters of the outer fixed point and the inner method.
#[derive(Debug)]
pub struct Settings {
    /// The inner method.
    pub method: Box<dyn InnerMethod>,
    /// Cap on fixed-point iterations.
    pub max_outer: usize,
}

impl Settings {
    /// `method` with at most `max_outer` fixed-point iterations.
    pub fn new(method: impl InnerMethod + 'static, max_outer: usize) -> Self {
        Self { method: Box::new(method), max_outer }
    }
}

impl Clone for Settings {
    fn clone(&self) -> Self {
        Self { method: self.method.fresh(), max_outer: self.max_outer }
    }
}

/// What an inner method reads when it sets up a solve.
pub struct Setup<'a> {
    /// The problem.
    pub problem: &'a Problem,
    /// The DOF numbering, for the coupled system.
    pub dofs: DofMap,
    /// Γ3, with the gaps to the foundation.
    pub surface: &'a ContactSurface,
    /// The contact laws.
    pub model: &'a ContactModel,
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
    /// The run was asked to stop ([`crate::interrupt`]), by this signal.
    Interrupted(i32),
    /// The iterates came back to where they were this many steps before, a whole period
    /// over, and would go round again.
    Cycle(usize),
}

/// How an inner method's stops read in errors.
#[derive(Clone, Debug)]
pub struct StopContext {
    /// The loop, e.g. "the Uzawa loop (Algorithm 2) of outer step 3".
    pub what: String,
    /// The value its criterion must fall below.
    pub tolerance: f64,
    /// The advice when it hits its cap.
    pub cap_hint: String,
    /// The advice when it diverges or fails.
    pub hint: String,
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

/// The data of one outer step that an inner method reads.
pub struct Step<'a> {
    /// The problem.
    pub problem: &'a Problem,
    /// The L2(Ω) norm of the stopping rules.
    pub mass: &'a MassNorm,
    /// Γ3.
    pub surface: &'a ContactSurface,
    /// The contact laws.
    pub model: &'a ContactModel,
    /// µ per Γ3 node (PV2; empty for PV1).
    pub mu: &'a [f64],
    /// R of the friction bound.
    pub mollifier: &'a Mollifier,
    /// x_n: the previous outer iterate (global; zero at the first step).
    pub previous: &'a [f64],
    /// s_n on the Γ3 nodes: the friction bound at x_n \[stress\] (zero for PV1).
    pub friction_bound: &'a [f64],
    /// Hencky's law linearised at x_n, with which B̌ was factorised.
    pub linearisation: &'a Linearisation,
    /// The state the slip is measured from (global; the previous step of a loading path with
    /// incremental friction), `None` for the paper's static law (from the reference).
    pub slip_origin: Option<&'a [f64]>,
    /// Told of every inner iteration.
    pub progress: &'a (dyn Fn(Progress) + Sync),
}

impl Step<'_> {
    /// µ per node and R, with friction (PV2).
    pub fn friction(&self) -> Option<(&[f64], &Mollifier)> {
        self.model.pv2.as_ref().map(|_| (self.mu, self.mollifier))
    }
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
    /// A numeric factorisation of B̌ starts (it may take minutes in 3D; the next event says
    /// it ended).
    Factorising {
        /// The order of the matrix (the free unknowns).
        unknowns: usize,
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
    /// s_n: the friction bound used in the last inner solve \[stress\].
    pub s_used: Vec<f64>,
    /// s_{n+1} = µ|Rσ_ν(x_{n+1})|: the friction bound of the last outer step \[stress\].
    pub s: Vec<f64>,
    /// σ_ν on the Γ3 nodes \[stress\].
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
    /// The state the slip is measured from (global), empty for the static law.
    pub slip_origin: Vec<f64>,
    /// The outer steps in which the exact solver floored Hencky's tangent beyond e·t0
    /// (model §13).
    pub floored_steps: usize,
    /// The outer steps that were chord steps on a kept factorisation of the floored tangent
    /// instead of a factorisation (model §13).
    pub chord_steps: usize,
}

/// Solves PV1 (Algorithm 3 around the inner method) or PV2 (Algorithm 1 around it) with the
/// default linear solver, on a thread of rayon's global pool: called from outside it, each of
/// faer's parallel calls would be handed to the pool and waited for (model §13).
pub fn solve_contact(
    problem: &Problem,
    model: &ContactModel,
    settings: &Settings,
) -> Result<ContactSolution> {
    rayon::scope(|_| solve_contact_with(problem, model, settings, default_solver(), &|_| {}))
}

/// [`solve_contact`] with the caller's linear `solver`, telling `progress` of each outer step
/// and inner iteration.
pub fn solve_contact_with(
    problem: &Problem,
    model: &ContactModel,
    settings: &Settings,
    solver: Box<dyn LinearSolver>,
    progress: &(dyn Fn(Progress) + Sync),
) -> Result<ContactSolution> {
    ContactSolver::new(problem, model, settings, solver)?.solve(problem, model, progress)
}

/// The outer loop around an inner method, kept between solves of one body: a loading path
/// (model §14) solves the same mesh again with the foundation moved or the loads scaled,
/// with the pattern, the symbolic analysis, the factorisation (while Hencky's linearisation
/// does not change), the method's state (the exact solver's condensation) and the last
/// solution — the next solve's first iterate — kept.
pub struct ContactSolver {
    method: Box<dyn InnerMethod>,
    system: CoupledSystem,
    fixed: Fixed,
    /// Γ3's geometry (the gaps are set by each solve).
    surface: ContactSurface,
    /// Hencky's law linearised at the last solution (at 0 before the first solve).
    linearisation: Linearisation,
    /// Whether B̌ must be factorised with `linearisation` before the next step.
    changed: bool,
    /// What the tangent of `linearisation` does beyond t = e·t0.
    beyond: Beyond,
    /// How often Newton's whole tangent failed in this solve (its criterion grew, or B̌ lost
    /// its signs): once (or floored by the last solve), the floored tangent takes one step;
    /// twice, every step after.
    whole_failures: usize,
    /// Whether the factorisation holds B̌ with the floored tangent: once the floor stays,
    /// the steps are chord steps on it while they contract (model §13).
    floored_factor: bool,
    max_outer: usize,
    /// The load factor f̌ was assembled with.
    load_factor: f64,
    /// x and s of the last solve.
    last: Option<(Vec<f64>, Vec<f64>)>,
}

impl ContactSolver {
    /// Sets up the method and the coupled system of `problem` with the caller's `solver`.
    pub fn new(
        problem: &Problem,
        model: &ContactModel,
        settings: &Settings,
        solver: Box<dyn LinearSolver>,
    ) -> Result<Self> {
        let mut method = settings.method.fresh();
        let dofs = DofMap::new(problem)?;
        let surface = ContactSurface::new(problem, &dofs)?.with_gaps(
            problem,
            &model.foundation,
            model.compliance.gap,
        );
        let system = method.prepare(Setup { problem, dofs, surface: &surface, model }, solver)?;
        let fixed = Fixed::new(problem, &surface, model)?;
        let zero = vec![0.0; system.dofs().n_total()];
        let lags = method.lags_contact();
        let linearisation = linearise(problem, system.dofs(), &zero, lags, Beyond::Whole)?;
        let max_outer = settings.max_outer;
        Ok(Self {
            method,
            system,
            fixed,
            surface,
            linearisation,
            changed: true,
            beyond: Beyond::Whole,
            whole_failures: 0,
            floored_factor: false,
            max_outer,
            load_factor: problem.load_factor,
            last: None,
        })
    }

    /// What the first factorisation and the method's dense matrices will take, as predicted
    /// by the symbolic analysis [`ContactSolver::new`] made: the solver's statistics (factor
    /// entries, ordering, bytes), the bytes of the dense condensed matrices and their Γ3
    /// nodes (0 and 0 without a condensed problem).
    pub fn predicted_memory(&self) -> (SolverStats, f64, usize) {
        let method = self.method.as_ref();
        (self.system.solver_stats(), method.dense_bytes(), method.condensed_nodes())
    }

    /// Solves `problem` (that of [`ContactSolver::new`], its loads scaled by its `load_factor`) in
    /// contact with `model`'s foundation, from the last solution (from 0 the first time).
    pub fn solve(
        &mut self,
        problem: &Problem,
        model: &ContactModel,
        progress: &(dyn Fn(Progress) + Sync),
    ) -> Result<ContactSolution> {
        let surface =
            self.surface.clone().with_gaps(problem, &model.foundation, model.compliance.gap);
        let mut solution = ContactSolution::start(surface, self.system.dofs().n_total());
        if let Some((x, s)) = &self.last {
            (solution.x, solution.s) = (x.clone(), s.clone());
            if model.pv2.as_ref().is_some_and(|(f, _)| f.path == FrictionPath::Incremental) {
                solution.slip_origin = x.clone();
            }
        }
        if problem.load_factor != self.load_factor {
            self.system.reload(problem);
            self.load_factor = problem.load_factor;
        }
        let lags = self.method.lags_contact();
        // The linearisation of the last solve is kept (floored or not), its failures are not.
        self.whole_failures = 0;
        // Chord steps since the last factorisation.
        let mut chords = 0;
        for n in 1..=self.max_outer {
            if let Some(signal) = crate::interrupt::requested() {
                solution.failure = Some(Error::Interrupted { signal });
                break;
            }
            progress(Progress::Outer { step: n, max: self.max_outer });
            if self.changed && self.chord_contracts(&solution.outer_history, chords) {
                let blocks = self.method.blocks();
                if let Err(e) = self.system.chord(problem, &self.linearisation, blocks, &solution.x)
                {
                    solution.failure = Some(factorisation_failure(n, e));
                    break;
                }
                solution.chord_steps += 1;
                chords += 1;
            } else if self.changed {
                chords = 0;
                progress(Progress::Factorising { unknowns: self.system.dofs().n_free() });
                if let Err(e) = self.factorise(problem, &solution.x) {
                    solution.failure = Some(factorisation_failure(n, e));
                    break;
                }
            }
            self.changed = false;
            let s_n = solution.s.clone();
            solution.floored_steps += usize::from(self.beyond == Beyond::Floored);
            let (fixed, linearisation) = (&self.fixed, &self.linearisation);
            let step = fixed.step(problem, model, &solution, &s_n, linearisation, progress);
            let inner = self.method.solve(&step, &mut self.system)?;
            let failure = inner_failure(&self.method.stop_context(n, model.pv2.is_some()), &inner);
            solution.outer_iterations = n;
            let x_previous = solution.record(inner, s_n, lags, model, fixed, &self.system);
            if failure.is_some() {
                solution.failure = failure;
                break;
            }
            let criterion = self.relinearise(problem, &mut solution, &x_previous)?;
            if criterion < self.method.outer_tolerance() {
                solution.converged = true;
                break;
            }
            if lags && let Some(failure) = outer_failure(model, &solution) {
                solution.failure = Some(failure);
                break;
            }
        }
        let solution = self.finish(problem, model, solution)?;
        self.last = Some((solution.x.clone(), solution.s.clone()));
        Ok(solution)
    }

    /// After an outer step: Hencky's law linearised at its solution for the next step, and its
    /// criterion, pushed onto the history. Newton's whole tangent can cycle on a law that is
    /// not positive beyond e·t0: when its criterion grows while some element is there, it
    /// fails, and the floored tangent takes the next step (`whole_failures`).
    fn relinearise(
        &mut self,
        problem: &Problem,
        solution: &mut ContactSolution,
        x_previous: &[f64],
    ) -> Result<f64> {
        let (dofs, lags) = (self.system.dofs(), self.method.lags_contact());
        if self.beyond == Beyond::Floored && self.whole_failures < 2 {
            self.beyond = Beyond::Whole;
        }
        let mut next = linearise(problem, dofs, &solution.x, lags, self.beyond)?;
        let changed = next != self.linearisation;
        let criterion =
            self.fixed.outer_criterion(problem, &self.system, solution, x_previous, changed, lags);
        let grows = solution.outer_history.last().is_some_and(|last| criterion > *last);
        if !lags && self.beyond == Beyond::Whole && grows {
            let floored = linearise(problem, dofs, &solution.x, lags, Beyond::Floored)?;
            if floored != next {
                next = floored;
                (self.beyond, self.whole_failures) = (Beyond::Floored, self.whole_failures + 1);
            }
        }
        self.changed = next != self.linearisation;
        solution.outer_history.push(criterion);
        self.linearisation = next;
        Ok(criterion)
    }

    /// Whether the next step is a chord step on the factorisation held: once the floor stays
    /// (Newton's whole tangent failed twice) and B̌ was factorised with it, when the last
    /// step's criterion fell and, after a chord step, by a ratio at most the square root of
    /// the last fresh factorisation's (half its digits or more). The floored tangent
    /// converges linearly, and so does the chord on it, at the cost of solves instead of a
    /// factorisation per step.
    fn chord_contracts(&self, history: &[f64], chords: usize) -> bool {
        let ratio = |k: usize| history[k] / history[k - 1];
        let n = history.len();
        // The ratio of the last step on a fresh factorisation, and of the last step.
        let fresh = n.checked_sub(chords + 1).filter(|&k| k >= 1).map(ratio);
        let last = (n >= 2).then(|| ratio(n - 1));
        let contracts = match (fresh, last) {
            (Some(fresh), Some(last)) if chords > 0 => last <= fresh.sqrt(),
            (_, Some(last)) => last < 1.0,
            _ => false,
        };
        self.floored_factor && self.whole_failures >= 2 && contracts
    }

    /// Factorises B̌ with the linearisation made at `x` (x_n). When the whole tangent gives a
    /// pivot of the wrong sign (Hencky's law not positive beyond e·t0 in enough elements that
    /// B̌ is no longer quasi-definite), it fails (`whole_failures`) and the floored tangent at
    /// x is factorised instead.
    fn factorise(&mut self, problem: &Problem, x: &[f64]) -> Result<()> {
        self.method.before_factorisation(&mut self.system)?;
        let blocks = self.method.blocks();
        let factorised = self.system.factorize_linearised(problem, &self.linearisation, blocks);
        let lags = self.method.lags_contact();
        self.floored_factor = self.beyond == Beyond::Floored && factorised.is_ok();
        if !matches!(factorised, Err(Error::SingularSystem { .. })) || self.beyond != Beyond::Whole
        {
            return factorised;
        }
        let floored = linearise(problem, self.system.dofs(), x, lags, Beyond::Floored)?;
        if floored == self.linearisation {
            return factorised;
        }
        self.linearisation = floored;
        (self.beyond, self.whole_failures) = (Beyond::Floored, self.whole_failures + 1);
        let factorised = self.system.factorize_linearised(problem, &self.linearisation, blocks);
        self.floored_factor = factorised.is_ok();
        factorised
    }

    /// The end of a solve: the cap's error if no other stop, timings, the residuals, and the
    /// method's last word on them.
    fn finish(
        &self,
        problem: &Problem,
        model: &ContactModel,
        mut solution: ContactSolution,
    ) -> Result<ContactSolution> {
        let method = self.method.as_ref();
        if !solution.converged && solution.failure.is_none() {
            solution.failure = Some(outer_cap(model, &solution, self.max_outer, method));
        }
        solution.timings = self.system.timings();
        solution.timings.dense_bytes = method.dense_bytes();
        solution.timings.dense = method.dense_seconds();
        solution.condensed_nodes = method.condensed_nodes();
        solution.dofs = self.system.dofs().clone();
        let constant = method.complementarity_constant();
        (solution.kkt, solution.balance) = residual::assess(problem, model, constant, &solution)?;
        if solution.converged
            && let Some(failure) = method.accept(&solution.kkt, &solution.outer_history)
        {
            solution.converged = false;
            solution.failure = Some(failure);
        }
        Ok(solution)
    }
}

/// What stays the same over the outer steps: the norm of the stopping rules, R and µ.
struct Fixed {
    mass: MassNorm,
    mollifier: Mollifier,
    mu: Vec<f64>,
}

impl Fixed {
    fn new(problem: &Problem, surface: &ContactSurface, model: &ContactModel) -> Result<Self> {
        let mu = model
            .pv2
            .as_ref()
            .map_or_else(Vec::new, |(friction, _)| nodal_mu(problem, surface, friction));
        Ok(Self {
            mass: MassNorm::new(problem)?,
            mollifier: Mollifier::new(problem, surface, model)?,
            mu,
        })
    }

    /// The data of the outer step from x_n = `solution.x` and s_n.
    fn step<'a>(
        &'a self,
        problem: &'a Problem,
        model: &'a ContactModel,
        solution: &'a ContactSolution,
        friction_bound: &'a [f64],
        linearisation: &'a Linearisation,
        progress: &'a (dyn Fn(Progress) + Sync),
    ) -> Step<'a> {
        Step {
            problem,
            mass: &self.mass,
            surface: &solution.surface,
            model,
            mu: &self.mu,
            mollifier: &self.mollifier,
            previous: &solution.x,
            friction_bound,
            linearisation,
            slip_origin: (!solution.slip_origin.is_empty()).then_some(&solution.slip_origin),
            progress,
        }
    }

    /// The outer criterion after a step. With the contact terms lagged: (6.13)
    /// ‖s_{n+1} − s_n‖/‖s_{n+1}‖ for PV2 with s ≢ 0, else (6.15) ‖x_{n+1} − x_n‖/‖x_{n+1}‖,
    /// and the larger of both while Hencky's moduli still change. Without lagging, the loop is
    /// the Newton iteration of Hencky's law alone, done when the linearisation at the solution
    /// is the one it was solved with (criterion 0: the law is linear or secant there), else
    /// (6.15).
    fn outer_criterion(
        &self,
        problem: &Problem,
        system: &CoupledSystem,
        solution: &ContactSolution,
        x_previous: &[f64],
        linearisation_changed: bool,
        lags: bool,
    ) -> f64 {
        let x_criterion =
            relative_change(problem, system.dofs(), &self.mass, &solution.x, x_previous);
        if !lags {
            return if linearisation_changed { x_criterion } else { 0.0 };
        }
        match solution.friction_bound_change() {
            Some(s_criterion) if linearisation_changed => s_criterion.max(x_criterion),
            Some(s_criterion) => s_criterion,
            None => x_criterion,
        }
    }
}

/// Hencky's law at x_n as the outer loop uses it: the secant (model §7) when the method lags
/// the contact terms — the paper's fixed point — and else the consistent tangent with the
/// secant as its fallback (model §13), a Newton iteration on the law around an exact inner
/// solve.
fn linearise(
    problem: &Problem,
    dofs: &DofMap,
    x: &[f64],
    lags: bool,
    beyond: Beyond,
) -> Result<Linearisation> {
    if lags {
        Ok(Linearisation::secant(secant_moduli(problem, dofs, x)?))
    } else {
        Linearisation::tangent(problem, dofs, x, beyond)
    }
}

/// The error of a failed factorisation of B̌(x_n) in outer step n.
fn factorisation_failure(n: usize, e: Error) -> Error {
    let what = format!("the factorisation of B̌(x_n) in outer step {n}");
    match e {
        Error::SingularSystem { .. } => Error::NumericalFailure {
            what,
            iteration: n,
            cause: e.to_string(),
            hint: "a singular matrix means the body is not held (Γ1, Γa) or a material constant \
                   is not physical"
                .into(),
        },
        // A backend's own failure (memory, MUMPS's diagnostics) says what to change itself.
        Error::LinearAlgebra(cause) => Error::LinearAlgebra(format!("{what}: {cause}")),
        other => other,
    }
}

/// The name of the fixed-point loop in messages.
fn outer_loop_name(model: &ContactModel) -> String {
    format!("the fixed-point loop (Algorithm {})", if model.pv2.is_some() { 1 } else { 3 })
}

/// The way out of a fixed point that the lagged contact terms defeat.
const NOT_LAGGED: &str = "solver.method = \"newton\" (the exact solver) solves the same problem \
                          without lagging them";

/// The error of a fixed-point loop that reached solver.max_outer.
fn outer_cap(
    model: &ContactModel,
    solution: &ContactSolution,
    max_outer: usize,
    method: &dyn InnerMethod,
) -> Error {
    Error::NotConverged {
        what: outer_loop_name(model),
        iterations: solution.outer_iterations,
        criterion: solution.outer_history.last().copied().unwrap_or(f64::NAN),
        tolerance: method.outer_tolerance(),
        history: tail(&solution.outer_history),
        hint: if method.lags_contact() {
            format!(
                "raise solver.max_outer (now {max_outer}); a criterion that stalls means the \
                 lagged contact terms (h_ν, ψ, the friction bound) are too strong for the fixed \
                 point: {NOT_LAGGED}"
            )
        } else {
            format!(
                "raise solver.max_outer (now {max_outer}); the loop iterates on Hencky's law \
                 alone (summary.json's hencky_tangent says where its tangent was floored)"
            )
        },
    }
}

/// The error for an inner loop that stopped without converging: the one place where stops
/// become errors, with the method's hints.
fn inner_failure(context: &StopContext, inner: &InnerResult) -> Option<Error> {
    let StopContext { what, tolerance, cap_hint, hint } = context.clone();
    let history = tail(&inner.history);
    let iteration = inner.iterations;
    let criterion = inner.history.last().copied().unwrap_or(f64::NAN);
    let not_converged = |what, history, hint| {
        Some(Error::NotConverged {
            what,
            iterations: iteration,
            criterion,
            tolerance,
            history,
            hint,
        })
    };
    match &inner.stop {
        Stop::Converged => None,
        Stop::Cap => not_converged(
            what,
            history,
            match stalled(&inner.history) {
                Some(last) => format!(
                    "its criterion has not fallen by 1 % in its last {last} iterations, where \
                     more would not help: {hint}"
                ),
                None => cap_hint,
            },
        ),
        Stop::Cycle(period) => not_converged(
            what,
            history,
            format!(
                "its iterates cycle: each of its last {period} is, to round-off, the one \
                 {period} steps before it, so more iterations would not help: {hint}"
            ),
        ),
        Stop::Diverged => Some(Error::Diverged { what, iteration, history, hint }),
        Stop::NotFinite(cause) => {
            Some(Error::NumericalFailure { what, iteration, cause: cause.clone(), hint })
        }
        Stop::Interrupted(signal) => Some(Error::Interrupted { signal: *signal }),
    }
}

/// The length of the second half of a criterion history (10 values or more) whose least
/// value is not 1 % below the first half's — a cycle or a stall — else `None`.
fn stalled(history: &[f64]) -> Option<usize> {
    let half = history.len() / 2;
    let least = |values: &[f64]| values.iter().copied().fold(f64::INFINITY, f64::min);
    let stalled = history.len() >= 10 && least(&history[half..]) >= 0.99 * least(&history[..half]);
    stalled.then_some(history.len() - half)
}

/// The last values of a criterion history, for messages.
pub(crate) fn tail(history: &[f64]) -> String {
    let start = history.len().saturating_sub(5);
    let values: Vec<String> = history[start..].iter().map(|v| format!("{v:.3e}")).collect();
    values.join(", ")
}

/// A non-finite outer criterion or friction bound, or a growing outer criterion.
fn outer_failure(model: &ContactModel, solution: &ContactSolution) -> Option<Error> {
    let n = solution.outer_iterations;
    let what = outer_loop_name(model);
    let last = *solution.outer_history.last()?;
    let hint = format!(
        "the lagged contact terms are too strong for the fixed point: reduce conductivity.ke, \
         contact.c_nu or contact.penetration, or {NOT_LAGGED}"
    );
    if !last.is_finite() || solution.s.iter().any(|v| !v.is_finite()) {
        let cause = "the criterion or the friction bound s is not finite".into();
        return Some(Error::NumericalFailure { what, iteration: n, cause, hint });
    }
    let smallest = solution.outer_history.iter().copied().fold(f64::INFINITY, f64::min);
    (n >= 3 && last > DIVERGENCE * smallest).then(|| Error::Diverged {
        what,
        iteration: n,
        history: tail(&solution.outer_history),
        hint,
    })
}

/// ‖a − b‖ / ‖a‖ in the L2(Ω) norm of (6.15).
fn relative_change(problem: &Problem, dofs: &DofMap, mass: &MassNorm, a: &[f64], b: &[f64]) -> f64 {
    let difference: Vec<f64> = a.iter().zip(b).map(|(p, q)| p - q).collect();
    let norm = mass.squared(problem, dofs, a);
    if norm > 0.0 { (mass.squared(problem, dofs, &difference) / norm).sqrt() } else { 0.0 }
}

impl ContactSolution {
    /// The state before the first outer step: x_0 = 0, λ = 0, s_0 = 0.
    fn start(surface: ContactSurface, n_total: usize) -> Self {
        let n3 = surface.len();
        Self {
            kkt: KktResidual::default(),
            balance: Balance::default(),
            condensed_nodes: 0,
            x: vec![0.0; n_total],
            dofs: DofMap::default(),
            surface,
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
            slip_origin: Vec::new(),
            floored_steps: 0,
            chord_steps: 0,
        }
    }

    /// Takes the inner result of a step solved with the friction bound `s_n`: x_{n+1}, λ,
    /// σ_ν and s_{n+1} = µ|Rσ_ν(x_{n+1})|. Returns x_n.
    fn record(
        &mut self,
        inner: InnerResult,
        s_n: Vec<f64>,
        lags: bool,
        model: &ContactModel,
        fixed: &Fixed,
        system: &CoupledSystem,
    ) -> Vec<f64> {
        self.inner_iterations.push(inner.iterations);
        self.inner_history.push(inner.history);
        let x_previous = std::mem::replace(&mut self.x, inner.x);
        self.state = inner.state;
        let friction = model.pv2.as_ref().map(|_| (&fixed.mu[..], &fixed.mollifier));
        let at = (system.dofs(), &self.surface);
        (self.sigma_nu, self.s) = stress_and_bound(at, model, friction, &self.x, &self.state);
        // A method that solves friction at the solution used s_{n+1} itself.
        self.s_used = if lags { s_n } else { self.s.clone() };
        x_previous
    }

    /// ‖s_{n+1} − s_n‖ / ‖s_{n+1}‖ in L2(Γ3), (6.13); `None` when s ≡ 0.
    fn friction_bound_change(&self) -> Option<f64> {
        let w = &self.surface.weight;
        let s_norm: f64 = self.s.iter().zip(w).map(|(s, w)| w * s.powi(2)).sum();
        let ds: f64 =
            self.s.iter().zip(&self.s_used).zip(w).map(|((s, t), w)| w * (s - t).powi(2)).sum();
        (s_norm > 0.0).then(|| (ds / s_norm).sqrt())
    }

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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solver::solve_without_contact;
    use crate::testing::{PAPER_72, built};

    /// An inner method that ignores contact: each step is the solve without contact forces,
    /// and it stops as it is told. It shows what the outer loop does on its own.
    #[derive(Clone, Debug)]
    struct Stub {
        lags: bool,
        stop: Stop,
        reject: bool,
    }

    impl InnerMethod for Stub {
        fn name(&self) -> &'static str {
            "stub"
        }
        fn fresh(&self) -> Box<dyn InnerMethod> {
            Box::new(self.clone())
        }
        fn lags_contact(&self) -> bool {
            self.lags
        }
        fn complementarity_constant(&self) -> f64 {
            1.0
        }
        fn outer_tolerance(&self) -> f64 {
            1e-8
        }
        fn prepare(
            &mut self,
            setup: Setup,
            solver: Box<dyn LinearSolver>,
        ) -> Result<CoupledSystem> {
            CoupledSystem::new(setup.problem, setup.dofs, &[], solver)
        }
        fn blocks(&self) -> &[NodalBlock] {
            &[]
        }
        fn solve(&mut self, step: &Step, system: &mut CoupledSystem) -> Result<InnerResult> {
            let x = system.solve(None)?;
            let state = ContactState::cold(step.surface.len());
            Ok(InnerResult {
                x,
                state,
                iterations: 3,
                history: vec![0.5, 0.1],
                stop: self.stop.clone(),
            })
        }
        fn stop_context(&self, outer_step: usize, _pv2: bool) -> StopContext {
            StopContext {
                what: format!("the stub of outer step {outer_step}"),
                tolerance: 0.25,
                cap_hint: "the cap hint".into(),
                hint: "the hint".into(),
            }
        }
        fn accept(&self, _kkt: &KktResidual, _outer_history: &[f64]) -> Option<Error> {
            self.reject.then(|| Error::Input("rejected by the stub".into()))
        }
    }

    /// Example 7.2 (PV2) on a coarse mesh with the linear law: the stub's iterate, the solve
    /// without contact, sinks into the foundation, so σ_ν < 0 and s > 0 on part of Γ3.
    const COARSE: [&str; 3] = ["mesh.nx=12", "mesh.ny=2", "material.law=\"linear\""];

    fn run(stub: Stub, max_outer: usize) -> ContactSolution {
        let built = built(PAPER_72, &COARSE);
        let settings = Settings::new(stub, max_outer);
        let model = built.model.unwrap();
        solve_contact(&built.problem, &model, &settings).unwrap()
    }

    #[test]
    fn a_lagging_method_stops_when_the_iterate_settles() {
        let stub = Stub { lags: true, stop: Stop::Converged, reject: false };
        let solution = run(stub, 10);
        // s_1 from s_0 = 0: a change of 100 % (6.13); s_2 = s_1: none.
        assert!(solution.converged && solution.failure.is_none());
        assert_eq!(solution.outer_history, vec![1.0, 0.0]);
        assert_eq!((solution.outer_iterations, solution.inner_iterations.clone()), (2, vec![3, 3]));
        // Hencky's moduli never change with the linear law: one factorisation serves both steps.
        assert_eq!(solution.timings.numeric_count, 1);
        let problem = built(PAPER_72, &COARSE).problem;
        assert_eq!(solution.x, solve_without_contact(&problem, default_solver()).unwrap().x);
        // The lagged friction bound: after one step, the step used s_0 = 0 and s_1 > 0 waits.
        let one = run(Stub { lags: true, stop: Stop::Converged, reject: false }, 1);
        assert!(one.s_used.iter().all(|s| *s == 0.0) && one.s.iter().any(|s| *s > 0.0));
    }

    #[test]
    fn a_method_that_does_not_lag_stops_when_the_moduli_settle() {
        let solution = run(Stub { lags: false, stop: Stop::Converged, reject: false }, 10);
        assert!(solution.converged);
        assert_eq!((solution.outer_iterations, solution.outer_history.clone()), (1, vec![0.0]));
        // Nothing lagged: the step "used" the bound of its own solution.
        assert!(solution.s.iter().any(|s| *s > 0.0) && solution.s_used == solution.s);
    }

    #[test]
    fn inner_stops_become_errors_with_the_method_s_words() {
        for (stop, variant) in [
            (Stop::Cap, "NotConverged"),
            (Stop::Cycle(5), "NotConverged"),
            (Stop::Diverged, "Diverged"),
            (Stop::NotFinite("a NaN".into()), "NumericalFailure"),
        ] {
            let (capped, cycled) = (matches!(stop, Stop::Cap), matches!(stop, Stop::Cycle(_)));
            let solution = run(Stub { lags: true, stop, reject: false }, 10);
            assert!(!solution.converged);
            assert_eq!(solution.outer_iterations, 1, "{variant}: the loop stops at once");
            let failure = solution.failure.unwrap();
            assert!(format!("{failure:?}").starts_with(variant), "{failure:?}");
            let text = failure.to_string();
            assert!(text.contains("the stub of outer step 1"), "{text}");
            let hint = if capped { "the cap hint" } else { "the hint" };
            assert!(text.contains(hint), "{text}");
            if cycled {
                assert!(text.contains("cycle: each of its last 5") && !text.contains("cap hint"));
            }
        }
    }

    /// A cap reached by a cycle or a stall says that more iterations would not help; one
    /// reached while the criterion still falls keeps the cap hint.
    #[test]
    fn a_cap_reached_without_progress_is_told_from_a_slow_one() {
        let cycle: Vec<f64> = (0..100).map(|k| [2.7, 0.57, 0.12, 0.97, 42.0][k % 5]).collect();
        assert_eq!(stalled(&cycle), Some(50));
        let slow: Vec<f64> = (0..100).map(|k| 0.98_f64.powi(k)).collect();
        assert_eq!(stalled(&slow), None);
        assert_eq!(stalled(&cycle[..9]), None, "too short to judge");
        let inner = |history: Vec<f64>| InnerResult {
            x: vec![],
            state: ContactState::cold(0),
            iterations: history.len(),
            history,
            stop: Stop::Cap,
        };
        let context = Stub { lags: false, stop: Stop::Cap, reject: false }.stop_context(1, false);
        let text = |history| inner_failure(&context, &inner(history)).unwrap().to_string();
        let (cycling, falling) = (text(cycle), text(slow));
        assert!(cycling.contains("last 50 iterations") && cycling.contains("the hint"));
        assert!(!cycling.contains("the cap hint"), "{cycling}");
        assert!(falling.contains("the cap hint") && !falling.contains("last 50"), "{falling}");
    }

    /// A singular B̌ is blamed on the supports; a backend's own failure (here MUMPS out of
    /// its memory cap) keeps its own advice, without that blame; an interruption stays one.
    #[test]
    fn a_failed_factorisation_says_why_in_the_words_of_its_cause() {
        let singular = factorisation_failure(2, Error::SingularSystem { detail: "pivot 7".into() });
        let text = singular.to_string();
        assert!(matches!(singular, Error::NumericalFailure { iteration: 2, .. }), "{text}");
        assert!(text.contains("outer step 2") && text.contains("not held (Γ1, Γa)"), "{text}");
        let mumps = "MUMPS factorisation failed with INFOG(1) = -19, INFOG(2) = 3: the memory cap";
        let memory = factorisation_failure(1, Error::LinearAlgebra(mumps.into())).to_string();
        assert!(memory.contains("outer step 1") && memory.contains(mumps), "{memory}");
        assert!(!memory.contains("not held"), "{memory}");
        let stopped = factorisation_failure(1, Error::Interrupted { signal: 2 });
        assert!(matches!(stopped, Error::Interrupted { signal: 2 }));
    }

    #[test]
    fn the_outer_cap_and_the_method_s_verdict_are_failures() {
        let solution = run(Stub { lags: true, stop: Stop::Converged, reject: false }, 1);
        let failure = solution.failure.unwrap().to_string();
        assert!(!solution.converged && failure.contains("fixed-point loop (Algorithm 1)"));
        assert!(failure.contains("solver.max_outer (now 1)"), "{failure}");
        let solution = run(Stub { lags: true, stop: Stop::Converged, reject: true }, 10);
        assert!(!solution.converged && solution.outer_iterations == 2);
        assert!(solution.failure.unwrap().to_string().contains("rejected by the stub"));
    }
}
