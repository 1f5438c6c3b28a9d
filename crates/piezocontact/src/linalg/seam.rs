//! The seam between the coupled system and a linear-solver backend: what every backend does
//! ([`LinearSolver`]), the capabilities some have ([`SchurComplement`], [`Distributed`]), and
//! what they count ([`SolverStats`]). The module docs of [`crate::linalg`] say how it is
//! shaped.

use super::dense::DenseMatrix;
use super::rows::{Patched, RowMatrix};
use super::sparse::{SymmetricMatrix, SymmetricPattern};
use super::vectors::column_count;
use crate::error::Result;

/// The fill-reducing ordering of [`super::LdltSolver`]'s symbolic analysis ([`super::ordering`]).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub enum Ordering {
    /// Nested dissection straight away for the pattern of a 3D mesh (more than
    /// [`super::ordering::DENSE_ROWS`] stored entries per row of the lower half; about 30 for P1
    /// tetrahedra, 11 for triangles), where it gave the smaller factor and the faster run in
    /// every measurement; nested dissection too for a 2D pattern of at least
    /// [`super::ordering::NESTED_2D`] unknowns whose numbering has no locality (a Gmsh
    /// mesh's); otherwise AMD, one analysis either way ([`super::ordering::nested_pays`],
    /// model §13).
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

/// How a backend solves its linear systems, for summary.json's `linear`.
#[derive(Clone, Debug, PartialEq)]
pub struct LinearRoute {
    /// "direct" (a factorisation, solved by substitution) or "iterative" (a Krylov method).
    pub kind: &'static str,
    /// The Krylov method's name (PETSc's, after the options), `None` on the direct route.
    pub krylov: Option<String>,
    /// The preconditioner's name (with each field's, for a field split), `None` on the direct
    /// route.
    pub preconditioner: Option<String>,
    /// The Krylov iterations of each linear solve, in order (empty on the direct route).
    pub krylov_iterations: Vec<usize>,
}

impl Default for LinearRoute {
    /// The direct route.
    fn default() -> Self {
        Self { kind: "direct", krylov: None, preconditioner: None, krylov_iterations: Vec::new() }
    }
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
    /// factorisation. A backend whose rows live on several processes reads b on its own
    /// rows alone (the caller may leave the others 0).
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
    /// How the systems are solved, with the Krylov iterations of every solve so far: by
    /// default the direct route.
    fn route(&self) -> LinearRoute {
        LinearRoute::default()
    }
    /// The Schur-complement capability, for backends that have it.
    fn schur(&mut self) -> Option<&mut dyn SchurComplement> {
        None
    }
    /// The capability of a backend whose rows live on several processes.
    fn distributed(&mut self) -> Option<&mut dyn Distributed> {
        None
    }
    /// The solve with a general matrix of a backend that has its own (an iterative one);
    /// `None`: the caller's sparse LU.
    fn unsymmetric(&mut self) -> Option<&mut dyn UnsymmetricSolve> {
        None
    }
    /// Frees what the backend makes again at its next solve — a Krylov solver's work vectors
    /// and its preconditioner's setup —, keeping the matrix and its factorisation: called
    /// when the solves of a contact solve are done, so that its assessment does not add to
    /// them. By default nothing (a factorisation is not made again). Collective.
    fn release_work(&mut self) -> Result<()> {
        Ok(())
    }
}

/// What a backend with its own solver of general matrices does: solve with a matrix of the
/// factorised one's pattern and values that are not symmetric — the Jacobian of the
/// semismooth Newton method on the whole system (model §11).
pub trait UnsymmetricSolve {
    /// Solves J x = b in place (b on entry, x on exit, each on this process's rows: the
    /// unknowns whose rows it owns, increasing — every unknown on one process), J the
    /// factorised matrix K with the rows of `patched.jacobian` in place of K's (a process may
    /// hold only the rows it owns), to the relative residual `rtol` where the method is iterative,
    /// preconditioned as for P (K with the rows of `patched.preconditioner`: symmetric, near
    /// J). The factorised matrix stays the one [`LinearSolver::solve_in_place`] solves with.
    fn solve_unsymmetric(&mut self, patched: Patched, rhs: &mut [f64], rtol: f64) -> Result<()>;
    /// K x with the factorised matrix K as the backend holds it, `x` and the product on this
    /// process's rows (as [`UnsymmetricSolve::solve_unsymmetric`]'s), so that the caller need
    /// not keep a copy of K of its own.
    fn product(&mut self, x: &[f64]) -> Result<Vec<f64>>;
    /// From now to the next factorisation, the operator of every solve and product is the
    /// factorised matrix plus `correction` (rows of the factorised matrix's pattern `pattern`,
    /// in the seam's numbering; a process may hold only the rows it owns), while the
    /// preconditioner stays the factorised matrix's: a positive matrix preconditions an
    /// operator that is not (Hencky's whole tangent beyond e·t0, model §13).
    fn correct(&mut self, pattern: &SymmetricPattern, correction: RowMatrix) -> Result<()>;
    /// Stops the next solve alone after at most `iterations` Krylov iterations (an error if
    /// it has not converged by then): a check that need not cost a whole solve's budget.
    fn cap_next_solve(&mut self, iterations: usize);
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
    /// Each entry of `values` (of the same length on every process) summed over the
    /// processes, in place.
    fn sum_each(&self, values: &mut [f64]) -> Result<()>;
    /// The sum of `value` over the processes.
    fn sum(&self, value: f64) -> Result<f64> {
        let mut values = [value];
        self.sum_each(&mut values)?;
        Ok(values[0])
    }
    /// The largest `value` over the processes.
    fn max(&self, value: f64) -> Result<f64>;
    /// The mesh nodes' coordinates, `dim` per node, and the component of each unknown (`i`
    /// for u_i, `dim` for ϕ), given before the analysis: an iterative backend makes from them
    /// the rigid-body modes of the elastic block, and gives a node's constrained components
    /// identity rows so that each node keeps `dim` elastic rows; ignored by others.
    fn node_layout(&mut self, _dim: usize, _coordinates: &[f64], _components: &[u8]) {}
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
