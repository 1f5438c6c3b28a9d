//! Foundation surfaces (model §12) on the paper's bar: a horizontal plane is the paper's
//! constant gap, a tilted plane gives each Γ3 node its own gap, and a plane above the bottom
//! face (negative gaps) is pushed out of the body.

use super::common::{PAPER_UNITS, paper_model, paper_problem};
use piezocontact::algorithm::{ContactModel, ContactSolution, Method, Settings, solve_contact};
use piezocontact::contact::Foundation;
use piezocontact::material::ElasticLaw;
use piezocontact::problem::Problem;

fn newton() -> Settings {
    let young = PAPER_UNITS.stress(58.7102);
    Settings {
        method: Method::Newton { c: 0.25 * young, tol: 1e-10, max_inner: 100 },
        eps_fp: 1e-10,
        max_outer: 10,
    }
}

fn solve(problem: &Problem, model: &ContactModel) -> ContactSolution {
    let solution = solve_contact(problem, model, &newton()).unwrap();
    assert!(solution.converged && solution.kkt.max <= 1e-10, "{:?}", solution.failure);
    solution
}

/// A plane under Γ3 through (x, y0) with unit normal (sin θ, cos θ), and no offset.
fn plane(model: &ContactModel, y0: f64, theta: f64) -> ContactModel {
    let mut model = model.clone();
    model.compliance.gap = 0.0;
    model.foundation =
        Foundation::Plane { point: [6.0, y0, 0.0], normal: [theta.sin(), theta.cos(), 0.0] };
    model
}

#[test]
fn a_horizontal_plane_is_the_constant_gap() {
    let problem = paper_problem(48, 8, PAPER_UNITS, ElasticLaw::Linear);
    let paper = paper_model(Some((0.6, 1.0)), 0.0, PAPER_UNITS);
    let a = solve(&problem, &paper);
    let b = solve(&problem, &plane(&paper, -0.5, 0.0));
    assert!(b.surface.gap.iter().all(|g| (g - 0.5).abs() < 1e-15));
    let size = a.x.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let gap = a.x.iter().zip(&b.x).fold(0.0_f64, |m, (p, q)| m.max((p - q).abs()));
    assert!(gap <= 1e-12 * size, "{gap} of {size}");
}

#[test]
fn a_tilted_plane_gives_each_node_its_gap() {
    let problem = paper_problem(48, 8, PAPER_UNITS, ElasticLaw::Linear);
    let model = plane(&paper_model(None, 0.0, PAPER_UNITS), -0.5, 0.02);
    let solution = solve(&problem, &model);
    let surface = &solution.surface;
    let dofs = &solution.dofs;
    let mut touching = Vec::new();
    for i in 0..surface.len() {
        // ν = (0, −1): the gap is the vertical distance to the plane through (6, −0.5).
        let x = surface.position(&problem, i);
        let expected = x[1] + 0.5 + (x[0] - 6.0) * 0.02f64.tan();
        assert!((surface.gap[i] - expected).abs() < 1e-12, "node {i}");
        let (u_nu, _) = surface.split(dofs, &solution.x, i);
        assert!(u_nu <= surface.gap[i] + 1e-12, "node {i} penetrates the plane");
        if solution.sigma_nu[i] < 0.0 {
            touching.push(x[0]);
        }
    }
    // The plane falls away to the right (its gap grows with x), so the bar touches it more
    // on the left.
    let centre = touching.iter().sum::<f64>() / touching.len() as f64;
    assert!(centre < 6.0, "contact centred at x = {centre}");
}

#[test]
fn negative_gaps_are_removed() {
    let problem = paper_problem(48, 8, PAPER_UNITS, ElasticLaw::Linear);
    let model = plane(&paper_model(Some((0.2, 0.2)), 0.0, PAPER_UNITS), 0.01, 0.0);
    let solution = solve(&problem, &model);
    let surface = &solution.surface;
    for i in 0..surface.len() {
        assert!((surface.gap[i] + 0.01).abs() < 1e-15);
        let (u_nu, _) = surface.split(&solution.dofs, &solution.x, i);
        assert!(u_nu <= -0.01 + 1e-12, "node {i}: u_ν = {u_nu}");
    }
    assert!(solution.sigma_nu.iter().all(|s| *s < 0.0), "every node is pushed out");
}
