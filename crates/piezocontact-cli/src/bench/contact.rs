//! `piezocontact bench --contact`: a contact solve with the exact solver against one plain
//! factorisation of the same mesh (the floor), in wall time and peak memory, each measured
//! in a process of its own.

use super::{INDENTATION, PAPER_CASE, PAPER_PV2, in_child, paper_case, parse_size};
use crate::say;
use anyhow::{Result, anyhow};
use piezocontact::case::Case;
use std::path::Path;
use std::time::Instant;

/// The default sizes of the contact benchmark.
pub const CONTACT_SIZES: [&str; 4] = ["96x16", "192x32", "384x64", "768x128"];

/// What marks a case file among the targets of the contact benchmark.
const CASE_PREFIX: &str = "case:";

/// The target of `bench --contact --case FILE`.
pub fn case_target(file: &Path) -> String {
    format!("{CASE_PREFIX}{}", file.display())
}

/// The problems of the contact benchmark on a target: the paper's bar at a size "NXxNY"
/// (PV1, PV2 with µ = k_e = 0.2 and 0.6), a Gmsh mesh with the parts of
/// meshes/indent-3d.geo in the indentation case, or "case:FILE" (both: PV1, and PV2 with
/// µ = 0.3); each with the exact solver and the overrides `extra`.
pub fn contact_problems(target: &str, extra: &[String]) -> Result<Vec<(&'static str, Case)>> {
    let newton = || [&["solver.method=\"newton\"".to_string()][..], extra].concat();
    if let Some(file) = target.strip_prefix(CASE_PREFIX) {
        let with = |extra: &[&str]| -> Result<Case> {
            let mut overrides = newton();
            overrides.extend(extra.iter().map(|s| s.to_string()));
            let case = Case::load(Path::new(file), &overrides)?;
            case.one_position()
                .map_err(|e| anyhow!("{e}; `bench --path --case {file}` times the path"))?;
            Ok(case)
        };
        let pv2 = ["contact.problem=\"PV2\"", "friction.mu=0.3"];
        return Ok(vec![("PV1", with(&["contact.problem=\"PV1\""])?), ("PV2 mu=0.3", with(&pv2)?)]);
    }
    if let Ok((nx, ny)) = parse_size(target) {
        let pv2 = |mu: f64| {
            let mut o = newton();
            o.extend([format!("friction.mu={mu}"), format!("conductivity.ke={mu}")]);
            o
        };
        return Ok(vec![
            ("PV1", paper_case(PAPER_CASE, nx, ny, &newton())?),
            ("PV2 mu=0.2", paper_case(PAPER_PV2, nx, ny, &pv2(0.2))?),
            ("PV2 mu=0.6", paper_case(PAPER_PV2, nx, ny, &pv2(0.6))?),
        ]);
    }
    let file = std::fs::canonicalize(target).map_err(|e| anyhow!("--mesh {target}: {e}"))?;
    let with = |extra: &[&str]| -> Result<Case> {
        let mut overrides = newton();
        overrides.push(format!("mesh.file={:?}", file.display().to_string()));
        overrides.extend(extra.iter().map(|s| s.to_string()));
        Ok(Case::from_text(Path::new("cases/indentation-3d.toml"), INDENTATION, &overrides)?)
    };
    Ok(vec![("PV1", with(&["contact.problem=\"PV1\""])?), ("PV2 mu=0.3", with(&[])?)])
}

/// `bench --contact`: every measurement in a process of its own (peak memory per run), on
/// each target: a size "NXxNY" of the paper's bar or a Gmsh mesh.
pub fn contact(targets: &[String]) -> Result<()> {
    let names: Vec<Vec<&str>> = targets
        .iter()
        .map(|t| Ok(contact_problems(t, &[])?.into_iter().map(|(name, _)| name).collect()))
        .collect::<Result<_>>()?;
    say!(
        "{:>10} {:>9} {:>11} {:>11} {:>7} {:>12} {:>8} {:>8} {:>8} {:>8} {:>15} {:>7} {:>7} {:>8} {:>16} {:>9}",
        "mesh",
        "DOFs",
        "problem",
        "condensed",
        "newton",
        "kkt_residual",
        "run_s",
        "total_s",
        "solve_s",
        "files_s",
        "factorisation_s",
        "ratio",
        "solve_r",
        "peak_MB",
        "factorisation_MB",
        "mem_ratio"
    );
    for (target, names) in targets.iter().zip(names) {
        let plain = in_child(&format!("plain,{target}"), false)?;
        let (plain_s, plain_mb) = (plain.get("seconds")?, plain.get("peak_mb")?);
        let size =
            Path::new(target).file_name().map_or(target.clone(), |n| n.to_string_lossy().into());
        for (k, name) in names.into_iter().enumerate() {
            let start = Instant::now();
            let run = in_child(&format!("contact{k},{target}"), false)?;
            let wall = start.elapsed().as_secs_f64();
            let (seconds, mb) = (run.get("seconds")?, run.get("peak_mb")?);
            say!(
                "{:>10} {:>9} {:>11} {:>11} {:>7} {:>12.3e} {:>8.3} {:>8.3} {:>8.3} {:>8.3} {:>15.3} {:>7.2} {:>7.2} {:>8.0} {:>16.0} {:>9.2}",
                size,
                run.get("dofs")?,
                name,
                format!("{}/{}", run.get("condensed")?, run.get("gamma3")?),
                run.get("newton")?,
                run.get("kkt")?,
                wall,
                run.get("total")?,
                seconds,
                run.get("files")?,
                plain_s,
                wall / plain_s,
                seconds / plain_s,
                mb,
                plain_mb,
                mb / plain_mb
            );
        }
    }
    say!(
        "condensed: Γ3 nodes in the exact solver's dense problem / all Γ3 nodes; run_s: the wall \
         time of a process that runs the case as `piezocontact run` does with solver.method = \
         \"newton\" — the case's mesh and checks, the solve, its assessment and its files \
         (written to a temporary directory, the .vtu in binary) —, measured outside it; \
         total_s: its summary.json's total (from its start to summary.json); solve_s: the solve within it (pattern, ordering, factorisations, Schur complement, \
         Newton, solves, KKT residual, the Γ3 table); files_s: the writing of its files; \
         factorisation_s: one plain pattern + assembly + symbolic + numeric LDLᵀ of the same \
         mesh in a process of its own, the floor; both with solver.ordering = \"auto\" on {} \
         threads in 3D (one in 2D); ratio: run_s / factorisation_s; solve_r: solve_s / \
         factorisation_s; peak_MB: the process's peak resident memory; mem_ratio: contact / \
         factorisation",
        rayon::current_num_threads()
    );
    Ok(())
}
