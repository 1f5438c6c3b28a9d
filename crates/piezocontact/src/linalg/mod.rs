//! Sparse symmetric linear algebra and the seam between the coupled system and a linear-solver
//! backend (model §5, §7, §11). The only module that names faer.
//!
//! The matrix of Step 1 of Algorithms 2 and 4 (\[P\] Section 6) is symmetric quasi-definite,
//! `[K_uu G; Gᵀ −K_ϕϕ]` with K_uu and K_ϕϕ positive definite once the Dirichlet rows are
//! removed (model §5). The default backend, [`LdltSolver`], is faer's sparse LDLᵀ: it exists
//! for every symmetric ordering without pivoting, with d_k > 0 on u rows and d_k < 0 on ϕ
//! rows; LLᵀ fails on the indefinite matrix (pinned by a test) and LU ignores symmetry (several
//! times the time and memory: `piezocontact bench --lu` prints both).
//!
//! ## The seam
//!
//! A backend is a value the caller hands to the coupled system
//! ([`crate::solver::CoupledSystem::new`]), never one the system builds. Its capabilities are
//! separate traits:
//! - [`LinearSolver`], which every backend has: [`LinearSolver::analyze`] (symbolic analysis
//!   of a [`SymmetricPattern`], once per pattern), [`LinearSolver::factorize`] (whenever the
//!   values change), [`LinearSolver::solve_in_place`] (as often as needed), with counts and
//!   timings;
//! - [`SchurComplement`], which backends that can condense have and announce through
//!   [`LinearSolver::schur`]: "the Schur complement of this list of unknowns". The backend
//!   chooses its own fill-reducing ordering with those unknowns last. A method that needs it
//!   (the exact solver) asks for it when the run is set up and refuses a backend without it
//!   there, with a message, never in the middle of a solve.
//!
//! ## A distributed backend
//!
//! The traits are shaped so that a backend whose rows live on several processes (PETSc with
//! MUMPS under `mpirun`) fits without changes to its callers:
//! - every process runs the same program on the same mesh; the backend hands the rows it owns
//!   to the distributed matrix at [`LinearSolver::factorize`];
//! - vectors cross the seam whole on every process: `solve_in_place` reads the whole
//!   right-hand side, scatters the owned rows into the distributed vector, solves, and gathers
//!   the solution back to every process, so that the contact algorithms (O(|Γ3|) work) run
//!   redundantly and identically everywhere;
//! - [`SchurComplement::schur_complement`] returns the dense Schur complement on every process
//!   (MUMPS builds it on the host, which broadcasts it);
//! - a backend that has [`LinearSolver::distributed`] says which mesh nodes' rows its process
//!   owns; the assembly then builds the pattern of those rows and sums only the cells that
//!   touch them, so that no process holds the whole matrix ([`Distributed`]);
//! - the pivot signs passed to [`LinearSolver::analyze`] are a hint on the matrix's inertia,
//!   which a backend may check (LDLᵀ does) or ignore (an LU or an iterative method).
//!
//! [`LdltSolver`] scales the matrix symmetrically by its diagonal, `S A S` with
//! `S = diag(|a_ii|^{-1/2})`, so that the u and ϕ blocks, whose entries differ by many orders
//! of magnitude and depend on the case's unit system (model §9), meet on equal terms. A pivot
//! that is tiny (below 1e-12 after scaling) or has the wrong sign for a quasi-definite matrix
//! is reported as [`crate::Error::SingularSystem`], never silently regularised.

mod dense;
mod ldlt;
pub mod ordering;
#[cfg(feature = "petsc")]
pub mod petsc;
mod sparse;

pub use dense::{DenseMatrix, TransposedLu, max_distance, max_norm};
pub use ldlt::LdltSolver;
#[cfg(feature = "petsc")]
pub use petsc::PetscSolver;
pub use sparse::{SymmetricMatrix, SymmetricPattern};

use crate::error::{Error, Result};

/// The fill-reducing ordering of [`LdltSolver`]'s symbolic analysis ([`ordering`]).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub enum Ordering {
    /// Nested dissection straight away for the pattern of a 3D mesh (more than
    /// [`ordering::DENSE_ROWS`] stored entries per row of the lower half; about 30 for P1
    /// tetrahedra, 11 for triangles), where it gave the smaller factor in every measurement;
    /// otherwise both symbolic analyses, AMD's and nested dissection's, and the one with the
    /// smaller factor.
    #[default]
    Auto,
    /// Approximate minimum degree.
    Amd,
    /// METIS's nested dissection of the mesh nodes, each node's unknowns together.
    NestedDissection,
    /// The caller's: `order[k]` is the unknown eliminated k-th (a permutation of 0..n).
    Custom(Vec<usize>),
}

/// Counts and wall-clock times of a linear solver.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SolverStats {
    /// Symbolic analysis: the ordering, the elimination tree and the factor's storage \[s\].
    pub symbolic_seconds: f64,
    /// All numeric factorisations \[s\].
    pub numeric_seconds: f64,
    /// Number of numeric factorisations.
    pub numeric_count: usize,
    /// All solves \[s\].
    pub solve_seconds: f64,
    /// Number of solves.
    pub solve_count: usize,
    /// Stored values of the factor (a measure of its memory).
    pub factor_len: usize,
    /// The bytes the last analysis predicted for a numeric factorisation (factor, workspace,
    /// scaled matrix).
    pub factor_bytes: f64,
    /// The ordering of the last analysis ("amd", "nd", "custom"; empty before one).
    pub ordering: &'static str,
    /// The floating-point operations of a numeric factorisation, as the last analysis counted
    /// them (0 from a backend that does not count them).
    pub factor_flops: f64,
}

/// What every backend does: analyse the pattern once, factorise whenever the values change,
/// solve as often as needed.
pub trait LinearSolver: std::fmt::Debug + Send {
    /// The backend's name, for messages and reports.
    fn name(&self) -> &str;
    /// Symbolic analysis of `pattern`; `signs` are the expected pivot signs (+1 for u rows,
    /// −1 for ϕ rows) of the quasi-definite matrix, a hint the backend may check.
    fn analyze(&mut self, pattern: &SymmetricPattern, signs: &[i8]) -> Result<()>;
    /// Numeric factorisation of `matrix`, which has the analysed pattern.
    fn factorize(&mut self, matrix: &SymmetricMatrix) -> Result<()>;
    /// Solves A x = b in place (b on entry, x on exit, whole vectors) with the current
    /// factorisation.
    fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<()>;
    /// Solves A X = B in place for the right-hand sides stored one after another in `rhs`
    /// (the columns of B, `n` entries each): by default one [`Self::solve_in_place`] each; a
    /// backend with blocked sweeps reads its factor once for all of them.
    fn solve_columns_in_place(&mut self, rhs: &mut [f64], n: usize) -> Result<()> {
        match column_count(rhs.len(), n)? {
            0 => Ok(()),
            _ => rhs.chunks_mut(n).try_for_each(|column| self.solve_in_place(column)),
        }
    }
    /// Counts and timings so far.
    fn stats(&self) -> SolverStats;
    /// The Schur-complement capability, for backends that have it.
    fn schur(&mut self) -> Option<&mut dyn SchurComplement> {
        None
    }
    /// The capability of a backend whose rows live on several processes.
    fn distributed(&mut self) -> Option<&mut dyn Distributed> {
        None
    }
}

/// What a backend whose rows live on several processes tells the assembly, so that each
/// process assembles and holds only its rows.
pub trait Distributed {
    /// Splits the mesh nodes between the processes — given the free unknowns of each node
    /// (`weights[a]`) and each node's neighbours (`adjacency.1[adjacency.0[a]..adjacency.0[a +
    /// 1]]`) — and returns those this process owns; `None` when it owns them all. The matrix
    /// handed to [`LinearSolver::factorize`] must then hold every entry of the owned nodes'
    /// rows, and may lack the others.
    fn owned_nodes(
        &mut self,
        weights: &[usize],
        adjacency: (&[usize], &[usize]),
    ) -> Result<Option<Vec<bool>>>;
    /// The sum of `value` over the processes.
    fn sum(&self, value: f64) -> Result<f64>;
}

/// What a backend that can condense does: eliminate every unknown but a given list, and give
/// the Schur complement S = K_cc − K_ci K_ii⁻¹ K_ic of that list (model §11).
pub trait SchurComplement {
    /// Symbolic analysis of `pattern` as [`LinearSolver::analyze`], with the unknowns `last`
    /// (distinct, below n) kept for the Schur complement, in that order; the backend orders
    /// the others as it likes.
    fn analyze_with_last(
        &mut self,
        pattern: &SymmetricPattern,
        signs: &[i8],
        last: &[usize],
    ) -> Result<()>;
    /// S of the unknowns given to [`SchurComplement::analyze_with_last`] (rows and columns
    /// in that order), from the current factorisation.
    fn schur_complement(&self) -> Result<DenseMatrix>;
}

/// The number of columns of `n` entries in `len` entries; an error when they do not divide.
fn column_count(len: usize, n: usize) -> Result<usize> {
    match (len, n) {
        (0, _) => Ok(0),
        (_, 0) => {
            Err(Error::LinearAlgebra(format!("{len} right-hand side entries for 0 unknowns")))
        }
        _ if len.is_multiple_of(n) => Ok(len / n),
        _ => Err(Error::LinearAlgebra(format!(
            "{len} right-hand side entries are no whole number of columns of {n}"
        ))),
    }
}

/// An [`crate::Error::Length`] unless a vector of `what` has the `expected` length.
fn check_length(what: &str, expected: usize, got: usize) -> Result<()> {
    if got == expected {
        return Ok(());
    }
    Err(crate::Error::Length { what: what.into(), expected, got })
}

/// A slice as a one-column matrix, for faer's solves and products of one right-hand side.
fn column<T>(v: &mut [T]) -> faer::MatMut<'_, T> {
    let n = v.len();
    faer::MatMut::from_column_major_slice_mut(v, n, 1)
}

/// The processes of the run: those of PETSc's communicator once the PETSc backend has
/// started, else 1.
pub fn processes() -> usize {
    #[cfg(feature = "petsc")]
    return petsc::rank_and_size().1;
    #[cfg(not(feature = "petsc"))]
    1
}

/// How faer splits its parallel work (the numeric factorisation of a 3D mesh, the solves, the
/// dense products and LU factorisations of the exact solver): into as many parts as the
/// machine has cores, whatever the number of threads that run them (`--threads`, the rayon
/// pool the run is on). faer sums in an order set by the split, not by the threads, so a run
/// gives the same answer to the last bit on one thread as on all of them; one thread pays about
/// 5 % of a 3D numeric factorisation for it, against faer's sequential kernels, when the
/// caller runs on a thread of the rayon pool (as the command, the Python package and
/// [`crate::algorithm::solve_contact`] do); called from outside the pool, each of faer's
/// parallel calls is handed to the pool and waited for, which cost a third more on the
/// 64k-unknown whole-face block. The first call also makes this faer's global parallelism,
/// which its dense solvers read. One core: sequential.
pub fn parallelism() -> faer::Par {
    static SPLIT: std::sync::OnceLock<faer::Par> = std::sync::OnceLock::new();
    *SPLIT.get_or_init(|| {
        let cores = std::thread::available_parallelism().map_or(1, std::num::NonZero::get);
        let split = if cores <= 1 { faer::Par::Seq } else { faer::Par::rayon(cores) };
        faer::set_global_parallelism(split);
        split
    })
}

/// The default backend: [`LdltSolver`] with the [`Ordering::Auto`] choice on the run's threads.
pub fn default_solver() -> Box<dyn LinearSolver> {
    Box::new(LdltSolver::new())
}
