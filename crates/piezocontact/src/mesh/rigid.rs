//! The rigid motions of a body that its fixed displacement components leave free: 3 in 2D
//! (translations along x and y, the rotation about z), 6 in 3D (translations along and
//! rotations about x, y, z), tested against the fixed components of each connected piece.

use super::{Mesh, Pieces};
use crate::error::Result;
use crate::linalg::null_space;

/// Relative size of an eigenvalue of the rigid modes' Gram matrix below which a motion is
/// free: the fixed components do not hold it.
const FREE: f64 = 1e-10;

/// The rigid motions left free on each piece of the mesh by the fixed directions `fixed`
/// ((node, unit direction) pairs, 3 components), in words ("translate along y", "rotate about z", or a
/// combined motion with its axis): one entry (piece, motions) per piece that is not held.
pub fn free_rigid_motions(
    mesh: &Mesh,
    pieces: &Pieces,
    fixed: &[(usize, [f64; 3])],
) -> Result<Vec<(usize, Vec<String>)>> {
    let dim = mesh.dim();
    let m = if dim == 2 { 3 } else { 6 };
    let n_pieces = pieces.cells.len();
    let mut gram = vec![vec![0.0; m * m]; n_pieces];
    for &(node, direction) in fixed {
        let piece = pieces.of_node[node];
        let mut row = vec![0.0; m];
        for (component, n) in direction.iter().enumerate().take(dim).filter(|(_, n)| **n != 0.0) {
            let modes = mode_components(mesh, pieces, node, component);
            row.iter_mut().zip(modes).for_each(|(r, v)| *r += n * v);
        }
        for i in 0..m {
            for j in 0..m {
                gram[piece][i + m * j] += row[i] * row[j];
            }
        }
    }
    let mut free = Vec::new();
    for (piece, gram) in gram.iter().enumerate().filter(|(p, _)| pieces.cells[*p] > 0) {
        let basis = null_space(gram, m, FREE)?;
        if !basis.is_empty() {
            free.push((piece, describe(&basis, dim, pieces, piece)));
        }
    }
    Ok(free)
}

/// Component `component` at `node` of each rigid mode: the translations e_k, then the
/// rotations ω × (x − c) about the axes through the piece's centre c, divided by its size.
fn mode_components(mesh: &Mesh, pieces: &Pieces, node: usize, component: usize) -> Vec<f64> {
    let dim = mesh.dim();
    let (centre, size) = centre_and_size(pieces, pieces.of_node[node]);
    let mut r = [0.0; 3];
    for k in 0..dim {
        r[k] = (mesh.node(node)[k] - centre[k]) / size;
    }
    let mut row: Vec<f64> = (0..dim).map(|k| if k == component { 1.0 } else { 0.0 }).collect();
    let axes: &[usize] = if dim == 2 { &[2] } else { &[0, 1, 2] };
    for &axis in axes {
        let mut omega = [0.0; 3];
        omega[axis] = 1.0;
        row.push(cross(omega, r)[component]);
    }
    row
}

/// The centre of a piece's bounding box and its diagonal (1 for a point).
fn centre_and_size(pieces: &Pieces, piece: usize) -> ([f64; 3], f64) {
    let (lo, hi) = &pieces.boxes[piece];
    let mut centre = [0.0; 3];
    let mut size = 0.0;
    for k in 0..lo.len() {
        centre[k] = 0.5 * (lo[k] + hi[k]);
        size += (hi[k] - lo[k]).powi(2);
    }
    (centre, if size > 0.0 { size.sqrt() } else { 1.0 })
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// The free motions spanned by `basis` (orthonormal, in the modes' coordinates), in words:
/// first each mode along an axis that lies in the span, then what remains of the span.
fn describe(basis: &[Vec<f64>], dim: usize, pieces: &Pieces, piece: usize) -> Vec<String> {
    let m = basis[0].len();
    let axis = ["x", "y", "z"];
    let name = |k: usize| match (dim, k) {
        (_, k) if k < dim => format!("translate along {}", axis[k]),
        (2, _) => "rotate about z".to_string(),
        (_, k) => format!("rotate about {}", axis[k - dim]),
    };
    let in_span = |k: usize| basis.iter().map(|v| v[k] * v[k]).sum::<f64>() > 1.0 - 1e-8;
    let named: Vec<usize> = (0..m).filter(|&k| in_span(k)).collect();
    let mut words: Vec<String> = named.iter().map(|&k| name(k)).collect();
    // What the named modes leave of the span, orthonormalised.
    let mut rest: Vec<Vec<f64>> = Vec::new();
    for v in basis {
        let mut w = v.clone();
        named.iter().for_each(|&k| w[k] = 0.0);
        for r in &rest {
            let d: f64 = w.iter().zip(r).map(|(a, b)| a * b).sum();
            w.iter_mut().zip(r).for_each(|(a, b)| *a -= d * b);
        }
        let norm = w.iter().map(|a| a * a).sum::<f64>().sqrt();
        if norm > 1e-6 {
            rest.push(w.iter().map(|a| a / norm).collect());
        }
    }
    let (centre, size) = centre_and_size(pieces, piece);
    words.extend(rest.iter().map(|w| combined(w, dim, centre, size)));
    words
}

/// A free motion that is no single mode: a translation along a direction, or a rotation
/// about an axis through a point (u = t + ω × (x − c) = ω × (x − p), p = c + ω × t/|ω|²).
fn combined(w: &[f64], dim: usize, centre: [f64; 3], size: f64) -> String {
    let mut t = [0.0; 3];
    let mut omega = [0.0; 3];
    t[..dim].copy_from_slice(&w[..dim]);
    match dim {
        2 => omega[2] = w[2] / size,
        _ => omega.copy_from_slice(&w[3..6].iter().map(|o| o / size).collect::<Vec<_>>()),
    }
    let round = |v: f64| format!("{:.4}", v);
    let list = |v: &[f64]| v.iter().map(|a| round(*a)).collect::<Vec<_>>().join(", ");
    let omega_2 = omega.iter().map(|o| o * o).sum::<f64>();
    if omega_2.sqrt() * size < 1e-6 {
        return format!("translate along ({})", list(&t[..dim]));
    }
    let shift = cross(omega, t);
    let point: Vec<f64> = (0..dim).map(|k| centre[k] + shift[k] / omega_2).collect();
    let norm = omega_2.sqrt();
    let direction: Vec<f64> = omega.iter().map(|o| o / norm).collect();
    match dim {
        2 => format!("rotate about z through ({})", list(&point)),
        _ => {
            format!("rotate about an axis along ({}) through ({})", list(&direction), list(&point))
        }
    }
}

/// The motions in a sentence: "translate along y and rotate about z".
pub fn motions_sentence(motions: &[String]) -> String {
    match motions {
        [] => String::new(),
        [one] => one.clone(),
        [head @ .., last] => format!("{} and {last}", head.join(", ")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::rectangle::Rectangle;

    /// The unit square in 2 × 2 cells.
    fn square() -> Mesh {
        let diagonal = crate::mesh::rectangle::Diagonal::Right;
        Rectangle { x: [0.0, 1.0], y: [0.0, 1.0], nx: 2, ny: 2, diagonal }.mesh(&[]).unwrap()
    }

    /// A clamped edge holds the square; a roller along y on the bottom leaves x and the
    /// rotation free; a roller on the bottom and one along x at a corner leave the rotation
    /// about z free, through that corner... unless the corner is held along y as well.
    #[test]
    fn free_motions_are_named() {
        let mesh = square();
        let pieces = mesh.pieces();
        let node_at = |x: f64, y: f64| {
            (0..mesh.n_nodes()).find(|&a| mesh.node(a) == [x, y]).expect("a node there")
        };
        let bottom: Vec<usize> = [0.0, 0.5, 1.0].iter().map(|&x| node_at(x, 0.0)).collect();
        let e = crate::frames::axis;
        let clamp: Vec<(usize, [f64; 3])> =
            bottom.iter().flat_map(|&a| [(a, e(0)), (a, e(1))]).collect();
        assert!(free_rigid_motions(&mesh, &pieces, &clamp).unwrap().is_empty());
        let roller: Vec<(usize, [f64; 3])> = bottom.iter().map(|&a| (a, e(1))).collect();
        let free = free_rigid_motions(&mesh, &pieces, &roller).unwrap();
        assert_eq!(free, [(0, vec!["translate along x".to_string()])]);
        let nothing = free_rigid_motions(&mesh, &pieces, &[]).unwrap();
        let all = ["translate along x", "translate along y", "rotate about z"];
        assert_eq!(nothing, [(0, all.map(String::from).to_vec())]);
        assert_eq!(
            motions_sentence(&nothing[0].1),
            "translate along x, translate along y and rotate about z"
        );
        // One node held in both components: the rotation about it is free.
        let pin = [(node_at(1.0, 1.0), e(0)), (node_at(1.0, 1.0), e(1))];
        let free = free_rigid_motions(&mesh, &pieces, &pin).unwrap();
        assert_eq!(free, [(0, vec!["rotate about z through (1.0000, 1.0000)".to_string()])]);
        // A roller along the diagonal on the bottom holds the rotation (u·n varies with x)
        // and one translation: the one along the diagonal's normal stays free.
        let h = 0.5f64.sqrt();
        let turned: Vec<(usize, [f64; 3])> = bottom.iter().map(|&a| (a, [h, h, 0.0])).collect();
        let free = free_rigid_motions(&mesh, &pieces, &turned).unwrap();
        assert_eq!(free.len(), 1);
        assert_eq!(free[0].1.len(), 1, "{free:?}");
        assert!(!free[0].1[0].contains("rotate"), "{free:?}");
    }
}
