//! The outer fixed point of \[P\] Section 6 — Algorithm 1 (PV2) and Algorithm 3 (PV1) —
//! around an inner method (model §7).
//!
//! One outer step n: linearise Hencky's law at x_n ([`Hencky`]) and factorise B̌(x_n) when the
//! linearisation changed; solve the contact problem of the step with the inner method; record
//! σ_ν and the friction bound s_{n+1} = µ|Rσ_ν(x_{n+1})|; stop on the criteria (6.13)/(6.15)
//! when the method lags the contact terms, or when the linearisation no longer changes (or the
//! step is below the tolerance) when it does not. The reported number of outer iterations is
//! n + 1 at the stop, as Table 2 counts. Hitting an iteration cap is not a silent stop: the
//! result carries [`Error::NotConverged`] naming the loop and its last criterion. A growing
//! criterion ([`Error::Diverged`]), a singular matrix or a NaN ([`Error::NumericalFailure`])
//! stop the run the same way, keeping the last finite iterate.

use super::hencky::Hencky;
use super::inner::{InnerMethod, Progress, Setup, Step};
use super::residual;
use super::solution::ContactSolution;
use super::stops::{factorisation_failure, inner_failure, outer_cap, outer_failure};
use crate::assembly::MassNorm;
use crate::contact::law::FrictionPath;
use crate::contact::{ContactModel, ContactSurface, NodalFriction};
use crate::dofs::DofMap;
use crate::error::{Error, Result};
use crate::linalg::{LinearSolver, SolverStats, default_solver};
use crate::problem::{Factors, Problem};
use crate::system::CoupledSystem;

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

/// Solves PV1 (Algorithm 3 around the inner method) or PV2 (Algorithm 1 around it) under the
/// case's loads with the default linear solver, on a thread of rayon's global pool: called
/// from outside it, each of faer's parallel calls would be handed to the pool and waited for
/// (model §13).
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
    ContactSolver::new(problem, model, settings, solver)?.solve(problem, model, 1.0, progress)
}

/// The outer loop around an inner method, kept between solves of one body: a loading path
/// (model §14) solves the same mesh again with the foundation moved or the loads scaled,
/// with the pattern, the symbolic analysis, the factorisation (while Hencky's linearisation
/// does not change), the method's state (the exact solver's condensation) and the last
/// solution — the next solve's first iterate — kept.
pub struct ContactSolver {
    method: Box<dyn InnerMethod>,
    system: CoupledSystem,
    /// The L2(Ω) norm of the stopping rules.
    mass: MassNorm,
    /// µ_i and R on Γ3 (PV2).
    friction: Option<NodalFriction>,
    /// Γ3's geometry (the gaps are set by each solve).
    surface: ContactSurface,
    /// Hencky's law linearised at the last iterate.
    hencky: Hencky,
    max_outer: usize,
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
        let friction = model.friction.as_ref().map(|f| NodalFriction::new(problem, &surface, f));
        let hencky = Hencky::new(problem, system.dofs(), method.lags_contact())?;
        Ok(Self {
            method,
            system,
            mass: MassNorm::new(problem)?,
            friction: friction.transpose()?,
            surface,
            hencky,
            max_outer: settings.max_outer,
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

    /// Solves `problem` (that of [`ContactSolver::new`]) with its loads and electrodes scaled
    /// by `factors` (a bare factor [-] on both), in contact with `model`'s foundation, from the last solution (from 0
    /// the first time).
    pub fn solve(
        &mut self,
        problem: &Problem,
        model: &ContactModel,
        factors: impl Into<Factors>,
        progress: &(dyn Fn(Progress) + Sync),
    ) -> Result<ContactSolution> {
        let factors = factors.into();
        self.system.scale_loads(problem, factors);
        let mut solution = self.start(problem, model, factors);
        self.hencky.start(self.system.lifting_stale());
        solution.failure = self.iterate(problem, model, &mut solution, progress)?;
        let solution = self.finish(problem, model, solution)?;
        self.last = Some((solution.x.clone(), solution.s.clone()));
        Ok(solution)
    }

    /// The first iterate of a solve: the last solution (measuring the slip from it under
    /// incremental friction), or 0.
    fn start(&self, problem: &Problem, model: &ContactModel, factors: Factors) -> ContactSolution {
        let surface =
            self.surface.clone().with_gaps(problem, &model.foundation, model.compliance.gap);
        let dofs = self.system.dofs().clone();
        let mut solution = ContactSolution::start(surface, dofs, factors);
        if let Some((x, s)) = &self.last {
            (solution.x, solution.s) = (x.clone(), s.clone());
            if model.friction.as_ref().is_some_and(|f| f.path == FrictionPath::Incremental) {
                solution.slip_origin = x.clone();
            }
        }
        solution
    }

    /// The outer steps until a stopping rule holds (`None`) or a stop that is a failure.
    fn iterate(
        &mut self,
        problem: &Problem,
        model: &ContactModel,
        solution: &mut ContactSolution,
        progress: &(dyn Fn(Progress) + Sync),
    ) -> Result<Option<Error>> {
        let lags = self.method.lags_contact();
        for n in 1..=self.max_outer {
            if let Some(signal) = crate::interrupt::requested() {
                return Ok(Some(Error::Interrupted { signal }));
            }
            progress(Progress::Outer { step: n, max: self.max_outer });
            let at = (problem, solution.x.as_slice(), solution.outer_history.as_slice());
            if let Err(e) =
                self.hencky.prepare(at, self.method.as_mut(), &mut self.system, progress)
            {
                return Ok(Some(factorisation_failure(n, e)));
            }
            let s_n = solution.s.clone();
            let step = Step {
                problem,
                mass: &self.mass,
                surface: &solution.surface,
                model,
                friction: self.friction.as_ref(),
                previous: &solution.x,
                friction_bound: &s_n,
                linearisation: self.hencky.current(),
                slip_origin: (!solution.slip_origin.is_empty()).then_some(&solution.slip_origin),
                progress,
            };
            let inner = self.method.solve(&step, &mut self.system)?;
            let friction = model.friction.is_some();
            let failure = inner_failure(&self.method.stop_context(n, friction), &inner);
            let x_previous = solution.record(inner, model, self.friction.as_ref());
            if failure.is_some() {
                return Ok(failure);
            }
            let criterion = self.relinearise(problem, solution, &x_previous, &s_n)?;
            if criterion < self.method.outer_tolerance() {
                return Ok(None);
            }
            if lags && let Some(failure) = outer_failure(model, solution) {
                return Ok(Some(failure));
            }
        }
        Ok(Some(outer_cap(model, solution, self.max_outer, self.method.as_ref())))
    }

    /// Hencky's law linearised at the step's solution, and the step's criterion, pushed onto
    /// the history. With the contact terms lagged: (6.13) ‖s_{n+1} − s_n‖/‖s_{n+1}‖ for PV2
    /// with s ≢ 0, else (6.15) ‖x_{n+1} − x_n‖/‖x_{n+1}‖, and the larger of both while Hencky's
    /// moduli still change. Without lagging, the loop is the Newton iteration of Hencky's law
    /// alone, done when the linearisation at the solution is the one it was solved with
    /// (criterion 0: the law is linear or secant there), else (6.15).
    fn relinearise(
        &mut self,
        problem: &Problem,
        solution: &mut ContactSolution,
        x_previous: &[f64],
        s_n: &[f64],
    ) -> Result<f64> {
        let (dofs, lags) = (self.system.dofs(), self.method.lags_contact());
        let mass = &self.mass;
        let criterion = |changed: bool| {
            let x_criterion = relative_change(problem, dofs, mass, &solution.x, x_previous);
            if !lags {
                return if changed { x_criterion } else { 0.0 };
            }
            match solution.friction_bound_change(s_n) {
                Some(s_criterion) if changed => s_criterion.max(x_criterion),
                Some(s_criterion) => s_criterion,
                None => x_criterion,
            }
        };
        let at = (problem, dofs, solution.x.as_slice());
        let criterion = self.hencky.relinearise(at, &solution.outer_history, criterion)?;
        solution.outer_history.push(criterion);
        Ok(criterion)
    }

    /// The end of a solve: timings, the residuals (with the linear solver's work freed), and
    /// the method's last word on them.
    fn finish(
        &mut self,
        problem: &Problem,
        model: &ContactModel,
        mut solution: ContactSolution,
    ) -> Result<ContactSolution> {
        let method = self.method.as_ref();
        solution.timings = self.system.timings();
        solution.timings.dense_bytes = method.dense_bytes();
        solution.timings.dense = method.dense_seconds();
        solution.condensed_nodes = method.condensed_nodes();
        let steps = self.hencky.steps();
        (solution.floored_steps, solution.chord_steps) = (steps.floored, steps.chords);
        let constant = method.complementarity_constant();
        self.system.release_work()?;
        let start = std::time::Instant::now();
        (solution.kkt, solution.balance) =
            residual::assess(problem, model, constant, &solution.view())?;
        solution.timings.assessment = start.elapsed().as_secs_f64();
        if solution.converged() {
            solution.failure = method.accept(&solution.kkt, &solution.outer_history);
        }
        Ok(solution)
    }
}

/// ‖a − b‖ / ‖a‖ in the L2(Ω) norm of (6.15).
fn relative_change(problem: &Problem, dofs: &DofMap, mass: &MassNorm, a: &[f64], b: &[f64]) -> f64 {
    let difference: Vec<f64> = a.iter().zip(b).map(|(p, q)| p - q).collect();
    let norm = mass.squared(problem, dofs, a);
    if norm > 0.0 { (mass.squared(problem, dofs, &difference) / norm).sqrt() } else { 0.0 }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algorithm::inner::{InnerResult, Stop, StopContext};
    use crate::algorithm::residual::KktResidual;
    use crate::algorithm::stops::stalled;
    use crate::assembly::NodalBlock;
    use crate::contact::{ContactState, NodeStatus};
    use crate::system::solve_without_contact;
    use crate::testing::{PAPER_72, built};
    use std::sync::{Arc, Mutex};

    /// An inner method that ignores contact: each step is the solve without contact forces,
    /// and it stops as it is told. It shows what the outer loop does on its own.
    #[derive(Clone, Debug)]
    struct Stub {
        lags: bool,
        stop: Stop,
        reject: bool,
        /// The friction bounds s_n it was handed, one per outer step.
        seen: Arc<Mutex<Vec<Vec<f64>>>>,
    }

    impl Stub {
        fn new(lags: bool, stop: Stop, reject: bool) -> Self {
            Self { lags, stop, reject, seen: Arc::default() }
        }
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
            self.seen.lock().unwrap().push(step.friction_bound.to_vec());
            Ok(InnerResult {
                x,
                state,
                iterations: 3,
                history: vec![0.5, 0.1],
                status: vec![NodeStatus::Slip; step.surface.len()],
                stop: self.stop.clone(),
            })
        }
        fn stop_context(&self, outer_step: usize, _friction: bool) -> StopContext {
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
        let stub = Stub::new(true, Stop::Converged, false);
        let solution = run(stub, 10);
        // s_1 from s_0 = 0: a change of 100 % (6.13); s_2 = s_1: none.
        assert!(solution.converged() && solution.failure.is_none());
        assert_eq!(solution.outer_history, vec![1.0, 0.0]);
        assert_eq!(
            (solution.outer_iterations(), solution.inner_iterations.clone()),
            (2, vec![3, 3])
        );
        // Hencky's moduli never change with the linear law: one factorisation serves both steps.
        assert_eq!(solution.timings.solver.numeric_count, 1);
        let problem = built(PAPER_72, &COARSE).problem;
        assert_eq!(solution.x, solve_without_contact(&problem, default_solver()).unwrap().x);
        // The lagged friction bound: after one step, the step used s_0 = 0 and s_1 > 0 waits;
        // the second step was handed s_1.
        let stub = Stub::new(true, Stop::Converged, false);
        let seen = stub.seen.clone();
        let one = run(stub, 1);
        assert!(
            seen.lock().unwrap()[0].iter().all(|s| *s == 0.0) && one.s.iter().any(|s| *s > 0.0)
        );
        let stub = Stub::new(true, Stop::Converged, false);
        let seen = stub.seen.clone();
        let two = run(stub, 10);
        assert_eq!(seen.lock().unwrap()[1], one.s);
        // A node under compression takes the method's friction status; one without, separated.
        for (status, sigma_nu) in two.status.iter().zip(&two.sigma_nu) {
            let expected = if *sigma_nu < 0.0 { NodeStatus::Slip } else { NodeStatus::Separated };
            assert_eq!(*status, expected);
        }
    }

    #[test]
    fn a_method_that_does_not_lag_stops_when_the_moduli_settle() {
        let stub = Stub::new(false, Stop::Converged, false);
        let seen = stub.seen.clone();
        let solution = run(stub, 10);
        assert!(solution.converged());
        assert_eq!((solution.outer_iterations(), solution.outer_history.clone()), (1, vec![0.0]));
        // Nothing lagged: the step was handed s_0 = 0 while its solution has s > 0, and the
        // criterion does not count that change (a lagging method's (6.13) would be 1).
        assert!(solution.s.iter().any(|s| *s > 0.0));
        assert!(seen.lock().unwrap()[0].iter().all(|s| *s == 0.0));
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
            let solution = run(Stub::new(true, stop, false), 10);
            assert!(!solution.converged());
            assert_eq!(solution.outer_iterations(), 1, "{variant}: the loop stops at once");
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

    /// The linear solver's own failure keeps its message, without the method's advice (which
    /// is for the method's numbers, not the backend's).
    #[test]
    fn a_backend_failure_keeps_its_words_without_the_method_s_hint() {
        let stop = Stop::of_failed_solve(Error::LinearAlgebra("out of Krylov iterations".into()));
        let solution = run(Stub::new(true, stop, false), 10);
        let failure = solution.failure.unwrap();
        assert!(matches!(failure, Error::LinearAlgebra(_)), "{failure:?}");
        let text = failure.to_string();
        assert!(text.contains("the stub of outer step 1 failed at iteration"), "{text}");
        assert!(text.contains("out of Krylov iterations") && !text.contains("hint"), "{text}");
        let other = Stop::of_failed_solve(Error::NonFinite { what: "x".into() });
        assert!(matches!(other, Stop::NotFinite(_)));
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
            status: Vec::new(),
            stop: Stop::Cap,
        };
        let context = Stub::new(false, Stop::Cap, false).stop_context(1, false);
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
        let solution = run(Stub::new(true, Stop::Converged, false), 1);
        let converged = solution.converged();
        let failure = solution.failure.unwrap().to_string();
        assert!(!converged && failure.contains("fixed-point loop (Algorithm 1)"));
        assert!(failure.contains("solver.max_outer (now 1)"), "{failure}");
        let solution = run(Stub::new(true, Stop::Converged, true), 10);
        assert!(!solution.converged() && solution.outer_iterations() == 2);
        assert!(solution.failure.unwrap().to_string().contains("rejected by the stub"));
    }
}
