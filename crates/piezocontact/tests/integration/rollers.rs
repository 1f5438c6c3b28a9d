//! Rollers on faces of any orientation (`fix = ["normal"]`): the nodes of such a face get a
//! turned frame in the global system. A turned block on normal rollers takes the turned
//! uniform state to round-off, with the expected values computed here from the law; a
//! normal roller on a face along an axis is the axis roller; bad tables are errors.

use super::common::{EPS0, assert_displacements, build_text, mesh_file, solve_static};
use piezocontact::case::Built;
use piezocontact::run::StaticRun;

/// E, ν of the block [GPa, -] (an isotropic elastic body).
const YOUNG: f64 = 58.7102;
const POISSON: f64 = 0.3912;

/// The box [0,2]×[0,1]×[0,1] of `mesh` on normal rollers on x0, y0 and the bottom, grounded
/// at the bottom, with `extra` tables.
fn block(mesh: &str, extra: &str) -> String {
    format!(
        r#"
[mesh]
file = "{mesh}"

[material]
law = "linear"
young = {YOUNG}
poisson = {POISSON}
eps0 = {EPS0}
beta11_rel = 916.0
beta33_rel = 830.0

[boundary]
grounded = ["bottom"]

[[boundary.support]]
parts = ["x0"]
fix = ["normal"]

[[boundary.support]]
parts = ["y0"]
fix = ["normal"]

[[boundary.support]]
parts = ["bottom"]
fix = ["normal"]
{extra}
"#,
        mesh = mesh_file(mesh).display(),
    )
}

/// The reaction of the support `name`.
fn reaction<'a>(built: &Built, run: &'a StaticRun, name: &str) -> &'a [f64] {
    let k = built.problem.support_names().iter().position(|n| n == name).expect(name);
    &run.reactions.supports[k]
}

/// The box turned by 30° about z, pressed by p1 on its turned end x1 and by p on its top:
/// in the turned frame (x' along n1 = (cos 30°, sin 30°, 0)) the stress is uniform,
/// σ' = diag(−p1, 0, −p), so ε' = σ'^D/(2µ) + tr σ'/(9k) I and u = Rᵀ ε' R x, which the
/// rollers on x0, y0 and the bottom (each through the origin) allow without a rotation. The
/// x0 roller carries p1 (x1's area 1) along n1, the bottom p·2 along z, y0 nothing.
#[test]
fn a_turned_block_on_normal_rollers_takes_the_turned_uniform_state() {
    let (p1, p) = (0.3, 0.5);
    let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
    let loads = format!(
        "[[boundary.traction]]\nparts = [\"x1\"]\nf2 = [{}, {}, 0.0]\n\n[[boundary.traction]]\nparts = [\"top\"]\nf2 = [0.0, 0.0, {}]\n",
        -p1 * c,
        -p1 * s,
        -p
    );
    let (built, run) = solve_static(&block("box-turned.msh", &loads));
    let (k, mu) = (YOUNG / (3.0 - 6.0 * POISSON), YOUNG / (2.0 + 2.0 * POISSON));
    let sigma = [-p1, 0.0, -p];
    let trace: f64 = sigma.iter().sum();
    let strain: Vec<f64> =
        sigma.iter().map(|v| (v - trace / 3.0) / (2.0 * mu) + trace / (9.0 * k)).collect();
    let rows = [[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]];
    let expected = |x: &[f64]| -> Vec<f64> {
        let local: Vec<f64> = (0..3).map(|i| (0..3).map(|j| rows[i][j] * x[j]).sum()).collect();
        (0..3).map(|m| (0..3).map(|i| rows[i][m] * strain[i] * local[i]).sum()).collect()
    };
    let scale = strain.iter().fold(0.0f64, |a, e| a.max(e.abs())) * 2.0;
    assert_displacements(&built, &run, expected, 1e-10 * scale);
    let (x0, y0, bottom) = (
        reaction(&built, &run, "x0"),
        reaction(&built, &run, "y0"),
        reaction(&built, &run, "bottom"),
    );
    let close = |got: &[f64], want: [f64; 3]| {
        got.iter().zip(want).all(|(g, w)| (g - w).abs() < 1e-9 * (p + p1))
    };
    assert!(close(x0, [p1 * c, p1 * s, 0.0]), "{x0:?}");
    assert!(close(y0, [0.0; 3]), "{y0:?}");
    assert!(close(bottom, [0.0, 0.0, 2.0 * p]), "{bottom:?}");
    let total = &run.reactions.total;
    assert!(close(total, [p1 * c, p1 * s, 2.0 * p]), "{total:?}");
}

/// On faces along the axes a normal roller is the axis roller: the same solution to the
/// last bit as fix = ["x"], ["y"], ["z"] (the normals are the axes up to round-off, and a
/// node whose directions are all axes keeps the mesh's frame).
#[test]
fn a_normal_roller_on_a_face_along_an_axis_is_the_axis_roller() {
    let pressure = "[[boundary.traction]]\nparts = [\"top\"]\nf2 = [0.1, 0.0, -0.5]\n\n[[boundary.support]]\nparts = [\"x1\"]\nfix = [\"normal\"]\n";
    let text = block("box-faces.msh", pressure);
    let (_, normal) = solve_static(&text);
    let axes = text
        .replacen("[\"x0\"]\nfix = [\"normal\"]", "[\"x0\"]\nfix = [\"x\"]", 1)
        .replacen("[\"y0\"]\nfix = [\"normal\"]", "[\"y0\"]\nfix = [\"y\"]", 1)
        .replacen("[\"bottom\"]\nfix = [\"normal\"]", "[\"bottom\"]\nfix = [\"z\"]", 1)
        .replacen("[\"x1\"]\nfix = [\"normal\"]", "[\"x1\"]\nfix = [\"x\"]", 1);
    assert!(!axes.contains("normal"));
    let (_, along_axes) = solve_static(&axes);
    assert!(normal.solution.dofs.frame(0).is_none());
    assert_eq!(normal.solution.x, along_axes.solution.x);
}

/// A normal roller on parts that turn at an edge, and one that fixes a turned node's normal
/// to a value an axis support contradicts, are errors naming the node.
#[test]
fn bad_normal_rollers_are_errors_naming_the_node() {
    let error = |text: &str| build_text(text).err().expect("an error").to_string();
    let edge = block("box-turned.msh", "").replacen(
        "parts = [\"x0\"]\nfix = [\"normal\"]",
        "parts = [\"x0\", \"y1\"]\nfix = [\"normal\"]",
        1,
    );
    let e = error(&edge);
    assert!(
        e.contains("the support 'x0+y1' fixes the normal component")
            && e.contains("90.000° at node"),
        "{e}"
    );
    let lift = "[[boundary.support]]\nname = \"lift\"\nparts = [\"top\"]\nfix = [\"normal\"]\ndisplacement = [0.01]\n\n[[boundary.support]]\nname = \"press\"\nparts = [\"top\"]\nfix = [\"z\"]\n";
    let e = error(&block("box-turned.msh", lift));
    assert!(e.contains("fixed to 0.01 by 'lift' and to 0 by 'press'"), "{e}");
}
