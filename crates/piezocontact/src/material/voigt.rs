//! Voigt notation and the conversions between the two forms of the piezoelectric law.
//!
//! Voigt order 1 = xx, 2 = yy, 3 = zz, 4 = yz, 5 = xz, 6 = xy, with engineering shear strains
//! (γ_yz = 2ε_yz, …), so that σ_I = c_IJ ε_J and (Eε)_i = e_iJ ε_J. The stress-charge form is
//! σ = c^E ε − eᵀ E_field, D = e ε + ε^S E_field; the strain-charge form is ε = s^E σ + dᵀ
//! E_field, D = d σ + ε^T E_field, with E_field = −∇ϕ (the paper's (2.2)). One is converted into
//! the other by c^E = (s^E)⁻¹, e = d c^E, ε^S = ε^T − d c^E dᵀ.

use crate::error::Result;
use crate::linalg::symmetric_eigen;

/// A 6 × 6 matrix in Voigt order (c^E \[stress\] or s^E \[1/stress\]).
pub type Voigt = [[f64; 6]; 6];
/// A 3 × 6 coupling matrix in Voigt order (e [charge/length²] or d [charge/force]).
pub type Coupling = [[f64; 6]; 3];
/// A 3 × 3 matrix (a permittivity [charge/(potential·length)], a rotation).
pub type Matrix3 = [[f64; 3]; 3];
/// A fourth-order tensor c_ijkl \[stress\].
pub type Tensor4 = [[[[f64; 3]; 3]; 3]; 3];
/// A third-order tensor e_ijk [charge/length²].
pub type Tensor3 = [[[f64; 3]; 3]; 3];

/// The tensor index pair (i, j) of each Voigt index.
pub const PAIRS: [(usize, usize); 6] = [(0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1)];

/// The Voigt index of the tensor index pair (i, j).
pub fn voigt_index(i: usize, j: usize) -> usize {
    match (i.min(j), i.max(j)) {
        (a, b) if a == b => a,
        (1, 2) => 3,
        (0, 2) => 4,
        _ => 5,
    }
}

/// c_ijkl = c_IJ with I ↔ (i, j), J ↔ (k, l).
pub fn stiffness_tensor(c: &Voigt) -> Tensor4 {
    let mut t = [[[[0.0; 3]; 3]; 3]; 3];
    for (i, row) in t.iter_mut().enumerate() {
        for (j, block) in row.iter_mut().enumerate() {
            for (k, line) in block.iter_mut().enumerate() {
                for (l, v) in line.iter_mut().enumerate() {
                    *v = c[voigt_index(i, j)][voigt_index(k, l)];
                }
            }
        }
    }
    t
}

/// c_IJ of a tensor with the minor and major symmetries.
pub fn stiffness_voigt(t: &Tensor4) -> Voigt {
    let mut c = [[0.0; 6]; 6];
    for (a, &(i, j)) in PAIRS.iter().enumerate() {
        for (b, &(k, l)) in PAIRS.iter().enumerate() {
            c[a][b] = t[i][j][k][l];
        }
    }
    c
}

/// e_ijk = e_iJ with J ↔ (j, k).
pub fn coupling_tensor(e: &Coupling) -> Tensor3 {
    let mut t = [[[0.0; 3]; 3]; 3];
    for (i, plane) in t.iter_mut().enumerate() {
        for (j, row) in plane.iter_mut().enumerate() {
            for (k, v) in row.iter_mut().enumerate() {
                *v = e[i][voigt_index(j, k)];
            }
        }
    }
    t
}

/// e_iJ of a tensor symmetric in its last two indices.
pub fn coupling_voigt(t: &Tensor3) -> Coupling {
    let mut e = [[0.0; 6]; 3];
    for (i, row) in e.iter_mut().enumerate() {
        for (a, &(j, k)) in PAIRS.iter().enumerate() {
            row[a] = t[i][j][k];
        }
    }
    e
}

/// The stiffness of an isotropic material with bulk coefficient k0 and shear modulus µ
/// \[stress\]: c11 = k0 + 4µ/3, c12 = k0 − 2µ/3, c44 = µ.
pub fn isotropic_stiffness(k0: f64, mu: f64) -> Voigt {
    let mut c = [[0.0; 6]; 6];
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] = if i == j { k0 + 4.0 * mu / 3.0 } else { k0 - 2.0 * mu / 3.0 };
        }
        c[i + 3][i + 3] = mu;
    }
    c
}

/// The product A B of an M × K and a K × N matrix.
pub fn product<const M: usize, const K: usize, const N: usize>(
    a: &[[f64; K]; M],
    b: &[[f64; N]; K],
) -> [[f64; N]; M] {
    let mut p = [[0.0; N]; M];
    for (i, row) in p.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            *v = (0..K).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    p
}

/// Aᵀ.
pub fn transpose<const M: usize, const N: usize>(a: &[[f64; N]; M]) -> [[f64; M]; N] {
    let mut t = [[0.0; M]; N];
    for (i, row) in a.iter().enumerate() {
        for (j, v) in row.iter().enumerate() {
            t[j][i] = *v;
        }
    }
    t
}

/// The largest |a_ij − a_ji| relative to the largest |a_ij| (0 for a zero matrix).
pub fn asymmetry<const N: usize>(a: &[[f64; N]; N]) -> f64 {
    let scale = a.iter().flatten().fold(0.0_f64, |m, v| m.max(v.abs()));
    let mut worst = 0.0_f64;
    for i in 0..N {
        for j in 0..i {
            worst = worst.max((a[i][j] - a[j][i]).abs());
        }
    }
    if scale > 0.0 { worst / scale } else { 0.0 }
}

/// The eigenvalues of a symmetric matrix, ascending, with its eigenvectors.
fn eigen<const N: usize>(a: &[[f64; N]; N]) -> Result<(Vec<f64>, Vec<Vec<f64>>)> {
    let column_major: Vec<f64> = (0..N * N).map(|p| a[p % N][p / N]).collect();
    let (values, vectors) = symmetric_eigen(&column_major, N)?;
    let mut order: Vec<usize> = (0..N).collect();
    order.sort_by(|&p, &q| values[p].total_cmp(&values[q]));
    Ok((
        order.iter().map(|&k| values[k]).collect(),
        order.iter().map(|&k| vectors[k].clone()).collect(),
    ))
}

/// The smallest eigenvalue of a symmetric matrix.
pub fn smallest_eigenvalue<const N: usize>(a: &[[f64; N]; N]) -> Result<f64> {
    Ok(eigen(a)?.0[0])
}

/// A⁻¹ of a symmetric positive definite matrix, by its eigendecomposition (the caller has
/// checked the smallest eigenvalue).
pub fn inverse<const N: usize>(a: &[[f64; N]; N]) -> Result<[[f64; N]; N]> {
    let (values, vectors) = eigen(a)?;
    let mut inv = [[0.0; N]; N];
    for (i, row) in inv.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            *v = (0..N).map(|k| vectors[k][i] * vectors[k][j] / values[k]).sum();
        }
    }
    Ok(inv)
}

/// A⁻¹ of a general square matrix by Gauss–Jordan elimination with partial pivoting; `None`
/// when a pivot vanishes (A singular).
pub fn general_inverse<const N: usize>(a: &[[f64; N]; N]) -> Option<[[f64; N]; N]> {
    let mut m = *a;
    let mut inv = [[0.0; N]; N];
    (0..N).for_each(|i| inv[i][i] = 1.0);
    for col in 0..N {
        let pivot = (col..N).max_by(|&p, &q| m[p][col].abs().total_cmp(&m[q][col].abs()))?;
        if m[pivot][col] == 0.0 || !m[pivot][col].is_finite() {
            return None;
        }
        m.swap(col, pivot);
        inv.swap(col, pivot);
        let d = m[col][col];
        for j in 0..N {
            m[col][j] /= d;
            inv[col][j] /= d;
        }
        for row in 0..N {
            if row != col {
                let f = m[row][col];
                for j in 0..N {
                    m[row][j] -= f * m[col][j];
                    inv[row][j] -= f * inv[col][j];
                }
            }
        }
    }
    Some(inv)
}

/// A piezoelectric group as given: none (a dielectric), the stress-charge e [charge/length²]
/// (beside ε^S) or the strain-charge d [charge/force] (beside ε^T).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PiezoForm {
    /// A dielectric: no coupling.
    None,
    /// e, with ε^S.
    Stress(Coupling),
    /// d, with ε^T.
    Strain(Coupling),
}

impl PiezoForm {
    /// e and ε^S of this group beside the stiffness c^E \[stress\] and the permittivity it
    /// goes with (ε^T for d, else ε^S).
    pub fn stress_charge(&self, c: &Voigt, permittivity: &Matrix3) -> (Coupling, Matrix3) {
        match self {
            Self::None => ([[0.0; 6]; 3], *permittivity),
            Self::Stress(e) => (*e, *permittivity),
            Self::Strain(d) => stress_charge(c, d, permittivity),
        }
    }
}

/// The stress-charge form (c^E, e, ε^S) of a material given in the strain-charge form's
/// d [charge/force] and ε^T, with its stiffness c^E = (s^E)⁻¹ \[stress\] already known:
/// e = d c^E, ε^S = ε^T − e dᵀ.
pub fn stress_charge(c: &Voigt, d: &Coupling, eps_t: &Matrix3) -> (Coupling, Matrix3) {
    let e = product(d, c);
    let e_dt = product(&e, &transpose(d));
    let mut eps_s = *eps_t;
    for i in 0..3 {
        for j in 0..3 {
            eps_s[i][j] -= e_dt[i][j];
        }
    }
    (e, eps_s)
}

/// The strain-charge form (s^E, d, ε^T) of a material given in the stress-charge form:
/// s^E = (c^E)⁻¹, d = e s^E, ε^T = ε^S + d eᵀ.
pub fn strain_charge(
    c: &Voigt,
    e: &Coupling,
    eps_s: &Matrix3,
) -> Result<(Voigt, Coupling, Matrix3)> {
    let s = inverse(c)?;
    let d = product(e, &s);
    let d_et = product(&d, &transpose(e));
    let mut eps_t = *eps_s;
    for i in 0..3 {
        for j in 0..3 {
            eps_t[i][j] += d_et[i][j];
        }
    }
    Ok((s, d, eps_t))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn voigt_and_tensor_forms_agree() {
        let mut c = [[0.0; 6]; 6];
        for (i, row) in c.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                *v = (1 + i.min(j) * 7 + i.max(j)) as f64;
            }
        }
        let t = stiffness_tensor(&c);
        assert_eq!(stiffness_voigt(&t), c);
        // σ_xy from ε_yz through both: c_1223 = c_64.
        assert_eq!(t[0][1][1][2], c[5][3]);
        let e = [[1.0, 2.0, 3.0, 4.0, 5.0, 6.0], [7.0, 8.0, 9.0, 10.0, 11.0, 12.0], [0.5; 6]];
        assert_eq!(coupling_voigt(&coupling_tensor(&e)), e);
        assert_eq!(coupling_tensor(&e)[1][2][0], e[1][4]);
    }

    #[test]
    fn the_two_forms_convert_into_each_other() {
        // An isotropic stiffness with a ceramic's coupling: back and forth to round-off.
        let c = isotropic_stiffness(90.0, 21.0);
        let mut e = [[0.0; 6]; 3];
        (e[2][0], e[2][1], e[2][2], e[0][4], e[1][3]) = (-5.4, -5.4, 15.8, 12.3, 12.3);
        let eps_s = [[8.1, 0.0, 0.0], [0.0, 8.1, 0.0], [0.0, 0.0, 7.3]];
        let (s, d, eps_t) = strain_charge(&c, &e, &eps_s).unwrap();
        let identity = product(&c, &s);
        for (i, row) in identity.iter().enumerate() {
            for (j, v) in row.iter().enumerate() {
                assert!((v - if i == j { 1.0 } else { 0.0 }).abs() < 1e-14, "({i},{j})");
            }
        }
        let (e_back, eps_back) = stress_charge(&c, &d, &eps_t);
        for i in 0..3 {
            for j in 0..6 {
                assert!((e_back[i][j] - e[i][j]).abs() < 1e-13, "e ({i},{j})");
            }
            for j in 0..3 {
                assert!((eps_back[i][j] - eps_s[i][j]).abs() < 1e-13, "ε ({i},{j})");
            }
        }
        // ε^T exceeds ε^S along the poling by d33 e33 + 2 d31 e31.
        let gain = d[2][2] * e[2][2] + 2.0 * d[2][0] * e[2][0];
        assert!((eps_t[2][2] - eps_s[2][2] - gain).abs() < 1e-13);
        assert!(smallest_eigenvalue(&c).unwrap() > 0.0);
        assert!(asymmetry(&c) == 0.0 && asymmetry(&[[1.0, 2.0], [2.5, 1.0]]) == 0.2);
    }
}
