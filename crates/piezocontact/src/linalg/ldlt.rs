//! [`LdltSolver`]: faer's sparse LDLᵀ (supernodal or simplicial as faer chooses) behind the
//! [`LinearSolver`] seam, with the [`SchurComplement`] capability read off the factor's
//! trailing block.

use super::dense::{DenseMatrix, matrix_on_threads};
use super::ordering;
use super::seam::{LinearSolver, Ordering, SchurComplement, SolverStats};
use super::sparse::{SymmetricMatrix, SymmetricPattern, symbolic_cholesky};
use super::vectors::{check_length, column, column_count, parallelism};
use crate::error::{Error, Result};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::ldlt::factor::LdltRegularization;
use faer::linalg::matmul::triangular::{self, BlockStructure};
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::supernodal::SupernodalLdltRef;
use faer::sparse::linalg::cholesky::{
    LdltRef, SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat, SymbolicSparseColMatRef};
use faer::{Accum, Conj, MatMut, Par, Side};
use rayon::iter::ParallelExtend;
use std::time::Instant;

/// Pivots below this (after diagonal scaling) count as zero.
const PIVOT_THRESHOLD: f64 = 1e-12;
/// faer replaces a tiny or wrongly signed pivot by ±this marker, which no pivot of a scaled
/// matrix can reach; finding it in the factor reports the failure.
const PIVOT_MARKER: f64 = 1e300;

/// Sparse LDLᵀ of a symmetric quasi-definite matrix (faer's supernodal or simplicial LDLᵀ).
#[derive(Debug, Default)]
pub struct LdltSolver {
    symbolic: Option<SymbolicCholesky<usize>>,
    /// The analysed pattern with faer's `usize` indices, which its factorisation of a matrix
    /// of that pattern takes (the stored pattern's indices are 32 bits).
    wide: Option<SymbolicSparseColMat<usize>>,
    /// +1 for u rows, −1 for ϕ rows.
    signs: Vec<i8>,
    /// S = diag(|a_ii|^{-1/2}) of the last factorised matrix.
    scaling: Vec<f64>,
    l_values: Vec<f64>,
    factorized: bool,
    stats: SolverStats,
    /// The ordering of the next analysis.
    ordering: Ordering,
    /// The threads of the numeric factorisation and the solves; `None`: the run's
    /// [`super::parallelism`] on a 3D pattern, and for the numeric factorisation of a 2D
    /// pattern with a trailing block kept; one thread on others ([`LdltSolver::par`]).
    threads: Option<usize>,
    /// Whether the analysed pattern is a 3D mesh's ([`ordering::three_dimensional`]).
    three_dimensional: bool,
    /// The number of trailing unknowns kept for the Schur complement (0: none).
    last: usize,
}

impl LdltSolver {
    /// A solver with the [`Ordering::Auto`] choice, on the run's [`super::parallelism`] for a
    /// 3D mesh (on one thread for a 2D mesh's thin supernodes), with nothing analysed yet.
    pub fn new() -> Self {
        Self::with_ordering(Ordering::Auto)
    }

    /// A solver whose analyses use `ordering` (a [`Ordering::Custom`] must be a permutation
    /// of the unknowns of the pattern it analyses).
    pub fn with_ordering(ordering: Ordering) -> Self {
        Self { ordering, ..Self::default() }
    }

    /// The same solver on `threads` threads (at least 1).
    pub fn on_threads(self, threads: usize) -> Self {
        Self { threads: Some(threads.max(1)), ..self }
    }

    /// faer's parallelism of the solves with the solver's threads. A 2D mesh's supernodes
    /// are thin: its solves run on one thread (two took 0.079–0.090 s against 0.072–0.077 s
    /// on the paper's bar at 768 × 128, AMD).
    fn par(&self) -> Par {
        match self.threads {
            Some(threads) if threads > 1 => Par::rayon(threads),
            None if self.three_dimensional => parallelism(),
            _ => Par::Seq,
        }
    }

    /// faer's parallelism of the numeric factorisation: as the solves', but on every thread
    /// also for a 2D pattern whose trailing unknowns are kept for a Schur complement, whose
    /// last supernode is then dense and wide (the exact solver on the paper's bar at 768 × 128:
    /// 0.79–0.87 s on two threads against 0.96–0.97 s on one; without a trailing block 0.68–0.74
    /// against 0.73–0.87 s, within the spread of runs).
    fn numeric_par(&self) -> Par {
        match self.threads {
            None if self.last > 0 => parallelism(),
            _ => self.par(),
        }
    }

    /// The entries of D (supernodal: the diagonals of the supernodes' blocks), or every
    /// stored value of a simplicial factor (small matrices), for the pivot checks: a bad
    /// pivot, a NaN or an infinity anywhere in the matrix reaches D.
    fn pivots(&self) -> Box<dyn Iterator<Item = f64> + '_> {
        match self.symbolic.as_ref().map(|s| s.raw()) {
            Some(SymbolicCholeskyRaw::Supernodal(symbolic)) => {
                let factor = SupernodalLdltRef::new(symbolic, &self.l_values);
                Box::new((0..symbolic.n_supernodes()).flat_map(move |s| {
                    let block = factor.supernode(s).val();
                    (0..block.ncols()).map(move |k| block[(k, k)])
                }))
            }
            _ => Box::new(self.l_values.iter().copied()),
        }
    }

    fn symbolic(&self) -> Result<&SymbolicCholesky<usize>> {
        self.symbolic.as_ref().ok_or_else(unanalysed)
    }
}

/// Checks that `order` is a permutation of 0..n and returns it with its inverse.
fn permutation(order: &[usize], n: usize) -> Result<(Vec<usize>, Vec<usize>)> {
    let mut inverse = vec![usize::MAX; n];
    check_length("custom ordering", n, order.len())?;
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

impl LdltSolver {
    /// The symbolic analysis of `pattern` with the solver's ordering and the unknowns `last`
    /// kept last, then the check that the factor fits in memory, before any numeric work.
    /// The factor of the previous analysis is freed first: two are never held at once.
    fn analyze_ordered(
        &mut self,
        pattern: &SymmetricPattern,
        signs: &[i8],
        last: &[usize],
    ) -> Result<()> {
        let n = pattern.n();
        check_length("pivot signs", n, signs.len())?;
        let t = Instant::now();
        (self.symbolic, self.wide, self.l_values, self.factorized) =
            (None, None, Vec::new(), false);
        self.last = last.len();
        let wide = pattern.wide();
        let (symbolic, name) = self.ordered_symbolic(pattern, wide.as_ref(), last)?;
        self.three_dimensional = ordering::three_dimensional(pattern);
        let bytes = self.predicted_bytes(&symbolic, pattern);
        let what = format!(
            "the sparse LDLᵀ factor of {n} unknowns ({} entries, {name} ordering)",
            symbolic.len_val()
        );
        let fix = memory_fix(name);
        crate::limits::check_memory(bytes, crate::limits::available_memory(), &what, &fix)?;
        let mut l_values = Vec::new();
        l_values.try_reserve_exact(symbolic.len_val()).map_err(|_| {
            Error::Input(format!("{what}: the memory for it could not be had; {fix}"))
        })?;
        // Zeroed on the run's threads: the first touch of gigabytes is the kernel's page
        // faults, which two threads make in half the time of one (3.3 GB for the 215k-unknown
        // indentation: 2.2-2.6 s against 4.5-5.2 s, measured). The analysis's time includes
        // them; they were in no phase of the time line before.
        l_values.par_extend(rayon::iter::repeat_n(0.0, symbolic.len_val()));
        self.l_values = l_values;
        self.stats.symbolic_seconds += t.elapsed().as_secs_f64();
        self.symbolic = Some(symbolic);
        self.wide = Some(wide);
        self.signs = signs.to_vec();
        self.scaling = vec![1.0; n];
        self.stats.factor_len = self.l_values.len();
        self.stats.factor_bytes = bytes;
        self.stats.factor_flops = factor_flops(self.symbolic()?);
        self.stats.ordering = name;
        Ok(())
    }

    /// The symbolic analysis with the solver's ordering (for [`Ordering::Auto`], nested
    /// dissection where [`ordering::nested_pays`], else AMD), and the ordering's name. A factor
    /// whose trailing block is read (unknowns kept last) is supernodal.
    fn ordered_symbolic(
        &self,
        pattern: &SymmetricPattern,
        wide: SymbolicSparseColMatRef<'_, usize>,
        last: &[usize],
    ) -> Result<(SymbolicCholesky<usize>, &'static str)> {
        let n = pattern.n();
        let schur = !last.is_empty();
        let custom = |order: &[usize]| -> Result<SymbolicCholesky<usize>> {
            let (forward, inverse) = permutation(order, n)?;
            let perm = PermRef::new_checked(&forward, &inverse, n);
            symbolic_cholesky(wide, SymmetricOrdering::Custom(perm), schur)
        };
        let amd = || -> Result<SymbolicCholesky<usize>> {
            if schur {
                custom(&ordering::amd_with_last(wide, last)?)
            } else {
                symbolic_cholesky(wide, SymmetricOrdering::Amd, false)
            }
        };
        let nd = || custom(&ordering::nested_dissection(pattern, last)?);
        Ok(match &self.ordering {
            Ordering::Amd => (amd()?, "amd"),
            Ordering::NestedDissection => (nd()?, "nd"),
            Ordering::Custom(order) if !schur => (custom(order)?, "custom"),
            Ordering::Custom(_) => {
                return Err(Error::LinearAlgebra(
                    "a custom ordering cannot keep unknowns last for a Schur complement".into(),
                ));
            }
            Ordering::Auto if ordering::nested_pays(pattern) => (nd()?, "nd"),
            Ordering::Auto => (amd()?, "amd"),
        })
    }

    /// The bytes a numeric factorisation with `symbolic` needs: the factor, its workspace,
    /// the scaled copy of the matrix and the pattern with `usize` indices.
    fn predicted_bytes(
        &self,
        symbolic: &SymbolicCholesky<usize>,
        pattern: &SymmetricPattern,
    ) -> f64 {
        let scratch = symbolic
            .factorize_numeric_ldlt_scratch::<f64>(self.numeric_par(), Default::default())
            .size_bytes();
        8.0 * symbolic.len_val() as f64 + scratch as f64 + 24.0 * pattern.nnz() as f64
    }
}

/// The error of a factorisation before the symbolic analysis.
fn unanalysed() -> Error {
    Error::LinearAlgebra("factorisation before the symbolic analysis".into())
}

/// The analysed pattern with `usize` indices (the solver's `wide`), or the error of a
/// factorisation before the analysis.
fn analysed(
    wide: &Option<SymbolicSparseColMat<usize>>,
) -> Result<SymbolicSparseColMatRef<'_, usize>> {
    wide.as_ref().map(|w| w.as_ref()).ok_or_else(unanalysed)
}

/// The floating-point operations of a numeric factorisation with `symbolic`, counted per
/// supernode (per column of a simplicial factor) with c columns and r rows below them: the
/// LDLᵀ of its diagonal block (c³/3), the triangular solve of the rows below (c² r) and its
/// update of the later columns (c r²).
fn factor_flops(symbolic: &SymbolicCholesky<usize>) -> f64 {
    let flops = |c: f64, r: f64| c * c * c / 3.0 + c * c * r + c * r * r;
    match symbolic.raw() {
        SymbolicCholeskyRaw::Supernodal(s) => {
            let (begin, end) = (s.supernode_begin(), s.supernode_end());
            (0..s.n_supernodes())
                .map(|k| flops((end[k] - begin[k]) as f64, s.supernode(k).pattern().len() as f64))
                .sum()
        }
        SymbolicCholeskyRaw::Simplicial(s) => {
            s.col_ptr().windows(2).map(|w| flops(1.0, (w[1] - w[0]) as f64 - 1.0)).sum()
        }
    }
}

/// The ways out of a factor of the ordering `name` too large for this machine.
fn memory_fix(name: &str) -> String {
    let nd = if name == "nd" { "" } else { "solver.ordering = \"nd\" (nested dissection), " };
    format!("use a coarser mesh, {nd}or a machine with more memory")
}

impl LinearSolver for LdltSolver {
    fn name(&self) -> &str {
        "ldlt"
    }

    fn analyze(&mut self, pattern: &SymmetricPattern, signs: &[i8]) -> Result<()> {
        self.analyze_ordered(pattern, signs, &[])
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
        // The field alone, not `self`: the factor's fields are written beside it.
        let symbolic = analysed(&self.wide)?;
        let (col_ptr, row_idx) = (symbolic.col_ptr(), symbolic.row_idx());
        let mut values = matrix.values().to_vec();
        for j in 0..matrix.n() {
            for k in col_ptr[j]..col_ptr[j + 1] {
                values[k] *= self.scaling[row_idx[k]] * self.scaling[j];
            }
        }
        let scaled = SparseColMatRef::new(symbolic, &values);
        let (params, par) = (Default::default(), self.numeric_par());
        let symbolic = self.symbolic.take().ok_or_else(unanalysed)?;
        let result = (|| {
            let mut mem =
                MemBuffer::try_new(symbolic.factorize_numeric_ldlt_scratch::<f64>(par, params))
                    .map_err(|_| {
                        Error::LinearAlgebra("out of memory for the LDLᵀ workspace".into())
                    })?;
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
                    scaled,
                    Side::Lower,
                    regularization,
                    par,
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
        if self.pivots().any(|v| !v.is_finite() || v.abs() >= PIVOT_MARKER) {
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
        check_length("right-hand side", n, rhs.len())?;
        self.solve_columns_in_place(rhs, n)
    }

    /// All columns in one blocked sweep of the factor each way.
    fn solve_columns_in_place(&mut self, rhs: &mut [f64], n: usize) -> Result<()> {
        if !self.factorized {
            return Err(Error::LinearAlgebra("solve before a successful factorisation".into()));
        }
        check_length("right-hand side column", self.signs.len(), n)?;
        let (t, k) = (Instant::now(), column_count(rhs.len(), n)?);
        let (symbolic, par) = (self.symbolic()?, self.par());
        let scale = |rhs: &mut [f64]| {
            let scaling = self.scaling.iter().cycle();
            rhs.iter_mut().zip(scaling).for_each(|(v, s)| *v *= s);
        };
        scale(rhs);
        let mut mem = MemBuffer::try_new(symbolic.solve_in_place_scratch::<f64>(k, par))
            .map_err(|_| Error::LinearAlgebra("out of memory for the solve workspace".into()))?;
        LdltRef::new(symbolic, &self.l_values).solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(rhs, n, k),
            par,
            MemStack::new(&mut mem),
        );
        scale(rhs);
        self.stats.solve_count += k;
        self.stats.solve_seconds += t.elapsed().as_secs_f64();
        Ok(())
    }

    fn stats(&self) -> SolverStats {
        self.stats
    }

    fn schur(&mut self) -> Option<&mut dyn SchurComplement> {
        Some(self)
    }
}

impl SchurComplement for LdltSolver {
    fn analyze_with_last(
        &mut self,
        pattern: &SymmetricPattern,
        signs: &[i8],
        last: &[usize],
    ) -> Result<()> {
        self.analyze_ordered(pattern, signs, last)
    }

    /// Reads L22 and D2 of the trailing block of P S A S Pᵀ = L D Lᵀ (S the diagonal scaling)
    /// and returns S⁻¹ L22 D2 L22ᵀ S⁻¹ on the trailing unknowns: one triangular product of
    /// the factors as read, (S⁻¹ L22) D2 and S⁻¹ L22, gives its lower half.
    fn schur_complement(&self) -> Result<DenseMatrix> {
        let (symbolic, m) = (self.symbolic()?, self.last);
        let n = self.signs.len();
        let (Some(perm), SymbolicCholeskyRaw::Supernodal(supernodal), true) =
            (symbolic.perm(), symbolic.raw(), self.factorized && m <= n)
        else {
            return Err(Error::LinearAlgebra(
                "a Schur complement needs a factorisation analysed with unknowns last".into(),
            ));
        };
        let first = n - m;
        let forward = perm.arrays().0;
        let unscale: Vec<f64> = (first..n).map(|p| 1.0 / self.scaling[forward[p]]).collect();
        let factor = SupernodalLdltRef::new(supernodal, &self.l_values);
        let [weighted, l22] = trailing_factors(factor, first, &unscale);
        // Both factors triangular: a third of a full product.
        let mut schur = matrix_on_threads(m, m, |_, _| 0.0);
        triangular::matmul(
            schur.as_mut(),
            BlockStructure::TriangularLower,
            Accum::Replace,
            weighted.as_ref(),
            BlockStructure::TriangularLower,
            l22.transpose(),
            BlockStructure::TriangularUpper,
            1.0,
            parallelism(),
        );
        let mut schur = DenseMatrix { mat: schur };
        schur.mirror_lower();
        Ok(schur)
    }
}

/// The trailing unknowns' block of a supernodal LDLᵀ factor, from unknown `first` on, with
/// its rows scaled by `unscale` (U): [U L22 D2, U L22], both lower triangular; the columns
/// are read on the run's threads, each from its supernode.
fn trailing_factors(
    factor: SupernodalLdltRef<'_, usize, f64>,
    first: usize,
    unscale: &[f64],
) -> [faer::Mat<f64>; 2] {
    use rayon::prelude::*;
    let m = unscale.len();
    let [mut weighted, mut l22] = [(); 2].map(|_| matrix_on_threads(m, m, |_, _| 0.0));
    let begin = factor.symbolic().supernode_begin();
    let columns = weighted.par_col_iter_mut().zip(l22.par_col_iter_mut()).enumerate();
    columns.for_each(|(c, (mut weighted, mut l22))| {
        let j = first + c;
        let node = factor.supernode(begin.partition_point(|&b| b <= j) - 1);
        let (start, block, pattern) = (node.start(), node.val(), node.pattern());
        let (width, end) = (block.ncols(), start + block.ncols());
        let d = block[(j - start, j - start)];
        let below = (j + 1..end).map(|i| (i, block[(i - start, j - start)]));
        let outside = pattern.iter().enumerate().map(|(q, &i)| (i, block[(width + q, j - start)]));
        for (i, l) in std::iter::once((j, 1.0)).chain(below).chain(outside) {
            let value = l * unscale[i - first];
            l22[i - first] = value;
            weighted[i - first] = value * d;
        }
    });
    [weighted, l22]
}

impl LdltSolver {
    /// The floor for benchmarks: faer's own numeric LDLᵀ and one solve of `matrix` with this
    /// solver's symbolic analysis and threads (no scaling, no checks), timed: (numeric,
    /// solve) seconds.
    pub fn bare_seconds(&self, matrix: &SymmetricMatrix, rhs: &[f64]) -> Result<[f64; 2]> {
        let (symbolic, par, params) = (self.symbolic()?, self.par(), Default::default());
        let mut l_values = vec![0.0; symbolic.len_val()];
        let t = Instant::now();
        let mut mem =
            MemBuffer::try_new(symbolic.factorize_numeric_ldlt_scratch::<f64>(par, params))
                .map_err(|_| Error::LinearAlgebra("out of memory for the LDLᵀ workspace".into()))?;
        symbolic
            .factorize_numeric_ldlt(
                &mut l_values,
                SparseColMatRef::new(analysed(&self.wide)?, matrix.values()),
                Side::Lower,
                LdltRegularization::default(),
                par,
                MemStack::new(&mut mem),
                params,
            )
            .map_err(|e| Error::SingularSystem { detail: format!("{e:?}") })?;
        let numeric = t.elapsed().as_secs_f64();
        let mut x = rhs.to_vec();
        let t = Instant::now();
        let mut mem = MemBuffer::try_new(symbolic.solve_in_place_scratch::<f64>(1, par))
            .map_err(|_| Error::LinearAlgebra("out of memory for the solve workspace".into()))?;
        LdltRef::new(symbolic, &l_values).solve_in_place_with_conj(
            Conj::No,
            column(&mut x),
            par,
            MemStack::new(&mut mem),
        );
        Ok([numeric, t.elapsed().as_secs_f64()])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::{max_distance, max_norm};

    /// The pattern of `positions` and the matrix with `values` summed at them.
    pub(super) fn build(
        n: usize,
        positions: &[(usize, usize)],
        values: &[f64],
    ) -> Result<(SymmetricPattern, SymmetricMatrix)> {
        let pattern = SymmetricPattern::from_positions(n, positions)?;
        if values.len() != positions.len() {
            return Err(Error::Length {
                what: "values".into(),
                expected: positions.len(),
                got: values.len(),
            });
        }
        let mut summed = vec![0.0; pattern.nnz()];
        for (&(r, c), v) in positions.iter().zip(values) {
            summed[pattern.position(r, c).unwrap()] += v;
        }
        let matrix = pattern.matrix(summed)?;
        Ok((pattern, matrix))
    }

    fn analyzed(pattern: &SymmetricPattern, signs: &[i8], ordering: &Ordering) -> LdltSolver {
        let mut solver = LdltSolver::with_ordering(ordering.clone());
        solver.analyze(pattern, signs).unwrap();
        solver
    }

    /// A small quasi-definite matrix [K G; Gᵀ −M] with K, M tridiagonal SPD.
    fn quasi_definite(
        n_u: usize,
        n_phi: usize,
        scale_phi: f64,
    ) -> (SymmetricPattern, SymmetricMatrix, Vec<i8>) {
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
        let (pattern, matrix) = build(n_u + n_phi, &positions, &values).unwrap();
        (pattern, matrix, signs)
    }

    /// The flop count of two factors whose work is known in closed form: a dense matrix of
    /// order n (one supernode, n³/3) and a tridiagonal one (each column: one row below, so
    /// 1/3 + 1 + 1; the last: 1/3).
    #[test]
    fn the_analysis_counts_the_flops_of_dense_and_tridiagonal_factors() {
        let n = 40;
        let dense: Vec<(usize, usize)> = (0..n).flat_map(|j| (j..n).map(move |i| (i, j))).collect();
        let tridiagonal: Vec<(usize, usize)> =
            (0..n).flat_map(|j| [(j, j), (j + 1, j)]).filter(|&(i, _)| i < n).collect();
        let nf = n as f64;
        let expected = [nf.powi(3) / 3.0, (nf - 1.0) * (1.0 / 3.0 + 2.0) + 1.0 / 3.0];
        for (positions, expected) in [dense, tridiagonal].iter().zip(expected) {
            let pattern = SymmetricPattern::from_positions(n, positions).unwrap();
            let solver = analyzed(&pattern, &vec![1; n], &Ordering::Amd);
            let flops = solver.stats.factor_flops;
            assert!((flops - expected).abs() <= 1e-9 * expected, "{flops} against {expected}");
        }
    }

    #[test]
    fn ldlt_solves_a_quasi_definite_system_that_cholesky_cannot() {
        for scale in [1.0, 1e-12] {
            let (pattern, a, signs) = quasi_definite(30, 12, scale);
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
                let err = max_distance(&b[range.clone()], &x[range.clone()]);
                let size = max_norm(&x[range]);
                assert!(err < 1e-12 * size, "scale {scale}, {block}: error {err} of {size}");
            }
        }
    }

    #[test]
    fn factorisation_is_reused_across_solves() {
        let (pattern, a, signs) = quasi_definite(20, 5, 1.0);
        let mut solver = analyzed(&pattern, &signs, &Ordering::Amd);
        solver.factorize(&a).unwrap();
        for k in 0..5 {
            let mut b = vec![k as f64; a.n()];
            solver.solve_in_place(&mut b).unwrap();
        }
        let stats = solver.stats();
        assert_eq!((stats.numeric_count, stats.solve_count), (1, 5));
    }

    /// Right-hand sides solved at once give what they give one by one (to round-off: the
    /// blocked sweeps sum in another order) and solve A x = b; each counts as a solve; a
    /// length that is no whole number of columns is an error.
    #[test]
    fn columns_solved_at_once_are_those_solved_one_by_one() {
        for (n_u, n_phi) in [(20, 5), (600, 200)] {
            let (pattern, a, signs) = quasi_definite(n_u, n_phi, 1.0);
            let mut solver = analyzed(&pattern, &signs, &Ordering::Amd);
            solver.factorize(&a).unwrap();
            let n = a.n();
            let b: Vec<f64> = (0..3 * n).map(|i| ((i * 7919) % 13) as f64 - 6.0).collect();
            let mut at_once = b.clone();
            solver.solve_columns_in_place(&mut at_once, n).unwrap();
            for (x, column) in at_once.chunks(n).zip(b.chunks(n)) {
                let mut one = column.to_vec();
                solver.solve_in_place(&mut one).unwrap();
                let (size, apart) = (max_norm(&one), max_distance(x, &one));
                assert!(apart <= 1e-13 * size, "{apart:e} of {size:e}");
                let ax = a.mul(x);
                let residual = max_distance(&ax, column);
                assert!(residual <= 1e-12 * 6.0, "residual {residual:e}");
            }
            assert_eq!(solver.stats().solve_count, 6);
            assert!(solver.solve_columns_in_place(&mut vec![0.0; n + 1], n).is_err());
            assert!(solver.solve_columns_in_place(&mut [], n).is_ok());
        }
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
        let (pattern, a) = build(n, &positions, &values).unwrap();
        let mut solver = analyzed(&pattern, &vec![1; n], &Ordering::Amd);
        let e = solver.factorize(&a).unwrap_err().to_string();
        assert!(e.contains("singular or not quasi-definite"), "{e}");
        assert!(solver.solve_in_place(&mut vec![0.0; n]).is_err());
        // A definite matrix declared with a ϕ row: the sign check catches it.
        let mut values = values.clone();
        values[0] = 2.0;
        let a = build(n, &positions, &values).unwrap().1;
        let mut signs = vec![1; n];
        signs[n - 1] = -1;
        let mut solver = analyzed(&pattern, &signs, &Ordering::Amd);
        assert!(solver.factorize(&a).is_err());
        let e = pattern.matrix(values[1..].to_vec()).unwrap_err().to_string();
        assert!(e.contains("expected length"), "{e}");
    }
}

#[cfg(test)]
mod seam_tests {
    use super::*;

    #[test]
    fn patterns_are_checked_and_positions_found() {
        let pattern =
            SymmetricPattern::from_positions(3, &[(0, 0), (2, 1), (0, 0), (2, 2)]).unwrap();
        assert_eq!((pattern.n(), pattern.nnz()), (3, 3));
        assert_eq!(
            [(0, 0), (2, 1), (2, 2), (1, 1), (1, 2), (0, 3)].map(|(r, c)| pattern.position(r, c)),
            [Some(0), Some(1), Some(2), None, None, None]
        );
        for bad in [[(0, 1)], [(3, 0)]] {
            let e = SymmetricPattern::from_positions(3, &bad).unwrap_err().to_string();
            assert!(e.contains("outside the lower triangle"), "{e}");
        }
        for (col_ptr, rows) in [(vec![0, 2, 2], vec![1, 0]), (vec![0, 1, 2], vec![0, 0])] {
            let e = SymmetricPattern::from_columns(2, col_ptr, rows).unwrap_err().to_string();
            assert!(e.contains("not increasing"), "{e}");
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
        let (pattern, a) = super::tests::build(n, &positions, &values).unwrap();
        let b: Vec<f64> = (0..n).map(|i| (i as f64).cos()).collect();
        let solve = |ordering: &Ordering| {
            let mut solver = LdltSolver::with_ordering(ordering.clone());
            solver.analyze(&pattern, &signs).unwrap();
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
            let e = LdltSolver::with_ordering(Ordering::Custom(bad)).analyze(&pattern, &signs);
            assert!(e.is_err());
        }
    }
}
