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
//! ([`crate::system::CoupledSystem::new`]), never one the system builds. Its capabilities are
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
//! - vectors cross [`LinearSolver`] whole on every process: `solve_in_place` reads the
//!   right-hand side's owned rows, scatters them into the distributed vector, solves, and
//!   gathers the solution back to every process; [`UnsymmetricSolve`]'s product and solve
//!   take and give each process's own rows alone, so that the whole system's Newton method
//!   holds no whole vector, while the contact algorithms (O(|Γ3|) work) run redundantly and
//!   identically everywhere;
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
mod rows;
mod seam;
mod sparse;
mod vectors;

pub use dense::{DenseMatrix, TransposedLu, max_distance, max_norm, null_space, symmetric_eigen};
pub use ldlt::LdltSolver;
#[cfg(feature = "petsc")]
pub use petsc::PetscSolver;
pub use rows::{Patched, RowLu, RowMatrix};
pub use seam::{
    Distributed, LinearRoute, LinearSolver, Ordering, SchurComplement, SolverStats,
    UnsymmetricSolve,
};
pub use sparse::{PatternIndex, SymmetricMatrix, SymmetricPattern};
pub use vectors::parallelism;
pub(crate) use vectors::{check_length, masked, masked_view, unmasked};

/// The processes of the run: those of PETSc's communicator once the PETSc backend has
/// started, else 1.
pub fn processes() -> usize {
    #[cfg(feature = "petsc")]
    return petsc::rank_and_size().1;
    #[cfg(not(feature = "petsc"))]
    1
}

/// The default backend: [`LdltSolver`] with the [`Ordering::Auto`] choice on the run's threads.
pub fn default_solver() -> Box<dyn LinearSolver> {
    Box::new(LdltSolver::new())
}
