//! The `piezocontact` command's parts, as a library so that tests and fuzz targets reach them:
//! benchmarks, sweeps, the reproduction of the paper and the terminal report of a run. Case
//! files, runs, post-processing, figures and output files live in the `piezocontact` library.

pub mod bench;
pub mod fuzzing;
pub mod print;
pub mod processes;
pub mod progress;
pub mod reproduce;
pub mod say;
pub mod sheet;
pub mod sweep;
