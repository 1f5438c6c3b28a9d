//! The exact contact solver (model §11): a semismooth Newton method on the problem condensed
//! onto the Γ3 unknowns, as an [`InnerMethod`].
//!
//! The equations are model §11's; here is how the code holds them. With the Γ3 unknowns x_c
//! ([`Condensed`]) kept last by the backend ([`crate::linalg::SchurComplement`]), the Schur
//! complement S comes from the factor once per factorisation. The u unknowns of node i are
//! turned into its local coordinates (u_ν, u_τ) = Q_i u, and S with them. One solve without
//! contact forces gives x̂ and the condensed load b = S x̂_c; F = S x_c − b are then the contact
//! forces on the Γ3 rows (F_ν = w σ_ν, F_τ = −w λ_f, F_ϕ = w ψ φ_L), and the residual E
//! (E_n contact, E_t Coulomb, E_ϕ conduction) is evaluated by `Local::evaluate`, its
//! generalised Jacobian column by column by `Local::gradient`. Rows of nodes in contact (normal)
//! or sticking (tangential) fix their unknowns; the dense LU runs on the others, in single
//! precision with its solves refined in double ([`TransposedLu`]). On slipping
//! nodes the projection's derivative uses λ_f / max(s, ‖λ_f‖) (Hüeber, Stadler and Wohlmuth's
//! relaxation), and a backtracking line search on the scaled ‖E‖ keeps the iteration from
//! cycling. The constant c_i = (r/E_Y)·S_νν,i/w_i scales the case's r by the stiffness node i
//! sees (E_Y: Young's modulus). The iteration stops when the sets no longer change and the
//! step is at round-off; one solve with the contact forces recovers the interior. With the
//! sets settled, a chord step (the last step's dense LU with the new residual) replaces the
//! factorisation when it multiplies the merit by at most 1e−2. An iteration whose iterates go
//! round a loop stops once it has gone round twice (`Cycles`); where a strong conduction makes
//! them cycle from both starts, a continuation in k_e (`Local::continuation`) takes its place.

use super::condensed::{self, Condensed, Guess, Phi, SchurSource};
use super::held::Held;
use super::inner::{InnerMethod, InnerResult, Progress, Setup, Step, Stop, StopContext};
use super::residual::KktResidual;
use crate::assembly::NodalBlock;
use crate::contact::law::{coulomb, stop_complementarity};
use crate::contact::{ContactState, ContactSurface, NodeStatus};
use crate::dofs::DofMap;
use crate::error::{Error, Result};
use crate::linalg::{DenseMatrix, LinearSolver, RowMatrix, TransposedLu, max_distance, max_norm};
use crate::system::CoupledSystem;
use rayon::prelude::*;
use std::collections::VecDeque;
use std::sync::Mutex;

/// A relative Newton step below this, with unchanged sets, is round-off.
pub const STEP_TOLERANCE: f64 = 1e-12;
/// A relative Newton step below this ends the iteration whatever the sets do.
const STEP_FLOOR: f64 = 1e-15;
/// Halvings of the line search.
const HALVINGS: usize = 8;
/// Newton steps from the first iterate put onto the foundation before starting again from
/// the one it was made from.
const GUESS_STEPS: usize = 30;
/// A chord step (the last dense factorisation again, the sets unchanged) is taken when it
/// brings the merit ‖scaled E‖² down to this fraction of its value or less; else a Newton
/// step is.
const CHORD_DECREASE: f64 = 1e-2;
/// Condensed problems solved in one outer step, at most (each after a factorisation).
const MAX_ROUNDS: usize = 10;
/// The first increment of the continuation in k_e (a fraction of k_e).
const FIRST_INCREMENT: f64 = 1.0 / 16.0;
/// The continuation in k_e gives up when its increment falls below this fraction of k_e.
const LEAST_INCREMENT: f64 = 1.0 / 4096.0;
/// Stages of the continuation in k_e, at most.
const MAX_STAGES: usize = 64;
/// The loosest relative residual of an iterative solve of a whole-system Newton step.
const FORCING_CEILING: f64 = 1e-2;
/// The tightest relative residual of an iterative solve of a whole-system Newton step. The
/// last steps then converge linearly at this rate or faster, which costs a step or two: on
/// the 3D indentation (94k unknowns, 12 Newton steps whatever the floor) 1e−4 took 20.5 s,
/// 1e−6 22.2 s and 1e−12 25.0 s (its last solves 70 GMRES iterations each).
const FORCING_FLOOR: f64 = 1e-4;
/// The longest period of a cycle of iterates that [`Cycles`] tells.
const LONGEST_CYCLE: usize = 8;
/// Two iterates a period apart and nearer than this fraction of the longest step between
/// them are the same point: the round-off of the dense solves repeats a loop to a few 1e−7
/// of its steps (the strong-conduction cube of model §11).
const CYCLE_TOLERANCE: f64 = 1e-5;

/// One term of a row of the Jacobian: ∂E_k is the sum of factor · ∂F_j (F_j = row j of the
/// operator times y, less the load) and of factor · ∂y_j.
#[derive(Clone, Copy, Debug)]
enum Term {
    /// factor · ∂F_j.
    Force(usize, f64),
    /// factor · ∂y_j.
    Unknown(usize, f64),
}

/// The operator A of F = A y − b, in local coordinates.
enum Operator {
    /// Q S Qᵀ, S the Schur complement of the condensed unknowns.
    Dense(DenseMatrix),
    /// T K Tᵀ, K the whole system's matrix (the coupled system's, which multiplies),
    /// T turning each kept Γ3 node's u to its local frame: of T K Tᵀ, the rows that the
    /// Newton steps change (`rows`: the kept nodes' and their neighbours', the others empty;
    /// numbered by the free unknowns), the diagonal (per position) and what this process
    /// holds of the whole system.
    Sparse { rows: RowMatrix, diagonal: Vec<f64>, held: Held },
}

impl Operator {
    /// A_kk.
    fn diagonal(&self, k: usize) -> f64 {
        match self {
            Operator::Dense(schur) => schur.get(k, k),
            Operator::Sparse { diagonal, .. } => diagonal[k],
        }
    }
}

/// The condensed problem in local coordinates.
struct Local<'a> {
    semismooth: &'a Semismooth<'a>,
    /// A.
    operator: Operator,
    /// The coupled system: its solves of the whole system's Newton steps and the final
    /// solve of the condensed problem's interior.
    system: Mutex<&'a mut CoupledSystem>,
    /// Per position, its Γ3 node ([`INTERIOR`] for the whole system's other unknowns).
    node_of: Vec<usize>,
    /// Q b: the condensed load in local coordinates.
    load: Vec<f64>,
    /// Per node: Q_i (rows ν, τ1, τ2) in the components of its unknowns.
    frames: Vec<[[f64; 3]; 3]>,
    /// Per node on a "normal" support: its turned frame and u's indices.
    turned: Vec<Option<TurnedNode>>,
    /// Per node: c_i [stress/length].
    c: Vec<f64>,
    /// Per condensed unknown: the scale of its equation in the merit function.
    scale: Vec<f64>,
    /// x̂, the solve without contact forces, at the positions (local coordinates).
    y_hat: Vec<f64>,
    /// Per node whose ϕ is prescribed ([`Phi::Prescribed`]), x̂'s ϕ there (0 at the others).
    prescribed: Vec<f64>,
    /// Per node, where the slip is measured from in its local components (the tangential
    /// ones matter): 0, or the previous step of a path with incremental friction.
    origin: Vec<[f64; 3]>,
    /// θ ∈ (0, 1]: the fraction of k_e the conduction has, 1 but in the stages of a
    /// continuation ([`Local::continuation`]).
    conduction: f64,
    /// The merit of the first whole-system Newton step solved, the reference of the forcing
    /// tolerance ([`Local::forcing`]).
    first_merit: std::sync::OnceLock<f64>,
}

/// values += factor · (the entries of `row` in `columns`), both sorted by column; entries of
/// `row` outside `columns` are left out.
fn add_matching(row: (&[usize], &[f64]), factor: f64, columns: &[usize], values: &mut [f64]) {
    let mut at = 0;
    for (&c, &v) in row.0.iter().zip(row.1) {
        while at < columns.len() && columns[at] < c {
            at += 1;
        }
        if at < columns.len() && columns[at] == c {
            values[at] += factor * v;
        }
    }
}

/// λ̃ of a slipping node's derivative (s/‖z‖)(I − λ̃ẑᵀ) of the projection onto the ball:
/// λ_f / max(s, ‖λ_f‖) where it points along ẑ (λ̃·ẑ ≥ 0), else ẑ itself — the projection's
/// exact derivative. With λ̃·ẑ ≥ 0 the eigenvalues of I − (s/‖z‖)(I − λ̃ẑᵀ), 1 − s/‖z‖ and
/// 1 − (s/‖z‖)(1 − λ̃·ẑ), are positive on a slipping node (‖z‖ > s); a λ_f against z would
/// make the second vanish or turn negative, the node's tangential stiffness in the Jacobian
/// infinite or negative. At a slip solution λ̃ = ẑ, so the choice leaves Newton's local
/// convergence as it is.
fn slip_direction(lambda_f: &[f64], bound: f64, z_hat: &[f64]) -> Vec<f64> {
    let lambda_tilde: Vec<f64> = lambda_f.iter().map(|v| v / bound).collect();
    let along: f64 = lambda_tilde.iter().zip(z_hat).map(|(l, z)| l * z).sum();
    if along >= 0.0 { lambda_tilde } else { z_hat.to_vec() }
}

/// The node of a position of the whole system outside Γ3.
const INTERIOR: usize = usize::MAX;

/// A Γ3 node in a turned frame: the frame R (rows, mesh components) and the global indices
/// of u's mesh components there.
type TurnedNode = ([[f64; 3]; 3], [usize; 3]);

/// Per Γ3 node, its contact frame Q_i in the components of its unknowns (Q Rᵀ in a turned
/// frame R, on a "normal" support; else Q), and the turned ones.
fn unknown_frames(
    surface: &ContactSurface,
    dofs: &DofMap,
) -> (Vec<[[f64; 3]; 3]>, Vec<Option<TurnedNode>>) {
    let d = surface.dim();
    let turned = surface
        .nodes
        .iter()
        .map(|&node| {
            Some((*dofs.frame(node)?, std::array::from_fn(|m| dofs.u(node, m.min(d - 1)))))
        })
        .collect();
    let frames = (0..surface.len())
        .map(|i| surface.frame(i).map(|row| dofs.turned(surface.nodes[i], &row)))
        .collect();
    (frames, turned)
}

/// The active sets at an iterate, as the laws decide them: per node, whether the rigid
/// stop holds it ([`stop_complementarity`]) and what the friction law says ([`coulomb`]:
/// stick or slip; [`NodeStatus::Contact`] without friction; slip on the nodes left out of
/// the condensed problem, which bear no force).
#[derive(Clone, Debug, PartialEq)]
struct Sets {
    at_stop: Vec<bool>,
    status: Vec<NodeStatus>,
}

impl Sets {
    /// No node at the stop, every node slipping (in contact without `friction`).
    fn new(n3: usize, friction: bool) -> Self {
        let status = if friction { NodeStatus::Slip } else { NodeStatus::Contact };
        Self { at_stop: vec![false; n3], status: vec![status; n3] }
    }

    /// Nodes at the stop or sticking: those whose equations fix some unknown.
    #[cfg(test)]
    fn holding(&self) -> usize {
        (0..self.at_stop.len())
            .filter(|&i| self.at_stop[i] || self.status[i] == NodeStatus::Stick)
            .count()
    }
}

/// E and the sets at an iterate.
struct Evaluation {
    /// E, the residual of the condensed equations.
    residual: Vec<f64>,
    /// The active sets.
    sets: Sets,
    /// Per condensed unknown: whether its equation fixes it (contact normal, stick tangent).
    fixed: Vec<bool>,
    /// λ_c, λ_f (local tangential components).
    multipliers: ContactState,
    /// F = S x_c − b in local coordinates, the contact forces on the Γ3 rows, from which the
    /// condensed problem's interior is solved; empty on the whole system, whose solution is y
    /// itself (its laws read F on the Γ3 rows from `residual` before they replace it).
    forces: Vec<f64>,
    /// σ_ν per node and R σ_ν.
    sigma_nu: Vec<f64>,
    r_sigma: Vec<f64>,
}

/// Where a Newton iteration ended.
struct Iteration {
    /// The last iterate (local coordinates).
    y: Vec<f64>,
    stop: Stop,
    /// Steps taken.
    iterations: usize,
    /// The steps that factorised their dense system (the others were chord steps).
    factorisations: usize,
    /// The step criterion of each step.
    history: Vec<f64>,
}

/// The last iterates of a Newton iteration, to tell when it cycles: a semismooth iteration
/// can go round a loop of active sets for ever (model §11), and each step spent there is a
/// dense factorisation. It keeps [`LONGEST_CYCLE`] iterates — of the unknowns it is given,
/// the Γ3 unknowns ([`Local::watched`]) — and, for the last 2 × [`LONGEST_CYCLE`], the
/// distances to the ones before them: a period's test reads those numbers alone.
#[derive(Default)]
struct Cycles {
    /// The last [`LONGEST_CYCLE`] iterates, the newest last.
    recent: VecDeque<Vec<f64>>,
    /// Per iterate, the newest last: its max-norm distance to the iterate q before it at
    /// index q − 1 (as far back as there were iterates).
    distances: VecDeque<Vec<f64>>,
}

impl Cycles {
    /// Records the iterate `y`; the period p ≥ 2 when each of the last p iterates is the one
    /// p before it, to [`CYCLE_TOLERANCE`] of the longest of the 2p − 1 steps between them
    /// (max norm): the iteration has gone round a loop twice. Two iterates p apart differ by
    /// the sum of the p steps between them, which for a converging iteration is about the
    /// first of them, the longest: they coincide only when the steps go back and forth.
    fn period(&mut self, y: &[f64]) -> Option<usize> {
        let row = self.recent.iter().rev().map(|before| max_distance(y, before)).collect();
        if self.recent.len() == LONGEST_CYCLE {
            self.recent.pop_front();
        }
        self.recent.push_back(y.to_vec());
        if self.distances.len() == 2 * LONGEST_CYCLE {
            self.distances.pop_front();
        }
        self.distances.push_back(row);
        let n = self.distances.len();
        // The distance from the iterate at index k (of the last n) to the one q before it.
        let distance = |k: usize, q: usize| self.distances[k][q - 1];
        (2..=LONGEST_CYCLE).filter(|p| 2 * p <= n).find(|&p| {
            let longest = (n - 2 * p + 1..n).fold(0.0_f64, |l, k| l.max(distance(k, 1)));
            longest > 0.0 && (n - p..n).all(|k| distance(k, p) <= CYCLE_TOLERANCE * longest)
        })
    }
}

impl Iteration {
    /// Whether the iteration ended without converging, and not by an interrupt.
    fn failed(&self) -> bool {
        !matches!(self.stop, Stop::Converged | Stop::Interrupted(_))
    }

    /// This iteration followed by `next`: the steps, factorisations and histories of both,
    /// the iterate and the stop of `next`.
    fn then(self, next: Iteration) -> Iteration {
        Iteration {
            iterations: self.iterations + next.iterations,
            factorisations: self.factorisations + next.factorisations,
            history: [self.history, next.history].concat(),
            ..next
        }
    }
}

/// What the exact solver reads from `solver.*`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Parameters {
    /// r > 0 [stress/length]: the constant of the KKT residual; the Newton method uses
    /// c_i = (r/E)·S_νν,i/w_i, r scaled by the stiffness of Γ3 node i. The answer does not
    /// depend on it.
    pub r: f64,
    /// The run stops when the KKT residual is at most this [-].
    pub tol: f64,
    /// Cap on Newton steps per condensed problem.
    pub max_inner: usize,
    /// The most Γ3 nodes condensed into the dense problem: at this cap, clear nodes are traded
    /// for left-out nodes that turn out to touch (model §11). `None`: no cap but the memory
    /// the dense matrices need, so that the condensation grows as far as the contact zone.
    pub max_condensed: Option<usize>,
    /// The first guess of the condensed nodes (at most the cap).
    pub guess: Guess,
}

/// The exact solver as an inner method: it owns its condensation, and the outer loop only
/// linearises Hencky's law around it (model §13).
#[derive(Clone, Debug)]
pub struct Newton {
    parameters: Parameters,
    /// r/E: the complementarity constant relative to the local stiffness [-].
    c_factor: f64,
    /// The Γ3 unknowns of the condensed problem.
    condensed: Option<Condensed>,
    /// The Schur complements: the factor's trailing block (the unknowns of `condensed`, or
    /// of an earlier condensation that a growth by solves kept) and the last one by solves.
    schur: SchurSource,
    /// Outer steps solved so far: the first starts from the solve without contact, the next
    /// ones from x_n.
    solved: usize,
    /// Time in the steps outside the system's counted phases: the dense problem \[s\].
    dense_seconds: f64,
    /// Whether Newton runs on the whole system (a backend without a Schur complement)
    /// rather than on the problem condensed onto Γ3.
    whole: bool,
    /// θ ∈ [0, 1): the fraction of k_e the last outer step's iterate solves when its
    /// continuation in k_e stopped short of the whole (`None` otherwise).
    short_of: Option<f64>,
}

impl Newton {
    /// The method with `parameters`.
    pub fn new(parameters: Parameters) -> Self {
        Self {
            parameters,
            c_factor: 0.0,
            condensed: None,
            schur: SchurSource::default(),
            solved: 0,
            dense_seconds: 0.0,
            whole: false,
            short_of: None,
        }
    }
}

impl InnerMethod for Newton {
    fn name(&self) -> &'static str {
        "newton"
    }

    fn fresh(&self) -> Box<dyn InnerMethod> {
        Box::new(Self::new(self.parameters))
    }

    fn lags_contact(&self) -> bool {
        false
    }

    fn complementarity_constant(&self) -> f64 {
        self.parameters.r
    }

    fn outer_tolerance(&self) -> f64 {
        self.parameters.tol
    }

    /// On a backend that condenses ([`LinearSolver::schur`]) the problem condensed onto Γ3;
    /// on one that does not, the whole system's.
    fn prepare(
        &mut self,
        setup: Setup,
        mut solver: Box<dyn LinearSolver>,
    ) -> Result<CoupledSystem> {
        let Setup { problem, dofs, surface, model } = setup;
        let with_phi = model.compliance.penetration > 0.0;
        self.c_factor = self.parameters.r / problem.materials.reference_modulus();
        self.whole = solver.schur().is_none();
        if self.whole {
            let mut system = CoupledSystem::new(problem, dofs, &[], solver)?;
            let complete = system.assembler().complete_rows();
            let condensed = Condensed::whole(system.dofs(), surface, with_phi, complete);
            system.keep_rows(rows_read(&system, &condensed))?;
            self.condensed = Some(condensed);
            return Ok(system);
        }
        let Parameters { max_condensed, guess, .. } = self.parameters;
        let frictionless = model.friction.is_none();
        let guess = guess.at_most(max_condensed);
        let condensed = Condensed::new(&dofs, surface, (with_phi, frictionless), guess);
        condensed.check_memory(crate::limits::available_memory())?;
        let system = CoupledSystem::with_last(problem, dofs, &condensed.free, solver)?;
        self.schur = SchurSource::new(&condensed.free);
        self.condensed = Some(condensed);
        Ok(system)
    }

    fn blocks(&self) -> &[NodalBlock] {
        &[]
    }

    /// A condensation grown by solves (model §11) is ordered last before B̌ is factorised
    /// again, so that its Schur complement is read off the new factor instead of being taken
    /// by the same solves after every factorisation.
    fn before_factorisation(&mut self, system: &mut CoupledSystem) -> Result<()> {
        if let Some(condensed) = &self.condensed
            && !self.whole
            && !self.schur.analyses(&condensed.free)
        {
            system.put_last(&condensed.free)?;
            self.schur = SchurSource::new(&condensed.free);
        }
        Ok(())
    }

    fn solve(&mut self, step: &Step, system: &mut CoupledSystem) -> Result<InnerResult> {
        let mut condensed = self.condensed.take().ok_or_else(|| {
            Error::LinearAlgebra("the exact solver solved before it was prepared".into())
        })?;
        let mut schur = std::mem::take(&mut self.schur);
        let (start, counted) = (std::time::Instant::now(), system.timings().counted());
        let result = if self.whole {
            let start = (self.solved > 0).then_some(step.previous);
            let (c_factor, max_inner) = (self.c_factor, self.parameters.max_inner);
            let whole = Semismooth { step, condensed: &condensed, c_factor, max_inner, start };
            whole.run(system, None)
        } else {
            self.solve_growing(step, (&mut condensed, &mut schur), system)
        };
        let counted = system.timings().counted() - counted;
        self.dense_seconds += (start.elapsed().as_secs_f64() - counted).max(0.0);
        (self.condensed, self.schur) = (Some(condensed), schur);
        self.solved += 1;
        let (result, short_of) = result?;
        self.short_of = short_of;
        Ok(result)
    }

    fn stop_context(&self, outer_step: usize, _friction: bool) -> StopContext {
        let max_inner = self.parameters.max_inner;
        let mut hint = "the active set cycles or the Jacobian is singular: check that Γ3 can \
                        touch the foundation only where the body is held"
            .to_string();
        match self.short_of {
            // θ is a sum of powers of 2: printed in full, it is exact.
            Some(theta) if theta > 0.0 => {
                hint = format!(
                    "under the conduction the iteration cycles, and its continuation in k_e \
                     solved the problem with θ = {theta} of k_e at most (the iterate written \
                     solves that problem), no stage past it converging: the solution may turn \
                     back there (a fold in k_e) or not exist; solver.method = \"uzawa\" may \
                     converge"
                )
            }
            Some(_) => {
                hint = format!(
                    "under the conduction the iteration cycles, and its continuation in k_e did \
                     not converge even with 1/{:.0} of k_e: {hint}",
                    1.0 / LEAST_INCREMENT
                )
            }
            None => {}
        }
        hint += "; report the case if it persists";
        // A stage of the continuation has at most GUESS_STEPS steps whatever the cap above.
        let cap_hint = if self.short_of.is_some() && max_inner >= GUESS_STEPS {
            hint.clone()
        } else {
            format!("raise solver.max_inner (now {max_inner}); {hint}")
        };
        StopContext {
            what: format!("the semismooth Newton method of outer step {outer_step}"),
            tolerance: STEP_TOLERANCE,
            cap_hint,
            hint,
        }
    }

    fn accept(&self, kkt: &KktResidual, outer_history: &[f64]) -> Option<Error> {
        let tol = self.parameters.tol;
        (kkt.max > tol || kkt.max.is_nan()).then(|| Error::NotConverged {
            what: "the exact solver".into(),
            iterations: outer_history.len(),
            criterion: kkt.max,
            tolerance: tol,
            // The criterion is the KKT residual, measured once at the end: its parts say
            // which condition stays above the tolerance.
            history: format!(
                "KKT residual of equilibrium u {:.1e}, ϕ {:.1e}, contact {:.1e}, friction {:.1e}",
                kkt.equilibrium_u, kkt.equilibrium_phi, kkt.contact, kkt.friction
            ),
            hint: "the KKT residual stays above solver.tol: round-off of an ill-conditioned \
                   problem, or a tolerance below what double precision reaches here"
                .into(),
        })
    }

    fn condensed_nodes(&self) -> usize {
        let condensed = self.condensed.as_ref().filter(|_| !self.whole);
        condensed.map_or(0, Condensed::node_count)
    }

    fn dense_bytes(&self) -> f64 {
        let condensed = self.condensed.as_ref().filter(|_| !self.whole);
        condensed.map_or(0.0, Condensed::dense_bytes)
    }

    fn dense_seconds(&self) -> f64 {
        self.dense_seconds
    }
}

impl Newton {
    /// Solves an outer step with the factorised `system` (ordered with the unknowns `schur` was made for last),
    /// growing the condensation until no node left out touches (model §11). A growth takes
    /// the Schur complement of the new set from the factor by solves when that is cheaper
    /// ([`condensed::cheaper_by_solves`]), else orders the new set last and factorises B̌
    /// with the step's linearisation again; Newton restarts from the last solution, and the
    /// steps and histories of all rounds are summed. With the result, what the last round's
    /// [`Semismooth::run`] says of its continuation.
    fn solve_growing(
        &self,
        step: &Step,
        (condensed, schur): (&mut Condensed, &mut SchurSource),
        system: &mut CoupledSystem,
    ) -> Result<(InnerResult, Option<f64>)> {
        let Parameters { max_inner, max_condensed, .. } = self.parameters;
        let c_factor = self.c_factor;
        let start = (self.solved > 0).then_some(step.previous);
        let first = Semismooth { step, condensed, c_factor, max_inner, start };
        let (mut result, mut short_of) = first.run(system, Some(&mut *schur))?;
        let mut rounds = 1;
        while matches!(result.stop, Stop::Converged)
            && let Some(grown) = condensed.grown(
                (system.dofs(), step.surface),
                (&result.x, &friction_bound(step, system, &result)),
                max_condensed,
            )?
        {
            if rounds == MAX_ROUNDS {
                return Err(Error::Input(format!(
                    "the exact solver's condensation of Γ3 did not settle in {MAX_ROUNDS} factorisations ({} Γ3 nodes condensed, solver.max_condensed = {}): raise solver.max_condensed, or use solver.method = \"uzawa\"",
                    condensed.node_count(),
                    max_condensed.map_or("none".to_string(), |n| format!("{n} nodes"))
                )));
            }
            rounds += 1;
            grown.check_memory(crate::limits::available_memory())?;
            *condensed = grown;
            let solves = schur.solves_for(system, &condensed.free);
            if !condensed::cheaper_by_solves(solves, &system.agreed_stats()?) {
                system.put_last(&condensed.free)?;
                (step.progress)(Progress::Factorising { unknowns: system.dofs().n_free() });
                system.factorize_linearised(step.problem, step.linearisation, &[])?;
                *schur = SchurSource::new(&condensed.free);
            }
            let start = Some(result.x.as_slice());
            let next;
            (next, short_of) = Semismooth { step, condensed, c_factor, max_inner, start }
                .run(system, Some(&mut *schur))?;
            let history = [std::mem::take(&mut result.history), next.history].concat();
            result =
                InnerResult { iterations: result.iterations + next.iterations, history, ..next };
        }
        Ok((result, short_of))
    }
}

/// The friction bound s = µ|Rσ_ν| per Γ3 node at `result` as the outer loop records it: 0
/// where the laws make it so (λ_c = 0 off the active set, no compliance at u_ν ≤ g_a, no force
/// on a node left out), not the round-off of the condensed forces — so that a left-out node
/// bears friction only from nodes that touch.
fn friction_bound(step: &Step, system: &CoupledSystem, result: &InnerResult) -> Vec<f64> {
    let sigma_nu = result.state.normal_stress(system.dofs(), step.surface, step.model, &result.x);
    step.friction.map_or_else(|| vec![0.0; sigma_nu.len()], |f| f.bound(&sigma_nu))
}

/// One semismooth Newton solve of the condensed problem of an outer step.
struct Semismooth<'a> {
    /// The outer step.
    step: &'a Step<'a>,
    /// The Γ3 unknowns, last in the factorisation's ordering.
    condensed: &'a Condensed,
    /// r/E: the complementarity constant relative to the local stiffness [-].
    c_factor: f64,
    /// Cap on Newton steps.
    max_inner: usize,
    /// The iterate to start from (global); `None`: the solve without contact forces.
    start: Option<&'a [f64]>,
}

impl Semismooth<'_> {
    /// Solves the condensed problem with the factorised `system` (ordered with the free
    /// unknowns `schur` was made for last) and recovers the whole solution — or, without
    /// `schur`, the whole system's problem; with it, when a continuation in k_e stopped short
    /// of the whole, the fraction θ < 1 of k_e it solves.
    pub fn run(
        &self,
        system: &mut CoupledSystem,
        schur: Option<&mut SchurSource>,
    ) -> Result<(InnerResult, Option<f64>)> {
        let cond = self.condensed;
        let x_hat = system.solve(None)?;
        let node_of = nodes_of(cond);
        let (operator, rhs) = match schur {
            Some(schur) => (Operator::Dense(schur.get(system, &cond.free)?), None),
            None => whole_operator(&mut *system, cond, &node_of)?,
        };
        let mut local = Local::new(self, operator, node_of, (x_hat, rhs), system)?;
        // The first iterate and the guess made from it are made again where a second try
        // needs them rather than kept through the iteration (on the whole system, two
        // vectors of the unknowns).
        let cold = self.start.is_none();
        let from = local.first_iterate(self.start);
        let guess = local.onto_foundation(&from, cold);
        let moved = guess != from;
        drop(from);
        let cap = if moved { GUESS_STEPS.min(self.max_inner) } else { self.max_inner };
        let mut newton = local.iterate(guess, cap);
        let left = self.max_inner - newton.iterations;
        if moved && left > 0 && newton.failed() {
            // The guess led nowhere: again from the solve without contact forces, within the
            // cap on the steps of both.
            newton = newton.then(local.iterate(local.first_iterate(self.start), left));
        }
        let mut short_of = None;
        if newton.failed() && local.conducts() {
            let guess = local.onto_foundation(&local.first_iterate(self.start), cold);
            let (continued, theta) = local.continuation(guess, GUESS_STEPS.min(self.max_inner));
            newton = newton.then(continued);
            short_of = (theta < 1.0).then_some(theta);
        }
        let Iteration { y, stop, iterations, history, .. } = newton;
        let eval = local.evaluate(&y);
        let x = local.whole_solution(&y, &eval)?;
        let mut state = eval.multipliers;
        // Off the active set the law is λ_c = 0, held to round-off by the Newton equations.
        for (i, at_stop) in eval.sets.at_stop.iter().enumerate() {
            if !at_stop || !cond.kept[i] {
                state.lambda_c[i] = 0.0;
            }
        }
        if self.step.model.friction.is_none() {
            // Frictionless: σ_τ = 0 by the law; the tangential rows hold it to round-off.
            state.lambda_f.iter_mut().for_each(|l| *l = [0.0; 3]);
        }
        for i in 0..local.frames.len() {
            // λ_f from local tangential components to mesh components.
            let frame = self.step.surface.frame(i);
            let tangential = state.lambda_f[i];
            state.lambda_f[i] =
                [0, 1, 2].map(|k| (1..3).map(|a| frame[a][k] * tangential[a - 1]).sum());
        }
        let mut status = eval.sets.status;
        if let Some(friction) = self.step.friction {
            // A node left out bears no force: the law at rest, λ_f = 0, with its bound.
            for i in (0..status.len()).filter(|&i| !cond.kept[i]) {
                status[i] = coulomb([0.0; 2], friction.node_bound(i, eval.r_sigma[i])).1;
            }
        }
        Ok((InnerResult { x, state, iterations, history, status, stop }, short_of))
    }
}

/// Per position of `cond`, its Γ3 node ([`INTERIOR`] for the other unknowns).
fn nodes_of(cond: &Condensed) -> Vec<usize> {
    let mut node_of = vec![INTERIOR; cond.len()];
    for i in (0..cond.kept.len()).filter(|&i| cond.kept[i]) {
        cond.slots(i).0.iter().for_each(|&k| node_of[k] = i);
        if let Phi::Unknown(p) = cond.phi[i] {
            node_of[p] = i;
        }
    }
    node_of
}

/// The whole system's operator (K's rows that the Newton steps change — [`rows_read`] — and
/// K's diagonal, in the unknowns' frames, kept by the system at its factorisation, and what
/// this process holds) and its right-hand side: the diagonal and the right-hand side at the
/// positions of `cond`, right on the rows this process owns, 0 at the others; `node_of` is
/// [`nodes_of`]'s.
fn whole_operator(
    system: &mut CoupledSystem,
    cond: &Condensed,
    node_of: &[usize],
) -> Result<(Operator, Option<Vec<f64>>)> {
    let contact = (0..cond.len()).filter(|&k| node_of[k] != INTERIOR).collect();
    let held = Held::new(contact, &cond.free, system.assembler().complete_rows());
    let (rows, diagonal) = system.kept_rows().ok_or_else(|| {
        Error::LinearAlgebra("the whole system's Newton step before its matrix".into())
    })?;
    let (rows, diagonal) = (rows.clone(), held.spread(diagonal.to_vec()));
    let rhs = held.spread(system.rhs().to_vec());
    Ok((Operator::Sparse { rows, diagonal, held }, Some(rhs)))
}

/// The rows of K that the whole system's Newton steps change: the kept Γ3 nodes' and their
/// neighbours'. On several processes the rows are this process's complete ones (its nodes')
/// and, partial, the kept nodes' that others own: their columns are the neighbours whose
/// rows turn with them ([`RowMatrix::turn`]); their own values are not used.
fn rows_read(system: &CoupledSystem, cond: &Condensed) -> Vec<bool> {
    let pattern = system.assembler().pattern();
    let mut on_contact = vec![false; pattern.n()];
    for (k, _) in nodes_of(cond).iter().enumerate().filter(|(_, i)| **i != INTERIOR) {
        on_contact[cond.free[k]] = true;
    }
    let mut touched = on_contact.clone();
    for j in 0..pattern.n() {
        for i in pattern.column(j).1.iter().map(|&i| i as usize) {
            touched[i] |= on_contact[j];
            touched[j] |= on_contact[i];
        }
    }
    let complete = system.assembler().complete_rows();
    let held = |r: usize| on_contact[r] || complete.is_none_or(|c| c[r]);
    (0..pattern.n()).map(|r| touched[r] && held(r)).collect()
}

/// Node i's block of T: `q[a][b]`, from its free component b (in its unknowns' frame) to its
/// local component a.
fn node_block(cond: &Condensed, frames: &[[[f64; 3]; 3]], i: usize) -> [[f64; 3]; 3] {
    let axes = cond.slots(i).1;
    let mut q = [[0.0; 3]; 3];
    for (a, row) in q.iter_mut().enumerate().take(axes.len()) {
        axes.iter().enumerate().for_each(|(b, &axis)| row[b] = frames[i][a][axis]);
    }
    q
}

/// The operator in local coordinates: Q S Qᵀ, or T K Tᵀ, node block by node block (a node
/// that condenses u_ν alone has one slot, on the axis of its normal).
fn turned_operator(
    operator: Operator,
    cond: &Condensed,
    frames: &[[[f64; 3]; 3]],
) -> Result<Operator> {
    let kept: Vec<usize> = (0..frames.len()).filter(|&i| cond.kept[i]).collect();
    let block = |i: usize| node_block(cond, frames, i);
    match operator {
        Operator::Sparse { mut rows, mut diagonal, held } => {
            for &i in &kept {
                rows.turn(&cond.slot_unknowns(i), &block(i))?;
            }
            let row_of = |k: usize| cond.free[k];
            for (k, d) in diagonal.iter_mut().enumerate().filter(|(k, _)| rows.has_row(row_of(*k)))
            {
                *d = rows.diagonal(row_of(k));
            }
            Ok(Operator::Sparse { rows, diagonal, held })
        }
        Operator::Dense(mut schur) => {
            let rotate = |q: &[[f64; 3]; 3], old: &[f64; 3], n: usize, a: usize| -> f64 {
                (0..n).map(|b| q[a][b] * old[b]).sum()
            };
            // Columns, then rows: every node block of each column, the columns in parallel.
            for &i in &kept {
                let (idx, q) = (cond.slots(i).0, block(i));
                let columns: Vec<Vec<f64>> = idx.iter().map(|&k| schur.col(k).to_vec()).collect();
                for (a, &k) in idx.iter().enumerate() {
                    for (r, out) in schur.col_mut(k).iter_mut().enumerate() {
                        let mut old = [0.0; 3];
                        columns.iter().zip(&mut old).for_each(|(c, o)| *o = c[r]);
                        *out = rotate(&q, &old, idx.len(), a);
                    }
                }
            }
            schur.fill_columns(|_, column| {
                for &i in &kept {
                    let (idx, q) = (cond.slots(i).0, block(i));
                    let mut old = [0.0; 3];
                    idx.iter().zip(&mut old).for_each(|(&k, o)| *o = column[k]);
                    idx.iter()
                        .enumerate()
                        .for_each(|(a, &k)| column[k] = rotate(&q, &old, idx.len(), a));
                }
            });
            Ok(Operator::Dense(schur))
        }
    }
}

impl<'a> Local<'a> {
    /// Turns the operator (S, or the whole system's K with its right-hand side `rhs`, in the
    /// unknowns' frames, at the positions) and the load into local coordinates,
    /// keeps x̂ (the global solve without contact forces) at the positions, and sets the
    /// constants; `node_of` is [`nodes_of`]'s.
    fn new(
        semismooth: &'a Semismooth<'a>,
        operator: Operator,
        node_of: Vec<usize>,
        (x_hat, mut rhs): (Vec<f64>, Option<Vec<f64>>),
        system: &'a mut CoupledSystem,
    ) -> Result<Self> {
        let (cond, surface) = (semismooth.condensed, semismooth.step.surface);
        let (frames, turned) = unknown_frames(surface, system.dofs());
        let m = cond.len();
        let mut operator = turned_operator(operator, cond, &frames)?;
        if let Operator::Sparse { diagonal, held, .. } = &mut operator {
            held.complete(diagonal, system)?;
            if let Some(rhs) = rhs.as_mut() {
                held.complete(rhs, system)?;
            }
        }
        let mut this = Self {
            semismooth,
            operator,
            system: Mutex::new(system),
            node_of,
            load: Vec::new(),
            frames,
            turned,
            c: Vec::new(),
            scale: Vec::new(),
            y_hat: Vec::new(),
            prescribed: (cond.phi.iter())
                .map(|phi| if let Phi::Prescribed(g) = phi { x_hat[*g] } else { 0.0 })
                .collect(),
            origin: vec![[0.0; 3]; surface.len()],
            conduction: 1.0,
            first_merit: std::sync::OnceLock::new(),
        };
        this.y_hat = this.gather(&{ x_hat }); // the global one freed
        this.load = match rhs {
            Some(mut load) => {
                this.to_local(&mut load);
                load
            }
            None => this.product(&this.y_hat),
        };
        if let Some(origin) = semismooth.step.slip_origin {
            let local = this.gather(origin);
            for (i, node) in this.origin.iter_mut().enumerate().filter(|(i, _)| cond.kept[*i]) {
                cond.slots(i).0.iter().zip(node.iter_mut()).for_each(|(&k, o)| *o = local[k]);
            }
        }
        this.c = (0..surface.len())
            .map(|i| {
                let k = cond.u[i][0];
                if !cond.kept[i] {
                    return 0.0;
                }
                semismooth.c_factor * this.operator.diagonal(k).abs() / surface.weight[i]
            })
            .collect();
        this.scale = (0..m)
            .map(|k| 1.0 / this.operator.diagonal(k).abs().sqrt().max(f64::MIN_POSITIVE))
            .collect();
        for i in (0..surface.len()).filter(|&i| cond.kept[i]) {
            cond.slots(i).0.iter().for_each(|&k| this.scale[k] *= surface.weight[i]);
        }
        Ok(this)
    }

    /// The semismooth Newton iteration from y, with its line search, until the sets settle
    /// and the step is at round-off, its iterates go round a cycle ([`Cycles`]), or `cap`
    /// steps.
    fn iterate(&self, mut y: Vec<f64>, cap: usize) -> Iteration {
        let semismooth = self.semismooth;
        let (mut history, mut cycles) = (Vec::new(), Cycles::default());
        let mut previous_sets: Option<Sets> = None;
        let (mut stop, mut iterations) = (Stop::Cap, cap);
        let (mut frozen, mut factorisations) = (None, 0);
        // E at y when the last step's line search or chord test has evaluated it already.
        let mut next: Option<Evaluation> = None;
        for k in 0..cap {
            if let Some(signal) = crate::interrupt::requested() {
                (stop, iterations) = (Stop::Interrupted(signal), k);
                break;
            }
            let eval = next.take().unwrap_or_else(|| self.evaluate(&y));
            let (delta, alpha) = match self.step(&y, &eval, &mut frozen, &mut factorisations) {
                Ok((delta, alpha, at_next)) => {
                    next = at_next;
                    (delta, alpha)
                }
                Err(e) => {
                    (stop, iterations) = (Stop::of_failed_solve(e), k + 1);
                    break;
                }
            };
            y.iter_mut().zip(&delta).for_each(|(a, d)| *a += alpha * d);
            let size = self.max_norm(&y).max(f64::MIN_POSITIVE);
            let criterion = alpha * self.max_norm(&delta) / size;
            history.push(criterion);
            let tolerance = STEP_TOLERANCE;
            (semismooth.step.progress)(Progress::Inner { iteration: k + 1, criterion, tolerance });
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
            if let Some(period) = cycles.period(&self.watched(&y)) {
                (stop, iterations) = (Stop::Cycle(period), k + 1);
                break;
            }
        }
        Iteration { y, stop, iterations, factorisations, history }
    }

    /// The step δ at y, its length α and E at y + α δ when evaluated: a chord step — the
    /// dense system factorised last (`frozen`, made for the same sets) with the right-hand
    /// side at y — when it multiplies the merit by at most [`CHORD_DECREASE`], α = 1; else a
    /// Newton step, factorised (counted in `factorisations` and kept in `frozen`), with its
    /// line search. Once the sets have settled, Newton's last steps thus cost a solve each
    /// instead of a factorisation.
    fn step(
        &self,
        y: &[f64],
        eval: &Evaluation,
        frozen: &mut Option<(Sets, TransposedLu)>,
        factorisations: &mut usize,
    ) -> Result<(Vec<f64>, f64, Option<Evaluation>)> {
        let merit = self.merit(eval);
        if let Some((_, lu)) = frozen.as_ref().filter(|(sets, _)| *sets == eval.sets)
            && let Ok((delta, _)) = self.newton_step(y, eval, Some(lu))
        {
            let trial: Vec<f64> = y.iter().zip(&delta).map(|(a, d)| a + d).collect();
            let at_trial = self.evaluate(&trial);
            if self.merit(&at_trial) <= CHORD_DECREASE * merit {
                return Ok((delta, 1.0, Some(at_trial)));
            }
        }
        *frozen = None; // freed before the new factorisation: one dense LU at a time
        let (delta, lu) = self.newton_step(y, eval, None)?;
        *factorisations += 1;
        *frozen = lu.map(|lu| (eval.sets.clone(), lu));
        let (alpha, at_next) = self.line_search(y, &delta, merit);
        Ok((delta, alpha, at_next))
    }

    /// The first iterate from y (the solve without contact forces on a cold start, else the
    /// last solution): the nodes y pushes through the foundation (u_ν above the stop ρ of the
    /// normal law) put on it, u_ν = ρ, and on a cold start also sticking, u_τ = 0; the others
    /// at y. From the solve without contact forces, every such node would carry no normal
    /// force yet, hence a friction bound s = 0 and a slip everywhere — a whole face pressed
    /// onto a plane would start with every tangential unknown in the dense system; from the
    /// last step of a loading path, the nodes the foundation's move pushed through start on
    /// it. The iteration starts from it, and from y when it leads nowhere.
    fn onto_foundation(&self, y: &[f64], stick: bool) -> Vec<f64> {
        let mut y = y.to_vec();
        let (cond, step) = (self.semismooth.condensed, self.semismooth.step);
        for i in (0..cond.u.len()).filter(|&i| cond.kept[i]) {
            let u = cond.slots(i).0;
            let stop = step.model.compliance.stop(step.surface.gap[i]);
            if y[u[0]] > stop {
                y[u[0]] = stop;
                if stick {
                    (1..u.len()).for_each(|a| y[u[a]] = self.origin[i][a]);
                }
            }
        }
        y
    }

    /// Whether the conduction acts: PV2 with k_e > 0, and ϕ an unknown of the condensed
    /// problem at some node (a penetration g_p > 0 lets the laws read it).
    fn conducts(&self) -> bool {
        let (step, cond) = (self.semismooth.step, self.semismooth.condensed);
        step.model.conduction.as_ref().is_some_and(|conduction| conduction.ke > 0.0)
            && cond.phi.iter().any(|phi| matches!(phi, Phi::Unknown(_)))
    }

    /// A continuation in k_e from the first iterate y, for when Newton has failed on the
    /// whole conduction (model §11): the problems with k_e scaled by θ, θ rising to 1, each
    /// stage from the solution of the last one with the nodes it pushes through the
    /// foundation put on it, within `cap` steps. The first stage is θ = [`FIRST_INCREMENT`];
    /// an increment is doubled after a stage that converges and quartered after one that does
    /// not, down to [`LEAST_INCREMENT`], in [`MAX_STAGES`] stages at most. Ends with the
    /// conduction whole again; returns the iteration (its iterate the last stage's solution,
    /// when one converged) and the θ it solves (1: the problem; 0: none).
    fn continuation(&mut self, y: Vec<f64>, cap: usize) -> (Iteration, f64) {
        let (mut theta, mut increment, mut solved) = (0.0, FIRST_INCREMENT, y);
        let mut done = Iteration {
            y: Vec::new(),
            stop: Stop::Cap,
            iterations: 0,
            factorisations: 0,
            history: Vec::new(),
        };
        for _ in 0..MAX_STAGES {
            let interrupted = matches!(done.stop, Stop::Interrupted(_));
            if theta == 1.0 || increment < LEAST_INCREMENT || interrupted {
                break;
            }
            self.conduction = (theta + increment).min(1.0);
            done = done.then(self.iterate(self.onto_foundation(&solved, false), cap));
            if matches!(done.stop, Stop::Converged) {
                (theta, increment) = (self.conduction, 2.0 * increment);
                solved = std::mem::take(&mut done.y);
            } else {
                increment /= 4.0;
            }
        }
        if theta < 1.0 && matches!(done.stop, Stop::Converged) {
            done.stop = Stop::Cap; // out of stages with a part of k_e solved
        }
        self.conduction = 1.0;
        (Iteration { y: solved, ..done }, theta)
    }

    /// The unknowns of y that tell a cycle: on the whole system its Γ3 unknowns, the laws'
    /// arguments — within a Newton iteration the others follow them by linear equations (K's,
    /// fixed), so that a loop of the sets shows there — and not a whole vector per iterate;
    /// the condensed problem's whole y.
    fn watched<'y>(&self, y: &'y [f64]) -> std::borrow::Cow<'y, [f64]> {
        match self.held() {
            Some(held) => held.contact.iter().map(|&k| y[k]).collect(),
            None => std::borrow::Cow::Borrowed(y),
        }
    }

    /// What this process holds of the whole system; `None` on the condensed problem (the same
    /// on every process).
    fn held(&self) -> Option<&Held> {
        match &self.operator {
            Operator::Sparse { held, .. } => Some(held),
            Operator::Dense(_) => None,
        }
    }

    /// The sum of the terms (position, value): on the whole system over the positions each
    /// process owns, summed over the processes, so that every process has the same; else of
    /// every term. NaN where a reduction fails (whose errors end the job by default).
    fn total(&self, terms: impl Iterator<Item = (usize, f64)>) -> f64 {
        match self.held() {
            None => terms.map(|(_, v)| v).sum(),
            Some(held) => self
                .system()
                .and_then(|mut system| held.sum(&mut system, terms))
                .unwrap_or(f64::NAN),
        }
    }

    /// max |v_k| over the positions (on the whole system, every process's owned ones), NaN
    /// where the reduction fails.
    fn max_norm(&self, values: &[f64]) -> f64 {
        match self.held() {
            None => max_norm(values),
            Some(held) => (self.system())
                .and_then(|mut system| held.max_norm(&mut system, values))
                .unwrap_or(f64::NAN),
        }
    }

    /// The iterate the iteration starts from, before the guess ([`Local::onto_foundation`]):
    /// 0 where it solves every equation ([`Local::zero_if_solution`]), else `start` (a
    /// global vector: the last solution) or the solve without contact forces.
    fn first_iterate(&self, start: Option<&[f64]>) -> Vec<f64> {
        let start = || start.map_or_else(|| self.y_hat.clone(), |x| self.gather(x));
        self.zero_if_solution().unwrap_or_else(start)
    }

    /// y = 0 when it solves every equation exactly — no load and no foundation inside the
    /// body, as at the end of a path that unloads — else `None`. The problem having one
    /// solution, the iteration then starts there and stops at its first step: from another
    /// start its iterates would tend to 0, where a step relative to the iterate cannot fall
    /// below round-off.
    fn zero_if_solution(&self) -> Option<Vec<f64>> {
        let zero = vec![0.0; self.semismooth.condensed.len()];
        let residual = self.evaluate(&zero).residual;
        let nonzero = residual.iter().map(|e| f64::from(u8::from(*e != 0.0)));
        (self.total(nonzero.enumerate()) == 0.0).then_some(zero)
    }

    /// The condensed entries of a global vector (mesh components), in local coordinates.
    fn gather(&self, x: &[f64]) -> Vec<f64> {
        let cond = self.semismooth.condensed;
        let mut y: Vec<f64> = cond.global.iter().map(|&dof| x[dof]).collect();
        let d = self.semismooth.step.surface.dim();
        for (i, turned) in self.turned.iter().enumerate().filter(|(i, _)| cond.kept[*i]) {
            // The unknowns of a node in a turned frame: R u from u's mesh components.
            let Some((rows, u)) = turned else { continue };
            let (idx, axes) = cond.slots(i);
            for (&k, &axis) in idx.iter().zip(axes) {
                y[k] = (0..d).map(|m| rows[axis][m] * x[u[m]]).sum();
            }
        }
        self.to_local(&mut y);
        y
    }

    /// A vector of the positions from the unknowns' frames to local coordinates.
    fn to_local(&self, y: &mut [f64]) {
        let cond = self.semismooth.condensed;
        for (i, q) in self.frames.iter().enumerate().filter(|(i, _)| cond.kept[*i]) {
            let (idx, axes) = cond.slots(i);
            let u: Vec<f64> = idx.iter().map(|&k| y[k]).collect();
            for (a, &k) in idx.iter().enumerate() {
                y[k] = axes.iter().zip(&u).map(|(&axis, v)| q[a][axis] * v).sum();
            }
        }
    }

    /// A y: Q S Qᵀ y, or T K Tᵀ y with the coupled system's K (this process's rows and the
    /// Γ3 rows).
    fn product(&self, y: &[f64]) -> Vec<f64> {
        match &self.operator {
            Operator::Dense(schur) => schur.mul(y),
            Operator::Sparse { held, .. } => {
                // K is only read: a panic elsewhere while the lock was held cannot spoil it.
                let mut system =
                    self.system.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
                let x = held.owned_part(self.to_global(y));
                // The product fails only where MPI's reduction does, whose errors end the job
                // by default; were it to return, non-finite forces fail the Newton step.
                let forces = system.product(&x).map(|f| held.spread(f)).and_then(|mut f| {
                    held.complete(&mut f, &mut system)?;
                    Ok(f)
                });
                let mut forces = forces.unwrap_or_else(|_| vec![f64::NAN; y.len()]);
                self.to_local(&mut forces);
                forces
            }
        }
    }

    /// The coupled system, locked.
    fn system(&self) -> Result<std::sync::MutexGuard<'_, &'a mut CoupledSystem>> {
        let poisoned = |_| Error::LinearAlgebra("a Newton step panicked with the system".into());
        self.system.lock().map_err(poisoned)
    }

    /// The relative residual to which an iterative backend solves a whole-system Newton
    /// step at an iterate of merit ‖scaled E‖² (inexact Newton, a forcing term in the manner
    /// of Eisenstat and Walker): ‖scaled E‖ relative to its value at the first step of the
    /// solve, between [`FORCING_FLOOR`] and [`FORCING_CEILING`] — loose far from the solution,
    /// tighter near it. (Relative to the
    /// load it would stay at the ceiling where the load is nil, as under an indenter whose
    /// displacement alone loads the body: every step then solved to 1e−2, and Newton
    /// converged linearly, in 13–16 steps on the 3D indentation.)
    fn forcing(&self, merit: f64) -> f64 {
        let first = *self.first_merit.get_or_init(|| merit);
        let relative = (merit / first.max(f64::MIN_POSITIVE)).sqrt();
        relative.clamp(FORCING_FLOOR, FORCING_CEILING)
    }

    /// The global vector (mesh components) of the solution y with its evaluation: the
    /// condensed problem's interior by a solve with the contact forces on the Γ3 rows; the
    /// whole system's y itself.
    fn whole_solution(&self, y: &[f64], eval: &Evaluation) -> Result<Vec<f64>> {
        let cond = self.semismooth.condensed;
        if let Some(held) = self.held() {
            // Every process fails alike, so that none waits for the others' next collective.
            let not_finite = y.iter().map(|v| f64::from(u8::from(!v.is_finite())));
            if self.total(not_finite.enumerate()) > 0.0 {
                let what = match y.iter().position(|v| !v.is_finite()) {
                    Some(k) => format!("solution component {}", cond.free[k]),
                    None => "a solution component of another process".to_string(),
                };
                return Err(Error::NonFinite { what });
            }
            // Gathered once, for the outputs: each process's rows, summed.
            let mut system = self.system()?;
            let mut whole = vec![0.0; system.dofs().n_free()];
            let owned = self.to_global(y).into_iter().enumerate().filter(|(k, _)| held.owns(*k));
            owned.for_each(|(k, v)| whole[cond.free[k]] = v);
            system.sum_over_processes(&mut whole)?;
            return Ok(system.dofs().expand(&whole));
        }
        let mut system = self.system()?;
        let mut forces = vec![0.0; system.dofs().n_free()];
        for (k, f) in self.to_global(&eval.forces).into_iter().enumerate() {
            forces[cond.free[k]] = f;
        }
        system.solve(Some(&forces))
    }

    /// A condensed vector from local to global coordinates.
    fn to_global(&self, local: &[f64]) -> Vec<f64> {
        let cond = self.semismooth.condensed;
        let mut v = local.to_vec();
        for (i, q) in self.frames.iter().enumerate().filter(|(i, _)| cond.kept[*i]) {
            let (idx, axes) = cond.slots(i);
            for (&k, &axis) in idx.iter().zip(axes) {
                v[k] = idx.iter().enumerate().map(|(a, &l)| q[a][axis] * local[l]).sum();
            }
        }
        v
    }

    /// ϕ at node i, or `None` when the laws that read it are off.
    fn phi(&self, y: &[f64], i: usize) -> Option<f64> {
        match self.semismooth.condensed.phi[i] {
            Phi::Unknown(p) => Some(y[p]),
            Phi::Prescribed(_) => Some(self.prescribed[i]),
            Phi::Interior => None,
        }
    }

    /// The compliance pressure h_ν p_ν at node i (0 with the laws off).
    fn pressure(&self, u_nu: f64, phi: Option<f64>, i: usize) -> f64 {
        let (step, gap) = (self.semismooth.step, self.semismooth.step.surface.gap[i]);
        phi.map_or(0.0, |phi| step.model.pressure(u_nu, phi, gap))
    }

    /// ‖scaled E‖².
    fn merit(&self, eval: &Evaluation) -> f64 {
        let terms = eval.residual.iter().zip(&self.scale).map(|(r, s)| (r * s).powi(2));
        self.total(terms.enumerate())
    }

    /// E, the sets and the multipliers at the condensed iterate y (local coordinates).
    fn evaluate(&self, y: &[f64]) -> Evaluation {
        let (step, cond) = (self.semismooth.step, self.semismooth.condensed);
        let (surface, law) = (step.surface, &step.model.compliance);
        let n3 = surface.len();
        let mut forces = self.product(y);
        forces.iter_mut().zip(&self.load).for_each(|(f, b)| *f -= b);
        let sigma_nu: Vec<f64> = (0..n3)
            .map(|i| if cond.kept[i] { forces[cond.u[i][0]] / surface.weight[i] } else { 0.0 })
            .collect();
        let r_sigma = step.friction.map_or_else(|| sigma_nu.clone(), |f| f.regularised(&sigma_nu));
        let whole = matches!(self.operator, Operator::Sparse { .. });
        let mut eval = Evaluation {
            // The rows of the interior (of the whole system) and of ϕ: F; the others below.
            forces: if whole { Vec::new() } else { forces.clone() },
            residual: forces,
            sets: Sets::new(n3, step.friction.is_some()),
            fixed: vec![false; y.len()],
            multipliers: ContactState::cold(n3),
            sigma_nu,
            r_sigma,
        };
        // The ϕ rows are the condensed charge balance less the conduction flux of every node
        // that reads the unknown (a floating electrode's nodes share one), below.
        for i in (0..n3).filter(|&i| cond.kept[i]) {
            let (w, u, c) = (surface.weight[i], cond.u[i], self.c[i]);
            // The condensed components of the node: d, or the normal alone.
            let dim = cond.slots(i).0.len();
            let (u_nu, phi) = (y[u[0]], self.phi(y, i));
            let (gap, rho) = (surface.gap[i], law.stop(surface.gap[i]));
            let lambda_c = -eval.sigma_nu[i] - self.pressure(u_nu, phi, i);
            eval.multipliers.lambda_c[i] = lambda_c;
            let normal = stop_complementarity(lambda_c, c, u_nu, rho);
            if normal.at_stop {
                eval.residual[u[0]] = -normal.overlap;
                eval.fixed[u[0]] = true;
                eval.sets.at_stop[i] = true;
            } else {
                eval.residual[u[0]] = lambda_c;
            }
            // F on the tangential rows, which the laws' rows below replace.
            let lambda_f: Vec<f64> = (1..dim).map(|a| -eval.residual[u[a]] / w).collect();
            (0..dim - 1).for_each(|a| eval.multipliers.lambda_f[i][a] = lambda_f[a]);
            match step.friction {
                None => (1..dim).for_each(|a| eval.residual[u[a]] = lambda_f[a - 1]),
                Some(friction) => {
                    let s = friction.node_bound(i, eval.r_sigma[i]);
                    self.coulomb_rows(y, i, (&lambda_f, s), &mut eval);
                }
            }
            if let (Phi::Unknown(p), Some(phi)) = (cond.phi[i], phi) {
                eval.residual[p] -= w * self.conduction * step.model.flux(u_nu, phi, gap);
            }
        }
        eval
    }

    /// The tangential rows E_t of node i with friction, from λ_f and the bound s: where the
    /// Coulomb law ([`coulomb`]) says the node sticks, −c (u_τ − u_τ⁰), which fixes u_τ; where
    /// it slips, λ_f − s ẑ with ẑ = z/‖z‖ (the projection of z = λ_f + c (u_τ − u_τ⁰) on the
    /// ball, written as the Jacobian differentiates it).
    fn coulomb_rows(
        &self,
        y: &[f64],
        i: usize,
        (lambda_f, s): (&[f64], f64),
        eval: &mut Evaluation,
    ) {
        let (u, c) = (self.semismooth.condensed.u[i], self.c[i]);
        let slip = |a: usize| y[u[a]] - self.origin[i][a];
        let mut z = [0.0; 2];
        (0..lambda_f.len()).for_each(|a| z[a] = lambda_f[a] + c * slip(a + 1));
        let status = coulomb(z, s).1;
        eval.sets.status[i] = status;
        let norm = z.iter().map(|v| v * v).sum::<f64>().sqrt();
        for a in 1..=lambda_f.len() {
            if status == NodeStatus::Stick {
                eval.residual[u[a]] = -c * slip(a);
                eval.fixed[u[a]] = true;
            } else {
                let direction = if norm > 0.0 { z[a - 1] / norm } else { 0.0 };
                eval.residual[u[a]] = lambda_f[a - 1] - s * direction;
            }
        }
    }

    /// The Newton step δ at y: the fixed unknowns from their own rows, the others from the
    /// system of the remaining rows — the dense one of the condensed unknowns (factorised
    /// here and returned, or the `frozen` factors of an earlier step with the same sets, a
    /// chord step), or the whole system's sparse one.
    fn newton_step(
        &self,
        y: &[f64],
        eval: &Evaluation,
        frozen: Option<&TransposedLu>,
    ) -> Result<(Vec<f64>, Option<TransposedLu>)> {
        match &self.operator {
            Operator::Dense(_) => self.dense_step(y, eval, frozen),
            Operator::Sparse { rows, held, .. } => {
                Ok((self.sparse_step(y, eval, (rows, held))?, None))
            }
        }
    }

    /// The steps of the unknowns that their equations fix (−c δ = −E), 0 elsewhere.
    fn fixed_steps(&self, eval: &Evaluation) -> Vec<f64> {
        let cond = self.semismooth.condensed;
        let mut delta = vec![0.0; eval.residual.len()];
        for i in (0..cond.u.len()).filter(|&i| cond.kept[i]) {
            for &k in cond.slots(i).0.iter().filter(|&&k| eval.fixed[k]) {
                delta[k] = eval.residual[k] / self.c[i];
            }
        }
        delta
    }

    /// The whole system's Newton step δ at y ([`Local::sparse_jacobian`] on `rows`, T K Tᵀ's
    /// rows that it changes), solved in the unknowns' frames (Tᵀ J T, Tᵀ r), where the
    /// preconditioner's rigid-body modes are the nodes' (a fixed local component is then a
    /// fixed direction), to the forcing tolerance: J and P handed to the system as patches of
    /// its matrix K, whose other rows they share.
    fn sparse_step(
        &self,
        y: &[f64],
        eval: &Evaluation,
        (rows, held): (&RowMatrix, &Held),
    ) -> Result<Vec<f64>> {
        let (mut jacobian, mut preconditioner, rhs) = self.sparse_jacobian(y, eval, rows);
        let cond = self.semismooth.condensed;
        for i in (0..self.frames.len()).filter(|&i| cond.kept[i]) {
            let q = node_block(cond, &self.frames, i);
            let transposed = std::array::from_fn(|a| q.map(|row| row[a]));
            let unknowns = cond.slot_unknowns(i);
            jacobian.turn(&unknowns, &transposed)?;
            preconditioner.turn(&unknowns, &transposed)?;
        }
        let rhs = self.to_global(&{ rhs }); // the local one freed before the solve
        let rtol = self.forcing(self.merit(eval));
        let mut system = self.system()?;
        let mut owned = held.owned_part(rhs);
        system.solve_unsymmetric((&jacobian, &preconditioner), &mut owned, rtol)?;
        let mut delta = held.spread(owned);
        held.complete(&mut delta, &mut system)?;
        drop(system);
        self.to_local(&mut delta);
        Ok(delta)
    }

    /// The whole system's Jacobian J at y in local coordinates, a symmetric matrix P near it
    /// to precondition with, and the right-hand side. J: T K Tᵀ with the Γ3 rows that no set
    /// fixes replaced by the laws' rows (their terms on the rows of K of the same node; terms
    /// on other nodes' rows — a nonlocal R's — are left out, so that the pattern stays K's),
    /// each u row times −w (force units, as the interior's); the fixed unknowns eliminated
    /// with their steps, their rows and columns zeroed but for K's diagonal. P: T K Tᵀ with
    /// the laws' terms on the diagonal of those rows (the compliance's, a slip's, the
    /// conduction's: ≥ 0 on u rows and ≤ 0 on ϕ rows, as K's own) and the same eliminations,
    /// so that its blocks are like K's for the field split and algebraic multigrid. J and P
    /// are made from `matrix`, T K Tᵀ's rows of the kept nodes and their neighbours (the rows
    /// that differ from K's), and hold those rows alone.
    fn sparse_jacobian(
        &self,
        y: &[f64],
        eval: &Evaluation,
        matrix: &RowMatrix,
    ) -> (RowMatrix, RowMatrix, Vec<f64>) {
        let (surface, cond) = (self.semismooth.step.surface, self.semismooth.condensed);
        let row_of = |k: usize| cond.free[k];
        let delta = self.fixed_steps(eval);
        let (mut jacobian, mut preconditioner) = (matrix.clone(), matrix.clone());
        let mut rhs: Vec<f64> = eval.residual.iter().map(|e| -e).collect();
        let mut terms = Vec::new();
        for k in (0..y.len()).filter(|&k| self.node_of[k] != INTERIOR && !eval.fixed[k]) {
            let i = self.node_of[k];
            terms.clear();
            self.gradient(y, eval, i, k, &mut terms);
            let phi_row = matches!(cond.phi[i], Phi::Unknown(p) if p == k);
            let factor = if phi_row { 1.0 } else { -surface.weight[i] };
            let (columns, values) = jacobian.row_mut(row_of(k));
            values.iter_mut().for_each(|v| *v = 0.0);
            let mut diagonal = 0.0;
            for term in terms.iter().filter(|t| self.on_node(t, i)) {
                match *term {
                    Term::Force(j, f) => {
                        add_matching(matrix.row(row_of(j)), factor * f, columns, values)
                    }
                    Term::Unknown(j, f) => {
                        if let Ok(at) = columns.binary_search(&row_of(j)) {
                            values[at] += factor * f;
                        }
                        diagonal += if j == k { factor * f } else { 0.0 };
                    }
                }
            }
            if let Some(at) = preconditioner.position(row_of(k), row_of(k)) {
                preconditioner.row_mut(row_of(k)).1[at] += diagonal;
            }
            rhs[k] *= factor;
        }
        for k in (0..y.len()).filter(|&k| eval.fixed[k]) {
            let diagonal = matrix.diagonal(row_of(k)).abs();
            // The rows this process holds move the fixed step to the right-hand side.
            for (r, a_rk) in jacobian.eliminate(row_of(k), diagonal) {
                if let Ok(p) = cond.free.binary_search(&r) {
                    rhs[p] -= a_rk * delta[k];
                }
            }
            rhs[k] = diagonal * delta[k];
            preconditioner.eliminate(row_of(k), diagonal);
        }
        (jacobian, preconditioner, rhs)
    }

    /// Whether a Jacobian term of a row of node i is one the whole system's sparse Jacobian
    /// keeps: a term on an unknown, or on a row of K of node i (a nonlocal R's terms on other
    /// nodes' rows would widen the pattern, and are left out).
    fn on_node(&self, term: &Term, i: usize) -> bool {
        match *term {
            Term::Force(j, _) => self.node_of[j] == i,
            Term::Unknown(..) => true,
        }
    }

    /// The dense Newton step of the condensed problem (see [`Local::newton_step`]).
    fn dense_step(
        &self,
        y: &[f64],
        eval: &Evaluation,
        frozen: Option<&TransposedLu>,
    ) -> Result<(Vec<f64>, Option<TransposedLu>)> {
        let m = y.len();
        let mut delta = self.fixed_steps(eval);
        let node_of = &self.node_of;
        let free: Vec<usize> = (0..m).filter(|&k| !eval.fixed[k]).collect();
        let fixed: Vec<usize> = (0..m).filter(|&v| eval.fixed[v] && delta[v] != 0.0).collect();
        // Row k of the Jacobian into `out` (on the free unknowns, when given); returns the
        // right-hand side −E_k less the fixed unknowns' part.
        let row = |k: usize, out: Option<&mut [f64]>| -> f64 {
            let mut gradient = vec![0.0; m];
            self.dense_gradient(y, eval, node_of[k], k, &mut gradient);
            if let Some(out) = out {
                free.iter().zip(out.iter_mut()).for_each(|(&v, o)| *o = gradient[v]);
            }
            -eval.residual[k] - fixed.iter().map(|&v| gradient[v] * delta[v]).sum::<f64>()
        };
        // The same sets fix the same unknowns, so frozen factors have the free rows' order.
        let (solved, lu) = match frozen {
            Some(lu) => {
                let rhs: Vec<f64> = free.par_iter().map(|&k| row(k, None)).collect();
                (lu.solve(&rhs)?, None)
            }
            None => {
                let mut reduced = DenseMatrix::zeros(free.len());
                let rhs = reduced.fill_columns(|column, out| row(free[column], Some(out)));
                let lu = reduced.lu_transposed();
                (lu.solve(&rhs)?, Some(lu))
            }
        };
        free.iter().zip(solved).for_each(|(&k, d)| delta[k] = d);
        Ok((delta, lu))
    }

    /// Row k of the Jacobian (the equation of unknown k, node i), dense, added to `out`.
    fn dense_gradient(&self, y: &[f64], eval: &Evaluation, i: usize, k: usize, out: &mut [f64]) {
        let mut terms = Vec::new();
        self.gradient(y, eval, i, k, &mut terms);
        for term in terms {
            match term {
                Term::Force(j, factor) => self.add_row(j, factor, out),
                Term::Unknown(j, factor) => out[j] += factor,
            }
        }
    }

    /// out += factor · (row j of A) at the positions (A is symmetric: its column j).
    fn add_row(&self, j: usize, factor: f64, out: &mut [f64]) {
        match &self.operator {
            Operator::Dense(schur) => {
                out.iter_mut().zip(schur.col(j)).for_each(|(o, s)| *o += factor * s)
            }
            Operator::Sparse { rows, .. } => {
                let free = &self.semismooth.condensed.free;
                let (columns, values) = rows.row(free[j]);
                for (c, v) in columns.iter().zip(values) {
                    if let Ok(p) = free.binary_search(c) {
                        out[p] += factor * v;
                    }
                }
            }
        }
    }

    /// The gradient of the equation of unknown k (node i) with respect to y, as terms
    /// pushed onto `terms` in the order they are summed.
    fn gradient(&self, y: &[f64], eval: &Evaluation, i: usize, k: usize, terms: &mut Vec<Term>) {
        let (step, cond) = (self.semismooth.step, self.semismooth.condensed);
        let surface = step.surface;
        let (w, u, c, dim) = (surface.weight[i], cond.u[i], self.c[i], cond.slots(i).0.len());
        let (u_nu, phi) = (y[u[0]], self.phi(y, i));
        let phi_position = match cond.phi[i] {
            Phi::Unknown(p) => Some(p),
            _ => None,
        };
        if Some(k) == phi_position {
            terms.push(Term::Force(k, 1.0));
            if step.model.conduction.is_some() {
                self.flux_gradient(y, k, terms);
            }
            return;
        }
        if k == u[0] {
            // Not in contact: E_n = λ_c = −σ_ν − q.
            let derivative = |phi| step.model.pressure_derivative(u_nu, phi, surface.gap[i]);
            let (dq_du, dq_dphi) = phi.map_or((0.0, 0.0), derivative);
            terms.push(Term::Force(u[0], -1.0 / w));
            terms.push(Term::Unknown(u[0], -dq_du));
            if let Some(p) = phi_position {
                terms.push(Term::Unknown(p, -dq_dphi));
            }
            return;
        }
        // A tangential equation, component a = k's place among the tangents.
        let a = (1..dim).find(|&a| u[a] == k).unwrap_or(1);
        let Some(friction) = step.friction else {
            terms.push(Term::Force(k, -1.0 / w)); // E_t = λ_f = −r_τ / w.
            return;
        };
        // Slip: E_t = λ_f − s ẑ, ∂E_t = ∂λ_f − (s/‖z‖)(I − λ̃ẑᵀ)(∂λ_f + c ∂u_τ) − ẑ ∂s.
        let lambda_f: Vec<f64> = (1..dim).map(|b| eval.multipliers.lambda_f[i][b - 1]).collect();
        let z: Vec<f64> =
            (1..dim).map(|b| lambda_f[b - 1] + c * (y[u[b]] - self.origin[i][b])).collect();
        let norm = z.iter().map(|v| v * v).sum::<f64>().sqrt();
        let s = friction.node_bound(i, eval.r_sigma[i]);
        let z_hat: Vec<f64> = z.iter().map(|v| if norm > 0.0 { v / norm } else { 0.0 }).collect();
        let lambda_norm = lambda_f.iter().map(|v| v * v).sum::<f64>().sqrt();
        let bound = s.max(lambda_norm).max(f64::MIN_POSITIVE);
        let ratio = if norm > 0.0 { s / norm } else { 0.0 };
        let direction = slip_direction(&lambda_f, bound, &z_hat);
        for b in 1..dim {
            // Coefficient of ∂z_b in row a of (s/‖z‖)(I − λ̃ẑᵀ).
            let identity = if a == b { 1.0 } else { 0.0 };
            let coefficient = ratio * (identity - direction[a - 1] * z_hat[b - 1]);
            // ∂λ_f,b = −S_{τb,·} / w.
            terms.push(Term::Force(u[b], -(identity - coefficient) / w));
            terms.push(Term::Unknown(u[b], -coefficient * c));
        }
        if s > 0.0 {
            let sign = friction.mu[i] * eval.r_sigma[i].signum() * z_hat[a - 1];
            for (j, weight) in friction.mollifier.row(i).into_iter().filter(|(j, _)| cond.kept[*j])
            {
                // ∂σ_ν,j = S_{ν_j,·} / w_j.
                terms.push(Term::Force(cond.u[j][0], -sign * weight / surface.weight[j]));
            }
        }
    }

    /// The gradient of the conduction fluxes that the ϕ row `p` subtracts: those of every
    /// node whose ϕ is the unknown p (one node, or a floating electrode's nodes), pushed onto
    /// `terms`.
    fn flux_gradient(&self, y: &[f64], p: usize, terms: &mut Vec<Term>) {
        let (step, cond) = (self.semismooth.step, self.semismooth.condensed);
        let surface = step.surface;
        let reading =
            (0..cond.u.len()).filter(|&j| matches!(cond.phi[j], Phi::Unknown(q) if q == p));
        for j in reading.filter(|&j| cond.kept[j]) {
            let (w, u_nu) = (surface.weight[j], y[cond.u[j][0]]);
            let (d_u, d_phi) = step.model.flux_derivative(u_nu, y[p], surface.gap[j]);
            terms.push(Term::Unknown(cond.u[j][0], -w * self.conduction * d_u));
            terms.push(Term::Unknown(p, -w * self.conduction * d_phi));
        }
    }

    /// The step length: the first of 1, ½, ¼, … (2⁻⁸ at the least) that decreases ‖scaled
    /// E‖² enough (Armijo), else the full step.
    fn line_search(&self, y: &[f64], delta: &[f64], current: f64) -> (f64, Option<Evaluation>) {
        let mut alpha = 1.0;
        for _ in 0..=HALVINGS {
            let trial: Vec<f64> = y.iter().zip(delta).map(|(a, d)| a + alpha * d).collect();
            let at_trial = self.evaluate(&trial);
            if self.merit(&at_trial) <= (1.0 - 1e-4 * alpha) * current {
                return (alpha, Some(at_trial));
            }
            alpha *= 0.5;
        }
        (1.0, None)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::assembly::{Linearisation, secant_moduli};
    use crate::linalg::default_solver;
    use crate::testing::{Fixture, INDENTATION_3D, PAPER_72};

    /// Feeds `points` to a fresh [`Cycles`] as iterates; the step at which it tells a cycle,
    /// and the period.
    fn first_cycle(points: &[Vec<f64>]) -> Option<(usize, usize)> {
        let mut cycles = Cycles::default();
        points.iter().enumerate().find_map(|(k, y)| cycles.period(y).map(|period| (k, period)))
    }

    /// A loop of 5 iterates (with round-off) is told once it has gone round a whole period
    /// twice, with its period; a converging sequence, even one that turns around its limit or
    /// takes no step at all, and a loop that drifts (by 1e−3 a step) are never told.
    #[test]
    fn a_cycle_is_told_after_two_periods_and_a_convergence_never() {
        let corners = [[2.0, 0.0], [0.5, 1.0], [-1.0, 0.3], [-0.2, -1.5], [1.1, -0.7]];
        let noise = |k: usize| 1e-13 * ((k * 7919) % 13) as f64;
        let looped: Vec<Vec<f64>> =
            (0..40).map(|k| corners[k % 5].iter().map(|c| c + noise(k)).collect()).collect();
        assert_eq!(first_cycle(&looped), Some((9, 5)));
        let spiral: Vec<Vec<f64>> = (0..200)
            .map(|k| {
                let (r, angle) = (0.9_f64.powi(k), 2.0 * std::f64::consts::PI * k as f64 / 5.0);
                vec![1.0 + r * angle.cos(), r * angle.sin()]
            })
            .collect();
        assert_eq!(first_cycle(&spiral), None);
        assert_eq!(first_cycle(&vec![vec![1.0, 2.0]; 20]), None);
        let drifting: Vec<Vec<f64>> =
            (0..40).map(|k| corners[k % 5].iter().map(|c| c + 1e-3 * k as f64).collect()).collect();
        assert_eq!(first_cycle(&drifting), None);
    }

    /// A slipping node's tangential block I − (s/‖z‖)(I − λ̃ẑᵀ) of the Jacobian (2 tangents),
    /// for λ_f at every angle to z and every length against s: with [`slip_direction`] its
    /// determinant (1 − s/‖z‖)(1 − s/‖z‖ + (s/‖z‖) λ̃·ẑ) stays positive; with λ_f / max(s, ‖λ_f‖)
    /// throughout it vanishes or turns negative where λ_f points against z (so the test
    /// tells); at a slip solution, λ_f = s ẑ, the direction is ẑ, the exact derivative's.
    #[test]
    fn a_slip_derivative_keeps_the_tangential_block_invertible() {
        let (s, norm) = (1.0, 1.6);
        let determinant = |direction: &[f64], z_hat: &[f64]| {
            let ratio = s / norm;
            let block = |a: usize, b: usize| {
                let identity = if a == b { 1.0 } else { 0.0 };
                identity - ratio * (identity - direction[a] * z_hat[b])
            };
            block(0, 0) * block(1, 1) - block(0, 1) * block(1, 0)
        };
        let mut singular_without = 0;
        for angle in (0..36).map(|k| f64::from(k) * std::f64::consts::PI / 18.0) {
            for length in [0.2, 1.0, 3.0] {
                let z_hat = [0.6, 0.8];
                let (sin, cos) = angle.sin_cos();
                let lambda_f = [length * (cos * 0.6 - sin * 0.8), length * (sin * 0.6 + cos * 0.8)];
                let bound = s.max(length);
                let direction = slip_direction(&lambda_f, bound, &z_hat);
                assert!(determinant(&direction, &z_hat) > 1e-3, "angle {angle}, |λ_f| {length}");
                let relaxed: Vec<f64> = lambda_f.iter().map(|v| v / bound).collect();
                singular_without += usize::from(determinant(&relaxed, &z_hat) <= 0.0);
            }
        }
        assert!(singular_without > 0);
        let at_solution = slip_direction(&[0.6 * s, 0.8 * s], s, &[0.6, 0.8]);
        assert!((at_solution[0] - 0.6).abs() < 1e-15 && (at_solution[1] - 0.8).abs() < 1e-15);
    }

    /// Checks `Local::gradient` against central differences of `Local::evaluate` on every
    /// equation that does not fix its unknown, at the point `y`; `skip_slip` leaves out the
    /// tangential rows of slipping nodes, whose derivative is relaxed away from a solution.
    fn check_gradient(local: &Local, y: &[f64], skip_slip: bool) -> usize {
        let eval = local.evaluate(y);
        let cond = local.semismooth.condensed;
        let (m, node_of) = (y.len(), &local.node_of);
        let mut slip_row = vec![false; m];
        for i in (0..cond.u.len()).filter(|&i| cond.kept[i]) {
            let slipping = eval.sets.status[i] == NodeStatus::Slip;
            cond.slots(i).0[1..].iter().for_each(|&k| slip_row[k] = slipping);
        }
        // Steps relative to the size of each kind of unknown (u and ϕ differ by far): the
        // global ϕ unknowns follow every u.
        let dim = local.semismooth.step.surface.dim();
        let n_total = local.system().unwrap().dofs().n_total();
        let is_phi = |k: usize| cond.global[k] >= n_total / (dim + 1) * dim;
        let size = |k: usize| {
            let same_kind = |j: &usize| is_phi(*j) == is_phi(k);
            (0..m).filter(same_kind).map(|j| y[j].abs()).fold(0.0, f64::max).max(1e-12)
        };
        let mut checked = 0;
        let rows = (0..m).filter(|&k| node_of[k] != INTERIOR);
        for k in rows.filter(|&k| !(eval.fixed[k] || skip_slip && slip_row[k])) {
            let mut gradient = vec![0.0; m];
            local.dense_gradient(y, &eval, node_of[k], k, &mut gradient);
            let scale = gradient.iter().zip(y).map(|(g, _)| g.abs()).fold(0.0, f64::max);
            for j in 0..m {
                let h = 1e-7 * size(j);
                let (mut plus, mut minus) = (y.to_vec(), y.to_vec());
                plus[j] += h;
                minus[j] -= h;
                let (e_plus, e_minus) = (local.evaluate(&plus), local.evaluate(&minus));
                if e_plus.sets != eval.sets || e_minus.sets != eval.sets {
                    continue; // a kink within the step
                }
                let difference = (e_plus.residual[k] - e_minus.residual[k]) / (2.0 * h);
                let error = (difference - gradient[j]).abs();
                assert!(
                    error <= 1e-5 * scale + 1e-9 * difference.abs().max(scale),
                    "row {k} column {j}: gradient {} against difference {difference}",
                    gradient[j]
                );
            }
            checked += 1;
        }
        checked
    }

    #[test]
    fn the_newton_jacobian_matches_difference_quotients() {
        for (regularization, whole) in
            [("identity", false), ("mollifier", false), ("identity", true), ("mollifier", true)]
        {
            let regularization = format!("friction.regularization=\"{regularization}\"");
            let fixture = Fixture::new(
                PAPER_72,
                &[
                    "mesh.nx=24",
                    "mesh.ny=4",
                    "material.law=\"linear\"",
                    "contact.penetration=0.05",
                    "solver.method=\"newton\"",
                    "conductivity.ke=0.5",
                    "friction.radius=1.0",
                    &regularization,
                ],
            );
            let checked = jacobian_case(&fixture, whole);
            assert!(checked > 20, "{regularization}, whole {whole}: {checked} rows checked");
        }
    }

    /// The same with Γ3 a floating electrode (no charge given): its nodes share one ϕ
    /// unknown, whose row (never fixed, so checked) subtracts every node's conduction flux;
    /// a little friction leaves slipping nodes, whose rows are checked at the solution.
    #[test]
    fn the_jacobian_with_a_floating_electrode_on_the_contact_face_matches_too() {
        let text = format!(
            "{PAPER_72}\n[[boundary.electrode]]\nname = \"sense\"\nparts = [\"contact\"]\ncharge = 0.0\n"
        );
        let fixture = Fixture::new(
            &text,
            &[
                "mesh.nx=24",
                "mesh.ny=4",
                "mesh.segments.contact=[\"[3,9]x{0}\"]",
                "material.law=\"linear\"",
                "solver.method=\"newton\"",
                "conductivity.ke=0.5",
                "friction.mu=0.05",
                "contact.penetration=0.5",
            ],
        );
        let (shared, distinct) = solved_step(&fixture, |local, _| {
            let cond = local.semismooth.condensed;
            let mut unknowns: Vec<usize> = (cond.phi.iter())
                .filter_map(|phi| if let Phi::Unknown(p) = phi { Some(*p) } else { None })
                .collect();
            let shared = unknowns.len();
            unknowns.dedup();
            (shared, unknowns.len())
        });
        assert!(shared > 4 && distinct == 1, "{shared} nodes read {distinct} ϕ unknowns");
        for whole in [false, true] {
            let checked = jacobian_case(&fixture, whole);
            assert!(checked > 10, "whole {whole}: {checked} rows checked");
        }
    }

    /// Prepares the exact solver on the fixture, solves one step (on the condensed problem,
    /// or the `whole` system), and checks the Jacobian of the Γ3 rows at the start (x̂, slip
    /// rows left out) and at the solution (every row). Returns the number of rows checked.
    fn jacobian_case(fixture: &Fixture, whole: bool) -> usize {
        solved_step_on(fixture, whole, |local, result| {
            let start = local.y_hat.clone();
            let solution = local.gather(&result.x);
            // The loop detection keeps the Γ3 unknowns of the whole system's iterates: each
            // kept node's u slots and the ϕ unknowns they read.
            let cond = local.semismooth.condensed;
            let kept = (0..cond.kept.len()).filter(|&i| cond.kept[i]);
            let mut contact: Vec<usize> = kept.flat_map(|i| cond.slots(i).0.to_vec()).collect();
            contact.extend(cond.phi.iter().filter_map(|phi| match phi {
                Phi::Unknown(p) => Some(*p),
                _ => None,
            }));
            contact.sort_unstable();
            contact.dedup();
            let watched = local.watched(&solution);
            if whole {
                assert!(contact.len() < solution.len());
                let expected: Vec<f64> = contact.iter().map(|&k| solution[k]).collect();
                assert_eq!(watched.as_ref(), expected.as_slice());
            } else {
                assert_eq!(watched.as_ref(), solution.as_slice());
            }
            let contact = local.evaluate(&solution).sets.holding();
            assert!(contact > 3, "the bar touches the foundation at {contact} nodes");
            check_gradient(local, &start, true) + check_gradient(local, &solution, false)
        })
    }

    /// Prepares the exact solver on the fixture, solves one step from the solve without
    /// contact, and hands the step's dense problem and its result to `check`.
    fn solved_step<T>(fixture: &Fixture, check: impl FnOnce(&Local, &InnerResult) -> T) -> T {
        solved_step_on(fixture, false, check)
    }

    /// faer's LDLᵀ without its Schur complement: the exact solver then runs on the whole
    /// system.
    #[derive(Debug)]
    struct Uncondensing(crate::linalg::LdltSolver);

    impl LinearSolver for Uncondensing {
        fn name(&self) -> &str {
            "ldlt without a Schur complement"
        }
        fn analyze(
            &mut self,
            pattern: &crate::linalg::SymmetricPattern,
            signs: &[i8],
        ) -> Result<()> {
            self.0.analyze(pattern, signs)
        }
        fn factorize(&mut self, matrix: &crate::linalg::SymmetricMatrix) -> Result<()> {
            self.0.factorize(matrix)
        }
        fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<()> {
            self.0.solve_in_place(rhs)
        }
        fn stats(&self) -> crate::linalg::SolverStats {
            self.0.stats()
        }
    }

    fn uncondensing() -> Box<dyn LinearSolver> {
        Box::new(Uncondensing(crate::linalg::LdltSolver::new()))
    }

    /// [`solved_step`] on the condensed problem, or on the whole system (`whole`).
    fn solved_step_on<T>(
        fixture: &Fixture,
        whole: bool,
        check: impl FnOnce(&Local, &InnerResult) -> T,
    ) -> T {
        let parameters = Parameters {
            r: 14.7,
            tol: 1e-10,
            max_inner: 100,
            max_condensed: Some(2000),
            guess: Guess::Nearest(2000),
        };
        let mut method = Newton::new(parameters);
        let solver = if whole { uncondensing() } else { default_solver() };
        let mut system = method.prepare(fixture.setup(), solver).unwrap();
        assert_eq!(method.whole, whole);
        let zero = vec![0.0; system.dofs().n_total()];
        let moduli = secant_moduli(fixture.problem(), system.dofs(), &zero).unwrap();
        let moduli = Linearisation::secant(moduli);
        system.factorize_linearised(fixture.problem(), &moduli, &[]).unwrap();
        let s_n = vec![0.0; fixture.surface.len()];
        let step = fixture.step(&zero, &s_n, &moduli);
        let condensed = method.condensed.clone().unwrap();
        let c_factor = method.c_factor;
        let semismooth = Semismooth {
            step: &step,
            condensed: &condensed,
            c_factor,
            max_inner: 100,
            start: None,
        };
        let mut schur = SchurSource::new(&condensed.free);
        let (result, _) = semismooth.run(&mut system, (!whole).then_some(&mut schur)).unwrap();
        assert!(matches!(result.stop, Stop::Converged), "{:?}", result.stop);
        let x_hat = system.solve(None).unwrap();
        let node_of = nodes_of(&condensed);
        let (operator, rhs) = if whole {
            whole_operator(&mut system, &condensed, &node_of).unwrap()
        } else {
            (Operator::Dense(system.schur_complement().unwrap()), None)
        };
        let local = Local::new(&semismooth, operator, node_of, (x_hat, rhs), &mut system).unwrap();
        check(&local, &result)
    }

    /// A KKT residual above solver.tol fails the run, and the error names its parts (not the
    /// outer loop's history, another criterion) and the outer steps, one in the singular; at
    /// the tolerance it passes.
    #[test]
    fn a_kkt_residual_above_the_tolerance_names_its_parts() {
        let parameters = Parameters {
            r: 1.0,
            tol: 1e-12,
            max_inner: 100,
            max_condensed: None,
            guess: Guess::Nearest(2000),
        };
        let method = Newton::new(parameters);
        let kkt = KktResidual { contact: 3e-11, friction: 2e-13, max: 3e-11, ..Default::default() };
        let e = method.accept(&kkt, &[0.0]).unwrap().to_string();
        assert!(e.contains("contact 3.0e-11, friction 2.0e-13") && e.contains("1e-12"), "{e}");
        assert!(e.contains("in 1 iteration:"), "{e}");
        let e = method.accept(&kkt, &[0.0, 0.0]).unwrap().to_string();
        assert!(e.contains("in 2 iterations:"), "{e}");
        assert!(method.accept(&KktResidual { max: 1e-12, ..kkt }, &[0.0]).is_none());
    }

    /// The largest differences of u and of ϕ between the solutions of the case `text` with
    /// `overrides` on the condensed problem and on the whole system, each relative to the
    /// field's largest value; both runs must converge (KKT residual within solver.tol).
    fn whole_against_condensed(text: &str, overrides: &[&str]) -> (f64, f64) {
        let built = crate::testing::built(text, overrides);
        let (problem, model) = (&built.problem, built.model.as_ref().unwrap());
        let solve = |solver| {
            let solution =
                super::super::solve_contact_with(problem, model, &built.settings, solver, &|_| {})
                    .unwrap();
            assert!(solution.failure.is_none(), "{overrides:?}: {:?}", solution.failure);
            solution
        };
        let (condensed, whole) = (solve(default_solver()), solve(uncondensing()));
        let dofs = &condensed.dofs;
        let n_u = problem.mesh.n_nodes() * problem.mesh.dim();
        let largest = |range: std::ops::Range<usize>| {
            let difference = range.clone().map(|g| (condensed.x[g] - whole.x[g]).abs());
            let size = range.map(|g| condensed.x[g].abs()).fold(0.0, f64::max);
            assert!(size > 0.0, "{overrides:?}: a field is zero");
            difference.fold(0.0, f64::max) / size
        };
        assert_eq!(dofs.n_total(), condensed.x.len());
        (largest(0..n_u), largest(n_u..dofs.n_total()))
    }

    /// The exact solver on the whole system (a backend without a Schur complement) solves
    /// the problem it solves condensed onto Γ3, to 1e−10 of each field (measured: 3e−14 and
    /// below): the paper's bar with
    /// Hencky's law, friction by a mollifier and conduction (the sparse Jacobian leaves out a
    /// nonlocal R's neighbours, the residual does not); the 3D indentation with friction; the
    /// quarter model on rollers turned 30° from the axes (Γ3 nodes in turned frames).
    #[test]
    fn the_whole_system_s_newton_solves_the_condensed_problem_s_solution() {
        let mesh = |name: &str| format!("mesh.file={:?}", mesh_path(name));
        let quarter = include_str!("../../../../cases/indentation-quarter.toml")
            .replace("fix = [\"x\"]", "fix = [\"normal\"]")
            .replace("fix = [\"y\"]", "fix = [\"normal\"]");
        let cases: [(&str, Vec<String>); 3] = [
            (
                PAPER_72,
                [
                    "mesh.nx=24",
                    "mesh.ny=4",
                    "solver.method=\"newton\"",
                    "contact.penetration=0.05",
                    "conductivity.ke=0.5",
                    "friction.radius=1.0",
                    "friction.regularization=\"mollifier\"",
                ]
                .map(String::from)
                .to_vec(),
            ),
            (INDENTATION_3D, vec![mesh("indent-3d-h0.05.msh")]),
            (&quarter, vec![mesh("indent-quarter-turned-h0.05.msh")]),
        ];
        for (text, overrides) in &cases {
            let overrides: Vec<&str> = overrides.iter().map(String::as_str).collect();
            let (du, dphi) = whole_against_condensed(text, &overrides);
            assert!(du < 1e-10 && dphi < 1e-10, "{overrides:?}: u {du:e}, ϕ {dphi:e}");
        }
    }

    fn mesh_path(name: &str) -> String {
        format!("{}/../../meshes/{name}", env!("CARGO_MANIFEST_DIR"))
    }

    /// Once the sets have settled, Newton's last steps solve with the last dense
    /// factorisation (chord steps): fewer factorisations than steps, down to the same
    /// solution of E = 0.
    #[test]
    fn settled_sets_take_chord_steps_to_the_solution() {
        // The ball pressed into a block (µ = 0.3): in 3D the slip direction makes the slip
        // rows nonlinear, so Newton's last steps, the sets settled, are not exact.
        let mesh = concat!(env!("CARGO_MANIFEST_DIR"), "/../../meshes/indent-3d-h0.05.msh");
        let fixture = Fixture::new(INDENTATION_3D, &[&format!("mesh.file={mesh:?}")]);
        solved_step(&fixture, |local, _| {
            let start = local.onto_foundation(&local.y_hat, true);
            let newton = local.iterate(start.clone(), 100);
            assert!(matches!(newton.stop, Stop::Converged), "{:?}", newton.stop);
            let (steps, factorised) = (newton.iterations, newton.factorisations);
            assert!(factorised < steps, "{factorised} factorisations in {steps} steps");
            let (first, last) = (local.evaluate(&start), local.evaluate(&newton.y));
            let (from, to) = (local.merit(&first), local.merit(&last));
            assert!(to <= 1e-20 * from, "‖scaled E‖² from {from:e} to {to:e}");
        })
    }

    /// The time line accounts for the exact solver's dense problem apart from the phases the
    /// system counts (solves included): with them it stays within the run's wall-clock time.
    /// Uzawa has no dense problem.
    #[test]
    fn the_dense_problem_is_timed_apart_from_the_counted_phases() {
        for (method, has_dense) in [("newton", true), ("uzawa", false)] {
            let method_key = format!("solver.method=\"{method}\"");
            let built = crate::testing::built(
                PAPER_72,
                &["mesh.nx=48", "mesh.ny=8", "material.law=\"linear\"", &method_key],
            );
            let model = built.model.as_ref().unwrap();
            let start = std::time::Instant::now();
            let solution =
                crate::algorithm::solve_contact(&built.problem, model, &built.settings).unwrap();
            let (wall, t) = (start.elapsed().as_secs_f64(), solution.timings);
            assert_eq!(t.dense > 0.0, has_dense, "{method}: dense {} s", t.dense);
            assert!(t.counted() + t.dense <= wall, "{method}: {t:?} within {wall} s");
        }
    }
}
