//! Reports of a contact run: `contact.csv` (one row per Γ3 node, ordered along Γ3) and the
//! `summary.json` fields of Algorithms 1–4.

use crate::algorithm::{ContactModel, ContactSolution, NodeStatus};
use crate::problem::Problem;
use crate::solver::Timings;
use serde_json::{Value, json};
use std::fmt::Write;

/// Nodal Γ3 quantities in output form.
pub struct Row {
    /// Node coordinates (3 components).
    pub x: [f64; 3],
    /// u_ν [length].
    pub u_nu: f64,
    /// u_τ: along τ in 2D, ‖u_τ‖ in 3D [length].
    pub u_tau: f64,
    /// σ_ν [stress].
    pub sigma_nu: f64,
    /// σ_τ = −λ_f: along τ in 2D, ‖σ_τ‖ in 3D [stress].
    pub sigma_tau: f64,
    /// ϕ [potential].
    pub phi: f64,
    /// s of the last outer step [stress].
    pub s: f64,
    /// Status.
    pub status: NodeStatus,
}

/// The Γ3 rows of a solution.
pub fn rows(problem: &Problem, model: &ContactModel, solution: &ContactSolution) -> Vec<Row> {
    let dofs = &solution.dofs;
    let surface = &solution.surface;
    let dim = problem.mesh.dim();
    (0..surface.len())
        .map(|i| {
            let (u_nu, u_tau) = surface.split(dofs, &solution.x, i);
            let lambda_f = solution.state.lambda_f[i];
            let (u_tau, sigma_tau) = if dim == 2 {
                let t = surface.tangent(i);
                (u_tau[0] * t[0] + u_tau[1] * t[1], -(lambda_f[0] * t[0] + lambda_f[1] * t[1]))
            } else {
                let norm = |v: [f64; 3]| v.iter().map(|a| a * a).sum::<f64>().sqrt();
                (norm(u_tau), norm(lambda_f))
            };
            let mut x = [0.0; 3];
            x[..dim].copy_from_slice(surface.position(problem, i));
            Row {
                x,
                u_nu,
                u_tau,
                sigma_nu: solution.sigma_nu[i],
                sigma_tau,
                phi: surface.phi(dofs, &solution.x, i),
                s: solution.s[i],
                status: solution.status(i, model.pv2.is_some()),
            }
        })
        .collect()
}

/// `contact.csv`: columns exactly `x,y,u_nu,u_tau,sigma_nu,sigma_tau,phi,s,status`.
pub fn contact_csv(rows: &[Row]) -> String {
    let mut s = String::from("x,y,u_nu,u_tau,sigma_nu,sigma_tau,phi,s,status\n");
    for r in rows {
        let _ = writeln!(
            s,
            "{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{}",
            r.x[0],
            r.x[1],
            r.u_nu,
            r.u_tau,
            r.sigma_nu,
            r.sigma_tau,
            r.phi,
            r.s,
            r.status.name()
        );
    }
    s
}

/// Lengths (2D) or areas (3D) of Γ3 by status: (contact, stick, slip), from the nodal weights.
pub fn zone_measures(solution: &ContactSolution, rows: &[Row]) -> (f64, f64, f64) {
    let mut m = (0.0, 0.0, 0.0);
    for (r, w) in rows.iter().zip(&solution.surface.weight) {
        match r.status {
            NodeStatus::Separated => {}
            NodeStatus::Contact => m.0 += w,
            NodeStatus::Stick => {
                m.0 += w;
                m.1 += w;
            }
            NodeStatus::Slip => {
                m.0 += w;
                m.2 += w;
            }
        }
    }
    m
}

/// The contact part of `summary.json`.
pub fn contact_summary(model: &ContactModel, solution: &ContactSolution, rows: &[Row]) -> Value {
    let max_abs = |f: &dyn Fn(&Row) -> f64| rows.iter().map(|r| f(r).abs()).fold(0.0, f64::max);
    let (contact, stick, slip) = zone_measures(solution, rows);
    let (t, kkt, balance) = (solution.timings, &solution.kkt, &solution.balance);
    json!({
        "problem": model.name(),
        "converged": solution.converged,
        "failure": solution.failure.as_ref().map(|e| e.to_string()),
        "outer_iterations": solution.outer_iterations,
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
            "max_abs_sigma_nu": max_abs(&|r| r.sigma_nu),
            "max_abs_sigma_tau": max_abs(&|r| r.sigma_tau),
            "contact_measure": contact,
            "stick_measure": stick,
            "slip_measure": slip,
        },
        "timings_seconds": timings(&t),
    })
}

/// The `timings_seconds` object of summary.json (without the total).
pub fn timings(t: &Timings) -> Value {
    json!({
        "pattern": t.pattern, "assembly": t.assembly, "symbolic": t.symbolic, "numeric": t.numeric,
        "numeric_count": t.numeric_count, "solve": t.solve, "solve_count": t.solve_count,
    })
}
