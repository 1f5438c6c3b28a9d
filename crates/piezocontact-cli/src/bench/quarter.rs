//! `piezocontact bench --quarter`: the quarter model of cases/indentation-quarter.toml on
//! a quarter mesh against the whole block on its mirror (meshes/mirror-quarter.py), the
//! exact solver on PV2 (µ = 0.3) in wall time; and on the quarter, the factorisation of the
//! system held by a clamp at the bottom against the same held by rollers (the bottom along z
//! only): the factor's entries and the numeric factorisation's time per entry. The same
//! binary, the sides interleaved, the median of 5 of each.

use super::{contact_walls, numeric_times};
use crate::say;
use anyhow::{Result, anyhow};
use piezocontact::case::{Built, Case};
use std::path::Path;

/// The runs of each side.
const RUNS: usize = 5;

/// The quarter model's case.
const QUARTER: &str = include_str!("../../../../cases/indentation-quarter.toml");

/// The clamp of the bottom in [`QUARTER`], which the rollers replace.
const CLAMP: &str = "clamped = [\"bottom\"]";

/// Measures and prints both comparisons on the quarter mesh `quarter` (whose mirror is the
/// same name with "quarter" turned to "full").
pub fn run(quarter: &Path) -> Result<()> {
    let name = quarter.display().to_string();
    let whole = Path::new(&name.replace("quarter", "full")).to_path_buf();
    if name == whole.display().to_string() || !whole.exists() {
        return Err(anyhow!(
            "--mesh {name}: no mirrored mesh {} beside it: make it with python3 meshes/mirror-quarter.py {name} {}",
            whole.display(),
            whole.display()
        ));
    }
    let quarter_text = QUARTER.to_string();
    let start = QUARTER.find("[[boundary.support]]").unwrap_or(0);
    let end = QUARTER.find("[contact]").unwrap_or(start);
    let whole_text = format!("{}{}", &QUARTER[..start], &QUARTER[end..]);
    let rollers_text = QUARTER.replacen(CLAMP, "", 1).replacen(
        "[contact]",
        "[[boundary.support]]\nparts = [\"bottom\"]\nfix = [\"z\"]\n\n[contact]",
        1,
    );
    let built = |text: &str, mesh: &Path| -> Result<Built> {
        let file = std::fs::canonicalize(mesh).map_err(|e| anyhow!("{}: {e}", mesh.display()))?;
        let overrides = [format!("mesh.file={:?}", file.display().to_string())];
        Ok(Case::from_text(Path::new("cases/indentation-quarter.toml"), text, &overrides)?
            .build()?)
    };
    let sides = [built(&quarter_text, quarter)?, built(&whole_text, &whole)?];
    contact_times(&sides, [&name, &whole.display().to_string()])?;
    let held = [built(&quarter_text, quarter)?, built(&rollers_text, quarter)?];
    factor_times(&held)
}

/// The exact solver on the quarter and on the whole block: the median wall time of
/// [`RUNS`] interleaved runs each.
fn contact_times(sides: &[Built; 2], names: [&str; 2]) -> Result<()> {
    let (medians, runs) = contact_walls(sides, RUNS)?;
    let figures = runs.iter().map(|r| {
        let s = &r.solution;
        (s.dofs.n_free(), s.condensed_nodes, s.surface.len(), s.kkt.max)
    });
    say!("the exact solver on PV2 (µ = 0.3), median of {RUNS} interleaved runs:");
    for ((name, median), (dofs, condensed, gamma3, kkt)) in names.iter().zip(medians).zip(figures) {
        say!(
            "  {name:<40} {dofs:>8} free DOFs  condensed {condensed}/{gamma3}  KKT {kkt:.1e}  wall {median:.4} s"
        );
    }
    say!("  whole / quarter wall time {:.2}", medians[1] / medians[0]);
    Ok(())
}

/// The quarter's system held by the clamp and by rollers: factor entries, the median
/// numeric factorisation time of [`RUNS`] interleaved ones, and the time per entry.
fn factor_times(held: &[Built; 2]) -> Result<()> {
    say!("the quarter's numeric factorisation, median of {RUNS} interleaved runs:");
    let names = ["clamped bottom", "bottom on rollers (z)"];
    let sides = numeric_times(held, names, RUNS)?;
    let per_entry = sides.map(|(seconds, entries)| seconds / entries);
    say!("  rollers / clamp time per entry {:.3} (target ≤ 1.1)", per_entry[1] / per_entry[0]);
    Ok(())
}
