//! The fields of `summary.json`: those common to every run, those of a contact solution
//! (Algorithms 1–4), the timings and the memory.

use super::contact::{Row, non_finite, zone_measures};
use crate::algorithm::ContactSolution;
use crate::case::Built;
use crate::contact::ContactModel;
use crate::dofs::DofMap;
use crate::error::Error;
use crate::linalg::LinearRoute;
use crate::material::plane::Plane;
use crate::system::Timings;
use serde_json::{Value, json};

/// Fields common to every summary.json: the case, its mesh and unknowns, the backend.
pub fn common_summary(built: &Built, dofs: &DofMap) -> Value {
    let (units, mesh) = (&built.units, &built.problem.mesh);
    let mut summary = json!({
        "case": built.origin.path.display().to_string(),
        "title": built.title,
        "units": { "length": units.length, "stress": units.stress, "charge": units.charge, "potential": units.potential },
        "dim": mesh.dim(),
        "nodes": mesh.n_nodes(),
        "elements": mesh.n_cells(),
        "dofs": { "total": dofs.n_total(), "free": dofs.n_free(), "free_u": dofs.n_free_u(), "free_phi": dofs.n_free() - dofs.n_free_u() },
        "backend": { "name": built.linear.backend_name(), "processes": crate::linalg::processes() },
        "threads": rayon::current_num_threads(),
        "materials": materials_json(built),
    });
    // A plane model says that its forces and charges are per unit thickness.
    match built.plane {
        Some(Plane::Axisymmetric) => merge(
            &mut summary,
            json!({ "model": "axisymmetric", "whole_revolution": "forces and charges are totals over the revolution about y; radial resultants vanish" }),
        ),
        Some(plane) => merge(
            &mut summary,
            json!({ "model": plane.name(), "per_unit_thickness": "forces [stress·length] and charges [charge/length] are per unit thickness" }),
        ),
        None => {}
    }
    summary
}

/// summary.json's `materials`: each material's name, its cells, its law ("hencky", "linear"
/// or "tensor"), whether it is piezoelectric, and its poling in mesh coordinates.
fn materials_json(built: &Built) -> Value {
    let materials = &built.problem.materials;
    let counts = materials.cell_counts(built.problem.mesh.n_cells());
    let list = materials.list().iter().zip(counts).map(|(named, cells)| {
        let m = &named.material;
        let law = match m.elasticity() {
            Some(el) if el.law == crate::material::ElasticLaw::Linear => "linear",
            Some(_) => "hencky",
            None => "tensor",
        };
        let piezoelectric = m.e.iter().flatten().flatten().any(|v| *v != 0.0);
        json!({ "name": named.name, "cells": cells, "law": law, "piezoelectric": piezoelectric, "poling": m.poling() })
    });
    Value::Array(list.collect())
}

/// The summary.json of a validated case that the solver refused before it had a result (a
/// factor too large for the memory, a backend without a capability the method needs): the
/// fields common to every summary ([`common_summary`]), `converged` false and the `failure`.
pub fn refusal_summary(built: &Built, failure: &Error) -> Value {
    let mut summary = match DofMap::new(&built.problem) {
        Ok(dofs) => common_summary(built, &dofs),
        Err(_) => json!({}),
    };
    merge(
        &mut summary,
        json!({ "converged": false, "failure": failure.to_string(), "method": built.method_name() }),
    );
    summary
}

/// summary.json's `reactions`: the force of each clamp and support on the body, by name
/// ([`crate::problem::Problem::support_names`]), d components [stress·length^(d−1)].
pub fn reactions_json(names: &[String], supports: &[Vec<f64>]) -> Value {
    Value::Object(names.iter().cloned().zip(supports.iter().map(|f| json!(f))).collect())
}

/// summary.json's `electrodes`: each grounded part (named by the part) and each electrode,
/// with its parts, kind ("voltage"), potential (read off the solution `x`) and charge (from
/// `charges`, in [`crate::problem::Problem::potential_parts`]' order of the electrodes).
pub fn electrodes_json(built: &Built, dofs: &DofMap, x: &[f64], charges: &[f64]) -> Value {
    let problem = &built.problem;
    let names = problem.mesh.parts();
    let potential =
        |parts: &[usize]| problem.part_nodes(parts).first().map_or(0.0, |&node| x[dofs.phi(node)]);
    let grounded =
        problem.boundary.grounded.iter().map(|&p| {
            (names[p].name.clone(), vec![names[p].name.clone()], "voltage", potential(&[p]))
        });
    let electrodes = problem.boundary.electrodes.iter().map(|e| {
        let parts = e.parts.iter().map(|&p| names[p].name.clone()).collect();
        (e.name.clone(), parts, e.kind(), potential(&e.parts))
    });
    let list: Vec<Value> = grounded
        .chain(electrodes)
        .zip(charges)
        .map(|((name, parts, kind, potential), charge)| {
            json!({ "name": name, "parts": parts, "kind": kind, "potential": potential, "charge": charge })
        })
        .collect();
    Value::Array(list)
}

/// Adds the fields of `b` to the object `a`.
pub fn merge(a: &mut Value, b: Value) {
    if let (Some(a), Value::Object(b)) = (a.as_object_mut(), b) {
        a.extend(b);
    }
}

/// How the outer loop linearised Hencky's law (model §7, §13): "secant" (the paper's fixed
/// point, with the Uzawa method), "whole" (the exact solver's Newton iteration with the whole
/// tangent, also beyond e·t0, where the law's modulus along ε^D is not positive; the word for
/// a linear law too), or "floored in k of n outer steps" where that iteration cycled or made
/// a pivot of B̌ change sign, with ", c of them chord steps on a kept factorisation" when
/// the floor stayed.
pub fn hencky_tangent(solution: &ContactSolution, lags: bool) -> String {
    let floored = format!(
        "floored in {} of {} outer steps",
        solution.floored_steps,
        solution.outer_iterations()
    );
    match (solution.floored_steps, solution.chord_steps) {
        _ if lags => "secant".into(),
        (0, _) => "whole".into(),
        (_, 0) => floored,
        (_, c) => format!("{floored}, {c} of them chord steps on a kept factorisation"),
    }
}

/// The contact part of `summary.json`.
pub fn contact_summary(model: &ContactModel, solution: &ContactSolution, rows: &[Row]) -> Value {
    let max_abs = |f: &dyn Fn(&Row) -> f64| rows.iter().map(|r| f(r).abs()).fold(0.0, f64::max);
    let (contact, stick, slip) = zone_measures(solution, rows);
    let (t, kkt, balance) = (&solution.timings, &solution.kkt, &solution.balance);
    json!({
        "problem": model.name(),
        "converged": solution.converged(),
        "failure": solution.failure.as_ref().map(|e| e.to_string()),
        "outer_iterations": solution.outer_iterations(),
        "inner_iterations": solution.inner_iterations,
        "outer_criterion_history": solution.outer_history,
        "inner_criterion_history": solution.inner_history,
        "kkt_residual": {
            "max": kkt.max,
            "equilibrium_u": kkt.equilibrium_u,
            "equilibrium_phi": kkt.equilibrium_phi,
            "contact": kkt.contact,
            "friction": kkt.friction,
            "max_penetration": kkt.penetration,
        },
        "balance": {
            "applied_load": balance.applied,
            "contact_force": balance.contact,
            "clamp_reaction": balance.reaction,
            "relative_imbalance": balance.imbalance,
        },
        "gamma3": {
            "nodes": rows.len(),
            "condensed_nodes": solution.condensed_nodes,
            "max_abs_sigma_nu": max_abs(&|r| r.sigma_nu),
            "max_abs_sigma_tau": max_abs(&|r| r.sigma_tau[0].hypot(r.sigma_tau[1])),
            "contact_measure": contact,
            "stick_measure": stick,
            "slip_measure": slip,
        },
        "timings_seconds": timings(t),
        "memory": memory(t),
        "linear": linear(&t.linear),
        "non_finite": non_finite(solution, rows),
    })
}

/// The `memory` object of summary.json \[bytes\]: the factorisation's size as its symbolic
/// analysis predicted it, the exact solver's dense condensed matrices (0 without), and the
/// process's peak resident memory measured when the solve ended (null where the system does
/// not say).
pub fn memory(t: &Timings) -> Value {
    json!({
        "factor_predicted_bytes": t.solver.factor_bytes,
        "dense_predicted_bytes": t.dense_bytes,
        "peak_resident_bytes": t.peak_resident_bytes,
    })
}

/// Completes the `timings_seconds` of a run of `built`: `files`, each file's (or series')
/// wall time as `written` lists them (empty before the files are written); `files_meanwhile`,
/// those written on a thread of their own while the solve went on, in that thread's time
/// (outside the sum below); `total`, the wall time since the run began (`built.started`);
/// and `other`, the part of it no phase holds: total − case − solver − files \[s\].
pub fn close_timings(
    summary: &mut Value,
    built: &Built,
    written: &[(String, f64)],
    meanwhile: &[(String, f64)],
) {
    let total = built.started.elapsed().as_secs_f64();
    let t = &mut summary["timings_seconds"];
    let object = |list: &[(String, f64)]| {
        Value::Object(list.iter().map(|(k, s)| (k.clone(), json!(s))).collect())
    };
    t["files_meanwhile"] = object(meanwhile);
    let phases: f64 = ["case", "solver"].iter().filter_map(|k| t[*k].as_f64()).sum();
    let files: f64 = written.iter().map(|(_, s)| s).sum();
    t["files"] = object(written);
    t["total"] = json!(total);
    t["other"] = json!(total - phases - files);
}

/// summary.json's `linear`: `kind` ("direct" or "iterative"), the Krylov method and the
/// preconditioner ("none" on the direct route: a null in summary.json is a number that was
/// not finite), and `krylov_iterations`, one count per linear solve in order (empty on the
/// direct route).
pub fn linear(route: &LinearRoute) -> Value {
    json!({
        "kind": route.kind,
        "krylov": route.krylov.as_deref().unwrap_or("none"),
        "preconditioner": route.preconditioner.as_deref().unwrap_or("none"),
        "krylov_iterations": route.krylov_iterations,
    })
}

/// The `timings_seconds` object of a solve in summary.json (without the run's phases).
pub fn timings(t: &Timings) -> Value {
    let s = &t.solver;
    json!({
        "pattern": t.pattern, "assembly": t.assembly, "symbolic": s.symbolic_seconds,
        "numeric": s.numeric_seconds, "numeric_count": s.numeric_count, "solve": s.solve_seconds,
        "solve_count": s.solve_count, "dense": t.dense, "assessment": t.assessment,
    })
}
