//! The one formatting of reals in every CSV the program writes.

/// A number for a CSV cell: `{:e}`, or an empty cell when it is not finite (every CSV
/// reader takes an empty cell as missing; no NaN or inf token is ever written). The
/// summary.json of the run says why ([`super::contact::non_finite`]).
pub fn csv_number(v: f64) -> String {
    if v.is_finite() { format!("{v:e}") } else { String::new() }
}
