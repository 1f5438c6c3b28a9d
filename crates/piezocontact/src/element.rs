//! P1 simplices: the linear triangle (`Tri3`, d = 2) and tetrahedron (`Tet4`, d = 3).
//!
//! Every function is generic over the space dimension `D` and the node count `N = D + 1`, so
//! 2D and 3D share one code path. Shape functions are the barycentric coordinates
//! `N_a(x)`, `a = 0..D`; their gradients are constant on an element:
//!
//! ```text
//! J = [x_1 − x_0 | … | x_D − x_0]        (columns)
//! ∇N_a = row a−1 of J⁻¹  (a ≥ 1),        ∇N_0 = −Σ_{a≥1} ∇N_a
//! |K| = |det J| / D!
//! ```

/// Geometry of one P1 simplex: signed measure and constant shape-function gradients.
#[derive(Clone, Copy, Debug)]
pub struct Simplex<const D: usize, const N: usize> {
    /// Signed measure det J / D! (area in 2D, volume in 3D) [length^D]; positive when the
    /// nodes are ordered counter-clockwise (2D) or right-handed (3D).
    pub signed_measure: f64,
    /// ∇N_a for a = 0..N [1/length].
    pub grad: [[f64; D]; N],
}

impl<const D: usize, const N: usize> Simplex<D, N> {
    /// Computes the geometry of the simplex with vertices `x`, or `None` when det J = 0.
    pub fn new(x: &[[f64; D]; N]) -> Option<Self> {
        debug_assert_eq!(N, D + 1);
        let mut j = [[0.0; D]; D];
        for col in 0..D {
            for row in 0..D {
                j[row][col] = x[col + 1][row] - x[0][row];
            }
        }
        let (det, inv) = invert(&j)?;
        let mut grad = [[0.0; D]; N];
        for a in 1..N {
            grad[a] = inv[a - 1];
            for i in 0..D {
                grad[0][i] -= inv[a - 1][i];
            }
        }
        let factorial: f64 = (1..=D).map(|k| k as f64).product();
        Some(Self { signed_measure: det / factorial, grad })
    }

    /// The unsigned measure |K|.
    pub fn measure(&self) -> f64 {
        self.signed_measure.abs()
    }
}

/// Determinant and inverse of a small matrix (D = 2, 3), `None` when singular.
fn invert<const D: usize>(a: &[[f64; D]; D]) -> Option<(f64, [[f64; D]; D])> {
    let mut inv = [[0.0; D]; D];
    let det = match D {
        2 => {
            let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
            if det == 0.0 {
                return None;
            }
            inv[0][0] = a[1][1] / det;
            inv[0][1] = -a[0][1] / det;
            inv[1][0] = -a[1][0] / det;
            inv[1][1] = a[0][0] / det;
            det
        }
        3 => {
            let c = |r: usize, s: usize| {
                let (r1, r2) = ((r + 1) % 3, (r + 2) % 3);
                let (s1, s2) = ((s + 1) % 3, (s + 2) % 3);
                a[r1][s1] * a[r2][s2] - a[r1][s2] * a[r2][s1]
            };
            let det = a[0][0] * c(0, 0) + a[0][1] * c(0, 1) + a[0][2] * c(0, 2);
            if det == 0.0 {
                return None;
            }
            for r in 0..3 {
                for s in 0..3 {
                    inv[s][r] = c(r, s) / det;
                }
            }
            det
        }
        _ => unreachable!("P1 simplices are used for d = 2, 3 only"),
    };
    Some((det, inv))
}

/// Measure of a facet (a simplex of dimension D − 1 embedded in R^D) and its unit normal.
/// The normal's sign follows the node order: in 2D, (t_y, −t_x) for the tangent t = x_1 − x_0;
/// in 3D, (x_1 − x_0) × (x_2 − x_0). Callers orient it outward.
pub fn facet_measure_normal<const D: usize>(x: &[[f64; D]]) -> (f64, [f64; D]) {
    let mut n = [0.0; D];
    let measure = match D {
        2 => {
            let t = [x[1][0] - x[0][0], x[1][1] - x[0][1]];
            n[0] = t[1];
            n[1] = -t[0];
            (t[0] * t[0] + t[1] * t[1]).sqrt()
        }
        3 => {
            let a = [x[1][0] - x[0][0], x[1][1] - x[0][1], x[1][2] - x[0][2]];
            let b = [x[2][0] - x[0][0], x[2][1] - x[0][1], x[2][2] - x[0][2]];
            n[0] = a[1] * b[2] - a[2] * b[1];
            n[1] = a[2] * b[0] - a[0] * b[2];
            n[2] = a[0] * b[1] - a[1] * b[0];
            0.5 * (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt()
        }
        _ => unreachable!("facets are defined for d = 2, 3"),
    };
    let norm = n.iter().map(|v| v * v).sum::<f64>().sqrt();
    if norm > 0.0 {
        n.iter_mut().for_each(|v| *v /= norm);
    }
    (measure, n)
}

/// A quadrature rule on a simplex of dimension `dim` (1 ≤ dim ≤ 3), exact for polynomials of
/// degree 2: points in barycentric coordinates (the first dim + 1 entries used) and weights
/// that sum to 1 (multiply by the measure).
pub fn quadrature(dim: usize) -> &'static [([f64; 4], f64)] {
    const G1: f64 = 0.211_324_865_405_187_1; // (1 − 1/√3)/2
    const G2: f64 = 0.788_675_134_594_812_9;
    const T1: f64 = 2.0 / 3.0;
    const T2: f64 = 1.0 / 6.0;
    const A: f64 = 0.585_410_196_624_968_5;
    const B: f64 = 0.138_196_601_125_010_5;
    match dim {
        1 => &[([G1, G2, 0.0, 0.0], 0.5), ([G2, G1, 0.0, 0.0], 0.5)],
        2 => &[
            ([T1, T2, T2, 0.0], 1.0 / 3.0),
            ([T2, T1, T2, 0.0], 1.0 / 3.0),
            ([T2, T2, T1, 0.0], 1.0 / 3.0),
        ],
        3 => &[
            ([A, B, B, B], 0.25),
            ([B, A, B, B], 0.25),
            ([B, B, A, B], 0.25),
            ([B, B, B, A], 0.25),
        ],
        _ => unreachable!("quadrature is defined for simplices of dimension 1 to 3"),
    }
}

/// The point with barycentric coordinates `lambda` in the simplex with vertices `x`.
pub fn point_at<const D: usize>(x: &[[f64; D]], lambda: &[f64; 4]) -> [f64; D] {
    let mut p = [0.0; D];
    for (a, xa) in x.iter().enumerate() {
        for i in 0..D {
            p[i] += lambda[a] * xa[i];
        }
    }
    p
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn triangle_gradients_sum_to_zero_and_reproduce_linear_functions() {
        let x = [[0.3, 0.1], [2.0, 0.4], [0.7, 1.9]];
        let s = Simplex::<2, 3>::new(&x).unwrap();
        // A linear f(x) = 2 + 3x − 5y is reproduced: Σ f(x_a) ∇N_a = ∇f.
        let f = |p: &[f64; 2]| 2.0 + 3.0 * p[0] - 5.0 * p[1];
        let mut g = [0.0; 2];
        for a in 0..3 {
            for i in 0..2 {
                g[i] += f(&x[a]) * s.grad[a][i];
            }
        }
        assert!((g[0] - 3.0).abs() < 1e-13 && (g[1] + 5.0).abs() < 1e-13);
        let area = 0.5 * ((2.0 - 0.3) * (1.9 - 0.1) - (0.7 - 0.3) * (0.4 - 0.1));
        assert!((s.signed_measure - area).abs() < 1e-14);
    }

    #[test]
    fn tetrahedron_measure_and_orientation() {
        let x = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let s = Simplex::<3, 4>::new(&x).unwrap();
        assert!((s.signed_measure - 1.0 / 6.0).abs() < 1e-15);
        let swapped = [x[0], x[2], x[1], x[3]];
        assert!(Simplex::<3, 4>::new(&swapped).unwrap().signed_measure < 0.0);
        let flat = [x[0], x[1], x[2], [1.0, 1.0, 0.0]];
        assert!(Simplex::<3, 4>::new(&flat).is_none());
    }

    #[test]
    fn quadrature_is_exact_for_quadratics() {
        // ∫_K λ_0² = 2 |K| / ((d+1)(d+2)) on the reference simplex of any dimension.
        for dim in 1..=3 {
            let q: f64 = quadrature(dim).iter().map(|(l, w)| w * l[0] * l[0]).sum();
            let exact = 2.0 / ((dim as f64 + 1.0) * (dim as f64 + 2.0));
            assert!((q - exact).abs() < 1e-14, "dim {dim}: {q} vs {exact}");
            let w: f64 = quadrature(dim).iter().map(|(_, w)| w).sum();
            assert!((w - 1.0).abs() < 1e-15);
        }
    }

    #[test]
    fn facet_normals() {
        let (m, n) = facet_measure_normal::<2>(&[[0.0, 0.0], [2.0, 0.0]]);
        assert!((m - 2.0).abs() < 1e-15 && n == [0.0, -1.0]);
        let (m, n) = facet_measure_normal::<3>(&[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
        assert!((m - 0.5).abs() < 1e-15 && n == [0.0, 0.0, 1.0]);
    }
}
