//! Entry points shared by the fuzz targets (`fuzz/`) and the regression tests that replay
//! their corpus: each takes untrusted input and must return, never panic.

use piezocontact::case::Case;
use std::path::Path;

/// Meshes larger than this many cells are parsed and validated but not built: the fuzzer's
/// memory limit is smaller than what a valid large mesh needs.
const MAX_CELLS: usize = 20_000;

/// Reads a case from text with overrides, validates it, and builds the problem, the contact
/// model, the settings and the warnings; every step may fail with an error.
pub fn case(toml: &str, overrides: &[String]) {
    let Ok(case) = Case::from_text(Path::new("fuzz.toml"), toml, overrides) else { return };
    let _ = case.contact_settings();
    let m = &case.file.mesh;
    let cells = m.nx.unwrap_or(1).saturating_mul(m.ny.unwrap_or(1));
    if m.file.is_some() || cells > MAX_CELLS {
        return;
    }
    let Ok(problem) = case.problem() else { return };
    let _ = case.contact_model(&problem);
    let _ = case.settings();
    let _ = case.hypothesis_warnings(&problem.material);
    let _ = case.uniqueness_note();
}
