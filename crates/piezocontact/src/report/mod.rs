//! What a run reports, as data and text: the Γ3 table `contact.csv` ([`contact`]), the rows
//! of a loading path's `curve.csv` ([`curve`]), the fields of `summary.json` ([`summary`]),
//! and the one formatting of reals in every CSV ([`csv`]). The files are written by
//! [`crate::output`].
//!
//! Each file imports its siblings' files, never this one.

pub mod contact;
pub mod csv;
pub mod curve;
pub mod summary;

pub use contact::{Row, contact_columns, contact_csv, row_values, rows, zone_measures};
pub use csv::csv_number;
pub use curve::{
    Column, CurveRow, StaticCurveRow, columns_csv, curve_columns, static_curve_columns,
};
