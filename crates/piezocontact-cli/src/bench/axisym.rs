//! `piezocontact bench --axisym`: the ball indentation of the library's PZT-5A poled along the
//! axis solved in 3D (meshes/indent-halfspace-fine.msh, a block of half-width 4 standing for
//! a half-space) and as a body of revolution (meshes/indent-axisym-h0.01.msh, a cylinder of
//! radius and height 20), the exact solver on PV1: each force against Hertz's with the
//! indentation modulus C* of the same tensor, and the wall times, the median of 3 interleaved
//! runs of each.

use crate::say;
use anyhow::{Result, anyhow};
use piezocontact::case::{Built, Case};
use piezocontact::linalg::default_solver;
use piezocontact::oracles::Piezoelectric;
use piezocontact::run::Run;
use std::path::Path;
use std::time::Instant;

/// The runs of each side.
const RUNS: usize = 3;

/// The depth of the ball (radius 1) [m].
const DEPTH: f64 = 0.0036;

/// The case of one side: `mesh`, the 2D model `plane` (or none in 3D), the ball's centre.
fn case(mesh: &str, plane: &str, center: &str) -> Result<Built> {
    let file = std::fs::canonicalize(mesh).map_err(|e| anyhow!("{mesh}: {e}"))?;
    let text = format!(
        "[units]\nstress = \"GPa\"\npotential = \"GV\"\n[mesh]\nfile = {:?}\n{plane}\n[material]\npreset = \"PZT-5A\"\n[boundary]\nclamped = [\"bottom\"]\ngrounded = [\"bottom\"]\ncontact = [\"contact\"]\n[contact]\nproblem = \"PV1\"\n[foundation]\nkind = \"sphere\"\ncenter = {center}\nradius = 1.0\n[solver]\nmethod = \"newton\"\nmax_condensed = 3000\n",
        file.display().to_string()
    );
    Ok(Case::from_text(Path::new("bench-axisym.toml"), &text, &[])?.build()?)
}

/// Measures and prints both sides and the ratio of their wall times.
pub fn run() -> Result<()> {
    let top = 1.0 - DEPTH;
    let sides = [
        (
            "3D",
            "meshes/indent-halfspace-fine.msh",
            case("meshes/indent-halfspace-fine.msh", "", &format!("[0.0, 0.0, {top}]"))?,
        ),
        (
            "axisymmetric",
            "meshes/indent-axisym-h0.01.msh",
            case(
                "meshes/indent-axisym-h0.01.msh",
                "plane = \"axisymmetric\"",
                &format!("[0.0, {top}]"),
            )?,
        ),
    ];
    let modulus = Piezoelectric::of(sides[0].2.problem.material(0)).indentation()?.insulating;
    let hertz = 4.0 / 3.0 * modulus * DEPTH.powf(1.5);
    let mut seconds = [Vec::new(), Vec::new()];
    let mut figures = Vec::new();
    for run in 0..RUNS {
        for (k, (_, _, built)) in sides.iter().enumerate() {
            let start = Instant::now();
            let Run::Contact(solved) = Run::solve(built, default_solver(), &|_| {})? else {
                return Err(anyhow!("the benchmark's case is no single contact run"));
            };
            seconds[k].push(start.elapsed().as_secs_f64());
            if run == 0 {
                let dim = built.problem.mesh.dim();
                let force = -solved.solution.balance.contact[dim - 1];
                figures.push((solved.solution.dofs.n_free(), force, solved.solution.kkt.max));
            }
        }
    }
    let medians = seconds.map(|mut s| {
        s.sort_by(f64::total_cmp);
        s[s.len() / 2]
    });
    say!(
        "a ball (R = 1 m) pressed {DEPTH} m into the library's PZT-5A poled along the axis, PV1, exact solver; Hertz with C* = {modulus:.4} GPa: {hertz:.5e} GPa·m² (median of {RUNS} interleaved runs):"
    );
    for (((name, mesh, _), median), (dofs, force, kkt)) in sides.iter().zip(medians).zip(figures) {
        say!(
            "  {name:<13} {mesh:<34} {dofs:>8} free DOFs  force {force:.5e}  force / Hertz − 1 = {:+.4}  KKT {kkt:.1e}  wall {median:.4} s",
            force / hertz - 1.0
        );
    }
    say!("  3D / axisymmetric wall time {:.1}", medians[0] / medians[1]);
    Ok(())
}
