//! A material's axes in the mesh: from a poling vector or from Euler angles, and the rotation
//! of its tensors into the mesh's axes.
//!
//! The axes are the columns of a rotation R (material axis k is column k, in mesh
//! coordinates), so that R maps material components to mesh components: c'_ijkl =
//! R_ip R_jq R_kr R_ls c_pqrs, e'_ijk = R_ip R_jq R_kr e_pqr, β' = R β Rᵀ — the tensor form of
//! Bond's rotation of the Voigt matrices (c' = M c Mᵀ, e' = R e Mᵀ).

use super::voigt::{Matrix3, Tensor3, Tensor4};

/// The identity: the material's axes are the mesh's.
pub const IDENTITY: Matrix3 = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

/// The axes of a material poled along `p` (mesh coordinates, nonzero): axis 3 = p/|p|, axis 1
/// = p × e_z normalised (e_x where p is along ±z), axis 2 = axis 3 × axis 1. For p = +z the
/// identity.
pub fn axes_from_poling(p: [f64; 3]) -> Matrix3 {
    let norm = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let length = norm(p);
    let axis3 = p.map(|v| v / length);
    let across = cross(axis3, [0.0, 0.0, 1.0]);
    let axis1 = if norm(across) < 1e-12 {
        [1.0, 0.0, 0.0]
    } else {
        let n = norm(across);
        across.map(|v| v / n)
    };
    let axis2 = cross(axis3, axis1);
    columns([axis1, axis2, axis3])
}

/// The axes of Euler angles [φ1, Φ, φ2] in degrees: R = Rz(φ1)·Rx(Φ)·Rz(φ2).
pub fn axes_from_euler([phi1, big_phi, phi2]: [f64; 3]) -> Matrix3 {
    let rz = |angle: f64| {
        let (s, c) = angle.to_radians().sin_cos();
        [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]
    };
    let (s, c) = big_phi.to_radians().sin_cos();
    let rx = [[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]];
    super::voigt::product(&super::voigt::product(&rz(phi1), &rx), &rz(phi2))
}

/// The matrix whose columns are `axes`.
fn columns(axes: [[f64; 3]; 3]) -> Matrix3 {
    let mut r = [[0.0; 3]; 3];
    for (k, axis) in axes.iter().enumerate() {
        for (i, v) in axis.iter().enumerate() {
            r[i][k] = *v;
        }
    }
    r
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// R β Rᵀ.
pub fn rotate_matrix(beta: &Matrix3, r: &Matrix3) -> Matrix3 {
    let mut out = [[0.0; 3]; 3];
    for (i, row) in out.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            for p in 0..3 {
                for q in 0..3 {
                    *v += r[i][p] * r[j][q] * beta[p][q];
                }
            }
        }
    }
    out
}

/// e'_ijk = R_ip R_jq R_kr e_pqr.
pub fn rotate_coupling(e: &Tensor3, r: &Matrix3) -> Tensor3 {
    let mut out = [[[0.0; 3]; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            for k in 0..3 {
                let mut v = 0.0;
                for p in 0..3 {
                    for q in 0..3 {
                        for s in 0..3 {
                            v += r[i][p] * r[j][q] * r[k][s] * e[p][q][s];
                        }
                    }
                }
                out[i][j][k] = v;
            }
        }
    }
    out
}

/// c'_ijkl = R_ip R_jq R_kr R_ls c_pqrs, in two passes of two indices.
pub fn rotate_stiffness(c: &Tensor4, r: &Matrix3) -> Tensor4 {
    // half[i][j][r][s] = Σ_pq R_ip R_jq c_pqrs, then the last two indices alike.
    let mut half = [[[[0.0; 3]; 3]; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            for a in 0..3 {
                for b in 0..3 {
                    half[i][j][a][b] = (0..9)
                        .map(|pq| r[i][pq / 3] * r[j][pq % 3] * c[pq / 3][pq % 3][a][b])
                        .sum();
                }
            }
        }
    }
    let mut out = [[[[0.0; 3]; 3]; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            for k in 0..3 {
                for l in 0..3 {
                    out[i][j][k][l] = (0..9)
                        .map(|rs| r[k][rs / 3] * r[l][rs % 3] * half[i][j][rs / 3][rs % 3])
                        .sum();
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::super::voigt::{coupling_tensor, stiffness_tensor};
    use super::*;

    fn close(a: &Matrix3, b: &Matrix3) -> bool {
        a.iter().flatten().zip(b.iter().flatten()).all(|(x, y)| (x - y).abs() < 1e-14)
    }

    #[test]
    fn poling_and_euler_angles_give_the_same_axes() {
        assert_eq!(axes_from_poling([0.0, 0.0, 2.0]), IDENTITY);
        let along_x = axes_from_poling([3.0, 0.0, 0.0]);
        assert_eq!(along_x, [[0.0, 0.0, 1.0], [-1.0, 0.0, 0.0], [0.0, -1.0, 0.0]]);
        assert!(close(&along_x, &axes_from_euler([90.0, 90.0, 180.0])));
        // −z (the opposite-poled layer): axis 1 = e_x, axis 2 = −e_y.
        assert_eq!(
            axes_from_poling([0.0, 0.0, -1.0]),
            [[1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, -1.0]]
        );
        let tilted = axes_from_poling([1.0, 2.0, 2.0]);
        let rtr = super::super::voigt::product(&super::super::voigt::transpose(&tilted), &tilted);
        assert!(close(&rtr, &IDENTITY));
        assert!((0..3).all(|i| (tilted[i][2] - [1.0, 2.0, 2.0][i] / 3.0).abs() < 1e-15));
    }

    #[test]
    fn rotations_move_the_tensors_as_the_axes() {
        // A ceramic poled along x: e'_{x,xx} = +e33, e'_{x,yy} = e'_{x,zz} = e31, e'_{y,xy} = e15.
        let mut e = [[0.0; 6]; 3];
        (e[2][0], e[2][1], e[2][2], e[0][4], e[1][3]) = (-5.4, -5.4, 15.8, 12.3, 12.3);
        let rotated = rotate_coupling(&coupling_tensor(&e), &axes_from_poling([1.0, 0.0, 0.0]));
        assert!((rotated[0][0][0] - 15.8).abs() < 1e-14);
        assert!((rotated[0][1][1] + 5.4).abs() < 1e-14 && (rotated[0][2][2] + 5.4).abs() < 1e-14);
        assert!((rotated[1][0][1] - 12.3).abs() < 1e-14 && rotated[2][2][2].abs() < 1e-14);
        // A transversely isotropic stiffness: unchanged by a turn about its axis 3, and by a
        // whole turn about any axis.
        let mut c = [[0.0; 6]; 6];
        for (i, j, v) in
            [(0, 0, 120.3), (1, 1, 120.3), (2, 2, 110.9), (0, 1, 75.2), (0, 2, 75.1), (1, 2, 75.1)]
        {
            (c[i][j], c[j][i]) = (v, v);
        }
        (c[3][3], c[4][4], c[5][5]) = (21.1, 21.1, 22.55);
        let t = stiffness_tensor(&c);
        for r in [
            axes_from_euler([0.0, 0.0, 37.0]),
            axes_from_euler([360.0, 0.0, 0.0]),
            axes_from_euler([10.0, 360.0, -10.0]),
        ] {
            let turned = rotate_stiffness(&t, &r);
            let flat =
                |t: &Tensor4| t.iter().flatten().flatten().flatten().copied().collect::<Vec<f64>>();
            let distance =
                flat(&turned).iter().zip(flat(&t)).fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
            assert!(distance < 1e-12, "{distance:e}");
        }
    }
}
