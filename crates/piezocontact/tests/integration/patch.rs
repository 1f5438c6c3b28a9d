//! Patch tests: for every linear field (u, ϕ) the P1 solution is exact. The fields are
//! imposed on Γ1/Γa and, in the Neumann variant, through the tractions σν and charges D·ν they
//! produce on the other sides — which checks the load assembly as well.

use super::common::{perturbed_square, pzt, read_mesh};
use piezocontact::dofs::DofMap;
use piezocontact::linalg::default_solver;
use piezocontact::material::ElasticLaw;
use piezocontact::mesh::Mesh;
use piezocontact::problem::{BodyLoads, Boundary, Problem, ScalarField, VectorField};
use piezocontact::system::solve_without_contact;
use std::sync::Arc;

/// u = A x + a, ϕ = c·x + c0 with coefficients of the natural sizes of the paper's units.
fn linear_fields(dim: usize) -> (VectorField, ScalarField, Vec<Vec<f64>>, Vec<f64>) {
    let a: Vec<Vec<f64>> = (0..dim)
        .map(|i| (0..dim).map(|j| 0.01 * ((3 * i + j) as f64 + 1.0).sin()).collect())
        .collect();
    let c: Vec<f64> = (0..dim).map(|i| 0.2 * (i as f64 + 0.5).cos()).collect();
    let (a2, c2) = (a.clone(), c.clone());
    let u: VectorField = Arc::new(move |x: &[f64]| {
        (0..x.len())
            .map(|i| 0.003 * i as f64 + (0..x.len()).map(|j| a2[i][j] * x[j]).sum::<f64>())
            .collect()
    });
    let phi: ScalarField =
        Arc::new(move |x: &[f64]| 0.05 + (0..x.len()).map(|j| c2[j] * x[j]).sum::<f64>());
    (u, phi, a, c)
}

fn assert_exact(problem: &Problem, u: &VectorField, phi: &ScalarField) {
    let solution = solve_without_contact(problem, default_solver()).unwrap();
    let dofs = DofMap::new(problem).unwrap();
    let mesh = &problem.mesh;
    let (mut err_u, mut err_phi, mut size_u, mut size_phi) = (0.0_f64, 0.0_f64, 0.0_f64, 0.0_f64);
    for n in 0..mesh.n_nodes() {
        let (ue, pe) = (u(mesh.node(n)), phi(mesh.node(n)));
        for (i, ue_i) in ue.iter().enumerate() {
            err_u = err_u.max((solution.x[dofs.u(n, i)] - ue_i).abs());
            size_u = size_u.max(ue_i.abs());
        }
        err_phi = err_phi.max((solution.x[dofs.phi(n)] - pe).abs());
        size_phi = size_phi.max(pe.abs());
    }
    assert!(err_u < 1e-11 * size_u, "u error {err_u:e} of {size_u:e}");
    assert!(err_phi < 1e-11 * size_phi, "phi error {err_phi:e} of {size_phi:e}");
}

fn dirichlet_everywhere(mesh: Mesh) -> (Problem, VectorField, ScalarField) {
    let dim = mesh.dim();
    let (u, phi, _, _) = linear_fields(dim);
    let all: Vec<usize> = (0..mesh.parts().len()).collect();
    let boundary = Boundary {
        clamped: all.clone(),
        grounded: all,
        clamped_value: Some(u.clone()),
        grounded_value: Some(phi.clone()),
        ..Boundary::default()
    };
    let problem =
        Problem::new(mesh, pzt(dim, ElasticLaw::Linear), boundary, BodyLoads::default()).unwrap();
    (problem, u, phi)
}

#[test]
fn linear_fields_are_exact_on_unstructured_2d_meshes() {
    for mesh in [perturbed_square(6, 0.3), read_mesh("paper-rectangle.msh"), read_mesh("arch.msh")]
    {
        let (problem, u, phi) = dirichlet_everywhere(mesh);
        assert_exact(&problem, &u, &phi);
    }
}

#[test]
fn linear_fields_are_exact_on_a_3d_mesh() {
    let (problem, u, phi) = dirichlet_everywhere(read_mesh("cube.msh"));
    assert_exact(&problem, &u, &phi);
}

#[test]
fn linear_fields_are_exact_with_tractions_and_charges() {
    let mesh = perturbed_square(5, 0.3);
    let material = pzt(2, ElasticLaw::Linear);
    let (u, phi, a, c) = linear_fields(2);
    let eps = [[a[0][0], 0.5 * (a[0][1] + a[1][0])], [0.5 * (a[0][1] + a[1][0]), a[1][1]]];
    let grad_phi = [c[0], c[1]];
    let sigma = material.true_stress(&eps, &grad_phi);
    let d = material.displacement_field(&eps, &grad_phi);
    let normals = [
        ("left", [-1.0, 0.0]),
        ("right", [1.0, 0.0]),
        ("bottom", [0.0, -1.0]),
        ("top", [0.0, 1.0]),
    ];
    let part = |name: &str| mesh.part_index(name).unwrap();
    let traction = |n: [f64; 2]| -> VectorField {
        let t =
            vec![sigma[0][0] * n[0] + sigma[0][1] * n[1], sigma[1][0] * n[0] + sigma[1][1] * n[1]];
        Arc::new(move |_| t.clone())
    };
    let charge = |n: [f64; 2]| -> ScalarField {
        let q = d[0] * n[0] + d[1] * n[1];
        Arc::new(move |_| q)
    };
    let boundary = Boundary {
        clamped: vec![part("left")],
        grounded: vec![part("bottom")],
        traction: normals[1..].iter().map(|(name, n)| (part(name), traction(*n))).collect(),
        charge: [normals[0], normals[1], normals[3]]
            .iter()
            .map(|(name, n)| (part(name), charge(*n)))
            .collect(),
        clamped_value: Some(u.clone()),
        grounded_value: Some(phi.clone()),
        ..Boundary::default()
    };
    let problem = Problem::new(mesh, material, boundary, BodyLoads::default()).unwrap();
    assert_exact(&problem, &u, &phi);
}
