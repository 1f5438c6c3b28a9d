//! Manufactured solutions for the coupled piezoelectric system without contact (model §10):
//! P1 errors must fall like h² in L2 and like h in H1, for u and for ϕ.
//!
//! Exact fields on Ω = (0,1)², zero on ∂Ω (Γ1 = Γa = ∂Ω):
//! u = (sin πx sin πy, ½ sin 2πx sin πy),   ϕ = A (1 + x) sin πx sin πy,
//! with the paper's PZT-5A in the units (m, GPa, C, GV). With A = 3 the coupling term Eᵀ∇ϕ is
//! of the size of Fε in σ, and Eε dominates β∇ϕ in D: the coupling matters in both equations.
//! f0 = −Div σ and q0 = div D are computed from the exact σ, D by fourth-order differences.

use super::common::{perturbed_square, pzt};
use piezocontact::assembly::cell_gradients;
use piezocontact::dofs::DofMap;
use piezocontact::element::{Simplex, point_at, quadrature};
use piezocontact::linalg::default_solver;
use piezocontact::material::{ElasticLaw, Material};
use piezocontact::problem::{BodyLoads, Boundary, Problem};
use piezocontact::system::solve_without_contact;
use std::f64::consts::PI;
use std::sync::Arc;

const A: f64 = 3.0;

/// Exact (u, ∇u, ϕ, ∇ϕ) at x.
fn exact(x: &[f64]) -> ([f64; 2], [[f64; 2]; 2], f64, [f64; 2]) {
    let (sx, cx, sy, cy) =
        ((PI * x[0]).sin(), (PI * x[0]).cos(), (PI * x[1]).sin(), (PI * x[1]).cos());
    let (s2x, c2x) = ((2.0 * PI * x[0]).sin(), (2.0 * PI * x[0]).cos());
    let u = [sx * sy, 0.5 * s2x * sy];
    let grad_u = [[PI * cx * sy, PI * sx * cy], [PI * c2x * sy, 0.5 * PI * s2x * cy]];
    let phi = A * (1.0 + x[0]) * sx * sy;
    let grad_phi = [A * (sx * sy + (1.0 + x[0]) * PI * cx * sy), A * (1.0 + x[0]) * PI * sx * cy];
    (u, grad_u, phi, grad_phi)
}

fn sigma_and_d(m: &Material, x: &[f64]) -> ([[f64; 2]; 2], [f64; 2]) {
    let (_, gu, _, gp) = exact(x);
    let eps = [[gu[0][0], 0.5 * (gu[0][1] + gu[1][0])], [0.5 * (gu[0][1] + gu[1][0]), gu[1][1]]];
    (m.true_stress(&eps, &gp), m.displacement_field(&eps, &gp))
}

/// ∂/∂x_k of g at x by fourth-order central differences.
fn derivative(g: &dyn Fn(&[f64]) -> f64, x: &[f64], k: usize) -> f64 {
    let h = 1e-3;
    let at = |t: f64| {
        let mut y = [x[0], x[1]];
        y[k] += t;
        g(&y)
    };
    (-at(2.0 * h) + 8.0 * at(h) - 8.0 * at(-h) + at(-2.0 * h)) / (12.0 * h)
}

fn problem(n: usize, material: &Material) -> Problem {
    let mesh = perturbed_square(n, 0.0);
    let (m1, m2) = (material.clone(), material.clone());
    let f0 = Arc::new(move |x: &[f64]| {
        (0..2)
            .map(|i| {
                -(0..2).map(|j| derivative(&|y| sigma_and_d(&m1, y).0[i][j], x, j)).sum::<f64>()
            })
            .collect()
    });
    let q0 = Arc::new(move |x: &[f64]| {
        (0..2).map(|j| derivative(&|y| sigma_and_d(&m2, y).1[j], x, j)).sum::<f64>()
    });
    let all: Vec<usize> = (0..4).collect();
    let boundary = Boundary { clamped: all.clone(), grounded: all, ..Boundary::default() };
    Problem::new(mesh, material.clone(), boundary, BodyLoads { f0: Some(f0), q0: Some(q0) })
        .unwrap()
}

/// [L2(u), H1(u), L2(ϕ), H1(ϕ)] errors (H1 = seminorm).
fn errors(problem: &Problem, x: &[f64]) -> [f64; 4] {
    let dofs = DofMap::new(problem).unwrap();
    let mesh = &problem.mesh;
    let mut e = [0.0; 4];
    for c in 0..mesh.n_cells() {
        let xs = mesh.cell_coords::<2, 3>(c);
        let s = Simplex::<2, 3>::new(&xs).unwrap();
        let (eps_h, grad_phi_h) = cell_gradients::<2, 3>(problem, &dofs, x, c).unwrap();
        // ∇u_h from the strain is not enough (rotation): rebuild it from the nodes.
        let mut grad_u_h = [[0.0; 2]; 2];
        for (a, &node) in mesh.cell(c).iter().enumerate() {
            for i in 0..2 {
                for j in 0..2 {
                    grad_u_h[i][j] += x[dofs.u(node, i)] * s.grad[a][j];
                }
            }
        }
        assert!((grad_u_h[0][1] + grad_u_h[1][0] - 2.0 * eps_h[0][1]).abs() < 1e-12);
        for (lambda, w) in quadrature(2) {
            let p = point_at(&xs, lambda);
            let (u, gu, phi, gp) = exact(&p);
            let weight = w * s.measure();
            let cell = mesh.cell(c);
            for i in 0..2 {
                let uh: f64 = (0..3).map(|a| lambda[a] * x[dofs.u(cell[a], i)]).sum();
                e[0] += weight * (uh - u[i]).powi(2);
                for j in 0..2 {
                    e[1] += weight * (grad_u_h[i][j] - gu[i][j]).powi(2);
                }
                e[3] += weight * (grad_phi_h[i] - gp[i]).powi(2);
            }
            let phih: f64 = (0..3).map(|a| lambda[a] * x[dofs.phi(cell[a])]).sum();
            e[2] += weight * (phih - phi).powi(2);
        }
    }
    e.map(f64::sqrt)
}

#[test]
fn coupled_system_converges_at_optimal_rates() {
    let material = pzt(2, ElasticLaw::Linear);
    let sizes = [8, 16, 32, 64, 128];
    let errs: Vec<[f64; 4]> = sizes
        .iter()
        .map(|&n| {
            let p = problem(n, &material);
            errors(&p, &solve_without_contact(&p, default_solver()).unwrap().x)
        })
        .collect();
    println!(
        "{:>5} {:>11} {:>5} {:>11} {:>5} {:>11} {:>5} {:>11} {:>5}",
        "n", "L2(u)", "rate", "H1(u)", "rate", "L2(phi)", "rate", "H1(phi)", "rate"
    );
    let mut last_rates = [0.0; 4];
    for (k, (n, e)) in sizes.iter().zip(&errs).enumerate() {
        let rates: Vec<f64> = (0..4)
            .map(|q| if k == 0 { f64::NAN } else { (errs[k - 1][q] / e[q]).log2() })
            .collect();
        println!(
            "{n:>5} {:>11.3e} {:>5.2} {:>11.3e} {:>5.2} {:>11.3e} {:>5.2} {:>11.3e} {:>5.2}",
            e[0], rates[0], e[1], rates[1], e[2], rates[2], e[3], rates[3]
        );
        if k > 0 {
            last_rates.copy_from_slice(&rates);
        }
    }
    for (q, (name, expected)) in
        [("L2(u)", 2.0), ("H1(u)", 1.0), ("L2(phi)", 2.0), ("H1(phi)", 1.0)].iter().enumerate()
    {
        assert!(
            (last_rates[q] - expected).abs() < 0.1,
            "{name}: rate {} (expected {expected})",
            last_rates[q]
        );
    }
}
