//! Checks and views of the slices that cross the seam, and how faer splits its parallel
//! work.

use crate::error::{Error, Result};
use std::borrow::Cow;

/// The number of columns of `n` entries in `len` entries; an error when they do not divide.
pub(super) fn column_count(len: usize, n: usize) -> Result<usize> {
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

/// An [`Error::Length`] unless a vector of `what` has the `expected` length.
pub(crate) fn check_length(what: &str, expected: usize, got: usize) -> Result<()> {
    if got == expected {
        return Ok(());
    }
    Err(Error::Length { what: what.into(), expected, got })
}

/// The entries of `values` where `mask` holds, in order (every one without a mask): a
/// process's own rows of a vector of the unknowns, or its owned positions of one.
pub(crate) fn masked(mask: Option<&[bool]>, values: Vec<f64>) -> Vec<f64> {
    match mask {
        None => values,
        Some(mask) => values.into_iter().zip(mask).filter(|(_, m)| **m).map(|(v, _)| v).collect(),
    }
}

/// [`masked`] of a borrowed vector, which comes back borrowed without a mask.
pub(crate) fn masked_view<'v>(mask: Option<&[bool]>, values: &'v [f64]) -> Cow<'v, [f64]> {
    match mask {
        None => Cow::Borrowed(values),
        Some(mask) => values.iter().zip(mask).filter(|(_, m)| **m).map(|(v, _)| *v).collect(),
    }
}

/// The inverse of [`masked`]: `values`, one per entry where `mask` holds, put there in a
/// vector of the mask's length, 0 at the other entries.
pub(crate) fn unmasked(mask: Option<&[bool]>, values: Vec<f64>) -> Vec<f64> {
    let Some(mask) = mask else { return values };
    let mut values = values.into_iter();
    mask.iter().map(|&m| if m { values.next().unwrap_or(0.0) } else { 0.0 }).collect()
}

/// A slice as a one-column matrix, for faer's solves and products of one right-hand side.
pub(super) fn column<T>(v: &mut [T]) -> faer::MatMut<'_, T> {
    let n = v.len();
    faer::MatMut::from_column_major_slice_mut(v, n, 1)
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
