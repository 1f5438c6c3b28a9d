//! Sparse symmetric linear algebra: the only module that names faer.
//!
//! The matrix of Step 1 of Algorithms 2 and 4 ([P] Section 6) is symmetric quasi-definite,
//! `[K_uu G; Gᵀ −K_ϕϕ]` with K_uu and K_ϕϕ positive definite once the Dirichlet rows are
//! removed (SPEC §5). Such a matrix has an LDLᵀ factorisation for every symmetric ordering
//! without pivoting, with d_k > 0 on u rows and d_k < 0 on ϕ rows. We therefore use faer's
//! sparse LDLᵀ (supernodal or simplicial as faer chooses, AMD ordering) and not:
//! - LLᵀ (Cholesky), which fails on the indefinite matrix (pinned by a test below);
//! - LU, which ignores symmetry: on this matrix it takes several times the time and memory
//!   (`piezocontact bench` prints both).
//!
//! Work is split as the algorithms need it (SPEC §7):
//! - [`SymmetricPattern`]: the sparsity pattern, built once from the assembly's index list,
//!   with faer's argsort so that new values are placed without sorting again;
//! - [`LdltSolver::analyze`]: symbolic analysis, once per run;
//! - [`LdltSolver::factorize`]: numeric factorisation, whenever the values change;
//! - [`LdltSolver::solve_in_place`]: two triangular solves, as often as needed.
//!
//! The solver scales the matrix symmetrically by its diagonal, `S A S` with
//! `S = diag(|a_ii|^{-1/2})`, so that the u and ϕ blocks, whose entries differ by many orders
//! of magnitude and depend on the case's unit system (SPEC §9), meet on equal terms. A pivot
//! that is tiny (below 1e-12 after scaling) or has the wrong sign for a quasi-definite matrix
//! is reported as [`Error::SingularSystem`], never silently regularised.

use crate::error::{Error, Result};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::ldlt::factor::LdltRegularization;
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, LdltRef, SymbolicCholesky, SymmetricOrdering,
    factorize_symbolic_cholesky,
};
use faer::sparse::{Argsort, Pair, SparseColMat, SymbolicSparseColMat, Triplet};
use faer::{Conj, MatMut, Par, Side};

/// Pivots below this (after diagonal scaling) count as zero.
const PIVOT_THRESHOLD: f64 = 1e-12;
/// faer replaces a tiny or wrongly signed pivot by ±this marker, which no pivot of a scaled
/// matrix can reach; finding it in the factor reports the failure.
const PIVOT_MARKER: f64 = 1e300;

/// The lower-triangle sparsity pattern of a symmetric matrix and the permutation that sorts
/// an assembly's (row, column) list into it.
#[derive(Debug)]
pub struct SymmetricPattern {
    symbolic: SymbolicSparseColMat<usize>,
    argsort: Argsort<usize>,
    entries: usize,
}

impl SymmetricPattern {
    /// Builds the pattern of an n × n matrix from a list of (row, column) positions with
    /// row ≥ column, in the order in which an assembly produces its values (repetitions are
    /// summed).
    pub fn new(n: usize, positions: &[(usize, usize)]) -> Result<Self> {
        debug_assert!(positions.iter().all(|&(r, c)| r >= c && r < n));
        let pairs: Vec<Pair<usize, usize>> =
            positions.iter().map(|&(row, col)| Pair { row, col }).collect();
        let (symbolic, argsort) = SymbolicSparseColMat::try_new_from_indices(n, n, &pairs)
            .map_err(|e| Error::LinearAlgebra(format!("sparsity pattern: {e:?}")))?;
        Ok(Self { symbolic, argsort, entries: positions.len() })
    }

    /// Order of the matrix.
    pub fn n(&self) -> usize {
        self.symbolic.nrows()
    }

    /// Number of values an assembly produces (positions, repetitions included).
    pub fn entries(&self) -> usize {
        self.entries
    }

    /// Places `values` (in the order of the positions given to [`SymmetricPattern::new`])
    /// into a matrix with this pattern.
    pub fn matrix(&self, values: &[f64]) -> Result<SymmetricMatrix> {
        if values.len() != self.entries {
            return Err(Error::Length {
                what: "assembled values".into(),
                expected: self.entries,
                got: values.len(),
            });
        }
        let lower = SparseColMat::new_from_argsort(self.symbolic.clone(), &self.argsort, values)
            .map_err(|e| Error::LinearAlgebra(format!("refill: {e:?}")))?;
        Ok(SymmetricMatrix { lower })
    }
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
        let symbolic = symbolic_cholesky(&self.lower.symbolic().as_ref())?;
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
    pattern: &faer::sparse::SymbolicSparseColMatRef<'_, usize>,
) -> Result<SymbolicCholesky<usize>> {
    factorize_symbolic_cholesky(
        *pattern,
        Side::Lower,
        SymmetricOrdering::Amd,
        CholeskySymbolicParams::default(),
    )
    .map_err(|e| Error::LinearAlgebra(format!("symbolic analysis: {e:?}")))
}

/// Sparse LDLᵀ of a symmetric quasi-definite matrix: symbolic analysis once, numeric
/// factorisation when values change, solves in between.
#[derive(Debug)]
pub struct LdltSolver {
    symbolic: SymbolicCholesky<usize>,
    /// +1 for u rows, −1 for ϕ rows.
    signs: Vec<i8>,
    /// S = diag(|a_ii|^{-1/2}) of the last factorised matrix.
    scaling: Vec<f64>,
    l_values: Vec<f64>,
    factorized: bool,
    numeric_count: usize,
    solve_count: usize,
}

impl LdltSolver {
    /// Symbolic analysis (AMD ordering, elimination tree, supernodes) of `pattern`, whose
    /// rows have the expected pivot `signs` (+1 for u, −1 for ϕ).
    pub fn analyze(pattern: &SymmetricPattern, signs: Vec<i8>) -> Result<Self> {
        if signs.len() != pattern.n() {
            return Err(Error::Length {
                what: "pivot signs".into(),
                expected: pattern.n(),
                got: signs.len(),
            });
        }
        let symbolic = symbolic_cholesky(&pattern.symbolic.as_ref())?;
        let l_values = vec![0.0; symbolic.len_val()];
        Ok(Self {
            symbolic,
            scaling: vec![1.0; signs.len()],
            signs,
            l_values,
            factorized: false,
            numeric_count: 0,
            solve_count: 0,
        })
    }

    /// Numeric factorisation of `matrix`, which must have the analysed pattern.
    pub fn factorize(&mut self, matrix: &SymmetricMatrix) -> Result<()> {
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
            let (col_ptr, row_idx) = (symbolic.col_ptr().to_vec(), symbolic.row_idx().to_vec());
            let values = scaled.val_mut();
            for j in 0..matrix.n() {
                for k in col_ptr[j]..col_ptr[j + 1] {
                    values[k] *= self.scaling[row_idx[k]] * self.scaling[j];
                }
            }
        }
        let params = Default::default();
        let mut mem = MemBuffer::try_new(
            self.symbolic.factorize_numeric_ldlt_scratch::<f64>(Par::Seq, params),
        )
        .map_err(|_| Error::LinearAlgebra("out of memory for the LDLᵀ workspace".into()))?;
        // A tiny or wrongly signed pivot is replaced by the marker, which then shows in the
        // factor.
        let regularization = LdltRegularization {
            dynamic_regularization_signs: Some(&self.signs),
            dynamic_regularization_delta: PIVOT_MARKER,
            dynamic_regularization_epsilon: PIVOT_THRESHOLD,
        };
        self.symbolic
            .factorize_numeric_ldlt(
                &mut self.l_values,
                scaled.as_ref(),
                Side::Lower,
                regularization,
                Par::Seq,
                MemStack::new(&mut mem),
                params,
            )
            .map_err(|e| Error::SingularSystem { detail: format!("{e:?}") })?;
        self.numeric_count += 1;
        if self.l_values.iter().any(|v| !v.is_finite() || v.abs() >= PIVOT_MARKER) {
            return Err(Error::SingularSystem {
                detail: "a pivot was below 1e-12 after diagonal scaling, or had the wrong sign"
                    .into(),
            });
        }
        self.factorized = true;
        Ok(())
    }

    /// Solves A x = b in place (b on entry, x on exit) with the current factorisation.
    pub fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<()> {
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
        rhs.iter_mut().zip(&self.scaling).for_each(|(b, s)| *b *= s);
        let mut mem = MemBuffer::try_new(self.symbolic.solve_in_place_scratch::<f64>(1, Par::Seq))
            .map_err(|_| Error::LinearAlgebra("out of memory for the solve workspace".into()))?;
        LdltRef::new(&self.symbolic, &self.l_values).solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(rhs, n, 1),
            Par::Seq,
            MemStack::new(&mut mem),
        );
        rhs.iter_mut().zip(&self.scaling).for_each(|(x, s)| *x *= s);
        self.solve_count += 1;
        Ok(())
    }

    /// Number of numeric factorisations so far.
    pub fn numeric_factorizations(&self) -> usize {
        self.numeric_count
    }

    /// Number of solves so far.
    pub fn solves(&self) -> usize {
        self.solve_count
    }

    /// Number of stored values of the factor L (a measure of its memory).
    pub fn factor_len(&self) -> usize {
        self.l_values.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
            let a = pattern.matrix(&values).unwrap();
            assert!(!a.is_positive_definite().unwrap(), "LLᵀ must fail: the matrix is indefinite");
            let mut solver = LdltSolver::analyze(&pattern, signs).unwrap();
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
        let a = pattern.matrix(&values).unwrap();
        let mut solver = LdltSolver::analyze(&pattern, signs).unwrap();
        solver.factorize(&a).unwrap();
        for k in 0..5 {
            let mut b = vec![k as f64; a.n()];
            solver.solve_in_place(&mut b).unwrap();
        }
        assert_eq!((solver.numeric_factorizations(), solver.solves()), (1, 5));
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
        let a = pattern.matrix(&values).unwrap();
        let mut solver = LdltSolver::analyze(&pattern, vec![1; n]).unwrap();
        let e = solver.factorize(&a).map(|_| solver.factor_len()).unwrap_err().to_string();
        assert!(e.contains("singular or not quasi-definite"), "{e}");
        assert!(solver.solve_in_place(&mut vec![0.0; n]).is_err());
        // A definite matrix declared with a ϕ row: the sign check catches it.
        let mut values = values.clone();
        values[0] = 2.0;
        let a = pattern.matrix(&values).unwrap();
        let mut signs = vec![1; n];
        signs[n - 1] = -1;
        let mut solver = LdltSolver::analyze(&pattern, signs).unwrap();
        assert!(solver.factorize(&a).is_err());
        let e = pattern.matrix(&values[1..]).unwrap_err().to_string();
        assert!(e.contains("expected length"), "{e}");
    }
}
