//! Fields and norms of a solution, element by element: strain and ∇ϕ, the secant moduli of
//! Hencky's law, the internal force with the true law, σ and D for output, the L2 norm of the
//! stopping rules and the norm of the space X of \[P\] (3.1).

use super::axisymmetric;
use super::axisymmetric::cell_matrix;
use super::kernel::{local_dofs, simplex};
use crate::dofs::DofMap;
use crate::error::Result;
use crate::problem::Problem;
use rayon::prelude::*;

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

/// The internal force F_int = Σ_e K_e(g_e) x_e on the global DOFs, with the secant `moduli`
/// g_e, and the row scale
/// Σ_e |K_e x_e| (to make residuals relative). With g_e = g(‖ε^D(u)‖²) of x itself this is
/// the exact nonlinear internal force of (6.2): Fε is linear in ε at a fixed g.
pub fn internal_force(
    problem: &Problem,
    dofs: &DofMap,
    x: &[f64],
    moduli: &[f64],
) -> Result<(Vec<f64>, Vec<f64>)> {
    with_simplex!(problem.mesh.dim(), internal_force_on(problem, dofs, x, moduli))
}

/// Cells whose products K_e x_e [`internal_force`] computes at once, in parallel, before it
/// adds them to the rows in cell order: the sums are the same on any number of threads.
const FORCE_BLOCK: usize = 1 << 14;

fn internal_force_on<const D: usize, const N: usize>(
    problem: &Problem,
    dofs: &DofMap,
    x: &[f64],
    moduli: &[f64],
) -> Result<(Vec<f64>, Vec<f64>)> {
    let m = N * (D + 1);
    let n_cells = problem.mesh.n_cells();
    let mut force = vec![0.0; dofs.n_total()];
    let mut scale = vec![0.0; dofs.n_total()];
    // Per cell: the m rows of K_e x_e, then those of Σ_q |K_e,pq x_q|.
    let mut products = vec![0.0; 2 * m * FORCE_BLOCK.min(n_cells)];
    for first in (0..n_cells).step_by(FORCE_BLOCK) {
        let cells = first..(first + FORCE_BLOCK).min(n_cells);
        let products = &mut products[..2 * m * cells.len()];
        products.par_chunks_mut(2 * m).zip(cells.clone()).try_for_each(|(out, c)| {
            let k = cell_matrix(problem, c, &simplex::<D, N>(problem, c)?, moduli[c])?;
            let global = local_dofs::<D, N>(dofs, problem.mesh.cell(c));
            for p in 0..m {
                for q in 0..m {
                    let v = k[p][q] * x[global[q]];
                    out[p] += v;
                    out[m + p] += v.abs();
                }
            }
            Ok::<_, crate::error::Error>(())
        })?;
        for (out, c) in products.chunks_mut(2 * m).zip(cells) {
            let global = local_dofs::<D, N>(dofs, problem.mesh.cell(c));
            for (p, &dof) in global[..m].iter().enumerate() {
                force[dof] += out[p];
                scale[dof] += out[m + p];
            }
            out.fill(0.0);
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
                let measure = with_simplex!(problem.mesh.dim(), cell_measure(problem, c))?;
                Ok(factor * measure * revolution_at_centroid(problem, c))
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

/// ‖x‖²_X = ‖ε(u)‖²_{L2} + ‖∇ϕ‖²_{L2}, the norm of the product space X of \[P\] (3.1), in
/// which Theorem 4.1 bounds ‖x(µ, k_e) − x‖_X.
pub fn x_norm_squared(problem: &Problem, dofs: &DofMap, x: &[f64]) -> Result<f64> {
    let mut sum = 0.0;
    for c in 0..problem.mesh.n_cells() {
        sum += with_simplex!(problem.mesh.dim(), x_norm_on(problem, dofs, x, c))?;
    }
    Ok(sum)
}

/// In a body of revolution: the 3 × 3 strain (θθ the hoop strain u_r / r) and ∇ϕ at the
/// centroid of cell `c`, and 2πr there.
fn centroid_fields(
    problem: &Problem,
    dofs: &DofMap,
    x: &[f64],
    c: usize,
) -> Result<([[f64; 3]; 3], [f64; 3], f64)> {
    let coords = problem.mesh.cell_coords::<2, 3>(c);
    let s = simplex::<2, 3>(problem, c)?;
    let cell = problem.mesh.cell(c);
    let u: [[f64; 2]; 3] = std::array::from_fn(|a| [x[dofs.u(cell[a], 0)], x[dofs.u(cell[a], 1)]]);
    let phi: [f64; 3] = std::array::from_fn(|a| x[dofs.phi(cell[a])]);
    let third = 1.0 / 3.0;
    let (eps, grad_phi) =
        axisymmetric::strain_at(&coords, &s, (&u, &phi), &[third, third, third, 0.0]);
    let r = (coords[0][0] + coords[1][0] + coords[2][0]) / 3.0;
    Ok((eps, grad_phi, problem.revolution(&[r, 0.0])))
}

fn x_norm_on<const D: usize, const N: usize>(
    problem: &Problem,
    dofs: &DofMap,
    x: &[f64],
    c: usize,
) -> Result<f64> {
    if problem.axisymmetric {
        let (eps, grad_phi, around) = centroid_fields(problem, dofs, x, c)?;
        let vol = simplex::<2, 3>(problem, c)?.measure() * around;
        let e2: f64 = eps.iter().flatten().map(|v| v * v).sum();
        return Ok(vol * (e2 + grad_phi.iter().map(|v| v * v).sum::<f64>()));
    }
    let (eps, grad_phi) = cell_gradients::<D, N>(problem, dofs, x, c)?;
    let vol = simplex::<D, N>(problem, c)?.measure();
    let e2: f64 = eps.iter().flatten().map(|v| v * v).sum();
    let p2: f64 = grad_phi.iter().map(|v| v * v).sum();
    Ok(vol * (e2 + p2))
}

/// The smallest modulus along ε^D that a linearisation keeps, as a fraction of the secant's
/// (0.3: measured on the paper's bar with t0 from 1e−6 to 8e−2, where 0.1 and 0.5 converge
/// slower or not at all in 100 steps).
pub const FLOOR: f64 = 0.3;

/// What the consistent tangent does beyond t = e·t0, where the law's modulus along ε^D,
/// 2(g + 2 g' t), is not positive.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Beyond {
    /// Keeps the law's tangent: Newton's iteration, quadratic near a solution.
    Whole,
    /// Floors the modulus along ε^D at [`FLOOR`] times the secant's: a positive matrix.
    Floored,
}

/// Hencky's law linearised at an iterate x_n, element by element (model §13): the secant
/// modulus g_e, and for a Newton step the rank-one part of the consistent tangent,
///
/// ```text
/// σ = k0 tr ε I + 2 g(t) ε^D,  t = ‖ε^D‖²
/// dσ = k0 tr dε I + 2 g dε^D + 4 g'(t) (ε^D : dε) ε^D
/// ```
///
/// used where the law softens (g' ≠ 0). Beyond t = e·t0 the law's tangent along ε^D,
/// 2(g + 2 g' t), is no longer positive (the limit of (h1)(b)); the whole tangent keeps it
/// there ([`Beyond::Whole`]: Newton's iteration), the floored one ([`Beyond::Floored`])
/// replaces the coefficient 4 g' by the β that leaves the modulus along ε^D, 2g + β t, at
/// [`FLOOR`] times the secant's 2g: a positive matrix between the secant and the tangent,
/// which converges linearly where the secant alone converges more slowly.
#[derive(Clone, Debug, PartialEq)]
pub struct Linearisation {
    /// g_e(‖ε^D(u_n)‖²) \[stress\].
    pub moduli: Vec<f64>,
    /// The elements that use the rank-one part, in increasing order: (element, 4 g'(t) or
    /// the floored coefficient \[stress\], ε^D(u_n) padded to 3 × 3); empty for the secant.
    /// The others keep their secant: where the law is linear (t ≤ t0) the list is empty, so
    /// that it costs nothing on a mesh whose law softens near the contact alone.
    pub tangent: Vec<(usize, f64, [[f64; 3]; 3])>,
}

impl Linearisation {
    /// The secant alone, with the moduli g_e \[stress\].
    pub fn secant(moduli: Vec<f64>) -> Self {
        Self { moduli, tangent: Vec::new() }
    }

    /// The consistent tangent of Hencky's law at x (global vector): whole, or floored where
    /// it is not positive along ε^D.
    pub fn tangent(problem: &Problem, dofs: &DofMap, x: &[f64], beyond: Beyond) -> Result<Self> {
        let mut moduli = Vec::with_capacity(problem.mesh.n_cells());
        let mut tangent = Vec::new();
        for c in 0..problem.mesh.n_cells() {
            let deviator = with_simplex!(problem.mesh.dim(), deviator_tensor(problem, dofs, x, c))?;
            let t: f64 = deviator.iter().flatten().map(|v| v * v).sum();
            let material = problem.material(c);
            let (g, dg) = (material.modulus(t), material.modulus_slope(t));
            moduli.push(g);
            // Only the elements that use the tangent keep ε^D: an unchanged linearisation then
            // means unchanged moduli wherever the law is linear.
            let floored = beyond == Beyond::Floored && g + 2.0 * dg * t <= 0.0;
            let coefficient = if floored { -2.0 * (1.0 - FLOOR) * g / t } else { 4.0 * dg };
            if dg != 0.0 && coefficient != 0.0 {
                tangent.push((c, coefficient, deviator));
            }
        }
        Ok(Self { moduli, tangent })
    }

    /// Whether a rank-one part is used on some element (the law softens there).
    pub fn is_tangent(&self) -> bool {
        !self.tangent.is_empty()
    }

    /// Element c's rank-one part (its coefficient \[stress\] and ε^D), if it uses one.
    pub fn tangent_of(&self, c: usize) -> Option<(f64, &[[f64; 3]; 3])> {
        let at = self.tangent.binary_search_by_key(&c, |(cell, _, _)| *cell).ok()?;
        let (_, coefficient, deviator) = &self.tangent[at];
        Some((*coefficient, deviator))
    }
}

/// ε^D(u) on cell `c`, padded to 3 × 3 (the deviator in the body's own dimension, model §1).
fn deviator_tensor<const D: usize, const N: usize>(
    problem: &Problem,
    dofs: &DofMap,
    x: &[f64],
    c: usize,
) -> Result<[[f64; 3]; 3]> {
    let (eps, _) = cell_gradients::<D, N>(problem, dofs, x, c)?;
    let m = problem.material(c).deviator_dim;
    let trace = (0..D).map(|i| eps[i][i]).sum::<f64>() / m as f64;
    let mut deviator = [[0.0; 3]; 3];
    for i in 0..D {
        for j in 0..D {
            deviator[i][j] = eps[i][j] - if i == j { trace } else { 0.0 };
        }
    }
    // Plane strain: the 3D deviator's out-of-plane entry (ε_zz = 0).
    (D..m).for_each(|k| deviator[k][k] = -trace);
    Ok(deviator)
}

/// Per-element secant moduli g(‖ε^D(u_n)‖²) \[stress\] at the iterate x_n (global vector).
pub fn secant_moduli(problem: &Problem, dofs: &DofMap, x: &[f64]) -> Result<Vec<f64>> {
    (0..problem.mesh.n_cells())
        .into_par_iter()
        .map(|c| {
            let t = with_simplex!(problem.mesh.dim(), deviator_at(problem, dofs, x, c))?;
            Ok(problem.material(c).modulus(t))
        })
        .collect()
}

/// Element fields of a solution, padded to 3D for output.
#[derive(Clone, Debug, Default)]
pub struct ElementFields {
    /// σ per element, 3 × 3 row-major \[stress\], with the true law g(‖ε^D(u)‖²).
    pub sigma: Vec<[f64; 9]>,
    /// D per element [charge/length^(d−1)].
    pub electric_displacement: Vec<[f64; 3]>,
}

/// σ and D on every element of the solution x (global vector).
pub fn element_fields(problem: &Problem, dofs: &DofMap, x: &[f64]) -> Result<ElementFields> {
    let cells: Vec<([f64; 9], [f64; 3])> = (0..problem.mesh.n_cells())
        .into_par_iter()
        .map(|c| with_simplex!(problem.mesh.dim(), fields_on(problem, dofs, x, c)))
        .collect::<Result<_>>()?;
    let (sigma, electric_displacement) = cells.into_iter().unzip();
    Ok(ElementFields { sigma, electric_displacement })
}

fn fields_on<const D: usize, const N: usize>(
    problem: &Problem,
    dofs: &DofMap,
    x: &[f64],
    c: usize,
) -> Result<([f64; 9], [f64; 3])> {
    let material = problem.material(c);
    if problem.axisymmetric {
        let (eps, grad_phi, _) = centroid_fields(problem, dofs, x, c)?;
        let sigma = material.true_stress(&eps, &grad_phi);
        let d = material.displacement_field(&eps, &grad_phi);
        return Ok((std::array::from_fn(|k| sigma[k / 3][k % 3]), d));
    }
    let (eps, grad_phi) = cell_gradients::<D, N>(problem, dofs, x, c)?;
    let sigma = material.true_stress(&eps, &grad_phi);
    let d = material.displacement_field(&eps, &grad_phi);
    let mut s9 = [0.0; 9];
    let mut d3 = [0.0; 3];
    for i in 0..D {
        d3[i] = d[i];
        for j in 0..D {
            s9[3 * i + j] = sigma[i][j];
        }
    }
    Ok((s9, d3))
}

/// 2πr at the centroid of cell `c` in a body of revolution (1 otherwise): the weight by which
/// the L2 norm of the stopping rules takes the revolution.
fn revolution_at_centroid(problem: &Problem, c: usize) -> f64 {
    let cell = problem.mesh.cell(c);
    let r = cell.iter().map(|&a| problem.mesh.node(a)[0]).sum::<f64>() / cell.len() as f64;
    problem.revolution(&[r, 0.0])
}

fn cell_measure<const D: usize, const N: usize>(problem: &Problem, c: usize) -> Result<f64> {
    Ok(simplex::<D, N>(problem, c)?.measure())
}

fn deviator_at<const D: usize, const N: usize>(
    problem: &Problem,
    dofs: &DofMap,
    x: &[f64],
    c: usize,
) -> Result<f64> {
    if problem.axisymmetric {
        let eps = centroid_fields(problem, dofs, x, c)?.0;
        return Ok(problem.material(c).deviator_norm_squared(&eps));
    }
    let eps = cell_gradients::<D, N>(problem, dofs, x, c)?.0;
    Ok(problem.material(c).deviator_norm_squared(&eps))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algorithm::solve_contact;
    use crate::assembly::Assembler;
    use crate::linalg::max_norm;
    use crate::testing::{PAPER_71, built};

    /// F_int = K x on the free rows (K assembled with the same secant moduli, x zero on the
    /// Dirichlet rows), on a mesh of more cells than [`FORCE_BLOCK`], and the same bits on 1
    /// and 3 threads.
    #[test]
    fn the_internal_force_is_the_matrix_times_x_on_any_number_of_threads() {
        let built = built(PAPER_71, &["mesh.nx=200", "mesh.ny=50"]);
        let problem = &built.problem;
        assert!(problem.mesh.n_cells() > FORCE_BLOCK);
        let dofs = DofMap::new(problem).unwrap();
        let assembler = Assembler::new(problem, dofs.clone(), &[], None).unwrap();
        let free: Vec<f64> = (0..dofs.n_free()).map(|k| ((k * 7919) % 13) as f64 - 6.0).collect();
        let x = dofs.expand(&free);
        let moduli = secant_moduli(problem, &dofs, &x).unwrap();
        let linearisation = Linearisation::secant(moduli.clone());
        let (matrix, _) = assembler.linearised_matrix(problem, &linearisation, &[]).unwrap();
        let on = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            pool.install(|| internal_force(problem, &dofs, &x, &moduli).unwrap())
        };
        let (force, scale) = on(1);
        assert_eq!((force.clone(), scale.clone()), on(3));
        let (ours, exact) = (assembler.restrict(&force), matrix.mul(&free));
        for (k, row_scale) in assembler.restrict(&scale).into_iter().enumerate() {
            assert!((ours[k] - exact[k]).abs() <= 1e-12 * row_scale, "row {k}");
        }
    }

    /// The consistent tangent of Hencky's law is the derivative of the true internal force
    /// K_sec(x) x, checked by central differences at a solution where the law softens.
    #[test]
    fn the_tangent_is_the_derivative_of_the_internal_force() {
        let overrides = ["mesh.nx=24", "mesh.ny=4", "material.t0=1e-2", "solver.method=\"newton\""];
        let built = built(PAPER_71, &overrides);
        let (problem, model) = (&built.problem, built.model.as_ref().unwrap());
        let x = solve_contact(problem, model, &built.settings).unwrap().x;
        let dofs = DofMap::new(problem).unwrap();
        let whole = Linearisation::tangent(problem, &dofs, &x, Beyond::Whole).unwrap();
        let used = whole.tangent.len();
        assert!(used > problem.mesh.n_cells() / 10, "the law softens in {used} elements");
        let assembler = Assembler::new(problem, dofs.clone(), &[], None).unwrap();
        let (matrix, _) = assembler.linearised_matrix(problem, &whole, &[]).unwrap();
        let force = |x: &[f64]| {
            let moduli = secant_moduli(problem, &dofs, x).unwrap();
            assembler.restrict(&internal_force(problem, &dofs, x, &moduli).unwrap().0)
        };
        let free = assembler.restrict(&x);
        let direction: Vec<f64> = (0..free.len()).map(|k| ((k * 7919) % 13) as f64 - 6.0).collect();
        let size = max_norm(&free);
        let h = 1e-6 * size / 6.0;
        let shifted = |sign: f64| {
            let moved: Vec<f64> =
                free.iter().zip(&direction).map(|(a, d)| a + sign * h * d).collect();
            force(&dofs.expand(&moved))
        };
        let (plus, minus) = (shifted(1.0), shifted(-1.0));
        let exact = matrix.mul(&direction);
        let scale = max_norm(&exact);
        let error = (0..free.len())
            .map(|k| ((plus[k] - minus[k]) / (2.0 * h) - exact[k]).abs())
            .fold(0.0, f64::max);
        assert!(error < 1e-5 * scale, "{error:e} against {scale:e}");
    }
}
