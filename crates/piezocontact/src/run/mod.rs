//! A run of a built case ([`Run`]): a solve without contact, one contact solve, or a loading
//! path — chosen once, here, from what the case holds — with its summary and its files. What
//! `piezocontact run`, `sweep` and `reproduce` do for each case, and what the Python package
//! and a library user call.
//!
//! Each file imports its siblings' files, never this one.

pub mod contact_run;
pub mod path_run;
pub mod static_path_run;
pub mod static_run;

pub use contact_run::ContactRun;
pub use path_run::{PathRun, StepFiles};
pub use static_path_run::StaticPathRun;
pub use static_run::StaticRun;

use crate::algorithm::Progress;
use crate::case::Built;
use crate::dofs::DofMap;
use crate::error::{Error, Result};
use crate::linalg::LinearSolver;
use crate::output::files::Outputs;
use crate::output::vtu::Encoding;
use crate::report::Column;
use crate::report::summary::close_timings;
use serde_json::Value;
use std::path::Path;

/// A solved case.
pub enum Run {
    /// No `[contact]` table: the coupled problem alone (Γ3, if named, is free).
    Static(StaticRun),
    /// One contact solve.
    Contact(ContactRun),
    /// A loading path (`[loading]`): one contact solve per step.
    Path(PathRun),
    /// A loading path without `[contact]` (`loading.load_factors`): one solve without contact
    /// per step.
    StaticPath(StaticPathRun),
}

impl Run {
    /// Solves `built` with the caller's linear `solver` (`built.linear_solver()` for the
    /// case's own), telling `progress` of each outer step and inner iteration.
    pub fn solve(
        built: &Built,
        solver: Box<dyn LinearSolver>,
        progress: &(dyn Fn(Progress) + Sync),
    ) -> Result<Self> {
        Self::solve_writing(built, (solver, progress), None)
    }

    /// [`Run::solve`], a contact path writing each step's solution-NNNN.vtu into `files` while
    /// the next step solves (what [`Run::write`] into the same directory then keeps).
    pub fn solve_writing(
        built: &Built,
        (solver, progress): (Box<dyn LinearSolver>, &(dyn Fn(Progress) + Sync)),
        files: Option<StepFiles>,
    ) -> Result<Self> {
        match (&built.model, &built.loading) {
            (Some(model), Some(loading)) => {
                PathRun::solve(built, (model, loading), (solver, progress), files).map(Self::Path)
            }
            (Some(model), None) => {
                ContactRun::solve(built, model, solver, progress).map(Self::Contact)
            }
            (None, loading) => {
                if !built.problem.boundary.contact.is_empty() {
                    log::warn!(
                        "the case has no [contact] table: Γ3 is treated as free (traction and charge free)"
                    );
                }
                match loading {
                    Some(loading) => {
                        StaticPathRun::solve(built, loading, solver).map(Self::StaticPath)
                    }
                    None => StaticRun::solve(built, solver).map(Self::Static),
                }
            }
        }
    }

    /// The summary.json document, its timings up to now (before the files are written).
    pub fn summary(&self, built: &Built) -> Value {
        let mut summary = self.solve_summary(built);
        close_timings(&mut summary, built, &[], &[]);
        summary
    }

    /// The summary.json document of the solve, without the run's total time.
    fn solve_summary(&self, built: &Built) -> Value {
        match (self, &built.loading) {
            (Self::Static(run), _) => run.summary(built),
            (Self::Contact(run), _) => run.summary(built),
            (Self::Path(path), Some(loading)) => path.summary(built, loading),
            (Self::Path(path), None) => path.last.summary(built),
            (Self::StaticPath(path), _) => path.summary(built),
        }
    }

    /// Writes the run's files into `out` (created if needed): summary.json and solution.vtu;
    /// with contact contact.csv (and the map of Γ3 in 3D); on a path curve.csv, the steps'
    /// solution-NNNN.vtu with solution.pvd and the curves' figure; the .vtu files in `vtu`'s
    /// encoding (ParaView's binary one by default). summary.json comes last, with the time
    /// each other file took; it is returned.
    pub fn write(&self, built: &Built, out: &Path, vtu: Encoding) -> Result<Value> {
        let mut outputs = Outputs::new(out, vtu)?;
        match (self, &built.loading) {
            (Self::Static(run), _) => run.write_files(built, &mut outputs),
            (Self::Contact(run), _) => run.write_files(built, &mut outputs),
            (Self::Path(path), Some(loading)) => path.write_files((built, loading), &mut outputs),
            (Self::Path(path), None) => path.last.write_files(built, &mut outputs),
            (Self::StaticPath(path), _) => path.write_files(built, &mut outputs),
        }?;
        outputs.finish(built, self.solve_summary(built))
    }

    /// The contact run: the run itself, or the last step of a path; `None` without contact.
    pub fn contact(&self) -> Option<&ContactRun> {
        match self {
            Self::Static(_) | Self::StaticPath(_) => None,
            Self::Contact(run) => Some(run),
            Self::Path(path) => Some(&path.last),
        }
    }

    /// The DOF numbering and x = (u, ϕ) of the solution (of the last step of a path).
    pub fn state(&self) -> (&DofMap, &[f64]) {
        match self {
            Self::Static(run) => (&run.solution.dofs, &run.solution.x),
            Self::Contact(run) => (&run.solution.dofs, &run.solution.x),
            Self::Path(path) => (&path.last.solution.dofs, &path.last.solution.x),
            Self::StaticPath(path) => (&path.last.solution.dofs, &path.last.solution.x),
        }
    }

    /// Why the run did not converge, `None` when it did: the solution's failure, or the step
    /// of a path that stopped it.
    pub fn failure(&self) -> Option<String> {
        match self {
            Self::Static(run) => run.solution.failure.as_ref().map(ToString::to_string),
            Self::Contact(run) => run.solution.failure.as_ref().map(ToString::to_string),
            Self::Path(path) => path.failure.clone(),
            Self::StaticPath(path) => path.failure(),
        }
    }

    /// The solution's own error when the run did not converge (a path's last step's): a cap,
    /// a divergence, an interruption; `None` otherwise, and for a path step that failed
    /// outright.
    pub fn error(&self) -> Option<&Error> {
        match self {
            Self::Static(run) => run.solution.failure.as_ref(),
            Self::StaticPath(path) => path.last.solution.failure.as_ref(),
            _ => self.contact().and_then(|run| run.solution.failure.as_ref()),
        }
    }

    /// The columns of a loading path's curve.csv, one entry per step solved; empty for a
    /// single solve.
    pub fn curve(&self, built: &Built) -> Vec<(String, Column)> {
        match self {
            Self::Path(path) => path.columns(built),
            Self::StaticPath(path) => path.columns(built),
            _ => Vec::new(),
        }
    }

    /// x = (u, ϕ) of each step of a loading path, in order (numbered as [`Run::state`]'s);
    /// empty for a single solve.
    pub fn steps(&self) -> Vec<&[f64]> {
        match self {
            Self::Path(path) => path.states().collect(),
            Self::StaticPath(path) => path.states().collect(),
            _ => Vec::new(),
        }
    }

    /// What of the run is kept when it did not converge, for messages: "the partial result
    /// is" or, on a path, "the steps before it are".
    pub fn kept(&self) -> &'static str {
        match self {
            Self::Path(_) | Self::StaticPath(_) => "the steps before it are",
            _ => "the partial result is",
        }
    }
}
