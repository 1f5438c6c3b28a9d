//! The `piezocontact` command's parts, as a library so that tests and fuzz targets reach them:
//! case files, runs, sweeps, the reproduction of the paper, figures and output files. All
//! numerics live in the `piezocontact` crate.

pub mod bench;
pub mod case;
pub mod fuzzing;
pub mod output;
pub mod plot;
pub mod report;
pub mod reproduce;
pub mod runner;
pub mod sweep;
