//! `contact.csv`: one row per Γ3 node, ordered along Γ3, with what the laws say of it; the
//! zones it gives, and what summary.json says of values that are not finite.

use super::csv::csv_number;
use crate::algorithm::ContactSolution;
use crate::contact::{ContactModel, NodeStatus};
use crate::problem::Problem;
use serde_json::{Value, json};
use std::fmt::Write;

/// Nodal Γ3 quantities in output form.
#[derive(Clone, Debug)]
pub struct Row {
    /// Node coordinates (3 components).
    pub x: [f64; 3],
    /// u_ν \[length\].
    pub u_nu: f64,
    /// u_τ along τ1 and τ2 of [`crate::contact::ContactSurface::frame`] (τ2 = 0 in 2D) \[length\].
    pub u_tau: [f64; 2],
    /// σ_ν \[stress\].
    pub sigma_nu: f64,
    /// σ_τ = −λ_f along τ1 and τ2 \[stress\].
    pub sigma_tau: [f64; 2],
    /// σ_τ as a vector in the global axes \[stress\].
    pub friction_traction: [f64; 3],
    /// g_a,i: the gap along ν_i; where ν_i misses the foundation (the node cannot touch it),
    /// the shortest distance to the foundation instead \[length\].
    pub gap: f64,
    /// ϕ \[potential\].
    pub phi: f64,
    /// s of the last outer step \[stress\].
    pub s: f64,
    /// Status.
    pub status: NodeStatus,
}

/// The Γ3 rows of a solution.
pub fn rows(problem: &Problem, model: &ContactModel, solution: &ContactSolution) -> Vec<Row> {
    let dofs = &solution.dofs;
    let surface = &solution.surface;
    (0..surface.len())
        .map(|i| {
            let (u_nu, u_tau) = surface.split(dofs, &solution.x, i);
            let friction_traction = solution.state.lambda_f[i].map(|l| -l);
            let frame = surface.frame(i);
            let along = |v: [f64; 3], a: usize| (0..3).map(|k| v[k] * frame[a][k]).sum::<f64>();
            let x = surface.position3(problem, i);
            let gap = match surface.gap[i] {
                g if g.is_finite() => g,
                _ => model.compliance.gap + model.foundation.distance(x),
            };
            Row {
                x,
                u_nu,
                u_tau: [along(u_tau, 1), along(u_tau, 2)],
                sigma_nu: solution.sigma_nu[i],
                sigma_tau: [along(friction_traction, 1), along(friction_traction, 2)],
                friction_traction,
                gap,
                phi: surface.phi(dofs, &solution.x, i),
                s: solution.s[i],
                status: solution.status[i],
            }
        })
        .collect()
}

/// The numeric columns of `contact.csv`, without `status`: exactly
/// `x,y,u_nu,u_tau,sigma_nu,sigma_tau,phi,s` in 2D (u_τ, σ_τ along τ = ν turned by +90°),
/// and `x,y,z,u_nu,u_tau1,u_tau2,sigma_nu,sigma_tau1,sigma_tau2,phi,s` in 3D (along τ1, τ2 of
/// [`crate::contact::ContactSurface::frame`]).
pub fn contact_columns(dim: usize) -> &'static [&'static str] {
    if dim == 2 {
        &["x", "y", "u_nu", "u_tau", "sigma_nu", "sigma_tau", "phi", "s"]
    } else {
        &[
            "x",
            "y",
            "z",
            "u_nu",
            "u_tau1",
            "u_tau2",
            "sigma_nu",
            "sigma_tau1",
            "sigma_tau2",
            "phi",
            "s",
        ]
    }
}

/// The values of a row in the order of [`contact_columns`].
pub fn row_values(r: &Row, dim: usize) -> Vec<f64> {
    let mut values: Vec<f64> = r.x[..dim].to_vec();
    values.push(r.u_nu);
    values.extend_from_slice(&r.u_tau[..dim - 1]);
    values.push(r.sigma_nu);
    values.extend_from_slice(&r.sigma_tau[..dim - 1]);
    values.extend([r.phi, r.s]);
    values
}

/// `contact.csv`: the [`contact_columns`] and `status`, one row per Γ3 node.
pub fn contact_csv(rows: &[Row], dim: usize) -> String {
    let mut s = contact_columns(dim).join(",");
    s.push_str(",status\n");
    for r in rows {
        for v in row_values(r, dim) {
            let _ = write!(s, "{},", csv_number(v));
        }
        let _ = writeln!(s, "{}", r.status.name());
    }
    s
}

/// The `non_finite` object of summary.json: for each output field that holds values that are
/// not finite — written as null in summary.json and as empty cells in contact.csv — how
/// many and why. Empty when every value is finite.
pub fn non_finite(solution: &ContactSolution, rows: &[Row]) -> Value {
    let (kkt, balance) = (&solution.kkt, &solution.balance);
    let dim = solution.surface.dim();
    let fields: [(&str, Vec<f64>); 5] = [
        (
            "kkt_residual",
            vec![
                kkt.max,
                kkt.equilibrium_u,
                kkt.equilibrium_phi,
                kkt.contact,
                kkt.friction,
                kkt.penetration,
            ],
        ),
        (
            "balance",
            [&balance.applied, &balance.contact, &balance.reaction]
                .map(|v| v.iter().copied())
                .into_iter()
                .flatten()
                .chain([balance.imbalance])
                .collect(),
        ),
        ("outer_criterion_history", solution.outer_history.clone()),
        ("inner_criterion_history", solution.inner_history.concat()),
        ("contact.csv", rows.iter().flat_map(|r| row_values(r, dim)).collect()),
    ];
    let why = match &solution.failure {
        Some(failure) => format!("the run failed: {failure}"),
        None => "an overflow in the post-processing".to_string(),
    };
    let mut object = serde_json::Map::new();
    for (name, values) in fields {
        let count = values.iter().filter(|v| !v.is_finite()).count();
        if count > 0 {
            let how = if name == "contact.csv" { "empty cells" } else { "null" };
            let text = format!("{count} values are NaN or infinite, written as {how}; {why}");
            object.insert(name.to_string(), json!(text));
        }
    }
    Value::Object(object)
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algorithm::solve_contact;
    use crate::testing::{PAPER_72, built};

    /// The Γ3 table of a PV2 solution: one row per node, the solution's σ_ν and s, statuses
    /// that partition the contact zone, and a CSV with the documented columns.
    #[test]
    fn the_table_agrees_with_the_solution_and_the_zones_add_up() {
        let built = built(PAPER_72, &["mesh.nx=24", "mesh.ny=4", "solver.method=\"newton\""]);
        let (problem, model) = (&built.problem, built.model.as_ref().unwrap());
        let solution = solve_contact(problem, model, &built.settings).unwrap();
        let rows = rows(problem, model, &solution);
        assert_eq!(rows.len(), solution.surface.len());
        for (i, r) in rows.iter().enumerate() {
            assert_eq!((r.sigma_nu, r.s), (solution.sigma_nu[i], solution.s[i]));
            // σ_τ = −λ_f, and in 2D it lies along τ: its norm is |σ_τ|.
            let norm = r.friction_traction.iter().map(|v| v * v).sum::<f64>().sqrt();
            assert!((norm - r.sigma_tau[0].abs()).abs() < 1e-12 * norm.max(1.0));
            let touching = r.sigma_nu < 0.0;
            assert_eq!(touching, r.status != NodeStatus::Separated, "node {i}");
        }
        let (contact, stick, slip) = zone_measures(&solution, &rows);
        assert!(contact > 0.0 && slip > 0.0, "{contact} {stick} {slip}");
        assert!((contact - stick - slip).abs() < 1e-12);
        let touching: f64 = rows
            .iter()
            .zip(&solution.surface.weight)
            .filter(|(r, _)| r.sigma_nu < 0.0)
            .map(|(_, w)| w)
            .sum();
        assert!((contact - touching).abs() < 1e-12);
        let csv = contact_csv(&rows, 2);
        let mut lines = csv.lines();
        assert_eq!(lines.next(), Some("x,y,u_nu,u_tau,sigma_nu,sigma_tau,phi,s,status"));
        assert_eq!(lines.count(), rows.len());
        assert_eq!((csv_number(f64::NAN), csv_number(-0.5)), (String::new(), "-5e-1".into()));
        let summary = super::super::summary::contact_summary(model, &solution, &rows);
        assert_eq!(summary["gamma3"]["nodes"], rows.len());
        assert_eq!(summary["non_finite"], json!({}));
    }
}
