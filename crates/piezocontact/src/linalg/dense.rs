//! Dense square matrices, for the condensed contact problem (model §11).

use super::check_length;
use crate::error::{Error, Result};
use faer::MatMut;

/// A dense square matrix, for the condensed contact problem.
#[derive(Clone, Debug)]
pub struct DenseMatrix {
    pub(super) mat: faer::Mat<f64>,
}

impl DenseMatrix {
    /// The n × n zero matrix.
    pub fn zeros(n: usize) -> Self {
        Self { mat: faer::Mat::zeros(n, n) }
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
        let n = self.n();
        let mut y = vec![0.0; n];
        faer::linalg::matmul::matmul(
            MatMut::from_column_major_slice_mut(&mut y, n, 1),
            faer::Accum::Replace,
            self.mat.as_ref(),
            faer::MatRef::from_column_major_slice(x, n, 1),
            1.0,
            super::parallelism(),
        );
        y
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
        for j in 0..self.n() {
            for i in 0..j {
                let mean = 0.5 * (self.mat[(i, j)] + self.mat[(j, i)]);
                self.mat[(i, j)] = mean;
                self.mat[(j, i)] = mean;
            }
        }
    }

    /// A⁻¹ by LU with partial pivoting; an error when an entry of it is not finite (A
    /// singular).
    pub fn inverse(&self) -> Result<DenseMatrix> {
        use faer::linalg::solvers::DenseSolveCore;
        super::parallelism(); // faer's LU reads its global parallelism: the run's split.
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

    /// The LU factors (partial pivoting) of Aᵀ (the matrix stored by the columns of Aᵀ, that
    /// is by the rows of A), kept to solve with again.
    pub fn lu_transposed(&self) -> TransposedLu {
        super::parallelism(); // As in `inverse`.
        TransposedLu { lu: self.mat.transpose().partial_piv_lu() }
    }
}

/// The LU factors of the transpose of a [`DenseMatrix`] (Newton's dense system, model §11).
#[derive(Debug)]
pub struct TransposedLu {
    lu: faer::linalg::solvers::PartialPivLu<f64>,
}

impl TransposedLu {
    /// Order of the matrix.
    pub fn n(&self) -> usize {
        use faer::linalg::solvers::ShapeCore;
        self.lu.nrows()
    }

    /// Solves Aᵀ x = b with the factors; an error when x is not finite (A singular).
    pub fn solve(&self, b: &[f64]) -> Result<Vec<f64>> {
        use faer::linalg::solvers::Solve;
        let n = self.n();
        check_length("right-hand side", n, b.len())?;
        let mut x = b.to_vec();
        self.lu.solve_in_place(MatMut::from_column_major_slice_mut(&mut x, n, 1));
        if let Some(k) = x.iter().position(|v| !v.is_finite()) {
            return Err(Error::SingularSystem {
                detail: format!("the dense Newton system is singular (component {k})"),
            });
        }
        Ok(x)
    }
}
