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
/// r < 0, contact (not available yet), and a 3D mesh.
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
    let contact = cylinder(&stress_charge(), "[contact]\ngap = 0.1\n").replace(
        "grounded = [\"bottom\", \"top\"]",
        "grounded = [\"bottom\"]\ncontact = [\"top\"]",
    );
    let e = error(&contact);
    assert!(e.contains("not available yet"), "{e}");
}
