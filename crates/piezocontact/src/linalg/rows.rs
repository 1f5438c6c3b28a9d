//! General (unsymmetric) sparse matrices stored by rows, with the full pattern of a symmetric
//! one: the Jacobian of the semismooth Newton method on the whole system (model §11), whose
//! Γ3 rows are the contact laws' combinations of the stiffness rows of their node, and its
//! direct solve by faer's sparse LU.

use super::sparse::{SymmetricMatrix, SymmetricPattern};
use super::vectors::{check_length, column};
use crate::error::{Error, Result};
use faer::linalg::solvers::SolveCore;
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};
use faer::{Conj, MatMut};
use std::sync::Arc;

/// The pattern of a [`RowMatrix`]: the columns of each row that has entries, increasing —
/// held as faer's compressed columns of the transpose (which its LU factorises, [`RowLu`]),
/// one column for each such row, so that a matrix of a few rows (a Newton step's patch)
/// holds no index of every row.
#[derive(Debug)]
struct RowPattern {
    /// The rows that have entries, increasing; `None`: every row, each at its own column.
    rows: Option<Vec<usize>>,
    transposed: SymbolicSparseColMat<usize>,
}

impl RowPattern {
    /// Row r's entries: their range in the columns and values.
    fn range(&self, r: usize) -> std::ops::Range<usize> {
        let at = match &self.rows {
            None => r,
            Some(rows) => match rows.binary_search(&r) {
                Ok(at) => at,
                Err(_) => return 0..0,
            },
        };
        self.transposed.col_range(at)
    }
}

/// A square sparse matrix stored row by row; matrices made from one another share the pattern.
#[derive(Clone, Debug)]
pub struct RowMatrix {
    pattern: Arc<RowPattern>,
    values: Vec<f64>,
}

impl RowMatrix {
    /// The whole matrix of `symmetric` (both triangles).
    pub fn from_symmetric(symmetric: &SymmetricMatrix) -> Self {
        Self::from_symmetric_rows(symmetric, |_| true)
    }

    /// The rows r of `symmetric` for which `keep(r)` (both triangles' entries), the others
    /// empty: the part of a matrix that a few rows' changes touch.
    pub fn from_symmetric_rows(symmetric: &SymmetricMatrix, keep: impl Fn(usize) -> bool) -> Self {
        let n = symmetric.n();
        let rows: Vec<usize> = (0..n).filter(|&r| keep(r)).collect();
        // The column of each kept row in the transpose (a row left out: NONE).
        const NONE: usize = usize::MAX;
        let mut slot = vec![NONE; n];
        rows.iter().enumerate().for_each(|(k, &r)| slot[r] = k);
        let column = |r: usize| Some(slot[r]).filter(|&k| k != NONE);
        let m = rows.len();
        let mut counts = vec![0usize; m + 1];
        for (i, j, _) in symmetric.lower_entries() {
            let mut count = |r: usize| {
                if let Some(k) = column(r) {
                    counts[k + 1] += 1;
                }
            };
            count(i);
            if i != j {
                count(j);
            }
        }
        (0..m).for_each(|k| counts[k + 1] += counts[k]);
        let starts = counts.clone();
        let mut next = counts;
        let mut columns = vec![0; starts[m]];
        let mut values = vec![0.0; starts[m]];
        // Column j of the lower triangle, in increasing j: row i ≥ j receives column j, and
        // row j receives columns i ≥ j after every column below j — each row in order.
        for (i, j, v) in symmetric.lower_entries() {
            let mut put = |row: usize, col: usize| {
                if let Some(k) = column(row) {
                    (columns[next[k]], values[next[k]]) = (col, v);
                    next[k] += 1;
                }
            };
            put(i, j);
            if i != j {
                put(j, i);
            }
        }
        let transposed = SymbolicSparseColMat::new_checked(n, m, starts, None, columns);
        let rows = (m < n).then_some(rows);
        Self { pattern: Arc::new(RowPattern { rows, transposed }), values }
    }

    /// `a − b` on the rows where two matrices of one pattern differ (both triangles' entries,
    /// a's pattern), the others empty (all of them where the matrices are equal).
    pub fn difference(a: &SymmetricMatrix, b: &SymmetricMatrix) -> Result<Self> {
        if !a.shares_pattern(b) {
            return Err(Error::LinearAlgebra("a difference of matrices of two patterns".into()));
        }
        let mut differs = vec![false; a.n()];
        for ((i, j, x), (_, _, y)) in a.lower_entries().zip(b.lower_entries()) {
            if x != y {
                (differs[i], differs[j]) = (true, true);
            }
        }
        let mut difference = Self::from_symmetric_rows(a, |r| differs[r]);
        let subtrahend = Self::from_symmetric_rows(b, |r| differs[r]);
        difference.values.iter_mut().zip(&subtrahend.values).for_each(|(x, y)| *x -= y);
        Ok(difference)
    }

    /// Order of the matrix.
    pub fn n(&self) -> usize {
        self.pattern.transposed.nrows()
    }

    /// Stored entries.
    pub fn nnz(&self) -> usize {
        self.values.len()
    }

    /// Whether `other` was made from this matrix, or this one from it (a clone): the same
    /// pattern, held once.
    pub fn shares_pattern(&self, other: &RowMatrix) -> bool {
        Arc::ptr_eq(&self.pattern, &other.pattern)
    }

    /// Whether row r has entries (a row left out of [`RowMatrix::from_symmetric_rows`] has
    /// none; a kept one has at least its diagonal).
    pub fn has_row(&self, r: usize) -> bool {
        !self.pattern.range(r).is_empty()
    }

    /// Row r: its columns (increasing) and values.
    pub fn row(&self, r: usize) -> (&[usize], &[f64]) {
        let range = self.pattern.range(r);
        (&self.pattern.transposed.row_idx()[range.clone()], &self.values[range])
    }

    /// Row r: its columns and values to change.
    pub fn row_mut(&mut self, r: usize) -> (&[usize], &mut [f64]) {
        let range = self.pattern.range(r);
        (&self.pattern.transposed.row_idx()[range.clone()], &mut self.values[range])
    }

    /// The index of column c within row r, if the pattern has the entry.
    pub fn position(&self, r: usize, c: usize) -> Option<usize> {
        self.row(r).0.binary_search(&c).ok()
    }

    /// Entry (r, r), 0 where the pattern lacks it.
    pub fn diagonal(&self, r: usize) -> f64 {
        self.position(r, r).map_or(0.0, |k| self.row(r).1[k])
    }

    /// A ← T A Tᵀ with T the identity but on the unknowns `positions`, where it is the
    /// orthogonal block `q` (`q[a][b]`: row a, column b, `positions.len()` of each): unknowns
    /// turned to another frame. Their rows must have the same columns (the components of a
    /// mesh node do), as must every row's entries in them; the rows that the matrix lacks
    /// ([`RowMatrix::from_symmetric_rows`]) are left out.
    pub fn turn(&mut self, positions: &[usize], q: &[[f64; 3]; 3]) -> Result<()> {
        let m = positions.len();
        let columns = self.row(positions[0]).0.to_vec();
        if positions.iter().any(|&p| self.row(p).0 != columns.as_slice()) {
            return Err(Error::LinearAlgebra(format!(
                "unknowns {positions:?}, turned together, have different sparsity patterns"
            )));
        }
        // Rows: row a ← Σ_b q[a][b] row b.
        let old: Vec<Vec<f64>> = positions.iter().map(|&p| self.row(p).1.to_vec()).collect();
        for (a, &p) in positions.iter().enumerate() {
            let (_, values) = self.row_mut(p);
            for (k, v) in values.iter_mut().enumerate() {
                *v = (0..m).map(|b| q[a][b] * old[b][k]).sum();
            }
        }
        // Columns: in each row that has them (the pattern is symmetric), the same.
        let rows: Vec<usize> = columns.into_iter().filter(|&r| self.has_row(r)).collect();
        for r in rows {
            let at: Vec<usize> = positions
                .iter()
                .map(|&p| self.position(r, p))
                .collect::<Option<_>>()
                .ok_or_else(|| {
                    Error::LinearAlgebra(format!("row {r} lacks some of the columns {positions:?}"))
                })?;
            let (_, values) = self.row_mut(r);
            let old: Vec<f64> = at.iter().map(|&k| values[k]).collect();
            for (a, &k) in at.iter().enumerate() {
                values[k] = (0..m).map(|b| q[a][b] * old[b]).sum();
            }
        }
        Ok(())
    }

    /// Makes unknown k's row and column zero but for `diagonal` on the diagonal; returns the
    /// column's entries it zeroed, (r, a_rk) for the rows r ≠ k the matrix has, in increasing
    /// r. A caller that fixes k's equation to x_k = v moves them to its right-hand side (b_r
    /// −= a_rk v, and b_k = `diagonal` · v), so that the other equations keep their solution.
    /// The pattern must be symmetric.
    pub fn eliminate(&mut self, k: usize, diagonal: f64) -> Vec<(usize, f64)> {
        let columns = self.row(k).0.to_vec();
        let mut zeroed = Vec::new();
        for r in columns.into_iter().filter(|&r| r != k) {
            if let Some(at) = self.position(r, k) {
                let (_, values) = self.row_mut(r);
                zeroed.push((r, values[at]));
                values[at] = 0.0;
            }
        }
        let at = self.position(k, k);
        let (_, values) = self.row_mut(k);
        values.iter_mut().for_each(|v| *v = 0.0);
        // A row without its diagonal (one left out, or a partial one: another process's) stays
        // zero.
        if let Some(at) = at {
            values[at] = diagonal;
        }
        zeroed
    }
}

/// The Jacobian J of a whole-system Newton step and the matrix P its preconditioner is set up
/// for, as changes of the factorised matrix K (the seam's numbering, the unknowns' frames):
/// each is K but on the rows its patch has ([`RowMatrix::has_row`]), which replace K's and
/// have their pattern; the two patches share one pattern (the same rows, the same columns).
/// No copy of K is made for them: a backend writes the patched rows over its own matrix, or
/// adds them to it ([`Patched::whole_jacobian`] with K).
#[derive(Clone, Copy, Debug)]
pub struct Patched<'a> {
    /// K's pattern.
    pattern: &'a SymmetricPattern,
    /// J's rows that differ from K's.
    jacobian: &'a RowMatrix,
    /// P's rows that differ from K's.
    preconditioner: &'a RowMatrix,
}

impl<'a> Patched<'a> {
    /// The patches of J and P over a matrix of `pattern`: they must share their pattern and
    /// have its order.
    pub fn new(
        pattern: &'a SymmetricPattern,
        jacobian: &'a RowMatrix,
        preconditioner: &'a RowMatrix,
    ) -> Result<Self> {
        check_length("Jacobian's patch order", pattern.n(), jacobian.n())?;
        if !jacobian.shares_pattern(preconditioner) {
            return Err(Error::LinearAlgebra(
                "the Jacobian's and the preconditioner's patches have different patterns".into(),
            ));
        }
        Ok(Self { pattern, jacobian, preconditioner })
    }

    /// K's pattern.
    pub fn pattern(&self) -> &'a SymmetricPattern {
        self.pattern
    }

    /// J's patch.
    pub fn jacobian(&self) -> &'a RowMatrix {
        self.jacobian
    }

    /// P's patch.
    pub fn preconditioner(&self) -> &'a RowMatrix {
        self.preconditioner
    }

    /// J whole, with K = `matrix` (of the pattern).
    pub fn whole_jacobian(&self, matrix: &SymmetricMatrix) -> Result<RowMatrix> {
        check_length("K's order", self.pattern.n(), matrix.n())?;
        let mut whole = RowMatrix::from_symmetric(matrix);
        for r in (0..whole.n()).filter(|&r| self.jacobian.has_row(r)) {
            let ((columns, values), patch) = (whole.row_mut(r), self.jacobian.row(r));
            if columns != patch.0 {
                let detail = format!("row {r} of the patch has another pattern than the matrix's");
                return Err(Error::LinearAlgebra(detail));
            }
            values.copy_from_slice(patch.1);
        }
        Ok(whole)
    }
}

/// faer's sparse LU of [`RowMatrix`]es of one pattern: the symbolic analysis once, a numeric
/// factorisation per matrix (a matrix made anew with the same pattern reuses the analysis).
#[derive(Debug, Default)]
pub struct RowLu {
    /// The pattern analysed and its analysis.
    symbolic: Option<(Arc<RowPattern>, SymbolicLu<usize>)>,
}

impl RowLu {
    /// Solves A x = b in place (b on entry, x on exit).
    pub fn solve(&mut self, a: &RowMatrix, rhs: &mut [f64]) -> Result<()> {
        check_length("right-hand side", a.n(), rhs.len())?;
        if a.pattern.rows.is_some() {
            let detail = "a sparse LU of a matrix with empty rows".into();
            return Err(Error::SingularSystem { detail });
        }
        // A's rows are the columns of Aᵀ: factorise Aᵀ, solve with its transpose.
        let transposed = a.pattern.transposed.as_ref();
        let same = |p: &RowPattern| {
            let (p, q) = (&p.transposed, &a.pattern.transposed);
            p.col_ptr() == q.col_ptr() && p.row_idx() == q.row_idx()
        };
        let analysed = self.symbolic.as_ref().is_some_and(|(p, _)| same(p));
        if !analysed {
            let symbolic = SymbolicLu::try_new(transposed)
                .map_err(|e| Error::LinearAlgebra(format!("sparse LU analysis: {e:?}")))?;
            self.symbolic = Some((a.pattern.clone(), symbolic));
        }
        let Some((_, symbolic)) = &self.symbolic else { unreachable!("analysed above") };
        let transposed = SparseColMatRef::new(transposed, &a.values);
        let lu = Lu::try_new_with_symbolic(symbolic.clone(), transposed)
            .map_err(|e| Error::SingularSystem { detail: format!("sparse LU: {e:?}") })?;
        let rhs_view: MatMut<'_, f64> = column(rhs);
        lu.solve_transpose_in_place_with_conj(Conj::No, rhs_view);
        if rhs.iter().all(|v| v.is_finite()) {
            Ok(())
        } else {
            Err(Error::SingularSystem { detail: "the sparse LU's solution is not finite".into() })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::DenseMatrix;
    use crate::linalg::SymmetricPattern;

    /// A symmetric 5 × 5 matrix with unknowns 1, 2 (a node's) coupled to 0, 3 and 4.
    fn symmetric() -> SymmetricMatrix {
        let entries = [
            (0, 0, 4.0),
            (1, 0, 1.0),
            (2, 0, -1.0),
            (1, 1, 5.0),
            (2, 1, 0.5),
            (3, 1, 1.5),
            (4, 1, -0.5),
            (2, 2, 6.0),
            (3, 2, 0.25),
            (4, 2, 2.0),
            (3, 3, 3.0),
            (4, 4, 7.0),
        ];
        let positions: Vec<(usize, usize)> = entries.iter().map(|&(r, c, _)| (r, c)).collect();
        let pattern = SymmetricPattern::from_positions(5, &positions).unwrap();
        let mut values = vec![0.0; pattern.nnz()];
        entries.iter().for_each(|&(r, c, v)| values[pattern.position(r, c).unwrap()] = v);
        pattern.matrix(values).unwrap()
    }

    /// The difference of two matrices of one pattern that differ in entry (4, 2) alone: rows
    /// 2 and 4 hold it (both triangles), the others are empty; matrices of two patterns are
    /// refused.
    #[test]
    fn the_difference_holds_the_rows_where_two_matrices_differ() {
        let s = symmetric();
        let pattern = s.pattern();
        let mut values: Vec<f64> = s.lower_entries().map(|(_, _, v)| v).collect();
        values[pattern.position(4, 2).unwrap()] += 0.75;
        let other = pattern.matrix(values).unwrap();
        let difference = RowMatrix::difference(&other, &s).unwrap();
        let rows: Vec<usize> = (0..5).filter(|&r| difference.has_row(r)).collect();
        assert_eq!(rows, vec![2, 4]);
        let d = dense(&difference);
        for (r, row) in d.iter().enumerate() {
            for (c, &v) in row.iter().enumerate() {
                let expected = if (r, c) == (4, 2) || (r, c) == (2, 4) { 0.75 } else { 0.0 };
                assert_eq!(v, expected, "({r}, {c})");
            }
        }
        assert!(RowMatrix::difference(&symmetric(), &s).is_err(), "two patterns");
    }

    fn dense(a: &RowMatrix) -> Vec<Vec<f64>> {
        let mut d = vec![vec![0.0; a.n()]; a.n()];
        for (r, row) in d.iter_mut().enumerate() {
            let (columns, values) = a.row(r);
            columns.iter().zip(values).for_each(|(&c, &v)| row[c] = v);
        }
        d
    }

    fn mul(a: &RowMatrix, x: &[f64]) -> Vec<f64> {
        let row = |r: usize| a.row(r).0.iter().zip(a.row(r).1).map(|(&c, v)| v * x[c]).sum();
        (0..a.n()).map(row).collect()
    }

    /// Both triangles, each row in order; A x as the symmetric matrix's.
    #[test]
    fn the_rows_are_the_whole_symmetric_matrix() {
        let s = symmetric();
        let a = RowMatrix::from_symmetric(&s);
        assert_eq!(a.nnz(), 2 * s.lower_entries().count() - 5);
        for r in 0..5 {
            assert!(a.row(r).0.windows(2).all(|w| w[0] < w[1]), "row {r} in order");
        }
        let d = dense(&a);
        (0..5).for_each(|r| (0..5).for_each(|c| assert_eq!(d[r][c], d[c][r])));
        let x = [1.0, -2.0, 0.5, 3.0, 0.25];
        assert_eq!(mul(&a, &x), s.mul(&x));
    }

    /// T A Tᵀ on unknowns 1, 2 turned by a rotation equals the dense product.
    #[test]
    fn turning_a_node_is_the_product_with_its_rotation() {
        let mut a = RowMatrix::from_symmetric(&symmetric());
        let before = dense(&a);
        let (c, s) = (0.6, 0.8);
        let q = [[c, s, 0.0], [-s, c, 0.0], [0.0; 3]];
        a.turn(&[1, 2], &q).unwrap();
        let mut t = vec![vec![0.0; 5]; 5];
        (0..5).for_each(|k| t[k][k] = 1.0);
        (t[1][1], t[1][2], t[2][1], t[2][2]) = (c, s, -s, c);
        let after = dense(&a);
        for r in 0..5 {
            for k in 0..5 {
                let expected: f64 = (0..5)
                    .flat_map(|i| (0..5).map(move |j| (i, j)))
                    .map(|(i, j)| t[r][i] * before[i][j] * t[k][j])
                    .sum();
                assert!((after[r][k] - expected).abs() < 1e-14, "({r}, {k})");
            }
        }
    }

    /// The LU solve of an unsymmetric matrix of the pattern, with one unknown eliminated,
    /// satisfies every equation, and the eliminated unknown has its value.
    #[test]
    fn the_sparse_lu_solves_an_unsymmetric_system_with_an_eliminated_unknown() {
        let mut a = RowMatrix::from_symmetric(&symmetric());
        let (_, values) = a.row_mut(1);
        values.iter_mut().enumerate().for_each(|(k, v)| *v += 0.3 * k as f64); // unsymmetric
        let original = a.clone();
        let b = vec![1.0, 2.0, -1.0, 0.5, 3.0];
        let mut rhs = b.clone();
        for (r, a_r3) in a.eliminate(3, 9.0) {
            rhs[r] -= a_r3 * 0.7;
        }
        rhs[3] = 9.0 * 0.7;
        let mut lu = RowLu::default();
        lu.solve(&a, &mut rhs).unwrap();
        assert!((rhs[3] - 0.7).abs() < 1e-14);
        let ax = mul(&original, &rhs);
        for r in (0..5).filter(|&r| r != 3) {
            assert!((ax[r] - b[r]).abs() < 1e-12, "row {r}: {} against {}", ax[r], b[r]);
        }
        // A second matrix of the pattern reuses the analysis and solves as the dense LU.
        let mut rhs = b.clone();
        lu.solve(&original, &mut rhs).unwrap();
        let mut d = DenseMatrix::zeros(5);
        for (r, row) in dense(&original).iter().enumerate() {
            d.col_mut(r).copy_from_slice(row); // the columns of the transposed LU are rows
        }
        let expected = d.lu_transposed().solve(&b).unwrap();
        rhs.iter().zip(&expected).for_each(|(x, e)| assert!((x - e).abs() < 1e-12));
    }

    /// Rows kept are the whole matrix's rows, the others empty (the pattern indexes the kept
    /// ones alone); a patch of kept rows makes
    /// the whole Jacobian with those rows replaced and every other row the symmetric
    /// matrix's.
    #[test]
    fn a_patch_of_some_rows_replaces_those_rows_alone() {
        let s = symmetric();
        let (whole, keep) = (RowMatrix::from_symmetric(&s), [false, true, true, false, false]);
        let mut patch = RowMatrix::from_symmetric_rows(&s, |r| keep[r]);
        for r in 0..5 {
            assert_eq!(patch.has_row(r), keep[r], "row {r}");
            if keep[r] {
                assert_eq!(patch.row(r), whole.row(r), "row {r}");
            }
        }
        assert_eq!(patch.pattern.rows.as_deref(), Some(&[1, 2][..]), "an index of its rows");
        assert_eq!((patch.n(), patch.pattern.transposed.ncols()), (5, 2));
        assert!(RowLu::default().solve(&patch, &mut [1.0; 5]).is_err(), "an LU of empty rows");
        patch.row_mut(2).1.iter_mut().for_each(|v| *v = -1.0);
        let pattern = s.pattern();
        let patched = Patched::new(&pattern, &patch, &patch).unwrap();
        let other = RowMatrix::from_symmetric_rows(&s, |r| keep[r]);
        assert!(Patched::new(&pattern, &patch, &other).is_err(), "patches of two patterns");
        let jacobian = dense(&patched.whole_jacobian(&s).unwrap());
        let original = dense(&whole);
        for r in 0..5 {
            for c in 0..5 {
                let expected = match (r, original[r][c]) {
                    (2, v) if v != 0.0 => -1.0,
                    (_, v) => v,
                };
                assert_eq!(jacobian[r][c], expected, "({r}, {c})");
            }
        }
    }
}
