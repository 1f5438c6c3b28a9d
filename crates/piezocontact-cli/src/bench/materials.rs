//! `piezocontact bench --materials`: the assembly of B̌ on one mesh with one material and with
//! four materials by region (the quadrants of its bounding box in x and y, `[mesh.regions]`
//! boxes), all four stiffness tensors as the one is, so that only the number of materials
//! differs; the same binary, the two interleaved, the median of 5 of each.

use super::mesh_case;
use crate::say;
use anyhow::Result;
use piezocontact::assembly::{Assembler, secant_moduli};
use piezocontact::case::Case;
use piezocontact::dofs::DofMap;
use piezocontact::problem::Problem;
use std::path::Path;
use std::time::Instant;

/// The runs of each side.
const RUNS: usize = 5;

/// The four presets of the regions; the lone material is the first.
const PRESETS: [&str; 4] = ["PZT-5A", "PZT-4", "PZT-5H", "BaTiO3"];

/// Measures and prints both sides and their ratio.
pub fn run(mesh: &Path) -> Result<()> {
    let base = mesh_case(mesh)?;
    let one = with_materials(&base, None)?;
    let four = with_materials(&base, Some(&one))?;
    let sides = [("one material", &one), ("four materials", &four)];
    let mut assemblers = Vec::new();
    for (_, problem) in sides {
        let dofs = DofMap::new(problem)?;
        let zero = vec![0.0; dofs.n_total()];
        let moduli = secant_moduli(problem, &dofs, &zero)?;
        assemblers.push((Assembler::new(problem, dofs, &[], None)?, moduli));
    }
    let mut seconds = [Vec::new(), Vec::new()];
    for _ in 0..RUNS {
        for (k, (_, problem)) in sides.iter().enumerate() {
            let (assembler, moduli) = &assemblers[k];
            let start = Instant::now();
            std::hint::black_box(assembler.matrix(problem, moduli, &[])?);
            seconds[k].push(start.elapsed().as_secs_f64());
        }
    }
    let medians = seconds.map(|mut s| {
        s.sort_by(f64::total_cmp);
        s[RUNS / 2]
    });
    say!(
        "{}: {} cells, assembly of B̌ (median of {RUNS} interleaved runs)",
        mesh.display(),
        one.mesh.n_cells()
    );
    for ((name, problem), median) in sides.iter().zip(medians) {
        let counts = problem.materials.cell_counts(problem.mesh.n_cells());
        say!("  {name:<15} {median:.4} s  (cells per material {counts:?})");
    }
    say!("  four / one      {:.3} (target ≤ 1.1)", medians[1] / medians[0]);
    Ok(())
}

/// The problem of `base` with the lone preset, or (`quadrants` of the lone one's mesh) the
/// four presets on the quadrants of its bounding box.
fn with_materials(base: &Case, quadrants: Option<&Problem>) -> Result<Problem> {
    let mut text = base.origin.text.clone();
    let start = text.find("[material]").expect("the bench's case has a [material] table");
    let end = text[start..].find("[boundary]").map_or(text.len(), |k| start + k);
    let materials = match quadrants {
        None => format!("[material]\npreset = \"{}\"\n", PRESETS[0]),
        Some(problem) => {
            let (lo, hi) = problem.mesh.bounding_box();
            let mid: Vec<f64> = lo.iter().zip(&hi).map(|(a, b)| 0.5 * (a + b)).collect();
            let mut tables = String::from("[mesh.regions]\n");
            for (k, (x, y)) in [(0, 0), (1, 0), (0, 1), (1, 1)].iter().enumerate() {
                let range = |i: usize, half: usize| {
                    if half == 0 {
                        format!("[{},{}]", lo[i], mid[i])
                    } else {
                        format!("[{},{}]", mid[i], hi[i])
                    }
                };
                tables += &format!(
                    "q{k} = [\"{}x{}x[{},{}]\"]\n",
                    range(0, *x),
                    range(1, *y),
                    lo[2],
                    hi[2]
                );
            }
            for (k, preset) in PRESETS.iter().enumerate() {
                tables += &format!(
                    "[[material]]\nname = \"m{k}\"\nregions = [\"q{k}\"]\npreset = \"{preset}\"\n"
                );
            }
            tables
        }
    };
    text.replace_range(start..end, &materials);
    let case = Case::from_text(&base.origin.path, &text, &[])?;
    Ok(case.problem()?)
}
