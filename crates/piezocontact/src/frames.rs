//! Nodal frames of the fixed displacement directions (model §4, supports). Clamps and
//! supports fix u·n = g at a node for directions n: the mesh axes, or a face's outward
//! normal (a roller on a turned face). At each node the directions are merged: two within
//! [`SAME_DIRECTION_DEGREES`] are one component (their values must agree), and the others
//! together fix the subspace they span. Where every direction is an axis the node keeps the
//! mesh axes; elsewhere it gets an orthonormal frame whose first components span the fixed
//! subspace, and the global system's unknowns at that node are its components in the frame.

use crate::error::{Error, Result};

/// The table of a condition no clamp or support sets (u_r = 0 on the axis of an
/// axisymmetric body), and of a u DOF that nothing fixes.
pub const NO_TABLE: usize = usize::MAX;

/// The name of table `table` among `names`, for messages.
fn table_name(names: &[String], table: usize) -> &str {
    names.get(table).map_or("the axis (u_r = 0 there)", String::as_str)
}

/// Two fixed directions at a node within this angle are the same component \[degrees\].
pub const SAME_DIRECTION_DEGREES: f64 = 1.0;

/// A component of a direction below this is taken as 0 (an axis up to round-off) [-].
const ROUND_OFF: f64 = 1e-12;

/// A direction whose part outside the span of the earlier ones is below this adds nothing
/// to the fixed subspace (its value must agree with theirs) [-].
const DEPENDENT: f64 = 1e-6;

/// A direction of u fixed at a node by a clamp or a support.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FixedDirection {
    /// The node.
    pub node: usize,
    /// The unit direction n (3 components, the last 0 in 2D).
    pub direction: [f64; 3],
    /// The prescribed u·n \[length\].
    pub value: f64,
    /// The clamp or support that fixes it: an index into
    /// [`crate::problem::Problem::support_names`].
    pub table: usize,
}

/// The fixed components of one node in its frame.
#[derive(Clone, Debug, PartialEq)]
pub struct NodeFrame {
    /// The node.
    pub node: usize,
    /// The frame's unit vectors (rows, in mesh components); `None`: the mesh axes.
    pub rows: Option<[[f64; 3]; 3]>,
    /// Each fixed component of the frame: (component, prescribed value \[length\], table).
    pub fixed: Vec<(usize, f64, usize)>,
}

impl NodeFrame {
    /// The unit vector of component `i` in mesh components.
    pub fn direction(&self, i: usize) -> [f64; 3] {
        self.rows.map_or_else(|| axis(i), |rows| rows[i])
    }
}

/// The unit vector along mesh axis `i`.
pub fn axis(i: usize) -> [f64; 3] {
    let mut e = [0.0; 3];
    e[i] = 1.0;
    e
}

fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

fn unit(v: [f64; 3]) -> [f64; 3] {
    let n = dot(&v, &v).sqrt();
    [v[0] / n, v[1] / n, v[2] / n]
}

/// The frame of one node from the directions fixed there (all with that node, in the order
/// of the tables: a component fixed again keeps its first table), in a `dim`-dimensional
/// mesh; `names` are the tables' names for errors.
pub fn node_frame(dim: usize, entries: &[FixedDirection], names: &[String]) -> Result<NodeFrame> {
    let merged = merge(entries, names)?;
    let node = entries.first().map_or(0, |e| e.node);
    let axes: Option<Vec<(usize, f64, usize)>> = merged
        .iter()
        .map(|e| {
            let k = (0..3).find(|&k| e.direction[k].abs() == 1.0)?;
            Some((k, e.value * e.direction[k], e.table))
        })
        .collect();
    if let Some(fixed) = axes {
        return Ok(NodeFrame { node, rows: None, fixed });
    }
    let (basis, tables) = span(&merged);
    let alpha = span_values(&merged, &basis).ok_or_else(|| {
        let list: Vec<String> = merged
            .iter()
            .map(|e| format!("{} along {:?} by '{}'", e.value, e.direction, table_name(names, e.table)))
            .collect();
        Error::Input(format!(
            "node {node} has its displacement fixed along directions that lie in one plane or line, to values no displacement meets: {}; give them consistent values, or hold the node by fewer supports",
            list.join(", ")
        ))
    })?;
    let rows = complete(dim, &basis);
    let fixed = (0..basis.len()).map(|i| (i, alpha[i], tables[i])).collect();
    Ok(NodeFrame { node, rows: Some(rows), fixed })
}

/// The directions with those within [`SAME_DIRECTION_DEGREES`] of an earlier one left out
/// (their values checked against it, an opposite direction with its value turned), and
/// components below round-off set to 0.
fn merge(entries: &[FixedDirection], names: &[String]) -> Result<Vec<FixedDirection>> {
    let same = SAME_DIRECTION_DEGREES.to_radians().cos();
    let mut merged: Vec<FixedDirection> = Vec::new();
    for e in entries {
        let mut e = *e;
        e.direction = e.direction.map(|c| if c.abs() < ROUND_OFF { 0.0 } else { c });
        e.direction = unit(e.direction);
        e.direction =
            e.direction.map(|c| if (c.abs() - 1.0).abs() < ROUND_OFF { c.signum() } else { c });
        match merged.iter().find(|m| dot(&m.direction, &e.direction).abs() >= same) {
            None => merged.push(e),
            Some(first) => {
                let value = e.value * dot(&first.direction, &e.direction).signum();
                check_same_value(first, (value, e.table), names)?;
            }
        }
    }
    Ok(merged)
}

/// Refuses `value` from table `table` for a component that `first` fixes already, unless it
/// is the same value (to 1e-12 relative).
fn check_same_value(
    first: &FixedDirection,
    (value, table): (f64, usize),
    names: &[String],
) -> Result<()> {
    let scale = first.value.abs().max(value.abs());
    if (first.value - value).abs() <= 1e-12 * scale {
        return Ok(());
    }
    let along = match (0..3).find(|&k| first.direction[k] == 1.0) {
        Some(k) => ["x", "y", "z"][k].to_string(),
        None => format!("{:?}", first.direction),
    };
    Err(Error::Input(format!(
        "node {} has its displacement along {along} fixed to {} by '{}' and to {value} by '{}': give both the same value there, or hold the node by one of them",
        first.node,
        first.value,
        table_name(names, first.table),
        table_name(names, table)
    )))
}

/// An orthonormal basis of the span of the directions (Gram–Schmidt in their order), with
/// the table of the direction each vector came from.
fn span(merged: &[FixedDirection]) -> (Vec<[f64; 3]>, Vec<usize>) {
    let (mut basis, mut tables): (Vec<[f64; 3]>, Vec<usize>) = (Vec::new(), Vec::new());
    for e in merged {
        let mut v = e.direction;
        for q in &basis {
            let c = dot(&v, q);
            v = [v[0] - c * q[0], v[1] - c * q[1], v[2] - c * q[2]];
        }
        if dot(&v, &v).sqrt() > DEPENDENT {
            basis.push(unit(v));
            tables.push(e.table);
        }
    }
    (basis, tables)
}

/// The components α of the fixed part of u in `basis` that meet every u·n = g (least
/// squares, then checked to 1e-9 of the largest value); `None` if they cannot all be met.
fn span_values(merged: &[FixedDirection], basis: &[[f64; 3]]) -> Option<Vec<f64>> {
    let k = basis.len();
    let a: Vec<Vec<f64>> =
        merged.iter().map(|e| basis.iter().map(|q| dot(&e.direction, q)).collect()).collect();
    let mut normal = vec![vec![0.0; k + 1]; k];
    for (row, e) in a.iter().zip(merged) {
        for i in 0..k {
            (0..k).for_each(|j| normal[i][j] += row[i] * row[j]);
            normal[i][k] += row[i] * e.value;
        }
    }
    let alpha = gauss(normal)?;
    let scale = merged.iter().map(|e| e.value.abs()).fold(0.0, f64::max);
    let met = a.iter().zip(merged).all(|(row, e)| {
        let got: f64 = row.iter().zip(&alpha).map(|(r, x)| r * x).sum();
        (got - e.value).abs() <= 1e-9 * scale
    });
    met.then_some(alpha)
}

/// Solves the k × k system held with its right-hand side as column k (partial pivoting).
fn gauss(mut m: Vec<Vec<f64>>) -> Option<Vec<f64>> {
    let k = m.len();
    for c in 0..k {
        let p = (c..k).max_by(|&i, &j| m[i][c].abs().total_cmp(&m[j][c].abs()))?;
        m.swap(c, p);
        if m[c][c].abs() < 1e-14 {
            return None;
        }
        for r in c + 1..k {
            let f = m[r][c] / m[c][c];
            (c..=k).for_each(|j| m[r][j] -= f * m[c][j]);
        }
    }
    let mut x = vec![0.0; k];
    for r in (0..k).rev() {
        let s: f64 = (r + 1..k).map(|j| m[r][j] * x[j]).sum();
        x[r] = (m[r][k] - s) / m[r][r];
    }
    Some(x)
}

/// The frame whose first rows are `basis`, completed to an orthonormal basis of the
/// `dim`-dimensional space (rows beyond `dim` 0).
fn complete(dim: usize, basis: &[[f64; 3]]) -> [[f64; 3]; 3] {
    let mut rows = [[0.0; 3]; 3];
    rows[..basis.len()].copy_from_slice(basis);
    let first = basis[0];
    match (dim, basis.len()) {
        (2, 1) => rows[1] = [-first[1], first[0], 0.0],
        (3, 1) => {
            let k = (0..3).min_by(|&i, &j| first[i].abs().total_cmp(&first[j].abs())).unwrap_or(0);
            let e = axis(k);
            let c = dot(&e, &first);
            rows[1] = unit([e[0] - c * first[0], e[1] - c * first[1], e[2] - c * first[2]]);
            rows[2] = cross(&first, &rows[1]);
        }
        (3, 2) => rows[2] = cross(&basis[0], &basis[1]),
        _ => {}
    }
    rows
}

#[cfg(test)]
mod tests {
    use super::*;

    fn entry(direction: [f64; 3], value: f64, table: usize) -> FixedDirection {
        FixedDirection { node: 7, direction, value, table }
    }

    fn names() -> Vec<String> {
        vec!["a".into(), "b".into(), "c".into()]
    }

    #[test]
    fn axes_keep_the_mesh_frame_and_an_opposite_axis_turns_its_value() {
        let f = node_frame(3, &[entry([0.0, 0.0, -1.0], 0.5, 1), entry(axis(0), 0.0, 2)], &names())
            .unwrap();
        assert_eq!(f.rows, None);
        assert_eq!(f.fixed, vec![(2, -0.5, 1), (0, 0.0, 2)]);
    }

    #[test]
    fn a_turned_normal_gets_an_orthonormal_frame_whose_first_row_is_the_normal() {
        let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
        let f = node_frame(3, &[entry([c, s, 0.0], 0.25, 0)], &names()).unwrap();
        let rows = f.rows.unwrap();
        for i in 0..3 {
            for j in 0..3 {
                let expected = if i == j { 1.0 } else { 0.0 };
                assert!((dot(&rows[i], &rows[j]) - expected).abs() < 1e-15);
            }
        }
        assert_eq!(rows[0], [c, s, 0.0]);
        assert!((dot(&cross(&rows[0], &rows[1]), &rows[2]) - 1.0).abs() < 1e-15);
        assert_eq!(f.fixed, vec![(0, 0.25, 0)]);
    }

    #[test]
    fn two_directions_fix_the_plane_they_span_with_both_values_met() {
        let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
        let f =
            node_frame(3, &[entry(axis(0), 0.1, 0), entry([c, s, 0.0], 0.3, 1)], &names()).unwrap();
        let rows = f.rows.unwrap();
        let u: Vec<f64> =
            (0..3).map(|m| f.fixed.iter().map(|&(i, v, _)| v * rows[i][m]).sum()).collect();
        assert!((u[0] - 0.1).abs() < 1e-15);
        assert!((c * u[0] + s * u[1] - 0.3).abs() < 1e-15);
        assert!(u[2].abs() < 1e-15 && rows[2][2].abs() == 1.0);
        assert_eq!(f.fixed.iter().map(|f| f.2).collect::<Vec<_>>(), vec![0, 1]);
    }

    #[test]
    fn directions_within_one_degree_are_one_component_and_must_agree() {
        let tilt = 0.5f64.to_radians();
        let near = [tilt.cos(), tilt.sin(), 0.0];
        let f = node_frame(2, &[entry(axis(0), 0.2, 0), entry(near, 0.2, 1)], &names()).unwrap();
        assert_eq!(f.fixed, vec![(0, 0.2, 0)]);
        let e = node_frame(2, &[entry(axis(0), 0.2, 0), entry(near, 0.3, 1)], &names());
        let message = e.unwrap_err().to_string();
        assert!(message.contains("node 7") && message.contains("'a'") && message.contains("'b'"));
    }

    #[test]
    fn dependent_directions_with_values_no_displacement_meets_are_refused() {
        let h = 0.5f64.sqrt();
        let fixed = [entry(axis(0), 0.0, 0), entry(axis(1), 0.0, 1), entry([h, h, 0.0], 1.0, 2)];
        let e = node_frame(3, &fixed, &names()).unwrap_err().to_string();
        assert!(e.contains("consistent values"), "{e}");
        let fixed =
            [entry(axis(0), 1.0, 0), entry(axis(1), 1.0, 1), entry([h, h, 0.0], 2.0 * h, 2)];
        let f = node_frame(3, &fixed, &names()).unwrap();
        assert_eq!(f.fixed.len(), 2);
    }
}
