//! `curve.csv` of a loading path: one row per step, with what the experimentalist reads at
//! it — the force on the foundation, the contact zone, the potential under the indenter, the
//! charges of the electrodes.

use super::contact::{Row, zone_measures};
use super::csv::csv_number;
use crate::algorithm::ContactSolution;
use crate::contact::{LoadStep, NodeStatus};
use std::f64::consts::PI;

/// One row of curve.csv: what the experimentalist reads at a step.
#[derive(Clone, Debug, PartialEq)]
pub struct CurveRow {
    /// The step, from 1.
    pub step: usize,
    /// The factor on the applied loads [-].
    pub load_factor: f64,
    /// The foundation's displacement along the loading direction \[length\].
    pub depth: f64,
    /// The force the body exerts on the foundation, d components [stress·length^(d−1)].
    pub force: Vec<f64>,
    /// The measure of the contact zone [length^(d−1)].
    pub contact_measure: f64,
    /// √(measure/π) in 3D, half the measure in 2D \[length\].
    pub contact_radius: f64,
    /// The largest contact pressure −σ_ν \[stress\].
    pub max_pressure: f64,
    /// ϕ at the Γ3 node with the largest pressure \[potential\].
    pub phi_center: f64,
    /// The mean of ϕ over the contact zone (over Γ3 when nothing touches) \[potential\].
    pub phi_mean: f64,
    /// The measures of the stick and slip zones [length^(d−1)].
    pub stick_measure: f64,
    pub slip_measure: f64,
    /// Inner iterations (Newton steps or Uzawa iterations) of the step.
    pub newton_steps: usize,
    /// The largest relative KKT residual [-].
    pub kkt_residual: f64,
    /// Whether the step converged.
    pub converged: bool,
    /// The charge on each part of Γa and each electrode [charge·length^(3−d)].
    pub charges: Vec<f64>,
    /// The potential of each electrode beyond the grounded parts \[potential\].
    pub potentials: Vec<f64>,
    /// The force of each clamp and support on the body, d components each.
    pub supports: Vec<Vec<f64>>,
}

impl CurveRow {
    /// The row of `step` (from 1) at `load` with its `solution` and Γ3 `rows`.
    pub fn new(step: usize, load: &LoadStep, solution: &ContactSolution, rows: &[Row]) -> Self {
        let dim = solution.surface.dim();
        let (contact, stick, slip) = zone_measures(solution, rows);
        let weight = &solution.surface.weight;
        let touching: Vec<usize> =
            (0..rows.len()).filter(|&i| rows[i].status != NodeStatus::Separated).collect();
        let zone = if touching.is_empty() { (0..rows.len()).collect() } else { touching };
        let measure: f64 = zone.iter().map(|&i| weight[i]).sum();
        let phi_mean = zone.iter().map(|&i| weight[i] * rows[i].phi).sum::<f64>()
            / measure.max(f64::MIN_POSITIVE);
        let center = (0..rows.len()).max_by(|&a, &b| rows[b].sigma_nu.total_cmp(&rows[a].sigma_nu));
        Self {
            step,
            load_factor: load.load_factor,
            depth: load.depth,
            force: solution.balance.contact.iter().map(|f| -f).collect(),
            contact_measure: contact,
            contact_radius: if dim == 3 || solution.surface.revolution() {
                (contact / PI).sqrt()
            } else {
                0.5 * contact
            },
            max_pressure: rows.iter().map(|r| -r.sigma_nu).fold(0.0, f64::max),
            phi_center: center.map_or(0.0, |i| rows[i].phi),
            phi_mean,
            stick_measure: stick,
            slip_measure: slip,
            newton_steps: solution.inner_iterations.iter().sum(),
            kkt_residual: solution.kkt.max,
            converged: solution.converged(),
            charges: solution.balance.charges.clone(),
            potentials: solution.balance.potentials.clone(),
            supports: solution.balance.supports.clone(),
        }
    }
}

/// A column of curve.csv.
#[derive(Clone, Debug, PartialEq)]
pub enum Column {
    /// Counts (step, newton_steps).
    Integer(Vec<usize>),
    /// Quantities.
    Real(Vec<f64>),
    /// converged.
    Flag(Vec<bool>),
}

impl Column {
    fn cell(&self, k: usize) -> String {
        match self {
            Self::Integer(v) => v[k].to_string(),
            Self::Real(v) => csv_number(v[k]),
            Self::Flag(v) => v[k].to_string(),
        }
    }
}

/// The columns of curve.csv, named and in order, for `rows` of a d-dimensional body whose
/// grounded parts are `parts` (one `charge_<part>` each) and whose reported clamps and
/// supports are `supports` (d `reaction_<name>_<axis>` columns each).
pub fn curve_columns(
    rows: &[CurveRow],
    dim: usize,
    (supports, parts, electrodes): (&[String], &[String], &[String]),
) -> Vec<(String, Column)> {
    let real = |f: &dyn Fn(&CurveRow) -> f64| Column::Real(rows.iter().map(f).collect());
    let mut columns = vec![
        ("step".to_string(), Column::Integer(rows.iter().map(|r| r.step).collect())),
        ("load_factor".into(), real(&|r| r.load_factor)),
        ("depth".into(), real(&|r| r.depth)),
    ];
    for (k, name) in ["force_x", "force_y", "force_z"][..dim].iter().enumerate() {
        columns.push((name.to_string(), real(&|r| r.force[k])));
    }
    type Quantity = (&'static str, fn(&CurveRow) -> f64);
    let quantities: [Quantity; 7] = [
        ("contact_measure", |r| r.contact_measure),
        ("contact_radius", |r| r.contact_radius),
        ("max_pressure", |r| r.max_pressure),
        ("phi_center", |r| r.phi_center),
        ("phi_mean", |r| r.phi_mean),
        ("stick_measure", |r| r.stick_measure),
        ("slip_measure", |r| r.slip_measure),
    ];
    columns.extend(quantities.iter().map(|(name, f)| (name.to_string(), real(f))));
    columns.push((
        "newton_steps".into(),
        Column::Integer(rows.iter().map(|r| r.newton_steps).collect()),
    ));
    columns.push(("kkt_residual".into(), real(&|r| r.kkt_residual)));
    columns.push(("converged".into(), Column::Flag(rows.iter().map(|r| r.converged).collect())));
    let per_row: Vec<_> = rows
        .iter()
        .map(|r| (r.supports.as_slice(), r.charges.as_slice(), r.potentials.as_slice()))
        .collect();
    columns.extend(held_and_charge_columns(dim, (supports, parts, electrodes), &per_row));
    columns
}

/// What the last columns of curve.csv read of a step: the reactions of the clamps and
/// supports, the charges (grounded parts, then electrodes) and the electrodes' potentials.
type RowValues<'a> = (&'a [Vec<f64>], &'a [f64], &'a [f64]);

/// The columns every path's curve.csv ends with: `reaction_<name>_<x|y|z>` for each clamp
/// and support named in `supports`, then `charge_<part>` for each grounded part in `parts`,
/// then `phi_<name>` and `charge_<name>` for each electrode named in `electrodes`, from each
/// row's reactions, charges (the grounded parts', then the electrodes') and potentials.
fn held_and_charge_columns(
    dim: usize,
    (supports, parts, electrodes): (&[String], &[String], &[String]),
    per_row: &[RowValues],
) -> Vec<(String, Column)> {
    let mut columns = Vec::new();
    for (j, support) in supports.iter().enumerate() {
        for (k, axis) in ["x", "y", "z"][..dim].iter().enumerate() {
            let values = per_row.iter().map(|(r, ..)| r[j][k]).collect();
            columns.push((format!("reaction_{support}_{axis}"), Column::Real(values)));
        }
    }
    for (k, part) in parts.iter().enumerate() {
        let values = per_row.iter().map(|(_, q, _)| q[k]).collect();
        columns.push((format!("charge_{part}"), Column::Real(values)));
    }
    for (j, name) in electrodes.iter().enumerate() {
        let potentials = per_row.iter().map(|(.., phi)| phi[j]).collect();
        columns.push((format!("phi_{name}"), Column::Real(potentials)));
        let charges = per_row.iter().map(|(_, q, _)| q[parts.len() + j]).collect();
        columns.push((format!("charge_{name}"), Column::Real(charges)));
    }
    columns
}

/// A CSV of `n` rows: a header of the columns' names, then one line per row.
pub fn columns_csv(columns: &[(String, Column)], n: usize) -> String {
    let header: Vec<&str> = columns.iter().map(|(name, _)| name.as_str()).collect();
    let mut csv = header.join(",") + "\n";
    for k in 0..n {
        let line: Vec<String> = columns.iter().map(|(_, c)| c.cell(k)).collect();
        csv += &(line.join(",") + "\n");
    }
    csv
}

/// One row of the curve.csv of a loading path without contact: the step's load factor, the
/// clamps' reaction and the electrodes' charges.
#[derive(Clone, Debug, PartialEq)]
pub struct StaticCurveRow {
    /// The step, from 1.
    pub step: usize,
    /// The factor on the applied loads [-].
    pub load_factor: f64,
    /// The force of the clamps and supports on the body, d components
    /// [stress·length^(d−1)].
    pub reaction: Vec<f64>,
    /// The force of each clamp and support, d components each.
    pub supports: Vec<Vec<f64>>,
    /// The charge on each part of Γa and each electrode [charge·length^(3−d)].
    pub charges: Vec<f64>,
    /// The potential of each electrode beyond the grounded parts \[potential\].
    pub potentials: Vec<f64>,
}

/// The columns of the curve.csv of a loading path without contact: `step`, `load_factor`,
/// `reaction_x`… (the clamps' and supports' reaction in all), `reaction_<name>_x`… per
/// reported clamp and support (`supports`), and one `charge_<part>` per
/// grounded part (`parts`).
pub fn static_curve_columns(
    rows: &[StaticCurveRow],
    dim: usize,
    (supports, parts, electrodes): (&[String], &[String], &[String]),
) -> Vec<(String, Column)> {
    let real = |f: &dyn Fn(&StaticCurveRow) -> f64| Column::Real(rows.iter().map(f).collect());
    let mut columns = vec![
        ("step".to_string(), Column::Integer(rows.iter().map(|r| r.step).collect())),
        ("load_factor".into(), real(&|r| r.load_factor)),
    ];
    for (k, name) in ["reaction_x", "reaction_y", "reaction_z"][..dim].iter().enumerate() {
        columns.push((name.to_string(), real(&|r| r.reaction[k])));
    }
    let per_row: Vec<_> = rows
        .iter()
        .map(|r| (r.supports.as_slice(), r.charges.as_slice(), r.potentials.as_slice()))
        .collect();
    columns.extend(held_and_charge_columns(dim, (supports, parts, electrodes), &per_row));
    columns
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A curve's CSV writes no NaN or infinity as a token: such a cell is empty, and finite
    /// values keep the bytes of `{:e}`.
    #[test]
    fn non_finite_cells_are_empty_and_finite_ones_keep_their_bytes() {
        let columns = vec![
            ("step".to_string(), Column::Integer(vec![1, 2, 3])),
            ("value".to_string(), Column::Real(vec![f64::NAN, f64::INFINITY, -2.5e-3])),
            ("flag".to_string(), Column::Flag(vec![true, false, true])),
        ];
        let csv = columns_csv(&columns, 3);
        assert_eq!(csv, "step,value,flag\n1,,true\n2,,false\n3,-2.5e-3,true\n");
    }
}
