//! Entry points shared by the fuzz targets (`fuzz/`) and the regression tests that replay
//! their corpus: each takes untrusted input and must return, never panic.

use piezocontact::case::{Built, Case};
use piezocontact::contact::ContactSurface;
use piezocontact::dofs::DofMap;
use std::path::Path;

/// Meshes larger than this many cells are parsed and validated but not built: the fuzzer's
/// memory limit is smaller than what a valid large mesh needs.
const MAX_CELLS: usize = 20_000;

/// Mesh files larger than this are not read (the committed 3D test meshes are smaller).
const MAX_MESH_BYTES: u64 = 1 << 20;

/// Reads a case from text with overrides, validates it, and builds the problem, the contact
/// model (with the foundation), the loading path, the settings and the warnings; every step
/// may fail with an error. The case sits in the repository's `meshes/`, so `mesh.file =
/// "cube.msh"` reads a committed mesh (2D or 3D) and `foundation.file = "ball-tip.stl"` a
/// committed surface; other files — paths, large files — are not read. Returns the dimension
/// of the problem built, if one was.
pub fn case(toml: &str, overrides: &[String]) -> Option<usize> {
    let meshes = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../meshes");
    let case = Case::from_text(&meshes.join("fuzz.toml"), toml, overrides).ok()?;
    let m = &case.file.mesh;
    let cells = m.nx.unwrap_or(1).saturating_mul(m.ny.unwrap_or(1));
    let readable = |file: &Path, kinds: &[&str]| {
        let kind = file.extension().is_some_and(|e| kinds.iter().any(|k| e == *k));
        let plain = file.components().count() == 1 && kind;
        plain && std::fs::metadata(meshes.join(file)).is_ok_and(|f| f.len() <= MAX_MESH_BYTES)
    };
    let surface = case.file.foundation.as_ref().and_then(|f| f.file.as_deref()).map(Path::new);
    if m.file.as_deref().is_some_and(|f| !readable(f, &["msh"]))
        || surface.is_some_and(|f| !readable(f, &["msh", "stl"]))
        || cells > MAX_CELLS
    {
        return None;
    }
    let Built { problem, model, .. } = case.build().ok()?;
    if let (Some(model), Ok(dofs)) = (model, DofMap::new(&problem)) {
        // The gaps of Γ3 to the foundation.
        let surface = ContactSurface::new(&problem, &dofs);
        let _ = surface.map(|s| s.with_gaps(&problem, &model.foundation, model.compliance.gap));
    }
    let _ = case.uniqueness_note();
    Some(problem.mesh.dim())
}
