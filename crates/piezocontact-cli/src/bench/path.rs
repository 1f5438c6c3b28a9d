//! `piezocontact bench --path`: a loading path solved as a path — each step from the last,
//! the analysis, the factorisation and the condensation kept — against the same steps solved
//! cold, one solve each, in the same process.

use anyhow::{Result, anyhow, bail};
use piezocontact::algorithm::ContactSolver;
use piezocontact::case::Case;
use piezocontact::run::Run;
use std::path::Path;
use std::time::Instant;

/// Times the path of `case_file` (`mesh` replacing its mesh) and its steps solved cold.
pub fn path(case_file: &Path, mesh: Option<&Path>) -> Result<()> {
    let mut overrides = Vec::new();
    if let Some(mesh) = mesh {
        let file =
            std::fs::canonicalize(mesh).map_err(|e| anyhow!("--mesh {}: {e}", mesh.display()))?;
        overrides.push(format!("mesh.file={:?}", file.display().to_string()));
    }
    let built = Case::load(case_file, &overrides)?.build()?;
    let (Some(model), Some(loading)) = (&built.model, &built.loading) else {
        bail!("{}: bench --path needs a [contact] and a [loading] table", case_file.display());
    };
    let start = Instant::now();
    let Run::Path(path) = Run::solve(&built, built.linear_solver()?, &|_| {})? else {
        bail!("{}: the case did not run as a loading path", case_file.display());
    };
    let path_seconds = start.elapsed().as_secs_f64();
    if let Some(failure) = &path.failure {
        bail!("{}: {failure}", case_file.display());
    }
    let start = Instant::now();
    let (mut factorisations, mut newton, mut difference) = (0, 0, 0.0_f64);
    for (step, row) in loading.steps.iter().zip(&path.curve) {
        let (problem, model) = (&built.problem, loading.model_at(model, step));
        let mut solver =
            ContactSolver::new(problem, &model, &built.settings, built.linear_solver()?)?;
        let s = solver.solve(problem, &model, step.load_factor, &|_| {})?;
        factorisations += s.timings.solver.numeric_count;
        newton += s.inner_iterations.iter().sum::<usize>();
        let force: f64 = s.balance.contact.iter().map(|f| f * f).sum::<f64>().sqrt();
        let path_force: f64 = row.force.iter().map(|f| f * f).sum::<f64>().sqrt();
        difference = difference.max((force - path_force).abs() / force.max(f64::MIN_POSITIVE));
    }
    let cold_seconds = start.elapsed().as_secs_f64();
    let t = path.last.solution.timings;
    let path_newton: usize = path.curve.iter().map(|r| r.newton_steps).sum();
    crate::say!(
        "{}: {} steps, {} unknowns",
        case_file.display(),
        path.curve.len(),
        path.last.solution.dofs.n_free()
    );
    crate::say!("{:>6} {:>9} {:>15} {:>13}", "", "wall_s", "factorisations", "newton_steps");
    crate::say!(
        "{:>6} {:>9.3} {:>15} {:>13}",
        "path",
        path_seconds,
        t.solver.numeric_count,
        path_newton
    );
    crate::say!("{:>6} {:>9.3} {:>15} {:>13}", "cold", cold_seconds, factorisations, newton);
    crate::say!(
        "path / cold: {:.3} (wall time); largest relative difference of the force between a path step and its cold solve {difference:.1e}",
        path_seconds / cold_seconds
    );
    Ok(())
}
