//! `piezocontact bench --floating`: the 3D indentation of cases/indentation-3d.toml with its
//! top face (the parts `top` and `contact`) an electrode grounded at 0 V against the same
//! face a floating electrode (an open circuit), whose one unknown couples all its nodes: the
//! factor's entries, the numeric factorisation (median of 5 interleaved runs) and the exact
//! solver's wall time of each, in one run of the same binary.

use super::{contact_walls, numeric_times};
use crate::say;
use anyhow::{Result, anyhow};
use piezocontact::case::{Built, Case};
use std::path::Path;

/// The runs of each side.
const RUNS: usize = 5;

/// The indentation case.
const INDENTATION: &str = include_str!("../../../../cases/indentation-3d.toml");

/// Measures and prints both sides on `mesh` (the case's own when `None`).
pub fn run(mesh: Option<&Path>) -> Result<()> {
    let electrode = |condition: &str| {
        INDENTATION.replacen(
            "[contact]",
            &format!(
                "[[boundary.electrode]]\nname = \"face\"\nparts = [\"top\", \"contact\"]\n{condition}\n\n[contact]"
            ),
            1,
        )
    };
    let built = |text: &str| -> Result<Built> {
        let mut overrides = Vec::new();
        if let Some(mesh) = mesh {
            let file =
                std::fs::canonicalize(mesh).map_err(|e| anyhow!("{}: {e}", mesh.display()))?;
            overrides.push(format!("mesh.file={:?}", file.display().to_string()));
        }
        Ok(Case::from_text(Path::new("cases/indentation-3d.toml"), text, &overrides)?.build()?)
    };
    let sides = [built(&electrode("voltage = 0.0"))?, built(&electrode("charge = 0.0"))?];
    say!("the top face grounded and floating, median of {RUNS} interleaved runs:");
    let factors = numeric_times(&sides, ["top face at 0 V", "top face floating"], RUNS)?;
    say!(
        "  floating / grounded: numeric factorisation {:.3} (target ≤ 1.2), factor entries {:.3}",
        factors[1].0 / factors[0].0,
        factors[1].1 / factors[0].1
    );
    let (walls, runs) = contact_walls(&sides, RUNS)?;
    if let Some(k) = runs.iter().position(|r| !r.solution.converged()) {
        return Err(anyhow!("side {} did not converge", k + 1));
    }
    say!(
        "  the exact solver on PV2 (µ = 0.3): grounded {:.4} s, floating {:.4} s, ratio {:.3}",
        walls[0],
        walls[1],
        walls[1] / walls[0]
    );
    Ok(())
}
