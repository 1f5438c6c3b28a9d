//! `piezocontact bench --mesh FILE --backend petsc`, under `mpirun -n N`: the PETSc + MUMPS
//! backend's phases on the mesh's coupled system, per process, beside faer's LDLᵀ of the same
//! matrix (nested dissection on every thread) in a process of its own started by process 0
//! after PETSc's part, so that the two do not share the cores.

use super::mesh_case;
use super::{factorised_once, in_child, peak_mb, print_figures};
use crate::{processes, say};
use anyhow::Result;
use piezocontact::linalg::petsc::{self, PetscSolver};
use piezocontact::linalg::{LdltSolver, LinearSolver, Ordering};
use piezocontact::problem::Problem;
use std::path::Path;

/// The phases of one backend: pattern, assembly, analysis, factorisation, solve [s], the
/// factor's entries and the peak memory of each process [MB].
struct Phases {
    pattern: f64,
    assembly: f64,
    analysis: f64,
    numeric: f64,
    solve: f64,
    factor_len: usize,
    peak_mb: Vec<f64>,
}

/// The PETSc rows (every process), then faer's (process 0 starts it), printed by process 0.
pub fn run(mesh: &Path) -> Result<()> {
    let (petsc, dofs) = measure_petsc(mesh)?;
    if !processes::is_root() {
        return Ok(());
    }
    let faer = measure_faer_apart(mesh)?;
    say!(
        "{:>10} {:>9} {:>9} {:>10} {:>11} {:>11} {:>11} {:>9} {:>12}  peak_MB per process",
        "backend",
        "processes",
        "DOFs",
        "pattern_s",
        "assembly_s",
        "analysis_s",
        "numeric_s",
        "solve_s",
        "len(L)"
    );
    for (name, p) in [("petsc", &petsc), ("faer", &faer)] {
        let peaks: Vec<String> = p.peak_mb.iter().map(|m| format!("{m:.0}")).collect();
        let n = if name == "petsc" { processes::size() } else { 1 };
        say!(
            "{name:>10} {n:>9} {dofs:>9} {:>10.3} {:>11.3} {:>11.3} {:>11.3} {:>9.4} {:>12}  {}",
            p.pattern,
            p.assembly,
            p.analysis,
            p.numeric,
            p.solve,
            p.factor_len,
            peaks.join(" ")
        );
    }
    say!(
        "  petsc/faer: numeric {:.2}× ({:.3} s / {:.3} s), solve {:.2}×, largest process peak {:.2}× ({:.0} MB / {:.0} MB)",
        petsc.numeric / faer.numeric,
        petsc.numeric,
        faer.numeric,
        petsc.solve / faer.solve,
        max(&petsc.peak_mb) / max(&faer.peak_mb),
        max(&petsc.peak_mb),
        max(&faer.peak_mb)
    );
    say!(
        "pattern_s, assembly_s: process 0's pattern and assembly of its nodes' rows; analysis_s: MUMPS's analysis with the owned rows' map (faer: nested dissection's); numeric_s: the hand-over of the owned rows to PETSc's MPIAIJ matrix and MUMPS's LDLᵀ (faer: its LDLᵀ on {} threads); peak_MB: VmHWM of each process",
        rayon::current_num_threads()
    );
    Ok(())
}

fn max(values: &[f64]) -> f64 {
    values.iter().fold(0.0, |m, v| m.max(*v))
}

/// The PETSc backend's phases on every process (peak memories gathered on process 0) and
/// the order of the system.
fn measure_petsc(mesh: &Path) -> Result<(Phases, usize)> {
    let problem = mesh_case(mesh)?.problem()?;
    let (mut phases, dofs) = measure(&problem, Box::new(PetscSolver::new()?))?;
    phases.peak_mb = petsc::gather(peak_mb())?;
    Ok((phases, dofs))
}

/// Pattern, assembly, analysis, one factorisation and one solve with `solver`.
fn measure(problem: &Problem, solver: Box<dyn LinearSolver>) -> Result<(Phases, usize)> {
    let (system, dof_map) = factorised_once(problem, solver)?;
    let timings = system.timings();
    let phases = Phases {
        pattern: dof_map + timings.pattern,
        assembly: timings.assembly,
        analysis: timings.solver.symbolic_seconds,
        numeric: timings.solver.numeric_seconds,
        solve: timings.solver.solve_seconds,
        factor_len: timings.solver.factor_len,
        peak_mb: vec![peak_mb()],
    };
    Ok((phases, system.dofs().n_free()))
}

/// faer's phases on the same mesh, in a process of its own (`bench --one faer,MESH`), its
/// environment cleared of mpirun's so that it runs alone.
fn measure_faer_apart(mesh: &Path) -> Result<Phases> {
    let figures = in_child(&format!("faer,{}", mesh.display()), true)?;
    Ok(Phases {
        pattern: figures.get("pattern")?,
        assembly: figures.get("assembly")?,
        analysis: figures.get("analysis")?,
        numeric: figures.get("numeric")?,
        solve: figures.get("solve")?,
        factor_len: figures.get("factor_len")? as usize,
        peak_mb: vec![figures.get("peak_mb")?],
    })
}

/// `bench --one faer,MESH`: faer's phases with nested dissection on every thread, printed as
/// key=value pairs.
pub fn measure_faer(mesh: &Path) -> Result<()> {
    let problem = mesh_case(mesh)?.problem()?;
    let solver = LdltSolver::with_ordering(Ordering::NestedDissection);
    let (p, _) = measure(&problem, Box::new(solver))?;
    print_figures(&[
        ("pattern", p.pattern.to_string()),
        ("assembly", p.assembly.to_string()),
        ("analysis", p.analysis.to_string()),
        ("numeric", p.numeric.to_string()),
        ("solve", p.solve.to_string()),
        ("factor_len", p.factor_len.to_string()),
        ("peak_mb", peak_mb().to_string()),
    ]);
    Ok(())
}
