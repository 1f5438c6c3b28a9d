//! Sparse symmetric linear algebra: the only module that names faer.
//!
//! The matrix of Step 1 of Algorithms 2 and 4 ([P] Section 6) is symmetric quasi-definite,
//! `[K_uu G; Gᵀ −K_ϕϕ]` with K_uu and K_ϕϕ positive definite once the Dirichlet rows are
//! removed ([model §5](../../../docs/model.md)). Such a matrix has an LDLᵀ factorisation for
//! every symmetric ordering without pivoting, with d_k > 0 on u rows and d_k < 0 on ϕ rows. We
//! therefore use faer's sparse LDLᵀ (supernodal or simplicial as faer chooses) and not:
//! - LLᵀ (Cholesky), which fails on the indefinite matrix (pinned by a test below);
//! - LU, which ignores symmetry: on this matrix it takes several times the time and memory
//!   (`piezocontact bench --lu` prints both).
//!
//! Work is split as the algorithms need it (model §7):
//! - [`SymmetricPattern`]: the sparsity pattern, built once from the assembly's list of
//!   positions, with a gather plan that sums new values into it in parallel;
//! - [`LinearSolver`]: the seam between the coupled system and a factorisation —
//!   [`LinearSolver::analyze`] (symbolic analysis with a caller-chosen [`Ordering`], once per
//!   run), [`LinearSolver::factorize`] (whenever the values change) and
//!   [`LinearSolver::solve_in_place`] (as often as needed), with counts and timings;
//! - [`LdltSolver`]: faer's sparse LDLᵀ behind that seam.
//!
//! [`LdltSolver`] scales the matrix symmetrically by its diagonal, `S A S` with
//! `S = diag(|a_ii|^{-1/2})`, so that the u and ϕ blocks, whose entries differ by many orders
//! of magnitude and depend on the case's unit system (model §9), meet on equal terms. A pivot
//! that is tiny (below 1e-12 after scaling) or has the wrong sign for a quasi-definite matrix
//! is reported as [`Error::SingularSystem`], never silently regularised.

use crate::error::{Error, Result};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::ldlt::factor::LdltRegularization;
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, LdltRef, SymbolicCholesky, SymmetricOrdering,
    factorize_symbolic_cholesky,
};
use faer::sparse::{SparseColMat, SymbolicSparseColMat, Triplet};
use faer::{Conj, MatMut, Par, Side};
use rayon::prelude::*;
use std::time::Instant;

/// Pivots below this (after diagonal scaling) count as zero.
const PIVOT_THRESHOLD: f64 = 1e-12;
/// faer replaces a tiny or wrongly signed pivot by ±this marker, which no pivot of a scaled
/// matrix can reach; finding it in the factor reports the failure.
const PIVOT_MARKER: f64 = 1e300;
/// Target slots summed by one parallel task.
const GATHER_CHUNK: usize = 8192;

/// The column of a position that goes to the vector assembled alongside the matrix (the
/// Dirichlet lifting) instead of the matrix: `(row, VECTOR_ENTRY)`.
pub const VECTOR_ENTRY: usize = usize::MAX;

/// The lower-triangle sparsity pattern of a symmetric matrix, and the plan that sums an
/// assembly's values — one per position, repetitions included — into its entries and into a
/// vector of the same order.
///
/// The sums run in parallel over target entries, each adding its contributions in the order of
/// the positions: the result does not depend on the number of threads, to the last bit.
#[derive(Debug)]
pub struct SymmetricPattern {
    symbolic: SymbolicSparseColMat<usize>,
    /// Contributions of target slot s (matrix entries 0..nnz, then vector rows):
    /// `slot_entries[slot_ptr[s]..slot_ptr[s + 1]]`, ascending.
    slot_ptr: Vec<usize>,
    slot_entries: Vec<u32>,
}

impl SymmetricPattern {
    /// Builds the pattern of an n × n matrix from the positions at which an assembly produces
    /// its values, in that order: `(row, column)` with row ≥ column for a matrix entry, or
    /// `(row, VECTOR_ENTRY)` for a vector entry.
    pub fn new(n: usize, positions: &[(usize, usize)]) -> Result<Self> {
        if positions.len() > u32::MAX as usize {
            return Err(Error::LinearAlgebra(format!(
                "{} assembled values are more than this build's limit of {}",
                positions.len(),
                u32::MAX
            )));
        }
        if let Some(&(r, c)) =
            positions.iter().find(|&&(r, c)| r >= n || (c != VECTOR_ENTRY && (c > r)))
        {
            return Err(Error::LinearAlgebra(format!(
                "position ({r}, {c}) is outside the lower triangle of a {n} × {n} matrix"
            )));
        }
        let symbolic = lower_pattern(n, positions);
        let nnz = symbolic.row_idx().len();
        let slot_of = |&(r, c): &(usize, usize)| {
            if c == VECTOR_ENTRY {
                return nnz + r;
            }
            let range = symbolic.col_range(c);
            // The row is in its column: the pattern was built from these positions.
            let k = symbolic.row_idx()[range.clone()].binary_search(&r).unwrap_or_default();
            range.start + k
        };
        let slots: Vec<usize> = positions.par_iter().map(slot_of).collect();
        let mut slot_ptr = vec![0usize; nnz + n + 1];
        slots.iter().for_each(|&s| slot_ptr[s + 1] += 1);
        for s in 0..nnz + n {
            slot_ptr[s + 1] += slot_ptr[s];
        }
        let mut next = slot_ptr.clone();
        let mut slot_entries = vec![0u32; positions.len()];
        for (entry, &s) in slots.iter().enumerate() {
            slot_entries[next[s]] = entry as u32;
            next[s] += 1;
        }
        Ok(Self { symbolic, slot_ptr, slot_entries })
    }

    /// Order of the matrix.
    pub fn n(&self) -> usize {
        self.symbolic.nrows()
    }

    /// Number of values an assembly produces (positions, repetitions included).
    pub fn entries(&self) -> usize {
        self.slot_entries.len()
    }

    /// Stored entries of the lower triangle.
    pub fn nnz(&self) -> usize {
        self.symbolic.row_idx().len()
    }

    /// Sums `values` (one per position given to [`SymmetricPattern::new`], in that order) into
    /// the matrix and the vector.
    pub fn assemble(&self, values: &[f64]) -> Result<(SymmetricMatrix, Vec<f64>)> {
        if values.len() != self.entries() {
            return Err(Error::Length {
                what: "assembled values".into(),
                expected: self.entries(),
                got: values.len(),
            });
        }
        let mut targets = vec![0.0; self.slot_ptr.len() - 1];
        targets.par_chunks_mut(GATHER_CHUNK).enumerate().for_each(|(chunk, out)| {
            let first = chunk * GATHER_CHUNK;
            for (k, target) in out.iter_mut().enumerate() {
                let s = first + k;
                let contributions = &self.slot_entries[self.slot_ptr[s]..self.slot_ptr[s + 1]];
                *target = contributions.iter().fold(0.0, |sum, &e| sum + values[e as usize]);
            }
        });
        let vector = targets.split_off(self.nnz());
        let lower = SparseColMat::new(self.symbolic.clone(), targets);
        Ok((SymmetricMatrix { lower }, vector))
    }
}

/// The sorted, duplicate-free lower-triangle pattern of the matrix positions.
fn lower_pattern(n: usize, positions: &[(usize, usize)]) -> SymbolicSparseColMat<usize> {
    let mut col_ptr = vec![0usize; n + 1];
    let matrix = || positions.iter().filter(|p| p.1 != VECTOR_ENTRY);
    matrix().for_each(|&(_, c)| col_ptr[c + 1] += 1);
    for c in 0..n {
        col_ptr[c + 1] += col_ptr[c];
    }
    let mut rows = vec![0usize; col_ptr[n]];
    let mut next = col_ptr.clone();
    for &(r, c) in matrix() {
        rows[next[c]] = r;
        next[c] += 1;
    }
    let mut columns = Vec::with_capacity(n);
    let mut rest = rows.as_mut_slice();
    for c in 0..n {
        let (column, tail) = rest.split_at_mut(col_ptr[c + 1] - col_ptr[c]);
        columns.push(column);
        rest = tail;
    }
    let distinct: Vec<usize> = columns
        .into_par_iter()
        .map(|column| {
            column.sort_unstable();
            let mut kept = 0;
            for k in 0..column.len() {
                if k == 0 || column[k] != column[kept - 1] {
                    column[kept] = column[k];
                    kept += 1;
                }
            }
            kept
        })
        .collect();
    let mut compact_ptr = vec![0usize; n + 1];
    let mut row_idx = Vec::with_capacity(distinct.iter().sum());
    for c in 0..n {
        row_idx.extend_from_slice(&rows[col_ptr[c]..col_ptr[c] + distinct[c]]);
        compact_ptr[c + 1] = row_idx.len();
    }
    SymbolicSparseColMat::new_checked(n, n, compact_ptr, None, row_idx)
}

/// A symmetric sparse matrix stored by its lower triangle.
#[derive(Clone, Debug)]
pub struct SymmetricMatrix {
    lower: SparseColMat<usize, f64>,
}

impl SymmetricMatrix {
    /// Order of the matrix.
    pub fn n(&self) -> usize {
        self.lower.nrows()
    }

    /// Lower-triangle entries (row, column, value) with row ≥ column.
    pub fn lower_entries(&self) -> impl Iterator<Item = (usize, usize, f64)> + '_ {
        let (symbolic, values) = (self.lower.symbolic(), self.lower.val());
        (0..self.n()).flat_map(move |j| {
            let range = symbolic.col_range(j);
            symbolic.row_idx()[range.clone()]
                .iter()
                .zip(&values[range])
                .map(move |(&i, &v)| (i, j, v))
        })
    }

    /// y = A x.
    pub fn mul(&self, x: &[f64]) -> Vec<f64> {
        let mut y = vec![0.0; self.n()];
        for (i, j, v) in self.lower_entries() {
            y[i] += v * x[j];
            if i != j {
                y[j] += v * x[i];
            }
        }
        y
    }

    /// The diagonal.
    pub fn diagonal(&self) -> Vec<f64> {
        let mut d = vec![0.0; self.n()];
        self.lower_entries().filter(|(i, j, _)| i == j).for_each(|(i, _, v)| d[i] = v);
        d
    }

    /// The principal sub-matrix of rows and columns `range`, multiplied by `factor`.
    pub fn block(&self, range: std::ops::Range<usize>, factor: f64) -> Result<Self> {
        let triplets: Vec<Triplet<usize, usize, f64>> = self
            .lower_entries()
            .filter(|(i, j, _)| range.contains(i) && range.contains(j))
            .map(|(i, j, v)| Triplet::new(i - range.start, j - range.start, factor * v))
            .collect();
        let lower = SparseColMat::try_new_from_triplets(range.len(), range.len(), &triplets)
            .map_err(|e| Error::LinearAlgebra(format!("block: {e:?}")))?;
        Ok(Self { lower })
    }

    /// Whether the matrix is positive definite (its sparse LLᵀ factorisation exists).
    pub fn is_positive_definite(&self) -> Result<bool> {
        let symbolic = symbolic_cholesky(self.lower.symbolic(), SymmetricOrdering::Amd)?;
        let mut l_values = vec![0.0; symbolic.len_val()];
        let mut mem = MemBuffer::try_new(
            symbolic.factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default()),
        )
        .map_err(|_| Error::LinearAlgebra("out of memory for the LLᵀ workspace".into()))?;
        let result = symbolic.factorize_numeric_llt(
            &mut l_values,
            self.lower.as_ref(),
            Side::Lower,
            LltRegularization::default(),
            Par::Seq,
            MemStack::new(&mut mem),
            Default::default(),
        );
        Ok(result.is_ok())
    }

    /// Symbolic and numeric LU of the full matrix and one solve, timed, for comparison in
    /// benchmarks: (symbolic, numeric, solve) seconds.
    pub fn time_lu(&self, rhs: &[f64]) -> Result<[f64; 3]> {
        use faer::linalg::solvers::Solve;
        use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
        let mut triplets = Vec::new();
        for (i, j, v) in self.lower_entries() {
            triplets.push(Triplet::new(i, j, v));
            if i != j {
                triplets.push(Triplet::new(j, i, v));
            }
        }
        let full = SparseColMat::try_new_from_triplets(self.n(), self.n(), &triplets)
            .map_err(|e| Error::LinearAlgebra(format!("{e:?}")))?;
        let t = std::time::Instant::now();
        let symbolic = SymbolicLu::try_new(full.symbolic())
            .map_err(|e| Error::LinearAlgebra(format!("{e:?}")))?;
        let t_symbolic = t.elapsed().as_secs_f64();
        let t = std::time::Instant::now();
        let lu = Lu::try_new_with_symbolic(symbolic, full.as_ref())
            .map_err(|e| Error::SingularSystem { detail: format!("LU: {e:?}") })?;
        let t_numeric = t.elapsed().as_secs_f64();
        let mut x = rhs.to_vec();
        let t = std::time::Instant::now();
        lu.solve_in_place(MatMut::from_column_major_slice_mut(&mut x, self.n(), 1));
        Ok([t_symbolic, t_numeric, t.elapsed().as_secs_f64()])
    }
}

fn symbolic_cholesky(
    pattern: faer::sparse::SymbolicSparseColMatRef<'_, usize>,
    ordering: SymmetricOrdering<'_, usize>,
) -> Result<SymbolicCholesky<usize>> {
    factorize_symbolic_cholesky(pattern, Side::Lower, ordering, CholeskySymbolicParams::default())
        .map_err(|e| Error::LinearAlgebra(format!("symbolic analysis: {e:?}")))
}

/// The fill-reducing ordering of a symbolic analysis.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub enum Ordering {
    /// Approximate minimum degree, chosen by the factorisation.
    #[default]
    Amd,
    /// The caller's: `order[k]` is the unknown eliminated k-th (a permutation of 0..n). The
    /// exact contact solver puts the Γ3 unknowns last this way.
    Custom(Vec<usize>),
}

/// Counts and wall-clock times of a linear solver.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SolverStats {
    /// Symbolic analysis [s].
    pub symbolic_seconds: f64,
    /// All numeric factorisations [s].
    pub numeric_seconds: f64,
    /// Number of numeric factorisations.
    pub numeric_count: usize,
    /// All solves [s].
    pub solve_seconds: f64,
    /// Number of solves.
    pub solve_count: usize,
    /// Stored values of the factor (a measure of its memory).
    pub factor_len: usize,
}

/// The seam between a symmetric system and its factorisation: analyse the pattern once,
/// factorise whenever the values change, solve as often as needed.
pub trait LinearSolver: std::fmt::Debug + Send {
    /// Symbolic analysis of `pattern` with the `ordering`; `signs` are the expected pivot
    /// signs (+1 for u rows, −1 for ϕ rows) of a quasi-definite matrix.
    fn analyze(
        &mut self,
        pattern: &SymmetricPattern,
        signs: &[i8],
        ordering: &Ordering,
    ) -> Result<()>;
    /// Numeric factorisation of `matrix`, which has the analysed pattern.
    fn factorize(&mut self, matrix: &SymmetricMatrix) -> Result<()>;
    /// Solves A x = b in place (b on entry, x on exit) with the current factorisation.
    fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<()>;
    /// Counts and timings so far.
    fn stats(&self) -> SolverStats;
}

/// Sparse LDLᵀ of a symmetric quasi-definite matrix (faer's supernodal or simplicial LDLᵀ).
#[derive(Debug, Default)]
pub struct LdltSolver {
    symbolic: Option<SymbolicCholesky<usize>>,
    /// +1 for u rows, −1 for ϕ rows.
    signs: Vec<i8>,
    /// S = diag(|a_ii|^{-1/2}) of the last factorised matrix.
    scaling: Vec<f64>,
    l_values: Vec<f64>,
    factorized: bool,
    stats: SolverStats,
}

impl LdltSolver {
    /// A solver with nothing analysed yet.
    pub fn new() -> Self {
        Self::default()
    }

    fn symbolic(&self) -> Result<&SymbolicCholesky<usize>> {
        self.symbolic.as_ref().ok_or_else(|| {
            Error::LinearAlgebra("factorisation before the symbolic analysis".into())
        })
    }
}

/// Checks that `order` is a permutation of 0..n and returns it with its inverse.
fn permutation(order: &[usize], n: usize) -> Result<(Vec<usize>, Vec<usize>)> {
    let mut inverse = vec![usize::MAX; n];
    if order.len() != n {
        return Err(Error::Length {
            what: "custom ordering".into(),
            expected: n,
            got: order.len(),
        });
    }
    for (k, &i) in order.iter().enumerate() {
        if i >= n || inverse[i] != usize::MAX {
            return Err(Error::LinearAlgebra(format!(
                "custom ordering: entry {k} = {i} repeats an unknown or is not below {n}"
            )));
        }
        inverse[i] = k;
    }
    Ok((order.to_vec(), inverse))
}

impl LinearSolver for LdltSolver {
    fn analyze(
        &mut self,
        pattern: &SymmetricPattern,
        signs: &[i8],
        ordering: &Ordering,
    ) -> Result<()> {
        let n = pattern.n();
        if signs.len() != n {
            return Err(Error::Length {
                what: "pivot signs".into(),
                expected: n,
                got: signs.len(),
            });
        }
        let t = Instant::now();
        let symbolic = match ordering {
            Ordering::Amd => symbolic_cholesky(pattern.symbolic.as_ref(), SymmetricOrdering::Amd)?,
            Ordering::Custom(order) => {
                let (forward, inverse) = permutation(order, n)?;
                let perm = PermRef::new_checked(&forward, &inverse, n);
                symbolic_cholesky(pattern.symbolic.as_ref(), SymmetricOrdering::Custom(perm))?
            }
        };
        self.l_values = vec![0.0; symbolic.len_val()];
        self.symbolic = Some(symbolic);
        self.signs = signs.to_vec();
        self.scaling = vec![1.0; n];
        self.factorized = false;
        self.stats.symbolic_seconds += t.elapsed().as_secs_f64();
        self.stats.factor_len = self.l_values.len();
        Ok(())
    }

    fn factorize(&mut self, matrix: &SymmetricMatrix) -> Result<()> {
        let t = Instant::now();
        self.factorized = false;
        let diagonal = matrix.diagonal();
        for (i, d) in diagonal.iter().enumerate() {
            if !d.is_finite() || *d == 0.0 {
                return Err(Error::SingularSystem { detail: format!("diagonal entry {i} is {d}") });
            }
        }
        self.scaling = diagonal.iter().map(|d| 1.0 / d.abs().sqrt()).collect();
        let mut scaled = matrix.lower.clone();
        {
            let symbolic = matrix.lower.symbolic();
            let (col_ptr, row_idx) = (symbolic.col_ptr(), symbolic.row_idx());
            let values = scaled.val_mut();
            for j in 0..matrix.n() {
                for k in col_ptr[j]..col_ptr[j + 1] {
                    values[k] *= self.scaling[row_idx[k]] * self.scaling[j];
                }
            }
        }
        let params = Default::default();
        let symbolic = self.symbolic.take().ok_or_else(|| {
            Error::LinearAlgebra("factorisation before the symbolic analysis".into())
        })?;
        let result = (|| {
            let mut mem = MemBuffer::try_new(
                symbolic.factorize_numeric_ldlt_scratch::<f64>(Par::Seq, params),
            )
            .map_err(|_| Error::LinearAlgebra("out of memory for the LDLᵀ workspace".into()))?;
            // A tiny or wrongly signed pivot is replaced by the marker, which then shows in the
            // factor.
            let regularization = LdltRegularization {
                dynamic_regularization_signs: Some(&self.signs),
                dynamic_regularization_delta: PIVOT_MARKER,
                dynamic_regularization_epsilon: PIVOT_THRESHOLD,
            };
            symbolic
                .factorize_numeric_ldlt(
                    &mut self.l_values,
                    scaled.as_ref(),
                    Side::Lower,
                    regularization,
                    Par::Seq,
                    MemStack::new(&mut mem),
                    params,
                )
                .map(|_| ())
                .map_err(|e| Error::SingularSystem { detail: format!("{e:?}") })
        })();
        self.symbolic = Some(symbolic);
        result?;
        self.stats.numeric_count += 1;
        self.stats.numeric_seconds += t.elapsed().as_secs_f64();
        if self.l_values.iter().any(|v| !v.is_finite() || v.abs() >= PIVOT_MARKER) {
            return Err(Error::SingularSystem {
                detail: "a pivot was below 1e-12 after diagonal scaling, or had the wrong sign"
                    .into(),
            });
        }
        self.factorized = true;
        Ok(())
    }

    fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<()> {
        let n = self.signs.len();
        if !self.factorized {
            return Err(Error::LinearAlgebra("solve before a successful factorisation".into()));
        }
        if rhs.len() != n {
            return Err(Error::Length {
                what: "right-hand side".into(),
                expected: n,
                got: rhs.len(),
            });
        }
        let t = Instant::now();
        let symbolic = self.symbolic()?;
        rhs.iter_mut().zip(&self.scaling).for_each(|(b, s)| *b *= s);
        let mut mem = MemBuffer::try_new(symbolic.solve_in_place_scratch::<f64>(1, Par::Seq))
            .map_err(|_| Error::LinearAlgebra("out of memory for the solve workspace".into()))?;
        LdltRef::new(symbolic, &self.l_values).solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(rhs, n, 1),
            Par::Seq,
            MemStack::new(&mut mem),
        );
        rhs.iter_mut().zip(&self.scaling).for_each(|(x, s)| *x *= s);
        self.stats.solve_count += 1;
        self.stats.solve_seconds += t.elapsed().as_secs_f64();
        Ok(())
    }

    fn stats(&self) -> SolverStats {
        self.stats
    }
}

/// The floor for benchmarks: faer's own numeric LDLᵀ and one solve of `matrix` (AMD, no
/// scaling, no checks), timed: (numeric, solve) seconds.
pub fn bare_ldlt_seconds(matrix: &SymmetricMatrix, rhs: &[f64]) -> Result<[f64; 2]> {
    let symbolic = symbolic_cholesky(matrix.lower.symbolic(), SymmetricOrdering::Amd)?;
    let mut l_values = vec![0.0; symbolic.len_val()];
    let params = Default::default();
    let t = Instant::now();
    let mut mem =
        MemBuffer::try_new(symbolic.factorize_numeric_ldlt_scratch::<f64>(Par::Seq, params))
            .map_err(|_| Error::LinearAlgebra("out of memory for the LDLᵀ workspace".into()))?;
    symbolic
        .factorize_numeric_ldlt(
            &mut l_values,
            matrix.lower.as_ref(),
            Side::Lower,
            LdltRegularization::default(),
            Par::Seq,
            MemStack::new(&mut mem),
            params,
        )
        .map_err(|e| Error::SingularSystem { detail: format!("{e:?}") })?;
    let numeric = t.elapsed().as_secs_f64();
    let mut x = rhs.to_vec();
    let t = Instant::now();
    let mut mem = MemBuffer::try_new(symbolic.solve_in_place_scratch::<f64>(1, Par::Seq))
        .map_err(|_| Error::LinearAlgebra("out of memory for the solve workspace".into()))?;
    LdltRef::new(&symbolic, &l_values).solve_in_place_with_conj(
        Conj::No,
        MatMut::from_column_major_slice_mut(&mut x, matrix.n(), 1),
        Par::Seq,
        MemStack::new(&mut mem),
    );
    Ok([numeric, t.elapsed().as_secs_f64()])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn analyzed(pattern: &SymmetricPattern, signs: &[i8], ordering: &Ordering) -> LdltSolver {
        let mut solver = LdltSolver::new();
        solver.analyze(pattern, signs, ordering).unwrap();
        solver
    }

    /// A small quasi-definite matrix [K G; Gᵀ −M] with K, M tridiagonal SPD.
    fn quasi_definite(
        n_u: usize,
        n_phi: usize,
        scale_phi: f64,
    ) -> (SymmetricPattern, Vec<f64>, Vec<i8>) {
        let mut positions = Vec::new();
        let mut values = Vec::new();
        for i in 0..n_u {
            positions.push((i, i));
            values.push(4.0);
            if i > 0 {
                positions.push((i, i - 1));
                values.push(-1.0);
            }
        }
        for k in 0..n_phi {
            let i = n_u + k;
            positions.push((i, i));
            values.push(-3.0 * scale_phi);
            if k > 0 {
                positions.push((i, i - 1));
                values.push(1.0 * scale_phi);
            }
            positions.push((i, k % n_u));
            values.push(2.0 * scale_phi.sqrt());
        }
        let signs = (0..n_u + n_phi).map(|i| if i < n_u { 1 } else { -1 }).collect();
        (SymmetricPattern::new(n_u + n_phi, &positions).unwrap(), values, signs)
    }

    #[test]
    fn ldlt_solves_a_quasi_definite_system_that_cholesky_cannot() {
        for scale in [1.0, 1e-12] {
            let (pattern, values, signs) = quasi_definite(30, 12, scale);
            let a = pattern.assemble(&values).unwrap().0;
            assert!(!a.is_positive_definite().unwrap(), "LLᵀ must fail: the matrix is indefinite");
            let mut solver = analyzed(&pattern, &signs, &Ordering::Amd);
            solver.factorize(&a).unwrap();
            // ϕ of the size the scaling implies (ϕ ~ 1/√scale), as in a physical solution.
            let x: Vec<f64> = (0..a.n())
                .map(|i| (i as f64 * 0.37).sin() / if i < 30 { 1.0 } else { scale.sqrt() })
                .collect();
            let mut b = a.mul(&x);
            solver.solve_in_place(&mut b).unwrap();
            for (block, range) in [("u", 0..30), ("phi", 30..42)] {
                let err = range.clone().map(|i| (b[i] - x[i]).abs()).fold(0.0, f64::max);
                let size = range.map(|i| x[i].abs()).fold(0.0, f64::max);
                assert!(err < 1e-12 * size, "scale {scale}, {block}: error {err} of {size}");
            }
        }
    }

    #[test]
    fn factorisation_is_reused_across_solves() {
        let (pattern, values, signs) = quasi_definite(20, 5, 1.0);
        let a = pattern.assemble(&values).unwrap().0;
        let mut solver = analyzed(&pattern, &signs, &Ordering::Amd);
        solver.factorize(&a).unwrap();
        for k in 0..5 {
            let mut b = vec![k as f64; a.n()];
            solver.solve_in_place(&mut b).unwrap();
        }
        let stats = solver.stats();
        assert_eq!((stats.numeric_count, stats.solve_count), (1, 5));
    }

    #[test]
    fn singular_and_wrong_sign_systems_are_errors() {
        // A singular Laplacian (no Dirichlet row): the last pivot is zero.
        let n = 6;
        let mut positions = Vec::new();
        let mut values = Vec::new();
        for i in 0..n {
            positions.push((i, i));
            values.push(if i == 0 || i == n - 1 { 1.0 } else { 2.0 });
            if i > 0 {
                positions.push((i, i - 1));
                values.push(-1.0);
            }
        }
        let pattern = SymmetricPattern::new(n, &positions).unwrap();
        let a = pattern.assemble(&values).unwrap().0;
        let mut solver = analyzed(&pattern, &vec![1; n], &Ordering::Amd);
        let e = solver.factorize(&a).unwrap_err().to_string();
        assert!(e.contains("singular or not quasi-definite"), "{e}");
        assert!(solver.solve_in_place(&mut vec![0.0; n]).is_err());
        // A definite matrix declared with a ϕ row: the sign check catches it.
        let mut values = values.clone();
        values[0] = 2.0;
        let a = pattern.assemble(&values).unwrap().0;
        let mut signs = vec![1; n];
        signs[n - 1] = -1;
        let mut solver = analyzed(&pattern, &signs, &Ordering::Amd);
        assert!(solver.factorize(&a).is_err());
        let e = pattern.assemble(&values[1..]).unwrap_err().to_string();
        assert!(e.contains("expected length"), "{e}");
    }
}

#[cfg(test)]
mod seam_tests {
    use super::*;

    #[test]
    fn the_gather_sums_repeated_positions_and_fills_the_vector() {
        // 3 × 3: (0,0) twice, (2,1), (1,1), a vector entry on row 2 twice.
        let positions =
            [(0, 0), (2, 1), (2, VECTOR_ENTRY), (0, 0), (1, 1), (2, VECTOR_ENTRY), (2, 2)];
        let pattern = SymmetricPattern::new(3, &positions).unwrap();
        assert_eq!((pattern.n(), pattern.entries(), pattern.nnz()), (3, 7, 4));
        let (a, v) = pattern.assemble(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0]).unwrap();
        let mut entries: Vec<(usize, usize, f64)> = a.lower_entries().collect();
        entries.sort_by_key(|e| (e.0, e.1));
        assert_eq!(entries, vec![(0, 0, 5.0), (1, 1, 5.0), (2, 1, 2.0), (2, 2, 7.0)]);
        assert_eq!(v, vec![0.0, 0.0, 9.0]);
        for bad in [[(0, 1)], [(3, 0)]] {
            let e = SymmetricPattern::new(3, &bad).unwrap_err().to_string();
            assert!(e.contains("outside the lower triangle"), "{e}");
        }
    }

    #[test]
    fn a_custom_ordering_gives_the_same_solution_and_is_checked() {
        // A tridiagonal quasi-definite matrix: u rows 0..6, ϕ rows 6..9.
        let n = 9;
        let mut positions = Vec::new();
        let mut values = Vec::new();
        for i in 0..n {
            positions.push((i, i));
            values.push(if i < 6 { 4.0 } else { -3.0 });
            if i > 0 {
                positions.push((i, i - 1));
                values.push(1.0);
            }
        }
        let signs: Vec<i8> = (0..n).map(|i| if i < 6 { 1 } else { -1 }).collect();
        let pattern = SymmetricPattern::new(n, &positions).unwrap();
        let a = pattern.assemble(&values).unwrap().0;
        let b: Vec<f64> = (0..n).map(|i| (i as f64).cos()).collect();
        let solve = |ordering: &Ordering| {
            let mut solver = LdltSolver::new();
            solver.analyze(&pattern, &signs, ordering).unwrap();
            solver.factorize(&a).unwrap();
            let mut x = b.clone();
            solver.solve_in_place(&mut x).unwrap();
            x
        };
        let (amd, last) =
            (solve(&Ordering::Amd), solve(&Ordering::Custom(vec![8, 0, 7, 1, 6, 2, 5, 3, 4])));
        let r = a.mul(&last);
        for i in 0..n {
            assert!((amd[i] - last[i]).abs() < 1e-13, "{i}");
            assert!((r[i] - b[i]).abs() < 1e-13, "{i}");
        }
        for bad in [vec![0, 1, 2], vec![0, 0, 1, 2, 3, 4, 5, 6, 7]] {
            let e = LdltSolver::new().analyze(&pattern, &signs, &Ordering::Custom(bad));
            assert!(e.is_err());
        }
    }
}
