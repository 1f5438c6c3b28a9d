//! The right-hand side f̌ of \[P\] (6.3), model §5:
//!
//! ```text
//! (f̌, y) = ∫Ω f0·v + ∫Γ2 f2·v − ∫Ω q0 ξ + ∫Γb q2 ξ
//! ```
//!
//! Loads are fields of x, integrated with a degree-2 rule on cells and facets (with the
//! weight 2πr in a body of revolution: the integrals are over the whole revolution).

use crate::dofs::DofMap;
use crate::element::{Simplex, point_at, quadrature};
use crate::problem::Problem;

/// f̌ on the global DOFs of `dofs`, every load scaled by `load_factor` [-] (a step of a
/// loading path; 1 for the case's loads).
pub fn load_vector(problem: &Problem, dofs: &DofMap, load_factor: f64) -> Vec<f64> {
    with_simplex!(problem.mesh.dim(), load_vector_on(problem, dofs, load_factor))
}

fn load_vector_on<const D: usize, const N: usize>(
    problem: &Problem,
    dofs: &DofMap,
    load_factor: f64,
) -> Vec<f64> {
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
                let around = problem.revolution(&p);
                for (a, &node) in mesh.cell(c).iter().enumerate() {
                    let weight = vol * w * lambda[a] * around;
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
    f.iter_mut().for_each(|v| *v *= load_factor);
    f
}

/// Calls `f(node, weight, point)` for each quadrature point and node of the part's facets,
/// with weight = |e| w_q N_a(x_q) (times 2πr_q in a body of revolution).
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
            let around = problem.revolution(&p);
            for (a, &node) in facet.iter().enumerate() {
                f(node, measure * w * lambda[a] * around, &p);
            }
        }
    }
}
