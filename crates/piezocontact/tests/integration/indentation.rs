//! Indentation experiments (model §14): the charge on the electrodes, loading paths, the
//! cone and the punch against Sneddon and Boussinesq.

use super::common::{
    EPS0, PAPER_UNITS, committed_case, contact_run, mesh_file, paper_model, path_run,
    perturbed_square,
};
use piezocontact::algorithm::condensed::Guess;
use piezocontact::algorithm::newton::{self, Newton};
use piezocontact::algorithm::{ContactSolver, Settings, solve_contact};
use piezocontact::case::{Built, Case};
use piezocontact::linalg::default_solver;
use piezocontact::material::{
    ElasticLaw, Elasticity, Material, PermittivityConstants, PiezoConstants,
};
use piezocontact::oracles;
use piezocontact::problem::{BodyLoads, Boundary, Problem};
use piezocontact::report::CurveRow;
use piezocontact::run::ContactRun;
use piezocontact::run::{PathRun, Run, StepFiles};
use std::path::Path;
use std::sync::Arc;

/// The exact solver with the KKT tolerance 1e−10.
fn newton() -> Settings {
    let parameters = newton::Parameters {
        r: 0.25 * 58.7102,
        tol: 1e-10,
        max_inner: 100,
        max_condensed: Some(2000),
        guess: Guess::Nearest(2000),
    };
    Settings::new(Newton::new(parameters), 20)
}

/// A plate capacitor: the unit square without piezoelectric coupling, ϕ = 0 on its bottom
/// and V on its top. The field is uniform, D = −β33 V/h along y, and the electrodes hold
/// ±β33 V L/h (per unit depth): the top, at the higher potential, the positive charge.
#[test]
fn the_electrodes_of_a_capacitor_hold_its_charge() {
    let mesh = perturbed_square(6, 0.2);
    let part = |n: &str| mesh.part_index(n).unwrap();
    let volts = 2.0;
    let boundary = Boundary {
        clamped: vec![part("left")],
        grounded: vec![part("bottom"), part("top")],
        grounded_value: Some(Arc::new(move |x: &[f64]| volts * x[1])),
        contact: vec![part("right")],
        ..Boundary::default()
    };
    let beta33 = 830.0 * EPS0;
    let elasticity = Elasticity::from_young_poisson(58.7102, 0.3912, ElasticLaw::Linear).unwrap();
    let material = Material::new(
        2,
        elasticity,
        PiezoConstants { e31: 0.0, e33: 0.0, e15: 0.0 },
        PermittivityConstants { beta11: 916.0 * EPS0, beta33 },
    )
    .unwrap();
    let problem = Problem::new(mesh, material, boundary, BodyLoads::default()).unwrap();
    let mut model = paper_model(None, 0.0, PAPER_UNITS);
    model.compliance.gap = 10.0; // the foundation is far: no contact
    let solution = solve_contact(&problem, &model, &newton()).unwrap();
    assert!(solution.converged(), "{:?}", solution.failure);
    let charges = &solution.balance.charges;
    let expected = beta33 * volts;
    println!("charges {charges:?}, expected ±{expected}");
    assert!((charges[1] - expected).abs() < 1e-10 * expected, "top: {charges:?}");
    assert!((charges[0] + expected).abs() < 1e-10 * expected, "bottom: {charges:?}");
}

/// A PZT-5A half-space (the block of meshes/indent-halfspace.geo, clamped and grounded at
/// its bottom, Γ3 the patch |x|, |y| ≤ 0.2 of its top face), frictionless, without its
/// piezoelectric coupling unless `coupled`, pressed by the indenter of `foundation` (TOML
/// lines) along −z to `depths`.
fn indentation_case(mesh: &str, foundation: &str, depths: &[f64], coupled: bool) -> Case {
    let coupling = if coupled {
        "e31 = -5.4\ne33 = 15.8\ne15 = 12.3"
    } else {
        "e31 = 0.0\ne33 = 0.0\ne15 = 0.0"
    };
    let material = format!(
        "law = \"linear\"\nyoung = 58.7102\npoisson = 0.3912\n{coupling}\neps0 = 8.885e-3\nbeta11_rel = 916.0\nbeta33_rel = 830.0"
    );
    indentation_of(mesh, foundation, depths, &material)
}

/// [`indentation_case`] with the `[material]` table's body `material`.
fn indentation_of(mesh: &str, foundation: &str, depths: &[f64], material: &str) -> Case {
    let depths: Vec<String> = depths.iter().map(|d| format!("{d:e}")).collect();
    let text = format!(
        r#"
[mesh]
file = "{}"
[material]
{material}
[boundary]
clamped = ["bottom"]
grounded = ["bottom"]
contact = ["contact"]
[contact]
problem = "PV1"
[foundation]
{foundation}
[loading]
direction = [0.0, 0.0, -1.0]
depths = [{}]
[solver]
method = "newton"
max_condensed = 3000
"#,
        mesh_file(mesh).display(),
        depths.join(", ")
    );
    Case::from_text(Path::new("indentation.toml"), &text, &[]).unwrap()
}

/// The path's steps: (depth, force on the indenter along +z), every step converged.
fn force_depth(case: &Case) -> Vec<(f64, f64)> {
    let path = path_run(&case.build().unwrap());
    assert!(path.converged(), "{:?}", path.failure);
    path.curve.iter().map(|r| (r.depth, r.force[2])).collect()
}

/// The least-squares slope of log P against log δ.
fn log_slope(points: &[(f64, f64)]) -> f64 {
    let logs: Vec<(f64, f64)> = points.iter().map(|(d, p)| (d.ln(), p.ln())).collect();
    let n = logs.len() as f64;
    let (mx, my) =
        (logs.iter().map(|p| p.0).sum::<f64>() / n, logs.iter().map(|p| p.1).sum::<f64>() / n);
    let sxy: f64 = logs.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = logs.iter().map(|(x, _)| (x - mx).powi(2)).sum();
    sxy / sxx
}

/// A ball, a cone and a flat punch pressed into the half-space follow P ∝ δ^{3/2}, δ², δ
/// (log–log slopes within 3 % on both meshes; measured within 1 %) and the prefactors of
/// Hertz, Sneddon and Boussinesq within the discretisation error, measured here: P1
/// tetrahedra are too stiff, by 11 % on the coarse mesh and 6.7 % on the fine one for the ball
/// and the cone (asserted: below 8 % on the fine mesh and falling); the punch, whose contact
/// disc is a polygon of the mesh's nodes with a singular edge, by 6–7 % on both (asserted:
/// below 8 %). Contact radii a = 0.03–0.06 against a block of half-width 4.
#[test]
fn ball_cone_and_punch_follow_the_classical_laws() {
    let e_star = oracles::plane_strain_modulus(58.7102, 0.3912);
    let alpha = 70f64.to_radians();
    type Law = Box<dyn Fn(f64) -> f64>;
    let cases: [(&str, &str, Vec<f64>, f64, Law); 3] = [
        (
            "ball",
            "kind = \"sphere\"\ncenter = [0.0, 0.0, 1.0]\nradius = 1.0",
            vec![0.001, 0.0016, 0.0025, 0.0036],
            1.5,
            Box::new(move |d| oracles::hertz(e_star, 1.0, d).force),
        ),
        (
            "cone",
            "kind = \"cone\"\napex = [0.0, 0.0, 0.0]\naxis = [0.0, 0.0, 1.0]\nhalf_angle = 70.0",
            vec![0.018, 0.024, 0.03, 0.036],
            2.0,
            Box::new(move |d| oracles::sneddon(e_star, alpha, d).force),
        ),
        (
            "punch",
            "kind = \"punch\"\ncenter = [0.0, 0.0, 0.0]\naxis = [0.0, 0.0, 1.0]\nradius = 0.05",
            vec![0.0001, 0.0002, 0.0003, 0.0004],
            1.0,
            Box::new(move |d| oracles::boussinesq(e_star, 0.05, d).force),
        ),
    ];
    for (name, foundation, depths, power, law) in cases {
        let mut errors = Vec::new();
        for mesh in ["indent-halfspace-coarse.msh", "indent-halfspace-fine.msh"] {
            let points = force_depth(&indentation_case(mesh, foundation, &depths, false));
            let slope = log_slope(&points);
            let error =
                points.iter().map(|(d, p)| p / law(*d) - 1.0).sum::<f64>() / points.len() as f64;
            println!(
                "{name} on {mesh}: slope {slope:.4} (law {power}), force / law − 1 = {error:+.4}"
            );
            assert!((slope / power - 1.0).abs() < 0.03, "{name} on {mesh}: slope {slope}");
            errors.push(error);
        }
        assert!(errors[1].abs() < 0.08, "{name}: the force is {errors:?} off the law");
        if name != "punch" {
            assert!(errors[1].abs() < errors[0].abs(), "{name}: {errors:?} does not fall");
        }
    }
}

/// cases/indentation-curve.toml (PV2 with friction, the piezoelectric coupling on, two
/// electrodes) with `overrides`.
fn curve_case(overrides: &[&str]) -> Case {
    committed_case("indentation-curve.toml", overrides)
}

/// The case solved once, cold, with the ball `depth` below its [foundation] position.
fn cold(depth: f64) -> ContactRun {
    let center = format!("foundation.center=[0.0, 0.0, {}]", 1.0 - depth);
    let case = curve_case(&[&center]);
    let run = contact_run(&Built { loading: None, ..case.build().unwrap() });
    assert!(run.solution.converged(), "{:?}", run.solution.failure);
    run
}

/// A command that solves one position per case (sweep, bench --contact) refuses a case with
/// a loading path, naming [loading] and its line: it would solve the ball where [foundation]
/// puts it (just touching: no contact at all). A run follows the path; without the path,
/// the same case is one contact run.
#[test]
fn one_position_refuses_a_loading_path() {
    let case = curve_case(&["loading.depths=[0.01]"]);
    let refused = case.one_position().err().map(|e| e.to_string()).unwrap_or_default();
    assert!(refused.contains("indentation-curve.toml:") && refused.contains("[loading] path"));
    let built = case.build().unwrap();
    assert!(matches!(Run::solve(&built, default_solver(), &|_| {}), Ok(Run::Path(_))));
    let built = Built { loading: None, ..built };
    assert!(matches!(Run::solve(&built, default_solver(), &|_| {}), Ok(Run::Contact(_))));
}

/// The largest difference of two solutions relative to the largest |x|.
fn difference(a: &[f64], b: &[f64]) -> f64 {
    let size = b.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    a.iter().zip(b).fold(0.0_f64, |m, (p, q)| m.max((p - q).abs())) / size
}

/// Each step of a path, started from the last with the factorisation kept, is the solve of
/// its own problem from scratch: the same x to 1e−9 (measured ~1e−13), the same curve row.
/// A path whose contact zone shrinks (the ball withdrawn) factorises once: the law is linear
/// and the condensation of its first step holds every later zone (a zone that grows takes
/// solves or a factorisation, whichever the last timings say is cheaper). A path of one step
/// is `run` on the moved foundation.
#[test]
fn the_steps_of_a_path_are_the_solves_of_their_problems() {
    let depths = [0.015, 0.01, 0.005];
    let built = curve_case(&["loading.depths=[0.015, 0.01, 0.005]"]).build().unwrap();
    let path = path_run(&built);
    assert!(path.converged() && path.curve.len() == 3, "{:?}", path.failure);
    let last = &path.last.solution;
    println!(
        "path: {} factorisations, Newton steps {:?}",
        last.timings.solver.numeric_count,
        path.curve.iter().map(|r| r.newton_steps).collect::<Vec<_>>()
    );
    assert_eq!(last.timings.solver.numeric_count, 1);
    for (k, depth) in depths.iter().enumerate() {
        let run = cold(*depth);
        let step = &built.loading.as_ref().unwrap().steps[k];
        let row = CurveRow::new(k + 1, step, &run.solution, &run.rows);
        let d = (row.force[2] - path.curve[k].force[2]).abs() / row.force[2];
        println!(
            "step {}: force {:.6e} (cold {:.6e}), relative difference {d:.1e}",
            k + 1,
            path.curve[k].force[2],
            row.force[2]
        );
        assert!(d < 1e-9, "step {}: {d}", k + 1);
    }
    let d = difference(&last.x, &cold(0.005).solution.x);
    assert!(d < 1e-9, "the last step differs from its cold solve by {d}");
    let one = curve_case(&["loading.depths=[0.01]"]);
    let single = path_run(&one.build().unwrap());
    let d = difference(&single.last.solution.x, &cold(0.01).solution.x);
    assert!(d < 1e-12, "a path of one step differs from run by {d}");
}

/// A path that withdraws the ball to where it just touches ends in the unloaded state x = 0,
/// which the exact solver takes in one step — with a conductive ball and a penetration, whose
/// laws have their kinks at 0, as without them. Before, its iterates tended to 0 (by a
/// factor of ~0.07 a step with the conduction) while its step, relative to them, stayed
/// O(1): the last step hit the cap of 100 Newton steps.
#[test]
fn a_path_back_to_the_unloaded_state_ends_at_zero() {
    for extra in [&[][..], &["conductivity.ke=0.5", "contact.penetration=0.01"][..]] {
        let case = curve_case(&[&["loading.depths=[0.002, 0.0]"], extra].concat());
        let path = path_run(&case.build().unwrap());
        assert!(path.converged(), "{extra:?}: {:?}", path.failure);
        let last = &path.last.solution;
        assert_eq!(path.curve[1].newton_steps, 1, "{extra:?}");
        assert!(last.x.iter().all(|v| *v == 0.0), "{extra:?}: x is not 0");
        assert!(path.curve[0].force[2] > 0.0 && path.curve[1].force[2] == 0.0, "{extra:?}");
    }
}

/// A path with Hencky's law active refactorises at every outer step; a condensation grown by
/// solves at the second depth is ordered last before the next factorisation, so that its
/// Schur complement is read off the factor: each factorisation serves the step's two solves
/// and a growth solves each new unknown once — not once per factorisation, as when the
/// ordering kept the first depth's set last.
#[test]
fn a_condensation_grown_by_solves_is_ordered_last_before_the_next_factorisation() {
    let case =
        curve_case(&["material.law=\"hencky\"", "material.t0=1e-4", "loading.depths=[0.01, 0.02]"]);
    let path = path_run(&case.build().unwrap());
    assert!(path.converged(), "{:?}", path.failure);
    let last = &path.last.solution;
    let t = &last.timings;
    let unknowns = 3 * last.condensed_nodes;
    println!(
        "{} factorisations, {} solves, {unknowns} condensed",
        t.solver.numeric_count, t.solver.solve_count
    );
    assert!(t.solver.numeric_count > 4, "Hencky's law is not active: {t:?}");
    assert!(t.solver.solve_count <= 2 * t.solver.numeric_count + unknowns, "{t:?}");
}

/// No charge enters the block but through its electrodes (the ball does not conduct, no
/// charge is applied): the charges of the two grounded electrodes cancel at every step, and
/// pressing deeper draws more.
#[test]
fn the_electrodes_charges_cancel_and_grow_with_the_depth() {
    let case = curve_case(&["loading.depths=[0.005, 0.01, 0.015]"]);
    let path = path_run(&case.build().unwrap());
    let mut previous = 0.0;
    for r in &path.curve {
        let (bottom, top) = (r.charges[0], r.charges[1]);
        println!("step {}: charges {bottom:.4e} (bottom), {top:.4e} (top)", r.step);
        assert!((bottom + top).abs() < 1e-10 * top.abs(), "{:?}", r.charges);
        assert!(top.abs() > previous, "{:?}", r.charges);
        previous = top.abs();
    }
}

/// A ball pressed into the piezoelectric half-space under an insulating ball: the force is
/// the uncoupled one times C*_piezo / C*_elastic (on the same mesh most of the
/// discretisation error cancels: measured 2.0–2.3 % off on the coarse mesh, 1.2–1.3 % on the
/// fine one, asserted within 2 % there), and the potential at the contact centre approaches
/// the analytic ϕ/δ ratio times δ under refinement (10.7 % → 5.2 %, asserted falling and
/// below 6 %).
#[test]
fn a_ball_on_a_piezoelectric_half_space_follows_its_indentation_modulus() {
    let ball = "kind = \"sphere\"\ncenter = [0.0, 0.0, 1.0]\nradius = 1.0";
    let depths = [0.0016, 0.0036];
    let case = indentation_case("indent-halfspace-fine.msh", ball, &depths, true);
    let material = case.build().unwrap().problem.material(0).clone();
    let piezo = oracles::Piezoelectric::of(&material).indentation().unwrap();
    let e_star = oracles::plane_strain_modulus(58.7102, 0.3912);
    let (mut phi_errors, mut ratios) = (Vec::new(), Vec::new());
    for mesh in ["indent-halfspace-coarse.msh", "indent-halfspace-fine.msh"] {
        let coupled = indentation_case(mesh, ball, &depths, true);
        let path = path_run(&coupled.build().unwrap());
        assert!(path.converged(), "{:?}", path.failure);
        let uncoupled = force_depth(&indentation_case(mesh, ball, &depths, false));
        for (k, row) in path.curve.iter().enumerate() {
            let ratio = row.force[2] / uncoupled[k].1;
            let expected = piezo.insulating / e_star;
            let phi = piezo.potential_ratio * row.depth;
            println!(
                "{mesh} δ = {}: force ratio {ratio:.4} (C* ratio {expected:.4}), ϕ at the centre {:.4e} (analytic {phi:.4e})",
                row.depth, row.phi_center
            );
            ratios.push(ratio / expected - 1.0);
            if k + 1 == depths.len() {
                phi_errors.push((row.phi_center / phi - 1.0).abs());
            }
        }
    }
    println!("ϕ at the centre against the analytic ratio × δ: relative errors {phi_errors:?}");
    println!("force ratios against the C* ratio, relative: {ratios:?}");
    assert!(ratios[2..].iter().all(|r| r.abs() < 0.02), "{ratios:?}");
    assert!(phi_errors[1] < phi_errors[0] && phi_errors[1] < 0.06, "{phi_errors:?}");
}

/// Berlincourt's PZT-5A by its full tensors, c^E [GPa] and e [C/m²] in Voigt order (the
/// coupling left out for a dielectric), with ε^S.
fn pzt_5a_tensors(coupled: bool) -> String {
    let c = "c = [[120.3, 75.2, 75.1, 0, 0, 0], [75.2, 120.3, 75.1, 0, 0, 0], [75.1, 75.1, 110.9, 0, 0, 0], [0, 0, 0, 21.1, 0, 0], [0, 0, 0, 0, 21.1, 0], [0, 0, 0, 0, 0, 22.55]]";
    let e = "e = [[0, 0, 0, 0, 12.3, 0], [0, 0, 0, 12.3, 0, 0], [-5.4, -5.4, 15.8, 0, 0, 0]]";
    let e = if coupled { e } else { "" };
    format!("{c}\n{e}\neps0 = {EPS0}\neps_rel = [916.0, 916.0, 830.0]")
}

/// A ball pressed into the half-space of the full PZT-5A tensor: Hertz's force with the
/// indentation modulus C* that the oracle computes from the same tensor, P = (4/3) C* √R δ^{3/2}.
/// P1 tetrahedra are too stiff (the isotropic test above: 11 % and 6.7 %); measured here
/// against C* = 95.48 GPa at δ = 0.0036: 13.3 % on the coarse mesh, 8.2 % on the fine one (an
/// order of about 0.7 in the element size at the centre, which halves; asserted: falling, and
/// below 9 % on the fine mesh). The coupled force over the uncoupled one (the same c^E without
/// e, on the same mesh, whose discretisation error mostly cancels) against C*_piezo /
/// C*_elastic: 2.2 % and 1.3 % off (asserted within 2 % on the fine mesh).
#[test]
fn a_ball_on_the_full_pzt_5a_tensor_follows_hertz_with_its_indentation_modulus() {
    let ball = "kind = \"sphere\"\ncenter = [0.0, 0.0, 1.0]\nradius = 1.0";
    let depths = [0.0016, 0.0036];
    let case = indentation_of("indent-halfspace-fine.msh", ball, &depths, &pzt_5a_tensors(true));
    let constants = oracles::Piezoelectric::of(case.build().unwrap().problem.material(0));
    let piezo = constants.indentation().unwrap();
    let elastic = oracles::Piezoelectric { e31: 0.0, e33: 0.0, e15: 0.0, ..constants };
    let elastic = elastic.indentation().unwrap();
    let (mut errors, mut ratios) = (Vec::new(), Vec::new());
    for mesh in ["indent-halfspace-coarse.msh", "indent-halfspace-fine.msh"] {
        let coupled = force_depth(&indentation_of(mesh, ball, &depths, &pzt_5a_tensors(true)));
        let uncoupled = force_depth(&indentation_of(mesh, ball, &depths, &pzt_5a_tensors(false)));
        let (depth, force) = coupled[1];
        let hertz = 4.0 / 3.0 * piezo.insulating * depth.powf(1.5);
        errors.push(force / hertz - 1.0);
        ratios.push(force / uncoupled[1].1 / (piezo.insulating / elastic.insulating) - 1.0);
        println!(
            "{mesh}: P = {force:.5e} against Hertz with C* = {:.4} GPa: {hertz:.5e}; ratio to the uncoupled force off by {:.4}",
            piezo.insulating,
            ratios.last().unwrap()
        );
    }
    println!(
        "relative errors against Hertz with C*: {errors:?}; force ratios against C* ratios: {ratios:?}"
    );
    assert!(errors[1] > 0.0 && errors[1] < errors[0] && errors[1] < 0.09, "{errors:?}");
    assert!(ratios[1].abs() < 0.02, "{ratios:?}");
}

/// The radial friction traction σ_τ·r̂ at the Γ3 nodes in contact at step k whose distance
/// to the axis lies in [0.4 a, a], a the contact radius of the step.
fn radial_tractions(path: &PathRun, k: usize) -> Vec<(usize, f64)> {
    let a = path.curve[k].contact_radius;
    path.rows(k)
        .iter()
        .enumerate()
        .filter(|(_, r)| r.sigma_nu < 0.0)
        .filter_map(|(i, r)| {
            let radius = r.x[0].hypot(r.x[1]);
            let radial =
                (r.friction_traction[0] * r.x[0] + r.friction_traction[1] * r.x[1]) / radius;
            (radius >= 0.4 * a && radius <= a).then_some((i, radial))
        })
        .collect()
}

/// Pressed to 0.02 and back with incremental friction (µ = 0.1: at 0.3 the block sticks
/// almost everywhere), the ball meets on the way back, at the same depths, a contact whose
/// outer part slips the other way: the radial friction traction changes sign at most nodes
/// there (measured: 10 of 11 at δ = 0.01, 6 of 6 at 0.005) — hysteresis. With the paper's
/// static law the way back retraces the way in (no sign changes). The first step of a path
/// from rest is the static law's.
#[test]
fn incremental_friction_makes_loading_and_unloading_differ() {
    let depths = "loading.depths=[0.005, 0.01, 0.015, 0.02, 0.015, 0.01, 0.005]";
    let run = |law: &str| {
        let case = curve_case(&[depths, &format!("friction.path={law:?}"), "friction.mu=0.1"]);
        let path = path_run(&case.build().unwrap());
        assert!(path.converged(), "{law}: {:?}", path.failure);
        path
    };
    let (incremental, fixed) = (run("incremental"), run("static"));
    let first = difference(incremental.states().next().unwrap(), fixed.states().next().unwrap());
    assert!(first < 1e-12, "the first step differs from the static law's by {first}");
    for (loading, unloading) in [(1, 5), (0, 6)] {
        let count = |path: &PathRun| {
            let (a, b) = (radial_tractions(path, loading), radial_tractions(path, unloading));
            let both: Vec<(f64, f64)> = a
                .iter()
                .filter_map(|(i, ta)| b.iter().find(|(j, _)| j == i).map(|(_, tb)| (*ta, *tb)))
                .collect();
            let flipped = both.iter().filter(|(ta, tb)| ta * tb < 0.0).count();
            (flipped, both.len())
        };
        let ((flipped, of), (fixed_flipped, fixed_of)) = (count(&incremental), count(&fixed));
        println!(
            "depth {}: incremental {flipped} of {of} nodes flip their radial traction, static {fixed_flipped} of {fixed_of}",
            incremental.curve[loading].depth
        );
        assert!(of >= 4 && 2 * flipped > of, "incremental: {flipped} of {of}");
        assert_eq!(fixed_flipped, 0, "static: {fixed_flipped} of {fixed_of}");
    }
}

/// The ball as a triangulated surface (meshes/ball-tip.stl, found by ray casting) presses
/// the half-space as the analytic ball does: the forces agree within 0.5 % (measured 0.34 %
/// and 0.32 %: the triangles' sagitta near the contact, ~2e−6, against depths of 1e−3).
#[test]
fn a_ball_from_an_stl_file_presses_like_the_analytic_ball() {
    let file = mesh_file("ball-tip.stl");
    let surface = format!("kind = \"surface\"\nfile = {:?}", file.display().to_string());
    let ball = "kind = \"sphere\"\ncenter = [0.0, 0.0, 1.0]\nradius = 1.0";
    let depths = [0.001, 0.0025];
    let mesh = "indent-halfspace-coarse.msh";
    let ours = force_depth(&indentation_case(mesh, &surface, &depths, false));
    let exact = force_depth(&indentation_case(mesh, ball, &depths, false));
    for (a, b) in ours.iter().zip(&exact) {
        println!("δ = {}: force {:.6e} (analytic ball {:.6e})", a.0, a.1, b.1);
        assert!((a.1 / b.1 - 1.0).abs() < 5e-3, "{a:?} against {b:?}");
    }
}

/// A surface that no Γ3 normal meets is refused when the case is built, naming the file.
#[test]
fn a_surface_out_of_reach_is_refused() {
    let overrides = ["foundation.kind=\"surface\"", "foundation.file=\"../meshes/ball-tip.stl\""];
    let e = committed_case("block-3d.toml", &overrides).build().err().unwrap().to_string();
    assert!(
        e.contains("foundation.file")
            && e.contains("ball-tip.stl")
            && e.contains("no normal of the 1370 Γ3 nodes meets the foundation"),
        "{e}"
    );
}

/// A punch whose axis points toward the body, and a ball beside the patch, are refused when
/// the case is built, with the key to check; the same ball on a path that carries it over
/// the patch is not; a path that carries the ball through the contact face is.
#[test]
fn a_foundation_no_normal_meets_is_refused() {
    let build = |overrides: &[&str]| curve_case(overrides).build().err().map(|e| e.to_string());
    let punch = [
        "foundation.kind=\"punch\"",
        "foundation.center=[0.0, 0.0, 0.01]",
        "foundation.radius=0.2",
        "loading.direction=[0.0, 0.0, 1.0]",
    ];
    let e = build(&[&punch[..], &["foundation.axis=[0.0, 0.0, -1.0]"]].concat()).unwrap();
    assert!(
        e.contains("no normal of the")
            && e.contains("at any step")
            && e.contains("foundation.axis"),
        "{e}"
    );
    assert_eq!(build(&[&punch[..], &["foundation.axis=[0.0, 0.0, 1.0]"]].concat()), None);
    let beside = ["foundation.center=[3.0, 0.0, 0.98]", "loading.direction=[-1.0, 0.0, 0.0]"];
    let e = build(&[&beside[..], &["loading.depths=[0.0, 1.0]"]].concat()).unwrap();
    assert!(e.contains("no normal of the") && e.contains("foundation.center"), "{e}");
    assert_eq!(build(&[&beside[..], &["loading.depths=[0.0, 3.0]"]].concat()), None);
    // A ball pressed through the contact face (depths of millimetres in metres, say): at 2.5
    // its centre is 1.5 below the face, out of every normal's reach but behind the face, and
    // the step ended without contact; at 1.5 the face is inside the ball, its gaps negative.
    let e = build(&["loading.depths=[0.002, 2.5]"]).unwrap();
    assert!(e.contains("at step 2 (depth 2.5 m) the foundation has passed through Γ3"), "{e}");
    assert!(e.contains("loading.depths"), "{e}");
    assert_eq!(build(&["loading.depths=[0.002, 1.5]"]), None);
    // Every step through the face: still the depths, not the ball's place, are at fault.
    let e = build(&["loading.depths=[2.5]"]).unwrap();
    assert!(e.contains("at step 1 (depth 2.5 m) the foundation has passed through Γ3"), "{e}");
}

/// A path of load factors (the paper's bar, its load halved then whole) gives at each step the
/// single run of the scaled loads: f̌ is assembled again only when the factor changes.
#[test]
fn a_path_of_load_factors_scales_the_loads() {
    let sets = ["mesh.nx=24", "mesh.ny=4", "solver.method=\"newton\""];
    let bar = |extra: &[&str]| committed_case("paper-7.1.toml", &[&sets, extra].concat());
    let case = bar(&["loading.load_factors=[0.5, 0.5, 1.0]"]);
    let path = path_run(&case.build().unwrap());
    assert!(path.converged() && path.curve.len() == 3, "{:?}", path.failure);
    let single = bar(&[]);
    let built = single.build().unwrap();
    let (problem, model) = (&built.problem, built.model.as_ref().unwrap());
    for (k, factor) in [0.5, 0.5, 1.0].into_iter().enumerate() {
        let mut solver =
            ContactSolver::new(problem, model, &built.settings, default_solver()).unwrap();
        let solution = solver.solve(problem, model, factor, &|_| {}).unwrap();
        let (ours, theirs) = (path.curve[k].force[1], -solution.balance.contact[1]);
        println!("step {}: factor {factor}, force {ours:.6e} (single run {theirs:.6e})", k + 1);
        assert!(
            (ours - theirs).abs() <= 1e-9 * theirs.abs(),
            "step {}: {ours} against {theirs}",
            k + 1
        );
    }
    assert!((path.curve[2].force[1] / path.curve[0].force[1] - 1.0).abs() > 0.1);
}

/// A path that writes each step's solution-NNNN.vtu while the next step solves (as the
/// command line does) writes the bytes that a path writing them at the end writes; its run's
/// files, written into the same directory, keep them (not written again), and summary.json
/// reports the writer's time apart (`files_meanwhile`), outside the sum that makes `total`.
#[test]
fn the_steps_written_during_a_path_are_those_written_after_it() {
    let built = curve_case(&["loading.depths=[0.004, 0.008, 0.012]"]).build().unwrap();
    let root = std::env::temp_dir().join(format!("piezocontact-steps-{}", std::process::id()));
    let (during, after) = (root.join("during"), root.join("after"));
    std::fs::create_dir_all(&during).unwrap();
    let files = StepFiles { dir: &during, vtu: Default::default() };
    let run = Run::solve_writing(&built, (default_solver(), &|_| {}), Some(files)).unwrap();
    let names: Vec<String> = (1..=3).map(|k| format!("solution-{k:04}.vtu")).collect();
    let read = |dir: &Path| -> Vec<Vec<u8>> {
        names.iter().map(|n| std::fs::read(dir.join(n)).unwrap()).collect()
    };
    let modified = |dir: &Path| -> Vec<std::time::SystemTime> {
        names.iter().map(|n| std::fs::metadata(dir.join(n)).unwrap().modified().unwrap()).collect()
    };
    let (written, times) = (read(&during), modified(&during));
    let summary = run.write(&built, &during, Default::default()).unwrap();
    assert_eq!(modified(&during), times);
    let at_the_end = Run::solve(&built, default_solver(), &|_| {}).unwrap();
    at_the_end.write(&built, &after, Default::default()).unwrap();
    assert!(read(&after) == written, "the steps' files differ");
    let t = &summary["timings_seconds"];
    assert!(t["files_meanwhile"]["solution-NNNN.vtu"].as_f64().unwrap() > 0.0, "{t}");
    assert!(t["files"].get("solution-NNNN.vtu").is_none(), "{t}");
    assert!(t["files"]["solution.pvd"].as_f64().is_some(), "{t}");
    std::fs::remove_dir_all(&root).unwrap();
}

/// A path that writes its steps while it solves with every thread of the run's pool taken
/// (as `--threads 1`, or each process under mpirun on as many processes as cores, where the
/// run is the pool's one thread): the writer's parallel loops do not wait for a thread that
/// waits for the writer (they did: the run hung at its last step).
#[test]
fn a_path_writing_its_steps_runs_on_a_pool_with_no_thread_free() {
    let dir = std::env::temp_dir().join(format!("piezocontact-no-thread-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (done, finished) = std::sync::mpsc::channel();
    let steps = dir.clone();
    // A thread of its own, so that a hang fails the test instead of holding it.
    std::thread::spawn(move || {
        let built = curve_case(&["loading.depths=[0.004, 0.008]"]).build().unwrap();
        let solved = std::sync::atomic::AtomicBool::new(false);
        rayon::scope(|scope| {
            // Every other thread of the pool held until the path is solved.
            for _ in 1..rayon::current_num_threads() {
                scope.spawn(|_| {
                    while !solved.load(std::sync::atomic::Ordering::Acquire) {
                        std::thread::sleep(std::time::Duration::from_millis(1));
                    }
                });
            }
            let files = StepFiles { dir: &steps, vtu: Default::default() };
            let run = Run::solve_writing(&built, (default_solver(), &|_| {}), Some(files));
            solved.store(true, std::sync::atomic::Ordering::Release);
            let _ = done.send(run.is_ok());
        });
    });
    let ok = finished.recv_timeout(std::time::Duration::from_secs(120));
    assert_eq!(ok, Ok(true), "the path did not finish in 120 s");
    assert!(dir.join("solution-0002.vtu").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
