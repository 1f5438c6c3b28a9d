//! The seam between the outer loop and an inner method (model §7): what the outer loop asks
//! of a method ([`InnerMethod`]), what it hands it ([`Setup`], [`Step`]), and what comes back
//! ([`InnerResult`], [`Stop`]), with the events a running solve reports ([`Progress`]).

use super::residual::KktResidual;
use crate::assembly::{Linearisation, MassNorm, NodalBlock};
use crate::contact::{ContactModel, ContactState, ContactSurface, NodalFriction, NodeStatus};
use crate::dofs::DofMap;
use crate::error::{Error, Result};
use crate::linalg::LinearSolver;
use crate::problem::Problem;
use crate::system::CoupledSystem;

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
    fn stop_context(&self, outer_step: usize, friction: bool) -> StopContext;
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
    /// ([`crate::system::Timings::dense`]), over every step so far \[s\].
    fn dense_seconds(&self) -> f64 {
        0.0
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
    /// The linear solver failed for a reason of its own (memory, a Krylov solve short of its
    /// tolerance), which its message says how to change: the method's advice does not apply.
    Backend(String),
    /// The run was asked to stop ([`crate::interrupt`]), by this signal.
    Interrupted(i32),
    /// The iterates came back to where they were this many steps before, a whole period
    /// over, and would go round again.
    Cycle(usize),
}

impl Stop {
    /// The stop of a loop whose solve failed with `error`: [`Stop::Backend`] for the linear
    /// solver's own failure, else [`Stop::NotFinite`].
    pub fn of_failed_solve(error: Error) -> Self {
        match error {
            Error::LinearAlgebra(cause) => Stop::Backend(cause),
            other => Stop::NotFinite(other.to_string()),
        }
    }
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
    /// What the friction law said of each Γ3 node at that iterate ([`crate::contact::law::coulomb`]'s status;
    /// [`NodeStatus::Contact`] without friction).
    pub status: Vec<NodeStatus>,
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
    /// µ_i and R of the friction bound (PV2; `None` without friction).
    pub friction: Option<&'a NodalFriction>,
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

/// What a running solve reports to the observer of [`super::solve_contact_with`].
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
