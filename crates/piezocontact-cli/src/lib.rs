//! The `piezocontact` command's parts, as a library so that tests and fuzz targets reach them:
//! benchmarks, sweeps, the reproduction of the paper, figures and the terminal report of a run.
//! Case files, runs, post-processing and output files live in the `piezocontact` library.

pub mod bench;
pub mod fuzzing;
pub mod outputs;
pub mod plot;
pub mod print;
pub mod progress;
pub mod reproduce;
pub mod say;
pub mod sweep;
