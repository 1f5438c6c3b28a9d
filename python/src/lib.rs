//! piezocontact from Python: solve a case file (or a case built from a dict) with the library
//! that the `piezocontact` command uses, and get its results as numpy arrays.
//!
//! - `solve(case_path, overrides=None)` runs what `piezocontact run` runs; `overrides` maps
//!   dotted keys to values, applied in the dict's order as `--set`s are.
//! - `Case.from_dict(...)`, `Case.from_file(...)` and `Case.solve()`.
//! - `Solution`: `summary` (summary.json as a dict), `contact` (the contact.csv columns),
//!   `electrodes` (summary.json's list: name, parts, kind, potential, charge), `points`, `u`,
//!   `phi`, `converged`, and `write(directory)` (the files `run` writes).
//!
//! Bad input raises `CaseError`, a `ValueError` with the command line's message (file, line,
//! key); what `run` warns of a case, a `CaseWarning` (a `UserWarning`). In `overrides`, a
//! dict sets the keys it names and keeps the table's others. The solve runs without the GIL,
//! and a panic inside it becomes a `RuntimeError`.

use numpy::{PyArray1, PyArray2, PyArrayMethods};
use piezocontact::case::{Built, Case as CaseFile};
use piezocontact::output::files::Claimed;
use piezocontact::output::vtu::Encoding;
use piezocontact::report::{Column, contact_columns, row_values};
use piezocontact::run::Run;
use pyo3::create_exception;
use pyo3::exceptions::{PyOSError, PyRuntimeError, PyRuntimeWarning, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use std::ffi::CString;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};

create_exception!(
    piezocontact,
    CaseError,
    PyValueError,
    "Bad input — a case file, a key, a value, a mesh — with the message the command line gives \
     (file, line, key and the fix)."
);

create_exception!(
    piezocontact,
    CaseWarning,
    pyo3::exceptions::PyUserWarning,
    "What the command line warns of a case before it runs it: a key nothing reads, a \
     segment end between two nodes."
);

/// A library error as the Python exception that carries its message.
fn case_error(e: impl std::fmt::Display) -> PyErr {
    CaseError::new_err(e.to_string())
}

/// A Python value as a TOML value: bool, int, float (numpy scalars and arrays through their
/// `tolist()`), str, list or tuple, dict; `key` (dotted) names it in errors.
fn toml_value(value: &Bound<'_, PyAny>, key: &str) -> PyResult<toml::Value> {
    let value = if value.hasattr("tolist")? && !value.is_instance_of::<PyString>() {
        value.call_method0("tolist")?
    } else {
        value.clone()
    };
    if value.is_instance_of::<PyBool>() {
        Ok(toml::Value::Boolean(value.extract()?))
    } else if value.is_instance_of::<PyInt>() {
        let integer = value.extract().map_err(|_| {
            CaseError::new_err(format!(
                "{key} = {value}: an integer of a case is at most 2⁶³ − 1 in magnitude"
            ))
        })?;
        Ok(toml::Value::Integer(integer))
    } else if value.is_instance_of::<PyFloat>() {
        Ok(toml::Value::Float(value.extract()?))
    } else if value.is_instance_of::<PyString>() {
        Ok(toml::Value::String(value.extract()?))
    } else if value.is_instance_of::<PyDict>() {
        Ok(toml::Value::Table(toml_table(value.cast::<PyDict>()?, &format!("{key}."))?))
    } else if value.is_instance_of::<PyList>() || value.is_instance_of::<PyTuple>() {
        let items: PyResult<Vec<toml::Value>> =
            value.try_iter()?.map(|item| toml_value(&item?, key)).collect();
        Ok(toml::Value::Array(items?))
    } else {
        Err(CaseError::new_err(format!(
            "{key}: a value of type {} cannot be a case value: give a bool, int, float, str, list or dict",
            value.get_type().name()?
        )))
    }
}

/// A dict with string keys as a TOML table; `prefix` (dotted, "" at the top) names its keys
/// in errors.
fn toml_table(dict: &Bound<'_, PyDict>, prefix: &str) -> PyResult<toml::Table> {
    let mut table = toml::Table::new();
    for (key, value) in dict.iter() {
        let key: String = key.extract().map_err(|_| key_error(&key))?;
        let value = toml_value(&value, &format!("{prefix}{key}"))?;
        table.insert(key, value);
    }
    Ok(table)
}

/// The error of a dict key that is not a string.
fn key_error(key: &Bound<'_, PyAny>) -> PyErr {
    let shown = key.repr().map_or_else(|_| "?".into(), |r| r.to_string());
    CaseError::new_err(format!("case keys are strings, not {shown}"))
}

/// `overrides` as `--set` strings "dotted.key=value", in the dict's order (a later key
/// overrides an earlier one, as a later `--set` does).
fn override_strings(overrides: Option<&Bound<'_, PyDict>>) -> PyResult<Vec<String>> {
    let Some(overrides) = overrides else { return Ok(Vec::new()) };
    overrides
        .iter()
        .map(|(key, value)| {
            let key: String = key.extract().map_err(|_| key_error(&key))?;
            Ok(format!("{key}={}", toml_value(&value, &key)?))
        })
        .collect()
}

/// Runs `work` without the GIL; a panic in it becomes a `RuntimeError` instead of unwinding
/// into the interpreter.
fn guarded<T: Send>(py: Python<'_>, work: impl FnOnce() -> T + Send) -> PyResult<T> {
    py.detach(|| catch_unwind(AssertUnwindSafe(work))).map_err(internal_error)
}

/// The `RuntimeError` of a panic's payload.
fn internal_error(payload: Box<dyn std::any::Any + Send>) -> PyErr {
    let message = payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "no message".into());
    PyRuntimeError::new_err(format!(
        "internal error in piezocontact (please report it with the case): {message}"
    ))
}

/// The threads a solve may use (assembly, factorisation, solves): at most `threads`, else
/// every core. Each solve has a pool of its own, so that solves in several Python threads
/// keep to their own bounds.
fn thread_pool(threads: Option<i64>) -> PyResult<rayon::ThreadPool> {
    let threads = match threads.map(usize::try_from) {
        None => 0,
        Some(Ok(n)) if n > 0 => n,
        Some(_) => {
            let given = threads.unwrap_or_default();
            let message = format!("threads = {given}: give at least 1 (or None: every core)");
            return Err(PyValueError::new_err(message));
        }
    };
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| PyRuntimeError::new_err(format!("cannot start the solve's threads: {e}")))
}

/// Runs `work` on a pool of `threads` without the GIL while the calling thread looks at
/// Python's signals every 100 ms (Python runs its signal handlers on the main thread only): a
/// pending KeyboardInterrupt asks the run to stop at its next safe point
/// ([`piezocontact::interrupt`]) and is raised once `work` has returned. A panic becomes a
/// `RuntimeError`.
fn watched<T: Send + 'static>(
    py: Python<'_>,
    threads: Option<i64>,
    work: impl FnOnce() -> T + Send + 'static,
) -> PyResult<T> {
    let pool = thread_pool(threads)?;
    piezocontact::interrupt::clear();
    let (sender, receiver) = std::sync::mpsc::channel();
    pool.spawn(move || {
        let _ = sender.send(catch_unwind(AssertUnwindSafe(work)));
    });
    let (result, raised) = py.detach(move || {
        let mut raised = None;
        loop {
            match receiver.recv_timeout(std::time::Duration::from_millis(100)) {
                Ok(result) => return (result, raised),
                Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {
                    if let Err(e) = Python::attach(|py| py.check_signals()) {
                        piezocontact::interrupt::request(2);
                        raised.get_or_insert(e);
                    }
                }
                Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => {
                    let lost = "the solve's thread ended without a result";
                    return (Err(Box::new(lost) as Box<dyn std::any::Any + Send>), raised);
                }
            }
        }
    });
    match (raised, result) {
        (Some(interrupt), _) => Err(interrupt),
        (None, result) => result.map_err(internal_error),
    }
}

/// Solves `case` on at most `threads` threads without the GIL; its warnings (those `run`
/// prints) are `CaseWarning`s, a panic becomes a `RuntimeError`, an unconverged run a
/// `RuntimeWarning` (its results are there, marked `converged = False`), Ctrl-C during the
/// solve a `KeyboardInterrupt` once the run has stopped.
fn solve_case(py: Python<'_>, case: CaseFile, threads: Option<i64>) -> PyResult<Solution> {
    for warning in case.setting_warnings() {
        let message = CString::new(warning).unwrap_or_default();
        PyErr::warn(py, &py.get_type::<CaseWarning>(), &message, 1)?;
    }
    let solved = watched(py, threads, move || {
        let built = case.build()?;
        let run = built.linear_solver().and_then(|solver| Run::solve(&built, solver, &|_| {}))?;
        Ok::<_, piezocontact::Error>(Solution { run, built })
    })?;
    let solution = solved.map_err(case_error)?;
    if let Some(failure) = solution.run.failure() {
        let message = CString::new(format!(
            "{}: {failure}; {} in the Solution (converged = False)",
            solution.built.origin.path.display(),
            solution.run.kept()
        ))
        .unwrap_or_default();
        PyErr::warn(py, &py.get_type::<PyRuntimeWarning>(), &message, 1)?;
    }
    Ok(solution)
}

/// Runs what `piezocontact run CASE_PATH --set key=value ...` runs and returns the solution.
#[pyfunction]
#[pyo3(signature = (case_path, overrides = None, threads = None))]
fn solve(
    py: Python<'_>,
    case_path: PathBuf,
    overrides: Option<&Bound<'_, PyDict>>,
    threads: Option<i64>,
) -> PyResult<Solution> {
    let case = CaseFile::load(&case_path, &override_strings(overrides)?).map_err(case_error)?;
    solve_case(py, case, threads)
}

/// Panics inside the guard that every solve runs in: the interpreter must get a
/// RuntimeError, not die (the tests of that guard call it).
#[pyfunction]
fn _panic_inside_the_guard(py: Python<'_>) -> PyResult<()> {
    guarded(py, || panic!("a deliberate panic"))
}

/// A case, read from a file or built from a dict with the case file's structure.
#[pyclass(frozen, module = "piezocontact")]
struct Case {
    case: CaseFile,
}

#[pymethods]
impl Case {
    /// A case from a dict shaped like a case file ({"mesh": {...}, "material": {...}, ...});
    /// relative paths in it (mesh.file) are relative to `base_dir` (default: the current
    /// directory). Messages name it "<base_dir>/case-from-dict.toml".
    #[staticmethod]
    #[pyo3(signature = (data, base_dir = None))]
    fn from_dict(data: &Bound<'_, PyDict>, base_dir: Option<PathBuf>) -> PyResult<Self> {
        let text = toml::to_string(&toml_table(data, "")?).map_err(case_error)?;
        let path = base_dir.unwrap_or_else(|| PathBuf::from(".")).join("case-from-dict.toml");
        Ok(Self { case: CaseFile::from_text(&path, &text, &[]).map_err(case_error)? })
    }

    /// A case file with `overrides` (dotted keys, as `--set`).
    #[staticmethod]
    #[pyo3(signature = (path, overrides = None))]
    fn from_file(path: PathBuf, overrides: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        let case = CaseFile::load(&path, &override_strings(overrides)?).map_err(case_error)?;
        Ok(Self { case })
    }

    /// The case as TOML text (with its overrides applied).
    #[getter]
    fn text(&self) -> &str {
        &self.case.origin.text
    }

    /// Solves the case.
    #[pyo3(signature = (threads = None))]
    fn solve(&self, py: Python<'_>, threads: Option<i64>) -> PyResult<Solution> {
        solve_case(py, self.case.clone(), threads)
    }
}

/// The solution of a case: its run and the built case it ran.
#[pyclass(frozen, module = "piezocontact")]
struct Solution {
    run: Run,
    built: Built,
}

impl Solution {
    /// An n × d array of the nodes.
    fn nodal<'py>(
        &self,
        py: Python<'py>,
        value: impl Fn(usize, usize) -> f64,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let mesh = &self.built.problem.mesh;
        let (n, d) = (mesh.n_nodes(), mesh.dim());
        let flat: Vec<f64> =
            (0..n).flat_map(|a| (0..d).map(move |k| (a, k))).map(|(a, k)| value(a, k)).collect();
        PyArray1::from_vec(py, flat).reshape([n, d])
    }
}

#[pymethods]
impl Solution {
    /// summary.json as a dict.
    #[getter]
    fn summary<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let text = serde_json::to_string(&self.run.summary(&self.built)).map_err(case_error)?;
        py.import("json")?.call_method1("loads", (text,))
    }

    /// Every electrode (the grounded parts, then the `[[boundary.electrode]]` tables) as
    /// summary.json's `electrodes` gives it: a list of dicts with `name`, `parts`, `kind`
    /// ("voltage" or "floating"), `potential` and `charge` (the case's units).
    #[getter]
    fn electrodes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.summary(py)?.get_item("electrodes")
    }

    /// The contact.csv columns as 1-D numpy arrays (float, and `status` as str), one entry per
    /// Γ3 node (of the last step of a path); empty without contact.
    #[getter]
    fn contact<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let dict = PyDict::new(py);
        let Some(run) = self.run.contact() else { return Ok(dict) };
        let dim = self.built.problem.mesh.dim();
        let rows: Vec<Vec<f64>> = run.rows.iter().map(|r| row_values(r, dim)).collect();
        for (k, name) in contact_columns(dim).iter().enumerate() {
            let column: Vec<f64> = rows.iter().map(|r| r[k]).collect();
            dict.set_item(*name, PyArray1::from_vec(py, column))?;
        }
        let status: Vec<&str> = run.rows.iter().map(|r| r.status.name()).collect();
        dict.set_item("status", py.import("numpy")?.call_method1("array", (status,))?)?;
        Ok(dict)
    }

    /// The node coordinates, n × d.
    #[getter]
    fn points<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let mesh = &self.built.problem.mesh;
        self.nodal(py, |a, k| mesh.node(a)[k])
    }

    /// The displacement u at the nodes, n × d.
    #[getter]
    fn u<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let (dofs, x) = self.run.state();
        self.nodal(py, |a, k| x[dofs.u(a, k)])
    }

    /// The electric potential ϕ at the nodes, n.
    #[getter]
    fn phi<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let (dofs, x) = self.run.state();
        let n = self.built.problem.mesh.n_nodes();
        let phi: Vec<f64> = (0..n).map(|a| x[dofs.phi(a)]).collect();
        PyArray1::from_vec(py, phi)
    }

    /// Whether every loop converged (a run without contact always does; a path when every
    /// step did).
    #[getter]
    fn converged(&self) -> bool {
        self.run.failure().is_none()
    }

    /// The curve.csv columns of a loading path as 1-D numpy arrays (`step` and
    /// `newton_steps` as int, `converged` as bool), one entry per step solved; empty for a
    /// single run.
    #[getter]
    fn curve<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let dict = PyDict::new(py);
        let numpy = py.import("numpy")?;
        for (name, column) in self.run.curve(&self.built) {
            match column {
                Column::Integer(v) => dict.set_item(name, numpy.call_method1("array", (v,))?)?,
                Column::Real(v) => dict.set_item(name, PyArray1::from_vec(py, v))?,
                Column::Flag(v) => dict.set_item(name, numpy.call_method1("array", (v,))?)?,
            }
        }
        Ok(dict)
    }

    /// The state of each step of a loading path: dicts with `u` (n × d) and `phi` (n); empty
    /// for a single run.
    #[getter]
    fn steps<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
        let (dofs, _) = self.run.state();
        let n = self.built.problem.mesh.n_nodes();
        self.run
            .steps()
            .into_iter()
            .map(|x| {
                let dict = PyDict::new(py);
                dict.set_item("u", self.nodal(py, |a, k| x[dofs.u(a, k)])?)?;
                let phi: Vec<f64> = (0..n).map(|a| x[dofs.phi(a)]).collect();
                dict.set_item("phi", PyArray1::from_vec(py, phi))?;
                Ok(dict)
            })
            .collect()
    }

    /// Writes the files `piezocontact run` writes into `directory`; a directory holding
    /// files piezocontact did not write is refused unless `force`. `vtu` is how solution.vtu
    /// holds its numbers: "binary" (ParaView's appended raw data) or "ascii" (text).
    #[pyo3(signature = (directory, force = false, vtu = "binary"))]
    fn write(&self, py: Python<'_>, directory: PathBuf, force: bool, vtu: &str) -> PyResult<()> {
        let vtu = match vtu {
            "binary" => Encoding::Binary,
            "ascii" => Encoding::Ascii,
            other => {
                return Err(case_error(format!(
                    "vtu = {other:?}: solution.vtu is written \"binary\" or \"ascii\""
                )));
            }
        };
        guarded(py, || self.write_files(&directory, force, vtu))?.map_err(|e| match e {
            // A file that cannot be made or written is the system's: an OSError.
            piezocontact::Error::Io { .. } => PyOSError::new_err(e.to_string()),
            piezocontact::Error::ForeignOutput { .. } => {
                case_error(format!("{e}: choose another directory, or pass force=True"))
            }
            e => case_error(e),
        })
    }
}

impl Solution {
    /// [`Solution::write`] without the GIL.
    fn write_files(
        &self,
        directory: &Path,
        force: bool,
        vtu: Encoding,
    ) -> piezocontact::Result<()> {
        let _claim = Claimed::new(directory, force)?;
        self.run.write(&self.built, directory, vtu).map(|_| ())
    }
}

/// The module `piezocontact._native`, re-exported by the package `piezocontact`.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(solve, m)?)?;
    m.add_function(wrap_pyfunction!(_panic_inside_the_guard, m)?)?;
    m.add_class::<Case>()?;
    m.add_class::<Solution>()?;
    m.add("CaseError", m.py().get_type::<CaseError>())?;
    m.add("CaseWarning", m.py().get_type::<CaseWarning>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
