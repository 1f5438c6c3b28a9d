//! The coupled electro-elastic system without contact: assemble B̌(x_n) and f̌ (model §5),
//! factor once, solve. [`CoupledSystem`] keeps the pattern, the symbolic analysis and the
//! current factorisation so that the contact algorithms reuse them (model §7). The
//! factorisation is the caller's backend, behind the [`LinearSolver`] seam.

use crate::assembly::secant_moduli;
use crate::assembly::{Assembler, Linearisation, NodalBlock, load_vector, node_neighbours};
use crate::dofs::DofMap;
use crate::error::{Error, Result};
use crate::linalg::{
    DenseMatrix, LinearRoute, LinearSolver, Patched, RowLu, RowMatrix, SchurComplement,
    SolverStats, SymmetricMatrix, check_length, masked, masked_view, unmasked,
};
use crate::problem::{Factors, Problem};
use std::time::Instant;

/// The cap of [`CoupledSystem::check_solve`] in multiples of the most Krylov iterations of a
/// solve so far.
pub const CHECK_ITERATIONS: usize = 10;

/// The least cap of [`CoupledSystem::check_solve`].
pub const CHECK_FLOOR: usize = 100;

/// Wall-clock seconds spent in each phase, and what the linear solver counted.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Timings {
    /// The sparsity pattern, once per run \[s\].
    pub pattern: f64,
    /// Element matrices summed into the pattern (every refill), and f̌ \[s\].
    pub assembly: f64,
    /// The linear solver's counts and times: symbolic analysis, numeric factorisations and
    /// solves, and the bytes its last analysis predicted for a factorisation.
    pub solver: SolverStats,
    /// The exact solver's own work beyond the phases above: on the condensed problem its
    /// Schur complements (beyond the solves counted above) and Newton's dense iterations; on
    /// the whole system its Jacobians and, without a backend solver of general matrices, their
    /// sparse LU (0 without the exact solver) \[s\].
    pub dense: f64,
    /// The assessment of the solution: its KKT residual and force balance, the table of Γ3
    /// (without contact: the reactions and the extremes) \[s\].
    pub assessment: f64,
    /// The bytes of the exact solver's dense condensed matrices at the end (0 without).
    pub dense_bytes: f64,
    /// The process's peak resident memory when these timings were taken \[bytes\] (`None`
    /// where the system does not say).
    pub peak_resident_bytes: Option<f64>,
    /// How the linear systems were solved: direct or iterative, with the Krylov iterations
    /// of each solve.
    pub linear: LinearRoute,
}

impl Timings {
    /// The phases the system counts: pattern, assembly, symbolic, numeric and solves \[s\].
    pub fn counted(&self) -> f64 {
        let s = &self.solver;
        self.pattern + self.assembly + s.symbolic_seconds + s.numeric_seconds + s.solve_seconds
    }
}

/// Rows of K that a caller reads while the backend holds K ([`CoupledSystem::keep_rows`]).
#[derive(Debug)]
struct KeptRows {
    /// Which rows: a flag per free unknown.
    select: Vec<bool>,
    /// Those rows and K's diagonal on this process's rows ([`CoupledSystem::product`]'s), as
    /// of the last factorisation.
    rows: Option<(RowMatrix, Vec<f64>)>,
}

/// Assembler, factorisation and load vector of one problem.
#[derive(Debug)]
pub struct CoupledSystem {
    assembler: Assembler,
    solver: Box<dyn LinearSolver>,
    /// K, the last factorised matrix, where the backend does not multiply with its own
    /// ([`LinearSolver::unsymmetric`]): then no copy of it is kept here.
    matrix: Option<SymmetricMatrix>,
    /// The rows of K a caller reads ([`CoupledSystem::keep_rows`]).
    kept: Option<KeptRows>,
    /// f̌ on this process's rows ([`CoupledSystem::product`]'s), the loads scaled by
    /// `factors`: it does not depend on x_n.
    load: Vec<f64>,
    /// The factors on the applied loads and electrodes that `load` holds.
    factors: Factors,
    /// The Dirichlet lifting of the current matrix (with Hencky's tangent, (K_T − K_sec) x_n),
    /// on this process's rows.
    lifting: Vec<f64>,
    /// f̌ plus the lifting, on this process's rows.
    rhs: Vec<f64>,
    /// The solution for `rhs` alone on this process's rows (of the free unknowns), kept until
    /// the factorisation or `rhs` changes: the exact solver starts each round of a growing
    /// condensation and each step of a loading path that keeps the loads from it. (On
    /// several processes asking for it again sums the whole from each process's rows.)
    unloaded: Option<Vec<f64>>,
    /// Time of the pattern [s].
    pattern_seconds: f64,
    /// Assembly time so far [s].
    assembly_seconds: f64,
    /// Whether the prescribed displacements changed since the lifting was assembled
    /// ([`CoupledSystem::scale_loads`]): the next solve needs a new assembly.
    lifting_stale: bool,
    /// The sparse LU of general matrices, for a backend without its own
    /// ([`LinearSolver::unsymmetric`]).
    row_lu: RowLu,
}

impl CoupledSystem {
    /// Builds the pattern on the DOFs of `dofs` (with room for nodal blocks on
    /// `block_nodes`), assembles f̌ and runs the symbolic analysis of the caller's `solver`.
    pub fn new(
        problem: &Problem,
        dofs: DofMap,
        block_nodes: &[usize],
        solver: Box<dyn LinearSolver>,
    ) -> Result<Self> {
        let mut this = Self::unanalysed(problem, dofs, block_nodes, solver)?;
        this.solver.analyze(this.assembler.pattern(), &this.assembler.dofs().signs())?;
        Ok(this)
    }

    /// As [`CoupledSystem::new`] without nodal blocks, with the free unknowns `last` kept
    /// for the Schur complement ([`CoupledSystem::schur_complement`]). Refuses a `solver`
    /// without that capability, before any work.
    pub fn with_last(
        problem: &Problem,
        dofs: DofMap,
        last: &[usize],
        mut solver: Box<dyn LinearSolver>,
    ) -> Result<Self> {
        schur_capability(solver.as_mut())?;
        let mut this = Self::unanalysed(problem, dofs, &[], solver)?;
        this.put_last(last)?;
        Ok(this)
    }

    /// The pattern and f̌, before the symbolic analysis.
    fn unanalysed(
        problem: &Problem,
        dofs: DofMap,
        block_nodes: &[usize],
        mut solver: Box<dyn LinearSolver>,
    ) -> Result<Self> {
        let t = Instant::now();
        let owned = match solver.distributed() {
            Some(d) => {
                let (dim, coordinates) = (problem.mesh.dim(), problem.mesh.coordinates());
                d.node_layout(dim, coordinates, &dofs.free_components());
                let (ptr, neighbours) = node_neighbours(&problem.mesh);
                d.owned_nodes(&dofs.free_per_node(), (&ptr, &neighbours))?
            }
            None => None,
        };
        let assembler = Assembler::new(problem, dofs, block_nodes, owned.as_deref())?;
        let pattern_seconds = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let load = assembler.restrict_load(&load_vector(problem, assembler.dofs(), 1.0), 1.0);
        let load = masked(assembler.complete_rows(), load);
        let assembly_seconds = t.elapsed().as_secs_f64();
        Ok(Self {
            assembler,
            solver,
            matrix: None,
            kept: None,
            load,
            factors: Factors::from(1.0),
            lifting: Vec::new(),
            rhs: Vec::new(),
            unloaded: None,
            pattern_seconds,
            assembly_seconds,
            lifting_stale: false,
            row_lu: RowLu::default(),
        })
    }

    /// Keeps the free unknowns `last` (in that order) for the Schur complement and runs the
    /// symbolic analysis again; the next [`CoupledSystem::factorize`] uses it.
    pub fn put_last(&mut self, last: &[usize]) -> Result<()> {
        let signs = self.assembler.dofs().signs();
        (self.matrix, self.unloaded) = (None, None);
        let pattern = self.assembler.pattern();
        schur_capability(self.solver.as_mut())?.analyze_with_last(pattern, &signs, last)
    }

    /// Assembles B̌ with the secant `moduli` g_e (one per element) plus the nodal `blocks`,
    /// and factorises.
    pub fn factorize(
        &mut self,
        problem: &Problem,
        moduli: &[f64],
        blocks: &[NodalBlock],
    ) -> Result<()> {
        self.factorize_linearised(problem, &Linearisation::secant(moduli.to_vec()), blocks)
    }

    /// [`CoupledSystem::factorize`] with Hencky's law linearised at x_n (secant moduli and
    /// tangent parts); the right-hand side includes (K_T − K_sec) x_n.
    pub fn factorize_linearised(
        &mut self,
        problem: &Problem,
        linearisation: &Linearisation,
        blocks: &[NodalBlock],
    ) -> Result<()> {
        self.factorize_with(problem, (linearisation, None), blocks)
    }

    /// [`CoupledSystem::factorize_linearised`] on a route that solves with an operator other
    /// than its preconditioner ([`crate::linalg::UnsymmetricSolve`]): B̌ made with
    /// `linearisation` is the operator of every solve and product, B̌ made with
    /// `preconditioning` (Hencky's floored tangent, positive where the whole one is not) is
    /// factorised — set up as the preconditioner — and the backend holds their difference on
    /// the rows where they differ. Elsewhere the same as `factorize_linearised`.
    pub fn factorize_preconditioned(
        &mut self,
        problem: &Problem,
        (linearisation, preconditioning): (&Linearisation, &Linearisation),
        blocks: &[NodalBlock],
    ) -> Result<()> {
        if self.solver.unsymmetric().is_none() {
            return self.factorize_linearised(problem, linearisation, blocks);
        }
        self.factorize_with(problem, (linearisation, Some(preconditioning)), blocks)
    }

    /// The factorisation of B̌ made with the first linearisation, or of B̌ made with the
    /// second, corrected to the first ([`CoupledSystem::factorize_preconditioned`]).
    fn factorize_with(
        &mut self,
        problem: &Problem,
        (linearisation, preconditioning): (&Linearisation, Option<&Linearisation>),
        blocks: &[NodalBlock],
    ) -> Result<()> {
        let t = Instant::now();
        let (matrix, lifting) = self.assembler.linearised_matrix(problem, linearisation, blocks)?;
        let preconditioner = match preconditioning {
            Some(p) => Some(self.assembler.linearised_matrix(problem, p, blocks)?.0),
            None => None,
        };
        self.put_lifting(lifting);
        self.assembly_seconds += t.elapsed().as_secs_f64();
        match &preconditioner {
            None => self.solver.factorize(&matrix)?,
            Some(preconditioner) => {
                self.solver.factorize(preconditioner)?;
                // On every process (the backend's work is collective), whatever its rows.
                let correction = RowMatrix::difference(&matrix, preconditioner)?;
                let backend = self.solver.unsymmetric().expect("checked by the caller");
                backend.correct(self.assembler.pattern(), correction)?;
            }
        }
        if let Some(KeptRows { select, rows }) = &mut self.kept {
            let diagonal = masked(self.assembler.complete_rows(), matrix.diagonal());
            *rows = Some((RowMatrix::from_symmetric_rows(&matrix, |r| select[r]), diagonal));
        }
        self.matrix = self.solver.unsymmetric().is_none().then_some(matrix);
        Ok(())
    }

    /// Keeps the rows of K that `select` takes (one flag per free unknown) and K's diagonal
    /// at every factorisation from now on, for a caller that reads them while the backend
    /// holds K ([`CoupledSystem::kept_rows`]).
    pub fn keep_rows(&mut self, select: Vec<bool>) -> Result<()> {
        check_length("rows to keep", self.dofs().n_free(), select.len())?;
        self.kept = Some(KeptRows { select, rows: None });
        Ok(())
    }

    /// The rows of K chosen by [`CoupledSystem::keep_rows`] and K's diagonal on this process's
    /// rows ([`CoupledSystem::product`]'s), as of the last factorisation since.
    pub fn kept_rows(&self) -> Option<(&RowMatrix, &[f64])> {
        let (rows, diagonal) = self.kept.as_ref()?.rows.as_ref()?;
        Some((rows, diagonal))
    }

    /// Keeps the factorisation of B̌ (made with an earlier linearisation, matrix M) and sets
    /// the right-hand side of a chord step at x: that of `linearisation` (made at x, matrix
    /// K) plus (M − K) x on the free DOFs. The step M x_{n+1} = f̌ + (M − K_sec(x)) x +
    /// contact forces then has the same fixed point as Newton's, the true equations, at the
    /// cost of solves (model §13).
    pub fn chord(
        &mut self,
        problem: &Problem,
        linearisation: &Linearisation,
        blocks: &[NodalBlock],
        x: &[f64],
    ) -> Result<()> {
        let t = Instant::now();
        let (matrix, lifting) = self.assembler.linearised_matrix(problem, linearisation, blocks)?;
        let x_free = self.assembler.restrict(x);
        let (m_x, k_x) = (self.multiply(&x_free)?, matrix.mul(&x_free));
        let lifting = lifting.iter().zip(m_x.iter().zip(&k_x)).map(|(l, (m, k))| l + m - k);
        self.put_lifting(lifting.collect());
        self.assembly_seconds += t.elapsed().as_secs_f64();
        Ok(())
    }

    /// Takes `lifting` (on the free DOFs; this process's rows kept) as the matrix's lifting:
    /// the right-hand side is f̌ plus it from now on.
    fn put_lifting(&mut self, lifting: Vec<f64>) {
        self.lifting = masked(self.assembler.complete_rows(), lifting);
        self.lifting_stale = false;
        self.add_lifting();
    }

    /// The right-hand side f̌ + lifting of the current f̌ and lifting; the solve without
    /// contact forces kept for them is stale.
    fn add_lifting(&mut self) {
        self.rhs = self.load.iter().zip(&self.lifting).map(|(f, l)| f + l).collect();
        self.unloaded = None;
    }

    /// Assembles f̌ again with every load of `problem` scaled by `factors` (a step of a
    /// loading path: a bare factor [-] on the loads and the electrodes alike), keeping the
    /// matrix and its factorisation; nothing when f̌ holds those factors already.
    pub fn scale_loads(&mut self, problem: &Problem, factors: impl Into<Factors>) {
        let factors = factors.into();
        if factors == self.factors {
            return;
        }
        let t = Instant::now();
        if self.assembler.dofs().has_prescribed_displacements() {
            self.assembler.scale_displacements(factors);
            self.lifting_stale = true;
        }
        let dofs = self.assembler.dofs();
        let load = load_vector(problem, dofs, factors.loads);
        let load = self.assembler.restrict_load(&load, factors.electrodes);
        self.load = masked(self.assembler.complete_rows(), load);
        self.factors = factors;
        self.unloaded = None;
        if !self.lifting.is_empty() {
            self.add_lifting();
        }
        self.assembly_seconds += t.elapsed().as_secs_f64();
    }

    /// Whether the prescribed displacements changed since the lifting was assembled: the
    /// caller assembles again (a chord step or a factorisation) before it solves.
    pub fn lifting_stale(&self) -> bool {
        self.lifting_stale
    }

    /// Solves with the current factorisation for the current right-hand side plus `extra`
    /// (free DOFs), returning the global vector x = (u, ϕ) with prescribed values in place.
    /// Without `extra`, the solution is kept and given again until the factorisation or the
    /// right-hand side changes.
    pub fn solve(&mut self, extra: Option<&[f64]>) -> Result<Vec<f64>> {
        if let (None, Some(kept)) = (extra, &self.unloaded) {
            let mut x = unmasked(self.assembler.complete_rows(), kept.clone());
            if self.assembler.complete_rows().is_some() {
                self.sum_over_processes(&mut x)?;
            }
            return Ok(self.assembler.dofs().expand(&x));
        }
        let mut x = unmasked(self.assembler.complete_rows(), self.rhs.clone());
        if let Some(extra) = extra {
            x.iter_mut().zip(extra).for_each(|(b, e)| *b += e);
        }
        self.solver.solve_in_place(&mut x)?;
        if let Some(k) = x.iter().position(|v| !v.is_finite()) {
            return Err(Error::NonFinite { what: format!("solution component {k}") });
        }
        if extra.is_none() {
            self.unloaded = Some(masked_view(self.assembler.complete_rows(), &x).into_owned());
        }
        Ok(self.assembler.dofs().expand(&x))
    }

    /// The first solve after a factorisation on an iterative route, as the check that B̌ kept
    /// its signs (a Krylov method sees no pivots: a solve that fails stands in for a pivot of
    /// the wrong sign), capped at [`CHECK_ITERATIONS`] times the most iterations of a solve
    /// so far (at least [`CHECK_FLOOR`]), so that a failing check does not spend a whole
    /// solve's budget; its solution kept as [`CoupledSystem::solve`] keeps it.
    pub fn check_solve(&mut self) -> Result<Vec<f64>> {
        let most = self.solver.route().krylov_iterations.iter().max().copied();
        if let (None, Some(most), Some(backend)) = (&self.unloaded, most, self.solver.unsymmetric())
        {
            backend.cap_next_solve((CHECK_ITERATIONS * most).max(CHECK_FLOOR));
        }
        self.solve(None)
    }

    /// Solves J x = b in place (b and x on this process's rows, as [`CoupledSystem::product`]'s)
    /// for J the factorised matrix B̌ but on the rows of
    /// `jacobian` (a [`Patched`] row matrix of B̌'s pattern): by the backend where it has its
    /// own solver of such matrices, to the relative residual `rtol`, preconditioned as for P,
    /// B̌ with the rows of `preconditioner` (symmetric, near J); else by a sparse LU of J.
    pub fn solve_unsymmetric(
        &mut self,
        (jacobian, preconditioner): (&RowMatrix, &RowMatrix),
        rhs: &mut [f64],
        rtol: f64,
    ) -> Result<()> {
        let patched = Patched::new(self.assembler.pattern(), jacobian, preconditioner)?;
        let whole = self.assembler.complete_rows().is_none();
        match (self.solver.unsymmetric(), &self.matrix) {
            (Some(solver), _) => solver.solve_unsymmetric(patched, rhs, rtol),
            (None, Some(matrix)) if whole => {
                self.row_lu.solve(&patched.whole_jacobian(matrix)?, rhs)
            }
            (None, Some(_)) => Err(Error::LinearAlgebra(
                "a solve with a patched matrix on several processes needs a backend that solves it"
                    .into(),
            )),
            (None, None) => Err(Error::LinearAlgebra(
                "a solve with a patched matrix before the factorisation".into(),
            )),
        }
    }

    /// Solves B̌ Y = B in place with the current factorisation for the columns of B stored
    /// one after another in `columns` (each on the free DOFs, without f̌ or lifting).
    pub fn solve_free(&mut self, columns: &mut [f64]) -> Result<()> {
        let n = self.dofs().n_free();
        self.solver.solve_columns_in_place(columns, n)
    }

    /// The assembler (DOF map, pattern).
    pub fn assembler(&self) -> &Assembler {
        &self.assembler
    }

    /// The DOF map.
    pub fn dofs(&self) -> &DofMap {
        self.assembler.dofs()
    }

    /// The last factorised matrix, where this system keeps it (not where the backend
    /// multiplies with its own).
    pub fn matrix(&self) -> Option<&SymmetricMatrix> {
        self.matrix.as_ref()
    }

    /// The right-hand side f̌ + lifting on this process's rows ([`CoupledSystem::product`]'s).
    pub fn rhs(&self) -> &[f64] {
        &self.rhs
    }

    /// The Schur complement of the unknowns given to [`CoupledSystem::with_last`] or
    /// [`CoupledSystem::put_last`], from the current factorisation.
    pub fn schur_complement(&mut self) -> Result<DenseMatrix> {
        schur_capability(self.solver.as_mut())?.schur_complement()
    }

    /// ‖B̌x − f̌‖ / ‖f̌‖ on the free DOFs for the global `x`, over the complete rows of every
    /// process.
    pub fn relative_residual(&mut self, x: &[f64]) -> Result<f64> {
        let ax = self.multiply(&self.assembler.restrict(x))?;
        let ax = masked_view(self.assembler.complete_rows(), &ax);
        let (mut r2, mut b2) = (0.0, 0.0);
        for (a, b) in ax.iter().zip(&self.rhs) {
            (r2, b2) = (r2 + (a - b).powi(2), b2 + b.powi(2));
        }
        let mut sums = [r2, b2];
        self.sum_over_processes(&mut sums)?;
        Ok(sums[0].sqrt() / sums[1].sqrt().max(f64::MIN_POSITIVE))
    }

    /// Each entry of `values` (of the same length on every process) summed over the
    /// processes of a distributed backend, in place; unchanged on one process.
    pub fn sum_over_processes(&mut self, values: &mut [f64]) -> Result<()> {
        match self.solver.distributed() {
            Some(distributed) => distributed.sum_each(values),
            None => Ok(()),
        }
    }

    /// The largest `value` over the processes of a distributed backend; `value` on one.
    pub fn max_over_processes(&mut self, value: f64) -> Result<f64> {
        match self.solver.distributed() {
            Some(distributed) => distributed.max(value),
            None => Ok(value),
        }
    }

    /// B̌ x on this process's rows: `x` and the product on the free unknowns whose rows it
    /// owns, increasing (every one on one process).
    pub fn product(&mut self, x: &[f64]) -> Result<Vec<f64>> {
        let whole = self.assembler.complete_rows().is_none();
        match (&self.matrix, self.solver.unsymmetric()) {
            (_, Some(backend)) => backend.product(x),
            (Some(matrix), None) if whole => {
                check_length("x", matrix.n(), x.len())?;
                Ok(matrix.mul(x))
            }
            (Some(_), None) => Err(Error::LinearAlgebra(
                "a product on each process's rows needs a backend that multiplies".into(),
            )),
            (None, None) => {
                Err(Error::LinearAlgebra("a product with K before its assembly".into()))
            }
        }
    }

    /// K x on the free unknowns (`x` whole), each process's complete rows right (the others
    /// 0 with the backend's K).
    fn multiply(&mut self, x: &[f64]) -> Result<Vec<f64>> {
        match (&self.matrix, self.solver.unsymmetric()) {
            (Some(matrix), _) => {
                check_length("x", matrix.n(), x.len())?;
                Ok(matrix.mul(x))
            }
            (None, Some(backend)) => {
                let complete = self.assembler.complete_rows();
                let product = backend.product(&masked_view(complete, x))?;
                Ok(unmasked(complete, product))
            }
            (None, None) => {
                Err(Error::LinearAlgebra("a product with K before its assembly".into()))
            }
        }
    }

    /// Whether the systems are solved by a Krylov method (which, unlike a factorisation,
    /// cannot see a pivot of the wrong sign: its solve fails instead).
    pub fn is_iterative(&self) -> bool {
        self.solver.route().kind == "iterative"
    }

    /// The linear solver's counts, times, factor size and ordering.
    pub fn solver_stats(&self) -> SolverStats {
        self.solver.stats()
    }

    /// [`CoupledSystem::solver_stats`] with the times of a distributed backend summed over its
    /// processes, so that a choice made from them is the same on every process (each
    /// measures its own; processes that chose apart would call the solver apart and hang).
    pub fn agreed_stats(&mut self) -> Result<SolverStats> {
        let mut stats = self.solver.stats();
        if let Some(d) = self.solver.distributed() {
            stats.solve_seconds = d.sum(stats.solve_seconds)?;
            stats.numeric_seconds = d.sum(stats.numeric_seconds)?;
        }
        Ok(stats)
    }

    /// Timings so far.
    pub fn timings(&self) -> Timings {
        Timings {
            pattern: self.pattern_seconds,
            assembly: self.assembly_seconds,
            solver: self.solver.stats(),
            dense: 0.0,
            assessment: 0.0,
            dense_bytes: 0.0,
            peak_resident_bytes: crate::limits::peak_resident_bytes(),
            linear: self.solver.route(),
        }
    }

    /// Frees what the linear solver makes again at its next solve
    /// ([`LinearSolver::release_work`]): at the end of a contact solve, before its assessment.
    pub fn release_work(&mut self) -> Result<()> {
        self.solver.release_work()
    }

    /// Gives up the DOF map (at the end of a solve, for its result).
    pub fn into_dofs(self) -> DofMap {
        self.assembler.into_dofs()
    }
}

/// The Schur-complement capability of `solver`, or the error that refuses it.
fn schur_capability(solver: &mut dyn LinearSolver) -> Result<&mut dyn SchurComplement> {
    let name = solver.name().to_string();
    solver.schur().ok_or_else(|| {
        Error::Input(format!(
            "the linear solver '{name}' gives no Schur complement, which the exact solver (solver.method = \"newton\") needs; use solver.method = \"uzawa\" with it, or a backend that condenses"
        ))
    })
}

/// Result of a solve without contact.
#[derive(Clone, Debug)]
pub struct StaticSolution {
    /// x = (u, ϕ) on all DOFs, global numbering (u_i at node a: a·d + i; ϕ: n·d + a).
    pub x: Vec<f64>,
    /// The DOF numbering of `x`.
    pub dofs: DofMap,
    /// Relative residual ‖B̌x − f̌‖ / ‖f̌‖ of the last linear system on the free DOFs.
    pub relative_residual: f64,
    /// Factorisations of B̌ made: 1, and one more per secant step of Hencky's law.
    pub factorisations: usize,
    /// Why the secant steps stopped before the law was met (the cap), `None` when it was.
    pub failure: Option<Error>,
    /// Time spent.
    pub timings: Timings,
}

/// The most secant steps of Hencky's law a solve without contact makes.
const MAX_SECANT_STEPS: usize = 200;

/// The relative residual of the true law, ‖B̌(g(x)) x − f̌‖ / ‖f̌‖, at which the secant steps
/// stop.
const SECANT_TOLERANCE: f64 = 1e-8;

/// Solves the coupled problem without contact with the caller's `solver`: B̌(g(x)) x = f̌,
/// Hencky's law followed by secant steps from x_0 = 0 (B̌ with g(x_n), then x_{n+1}: Kačanov's
/// iteration, model §7's outer loop without contact) until g no longer changes or the
/// residual of the true law is at most 1e-8 of f̌; one factorisation when the law is linear
/// or the solution stays within t0.
pub fn solve_without_contact(
    problem: &Problem,
    solver: Box<dyn LinearSolver>,
) -> Result<StaticSolution> {
    let mut steps = solve_without_contact_at(problem, solver, &[Factors::from(1.0)])?;
    Ok(steps.pop().expect("one solution per load factor"))
}

/// [`solve_without_contact`] at each of `load_factors` in turn (a loading path without
/// contact), every load, prescribed displacement and electrode scaled by its factors, each from the last
/// one's secant moduli, on one system (one symbolic analysis); a step whose secant steps reach
/// their cap is the last, marked with its failure.
pub fn solve_without_contact_at(
    problem: &Problem,
    solver: Box<dyn LinearSolver>,
    load_factors: &[Factors],
) -> Result<Vec<StaticSolution>> {
    let mut system = CoupledSystem::new(problem, DofMap::new(problem)?, &[], solver)?;
    let zero = vec![0.0; system.dofs().n_total()];
    let mut moduli = secant_moduli(problem, system.dofs(), &zero)?;
    system.factorize(problem, &moduli, &[])?;
    let mut solutions = Vec::with_capacity(load_factors.len());
    for &factors in load_factors {
        system.scale_loads(problem, factors);
        if system.lifting_stale() {
            system.factorize(problem, &moduli, &[])?;
        }
        let (x, factorisations, failure) = secant_steps(problem, &mut system, &mut moduli)?;
        let relative_residual = system.relative_residual(&x)?;
        let (dofs, timings) = (system.dofs().clone(), system.timings());
        let stop = failure.is_some();
        let solution =
            StaticSolution { x, dofs, relative_residual, factorisations, failure, timings };
        solutions.push(solution);
        if stop {
            break;
        }
    }
    Ok(solutions)
}

/// Solves with the factorisation held, then secant steps while Hencky's law at the solution
/// differs from `moduli` (updated): the solution, the factorisations made (counting the one
/// held), and the failure when the steps reached their cap (the last iterate kept).
fn secant_steps(
    problem: &Problem,
    system: &mut CoupledSystem,
    moduli: &mut Vec<f64>,
) -> Result<(Vec<f64>, usize, Option<Error>)> {
    let mut x = system.solve(None)?;
    let mut residuals: Vec<f64> = Vec::new();
    for factorisations in 1..=MAX_SECANT_STEPS {
        let next = secant_moduli(problem, system.dofs(), &x)?;
        if next == *moduli {
            return Ok((x, factorisations, None));
        }
        system.factorize(problem, &next, &[])?;
        *moduli = next;
        // B̌ now holds g(x): its residual at x is the true law's.
        let residual = system.relative_residual(&x)?;
        residuals.push(residual);
        if residual <= SECANT_TOLERANCE {
            return Ok((x, factorisations + 1, None));
        }
        x = system.solve(None)?;
    }
    let failure = Error::NotConverged {
        what: "the secant steps of Hencky's law without contact".into(),
        iterations: MAX_SECANT_STEPS,
        criterion: residuals.last().copied().unwrap_or_default(),
        tolerance: SECANT_TOLERANCE,
        history: residuals
            .iter()
            .rev()
            .take(5)
            .rev()
            .map(|c| format!("{c:.1e}"))
            .collect::<Vec<_>>()
            .join(", "),
        hint: "the loads take the body far beyond Hencky's elasticity limit t0; lower them, or scale them up along a [loading] path".into(),
    };
    Ok((x, MAX_SECANT_STEPS + 1, Some(failure)))
}
