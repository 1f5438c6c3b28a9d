//! `piezocontact bench --contact --mesh FILE --backend petsc --linear direct,iterative`, under
//! `mpirun -n N`: the exact solver on the 3D indentation (PV1, and PV2 with µ = 0.3) by each
//! route of the PETSc backend in one run — MUMPS's factor with the problem condensed onto Γ3
//! (direct), the semismooth Newton method on the whole system with GMRES, the field split
//! and GAMG (iterative) —: Newton steps, the Krylov iterations of each linear solve, wall
//! time, each process's peak memory, the KKT residual and each route's answer against the
//! first route's.

use super::contact::contact_problems;
use super::{largest, peak_mb};
use crate::{processes, say};
use anyhow::{Result, anyhow};
use piezocontact::case::Case;
use piezocontact::linalg::petsc;
use piezocontact::run::Run;
use std::path::Path;
use std::time::Instant;

/// One route's contact run, or why it did not run.
struct Row {
    problem: &'static str,
    route: String,
    outcome: std::result::Result<Measured, String>,
}

/// What one route's contact run measured.
struct Measured {
    dofs: usize,
    newton: usize,
    solves: usize,
    krylov: Vec<usize>,
    seconds: f64,
    peak_mb: Vec<f64>,
    kkt: f64,
    converged: bool,
    /// The largest differences of u and of ϕ from the first route's answer, each relative to
    /// the field's largest value (`None` on the first route).
    difference: Option<(f64, f64)>,
}

/// Every route of `linear` on the problems of `mesh` (every process), printed by process 0.
pub fn run(mesh: &Path, linear: &[String]) -> Result<()> {
    // Per route, the problems of the contact benchmark on the mesh (PV1, PV2 µ = 0.3).
    let problems = linear
        .iter()
        .map(|route| {
            let sets = ["solver.backend=\"petsc\"".into(), format!("solver.linear={route:?}")];
            contact_problems(&mesh.display().to_string(), &sets)
        })
        .collect::<Result<Vec<_>>>()?;
    let mut rows = Vec::new();
    for k in 0..problems.first().map_or(0, Vec::len) {
        let mut first: Option<(Vec<f64>, usize)> = None;
        for (route, cases) in linear.iter().zip(&problems) {
            let (problem, case) = &cases[k];
            let outcome = measure(case, &mut first).map_err(|e| e.to_string());
            rows.push(Row { problem, route: route.clone(), outcome });
        }
    }
    if processes::is_root() {
        print(&rows);
    }
    Ok(())
}

/// One contact run of `case` as `piezocontact run` solves it (no files), the peak memory
/// reset before it; its answer compared with `first` (the first route's x and u entries),
/// which it becomes when empty.
fn measure(case: &Case, first: &mut Option<(Vec<f64>, usize)>) -> Result<Measured> {
    piezocontact::limits::reset_peak_resident();
    let start = Instant::now();
    let built = case.build()?;
    let run = Run::solve(&built, built.linear_solver()?, &|_| {})?;
    let seconds = start.elapsed().as_secs_f64();
    let s = &run.contact().ok_or_else(|| anyhow!("no [contact] table"))?.solution;
    let n_u = built.problem.mesh.n_nodes() * built.problem.mesh.dim();
    let difference = first.as_ref().map(|(x, n_u)| {
        let field = |range: std::ops::Range<usize>| {
            let size = range.clone().map(|g| x[g].abs()).fold(0.0, f64::max);
            let most = range.map(|g| (x[g] - s.x[g]).abs()).fold(0.0, f64::max);
            most / size.max(f64::MIN_POSITIVE)
        };
        (field(0..*n_u), field(*n_u..x.len()))
    });
    first.get_or_insert_with(|| (s.x.clone(), n_u));
    Ok(Measured {
        dofs: s.dofs.n_free(),
        newton: s.inner_iterations.iter().sum(),
        solves: s.timings.solver.solve_count,
        krylov: s.timings.linear.krylov_iterations.clone(),
        seconds,
        peak_mb: petsc::gather(peak_mb())?,
        kkt: s.kkt.max,
        converged: s.converged(),
        difference,
    })
}

/// The table, its ratios and its legend.
fn print(rows: &[Row]) {
    say!(
        "{:>11} {:>10} {:>9} {:>7} {:>7} {:>13} {:>9} {:>11} {:>9} {:>9} {:>9}  peak_MB per process",
        "problem",
        "route",
        "DOFs",
        "newton",
        "solves",
        "krylov_max",
        "run_s",
        "kkt",
        "KB/DOF",
        "du",
        "dphi"
    );
    for row in rows {
        let m = match &row.outcome {
            Ok(m) => m,
            Err(e) => {
                say!("{:>11} {:>10} did not run: {e}", row.problem, row.route);
                continue;
            }
        };
        let solving: Vec<usize> = m.krylov.iter().copied().filter(|&k| k > 0).collect();
        let mean = solving.iter().sum::<usize>() as f64 / solving.len().max(1) as f64;
        let krylov = match solving.iter().max() {
            Some(most) => format!("{most} ({mean:.0})"),
            None => "-".to_string(),
        };
        let (du, dphi) = m
            .difference
            .map_or(("-".into(), "-".into()), |(u, p)| (format!("{u:.1e}"), format!("{p:.1e}")));
        let peaks: Vec<String> = m.peak_mb.iter().map(|p| format!("{p:.0}")).collect();
        say!(
            "{:>11} {:>10} {:>9} {:>7} {:>7} {:>13} {:>9.2} {:>11.2e} {:>9.2} {du:>9} {dphi:>9}  {}{}",
            row.problem,
            row.route,
            m.dofs,
            m.newton,
            m.solves,
            krylov,
            m.seconds,
            m.kkt,
            m.peak_mb.iter().sum::<f64>() * 1024.0 / m.dofs as f64,
            peaks.join(" "),
            if m.converged { "" } else { "  NOT CONVERGED" }
        );
    }
    ratios(rows);
    say!(
        "newton: Newton steps; solves: linear solves (iterative: one per Newton step and the solve without contact forces); krylov_max: the most GMRES iterations of one solve (their mean over the solves that iterate; - on the direct route); run_s: the case built and solved as `piezocontact run` solves it, without its files; kkt: the KKT residual of the answer; KB/DOF: the processes' peaks summed, per unknown; du, dphi: the largest difference of u and of ϕ from the first route's answer, each relative to the field's largest value; peak_MB: VmHWM of each process, reset before each run"
    );
}

/// Each route's wall time and largest process peak against the first route's, per problem.
fn ratios(rows: &[Row]) {
    let measured = |row: &Row| row.outcome.as_ref().ok().map(|m| (m.seconds, largest(&m.peak_mb)));
    for pair in rows.chunk_by(|a, b| a.problem == b.problem) {
        let Some(base) = pair.first().and_then(measured) else { continue };
        for row in &pair[1..] {
            if let Some((seconds, peak)) = measured(row) {
                say!(
                    "  {} {} / {}: run_s {:.2}× ({seconds:.2} s / {:.2} s), largest process peak {:.2}× ({peak:.0} MB / {:.0} MB)",
                    row.problem,
                    row.route,
                    pair[0].route,
                    seconds / base.0,
                    base.0,
                    peak / base.1,
                    base.1
                );
            }
        }
    }
}
