//! When the iterative route sets its preconditioner up again for a Newton step's matrix
//! ([`Lag`]).
//!
//! Each step of the semismooth Newton method on the whole system solves with a matrix P that
//! differs from the last step's on the rows of the Γ3 nodes and their neighbours alone;
//! setting algebraic multigrid up for it (above all its Galerkin products) is most of a
//! step's solve on large meshes. A preconditioner set up for an earlier step's P stays a good
//! one for the next while the active sets change little: the steps keep it until a solve
//! shows it has worn, by its Krylov iterations — numbers every process has alike, so that
//! every process takes the same decision (one made from each process's timings could differ
//! and leave the processes waiting in different calls).

use super::ffi::option;
use crate::error::{Error, Result};

/// The options-database key of [`Lag`]'s ratio.
pub const RATIO_OPTION: &str = "-piezocontact_pc_rebuild_ratio";

/// The ratio by default: a reused preconditioner is kept while its solves take at most twice
/// the iterations per decade of relative tolerance of the first solve after its setup.
const DEFAULT_RATIO: f64 = 2.0;

/// The Newton steps' choice between keeping the preconditioner of the last setup and setting
/// it up again for the step's matrix.
///
/// By default (the direct route's, which has no preconditioner): a setup every step.
#[derive(Clone, Copy, Debug, Default)]
pub struct Lag {
    /// A step keeps the preconditioner while the last solve took at most this times the
    /// iterations per decade of the first solve after its setup; 0: a setup every step.
    ratio: f64,
    /// Iterations per decade of relative tolerance (a solve to 1e−4 has four) of the first
    /// solve after the last setup, and of the last solve (`None`: no solve since a setup for
    /// a Newton step's matrix).
    fresh: Option<f64>,
    last: Option<f64>,
}

impl Lag {
    /// The ratio from PETSc's options database ([`RATIO_OPTION`]), [`DEFAULT_RATIO`] where
    /// it is not set; a value that is not a number ≥ 0 is an error naming the option.
    pub fn from_options() -> Result<Self> {
        let ratio = match option(RATIO_OPTION)? {
            None => DEFAULT_RATIO,
            Some(text) => text.trim().parse::<f64>().ok().filter(|r| *r >= 0.0).ok_or_else(|| {
                Error::Input(format!(
                    "PETSc option {RATIO_OPTION} {text}: give a number ≥ 0 (0 sets the preconditioner up at every Newton step; the default is {DEFAULT_RATIO})"
                ))
            })?,
        };
        Ok(Self { ratio, fresh: None, last: None })
    }

    /// Whether the next Newton step's solve keeps the preconditioner of the last setup.
    pub fn keep(&self) -> bool {
        match (self.fresh, self.last) {
            (Some(fresh), Some(last)) => self.ratio > 0.0 && last <= self.ratio * fresh,
            _ => false,
        }
    }

    /// Records a Newton step's solve to the relative residual `rtol` in `iterations`, which
    /// `kept` the preconditioner of an earlier setup or set it up for its matrix.
    pub fn record(&mut self, kept: bool, iterations: usize, rtol: f64) {
        let decades = (1.0 / rtol).log10().max(1.0);
        let rate = iterations as f64 / decades;
        if !kept {
            self.fresh = Some(rate);
        }
        self.last = Some(rate);
    }

    /// The preconditioner set up for another matrix (a factorisation's, a plain solve's, a
    /// Krylov solver made again): the next Newton step sets it up for its own.
    pub fn reset(&mut self) {
        (self.fresh, self.last) = (None, None);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lag(ratio: f64) -> Lag {
        Lag { ratio, fresh: None, last: None }
    }

    #[test]
    fn a_preconditioner_is_kept_until_its_iterations_per_decade_pass_the_ratio() {
        let mut lag = lag(2.0);
        assert!(!lag.keep(), "no setup for a Newton step yet");
        lag.record(false, 20, 1e-4); // 5 per decade
        assert!(lag.keep());
        lag.record(true, 20, 1e-2); // 10 per decade: twice, kept
        assert!(lag.keep());
        lag.record(true, 41, 1e-4); // 10.25: beyond
        assert!(!lag.keep());
        lag.record(false, 8, 1e-4); // a new setup: 2 per decade
        assert!(lag.keep());
        lag.reset();
        assert!(!lag.keep());
    }

    #[test]
    fn a_ratio_of_zero_sets_up_at_every_step() {
        let mut lag = lag(0.0);
        lag.record(false, 20, 1e-4);
        assert!(!lag.keep());
        lag.record(false, 0, 1e-4); // a right-hand side of 0: no iteration
        assert!(!lag.keep());
    }
}
