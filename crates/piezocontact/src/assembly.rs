//! Assembly of the symmetric coupled system of SPEC §5, [P] (6.2)–(6.3):
//!
//! ```text
//! B̌(x_n; x, y) = (k0 tr ε(u) I + 2 g_n ε^D(u), ε(v)) + (Eᵀ∇ϕ, ε(v)) − (β∇ϕ, ∇ξ) + (Eε(u), ∇ξ)
//! (f̌, y)       = ∫Ω f0·v + ∫Γ2 f2·v − ∫Ω q0 ξ + ∫Γb q2 ξ
//! ```
//!
//! with the secant modulus g_n = g(‖ε^D(u_n)‖²) frozen per element at the previous iterate
//! (Section 5). With P1 elements all gradients are constant on an element, so the element
//! matrices are exact; loads use a degree-2 rule. The sparsity pattern is built once
//! ([`Assembler::new`]); [`Assembler::matrix`] produces values in the same order and refills.
//!
//! Local DOF order on an element with N = d + 1 nodes: u_i at node a is `a·d + i`, ϕ at node
//! a is `N·d + a` (M = N(d + 1) ≤ 16 DOFs).

use crate::dofs::{CONSTRAINED, DofMap};
use crate::element::{Simplex, point_at, quadrature};
use crate::error::{Error, Result};
use crate::linalg::{SymmetricMatrix, SymmetricPattern};
use crate::material::{Material, deviator_norm_squared};
use crate::problem::Problem;

/// Largest local system: a tetrahedron with 4 × 4 DOFs.
const M_MAX: usize = 16;
/// An element matrix (first M × M entries used).
pub type ElementMatrix = [[f64; M_MAX]; M_MAX];

/// The element matrix of B̌ on a simplex with secant modulus `g` [stress].
///
/// ```text
/// uu: |K| [k0 ∂_iN_a ∂_jN_b + 2g (½(δ_ij ∇N_a·∇N_b + ∂_jN_a ∂_iN_b) − ∂_iN_a ∂_jN_b / d)]
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
    let (vol, grad, k0) = (s.measure(), &s.grad, material.elasticity.k0);
    let (e, beta) = (&material.e, &material.beta);
    let dot = |a: usize, b: usize| (0..D).map(|i| grad[a][i] * grad[b][i]).sum::<f64>();
    for a in 0..N {
        for b in 0..N {
            let ab = dot(a, b);
            for i in 0..D {
                for j in 0..D {
                    let delta = if i == j { ab } else { 0.0 };
                    let (gi, gj) = (grad[a][i] * grad[b][j], grad[a][j] * grad[b][i]);
                    k[a * D + i][b * D + j] =
                        vol * (k0 * gi + 2.0 * g * (0.5 * (delta + gj) - gi / D as f64));
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

/// Global DOF indices of the element's local DOFs.
fn local_dofs<const D: usize, const N: usize>(dofs: &DofMap, cell: &[usize]) -> [usize; M_MAX] {
    let mut g = [0; M_MAX];
    for (a, &node) in cell.iter().enumerate() {
        for i in 0..D {
            g[a * D + i] = dofs.u(node, i);
        }
        g[N * D + a] = dofs.phi(node);
    }
    g
}

/// The geometry of cell `c`, or an error naming it (the mesh check makes this unreachable).
fn simplex<const D: usize, const N: usize>(problem: &Problem, c: usize) -> Result<Simplex<D, N>> {
    Simplex::new(&problem.mesh.cell_coords::<D, N>(c)).ok_or_else(|| Error::DegenerateElement {
        element: c,
        nodes: problem.mesh.cell(c).to_vec(),
        measure: 0.0,
        edge: 0.0,
    })
}

/// Assembles B̌ and f̌ on the free DOFs of a problem, reusing one sparsity pattern.
///
/// Besides the element matrices, the matrix may carry a d × d block on the u DOFs of given
/// nodes: the r M term of Algorithms 2 and 4 on the Γ3 nodes (SPEC §7).
#[derive(Debug)]
pub struct Assembler {
    dofs: DofMap,
    pattern: SymmetricPattern,
    /// Nodes that carry a nodal block.
    block_nodes: Vec<usize>,
}

/// A symmetric d × d nodal block, row-major in a 3 × 3 array.
pub type NodalBlock = [[f64; 3]; 3];

impl Assembler {
    /// Numbers the DOFs and builds the sparsity pattern (once per run), with room for nodal
    /// blocks on `block_nodes`.
    pub fn new(problem: &Problem, block_nodes: &[usize]) -> Result<Self> {
        let dofs = DofMap::new(problem)?;
        let mut positions = match problem.mesh.dim() {
            2 => free_positions::<2, 3>(problem, &dofs),
            _ => free_positions::<3, 4>(problem, &dofs),
        };
        let dim = problem.mesh.dim();
        for &node in block_nodes {
            positions.extend(nodal_pairs(&dofs, dim, node).map(|(_, _, r, c)| (r, c)));
        }
        let pattern = SymmetricPattern::new(dofs.n_free(), &positions)?;
        Ok(Self { dofs, pattern, block_nodes: block_nodes.to_vec() })
    }

    /// The DOF map.
    pub fn dofs(&self) -> &DofMap {
        &self.dofs
    }

    /// The sparsity pattern.
    pub fn pattern(&self) -> &SymmetricPattern {
        &self.pattern
    }

    /// The matrix of B̌(x_n) for per-element secant moduli `g` [stress], plus the nodal
    /// `blocks` (one per block node, or none at all), and the Dirichlet lifting −K_fc x_c
    /// (free DOFs) to add to the right-hand side.
    pub fn matrix(
        &self,
        problem: &Problem,
        g: &[f64],
        blocks: &[NodalBlock],
    ) -> Result<(SymmetricMatrix, Vec<f64>)> {
        if !blocks.is_empty() && blocks.len() != self.block_nodes.len() {
            return Err(Error::Length {
                what: "nodal blocks".into(),
                expected: self.block_nodes.len(),
                got: blocks.len(),
            });
        }
        if g.len() != problem.mesh.n_cells() {
            return Err(Error::Length {
                what: "secant moduli".into(),
                expected: problem.mesh.n_cells(),
                got: g.len(),
            });
        }
        let mut values = Vec::with_capacity(self.pattern.entries());
        let mut lifting = vec![0.0; self.dofs.n_free()];
        let dofs = &self.dofs;
        let mut visit = |k_pq: f64, r: usize, c: usize, prescribed: f64| {
            if c == CONSTRAINED {
                lifting[r] -= k_pq * prescribed;
            } else {
                values.push(k_pq);
            }
        };
        match problem.mesh.dim() {
            2 => assemble_elements::<2, 3>(problem, dofs, g, &mut visit)?,
            _ => assemble_elements::<3, 4>(problem, dofs, g, &mut visit)?,
        }
        let dim = problem.mesh.dim();
        for (b, &node) in self.block_nodes.iter().enumerate() {
            values.extend(
                nodal_pairs(dofs, dim, node)
                    .map(|(i, j, _, _)| blocks.get(b).map_or(0.0, |k| k[i][j])),
            );
        }
        Ok((self.pattern.matrix(&values)?, lifting))
    }

    /// f̌ of (6.3) on the global DOFs.
    pub fn load_vector(&self, problem: &Problem) -> Vec<f64> {
        Self::load_vector_of(problem, &self.dofs)
    }

    /// f̌ of (6.3) on the global DOFs of `dofs`.
    pub fn load_vector_of(problem: &Problem, dofs: &DofMap) -> Vec<f64> {
        match problem.mesh.dim() {
            2 => load_vector::<2, 3>(problem, dofs),
            _ => load_vector::<3, 4>(problem, dofs),
        }
    }

    /// The entries of a global vector at the free DOFs.
    pub fn restrict(&self, global: &[f64]) -> Vec<f64> {
        let mut free = vec![0.0; self.dofs.n_free()];
        for (g, v) in global.iter().enumerate() {
            let k = self.dofs.free_index(g);
            if k != CONSTRAINED {
                free[k] = *v;
            }
        }
        free
    }
}

/// The local pairs (p, q) of an element whose row is free, with their free row r and free
/// column (or [`CONSTRAINED`]): pairs of free DOFs only in the lower triangle (r ≥ column),
/// constrained columns always (they feed the Dirichlet lifting). The order is fixed, so the
/// pattern and every refill agree.
fn local_pairs<'a>(
    dofs: &'a DofMap,
    global: &'a [usize],
) -> impl Iterator<Item = (usize, usize, usize, usize)> + 'a {
    global.iter().enumerate().flat_map(move |(p, &gp)| {
        let r = dofs.free_index(gp);
        global.iter().enumerate().filter_map(move |(q, &gq)| {
            let col = dofs.free_index(gq);
            (r != CONSTRAINED && (col == CONSTRAINED || r >= col)).then_some((p, q, r, col))
        })
    })
}

/// The (i, j, free row, free column) pairs of the u block of `node` with both DOFs free, in
/// the lower triangle.
fn nodal_pairs(
    dofs: &DofMap,
    dim: usize,
    node: usize,
) -> impl Iterator<Item = (usize, usize, usize, usize)> + '_ {
    (0..dim).flat_map(move |i| {
        (0..dim).filter_map(move |j| {
            let (r, c) = (dofs.free_index(dofs.u(node, i)), dofs.free_index(dofs.u(node, j)));
            (r != CONSTRAINED && c != CONSTRAINED && r >= c).then_some((i, j, r, c))
        })
    })
}

/// Calls `visit(K_pq, free row, free column or CONSTRAINED, prescribed value of the column)`
/// for the [`local_pairs`] of every element.
fn assemble_elements<const D: usize, const N: usize>(
    problem: &Problem,
    dofs: &DofMap,
    g: &[f64],
    visit: &mut impl FnMut(f64, usize, usize, f64),
) -> Result<()> {
    let m = N * (D + 1);
    for c in 0..problem.mesh.n_cells() {
        let k = element_matrix(&problem.material, &simplex::<D, N>(problem, c)?, g[c]);
        let global = local_dofs::<D, N>(dofs, problem.mesh.cell(c));
        for (p, q, r, col) in local_pairs(dofs, &global[..m]) {
            visit(k[p][q], r, col, dofs.prescribed(global[q]));
        }
    }
    Ok(())
}

/// The (row, column) positions of free pairs in [`assemble_elements`] order, without
/// element matrices.
fn free_positions<const D: usize, const N: usize>(
    problem: &Problem,
    dofs: &DofMap,
) -> Vec<(usize, usize)> {
    let m = N * (D + 1);
    let mut positions = Vec::new();
    for c in 0..problem.mesh.n_cells() {
        let global = local_dofs::<D, N>(dofs, problem.mesh.cell(c));
        positions.extend(
            local_pairs(dofs, &global[..m])
                .filter(|&(.., col)| col != CONSTRAINED)
                .map(|(_, _, r, col)| (r, col)),
        );
    }
    positions
}

fn load_vector<const D: usize, const N: usize>(problem: &Problem, dofs: &DofMap) -> Vec<f64> {
    let mesh = &problem.mesh;
    let mut f = vec![0.0; dofs.n_total()];
    let (f0, q0) = (&problem.loads.f0, &problem.loads.q0);
    if f0.is_some() || q0.is_some() {
        for c in 0..mesh.n_cells() {
            let x = mesh.cell_coords::<D, N>(c);
            let vol = Simplex::<D, N>::new(&x).map_or(0.0, |s| s.measure());
            for (lambda, w) in quadrature(D) {
                let p = point_at(&x, lambda);
                let body_force = f0.as_ref().map(|f| f(&p));
                let charge = q0.as_ref().map_or(0.0, |q| q(&p));
                for (a, &node) in mesh.cell(c).iter().enumerate() {
                    let weight = vol * w * lambda[a];
                    if let Some(v) = &body_force {
                        (0..D).for_each(|i| f[dofs.u(node, i)] += weight * v[i]);
                    }
                    f[dofs.phi(node)] -= weight * charge;
                }
            }
        }
    }
    for (part, traction) in &problem.boundary.traction {
        integrate_facets::<D>(problem, *part, |node, weight, p| {
            let v = traction(p);
            (0..D).for_each(|i| f[dofs.u(node, i)] += weight * v[i]);
        });
    }
    for (part, charge) in &problem.boundary.charge {
        integrate_facets::<D>(problem, *part, |node, weight, p| {
            f[dofs.phi(node)] += weight * charge(p)
        });
    }
    f
}

/// Calls `f(node, weight, point)` for each quadrature point and node of the part's facets,
/// with weight = |e| w_q N_a(x_q).
fn integrate_facets<const D: usize>(
    problem: &Problem,
    part: usize,
    mut f: impl FnMut(usize, f64, &[f64]),
) {
    let mesh = &problem.mesh;
    for facet in mesh.part_facets(part) {
        let (measure, _) = mesh.facet_geometry::<D>(facet);
        let x = mesh.points::<D>(facet);
        for (lambda, w) in quadrature(D - 1) {
            let p = point_at(&x, lambda);
            for (a, &node) in facet.iter().enumerate() {
                f(node, measure * w * lambda[a], &p);
            }
        }
    }
}

/// Strain ε(u) and ∇ϕ on cell `c` from a global vector x = (u, ϕ).
pub fn cell_gradients<const D: usize, const N: usize>(
    problem: &Problem,
    dofs: &DofMap,
    x: &[f64],
    c: usize,
) -> Result<([[f64; D]; D], [f64; D])> {
    let s = simplex::<D, N>(problem, c)?;
    let mut eps = [[0.0; D]; D];
    let mut grad_phi = [0.0; D];
    for (a, &node) in problem.mesh.cell(c).iter().enumerate() {
        for i in 0..D {
            grad_phi[i] += x[dofs.phi(node)] * s.grad[a][i];
            for j in 0..D {
                eps[i][j] +=
                    0.5 * (x[dofs.u(node, i)] * s.grad[a][j] + x[dofs.u(node, j)] * s.grad[a][i]);
            }
        }
    }
    Ok((eps, grad_phi))
}

/// The internal force F_int = Σ_e K_e(g_e) x_e on the global DOFs, and the row scale
/// Σ_e |K_e x_e| (to make residuals relative). With g_e = g(‖ε^D(u)‖²) of x itself this is
/// the exact nonlinear internal force of (6.2): Fε is linear in ε at a fixed g.
pub fn internal_force(
    problem: &Problem,
    dofs: &DofMap,
    x: &[f64],
    g: &[f64],
) -> Result<(Vec<f64>, Vec<f64>)> {
    match problem.mesh.dim() {
        2 => internal_force_on::<2, 3>(problem, dofs, x, g),
        _ => internal_force_on::<3, 4>(problem, dofs, x, g),
    }
}

fn internal_force_on<const D: usize, const N: usize>(
    problem: &Problem,
    dofs: &DofMap,
    x: &[f64],
    g: &[f64],
) -> Result<(Vec<f64>, Vec<f64>)> {
    let m = N * (D + 1);
    let mut force = vec![0.0; dofs.n_total()];
    let mut scale = vec![0.0; dofs.n_total()];
    for c in 0..problem.mesh.n_cells() {
        let k = element_matrix(&problem.material, &simplex::<D, N>(problem, c)?, g[c]);
        let global = local_dofs::<D, N>(dofs, problem.mesh.cell(c));
        for p in 0..m {
            for q in 0..m {
                let v = k[p][q] * x[global[q]];
                force[global[p]] += v;
                scale[global[p]] += v.abs();
            }
        }
    }
    Ok((force, scale))
}

/// The L2(Ω) norm of the stopping rules (6.12), (6.15): the consistent P1 mass matrix on
/// every component of x = (u, ϕ), applied element by element with the element measures
/// computed once.
#[derive(Clone, Debug)]
pub struct MassNorm {
    /// |K| / ((d+1)(d+2)) per element.
    scaled_measures: Vec<f64>,
}

impl MassNorm {
    /// Computes the element measures of `problem`'s mesh.
    pub fn new(problem: &Problem) -> Result<Self> {
        let n = problem.mesh.dim() + 1;
        let factor = 1.0 / ((n * (n + 1)) as f64);
        let scaled_measures = (0..problem.mesh.n_cells())
            .map(|c| {
                let measure = match problem.mesh.dim() {
                    2 => simplex::<2, 3>(problem, c)?.measure(),
                    _ => simplex::<3, 4>(problem, c)?.measure(),
                };
                Ok(factor * measure)
            })
            .collect::<Result<_>>()?;
        Ok(Self { scaled_measures })
    }

    /// ‖x‖²_{L2(Ω)} of a global vector x, summed over the components of u and ϕ.
    pub fn squared(&self, problem: &Problem, dofs: &DofMap, x: &[f64]) -> f64 {
        let mesh = &problem.mesh;
        let dim = mesh.dim();
        let mut sum = 0.0;
        for (c, scaled) in self.scaled_measures.iter().enumerate() {
            let cell = mesh.cell(c);
            for comp in 0..=dim {
                let value = |node: usize| {
                    if comp < dim { x[dofs.u(node, comp)] } else { x[dofs.phi(node)] }
                };
                // M_ab = |K| (1 + δ_ab) / ((d+1)(d+2)): Σ_ab M_ab v_a v_b = |K| f ((Σ v)² + Σ v²).
                let (total, squares) = cell
                    .iter()
                    .fold((0.0, 0.0), |(t, q), &n| (t + value(n), q + value(n) * value(n)));
                sum += scaled * (total * total + squares);
            }
        }
        sum
    }
}

/// ‖x‖²_X = ‖ε(u)‖²_{L2} + ‖∇ϕ‖²_{L2}, the norm of the product space X of [P] (3.1), in
/// which Theorem 4.1 bounds ‖x(µ, k_e) − x‖_X.
pub fn x_norm_squared(problem: &Problem, dofs: &DofMap, x: &[f64]) -> Result<f64> {
    let mut sum = 0.0;
    for c in 0..problem.mesh.n_cells() {
        sum += match problem.mesh.dim() {
            2 => x_norm_on::<2, 3>(problem, dofs, x, c)?,
            _ => x_norm_on::<3, 4>(problem, dofs, x, c)?,
        };
    }
    Ok(sum)
}

fn x_norm_on<const D: usize, const N: usize>(
    problem: &Problem,
    dofs: &DofMap,
    x: &[f64],
    c: usize,
) -> Result<f64> {
    let (eps, grad_phi) = cell_gradients::<D, N>(problem, dofs, x, c)?;
    let vol = simplex::<D, N>(problem, c)?.measure();
    let e2: f64 = eps.iter().flatten().map(|v| v * v).sum();
    let p2: f64 = grad_phi.iter().map(|v| v * v).sum();
    Ok(vol * (e2 + p2))
}

/// Per-element secant moduli g(‖ε^D(u_n)‖²) [stress] at the iterate x_n (global vector).
pub fn secant_moduli(problem: &Problem, dofs: &DofMap, x: &[f64]) -> Result<Vec<f64>> {
    (0..problem.mesh.n_cells())
        .map(|c| {
            let t = match problem.mesh.dim() {
                2 => deviator_norm_squared(&cell_gradients::<2, 3>(problem, dofs, x, c)?.0),
                _ => deviator_norm_squared(&cell_gradients::<3, 4>(problem, dofs, x, c)?.0),
            };
            Ok(problem.material.elasticity.g(t))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
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
