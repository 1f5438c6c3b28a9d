//! Integration tests of the `piezocontact` command, one binary (fast linking on 2 cores).

/// The commands end to end: outputs, overrides, reproduce, and one test per error message.
mod commands;
/// Helpers: running the command, temporary directories.
mod common;
/// The fuzz targets' regression corpus, replayed.
mod corpus;
/// Numerical failures, output-directory rules, a killed run.
mod failures;
/// Bad input, round 2: closed pipes, unusable meshes, overflow, loose pieces, progress.
mod input;
/// Random valid cases solve or fail with typed errors, never NaN in outputs.
mod properties;
