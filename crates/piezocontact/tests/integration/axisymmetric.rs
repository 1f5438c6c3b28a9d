//! Axisymmetric bodies (`mesh.plane = "axisymmetric"`): the meridian section x = r ≥ 0 of a
//! body of revolution about y, the hoop strain u_r / r in the law and 2πr in every integral.
//! Uniform states of a cylinder, which P1 reproduces to round-off, with the expected values
//! computed here from the 3D law; the totals over the revolution; bad input.

use super::common::{assert_displacements, build_text, solve_static};
use super::materials::{C, E, stress_charge};
use std::f64::consts::PI;

/// The cylinder r ≤ 1, 0 ≤ y ≤ 2 in `nx` × `ny` cells, on a roller along y at the bottom,
/// its bottom and top grounded, with the material `material` and the loads `loads`.
fn cylinder(material: &str, loads: &str) -> String {
    format!(
        r#"
[mesh]
x = [0.0, 1.0]
y = [0.0, 2.0]
nx = 3
ny = 5
plane = "axisymmetric"
[mesh.segments]
outer = ["{{1}}x[0,2]"]
bottom = ["[0,1]x{{0}}"]
top = ["[0,1]x{{2}}"]
[material]
{material}
[boundary]
grounded = ["bottom", "top"]
[[boundary.support]]
parts = ["bottom"]
fix = ["y"]
{loads}
"#
    )
}

/// A PZT-5A cylinder poled along its axis, short-circuited between its end faces (E = 0),
/// pressed by p on its top: σ_yy = −p, σ_rr = σ_θθ = 0, so with ε_rr = ε_θθ = a, ε_yy = b,
/// (c11 + c12) a + c13 b = 0 and 2 c13 a + c33 b = −p; D_y = 2 e31 a + e33 b. The bottom
/// roller carries p π R² (the whole disc: the revolution's total), the electrodes ±D_y π R².
#[test]
fn a_cylinder_poled_along_its_axis_under_axial_stress_takes_the_uniform_state() {
    let p = 0.5;
    let top = format!("[[boundary.traction]]\nparts = [\"top\"]\nf2 = [0.0, {}]\n", -p);
    let (built, run) = solve_static(&cylinder(&stress_charge(), &top));
    let (c11, c12, c13, c33) = (C[0][0], C[0][1], C[0][2], C[2][2]);
    let b = -p / (c33 - 2.0 * c13 * c13 / (c11 + c12));
    let a = -c13 * b / (c11 + c12);
    let scale = a.abs().max(b.abs()) * 2.0;
    assert_displacements(&built, &run, |q| vec![a * q[0], b * q[1]], 1e-10 * scale);
    let force = p * PI;
    let bottom = &run.reactions.supports[0];
    assert!((bottom[1] - force).abs() < 1e-9 * force, "{bottom:?} vs {force}");
    assert_eq!(bottom[0], 0.0, "no radial resultant");
    let q = (2.0 * E[2][0] * a + E[2][2] * b) * PI;
    let charges = &run.reactions.charges;
    assert!((charges[0] - q).abs() < 1e-9 * q.abs(), "bottom: {} vs {q}", charges[0]);
    assert!((charges[1] + q).abs() < 1e-9 * q.abs(), "top: {} vs {}", charges[1], -q);
    let summary = piezocontact::report::summary::common_summary(&built, &run.solution.dofs);
    assert_eq!(summary["model"], "axisymmetric");
    assert!(summary.get("per_unit_thickness").is_none());
}

/// An isotropic cylinder under a uniform pressure p on its side and top, with Hencky's law:
/// σ = −p I, ε = −p/(3 k0) I (ε^D = 0, so the secant modulus plays no part): u = ε (r, y),
/// whose hoop strain u_r / r = ε is the radial one — the path through the hoop term.
#[test]
fn an_isotropic_cylinder_under_uniform_pressure_shrinks_uniformly() {
    let (young, poisson, p): (f64, f64, f64) = (60.0, 0.3, 0.4);
    let material = format!(
        "law = \"hencky\"\nyoung = {young}\npoisson = {poisson}\ne31 = 0.0\ne33 = 0.0\ne15 = 0.0\neps0 = 1.0\nbeta11_rel = 1.0\nbeta33_rel = 1.0"
    );
    let loads = format!(
        "[[boundary.traction]]\nparts = [\"top\"]\nf2 = [0.0, {m}]\n[[boundary.traction]]\nparts = [\"outer\"]\nf2 = [{m}, 0.0]\n",
        m = -p
    );
    let (built, run) = solve_static(&cylinder(&material, &loads));
    let k0 = young / (3.0 - 6.0 * poisson);
    let strain = -p / (3.0 * k0);
    assert_displacements(
        &built,
        &run,
        |q| vec![strain * q[0], strain * q[1]],
        1e-10 * strain.abs(),
    );
    let force = p * PI;
    assert!((run.reactions.supports[0][1] - force).abs() < 1e-9 * force);
}

/// Bad input: a poling across the axis, a law a turn about the axis changes, a node at
/// r < 0, and a foundation off the axis.
#[test]
fn bad_axisymmetric_cases_are_errors_naming_the_key() {
    let error = |text: &str| build_text(text).err().expect("an error").to_string();
    let across = format!("{}poling = [1.0, 0.0]\n", stress_charge());
    let e = error(&cylinder(&across, ""));
    assert!(e.contains("poling") && e.contains("along the axis"), "{e}");
    let e = error(&cylinder("preset = \"LiNbO3\"\npoling = [0.0, 1.0]\n", ""));
    assert!(e.contains("transversely isotropic about the axis"), "{e}");
    let e = error(
        &cylinder(&stress_charge(), "")
            .replace("x = [0.0, 1.0]", "x = [-1.0, 1.0]")
            .replace("[0,1]x{0}", "[-1,1]x{0}")
            .replace("[0,1]x{2}", "[-1,1]x{2}"),
    );
    assert!(e.contains("r < 0"), "{e}");
    let off = "[contact]\ngap = 0.0\n[foundation]\nkind = \"sphere\"\ncenter = [0.5, 2.9]\nradius = 1.0\n";
    let contact = cylinder(&stress_charge(), off).replace(
        "grounded = [\"bottom\", \"top\"]",
        "grounded = [\"bottom\"]\ncontact = [\"top\"]",
    );
    let e = error(&contact);
    assert!(e.contains("a sphere must be centred on the axis"), "{e}");
}

/// A rigid ball of radius R = 1 pressed d = 0.01 into an isotropic cylinder of radius and
/// height 20 (nearly a half-space: meshes/indent-axisym.geo), frictionless, the exact solver:
/// the force against the exact sphere's (Segedin: d = (a/2) ln((R+a)/(R−a)),
/// P = (E*/2)[(R² + a²) ln((R+a)/(R−a)) − 2Ra], within 0.1 % of Hertz's here). Measured: 1.44 %
/// at h = 0.02 at the centre, 0.70 % at h = 0.01 (order 1.0 in h; what remains at the limit,
/// about 0.3 %, is the finite body's); the test holds the fine error below 0.8 % and the
/// order above 0.8.
#[test]
fn the_axisymmetric_ball_converges_to_the_exact_sphere_s_force() {
    let (young, poisson, radius, depth): (f64, f64, f64, f64) = (1.0, 0.3, 1.0, 0.01);
    let e_star = young / (1.0 - poisson * poisson);
    let half_depth = |a: f64| a / 2.0 * ((radius + a) / (radius - a)).ln() - depth;
    let (mut lo, mut hi) = (1e-9, 0.9 * radius);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if half_depth(mid) > 0.0 { hi = mid } else { lo = mid }
    }
    let a = lo;
    let log = ((radius + a) / (radius - a)).ln();
    let exact = e_star / 2.0 * ((radius * radius + a * a) * log - 2.0 * radius * a);
    let force = |h: &str| {
        let text = format!(
            r#"
[mesh]
file = "{mesh}"
plane = "axisymmetric"
[material]
law = "linear"
young = {young}
poisson = {poisson}
e31 = 0.0
e33 = 0.0
e15 = 0.0
eps0 = 1.0
beta11_rel = 1.0
beta33_rel = 1.0
[boundary]
clamped = ["bottom"]
grounded = ["bottom"]
contact = ["contact"]
[contact]
problem = "PV1"
[foundation]
kind = "sphere"
center = [0.0, {y}]
radius = {radius}
[solver]
method = "newton"
"#,
            mesh = super::common::mesh_file(&format!("indent-axisym-h{h}.msh")).display(),
            y = radius - depth
        );
        let built = build_text(&text).unwrap();
        let run = super::common::contact_run(&built);
        assert!(run.solution.converged() && run.solution.kkt.max < 1e-10);
        -run.solution.balance.contact[1]
    };
    let (coarse, fine) = ((force("0.02") - exact) / exact, (force("0.01") - exact) / exact);
    let order = (coarse / fine).log2();
    assert!(
        fine > 0.0 && fine < 8e-3 && order > 0.8,
        "errors {coarse:e} → {fine:e}, order {order}"
    );
}
