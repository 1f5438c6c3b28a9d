//! Writing results safely.
//!
//! - Every file is written in full under a temporary name and renamed into place, so a reader
//!   never sees half a file. While an output directory is claimed, the temporary files live in
//!   a staging directory *beside* it: a run killed at any moment leaves only complete files in
//!   the output directory.
//! - `claim` refuses a directory holding files that piezocontact did not write (unless
//!   forced) and clears our own earlier output there, so that a rerun replaces it whole. The
//!   files written are listed in the directory's [`MARKER`] file.

use super::vtu::{Encoding, Field, pvd, write_vtu};
use crate::assembly::element_fields;
use crate::case::Built;
use crate::dofs::DofMap;
use crate::error::{Error, Result};
use crate::problem::Problem;
use crate::report::summary::close_timings;
use serde_json::Value;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The file that marks a directory as piezocontact's output and lists what was written.
pub const MARKER: &str = ".piezocontact-output";

/// The claimed output directory and its staging directory.
struct Claim {
    root: PathBuf,
    staging: PathBuf,
}

static CLAIM: Mutex<Option<Claim>> = Mutex::new(None);
static COUNTER: AtomicUsize = AtomicUsize::new(0);

/// An [`Error::Io`] for `what` from an I/O error.
fn io(what: String) -> impl FnOnce(std::io::Error) -> Error {
    move |e| Error::Io { what, cause: e.to_string() }
}

/// Claims `dir` for this process's output: creates it, refuses it if it holds files that
/// piezocontact did not write (unless `force`), deletes the files of our earlier output
/// listed in its marker, and prepares the staging directory beside it.
fn claim(dir: &Path, force: bool) -> Result<()> {
    if dir.as_os_str().is_empty() {
        return Err(Error::Input(
            "the output directory is an empty path: name a directory, e.g. out/run".into(),
        ));
    }
    std::fs::create_dir_all(dir)
        .map_err(io(format!("cannot create the output directory {}", dir.display())))?;
    let marker = dir.join(MARKER);
    let listed: Vec<PathBuf> = std::fs::read_to_string(&marker)
        .map(|t| t.lines().map(PathBuf::from).collect())
        .unwrap_or_default();
    let ours = |name: &std::ffi::OsStr| {
        name == MARKER
            || listed.iter().any(|p| p.components().next().is_some_and(|c| c.as_os_str() == name))
    };
    let mut foreign: Vec<String> = std::fs::read_dir(dir)
        .map_err(io(format!("cannot read the output directory {}", dir.display())))?
        .filter_map(|e| e.ok())
        .filter(|e| !ours(&e.file_name()))
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    foreign.sort();
    if !foreign.is_empty() && !force {
        return Err(Error::ForeignOutput { dir: dir.display().to_string(), files: foreign });
    }
    for rel in &listed {
        let _ = std::fs::remove_file(dir.join(rel));
        let mut parent = rel.parent();
        while let Some(p) = parent.filter(|p| !p.as_os_str().is_empty()) {
            let _ = std::fs::remove_dir(dir.join(p)); // only when empty
            parent = p.parent();
        }
    }
    std::fs::write(&marker, "").map_err(io(format!("cannot write {}", marker.display())))?;
    let root =
        std::fs::canonicalize(dir).map_err(io(format!("cannot resolve {}", dir.display())))?;
    let name =
        root.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_else(|| "out".into());
    let parent = root.parent().unwrap_or(Path::new("/")).to_path_buf();
    let prefix = format!(".{name}.piezocontact-staging-");
    if let Ok(entries) = std::fs::read_dir(&parent) {
        for e in entries.filter_map(|e| e.ok()) {
            let name = e.file_name().to_string_lossy().into_owned();
            let pid = name.strip_prefix(&prefix).and_then(|p| p.parse::<u32>().ok());
            if pid.is_some_and(|p| !running(p)) {
                let _ = std::fs::remove_dir_all(e.path()); // left by a killed run
            }
        }
    }
    let staging = parent.join(format!("{prefix}{}", std::process::id()));
    std::fs::create_dir_all(&staging)
        .map_err(io(format!("cannot create the staging directory {}", staging.display())))?;
    *CLAIM.lock().unwrap_or_else(|e| e.into_inner()) = Some(Claim { root, staging });
    Ok(())
}

/// Whether process `pid` still runs (Linux's /proc; elsewhere, taken as ended).
fn running(pid: u32) -> bool {
    pid != std::process::id() && Path::new(&format!("/proc/{pid}")).exists()
}

/// Ends the claim: removes the staging directory.
fn release() {
    if let Some(claim) = CLAIM.lock().unwrap_or_else(|e| e.into_inner()).take() {
        let _ = std::fs::remove_dir_all(claim.staging);
    }
}

/// Holds the claim on an output directory until dropped.
pub struct Claimed(());

impl Claimed {
    /// Claims `dir` (the module documentation says how).
    pub fn new(dir: &Path, force: bool) -> Result<Self> {
        claim(dir, force)?;
        Ok(Self(()))
    }
}

impl Drop for Claimed {
    fn drop(&mut self) {
        release();
    }
}

/// A temporary path for `path`: in the staging directory when `path` is inside the claimed
/// directory, else a hidden name beside `path`. The name keeps `path`'s extension.
pub fn temporary(path: &Path) -> PathBuf {
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let unique =
        format!(".{}-{}-{name}", std::process::id(), COUNTER.fetch_add(1, Ordering::SeqCst));
    let claim = CLAIM.lock().unwrap_or_else(|e| e.into_inner());
    match claim.as_ref() {
        Some(c) if absolute(path).starts_with(&c.root) => c.staging.join(unique),
        _ => path.with_file_name(unique),
    }
}

/// Renames a complete temporary file into place and lists it in the marker.
pub fn commit(temporary: &Path, path: &Path) -> Result<()> {
    if let Err(e) = std::fs::rename(temporary, path) {
        let _ = std::fs::remove_file(temporary);
        return Err(e).map_err(io(format!("cannot write {}", path.display())));
    }
    let claim = CLAIM.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(c) = claim.as_ref()
        && let Ok(rel) = absolute(path).strip_prefix(&c.root)
    {
        let marker = c.root.join(MARKER);
        std::fs::OpenOptions::new()
            .append(true)
            .create(true)
            .open(&marker)
            .and_then(|mut m| writeln!(m, "{}", rel.display()))
            .map_err(io(format!("cannot write {}", marker.display())))?;
    }
    Ok(())
}

fn absolute(path: &Path) -> PathBuf {
    let parent = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let dir = std::fs::canonicalize(parent).unwrap_or_else(|_| parent.to_path_buf());
    dir.join(path.file_name().unwrap_or_default())
}

/// Writes `bytes` to `path` atomically.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    write_atomic_with(path, |out| out.write_all(bytes))
}

/// Writes to `path` atomically what `write` writes to the stream it is given (buffered),
/// so that a large file is never held whole in memory.
pub fn write_atomic_with(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<()> {
    let tmp = temporary(path);
    let written = (|| -> std::io::Result<()> {
        let mut out = std::io::BufWriter::with_capacity(1 << 20, std::fs::File::create(&tmp)?);
        write(&mut out)?;
        out.into_inner().map_err(|e| e.into_error())?.sync_all()
    })();
    if let Err(e) = written {
        let _ = std::fs::remove_file(&tmp);
        return Err(e).map_err(io(format!("cannot write {}", path.display())));
    }
    commit(&tmp, path)
}

/// The files a run writes into its output directory, each atomically, with the wall time
/// each took — making its bytes and writing them \[s\] — under its name (the steps of a
/// series summed under "solution-NNNN.vtu"), in the order written.
pub struct Outputs<'a> {
    /// The output directory.
    pub dir: &'a Path,
    /// The encoding of the .vtu files.
    pub vtu: Encoding,
    seconds: Vec<(String, f64)>,
    /// Files written on a thread of their own while the solve went on, and their time.
    meanwhile: Vec<(String, f64)>,
}

impl<'a> Outputs<'a> {
    /// The files of a run in `dir` (created if needed), the .vtu files in `vtu`.
    pub fn new(dir: &'a Path, vtu: Encoding) -> Result<Self> {
        std::fs::create_dir_all(dir)
            .map_err(io(format!("cannot create the output directory {}", dir.display())))?;
        Ok(Self { dir, vtu, seconds: Vec::new(), meanwhile: Vec::new() })
    }

    /// Writes DIR/`name` with the bytes `make` returns.
    pub fn file(&mut self, name: &str, make: impl FnOnce() -> Result<Vec<u8>>) -> Result<()> {
        self.timed(name, |dir| write_atomic(&dir.join(name), &make()?))
    }

    /// Runs `write`, which writes the files `key` names into the directory it is given.
    pub fn timed(&mut self, key: &str, write: impl FnOnce(&Path) -> Result<()>) -> Result<()> {
        let start = std::time::Instant::now();
        write(self.dir)?;
        let seconds = start.elapsed().as_secs_f64();
        match self.seconds.iter_mut().find(|(k, _)| k == key) {
            Some((_, total)) => *total += seconds,
            None => self.seconds.push((key.to_string(), seconds)),
        }
        Ok(())
    }

    /// Records the files `key` names, written on a thread of their own while the solve went
    /// on, in `seconds` of that thread's time.
    pub fn written_meanwhile(&mut self, key: &str, seconds: f64) {
        self.meanwhile.push((key.to_string(), seconds));
    }

    /// Writes summary.json last: the solve's `summary` of a run of `built` with the run's
    /// timings closed by the files written ([`close_timings`]); returns it.
    pub fn finish(mut self, built: &Built, mut summary: Value) -> Result<Value> {
        close_timings(&mut summary, built, &self.seconds, &self.meanwhile);
        self.file("summary.json", || summary_json(&summary))?;
        Ok(summary)
    }

    /// Writes DIR/solution.vtu: the solution `state` with the extra point fields.
    pub fn solution(
        &mut self,
        problem: &Problem,
        (dofs, x): (&DofMap, &[f64]),
        extra: &[Field],
    ) -> Result<()> {
        let vtu = self.vtu;
        let write =
            |dir: &Path| solution_vtu(problem, (dofs, x), extra, vtu, &dir.join("solution.vtu"));
        self.timed("solution.vtu", write)
    }

    /// The series of a loading path: solution-NNNN.vtu for each of its `steps` (`write(k,
    /// path)` writes step k's, from 0; files numbered from 1; without `write`, written
    /// already) and solution.pvd, which ParaView opens as one animation.
    pub fn series(&mut self, steps: usize, write: Option<&WriteStep>) -> Result<()> {
        let mut collection = Vec::new();
        for k in 0..steps {
            let name = step_name(k);
            if let Some(write) = write {
                self.timed("solution-NNNN.vtu", |dir| write(k, &dir.join(&name)))?;
            }
            collection.push((k + 1, name));
        }
        self.file("solution.pvd", || Ok(pvd(&collection).into_bytes()))
    }
}

/// Writes step k's (from 0) .vtu file of a series at the path given.
pub type WriteStep<'a> = dyn Fn(usize, &Path) -> Result<()> + 'a;

/// The name of the .vtu file of step k (from 0) of a loading path: solution-NNNN.vtu,
/// numbered from 1.
pub fn step_name(k: usize) -> String {
    format!("solution-{:04}.vtu", k + 1)
}

/// Writes DIR/summary.json.
pub fn write_summary(out: &Path, summary: &serde_json::Value) -> Result<()> {
    write_atomic(&out.join("summary.json"), &summary_json(summary)?)
}

/// The bytes of summary.json.
pub fn summary_json(summary: &serde_json::Value) -> Result<Vec<u8>> {
    serde_json::to_vec_pretty(summary)
        .map_err(|e| Error::Input(format!("summary.json cannot be written: {e}")))
}

/// Writes `path` atomically: the solution as a ParaView file, point data u (3 components),
/// phi and `extra`; cell data sigma (3 × 3), D (3 components), material (the index of each
/// cell's, in the case's order) and poling (3 components); its numbers in `encoding`.
pub fn solution_vtu(
    problem: &Problem,
    (dofs, x): (&DofMap, &[f64]),
    extra: &[Field],
    encoding: Encoding,
    path: &Path,
) -> Result<()> {
    let mesh = &problem.mesh;
    let dim = mesh.dim();
    let mut u = Vec::with_capacity(3 * mesh.n_nodes());
    for n in 0..mesh.n_nodes() {
        for i in 0..3 {
            u.push(if i < dim { x[dofs.u(n, i)] } else { 0.0 });
        }
    }
    let phi: Vec<f64> = (0..mesh.n_nodes()).map(|n| x[dofs.phi(n)]).collect();
    let fields = element_fields(problem, dofs, x)?;
    // Each cell's material (its index in the case's order) and poling (material axis 3).
    let materials = &problem.materials;
    let material: Vec<f64> = (0..mesh.n_cells()).map(|c| materials.index_of(c) as f64).collect();
    let poling: Vec<f64> = (0..mesh.n_cells()).flat_map(|c| materials.of(c).poling()).collect();
    let mut points = vec![
        Field { name: "u", components: 3, values: &u },
        Field { name: "phi", components: 1, values: &phi },
    ];
    points.extend(extra.iter().map(|f| Field {
        name: f.name,
        components: f.components,
        values: f.values,
    }));
    let cells = [
        Field { name: "sigma", components: 9, values: fields.sigma.as_flattened() },
        Field { name: "D", components: 3, values: fields.electric_displacement.as_flattened() },
        Field { name: "material", components: 1, values: &material },
        Field { name: "poling", components: 3, values: &poling },
    ];
    write_atomic_with(path, |out| write_vtu(mesh, (&points, &cells), encoding, out))
}
