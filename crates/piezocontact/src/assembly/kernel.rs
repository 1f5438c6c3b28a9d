//! Element kernels of the symmetric coupled form B̌ (\[P\] (6.2), model §5): one P1 simplex at a
//! time, exact (all gradients are constant on an element).
//!
//! Local DOF order on an element with N = d + 1 nodes: u_i at node a is `a·d + i`, ϕ at node
//! a is `N·d + a` (M = N(d + 1) ≤ 16 DOFs).

use crate::dofs::DofMap;
use crate::element::Simplex;
use crate::error::{Error, Result};
use crate::material::{Elastic, Material};
use crate::problem::Problem;

/// Largest local system: a tetrahedron with 4 × 4 DOFs.
pub const M_MAX: usize = 16;
/// An element matrix (first M × M entries used).
pub type ElementMatrix = [[f64; M_MAX]; M_MAX];

/// The rank-one part of Hencky's consistent tangent on a simplex, `coefficient` = 4 g'(t)
/// \[stress\] and `deviator` = ε^D(u_n) ([`super::Linearisation`]): the vector a with
/// a_(a,i) = Σ_j ε^D_ij ∂_jN_a, so that the uu block gains |K| coefficient a aᵀ and aᵀ u_e = t.
pub fn tangent_vector<const D: usize, const N: usize>(
    s: &Simplex<D, N>,
    deviator: &[[f64; 3]; 3],
) -> [f64; M_MAX] {
    let mut a = [0.0; M_MAX];
    for node in 0..N {
        for i in 0..D {
            a[node * D + i] = (0..D).map(|j| deviator[i][j] * s.grad[node][j]).sum();
        }
    }
    a
}

/// The element matrix of B̌ on a simplex with secant modulus `g` \[stress\].
///
/// ```text
/// uu: |K| [k0 ∂_iN_a ∂_jN_b + 2g (½(δ_ij ∇N_a·∇N_b + ∂_jN_a ∂_iN_b) − ∂_iN_a ∂_jN_b / d)]
///     or, for a stiffness tensor, |K| ∂_kN_a c_ikjl ∂_lN_b
/// uϕ: |K| e_kil ∂_kN_b ∂_lN_a            from (Eᵀ∇ϕ, ε(v))
/// ϕu: |K| e_ijl ∂_lN_b ∂_iN_a            from (Eε(u), ∇ξ)
/// ϕϕ: −|K| ∂_iN_a β_ij ∂_jN_b
/// ```
pub fn element_matrix<const D: usize, const N: usize>(
    material: &Material,
    s: &Simplex<D, N>,
    g: f64,
) -> ElementMatrix {
    let mut k = [[0.0; M_MAX]; M_MAX];
    let (vol, grad) = (s.measure(), &s.grad);
    let (e, beta) = (&material.e, &material.beta);
    for a in 0..N {
        for b in 0..N {
            for i in 0..D {
                for j in 0..D {
                    k[a * D + i][b * D + j] = vol * elastic_entry(material, s, g, [a, b], [i, j]);
                }
                let mut coupling = 0.0;
                for p in 0..D {
                    for l in 0..D {
                        coupling += e[p][i][l] * grad[b][p] * grad[a][l];
                    }
                }
                k[a * D + i][N * D + b] = vol * coupling;
            }
            for j in 0..D {
                let mut coupling = 0.0;
                for i in 0..D {
                    for l in 0..D {
                        coupling += e[i][j][l] * grad[b][l] * grad[a][i];
                    }
                }
                k[N * D + a][b * D + j] = vol * coupling;
            }
            let mut perm = 0.0;
            for i in 0..D {
                for j in 0..D {
                    perm += grad[a][i] * beta[i][j] * grad[b][j];
                }
            }
            k[N * D + a][N * D + b] = -vol * perm;
        }
    }
    k
}

/// The uu entry of B̌ for the components i, j at the nodes a, b, per unit measure \[stress/length²\]:
/// Hencky's k0 ∂_iN_a ∂_jN_b + 2g (½(δ_ij ∇N_a·∇N_b + ∂_jN_a ∂_iN_b) − ∂_iN_a ∂_jN_b / d), or a
/// stiffness tensor's Σ_kl ∂_kN_a c_ikjl ∂_lN_b.
fn elastic_entry<const D: usize, const N: usize>(
    material: &Material,
    s: &Simplex<D, N>,
    g: f64,
    [a, b]: [usize; 2],
    [i, j]: [usize; 2],
) -> f64 {
    let grad = &s.grad;
    match &material.elastic {
        Elastic::Isotropic(el) => {
            let ab: f64 = (0..D).map(|m| grad[a][m] * grad[b][m]).sum();
            let delta = if i == j { ab } else { 0.0 };
            let (gi, gj) = (grad[a][i] * grad[b][j], grad[a][j] * grad[b][i]);
            el.k0 * gi + 2.0 * g * (0.5 * (delta + gj) - gi / material.deviator_dim as f64)
        }
        Elastic::Anisotropic(c) => {
            let mut entry = 0.0;
            for k in 0..D {
                for l in 0..D {
                    entry += grad[a][k] * c[i][k][j][l] * grad[b][l];
                }
            }
            entry
        }
    }
}

/// Global DOF indices of the element's local DOFs.
pub fn local_dofs<const D: usize, const N: usize>(dofs: &DofMap, cell: &[usize]) -> [usize; M_MAX] {
    let mut global = [0; M_MAX];
    for (a, &node) in cell.iter().enumerate() {
        for i in 0..D {
            global[a * D + i] = dofs.u(node, i);
        }
        global[N * D + a] = dofs.phi(node);
    }
    global
}

/// The geometry of cell `c`, or an error naming it (the mesh check makes this unreachable).
pub fn simplex<const D: usize, const N: usize>(
    problem: &Problem,
    c: usize,
) -> Result<Simplex<D, N>> {
    Simplex::new(&problem.mesh.cell_coords::<D, N>(c)).ok_or_else(|| Error::DegenerateElement {
        element: c,
        nodes: problem.mesh.cell(c).to_vec(),
        measure: 0.0,
        edge: 0.0,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::Simplex;
    use crate::material::{ElasticLaw, Elasticity, PermittivityConstants, PiezoConstants};

    fn pzt(dim: usize) -> Material {
        let el = Elasticity::from_young_poisson(58.7102, 0.3912, ElasticLaw::Linear).unwrap();
        Material::new(
            dim,
            el,
            PiezoConstants { e31: -5.4, e33: 15.8, e15: 12.3 },
            PermittivityConstants { beta11: 8.14, beta33: 7.37 },
        )
        .unwrap()
    }

    #[test]
    fn element_matrices_are_symmetric_with_definite_diagonal_blocks() {
        let tri = Simplex::<2, 3>::new(&[[0.1, 0.2], [1.3, 0.1], [0.4, 0.9]]).unwrap();
        let tet = Simplex::<3, 4>::new(&[
            [0.0, 0.1, 0.0],
            [1.2, 0.0, 0.1],
            [0.2, 1.0, 0.0],
            [0.1, 0.3, 0.8],
        ])
        .unwrap();
        let k2 = element_matrix(&pzt(2), &tri, 17.0);
        let k3 = element_matrix(&pzt(3), &tet, 17.0);
        for (k, m) in [(k2, 9), (k3, 16)] {
            let scale = (0..m).map(|p| k[p][p].abs()).fold(0.0, f64::max);
            for p in 0..m {
                for q in 0..m {
                    assert!((k[p][q] - k[q][p]).abs() < 1e-13 * scale, "({p},{q})");
                }
            }
        }
        // Rigid motions give zero elastic energy; a pure potential shift gives zero field.
        let rigid = [1.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0];
        let y: Vec<f64> = (0..9).map(|p| (0..9).map(|q| k2[p][q] * rigid[q]).sum()).collect();
        assert!(y.iter().all(|v| v.abs() < 1e-12));
        let shift = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
        let y: Vec<f64> = (0..9).map(|p| (0..9).map(|q| k2[p][q] * shift[q]).sum()).collect();
        assert!(y.iter().all(|v| v.abs() < 1e-12));
    }
}
