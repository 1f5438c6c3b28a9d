//! Foundation surfaces (model §12) on the paper's bar: a horizontal plane is the paper's
//! constant gap, a tilted plane gives each Γ3 node its own gap, and a plane above the bottom
//! face (negative gaps) is pushed out of the body.

use super::common::{PAPER_UNITS, paper_model, paper_problem};
use piezocontact::algorithm::condensed::Guess;
use piezocontact::algorithm::newton::{self, Newton};
use piezocontact::algorithm::{ContactSolution, Settings, solve_contact};
use piezocontact::contact::ContactModel;
use piezocontact::contact::Foundation;
use piezocontact::material::ElasticLaw;
use piezocontact::problem::Problem;

/// Newton condensing at most `max_condensed` Γ3 nodes, the nearest first.
fn newton(max_condensed: usize) -> Settings {
    newton_with(Some(max_condensed), Guess::Nearest(max_condensed))
}

/// Newton with its cap and its first guess.
fn newton_with(max_condensed: Option<usize>, guess: Guess) -> Settings {
    let young = PAPER_UNITS.stress(58.7102);
    let parameters =
        newton::Parameters { r: 0.25 * young, tol: 1e-10, max_inner: 100, max_condensed, guess };
    Settings::new(Newton::new(parameters), 10)
}

fn solve_with(problem: &Problem, model: &ContactModel, settings: &Settings) -> ContactSolution {
    let solution = solve_contact(problem, model, settings).unwrap();
    assert!(solution.converged() && solution.kkt.max <= 1e-10, "{:?}", solution.failure);
    solution
}

fn solve(problem: &Problem, model: &ContactModel) -> ContactSolution {
    solve_with(problem, model, &newton(2000))
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

/// The block [−1,1]² × [−1,0] in n × n × m cubes, each split into 5 tetrahedra in a
/// checkerboard (the split of a cube and of its neighbours are mirror images), so that with n
/// even the mesh is symmetric under x ↦ −x and y ↦ −y. Parts: "top" (z = 0), "bottom".
fn symmetric_block(n: usize, m: usize) -> piezocontact::mesh::Mesh {
    let id = |i: usize, j: usize, k: usize| (k * (n + 1) + j) * (n + 1) + i;
    let mut coords = Vec::new();
    for k in 0..=m {
        for j in 0..=n {
            for i in 0..=n {
                let h = 2.0 / n as f64;
                coords.extend([
                    -1.0 + i as f64 * h,
                    -1.0 + j as f64 * h,
                    -1.0 + k as f64 / m as f64,
                ]);
            }
        }
    }
    // Corner v = a + 2b + 4c of a cube; the two 5-tetrahedron splits.
    const EVEN: [[usize; 4]; 5] =
        [[1, 2, 4, 7], [0, 1, 2, 4], [3, 1, 2, 7], [5, 1, 4, 7], [6, 2, 4, 7]];
    const ODD: [[usize; 4]; 5] =
        [[0, 3, 5, 6], [1, 0, 3, 5], [2, 0, 3, 6], [4, 0, 5, 6], [7, 3, 5, 6]];
    let mut cells = Vec::new();
    for k in 0..m {
        for j in 0..n {
            for i in 0..n {
                let corner = |v: usize| id(i + (v & 1), j + ((v >> 1) & 1), k + ((v >> 2) & 1));
                let split = if (i + j + k) % 2 == 0 { &EVEN } else { &ODD };
                for t in split {
                    let mut tet = t.map(corner);
                    // Right-handed: a positive signed volume.
                    let x = |a: usize, k: usize| coords[3 * tet[a] + k] - coords[3 * tet[0] + k];
                    let volume = x(1, 0) * (x(2, 1) * x(3, 2) - x(2, 2) * x(3, 1))
                        - x(1, 1) * (x(2, 0) * x(3, 2) - x(2, 2) * x(3, 0))
                        + x(1, 2) * (x(2, 0) * x(3, 1) - x(2, 1) * x(3, 0));
                    if volume < 0.0 {
                        tet.swap(2, 3);
                    }
                    cells.extend(tet);
                }
            }
        }
    }
    // Boundary faces on z = 0 and z = −1: the tetrahedron faces with three nodes there.
    let z = |a: usize| coords[3 * a + 2];
    let (mut top, mut bottom) = (Vec::new(), Vec::new());
    for tet in cells.chunks(4) {
        for skip in 0..4 {
            let face: Vec<usize> = (0..4).filter(|&q| q != skip).map(|q| tet[q]).collect();
            if face.iter().all(|&a| z(a) == 0.0) {
                top.extend(&face);
            } else if face.iter().all(|&a| z(a) == -1.0) {
                bottom.extend(&face);
            }
        }
    }
    let parts = vec![
        piezocontact::mesh::BoundaryPart::new("top", top),
        piezocontact::mesh::BoundaryPart::new("bottom", bottom),
    ];
    piezocontact::mesh::Mesh::new(3, coords, cells, parts).unwrap()
}

/// A ball of radius 0.5 pressed 0.1 into the middle of the PZT block [−1,1]² × [−1,0]
/// (12 × 12 × 4 cubes; poled along z, so the material has the block's mirror symmetries),
/// clamped and grounded at the bottom, with friction µ = 0.3.
fn ball_on_block() -> (Problem, ContactModel) {
    use piezocontact::problem::{BodyLoads, Boundary};
    let mesh = symmetric_block(12, 4);
    let part = |n: &str| mesh.part_index(n).unwrap();
    let boundary = Boundary {
        clamped: vec![part("bottom")],
        grounded: vec![part("bottom")],
        contact: vec![part("top")],
        ..Boundary::default()
    };
    let material = super::common::pzt(3, ElasticLaw::Linear);
    let problem = Problem::new(mesh, material, boundary, BodyLoads::default()).unwrap();
    let mut model = paper_model(Some((0.3, 0.0)), 0.0, PAPER_UNITS);
    model.compliance.gap = 0.0;
    model.foundation = Foundation::Sphere { center: [0.0, 0.0, 0.4], radius: 0.5 };
    (problem, model)
}

/// The ball on the block: the solution is mirror-symmetric.
#[test]
fn a_symmetric_3d_problem_has_a_symmetric_solution() {
    let (problem, model) = ball_on_block();
    let solution = solve(&problem, &model);
    let (mesh, dofs, x) = (&problem.mesh, &solution.dofs, &solution.x);
    let node_at = |p: [f64; 3]| {
        (0..mesh.n_nodes())
            .find(|&a| (0..3).all(|k| (mesh.node(a)[k] - p[k]).abs() < 1e-12))
            .unwrap()
    };
    let size = x.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let (mut checked, mut worst) = (0, 0.0_f64);
    for a in 0..mesh.n_nodes() {
        let p = mesh.node(a);
        for (axis, sign) in [(0, [-1.0, 1.0, 1.0]), (1, [1.0, -1.0, 1.0])] {
            let mut q = [p[0], p[1], p[2]];
            q[axis] = -q[axis];
            let b = node_at(q);
            for k in 0..3 {
                worst = worst.max((x[dofs.u(a, k)] - sign[k] * x[dofs.u(b, k)]).abs());
            }
            let phi_size = (0..mesh.n_nodes()).map(|c| x[dofs.phi(c)].abs()).fold(0.0, f64::max);
            assert!((x[dofs.phi(a)] - x[dofs.phi(b)]).abs() <= 1e-10 * phi_size, "ϕ at {p:?}");
            checked += 1;
        }
    }
    assert!(worst <= 1e-10 * size, "u is not mirror-symmetric: {worst} of {size}");
    let touching = solution.sigma_nu.iter().filter(|s| **s < 0.0).count();
    println!("{checked} mirror pairs, {touching} Γ3 nodes touch, worst u difference {worst:.1e}");
    assert!(touching >= 9, "the ball barely touches");
}

/// A disk under the middle of the bar: most Γ3 normals miss it (infinite gaps). The exact
/// solver leaves those nodes out of its condensed problem; the paper's Uzawa algorithm,
/// run tightly, keeps every node, and both give one solution.
#[test]
fn nodes_that_cannot_touch_change_nothing() {
    let problem = paper_problem(48, 8, PAPER_UNITS, ElasticLaw::Linear);
    let mut model = paper_model(Some((0.3, 0.0)), 0.0, PAPER_UNITS);
    model.compliance.gap = 0.0;
    model.foundation = Foundation::Sphere { center: [6.0, -1.3, 0.0], radius: 1.0 };
    let exact = solve(&problem, &model);
    let surface = &exact.surface;
    let misses = surface.gap.iter().filter(|g| g.is_infinite()).count();
    assert!(2 * misses > surface.len(), "{misses} of {} miss the disk", surface.len());
    // Only the nodes that can touch are condensed.
    assert_eq!(exact.condensed_nodes, surface.len() - misses);
    assert!(exact.sigma_nu.iter().filter(|s| **s < 0.0).count() >= 3, "no contact");
    let tight = super::common::paper_settings(PAPER_UNITS, 1e-13);
    let uzawa = solve_contact(&problem, &model, &tight).unwrap();
    assert!(uzawa.converged(), "{:?}", uzawa.failure);
    let size = exact.x.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let gap = exact.x.iter().zip(&uzawa.x).fold(0.0_f64, |m, (p, q)| m.max((p - q).abs()));
    assert!(gap <= 1e-7 * size, "{gap} of {size}");
}

/// The ball on the block with room for two more nodes than touch, of the 29 within the
/// ball's reach: the nodes nearest to the ball are the contact zone, so the first guess is
/// the answer — one factorisation, the solution of the whole condensation, and the nodes
/// left out clear of the ball.
#[test]
fn the_nodes_nearest_to_a_ball_are_its_contact_zone() {
    let (problem, model) = ball_on_block();
    let whole = solve(&problem, &model);
    let surface = &whole.surface;
    let touching = whole.sigma_nu.iter().filter(|s| **s < 0.0).count();
    let reach = surface.gap.iter().filter(|g| g.is_finite()).count();
    assert_eq!(whole.condensed_nodes, reach);
    let max_condensed = touching + 2;
    assert!(max_condensed < reach, "{touching}, {reach}");
    let part = solve_with(&problem, &model, &newton(max_condensed));
    assert_eq!((part.condensed_nodes, part.timings.solver.numeric_count), (max_condensed, 1));
    let size = whole.x.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let gap = whole.x.iter().zip(&part.x).fold(0.0_f64, |m, (p, q)| m.max((p - q).abs()));
    assert!(gap <= 1e-10 * size, "{gap} of {size}");
    for i in 0..surface.len() {
        let (u_nu, _) = surface.split(&part.dofs, &part.x, i);
        assert!(u_nu <= surface.gap[i] + 1e-12 * size, "node {i} passes through the ball");
    }
}

/// Room for fewer nodes than touch: the run is refused with the number it needs.
#[test]
fn a_contact_zone_larger_than_max_condensed_is_refused() {
    let (problem, model) = ball_on_block();
    let e = solve_contact(&problem, &model, &newton(4)).unwrap_err().to_string();
    assert!(
        e.contains("larger than solver.max_condensed = 4 nodes")
            && e.contains("raise solver.max_condensed to at least")
            && e.contains("uzawa"),
        "{e}"
    );
}

/// Without a cap, the same first set of the 4 nearest nodes grows as far as the contact
/// zone: the solution of the whole condensation, with every touching node condensed. The
/// growth's factorisation and solves happen inside the exact solver's steps, and its time line
/// counts them once: with the dense problem they stay within the run's wall-clock time.
#[test]
fn without_a_cap_the_condensation_grows_as_far_as_the_contact_zone() {
    let (problem, model) = ball_on_block();
    let whole = solve(&problem, &model);
    let start = std::time::Instant::now();
    let grown = solve_with(&problem, &model, &newton_with(None, Guess::Nearest(4)));
    let (wall, t) = (start.elapsed().as_secs_f64(), grown.timings);
    assert!(t.dense > 0.0 && t.counted() + t.dense <= wall, "{t:?} in {wall} s");
    let touching = whole.sigma_nu.iter().filter(|s| **s < 0.0).count();
    assert!(touching > 4 && grown.condensed_nodes >= touching, "{}", grown.condensed_nodes);
    let size = whole.x.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let gap = whole.x.iter().zip(&grown.x).fold(0.0_f64, |m, (p, q)| m.max((p - q).abs()));
    assert!(gap <= 1e-10 * size, "{gap} of {size}");
}

/// The default first guess of the exact solver: the nodes inside the ball (g_a ≤ 0), which
/// hold its contact zone — far fewer than the nodes within reach, one factorisation, and the
/// solution of the whole condensation.
#[test]
fn the_first_guess_is_the_nodes_inside_the_ball() {
    let (problem, model) = ball_on_block();
    let whole = solve(&problem, &model);
    let guessed = solve_with(&problem, &model, &newton_with(None, Guess::Interpenetration(2000)));
    let surface = &whole.surface;
    let inside = surface.gap.iter().filter(|g| **g <= 0.0).count();
    let touching = whole.sigma_nu.iter().filter(|s| **s < 0.0).count();
    println!("{inside} inside, {touching} touch, {} within reach", whole.condensed_nodes);
    assert_eq!((guessed.condensed_nodes, guessed.timings.solver.numeric_count), (inside, 1));
    assert!(touching <= inside && 2 * inside < whole.condensed_nodes);
    let size = whole.x.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let gap = whole.x.iter().zip(&guessed.x).fold(0.0_f64, |m, (p, q)| m.max((p - q).abs()));
    assert!(gap <= 1e-10 * size, "{gap} of {size}");
}

/// Nonlocal friction (a mollifier of radius 0.35, two mesh spacings) lends the nodes around
/// the contact zone a friction bound: the first guess — the nodes inside the ball — leaves
/// out nodes that bear friction though they do not touch, and the growth adds them, so that
/// the run ends at the solution of the whole condensation, with every node that has a bound
/// condensed.
#[test]
fn nonlocal_friction_grows_the_condensation_to_the_nodes_it_reaches() {
    use piezocontact::contact::law::Regularization;
    let (problem, mut model) = ball_on_block();
    let friction = &mut model.friction.as_mut().unwrap();
    friction.regularization = Regularization::Mollifier { radius: 0.35 };
    let whole = solve(&problem, &model);
    let guessed = solve_with(&problem, &model, &newton_with(None, Guess::Interpenetration(2000)));
    let surface = &whole.surface;
    let inside = surface.gap.iter().filter(|g| **g <= 0.0).count();
    let bound = whole.s.iter().filter(|s| **s > 0.0).count();
    assert!(bound > inside, "{bound} nodes with a friction bound, {inside} inside the ball");
    assert!(guessed.condensed_nodes >= bound, "{} condensed", guessed.condensed_nodes);
    let size = whole.x.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let gap = whole.x.iter().zip(&guessed.x).fold(0.0_f64, |m, (p, q)| m.max((p - q).abs()));
    assert!(gap <= 1e-10 * size, "{gap} of {size}");
}

/// Without friction, a flat contact face along the axes condenses u_ν alone (the tangential
/// components carry no force and stay with the interior): PV1 on the ball gives the solution
/// of PV2 with µ = k_e = 0, which condenses every component — to round-off — with the same
/// single factorisation.
#[test]
fn a_frictionless_flat_face_condenses_the_normal_alone() {
    let (problem, mut model) = ball_on_block();
    model.friction.as_mut().unwrap().mu = 0.0;
    model.conduction.as_mut().unwrap().ke = 0.0;
    let every_component = solve(&problem, &model);
    (model.friction, model.conduction) = (None, None);
    let normal_alone = solve(&problem, &model);
    let size = every_component.x.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let difference = every_component
        .x
        .iter()
        .zip(&normal_alone.x)
        .fold(0.0_f64, |m, (p, q)| m.max((p - q).abs()));
    assert!(difference <= 1e-10 * size, "{difference} of {size}");
    assert_eq!(normal_alone.timings.solver.numeric_count, 1);
    assert!(normal_alone.sigma_nu.iter().filter(|s| **s < 0.0).count() >= 9);
}
