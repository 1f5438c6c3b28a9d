//! Where the loops' stops become errors: an inner method's [`Stop`] with its [`StopContext`],
//! the outer loop's cap, its divergence and a failed factorisation — each with the advice
//! that fits it.

use super::inner::{DIVERGENCE, InnerMethod, InnerResult, Stop, StopContext};
use super::solution::ContactSolution;
use crate::contact::ContactModel;
use crate::error::Error;

/// The error of a failed factorisation of B̌(x_n) in outer step n.
pub(super) fn factorisation_failure(n: usize, e: Error) -> Error {
    let what = format!("the factorisation of B̌(x_n) in outer step {n}");
    match e {
        Error::SingularSystem { .. } => Error::NumericalFailure {
            what,
            iteration: n,
            cause: e.to_string(),
            hint: "a singular matrix means the body is not held (Γ1, Γa) or a material constant \
                   is not physical"
                .into(),
        },
        // A backend's own failure (memory, MUMPS's diagnostics) says what to change itself.
        Error::LinearAlgebra(cause) => Error::LinearAlgebra(format!("{what}: {cause}")),
        other => other,
    }
}

/// The name of the fixed-point loop in messages.
fn outer_loop_name(model: &ContactModel) -> String {
    format!("the fixed-point loop (Algorithm {})", if model.is_pv2() { 1 } else { 3 })
}

/// The way out of a fixed point that the lagged contact terms defeat.
const NOT_LAGGED: &str = "solver.method = \"newton\" (the exact solver) solves the same problem \
                          without lagging them";

/// The error of a fixed-point loop that reached solver.max_outer.
pub(super) fn outer_cap(
    model: &ContactModel,
    solution: &ContactSolution,
    max_outer: usize,
    method: &dyn InnerMethod,
) -> Error {
    Error::NotConverged {
        what: outer_loop_name(model),
        iterations: solution.outer_iterations(),
        criterion: solution.outer_history.last().copied().unwrap_or(f64::NAN),
        tolerance: method.outer_tolerance(),
        history: tail(&solution.outer_history),
        hint: if method.lags_contact() {
            format!(
                "raise solver.max_outer (now {max_outer}); a criterion that stalls means the \
                 lagged contact terms (h_ν, ψ, the friction bound) are too strong for the fixed \
                 point: {NOT_LAGGED}"
            )
        } else {
            format!(
                "raise solver.max_outer (now {max_outer}); the loop iterates on Hencky's law \
                 alone (summary.json's hencky_tangent says where its tangent was floored)"
            )
        },
    }
}

/// The error for an inner loop that stopped without converging: the one place where stops
/// become errors, with the method's hints.
pub(super) fn inner_failure(context: &StopContext, inner: &InnerResult) -> Option<Error> {
    let StopContext { what, tolerance, cap_hint, hint } = context.clone();
    let history = tail(&inner.history);
    let iteration = inner.iterations;
    let criterion = inner.history.last().copied().unwrap_or(f64::NAN);
    let not_converged = |what, history, hint| {
        Some(Error::NotConverged {
            what,
            iterations: iteration,
            criterion,
            tolerance,
            history,
            hint,
        })
    };
    match &inner.stop {
        Stop::Converged => None,
        Stop::Cap => not_converged(
            what,
            history,
            match stalled(&inner.history) {
                Some(last) => format!(
                    "its criterion has not fallen by 1 % in its last {last} iterations, where \
                     more would not help: {hint}"
                ),
                None => cap_hint,
            },
        ),
        Stop::Cycle(period) => not_converged(
            what,
            history,
            format!(
                "its iterates cycle: each of its last {period} is, to round-off, the one \
                 {period} steps before it, so more iterations would not help: {hint}"
            ),
        ),
        Stop::Diverged => Some(Error::Diverged { what, iteration, history, hint }),
        Stop::NotFinite(cause) => {
            Some(Error::NumericalFailure { what, iteration, cause: cause.clone(), hint })
        }
        Stop::Backend(cause) => {
            Some(Error::LinearAlgebra(format!("{what} failed at iteration {iteration}: {cause}")))
        }
        Stop::Interrupted(signal) => Some(Error::Interrupted { signal: *signal }),
    }
}

/// The length of the second half of a criterion history (10 values or more) whose least
/// value is not 1 % below the first half's — a cycle or a stall — else `None`.
pub(super) fn stalled(history: &[f64]) -> Option<usize> {
    let half = history.len() / 2;
    let least = |values: &[f64]| values.iter().copied().fold(f64::INFINITY, f64::min);
    let stalled = history.len() >= 10 && least(&history[half..]) >= 0.99 * least(&history[..half]);
    stalled.then_some(history.len() - half)
}

/// The last values of a criterion history, for messages.
fn tail(history: &[f64]) -> String {
    let start = history.len().saturating_sub(5);
    let values: Vec<String> = history[start..].iter().map(|v| format!("{v:.3e}")).collect();
    values.join(", ")
}

/// A non-finite outer criterion or friction bound, or a growing outer criterion.
pub(super) fn outer_failure(model: &ContactModel, solution: &ContactSolution) -> Option<Error> {
    let n = solution.outer_iterations();
    let what = outer_loop_name(model);
    let last = *solution.outer_history.last()?;
    let hint = format!(
        "the lagged contact terms are too strong for the fixed point: reduce conductivity.ke, \
         contact.c_nu or contact.penetration, or {NOT_LAGGED}"
    );
    if !last.is_finite() || solution.s.iter().any(|v| !v.is_finite()) {
        let cause = "the criterion or the friction bound s is not finite".into();
        return Some(Error::NumericalFailure { what, iteration: n, cause, hint });
    }
    let smallest = solution.outer_history.iter().copied().fold(f64::INFINITY, f64::min);
    (n >= 3 && last > DIVERGENCE * smallest).then(|| Error::Diverged {
        what,
        iteration: n,
        history: tail(&solution.outer_history),
        hint,
    })
}
