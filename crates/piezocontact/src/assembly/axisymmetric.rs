//! The element matrix of B̌ on a triangle of the meridian section of a body of revolution
//! (model §1, axisymmetry): x is the radius r, y the axis, and the hoop direction θ is the
//! material's third mesh axis. The strain of u = (u_r, u_y) has the in-plane components of
//! ∇u and the hoop strain ε_θθ = u_r / r; the electric field has no hoop component; every
//! integral carries 2πr:
//!
//! ```text
//! uu: Σ_q w_q 2π r_q ε_p : C : ε_q'      (ε_p the strain of local DOF p at point q)
//! uϕ: Σ_q w_q 2π r_q Σ_k ∂_kN_b e_kij ε_p,ij
//! ϕϕ: −Σ_q w_q 2π r_q ∂_iN_a β_ij ∂_jN_b
//! ```
//!
//! with C Hencky's k0 tr ε tr ε' + 2g (ε : ε' − tr ε tr ε' / 3) at the element's secant g, or
//! the stiffness tensor. The rule is the 3-point one of degree 2 (points inside the
//! triangle, so r_q > 0 even on the axis): it integrates every term but the hoop–hoop one
//! (N_a N_b / r) exactly, and a uniform state's virtual work exactly. [`cell_matrix`] is the
//! one place that picks this matrix or the plane one of [`kernel`].

use super::kernel::{self, ElementMatrix, M_MAX, simplex};
use crate::element::{Simplex, quadrature};
use crate::error::Result;
use crate::material::{Elastic, Material};
use crate::problem::Problem;

/// The element matrix of B̌ on cell `c` (geometry `s`) with secant modulus `g` \[stress\]:
/// [`kernel::element_matrix`], or in a body of revolution [`element_matrix`].
pub fn cell_matrix<const D: usize, const N: usize>(
    problem: &Problem,
    c: usize,
    s: &Simplex<D, N>,
    g: f64,
) -> Result<ElementMatrix> {
    if problem.axisymmetric {
        let x = problem.mesh.cell_coords::<2, 3>(c);
        let s = simplex::<2, 3>(problem, c)?;
        return Ok(element_matrix(problem.material(c), &x, &s, g));
    }
    Ok(kernel::element_matrix(problem.material(c), s, g))
}

/// The strain of each local u DOF (a, i) at the point with barycentric coordinates `lambda`
/// and radius `r` (3 × 3, θ the third axis).
fn dof_strains(s: &Simplex<2, 3>, lambda: &[f64; 4], r: f64) -> [[[f64; 3]; 3]; 6] {
    let mut strains = [[[0.0; 3]; 3]; 6];
    for a in 0..3 {
        for i in 0..2 {
            let e = &mut strains[a * 2 + i];
            for j in 0..2 {
                e[i][j] += 0.5 * s.grad[a][j];
                e[j][i] += 0.5 * s.grad[a][j];
            }
            if i == 0 {
                e[2][2] = lambda[a] / r;
            }
        }
    }
    strains
}

/// ε : C : ε' for the material at secant modulus g \[stress\].
fn energy(material: &Material, g: f64, e: &[[f64; 3]; 3], f: &[[f64; 3]; 3]) -> f64 {
    match &material.elastic {
        Elastic::Isotropic(el) => {
            let (tr_e, tr_f) = (e[0][0] + e[1][1] + e[2][2], f[0][0] + f[1][1] + f[2][2]);
            let inner: f64 = (0..3).flat_map(|i| (0..3).map(move |j| e[i][j] * f[i][j])).sum();
            el.k0 * tr_e * tr_f + 2.0 * g * (inner - tr_e * tr_f / 3.0)
        }
        Elastic::Anisotropic(c) => {
            let mut sum = 0.0;
            for i in 0..3 {
                for j in 0..3 {
                    for k in 0..3 {
                        for l in 0..3 {
                            sum += e[i][j] * c[i][j][k][l] * f[k][l];
                        }
                    }
                }
            }
            sum
        }
    }
}

/// The element matrix of B̌ on the triangle with vertices `x` (x = r) and geometry `s`, with
/// secant modulus `g` \[stress\], in the local DOF order of [`super::kernel`].
pub fn element_matrix(
    material: &Material,
    x: &[[f64; 2]; 3],
    s: &Simplex<2, 3>,
    g: f64,
) -> ElementMatrix {
    let mut k = [[0.0; M_MAX]; M_MAX];
    let (e, beta) = (&material.e, &material.beta);
    for (lambda, w) in quadrature(2) {
        let r: f64 = (0..3).map(|a| lambda[a] * x[a][0]).sum();
        let weight = w * s.measure() * 2.0 * std::f64::consts::PI * r;
        let strains = dof_strains(s, lambda, r);
        for p in 0..6 {
            for q in 0..6 {
                k[p][q] += weight * energy(material, g, &strains[p], &strains[q]);
            }
            for b in 0..3 {
                // Σ_k ∂_kN_b e_kij ε_p,ij: (Eᵀ∇ϕ, ε(v)) and, transposed, (Eε(u), ∇ξ).
                let mut coupling = 0.0;
                for kk in 0..2 {
                    for i in 0..3 {
                        for j in 0..3 {
                            coupling += s.grad[b][kk] * e[kk][i][j] * strains[p][i][j];
                        }
                    }
                }
                k[p][6 + b] += weight * coupling;
                k[6 + b][p] += weight * coupling;
            }
        }
        for a in 0..3 {
            for b in 0..3 {
                let perm: f64 = (0..2)
                    .flat_map(|i| (0..2).map(move |j| s.grad[a][i] * beta[i][j] * s.grad[b][j]))
                    .sum();
                k[6 + a][6 + b] -= weight * perm;
            }
        }
    }
    k
}

/// The 3 × 3 strain (θ third) and ∇ϕ (3 components) at the point with barycentric
/// coordinates `lambda` of the triangle with vertices `x` and geometry `s`, from the nodal
/// u (`u[a]` = (u_r, u_y)) and ϕ.
pub fn strain_at(
    x: &[[f64; 2]; 3],
    s: &Simplex<2, 3>,
    (u, phi): (&[[f64; 2]; 3], &[f64; 3]),
    lambda: &[f64; 4],
) -> ([[f64; 3]; 3], [f64; 3]) {
    let r: f64 = (0..3).map(|a| lambda[a] * x[a][0]).sum();
    let strains = dof_strains(s, lambda, r);
    let mut eps = [[0.0; 3]; 3];
    let mut grad_phi = [0.0; 3];
    for a in 0..3 {
        for i in 0..2 {
            let e = &strains[a * 2 + i];
            (0..3).for_each(|m| (0..3).for_each(|n| eps[m][n] += e[m][n] * u[a][i]));
            grad_phi[i] += phi[a] * s.grad[a][i];
        }
    }
    (eps, grad_phi)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The matrix is symmetric, and a rigid motion along the axis (u_y = 1) does no work; a
    /// radial translation does (it stretches the hoops).
    #[test]
    fn the_matrix_is_symmetric_and_the_axial_translation_is_free() {
        let x = [[0.5, 0.0], [1.5, 0.2], [0.7, 1.1]];
        let s = Simplex::<2, 3>::new(&x).unwrap();
        let material = crate::material::Material::new(
            2,
            crate::material::Elasticity::from_young_poisson(
                58.7,
                0.39,
                crate::material::ElasticLaw::Linear,
            )
            .unwrap(),
            crate::material::PiezoConstants { e31: -5.4, e33: 15.8, e15: 12.3 },
            crate::material::PermittivityConstants { beta11: 8.1, beta33: 7.3 },
        );
        let mut material = material.unwrap();
        material.deviator_dim = 3;
        let k = element_matrix(&material, &x, &s, 20.0);
        for p in 0..9 {
            for q in 0..9 {
                assert!((k[p][q] - k[q][p]).abs() < 1e-12 * k[p][p].abs().max(1.0), "{p} {q}");
            }
        }
        let axial: Vec<f64> = (0..9).map(|p| if p < 6 && p % 2 == 1 { 1.0 } else { 0.0 }).collect();
        let radial: Vec<f64> =
            (0..9).map(|p| if p < 6 && p % 2 == 0 { 1.0 } else { 0.0 }).collect();
        let work = |v: &[f64]| -> f64 {
            (0..9).map(|p| (0..9).map(|q| v[p] * k[p][q] * v[q]).sum::<f64>()).sum()
        };
        assert!(work(&axial).abs() < 1e-12 * k[1][1]);
        assert!(work(&radial) > 1e-3 * k[0][0]);
    }
}
