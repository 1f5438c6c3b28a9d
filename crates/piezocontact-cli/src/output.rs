//! Writing results: every file goes to a temporary name in its directory and is renamed into
//! place, so a reader never sees a half-written file.

use anyhow::{Context, Result};
use piezocontact::dofs::DofMap;
use piezocontact::output::vtu::{Field, to_vtu};
use piezocontact::problem::Problem;
use piezocontact::solver::element_fields;
use std::io::Write;
use std::path::Path;

/// Writes `bytes` to `path` atomically (temporary file in the same directory, then rename).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let dir = path.parent().unwrap_or(Path::new("."));
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let tmp = dir.join(format!(".{name}.{}.tmp", std::process::id()));
    let result = (|| -> std::io::Result<()> {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result.with_context(|| format!("cannot write {}", path.display()))
}

/// Writes DIR/summary.json and DIR/solution.vtu (with the extra point fields).
pub fn write_results(
    out: &Path,
    summary: &serde_json::Value,
    problem: &Problem,
    dofs: &DofMap,
    x: &[f64],
    extra: &[Field],
) -> Result<()> {
    write_atomic(&out.join("summary.json"), serde_json::to_string_pretty(summary)?.as_bytes())?;
    write_atomic(&out.join("solution.vtu"), solution_vtu(problem, dofs, x, extra)?.as_bytes())
}

/// The solution as a ParaView file: point data u (3 components), phi and `extra`; cell data
/// sigma (3 × 3), D (3 components).
pub fn solution_vtu(
    problem: &Problem,
    dofs: &DofMap,
    x: &[f64],
    extra: &[Field],
) -> Result<String> {
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
    let sigma: Vec<f64> = fields.sigma.iter().flatten().copied().collect();
    let d: Vec<f64> = fields.electric_displacement.iter().flatten().copied().collect();
    let mut points = vec![
        Field { name: "u", components: 3, values: &u },
        Field { name: "phi", components: 1, values: &phi },
    ];
    points.extend(extra.iter().map(|f| Field {
        name: f.name,
        components: f.components,
        values: f.values,
    }));
    Ok(to_vtu(
        mesh,
        &points,
        &[
            Field { name: "sigma", components: 9, values: &sigma },
            Field { name: "D", components: 3, values: &d },
        ],
    ))
}
