//! `piezocontact bench --mesh FILE --backend petsc [--linear direct,iterative]`, under
//! `mpirun -n N`: the PETSc backend's phases on the mesh's coupled system, per process — by
//! MUMPS's LDLᵀ (direct) and by GMRES with the field split and GAMG (iterative) —, and
//! with the direct route faer's LDLᵀ of the same matrix (nested dissection on every thread)
//! in a process of its own started by process 0 after PETSc's part, so that the two do not
//! share the cores.

use super::{
    factorised_once, in_child, largest, mesh_case, mesh_case_with, mesh_parts, peak_mb,
    print_figures,
};
use crate::{processes, say};
use anyhow::{Result, bail};
use piezocontact::case::Case;
use piezocontact::linalg::petsc::{self, PetscSolver};
use piezocontact::linalg::{LdltSolver, LinearSolver, Ordering};
use piezocontact::problem::Problem;
use std::path::Path;

/// The phases of one backend: pattern, assembly, analysis, factorisation (the
/// preconditioner's setup on the iterative route), solve [s], the factor's entries, the
/// Krylov iterations of the solve and the peak memory of each process [MB].
struct Phases {
    pattern: f64,
    assembly: f64,
    analysis: f64,
    numeric: f64,
    solve: f64,
    factor_len: usize,
    krylov: usize,
    peak_mb: Vec<f64>,
}

impl Phases {
    /// Every phase [s].
    fn total(&self) -> f64 {
        self.pattern + self.assembly + self.analysis + self.numeric + self.solve
    }
}

/// The PETSc rows of each route in `linear` ("direct", "iterative"; every process), then,
/// beside the direct route, faer's (process 0 starts it), printed by process 0.
pub fn run(mesh: &Path, linear: &[String]) -> Result<()> {
    let problem = bench_case(mesh, linear)?.problem()?;
    let mut rows = Vec::new();
    for route in linear {
        let (phases, dofs) = measure_petsc(&problem, route)?;
        rows.push((format!("petsc {route}"), phases, dofs));
    }
    if !processes::is_root() {
        return Ok(());
    }
    let dofs = rows.first().map_or(0, |r| r.2);
    if linear.iter().any(|r| r == "direct") {
        rows.push(("faer".into(), measure_faer_apart(mesh, linear)?, dofs));
    }
    say!(
        "{:>16} {:>9} {:>9} {:>10} {:>11} {:>11} {:>11} {:>9} {:>12} {:>7} {:>9}  peak_MB per process",
        "backend",
        "processes",
        "DOFs",
        "pattern_s",
        "assembly_s",
        "analysis_s",
        "numeric_s",
        "solve_s",
        "len(L)",
        "krylov",
        "KB/DOF"
    );
    for (name, p, dofs) in &rows {
        let peaks: Vec<String> = p.peak_mb.iter().map(|m| format!("{m:.0}")).collect();
        let n = if name == "faer" { 1 } else { processes::size() };
        say!(
            "{name:>16} {n:>9} {dofs:>9} {:>10.3} {:>11.3} {:>11.3} {:>11.3} {:>9.4} {:>12} {:>7} {:>9.2}  {}",
            p.pattern,
            p.assembly,
            p.analysis,
            p.numeric,
            p.solve,
            p.factor_len,
            p.krylov,
            p.peak_mb.iter().sum::<f64>() * 1024.0 / *dofs as f64,
            peaks.join(" ")
        );
    }
    ratios(&rows);
    say!(
        "pattern_s, assembly_s: process 0's pattern and assembly of its nodes' rows; analysis_s: MUMPS's analysis with the owned rows' map (faer: nested dissection's; iterative: PETSc's numbering alone); numeric_s: the hand-over of the owned rows to PETSc's MPIAIJ matrix and MUMPS's LDLᵀ (iterative: GAMG's setup on each field; faer: its LDLᵀ on {} threads); solve_s: one solve (iterative: GMRES to a relative residual of 1e-10, its iterations under krylov); KB/DOF: the processes' peaks summed, per unknown; peak_MB: VmHWM of each process, reset before each route",
        rayon::current_num_threads()
    );
    Ok(())
}

/// The ratios of the rows to the first (PETSc's first route): every phase's time and the
/// largest process peak.
fn ratios(rows: &[(String, Phases, usize)]) {
    let Some((first, base, _)) = rows.first() else { return };
    for (name, p, _) in &rows[1..] {
        say!(
            "  {name} / {first}: all phases {:.2}× ({:.3} s / {:.3} s), largest process peak {:.2}× ({:.0} MB / {:.0} MB)",
            p.total() / base.total(),
            p.total(),
            base.total(),
            largest(&p.peak_mb) / largest(&base.peak_mb),
            largest(&p.peak_mb),
            largest(&base.peak_mb)
        );
    }
}

/// The case of the bench on `mesh`: with the parts "bottom" and "contact" of
/// meshes/indent-3d.geo, the block clamped and grounded at its bottom with its contact patch
/// pressed 0.02 down (an indentation's linear system, with the load a Krylov solve needs);
/// else every boundary part clamped and grounded, which leaves no load and is refused on the
/// iterative route (its solve would take no iteration).
fn bench_case(mesh: &Path, linear: &[String]) -> Result<Case> {
    let parts = mesh_parts(mesh)?;
    if !["bottom", "contact"].iter().all(|name| parts.iter().any(|p| p == name)) {
        if linear.iter().any(|r| r == "iterative") {
            bail!(
                "{}: bench --linear iterative needs a mesh with the parts \"bottom\" and \"contact\" of meshes/indent-3d.geo (the patch is pressed down: a clamped mesh has no load)",
                mesh.display()
            );
        }
        return mesh_case(mesh);
    }
    let pressed =
        "[[boundary.support]]\nparts = [\"contact\"]\nfix = [\"z\"]\ndisplacement = [-0.02]\n";
    mesh_case_with(mesh, &format!("clamped = [\"bottom\"]\ngrounded = [\"bottom\"]\n{pressed}"))
}

/// The PETSc backend's phases on `route` ("direct": MUMPS; "iterative": the Krylov route),
/// on every process (the peak memories, reset before, gathered on process 0), and the
/// order of the system.
fn measure_petsc(problem: &Problem, route: &str) -> Result<(Phases, usize)> {
    let solver = match route {
        "iterative" => PetscSolver::iterative(petsc::KRYLOV_RTOL, petsc::KRYLOV_MAX_ITERATIONS)?,
        _ => PetscSolver::new()?,
    };
    if !piezocontact::limits::reset_peak_resident() && processes::is_root() {
        crate::say_err!(
            "note: the peak memory could not be reset (/proc/self/clear_refs): the {route} route's peak includes the routes' before it"
        );
    }
    let (mut phases, dofs) = measure(problem, Box::new(solver))?;
    phases.peak_mb = petsc::gather(phases.peak_mb[0])?;
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
        krylov: timings.linear.krylov_iterations.iter().sum(),
        peak_mb: vec![peak_mb()],
    };
    Ok((phases, system.dofs().n_free()))
}

/// faer's phases on the same mesh, in a process of its own (`bench --one faer,MESH` with
/// `linear`, which chooses the case), its environment cleared of mpirun's so that it runs
/// alone.
fn measure_faer_apart(mesh: &Path, linear: &[String]) -> Result<Phases> {
    let figures = in_child(&format!("faer,{},{}", linear.join("+"), mesh.display()), true)?;
    Ok(Phases {
        pattern: figures.get("pattern")?,
        assembly: figures.get("assembly")?,
        analysis: figures.get("analysis")?,
        numeric: figures.get("numeric")?,
        solve: figures.get("solve")?,
        factor_len: figures.get("factor_len")? as usize,
        krylov: 0,
        peak_mb: vec![figures.get("peak_mb")?],
    })
}

/// `bench --one faer,ROUTES,MESH`: faer's phases with nested dissection on every thread on
/// the case of the routes ("direct+iterative"), printed as key=value pairs.
pub fn measure_faer(routes: &str, mesh: &Path) -> Result<()> {
    let linear: Vec<String> = routes.split('+').map(String::from).collect();
    let problem = bench_case(mesh, &linear)?.problem()?;
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
