//! The outward normal of boundary parts at their nodes: the area-weighted mean of the
//! outward normals of the node's facets on the parts (the direction a roller on a turned
//! face holds).

use super::Mesh;

/// A node where the facets of the parts turn: their normals differ by `degrees` \[degrees\].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Corner {
    /// The node (an edge or a corner of the parts).
    pub node: usize,
    /// The largest angle between two of its facets' normals \[degrees\].
    pub degrees: f64,
}

/// Each node of `parts` (ascending) with the unit outward normal there (3 components, the
/// last 0 in 2D); a node whose facets' normals differ by more than `max_degrees` is a
/// [`Corner`].
pub fn node_normals(
    mesh: &Mesh,
    parts: &[usize],
    max_degrees: f64,
) -> std::result::Result<Vec<(usize, [f64; 3])>, Corner> {
    let nodes = mesh.part_nodes(parts);
    let mut facets: Vec<Vec<(f64, [f64; 3])>> = vec![Vec::new(); nodes.len()];
    for &p in parts {
        for facet in mesh.part_facets(p) {
            let frame = mesh.facet_frame(facet);
            for a in facet {
                if let Ok(k) = nodes.binary_search(a) {
                    facets[k].push(frame);
                }
            }
        }
    }
    let min_cos = max_degrees.to_radians().cos();
    let mut normals = Vec::with_capacity(nodes.len());
    for (&node, around) in nodes.iter().zip(&facets) {
        let mut worst = 1.0f64;
        for (i, (_, a)) in around.iter().enumerate() {
            for (_, b) in &around[i + 1..] {
                worst = worst.min(a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
            }
        }
        if worst < min_cos {
            return Err(Corner { node, degrees: worst.clamp(-1.0, 1.0).acos().to_degrees() });
        }
        let mut sum = [0.0; 3];
        for (measure, n) in around {
            (0..3).for_each(|c| sum[c] += measure * n[c]);
        }
        let length = (sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]).sqrt();
        normals.push((node, sum.map(|c| c / length)));
    }
    Ok(normals)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::rectangle::{Diagonal, Rectangle};

    #[test]
    fn a_straight_side_has_its_outward_normal_and_a_corner_is_refused() {
        let parts: Vec<(String, Vec<_>)> = [("right", "{2}x[0,1]"), ("bottom", "[0,2]x{0}")]
            .iter()
            .map(|(name, spec)| (name.to_string(), vec![spec.parse().unwrap()]))
            .collect();
        let rectangle =
            Rectangle { x: [0.0, 2.0], y: [0.0, 1.0], nx: 4, ny: 2, diagonal: Diagonal::Right };
        let mesh = rectangle.mesh(&parts).unwrap();
        let right = mesh.part_index("right").unwrap();
        let normals = node_normals(&mesh, &[right], 1.0).unwrap();
        assert_eq!(normals.len(), 3);
        assert!(normals.iter().all(|(_, n)| *n == [1.0, 0.0, 0.0]));
        let bottom = mesh.part_index("bottom").unwrap();
        let corner = node_normals(&mesh, &[right, bottom], 1.0).unwrap_err();
        assert_eq!(mesh.node(corner.node), &[2.0, 0.0]);
        assert!((corner.degrees - 90.0).abs() < 1e-9);
    }
}
