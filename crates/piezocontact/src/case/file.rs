//! A case read from its file ([`Case`]): the parsed document with its origin, which locates
//! the keys that messages name, and the choices of backend and method that it names.

use super::overrides::{apply_override, key_line};
use super::schema::{BackendKey, CaseFile, DEFAULTS, LinearKey, MethodKey, OrderingKey};
use crate::error::{Error, Result};
use crate::linalg::{LdltSolver, LinearSolver, Ordering};
use std::path::{Path, PathBuf};

/// Where a case came from: its file and its text after the overrides, which locate the keys
/// that messages name.
#[derive(Clone, Debug)]
pub struct Origin {
    /// The file it came from (relative mesh files are read from its folder).
    pub path: PathBuf,
    /// The document after overrides.
    pub text: String,
}

impl Origin {
    /// "file:line" of a dotted key, for messages.
    pub fn locate(&self, dotted: &str) -> String {
        match key_line(&self.text, dotted) {
            Some(line) => format!("{}:{line}", self.path.display()),
            None => self.path.display().to_string(),
        }
    }

    /// Places an error in this case: at the line of the key it names, else in the file.
    pub fn context(&self, e: Error) -> Error {
        let location = match &e {
            Error::InvalidParameter { name, .. } => self.locate(name),
            _ => self.path.display().to_string(),
        };
        Error::Located { location, error: Box::new(e) }
    }
}

/// A case read from a file, with the source text kept for error locations.
#[derive(Clone, Debug)]
pub struct Case {
    /// Its file and text.
    pub origin: Origin,
    /// The parsed case.
    pub file: CaseFile,
}

impl Case {
    /// Reads `path`, applies the overrides "dotted.key=value" (`--set` of the command line),
    /// and parses.
    pub fn load(path: &Path, overrides: &[String]) -> Result<Self> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::Io {
            what: format!("cannot read the case file {}", path.display()),
            cause: e.to_string(),
        })?;
        Self::from_text(path, &text, overrides)
    }

    /// Parses a case from text (`path` names it in messages and anchors relative mesh files).
    pub fn from_text(path: &Path, text: &str, overrides: &[String]) -> Result<Self> {
        let mut doc: toml_edit::DocumentMut =
            text.parse().map_err(|e| input!("{}: {e}", path.display()))?;
        for o in overrides {
            apply_override(&mut doc, o)?;
        }
        let source = doc.to_string();
        let file: CaseFile = toml::from_str(&source).map_err(|e| {
            let note = if overrides.is_empty() {
                String::new()
            } else {
                format!(" (with the overrides {})", overrides.join(", "))
            };
            input!("{}{note}: {e}", path.display())
        })?;
        let case = Self { origin: Origin { path: path.to_path_buf(), text: source }, file };
        case.check_magnitudes("", doc.as_item())?;
        Ok(case)
    }

    /// The file the case came from.
    pub fn path(&self) -> &Path {
        &self.origin.path
    }

    /// "file:line" of a dotted key, for messages.
    pub fn locate(&self, dotted: &str) -> String {
        self.origin.locate(dotted)
    }

    /// The error of a case with a `[loading]` path given to one run, which would solve the
    /// foundation where `[foundation]` puts it, under the loads unscaled, and ignore the path
    /// ([`crate::run::PathRun`] follows it).
    pub fn path_in_one_run(&self) -> Error {
        input!(
            "{}: the case has a [loading] path, which one run does not follow (it would solve \
             the foundation where [foundation] puts it, under the loads unscaled): solve the \
             path with `piezocontact run` (one row per step in curve.csv), or remove [loading] \
             for that one position",
            self.locate("loading")
        )
    }

    /// [`Case::path_in_one_run`] when the case has a `[loading]` path, for a command that
    /// solves one position per run.
    pub fn one_position(&self) -> Result<()> {
        match self.file.loading {
            Some(_) => Err(self.path_in_one_run()),
            None => Ok(()),
        }
    }

    /// Places an error in this case: at the line of the key it names, else in the file.
    pub fn context(&self, e: Error) -> Error {
        self.origin.context(e)
    }

    /// The linear solver the case asks for: `solver.backend` and `solver.ordering`.
    pub fn linear(&self) -> Linear {
        let ordering = match self.file.solver.ordering.unwrap_or(DEFAULTS.ordering) {
            OrderingKey::Auto => Ordering::Auto,
            OrderingKey::Nd => Ordering::NestedDissection,
            OrderingKey::Amd => Ordering::Amd,
        };
        let backend = self.file.solver.backend.unwrap_or(DEFAULTS.backend);
        let iterative = self.file.solver.linear == Some(LinearKey::Iterative);
        Linear { backend, ordering, iterative }
    }

    /// The linear solver the case asks for ([`Case::linear`]), refused with the command that
    /// builds the PETSc backend where it is not built in.
    pub fn linear_solver(&self) -> Result<Box<dyn LinearSolver>> {
        self.check_backend()?;
        self.linear().solver()
    }

    /// Refuses `solver.backend = "petsc"` in a build without the PETSc backend, with the
    /// command that builds it, and `solver.linear = "iterative"` where it cannot run.
    pub(super) fn check_backend(&self) -> Result<()> {
        self.check_linear()?;
        if cfg!(feature = "petsc") || self.file.solver.backend != Some(BackendKey::Petsc) {
            return Ok(());
        }
        Err(Error::Input(format!(
            "{}: solver.backend = \"petsc\" needs piezocontact built with the PETSc backend: install petsc-dev and openmpi-bin (Debian), then cargo build --release --features petsc; or use solver.backend = \"faer\"",
            self.locate("solver.backend")
        )))
    }

    /// `solver.linear = "iterative"` runs on PETSc (the exact solver then runs on the whole
    /// system, having no factorisation to condense with).
    fn check_linear(&self) -> Result<()> {
        let s = &self.file.solver;
        if s.linear != Some(LinearKey::Iterative) {
            return Ok(());
        }
        if s.backend != Some(BackendKey::Petsc) {
            return Err(Error::Input(format!(
                "{}: solver.linear = \"iterative\" runs on PETSc's Krylov solvers: set solver.backend = \"petsc\" too, or use solver.linear = \"direct\"",
                self.locate("solver.linear")
            )));
        }
        Ok(())
    }

    /// The name of the inner method the case chooses (`solver.method`).
    pub fn method_name(&self) -> &'static str {
        match self.file.solver.method.unwrap_or(DEFAULTS.method) {
            MethodKey::Newton => "newton",
            MethodKey::Uzawa => "uzawa",
        }
    }
}

/// The linear solver a case asks for (model §5): `solver.backend` and `solver.ordering`.
#[derive(Clone, Debug, PartialEq)]
pub struct Linear {
    /// faer's sparse LDLᵀ or PETSc + MUMPS.
    pub backend: BackendKey,
    /// The fill-reducing ordering of faer's LDLᵀ.
    pub ordering: Ordering,
    /// PETSc's Krylov solver instead of a factorisation (`solver.linear = "iterative"`).
    pub iterative: bool,
}

impl Linear {
    /// A new solver of this choice: faer's sparse LDLᵀ with the ordering on the run's
    /// threads, or PETSc + MUMPS on the run's processes.
    pub fn solver(&self) -> Result<Box<dyn LinearSolver>> {
        match self.backend {
            BackendKey::Faer => Ok(Box::new(LdltSolver::with_ordering(self.ordering.clone()))),
            BackendKey::Petsc => petsc_solver(self.iterative),
        }
    }

    /// The backend's name in case files and summaries.
    pub fn backend_name(&self) -> &'static str {
        match self.backend {
            BackendKey::Faer => "faer",
            BackendKey::Petsc => "petsc",
        }
    }
}

/// PETSc + MUMPS, or PETSc's Krylov solver where `iterative`.
#[cfg(feature = "petsc")]
fn petsc_solver(iterative: bool) -> Result<Box<dyn LinearSolver>> {
    use crate::linalg::PetscSolver;
    use crate::linalg::petsc::{KRYLOV_MAX_ITERATIONS, KRYLOV_RTOL};
    Ok(Box::new(match iterative {
        true => PetscSolver::iterative(KRYLOV_RTOL, KRYLOV_MAX_ITERATIONS)?,
        false => PetscSolver::new()?,
    }))
}

#[cfg(not(feature = "petsc"))]
fn petsc_solver(_iterative: bool) -> Result<Box<dyn LinearSolver>> {
    Err(Error::Input(
        "solver.backend = \"petsc\" needs piezocontact built with the PETSc backend (cargo build --features petsc)".into(),
    ))
}
