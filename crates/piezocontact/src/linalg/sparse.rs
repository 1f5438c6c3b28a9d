//! Sparse symmetric matrices by their lower triangle: the pattern, built once, into which the
//! assembly writes new values, and the matrices with it.

use super::vectors::{check_length, column};
use crate::error::{Error, Result};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, SymbolicCholesky, SymmetricOrdering, factorize_symbolic_cholesky,
};
use faer::sparse::{
    SparseColMat, SparseColMatRef, SymbolicSparseColMat, SymbolicSparseColMatRef, Triplet,
};
use faer::{Par, Side};
use std::sync::Arc;

/// The index of the stored patterns: 32 bits, half the memory of `usize` (the pattern of a
/// 3D mesh's matrix is about 30 entries per unknown); up to 2³² − 1 stored entries.
pub type PatternIndex = u32;

/// The lower-triangle sparsity pattern of a symmetric matrix.
#[derive(Debug)]
pub struct SymmetricPattern {
    /// Shared with every matrix made of it ([`SymmetricPattern::matrix`]).
    symbolic: Arc<SymbolicSparseColMat<PatternIndex>>,
    /// The group of each unknown (the mesh node it belongs to), for orderings that keep a
    /// group's unknowns together; `None`: each unknown its own group.
    groups: Option<Vec<usize>>,
}

impl SymmetricPattern {
    /// The pattern of an n × n matrix from its columns: the rows of column j are
    /// `row_idx[col_ptr[j]..col_ptr[j + 1]]`, strictly increasing, each ≥ j and < n. Refused
    /// when n or the entries are more than [`PatternIndex`] counts (checked before any row is
    /// read, so a caller may narrow rows below n to it unchecked).
    pub fn from_columns(n: usize, col_ptr: Vec<usize>, row_idx: Vec<PatternIndex>) -> Result<Self> {
        let bad = |what: String| Error::LinearAlgebra(format!("sparsity pattern: {what}"));
        if col_ptr.len() != n + 1 || col_ptr[0] != 0 || col_ptr[n] != row_idx.len() {
            return Err(bad(format!("{} column pointers for {n} columns", col_ptr.len())));
        }
        if PatternIndex::try_from(n.max(col_ptr[n])).is_err() {
            return Err(Error::Input(format!(
                "the matrix of {n} unknowns has {} stored entries, more than the {} its pattern's indices count; use a coarser mesh or several processes",
                col_ptr[n],
                PatternIndex::MAX
            )));
        }
        for j in 0..n {
            if col_ptr[j] > col_ptr[j + 1] {
                return Err(bad(format!("column {j} ends before it starts")));
            }
            let rows = &row_idx[col_ptr[j]..col_ptr[j + 1]];
            let outside = |&r: &PatternIndex| (r as usize) < j || r as usize >= n;
            if rows.iter().any(outside) || rows.windows(2).any(|w| w[0] >= w[1]) {
                return Err(bad(format!("the rows of column {j} are not increasing in {j}..{n}")));
            }
        }
        let col_ptr = col_ptr.into_iter().map(|k| k as PatternIndex).collect();
        let symbolic = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
        Ok(Self { symbolic: Arc::new(symbolic), groups: None })
    }

    /// The pattern of the (row, column) positions, row ≥ column, repetitions allowed.
    pub fn from_positions(n: usize, positions: &[(usize, usize)]) -> Result<Self> {
        if let Some(&(r, c)) = positions.iter().find(|&&(r, c)| r >= n || c > r) {
            return Err(Error::LinearAlgebra(format!(
                "position ({r}, {c}) is outside the lower triangle of a {n} × {n} matrix"
            )));
        }
        let mut columns = vec![Vec::new(); n];
        // Rows below n: narrowed unchecked, as from_columns refuses an n its indices miss.
        positions.iter().for_each(|&(r, c)| columns[c].push(r as PatternIndex));
        let mut col_ptr = vec![0];
        let mut row_idx = Vec::new();
        for mut rows in columns {
            rows.sort_unstable();
            rows.dedup();
            row_idx.extend(rows);
            col_ptr.push(row_idx.len());
        }
        Self::from_columns(n, col_ptr, row_idx)
    }

    /// Order of the matrix.
    pub fn n(&self) -> usize {
        self.symbolic.nrows()
    }

    /// The pattern with `groups[i]`, the group (mesh node) of unknown i.
    pub fn with_groups(self, groups: Vec<usize>) -> Result<Self> {
        check_length("unknown groups", self.n(), groups.len())?;
        Ok(Self { groups: Some(groups), ..self })
    }

    /// The group of unknown i.
    pub fn group(&self, i: usize) -> usize {
        self.groups.as_ref().map_or(i, |g| g[i])
    }

    /// faer's view, for the backends of this module.
    pub(super) fn symbolic(&self) -> SymbolicSparseColMatRef<'_, PatternIndex> {
        (*self.symbolic).as_ref()
    }

    /// The pattern with `usize` indices, for faer's factorisations (whose symbolic analysis
    /// takes the matrix's index type): a copy that a direct solver keeps beside its factor.
    pub(super) fn wide(&self) -> SymbolicSparseColMat<usize> {
        let widen = |v: &[PatternIndex]| v.iter().map(|&i| i as usize).collect();
        let (n, a) = (self.n(), &self.symbolic);
        SymbolicSparseColMat::new_checked(n, n, widen(a.col_ptr()), None, widen(a.row_idx()))
    }

    /// Stored entries of the lower triangle.
    pub fn nnz(&self) -> usize {
        self.symbolic.row_idx().len()
    }

    /// Column `col`'s stored rows (increasing, from the diagonal down) and the index of the
    /// first of them in the matrix's values.
    pub fn column(&self, col: usize) -> (usize, &[PatternIndex]) {
        let range = self.symbolic.col_range(col);
        (range.start, &self.symbolic.row_idx()[range])
    }

    /// The index of entry (row, column) in the matrix's values, if the pattern has it.
    pub fn position(&self, row: usize, col: usize) -> Option<usize> {
        if col >= self.n() {
            return None;
        }
        let range = self.symbolic.col_range(col);
        let rows = &self.symbolic.row_idx()[range.clone()];
        let row = PatternIndex::try_from(row).ok()?;
        rows.binary_search(&row).ok().map(|k| range.start + k)
    }

    /// The matrix with this pattern and `values` (one per stored entry, column by column).
    pub fn matrix(&self, values: Vec<f64>) -> Result<SymmetricMatrix> {
        check_length("matrix values", self.nnz(), values.len())?;
        Ok(SymmetricMatrix { symbolic: Arc::clone(&self.symbolic), values })
    }
}

/// A symmetric sparse matrix stored by its lower triangle.
#[derive(Clone, Debug)]
pub struct SymmetricMatrix {
    /// The lower triangle's pattern, shared with the [`SymmetricPattern`] it was made of.
    symbolic: Arc<SymbolicSparseColMat<PatternIndex>>,
    /// The lower triangle's values, column by column.
    values: Vec<f64>,
}

impl SymmetricMatrix {
    /// faer's matrix, for the backends of this module.
    pub(super) fn lower(&self) -> SparseColMatRef<'_, PatternIndex, f64> {
        SparseColMatRef::new((*self.symbolic).as_ref(), &self.values)
    }

    /// The lower triangle's values, column by column.
    pub(super) fn values(&self) -> &[f64] {
        &self.values
    }

    /// Whether `other` is a matrix of the same pattern (one made by the same
    /// [`SymmetricPattern`]).
    pub fn shares_pattern(&self, other: &SymmetricMatrix) -> bool {
        Arc::ptr_eq(&self.symbolic, &other.symbolic)
    }

    /// Its pattern (shared with it, without groups).
    pub fn pattern(&self) -> SymmetricPattern {
        SymmetricPattern { symbolic: Arc::clone(&self.symbolic), groups: None }
    }

    /// Order of the matrix.
    pub fn n(&self) -> usize {
        self.symbolic.nrows()
    }

    /// Lower-triangle entries (row, column, value) with row ≥ column.
    pub fn lower_entries(&self) -> impl Iterator<Item = (usize, usize, f64)> + '_ {
        let (symbolic, values) = ((*self.symbolic).as_ref(), &self.values[..]);
        (0..self.n()).flat_map(move |j| {
            let range = symbolic.col_range(j);
            symbolic.row_idx()[range.clone()]
                .iter()
                .zip(&values[range])
                .map(move |(&i, &v)| (i as usize, j, v))
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

    /// The diagonal (the first stored entry of each column, whose rows are sorted).
    pub fn diagonal(&self) -> Vec<f64> {
        let (symbolic, values) = ((*self.symbolic).as_ref(), &self.values[..]);
        (0..self.n())
            .map(|j| {
                let range = symbolic.col_range(j);
                if !range.is_empty() && symbolic.row_idx()[range.start] as usize == j {
                    values[range.start]
                } else {
                    0.0
                }
            })
            .collect()
    }

    /// The principal sub-matrix of rows and columns `range`, multiplied by `factor`.
    pub fn block(&self, range: std::ops::Range<usize>, factor: f64) -> Result<Self> {
        let index = |i: usize| (i - range.start) as PatternIndex;
        let triplets: Vec<Triplet<PatternIndex, PatternIndex, f64>> = self
            .lower_entries()
            .filter(|(i, j, _)| range.contains(i) && range.contains(j))
            .map(|(i, j, v)| Triplet::new(index(i), index(j), factor * v))
            .collect();
        let lower = SparseColMat::try_new_from_triplets(range.len(), range.len(), &triplets)
            .map_err(|e| Error::LinearAlgebra(format!("block: {e:?}")))?;
        let (symbolic, values) = lower.into_parts();
        Ok(Self { symbolic: Arc::new(symbolic), values })
    }

    /// Whether the matrix is positive definite (its sparse LLᵀ factorisation exists).
    pub fn is_positive_definite(&self) -> Result<bool> {
        let symbolic = symbolic_cholesky(self.lower().symbolic(), SymmetricOrdering::Amd, false)?;
        let mut l_values = vec![0.0; symbolic.len_val()];
        let mut mem = MemBuffer::try_new(
            symbolic.factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default()),
        )
        .map_err(|_| Error::LinearAlgebra("out of memory for the LLᵀ workspace".into()))?;
        let result = symbolic.factorize_numeric_llt(
            &mut l_values,
            self.lower(),
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
        lu.solve_in_place(column(&mut x));
        Ok([t_symbolic, t_numeric, t.elapsed().as_secs_f64()])
    }
}

pub(super) fn symbolic_cholesky<I: faer::Index>(
    pattern: faer::sparse::SymbolicSparseColMatRef<'_, I>,
    ordering: SymmetricOrdering<'_, I>,
    supernodal: bool,
) -> Result<SymbolicCholesky<I>> {
    let params = CholeskySymbolicParams {
        supernodal_flop_ratio_threshold: if supernodal {
            SupernodalThreshold::FORCE_SUPERNODAL
        } else {
            SupernodalThreshold::AUTO
        },
        ..Default::default()
    };
    factorize_symbolic_cholesky(pattern, Side::Lower, ordering, params)
        .map_err(|e| Error::LinearAlgebra(format!("symbolic analysis: {e:?}")))
}
