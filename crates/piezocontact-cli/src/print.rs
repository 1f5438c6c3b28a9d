//! The terminal report of a run: every number with its unit.

use crate::say;
use piezocontact::case::Built;
use piezocontact::case::schema::Units;
use piezocontact::contact::Loading;
use piezocontact::material::NamedMaterial;
use piezocontact::material::plane::Plane;
use piezocontact::oracles::{Piezoelectric, plane_strain_modulus};
use piezocontact::run::{ContactRun, PathRun, Run, StaticPathRun, StaticRun};
use std::path::Path;

/// Prints a run's figures on the terminal, each with its unit.
pub fn run(run: &Run, built: &Built, out: &Path) {
    match run {
        Run::Static(run) => static_run(run, built, out),
        Run::Contact(run) => contact_run(run, built, out),
        Run::Path(path) => path_run(path, built, out),
        Run::StaticPath(path) => static_path_run(path, built, out),
    }
}

/// Prints a contact run's figures on the terminal, each with its unit.
fn contact_run(run: &ContactRun, built: &Built, out: &Path) {
    let (units, solution, kkt) = (&built.units, &run.solution, &run.solution.kkt);
    let mesh = &built.problem.mesh;
    let (sigma_nu, sigma_tau) = run.peaks();
    let (c, st, sl) = run.zones();
    let t = &solution.timings;
    say!(
        "{}: {}, {} nodes, {} elements",
        built.origin.path.display(),
        run.model.name(),
        mesh.n_nodes(),
        mesh.n_cells()
    );
    plane_note(built);
    say!(
        "  outer iterations   = {} ({})",
        solution.outer_iterations(),
        if solution.converged() { "converged" } else { "NOT converged" }
    );
    let exact = !built.settings.method.lags_contact();
    let inner = if exact { "Newton steps" } else { "inner iterations" };
    say!("  {inner:<18} = {:?} (per outer step)", solution.inner_iterations);
    if exact {
        let n3 = solution.surface.len();
        say!("  condensed nodes    = {} of {n3} Γ3 nodes", solution.condensed_nodes);
    }
    if solution.floored_steps > 0 {
        let tangent = piezocontact::report::summary::hencky_tangent(solution, !exact);
        say!("  Hencky tangent     = {tangent} (beyond e·t0)");
    }
    say!("  max |sigma_nu|     = {sigma_nu:.6e} {}", units.stress);
    say!("  max |sigma_tau|    = {sigma_tau:.6e} {}", units.stress);
    let measure = match integrals_dim(built) {
        2 => units.length.clone(),
        _ => format!("{}^2", units.length),
    };
    say!("  contact / stick / slip measure = {c:.4} / {st:.4} / {sl:.4} {measure}");
    say!(
        "  KKT residual       = {:.3e} (equilibrium u {:.1e}, phi {:.1e}; contact {:.1e}; friction {:.1e})",
        kkt.max,
        kkt.equilibrium_u,
        kkt.equilibrium_phi,
        kkt.contact,
        kkt.friction
    );
    say!("  force balance      = relative imbalance {:.1e}", run.solution.balance.imbalance);
    reactions(built, &run.solution.balance.supports);
    electrodes(built, &run.summary(built));
    // The exact solver's condensed problem, where there is one.
    let dense = if t.dense > 0.0 { format!(", dense problem {:.3} s", t.dense) } else { "".into() };
    say!(
        "  time: pattern {:.3} s, assembly {:.3} s, symbolic {:.3} s, numeric {:.3} s ({} factorisations), solves {:.3} s ({}){dense}, solver in all {:.3} s",
        t.pattern,
        t.assembly,
        t.solver.symbolic_seconds,
        t.solver.numeric_seconds,
        t.solver.numeric_count,
        t.solver.solve_seconds,
        t.solver.solve_count,
        run.seconds
    );
    let map = if mesh.dim() == 3 { ", contact_map.png/.svg" } else { "" };
    say!("  wrote contact.csv, summary.json, solution.vtu{map} in {}", out.display());
}

/// Prints a loading path: a line per step, then the last step as a run.
fn path_run(path: &PathRun, built: &Built, out: &Path) {
    let units = &built.units;
    let force = if integrals_dim(built) == 3 {
        format!("{}·{}²", units.stress, units.length)
    } else {
        format!("{}·{}", units.stress, units.length)
    };
    say!(
        "{}: loading path of {} steps, {} solved",
        built.origin.path.display(),
        built.loading.as_ref().map_or(0, |l| l.steps.len()),
        path.curve.len()
    );
    say!(
        "  {:>4} {:>12} {:>11} {:>13} {:>13} {:>13} {:>7} {:>10} {:>9}",
        "step",
        format!("depth [{}]", units.length),
        "load factor",
        format!("|F| [{force}]"),
        format!("radius [{}]", units.length),
        format!("p_max [{}]", units.stress),
        "steps",
        "KKT",
        "converged"
    );
    for r in &path.curve {
        let magnitude = r.force.iter().map(|f| f * f).sum::<f64>().sqrt();
        say!(
            "  {:>4} {:>12.4e} {:>11.4} {:>13.4e} {:>13.4e} {:>13.4e} {:>7} {:>10.2e} {:>9}",
            r.step,
            r.depth,
            r.load_factor,
            magnitude,
            r.contact_radius,
            r.max_pressure,
            r.newton_steps,
            r.kkt_residual,
            r.converged
        );
    }
    say!("the last step:");
    contact_run(&path.last, built, out);
    say!(
        "  wrote curve.csv, curve.png/.svg, solution-NNNN.vtu and solution.pvd (every step) in {}",
        out.display()
    );
}

/// Prints a loading path without contact: a line per step, then the last step as a run.
fn static_path_run(path: &StaticPathRun, built: &Built, out: &Path) {
    let (units, dim) = (&built.units, built.problem.mesh.dim());
    let volume = integrals_dim(built) == 3;
    let force = if volume { format!("{}²", units.length) } else { units.length.clone() };
    let per = if volume { String::new() } else { format!("/{}", units.length) };
    let parts = PathRun::electrodes(built);
    say!(
        "{}: loading path of {} steps without contact",
        built.origin.path.display(),
        path.curve.len()
    );
    let mut header = format!("  {:>4} {:>11}", "step", "load factor");
    for c in &["x", "y", "z"][..dim] {
        header += &format!(" {:>22}", format!("reaction_{c} [{}·{force}]", units.stress));
    }
    for p in &parts {
        header += &format!(" {:>22}", format!("charge_{p} [{}{per}]", units.charge));
    }
    say!("{header}");
    for r in &path.curve {
        let mut line = format!("  {:>4} {:>11.4}", r.step, r.load_factor);
        for v in r.reaction.iter().chain(&r.charges) {
            line += &format!(" {v:>22.6e}");
        }
        say!("{line}");
    }
    say!("the last step:");
    static_run(&path.last, built, out);
    say!(
        "  wrote curve.csv, curve.png/.svg, solution-NNNN.vtu and solution.pvd (every step) in {}",
        out.display()
    );
}

/// Prints a loading path: its direction and each step's depth and load factor.
pub fn loading(loading: &Loading, dim: usize, units: &Units) {
    if !loading.moves() {
        let factors: Vec<String> =
            loading.steps.iter().map(|s| s.load_factor.to_string()).collect();
        say!("loading path: {} steps, load factors [{}]", loading.steps.len(), factors.join(", "));
        return;
    }
    let steps: Vec<String> = loading
        .steps
        .iter()
        .map(|s| {
            if s.load_factor == 1.0 {
                format!("{}", s.depth)
            } else {
                format!("{} (×{})", s.depth, s.load_factor)
            }
        })
        .collect();
    say!(
        "loading path: {} steps along {:?}, depths [{}] {} (× load factor where not 1)",
        loading.steps.len(),
        &loading.direction[..dim],
        steps.join(", "),
        units.length
    );
}

/// Prints the indentation moduli of the half-space of a material transversely isotropic
/// about the last axis, indented along it (the classical solutions with C* in place of E*).
pub fn indentation_moduli(named: &NamedMaterial, units: &Units) {
    let (s, material) = (&units.stress, &named.material);
    say!("  indentation of its half-space along the poling (small strain):");
    if let Some(el) = material.elasticity() {
        let e_star = plane_strain_modulus(el.young(), el.poisson());
        say!("  E/(1 − ν²)          = {e_star:.6} {s} (without the piezoelectric coupling)");
    }
    let constants = Piezoelectric::of(material);
    if [constants.e31, constants.e33, constants.e15].iter().all(|e| *e == 0.0) {
        return;
    }
    match constants.indentation() {
        Ok(m) => {
            say!("  C* insulating tip   = {:.6} {s}", m.insulating);
            say!("  C* grounded tip     = {:.6} {s}", m.conducting);
            say!(
                "  ϕ/δ insulating tip  = {:.6} {}/{} (surface potential per indentation into the body)",
                m.potential_ratio,
                units.potential,
                units.length
            );
        }
        Err(e) => say!("  C*: not computed ({e})"),
    }
}

/// The dimension of the body the integrals run over: 3 for a 3D mesh and for a body of
/// revolution (forces [stress·length²], measures of Γ3 areas), 2 for a plane model (per unit
/// thickness).
fn integrals_dim(built: &Built) -> usize {
    if built.problem.axisymmetric { 3 } else { built.problem.mesh.dim() }
}

/// Says, for a plane model, that its forces and charges are per unit thickness.
fn plane_note(built: &Built) {
    match built.plane {
        Some(Plane::Axisymmetric) => {
            say!("  axisymmetric: forces and charges are totals over the revolution about y")
        }
        Some(plane) => say!("  {}: forces and charges are per unit thickness", plane.name()),
        None => {}
    }
}

/// Prints a run without contact.
fn static_run(run: &StaticRun, built: &Built, out: &Path) {
    let (units, problem, t) = (&built.units, &built.problem, &run.solution.timings);
    say!(
        "{}: {} nodes, {} elements, {} free DOFs (no contact)",
        built.origin.path.display(),
        problem.mesh.n_nodes(),
        problem.mesh.n_cells(),
        run.solution.dofs.n_free()
    );
    plane_note(built);
    say!("  max |u|            = {:.6e} {}", run.max_u, units.length);
    let (lo, hi) = run.phi_range;
    say!("  phi range          = [{lo:.6e}, {hi:.6e}] {}", units.potential);
    if run.solution.failure.is_some() {
        say!("  NOT converged: Hencky's law not met (the last secant step's state is written)");
    }
    say!("  relative residual  = {:.3e}", run.solution.relative_residual);
    reactions(built, &run.reactions.supports);
    electrodes(built, &run.summary(built));
    if run.solution.factorisations > 1 {
        say!("  Hencky's law       = {} secant steps", run.solution.factorisations - 1);
    }
    say!(
        "  time: pattern {:.3} s, assembly {:.3} s, symbolic {:.3} s, numeric {:.3} s, solve {:.3} s, solver in all {:.3} s",
        t.pattern,
        t.assembly,
        t.solver.symbolic_seconds,
        t.solver.numeric_seconds,
        t.solver.solve_seconds,
        run.seconds
    );
    say!("  wrote summary.json and solution.vtu in {}", out.display());
}

/// Prints the table of a run's phases from its summary.json `timings_seconds`: the case,
/// the solver's phases, each file, the rest and the total \[s\].
pub fn timings(summary: &serde_json::Value) {
    let t = &summary["timings_seconds"];
    let seconds = |key: &str| t[key].as_f64().unwrap_or(0.0);
    let total = seconds("total");
    let line = |name: &str, s: f64| {
        let share = if total > 0.0 { 100.0 * s / total } else { 0.0 };
        say!("    {name:<28} {s:>9.3} s {share:>5.1} %");
    };
    say!("  the run's wall time by phase:");
    line("case (mesh, checks)", seconds("case"));
    let phases = ["pattern", "assembly", "symbolic", "numeric", "solve", "dense", "assessment"];
    for key in phases {
        line(&format!("  {key}"), seconds(key));
    }
    let counted: f64 = phases.iter().map(|k| seconds(k)).sum();
    line("  (rest of the solver)", seconds("solver") - counted);
    line("solver in all", seconds("solver"));
    for (name, s) in t["files"].as_object().into_iter().flatten() {
        line(&format!("writing {name}"), s.as_f64().unwrap_or(0.0));
    }
    for (name, s) in t["files_meanwhile"].as_object().into_iter().flatten() {
        let s = s.as_f64().unwrap_or(0.0);
        say!("    {:<28} {s:>9.3} s (while the solve went on)", format!("writing {name}"));
    }
    line("other", seconds("other"));
    line("total", total);
}

/// Prints a built case's mesh: its size, its bounding box and each boundary part with its
/// roles.
pub fn mesh(built: &Built) {
    let (mesh, units) = (&built.problem.mesh, &built.units);
    let (lo, hi) = mesh.bounding_box();
    say!(
        "mesh: {}D, {} nodes, {} elements, bounding box {lo:?}–{hi:?} {}",
        mesh.dim(),
        mesh.n_nodes(),
        mesh.n_cells(),
        units.length
    );
    plane_note(built);
    let unit = if mesh.dim() == 2 { units.length.clone() } else { format!("{}^2", units.length) };
    for (p, part) in mesh.parts().iter().enumerate() {
        say!(
            "  part {:<12} {:>6} facets, measure {:.6} {unit}  ({})",
            part.name,
            part.n_facets(),
            mesh.part_measure(p),
            roles(&built.problem.boundary, p)
        );
    }
    let materials = &built.problem.materials;
    for region in mesh.regions() {
        let of = |c: &usize| materials.list()[materials.index_of(*c)].name.as_str();
        let mut names: Vec<&str> = region.cells.iter().map(of).collect();
        names.sort_unstable();
        names.dedup();
        say!(
            "  region {:<10} {:>6} cells, material {}",
            region.name,
            region.cells.len(),
            names.join(", ")
        );
    }
    supports(built);
}

/// Prints the supports, for `check`: each one's parts, fixed components and nodes.
fn supports(built: &Built) {
    let problem = &built.problem;
    for support in &problem.boundary.supports {
        let parts: Vec<&str> =
            support.parts.iter().map(|&p| problem.mesh.parts()[p].name.as_str()).collect();
        let fixed: Vec<&str> = support.fixed.iter().map(|(d, _)| d.name()).collect();
        say!(
            "  support {:<12} parts {}, fixes {} on {} nodes",
            support.name,
            parts.join(", "),
            fixed.join(", "),
            problem.part_nodes(&support.parts).len()
        );
    }
}

/// Prints each electrode's potential and charge (summary.json's `electrodes`), when the case
/// has electrodes beside its grounded parts.
fn electrodes(built: &Built, summary: &serde_json::Value) {
    if built.problem.boundary.electrodes.is_empty() {
        return;
    }
    let units = &built.units;
    let per = if integrals_dim(built) == 3 { String::new() } else { format!("/{}", units.length) };
    for e in summary["electrodes"].as_array().into_iter().flatten() {
        say!(
            "  electrode {:<8} ({}) = potential {:.6e} {}, charge {:.6e} {}{per}",
            e["name"].as_str().unwrap_or(""),
            e["kind"].as_str().unwrap_or(""),
            e["potential"].as_f64().unwrap_or(f64::NAN),
            units.potential,
            e["charge"].as_f64().unwrap_or(f64::NAN),
            units.charge
        );
    }
}

/// Prints the reaction of each clamp and support, with its unit.
fn reactions(built: &Built, supports: &[Vec<f64>]) {
    let units = &built.units;
    let area = if integrals_dim(built) == 3 { "²" } else { "" };
    for (name, force) in built.problem.support_names().iter().zip(supports) {
        let components: Vec<String> = force.iter().map(|f| format!("{f:.6e}")).collect();
        say!(
            "  reaction {name:<9} = [{}] {}·{}{area}",
            components.join(", "),
            units.stress,
            units.length
        );
    }
}

/// The roles of boundary part `p`, for `check`.
fn roles(b: &piezocontact::problem::Boundary, p: usize) -> String {
    let mut roles = Vec::new();
    for (role, list) in
        [("Γ1 clamped", &b.clamped), ("Γa grounded", &b.grounded), ("Γ3 contact", &b.contact)]
    {
        if list.contains(&p) {
            roles.push(role);
        }
    }
    if b.supports.iter().any(|s| s.parts.contains(&p)) {
        roles.push("supported");
    }
    if b.traction.iter().any(|(q, _)| *q == p) {
        roles.push("Γ2 traction");
    }
    if b.charge.iter().any(|(q, _)| *q == p) {
        roles.push("Γb charge");
    }
    if roles.is_empty() {
        "no role: traction and charge free".to_string()
    } else {
        roles.join(", ")
    }
}

/// Prints a built case's material constants and unknowns.
pub fn material(built: &Built) -> piezocontact::Result<()> {
    let problem = &built.problem;
    let dofs = piezocontact::dofs::DofMap::new(problem)?;
    let counts = problem.materials.cell_counts(problem.mesh.n_cells());
    for (named, cells) in problem.materials.list().iter().zip(counts) {
        let p = named.material.poling();
        let law = match named.material.elasticity() {
            Some(el) => format!(
                "mu1 = {:.6} {s}, k0 = {:.6} {s}, law {:?}",
                el.mu1,
                el.k0,
                el.law,
                s = built.units.stress
            ),
            None => "a stiffness tensor (linear law)".into(),
        };
        say!(
            "material '{}': {cells} cells, {law}, poled along [{:.4}, {:.4}, {:.4}]",
            named.name,
            p[0],
            p[1],
            p[2]
        );
    }
    say!(
        "dofs: {} in all, {} free ({} u, {} phi)",
        dofs.n_total(),
        dofs.n_free(),
        dofs.n_free_u(),
        dofs.n_free() - dofs.n_free_u()
    );
    Ok(())
}

/// Prints the material library (`piezocontact materials`): each preset's nonzero constants in
/// its source's form, in SI.
pub fn presets() {
    use piezocontact::material::library::presets;
    use piezocontact::material::voigt::PiezoForm;
    let labels = ["11", "22", "33", "23", "13", "12"];
    let voigt = ["1", "2", "3", "4", "5", "6"];
    for preset in presets() {
        say!("{} — {}", preset.name, preset.source);
        let c = preset.stiffness;
        let mut line = String::from("  c^E [GPa]:");
        for i in 0..6 {
            for j in i..6 {
                if c[i][j] != 0.0 {
                    line += &format!(" c{}{}={:.4}", voigt[i], voigt[j], c[i][j] / 1e9);
                }
            }
        }
        say!("{line}");
        let (name, unit, scale, coupling) = match preset.piezo {
            PiezoForm::None => ("", "", 1.0, None),
            PiezoForm::Stress(e) => ("e", "C/m²", 1.0, Some(e)),
            PiezoForm::Strain(d) => ("d", "pC/N", 1e12, Some(d)),
        };
        if let Some(x) = coupling {
            let mut line = format!("  {name} [{unit}]:");
            for (i, row) in x.iter().enumerate() {
                for (j, v) in row.iter().enumerate() {
                    if *v != 0.0 {
                        line += &format!(" {name}{}{}={:.4}", i + 1, voigt[j], v * scale);
                    }
                }
            }
            say!("{line}");
        } else {
            say!("  a dielectric: no piezoelectric coupling");
        }
        let kind = if matches!(preset.piezo, PiezoForm::Strain(_)) { "ε^T" } else { "ε^S" };
        let [a, b, c3] = preset.permittivity;
        say!("  {kind}/ε0 [-]: {}={a} {}={b} {}={c3}", labels[0], labels[1], labels[2]);
    }
}
