//! Dense square matrices, for the condensed contact problem (model §11).

use super::vectors::{check_length, column, parallelism};
use crate::error::{Error, Result};
use std::sync::OnceLock;

/// A dense square matrix, for the condensed contact problem.
#[derive(Clone, Debug)]
pub struct DenseMatrix {
    pub(super) mat: faer::Mat<f64>,
}

impl DenseMatrix {
    /// The n × n zero matrix.
    pub fn zeros(n: usize) -> Self {
        Self { mat: matrix_on_threads(n, n, |_, _| 0.0) }
    }

    /// Order of the matrix.
    pub fn n(&self) -> usize {
        self.mat.nrows()
    }

    /// Entry (i, j).
    pub fn get(&self, i: usize, j: usize) -> f64 {
        self.mat[(i, j)]
    }

    /// Sets entry (i, j).
    pub fn set(&mut self, i: usize, j: usize, value: f64) {
        self.mat[(i, j)] = value;
    }

    /// Column j.
    pub fn col(&self, j: usize) -> &[f64] {
        self.mat.col(j).try_as_col_major().map(|c| c.as_slice()).unwrap_or(&[])
    }

    /// Column j, to write.
    pub fn col_mut(&mut self, j: usize) -> &mut [f64] {
        self.mat.col_mut(j).try_as_col_major_mut().map(|c| c.as_slice_mut()).unwrap_or(&mut [])
    }

    /// y = A x, by faer's matrix-vector product with the run's split of the work (the same
    /// bits on any number of threads, as [`super::parallelism`] says).
    pub fn mul(&self, x: &[f64]) -> Vec<f64> {
        product(self.mat.as_ref(), x)
    }

    /// Writes column j with `fill(j, column)` for every j, the columns in parallel (each by
    /// one call, so the bits do not depend on the threads), and returns what the calls
    /// returned, in column order.
    pub fn fill_columns<T: Send>(
        &mut self,
        fill: impl Fn(usize, &mut [f64]) -> T + Sync,
    ) -> Vec<T> {
        use rayon::prelude::*;
        self.mat
            .par_col_iter_mut()
            .enumerate()
            .map(|(j, column)| {
                let column = column.try_as_col_major_mut().map(|c| c.as_slice_mut());
                fill(j, column.unwrap_or(&mut []))
            })
            .collect()
    }

    /// A ← (A + Aᵀ)/2.
    pub fn symmetrize(&mut self) {
        for_upper_pairs(self.n(), |i, j| {
            let mean = 0.5 * (self.mat[(i, j)] + self.mat[(j, i)]);
            self.mat[(i, j)] = mean;
            self.mat[(j, i)] = mean;
        });
    }

    /// The upper half ← the lower half (a product that wrote the lower half alone).
    pub fn mirror_lower(&mut self) {
        for_upper_pairs(self.n(), |i, j| self.mat[(i, j)] = self.mat[(j, i)]);
    }

    /// A⁻¹ by LU with partial pivoting; an error when an entry of it is not finite (A
    /// singular).
    pub fn inverse(&self) -> Result<DenseMatrix> {
        use faer::linalg::solvers::DenseSolveCore;
        parallelism(); // faer's LU reads its global parallelism: the run's split.
        let inverse = self.mat.partial_piv_lu().inverse();
        for j in 0..self.n() {
            if let Some(i) = (0..self.n()).find(|&i| !inverse[(i, j)].is_finite()) {
                return Err(Error::SingularSystem {
                    detail: format!(
                        "a condensed matrix is singular (entry {i}, {j} of its inverse)"
                    ),
                });
            }
        }
        Ok(Self { mat: inverse })
    }

    /// The factors to solve Aᵀ x = b with, again and again ([`TransposedLu`]): the LU factors
    /// (partial pivoting) of A in single precision, kept with A.
    pub fn lu_transposed(self) -> TransposedLu {
        parallelism(); // As in `inverse`.
        let n = self.n();
        let single = matrix_on_threads(n, n, |i, j| self.mat[(i, j)] as f32);
        // The LU of A, whose transposed solves solve Aᵀ x = b.
        TransposedLu { single: PackedLu::new(single), matrix: self, double: OnceLock::new() }
    }
}

/// The m × n matrix of entries `entry(i, j)`, its columns written by the run's threads:
/// faer's `Mat::zeros` and `Mat::from_fn` write from one thread, and the first write to a
/// fresh block of hundreds of megabytes (a Schur complement of 5,295 unknowns is 224 MB) is
/// the kernel's page faults, which two threads make in about half the time of one.
pub(super) fn matrix_on_threads<T: Send + Sync>(
    m: usize,
    n: usize,
    entry: impl Fn(usize, usize) -> T + Sync,
) -> faer::Mat<T> {
    use rayon::prelude::*;
    /// The matrix's storage, shared by the tasks that write its columns.
    struct Storage<T>(*mut T);
    // SAFETY: the tasks write disjoint columns of the storage, which outlives them.
    unsafe impl<T> Sync for Storage<T> {}
    let mut mat = faer::Mat::<T>::with_capacity(m, n);
    let (stride, storage) = (mat.col_stride() as usize, Storage(mat.as_ptr_mut()));
    (0..n).into_par_iter().for_each(|j| {
        let storage = &storage;
        // SAFETY: the capacity holds n columns of `stride` ≥ m entries; task j writes the first
        // m of column j alone, through the raw pointer (nothing reads them before they are set).
        (0..m).for_each(|i| unsafe { storage.0.add(j * stride + i).write(entry(i, j)) });
    });
    // SAFETY: the capacity is at least m × n, and every entry within it was written above.
    unsafe { mat.set_dims(m, n) };
    mat
}

/// Refinements of a solve with single-precision factors, at most.
const MAX_REFINEMENTS: usize = 10;
/// A correction at most this fraction of the solution leaves it at double precision.
const REFINED: f64 = 4.0 * f64::EPSILON;
/// When the corrections stop shrinking (by half at least), the solution stands if the last
/// one that shrank was at most this fraction of it — the error of a double-precision LU on
/// a matrix of condition 1e6 — else the double-precision factors solve instead.
const SETTLED: f64 = 1e-10;

/// Solves with the transpose of a [`DenseMatrix`] A (Newton's dense system, model §11) by the
/// LU factors of A in single precision, each solve refined in double precision to the
/// accuracy of a double-precision LU: single precision halves the factorisation's time, the refinements
/// cost a product with the matrix and a solve each. Where they stop short (a matrix too
/// ill-conditioned for single precision), the double-precision factors are made and solve.
#[derive(Debug)]
pub struct TransposedLu {
    single: PackedLu<f32>,
    /// A (the system is Aᵀ x = b), for the residuals of the refinements and the
    /// double-precision factors.
    matrix: DenseMatrix,
    double: OnceLock<PackedLu<f64>>,
}

impl TransposedLu {
    /// Order of the matrix.
    pub fn n(&self) -> usize {
        self.matrix.n()
    }

    /// Solves Aᵀ x = b; an error when x is not finite (A singular).
    pub fn solve(&self, b: &[f64]) -> Result<Vec<f64>> {
        check_length("right-hand side", self.n(), b.len())?;
        let x = self.refined(b).unwrap_or_else(|| self.by_double(b));
        if let Some(k) = x.iter().position(|v| !v.is_finite()) {
            return Err(Error::SingularSystem {
                detail: format!("the dense Newton system is singular (component {k})"),
            });
        }
        Ok(x)
    }

    /// x by the single-precision factors and refinements; `None` when they stop short of
    /// [`SETTLED`] or are not finite.
    fn refined(&self, b: &[f64]) -> Option<Vec<f64>> {
        let mut x = self.by_single(b)?;
        let mut last = max_norm(&x);
        for _ in 0..MAX_REFINEMENTS {
            let product = product(self.matrix.mat.transpose(), &x);
            let residual: Vec<f64> = b.iter().zip(&product).map(|(b, p)| b - p).collect();
            let correction = self.by_single(&residual)?;
            let (size, change) = (max_norm(&x), max_norm(&correction));
            if change > 0.5 * last {
                return (last <= SETTLED * size).then_some(x);
            }
            x.iter_mut().zip(&correction).for_each(|(x, d)| *x += d);
            if change <= REFINED * size {
                return Some(x);
            }
            last = change;
        }
        (last <= SETTLED * max_norm(&x)).then_some(x)
    }

    /// (Aᵀ)⁻¹ v by the single-precision factors, v scaled to its largest entry so that no
    /// residual underflows; `None` when not finite.
    fn by_single(&self, v: &[f64]) -> Option<Vec<f64>> {
        let scale = max_norm(v);
        if scale == 0.0 {
            return Some(vec![0.0; v.len()]);
        }
        let mut single: Vec<f32> = v.iter().map(|e| (e / scale) as f32).collect();
        self.single.solve_transposed(&mut single);
        let x: Vec<f64> = single.iter().map(|&e| f64::from(e) * scale).collect();
        x.iter().all(|e| e.is_finite()).then_some(x)
    }

    /// (Aᵀ)⁻¹ b by double-precision factors of A, made at the first call.
    fn by_double(&self, b: &[f64]) -> Vec<f64> {
        let lu = self.double.get_or_init(|| PackedLu::new(self.matrix.mat.clone()));
        let mut x = b.to_vec();
        lu.solve_transposed(&mut x);
        x
    }
}

/// Calls `f(i, j)` for every i < j of an n × n matrix, by tiles of 64 × 64: a walk that reads
/// (j, i) beside (i, j) reads the lower half's rows, strided in column-major storage, within
/// a tile that stays in cache.
fn for_upper_pairs(n: usize, mut f: impl FnMut(usize, usize)) {
    const TILE: usize = 64;
    for column_tile in (0..n).step_by(TILE) {
        for row_tile in (0..=column_tile).step_by(TILE) {
            for j in column_tile..(column_tile + TILE).min(n) {
                for i in row_tile..(row_tile + TILE).min(j) {
                    f(i, j);
                }
            }
        }
    }
}

/// The LU factors (partial pivoting) of a square matrix, packed in its own storage: L below
/// the diagonal (its unit diagonal implied), U on and above it; the triangular solves read
/// only their own halves. faer's `PartialPivLu` copies the matrix, factorises the copy and
/// splits it into L and a new U, each pass from one thread and two of them through fresh
/// pages (42 MB each for a single-precision system of 3,248 unknowns).
#[derive(Debug)]
struct PackedLu<T> {
    lu: faer::Mat<T>,
    /// The rows' permutation's inverse: row i of the solution is row `inverse[i]`.
    inverse: Vec<usize>,
}

impl<T: faer::traits::ComplexField> PackedLu<T> {
    /// Factorises `matrix` in place, on faer's global parallelism.
    fn new(mut matrix: faer::Mat<T>) -> Self {
        use faer::dyn_stack::{MemBuffer, MemStack};
        use faer::linalg::lu::partial_pivoting::factor;
        let (n, par) = (matrix.nrows(), parallelism());
        let (mut forward, mut inverse) = (vec![0; n], vec![0; n]);
        let scratch = factor::lu_in_place_scratch::<usize, T>(n, n, par, Default::default());
        let mut stack = MemBuffer::new(scratch);
        let stack = MemStack::new(&mut stack);
        factor::lu_in_place(
            matrix.as_mut(),
            &mut forward,
            &mut inverse,
            par,
            stack,
            Default::default(),
        );
        Self { lu: matrix, inverse }
    }

    /// Solves Aᵀ x = v in place: with Uᵀ, then Lᵀ, then the rows back to the order of A.
    fn solve_transposed(&self, v: &mut [T]) {
        use faer::linalg::triangular_solve as triangular;
        let (par, lu) = (parallelism(), self.lu.transpose());
        triangular::solve_lower_triangular_in_place(lu, column(v), par);
        triangular::solve_unit_upper_triangular_in_place(lu, column(v), par);
        let permuted: Vec<T> = self.inverse.iter().map(|&k| v[k].clone()).collect();
        v.clone_from_slice(&permuted);
    }
}

/// The largest |v_i| (the max norm; 0 for no entries).
pub fn max_norm(v: &[f64]) -> f64 {
    v.iter().fold(0.0_f64, |a, e| a.max(e.abs()))
}

/// The largest |a_i − b_i| over the entries both have (the max norm of a − b).
pub fn max_distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).fold(0.0_f64, |d, (x, y)| d.max((x - y).abs()))
}

/// An orthonormal basis of the null space of the symmetric positive semidefinite n × n
/// matrix `a` (column-major): the eigenvectors whose eigenvalues are at most `tolerance` times
/// the largest (all of them for a zero matrix).
pub fn null_space(a: &[f64], n: usize, tolerance: f64) -> Result<Vec<Vec<f64>>> {
    check_length("the matrix of a null space", n * n, a.len())?;
    let (values, vectors) = symmetric_eigen(a, n)?;
    let largest = values.iter().copied().fold(0.0_f64, f64::max);
    Ok((0..n).filter(|&k| values[k] <= tolerance * largest).map(|k| vectors[k].clone()).collect())
}

/// The eigenvalues of the symmetric n × n matrix `a` (column-major, its lower triangle read),
/// ascending, and their orthonormal eigenvectors.
pub fn symmetric_eigen(a: &[f64], n: usize) -> Result<(Vec<f64>, Vec<Vec<f64>>)> {
    check_length("a symmetric matrix", n * n, a.len())?;
    let matrix = faer::MatRef::from_column_major_slice(a, n, n);
    let eigen = matrix
        .self_adjoint_eigen(faer::Side::Lower)
        .map_err(|e| Error::LinearAlgebra(format!("a symmetric eigendecomposition: {e:?}")))?;
    let values = eigen.S().column_vector();
    let vectors = eigen.U();
    Ok((
        (0..n).map(|k| values[k]).collect(),
        (0..n).map(|k| (0..n).map(|i| vectors[(i, k)]).collect()).collect(),
    ))
}

/// y = A x, as [`DenseMatrix::mul`] says.
fn product(a: faer::MatRef<'_, f64>, x: &[f64]) -> Vec<f64> {
    let n = a.nrows();
    let mut y = vec![0.0; n];
    faer::linalg::matmul::matmul(
        column(&mut y),
        faer::Accum::Replace,
        a,
        faer::MatRef::from_column_major_slice(x, n, 1),
        1.0,
        parallelism(),
    );
    y
}

#[cfg(test)]
mod tests {
    use super::*;

    /// (Aᵀ)⁻¹ b by faer's double-precision LU of A alone, made apart from the code tested.
    fn by_double_alone(a: &DenseMatrix, b: &[f64]) -> Vec<f64> {
        use faer::linalg::solvers::Solve;
        let mut x = b.to_vec();
        let lu = a.mat.partial_piv_lu();
        lu.solve_transpose_in_place(column(&mut x));
        x
    }

    /// A with entries `entry(i, j)`, and b = Aᵀ x for x_k = 1 + k/n.
    fn system(n: usize, entry: impl Fn(usize, usize) -> f64) -> (DenseMatrix, Vec<f64>, Vec<f64>) {
        let mut a = DenseMatrix::zeros(n);
        (0..n).for_each(|j| (0..n).for_each(|i| a.set(i, j, entry(i, j))));
        let x: Vec<f64> = (0..n).map(|k| 1.0 + k as f64 / n as f64).collect();
        let b = (0..n).map(|i| (0..n).map(|k| a.get(k, i) * x[k]).sum()).collect();
        (a, x, b)
    }

    fn relative_error(x: &[f64], exact: &[f64]) -> f64 {
        max_distance(x, exact) / max_norm(exact)
    }

    /// A nonsymmetric matrix of condition about 1e4 (rows scaled over four decades): the
    /// refinements bring the single-precision solve (alone, errors above 1e−9) to the
    /// accuracy of a double-precision LU, without the double-precision factors.
    #[test]
    fn a_refined_single_precision_solve_has_double_precision() {
        let n = 200;
        let (a, x, b) = system(n, |i, j| {
            let scale = 10f64.powf(4.0 * i as f64 / n as f64);
            scale * (if i == j { 4.0 } else { ((3 * i + 7 * j) % 11) as f64 / 11.0 - 0.5 } / 8.0)
        });
        let lu = a.clone().lu_transposed();
        let solved = lu.solve(&b).unwrap();
        let single = lu.by_single(&b).unwrap();
        assert!(relative_error(&single, &x) > 1e-9, "{}", relative_error(&single, &x));
        let (refined, double) =
            (relative_error(&solved, &x), relative_error(&by_double_alone(&a, &b), &x));
        assert!(refined < 1e-12 && refined < 4.0 * double, "{refined:e} against {double:e}");
        assert!(lu.double.get().is_none());
    }

    /// The Hilbert matrix of order 10 (condition 1.6e13) is beyond single precision: the
    /// solve is the double-precision LU's, bit for bit; and a matrix of entries below single
    /// precision's range (1e−42 times a well-conditioned one) is solved by it too.
    #[test]
    fn what_single_precision_cannot_solve_the_double_precision_factors_do() {
        let (hilbert, _, b) = system(10, |i, j| 1.0 / (i + j + 1) as f64);
        let by_double = by_double_alone(&hilbert, &b);
        let lu = hilbert.clone().lu_transposed();
        assert_eq!(lu.solve(&b).unwrap(), by_double);
        assert!(lu.double.get().is_some());
        let (tiny, x, b) = system(50, |i, j| 1e-42 * if i == j { 3.0 } else { 1.0 / 50.0 });
        let lu = tiny.lu_transposed();
        assert!(relative_error(&lu.solve(&b).unwrap(), &x) < 1e-14);
        assert!(lu.double.get().is_some());
    }

    /// Every entry of the matrices written by the threads is the one asked for, in shapes
    /// whose columns are padded (3 rows) or not, empty or one column: the heap is first
    /// filled with NaN of the same size, so an entry left unwritten would likely read NaN.
    #[test]
    fn matrix_on_threads_writes_every_entry() {
        let entry = |i: usize, j: usize| (1000 * j + i) as f64;
        for (m, n) in [(0, 0), (1, 1), (3, 5), (67, 2), (130, 130), (2, 0)] {
            drop(vec![f64::NAN; (m + 8) * n]);
            let double = matrix_on_threads(m, n, entry);
            assert_eq!((double.nrows(), double.ncols()), (m, n));
            assert!((0..n).all(|j| (0..m).all(|i| double[(i, j)] == entry(i, j))), "{m} × {n}");
            drop(vec![f32::NAN; (m + 16) * n]);
            let single = matrix_on_threads(m, n, |i, j| entry(i, j) as f32);
            let same = |i, j| single[(i, j)] == entry(i, j) as f32;
            assert!((0..n).all(|j| (0..m).all(|i| same(i, j))), "{m} × {n}");
        }
    }

    /// NaN above the diagonal: an entry not taken from the lower half shows. Orders of one
    /// tile, of one tile and one entry short, and of several with a partial last.
    #[test]
    fn the_halves_are_mirrored_and_averaged_across_whole_and_partial_tiles() {
        for n in [1, 63, 64, 150] {
            let lower = |i: usize, j: usize| (1000 * i.max(j) + i.min(j)) as f64;
            let (mut mirrored, _, _) =
                system(n, |i, j| if i >= j { lower(i, j) } else { f64::NAN });
            mirrored.mirror_lower();
            let (mut averaged, _, _) = system(n, |i, j| lower(i, j) + (i as f64 - j as f64));
            averaged.symmetrize();
            for (i, j) in (0..n).flat_map(|i| (0..n).map(move |j| (i, j))) {
                assert_eq!(mirrored.get(i, j), lower(i, j), "({i}, {j}) of {n}");
                assert_eq!(averaged.get(i, j), lower(i, j), "({i}, {j}) of {n}");
            }
        }
    }

    /// A singular matrix is told, by name, not solved into non-finite numbers.
    #[test]
    fn a_singular_newton_system_is_an_error() {
        let (singular, _, b) = system(4, |i, _| i as f64);
        let error = singular.lu_transposed().solve(&b).unwrap_err().to_string();
        assert!(error.contains("dense Newton system is singular"), "{error}");
    }
}
