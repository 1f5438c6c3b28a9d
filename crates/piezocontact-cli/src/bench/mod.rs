//! `piezocontact bench`: the measured figures behind the project's performance targets.
//!
//! - [`factorisation`]: assembly, symbolic, numeric and solve times of the coupled system on
//!   the paper's rectangle or a Gmsh mesh, per ordering and thread count, beside faer's bare
//!   LDLᵀ of the same matrix (the floor);
//! - [`contact`]: a contact solve against one plain factorisation of the same mesh, each in a
//!   process of its own;
//! - [`path`]: a loading path solved as a path against its steps solved cold;
//! - [`materials`]: the assembly with one material and with four by region;
//! - [`axisym`]: the ball indentation in 3D and as a body of revolution;
//! - [`quarter`]: the quarter model against the whole block, and rollers against a clamp;
//! - [`electrodes`]: the indentation with its top face floating against the same grounded;
//! - `petsc` (feature `petsc`): the PETSc + MUMPS backend under mpirun beside faer;
//! - `petsc_contact` (feature `petsc`): the exact solver on each route of the PETSc backend;
//! - [`one`]: `bench --one SPEC`, one measurement of the above in a child process.
//!
//! This file holds what they share, and they depend on it alone: the benchmark cases (the
//! paper's bar at a size "NXxNY", a Gmsh mesh with every boundary part clamped and grounded),
//! one factorisation and solve, the peak memory, and the protocol of `bench --one` — a child
//! process that prints its figures as key=value pairs. It imports none of them.

pub mod axisym;
pub mod contact;
pub mod electrodes;
pub mod factorisation;
pub mod materials;
pub mod one;
pub mod path;
#[cfg(feature = "petsc")]
pub mod petsc;
#[cfg(feature = "petsc")]
pub mod petsc_contact;
pub mod quarter;

use anyhow::{Result, anyhow, bail};
use piezocontact::assembly::secant_moduli;
use piezocontact::case::Case;
use piezocontact::dofs::DofMap;
use piezocontact::linalg::LinearSolver;
use piezocontact::problem::Problem;
use piezocontact::system::CoupledSystem;
use std::path::Path;
use std::process::Command;
use std::time::Instant;

/// Example 7.1 of the paper (PV1).
pub const PAPER_CASE: &str = include_str!("../../../../cases/paper-7.1.toml");
/// Example 7.2 of the paper (PV2).
pub const PAPER_PV2: &str = include_str!("../../../../cases/paper-7.2.toml");
/// The 3D indentation case.
pub const INDENTATION: &str = include_str!("../../../../cases/indentation-3d.toml");

/// The material of the paper's case, for meshes from files.
const MATERIAL: &str = "[material]
young = 58.7102
poisson = 0.3912
e32 = -5.4
e33 = 15.8
e24 = 12.3
eps0 = 8.885e-3
beta22_rel = 916
beta33_rel = 830
";

/// A case around a Gmsh mesh: every boundary part clamped and grounded, the paper's
/// material: the matrix has the structure of every run on that mesh.
pub fn mesh_case(path: &Path) -> Result<Case> {
    let parts = mesh_parts(path)?;
    mesh_case_with(path, &format!("clamped = {parts:?}\ngrounded = {parts:?}\n"))
}

/// The names of the boundary parts of the Gmsh mesh at `path` (an error where it has none).
pub fn mesh_parts(path: &Path) -> Result<Vec<String>> {
    let bytes = std::fs::read(path).map_err(|e| anyhow!("cannot read {}: {e}", path.display()))?;
    let mesh =
        piezocontact::mesh::gmsh::read(&bytes).map_err(|e| anyhow!("{}: {e}", path.display()))?;
    let parts: Vec<String> = mesh.parts().iter().map(|p| p.name.clone()).collect();
    if parts.is_empty() {
        bail!(
            "{}: the mesh has no boundary parts (physical groups of dimension d − 1)",
            path.display()
        );
    }
    Ok(parts)
}

/// A case on the Gmsh mesh at `path` with the paper's material and the `[boundary]` table's
/// lines `boundary`.
pub fn mesh_case_with(path: &Path, boundary: &str) -> Result<Case> {
    let file = std::fs::canonicalize(path).map_err(|e| anyhow!("{}: {e}", path.display()))?;
    let text = format!(
        "[mesh]\nfile = {:?}\n{MATERIAL}[boundary]\n{boundary}",
        file.display().to_string()
    );
    Ok(Case::from_text(Path::new("bench.toml"), &text, &[])?)
}

/// Parses "NXxNY".
pub fn parse_size(size: &str) -> Result<(usize, usize)> {
    let (nx, ny) = size
        .split_once('x')
        .and_then(|(a, b)| Some((a.parse::<usize>().ok()?, b.parse::<usize>().ok()?)))
        .ok_or_else(|| anyhow!("--sizes: '{size}' is not NXxNY, e.g. 384x64"))?;
    if nx == 0 || ny == 0 {
        bail!("--sizes: '{size}' needs at least one cell each way");
    }
    Ok((nx, ny))
}

/// A paper case (`text`) on an nx × ny mesh with more overrides.
pub fn paper_case(text: &str, nx: usize, ny: usize, extra: &[String]) -> Result<Case> {
    let mut overrides = vec![format!("mesh.nx={nx}"), format!("mesh.ny={ny}")];
    overrides.extend_from_slice(extra);
    Ok(Case::from_text(Path::new("cases/paper.toml"), text, &overrides)?)
}

/// Numbers the DOFs, assembles, analyses, factorises at x = 0 and solves once with `solver`;
/// returns the system and the seconds of the DOF map (the part of the pattern the system
/// does not time).
pub fn factorised_once(
    problem: &Problem,
    solver: Box<dyn LinearSolver>,
) -> Result<(CoupledSystem, f64)> {
    let t = Instant::now();
    let dofs = DofMap::new(problem)?;
    let dof_map = t.elapsed().as_secs_f64();
    let mut system = CoupledSystem::new(problem, dofs, &[], solver)?;
    let zero = vec![0.0; system.dofs().n_total()];
    let g = secant_moduli(problem, system.dofs(), &zero)?;
    system.factorize(problem, &g, &[])?;
    system.solve(None)?;
    Ok((system, dof_map))
}

/// The numeric factorisation of the systems of two cases at x = 0: the median time of
/// `runs` interleaved factorisations of each \[s\] and its factor's entries, printed on a
/// line per side named by `names`.
pub fn numeric_times(
    sides: &[piezocontact::case::Built; 2],
    names: [&str; 2],
    runs: usize,
) -> Result<[(f64, f64); 2]> {
    let mut systems = Vec::new();
    for built in sides {
        let (system, _) = factorised_once(&built.problem, piezocontact::linalg::default_solver())?;
        let zero = vec![0.0; system.dofs().n_total()];
        let moduli = secant_moduli(&built.problem, system.dofs(), &zero)?;
        systems.push((system, moduli));
    }
    let mut seconds = [Vec::new(), Vec::new()];
    for _ in 0..runs {
        for (k, (system, moduli)) in systems.iter_mut().enumerate() {
            let before = system.solver_stats().numeric_seconds;
            system.factorize(&sides[k].problem, moduli, &[])?;
            seconds[k].push(system.solver_stats().numeric_seconds - before);
        }
    }
    let medians = seconds.map(median);
    let mut out = [(0.0, 0.0); 2];
    for (k, name) in names.iter().enumerate() {
        let stats = systems[k].0.solver_stats();
        let entries = stats.factor_len as f64;
        out[k] = (medians[k], entries);
        crate::say!(
            "  {name:<22} {:>8} free DOFs  factor {entries:.3e} entries  numeric {:.4} s  {:.3} ns per entry",
            systems[k].0.dofs().n_free(),
            medians[k],
            1e9 * medians[k] / entries
        );
    }
    Ok(out)
}

/// Runs the contact cases `sides` `runs` times each, interleaved: the median wall time of
/// each \[s\], and each side's last run (an error where a side is no single contact run).
pub fn contact_walls(
    sides: &[piezocontact::case::Built; 2],
    runs: usize,
) -> Result<([f64; 2], Vec<piezocontact::run::ContactRun>)> {
    let mut seconds = [Vec::new(), Vec::new()];
    let mut last = Vec::new();
    for run in 0..runs {
        for (k, built) in sides.iter().enumerate() {
            let start = Instant::now();
            let solved = piezocontact::run::Run::solve(
                built,
                piezocontact::linalg::default_solver(),
                &|_| {},
            )?;
            seconds[k].push(start.elapsed().as_secs_f64());
            let piezocontact::run::Run::Contact(solved) = solved else {
                bail!("{}: no single contact run", built.origin.path.display());
            };
            if run + 1 == runs {
                last.push(solved);
            }
        }
    }
    Ok((seconds.map(median), last))
}

/// The median of `s` (the upper one of an even count).
pub fn median(mut s: Vec<f64>) -> f64 {
    s.sort_by(f64::total_cmp);
    s[s.len() / 2]
}

/// The largest of `values` (0 for none: they are sizes and times).
pub fn largest(values: &[f64]) -> f64 {
    values.iter().fold(0.0, |m, v| m.max(*v))
}

/// Peak resident memory of this process, in MiB (0 where the system does not say).
pub fn peak_mb() -> f64 {
    piezocontact::limits::peak_resident_bytes().map_or(0.0, |b| b / 1024.0 / 1024.0)
}

/// The figures a child process printed.
pub struct Figures(Vec<(String, String)>);

impl Figures {
    /// The figure `key`, an error naming it when the child did not print it.
    pub fn get(&self, key: &str) -> Result<f64> {
        self.0
            .iter()
            .find(|(k, _)| k == key)
            .and_then(|(_, v)| v.parse().ok())
            .ok_or_else(|| anyhow!("the measurement printed no {key}"))
    }
}

/// Prints `figures` as the key=value line a parent reads.
pub fn print_figures(figures: &[(&str, String)]) {
    let line: Vec<String> = figures.iter().map(|(k, v)| format!("{k}={v}")).collect();
    crate::say!("{}", line.join(" "));
}

/// Runs `bench --one spec` in a process of its own and reads its figures; `alone` clears
/// mpirun's environment so that the child runs outside the parent's MPI job.
pub fn in_child(spec: &str, alone: bool) -> Result<Figures> {
    let mut command = Command::new(std::env::current_exe()?);
    command.args(["bench", "--one", spec]);
    if alone {
        for (key, _) in std::env::vars() {
            if key.starts_with("OMPI_") || key.starts_with("PMIX_") || key.starts_with("OPAL_") {
                command.env_remove(key);
            }
        }
    }
    let out = command.output()?;
    if !out.status.success() {
        bail!("{spec}: {}", String::from_utf8_lossy(&out.stderr).trim());
    }
    Ok(Figures(
        String::from_utf8_lossy(&out.stdout)
            .split_whitespace()
            .filter_map(|kv| kv.split_once('=').map(|(k, v)| (k.to_string(), v.to_string())))
            .collect(),
    ))
}
