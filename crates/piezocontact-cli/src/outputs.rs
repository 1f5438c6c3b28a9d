//! The files of a run, as `piezocontact run` writes them: the library's contact.csv,
//! summary.json and solution.vtu, and for a 3D body the Γ3 map figure (contact_map.png/.svg).

use crate::plot;
use anyhow::Result;
use piezocontact::case::Case;
use piezocontact::run::ContactRun;
use std::path::Path;

/// Writes the files of a contact run into `out` (already claimed).
pub fn write_contact_run(run: &ContactRun, case: &Case, out: &Path) -> Result<()> {
    run.write(case, out)?;
    if run.problem.mesh.dim() == 3 {
        let units = &case.file.units;
        let title = if case.file.title.is_empty() { "Γ3" } else { case.file.title.as_str() };
        let labels = plot::MapLabels { title, length: &units.length, stress: &units.stress };
        plot::contact_map(run, &labels, &out.join("contact_map"))?;
    }
    Ok(())
}
