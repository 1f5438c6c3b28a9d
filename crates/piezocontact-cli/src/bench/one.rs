//! `piezocontact bench --one SPEC`: one measurement in a process of its own, printed as
//! key=value pairs for the parent benchmark — "plain,TARGET" (one factorisation),
//! "contactK,TARGET" (the K-th contact problem of the target), "faer,ROUTES,MESH" (faer's
//! phases beside PETSc's; feature `petsc`).

use super::contact::contact_problems;
use super::{peak_mb, print_figures};
use anyhow::{Result, anyhow};
use piezocontact::case::{Built, Case};
use piezocontact::dofs::DofMap;
use piezocontact::linalg::default_solver;
use piezocontact::output::vtu::Encoding;
use piezocontact::run::Run;
use piezocontact::system::CoupledSystem;
use std::time::Instant;

/// Runs the measurement `spec` names and prints its figures.
pub fn measure_one(spec: &str) -> Result<()> {
    let started = Instant::now();
    let (kind, target) = spec.split_once(',').ok_or_else(|| anyhow!("--one {spec}"))?;
    #[cfg(feature = "petsc")]
    if kind == "faer" {
        let (routes, mesh) = target.split_once(',').ok_or_else(|| anyhow!("--one {spec}"))?;
        return super::petsc::measure_faer(routes, std::path::Path::new(mesh));
    }
    let mut problems = contact_problems(target, &[])?;
    if kind == "plain" {
        let problem = problems.swap_remove(0).1.problem()?;
        let start = Instant::now();
        let mut system =
            CoupledSystem::new(&problem, DofMap::new(&problem)?, &[], default_solver())?;
        let g: Vec<f64> =
            (0..problem.mesh.n_cells()).map(|c| problem.material(c).modulus(0.0)).collect();
        system.factorize(&problem, &g, &[])?;
        let seconds = start.elapsed().as_secs_f64();
        print_figures(&[("seconds", seconds.to_string()), ("peak_mb", peak_mb().to_string())]);
        return Ok(());
    }
    let k: usize = kind.trim_start_matches("contact").parse()?;
    let (_, case) = problems.into_iter().nth(k).ok_or_else(|| anyhow!("--one {spec}"))?;
    contact_run(&case, started)
}

/// A contact run of `case` as `piezocontact run` makes it, from the case's build to its
/// files (written into a temporary directory, removed after), the process started at
/// `started`: its figures, with the solve's wall time and the files'.
fn contact_run(case: &Case, started: Instant) -> Result<()> {
    let built = Built { started, ..case.build()? };
    let run = Run::solve(&built, built.linear_solver()?, &|_| {})?;
    let s = &run.contact().ok_or_else(|| anyhow!("no [contact] table"))?.solution;
    let out = std::env::temp_dir().join(format!("piezocontact-bench-{}", std::process::id()));
    let summary = run.write(&built, &out, Encoding::default());
    let _ = std::fs::remove_dir_all(&out);
    let t = &summary?["timings_seconds"];
    let files: f64 =
        t["files"].as_object().into_iter().flatten().filter_map(|(_, s)| s.as_f64()).sum();
    print_figures(&[
        ("seconds", t["solver"].to_string()),
        ("files", files.to_string()),
        ("total", t["total"].to_string()),
        ("peak_mb", peak_mb().to_string()),
        ("dofs", s.dofs.n_free().to_string()),
        ("condensed", s.condensed_nodes.to_string()),
        ("gamma3", s.surface.len().to_string()),
        ("newton", s.inner_iterations.iter().sum::<usize>().to_string()),
        ("kkt", s.kkt.max.to_string()),
        ("converged", s.converged().to_string()),
    ]);
    Ok(())
}
