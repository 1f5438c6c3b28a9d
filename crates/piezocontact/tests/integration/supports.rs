//! Supports along the axes: uniform states on rollers, which P1 elements reproduce to
//! round-off, with the expected values computed here from the constitutive law
//! (σ = k0 tr(ε) I + 2µ1 ε^D + Eᵀ∇ϕ, D = Eε − β∇ϕ), each support's reaction, and the errors
//! of bad support tables.

use super::common::{EPS0, assert_displacements, build_text, mesh_file, solve_static};
use piezocontact::case::Built;
use piezocontact::linalg::default_solver;
use piezocontact::run::{Run, StaticRun};

/// E, ν of the block [GPa, -], and its size: the box [0,2]×[0,1]×[0,1] [m].
const YOUNG: f64 = 58.7102;
const POISSON: f64 = 0.3912;
const AREA: f64 = 2.0;

/// A block on rollers on x = 0 (along x), y = 0 (along y) and z = 0 (along z), grounded at
/// the bottom, with the piezoelectric constants (e31, e33, e15) and `extra` tables.
fn block(e: [f64; 3], extra: &str) -> String {
    format!(
        r#"
[mesh]
file = "{mesh}"

[material]
law = "linear"
young = {YOUNG}
poisson = {POISSON}
e31 = {e31}
e33 = {e33}
e15 = {e15}
eps0 = {EPS0}
beta11_rel = 916.0
beta33_rel = 830.0

[boundary]
grounded = ["bottom"]

[[boundary.support]]
parts = ["x0"]
fix = ["x"]

[[boundary.support]]
parts = ["y0"]
fix = ["y"]

[[boundary.support]]
parts = ["bottom"]
fix = ["z"]
{extra}
"#,
        mesh = mesh_file("box-faces.msh").display(),
        e31 = e[0],
        e33 = e[1],
        e15 = e[2],
    )
}

/// k0 and µ1 of the block.
fn moduli() -> (f64, f64) {
    (YOUNG / (3.0 - 6.0 * POISSON), YOUNG / (2.0 + 2.0 * POISSON))
}

/// The uniform state (ε_xx = ε_yy = a, ε_zz = c, ∂_zϕ = g) against the nodal solution: u =
/// (a x, a y, c z), ϕ = g z, to `1e-9` of its largest value.
fn assert_uniform(built: &Built, run: &StaticRun, (a, c, g): (f64, f64, f64)) {
    let scale = a.abs().max(c.abs()) * 2.0;
    assert_displacements(built, run, |p| vec![a * p[0], a * p[1], c * p[2]], 1e-9 * scale);
    let mesh = &built.problem.mesh;
    for node in 0..mesh.n_nodes() {
        let (p, phi) = (mesh.node(node), run.solution.x[run.solution.dofs.phi(node)]);
        assert!(
            (phi - g * p[2]).abs() < 1e-9 * g.abs().max(1e-300),
            "ϕ at {p:?}: {phi} vs {}",
            g * p[2]
        );
    }
}

/// The reaction of the support `name`.
fn reaction<'a>(built: &Built, run: &'a StaticRun, name: &str) -> &'a [f64] {
    let k = built.problem.support_names().iter().position(|n| n == name).expect(name);
    &run.reactions.supports[k]
}

/// An isotropic block on three rollers under a uniform pressure p on top deforms freely:
/// σ = −p e_z e_z, so tr ε = −p/(3k0) and ε^D = σ^D/(2µ1). The bottom roller carries p A, the
/// side rollers nothing.
#[test]
fn a_block_on_rollers_under_a_pressure_takes_the_uniform_state() {
    let p = 0.5;
    let text = block(
        [0.0; 3],
        &format!("[[boundary.traction]]\nparts = [\"top\"]\nf2 = [0.0, 0.0, {}]\n", -p),
    );
    let (built, run) = solve_static(&text);
    let (k0, mu1) = moduli();
    let trace = -p / (3.0 * k0);
    let (a, c) = (trace / 3.0 + p / (6.0 * mu1), trace / 3.0 - p / (3.0 * mu1));
    assert_uniform(&built, &run, (a, c, 0.0));
    let bottom = reaction(&built, &run, "bottom");
    assert!((bottom[2] - p * AREA).abs() < 1e-9 * p * AREA, "{bottom:?}");
    for side in ["x0", "y0"] {
        let r = reaction(&built, &run, side);
        assert!(r.iter().all(|f| f.abs() < 1e-9 * p * AREA), "{side}: {r:?}");
    }
}

/// The same block compressed by a displacement δ prescribed along z on its top: ε_zz = −δ,
/// the sides free (σ_xx = σ_yy = 0), so ε_xx = ε_zz (2µ1/3 − k0)/(2k0 + 2µ1/3); the top
/// support pushes with σ_zz A, the bottom one back.
#[test]
fn a_block_compressed_by_a_prescribed_displacement_takes_the_uniform_state() {
    let delta = 1e-3;
    let top = format!(
        "[[boundary.support]]\nname = \"press\"\nparts = [\"top\"]\nfix = [\"z\"]\ndisplacement = [{}]\n",
        -delta
    );
    let (built, run) = solve_static(&block([0.0; 3], &top));
    let (k0, mu1) = moduli();
    let c = -delta;
    let a = c * (2.0 * mu1 / 3.0 - k0) / (2.0 * k0 + 2.0 * mu1 / 3.0);
    assert_uniform(&built, &run, (a, c, 0.0));
    let sigma_zz = k0 * (2.0 * a + c) + 4.0 * mu1 / 3.0 * (c - a);
    let (press, bottom) = (reaction(&built, &run, "press"), reaction(&built, &run, "bottom"));
    let force = sigma_zz * AREA;
    assert!((press[2] - force).abs() < 1e-9 * force.abs(), "{press:?} vs {force}");
    assert!((bottom[2] + force).abs() < 1e-9 * force.abs(), "{bottom:?} vs {}", -force);
}

/// A PZT block on the same rollers, grounded at the bottom, its top charge-free, under a
/// pressure p: the uniform state with D_z = 0, from the three equations σ_xx = 0, σ_zz = −p,
/// D_z = 2 e31 a + e33 c − β33 g = 0 (Cramer's rule).
#[test]
fn a_piezoelectric_block_on_rollers_takes_the_uniform_state_with_no_charge_on_top() {
    let p = 0.5;
    let (e31, e33) = (-5.4, 15.8);
    let text = block(
        [e31, e33, 12.3],
        &format!("[[boundary.traction]]\nparts = [\"top\"]\nf2 = [0.0, 0.0, {}]\n", -p),
    );
    let (built, run) = solve_static(&text);
    let (k0, mu1) = moduli();
    let beta33 = 830.0 * EPS0;
    // Rows: σ_xx, σ_zz, D_z; columns: a, c, g.
    let m = [
        [2.0 * k0 + 2.0 * mu1 / 3.0, k0 - 2.0 * mu1 / 3.0, e31],
        [2.0 * k0 - 4.0 * mu1 / 3.0, k0 + 4.0 * mu1 / 3.0, e33],
        [2.0 * e31, e33, -beta33],
    ];
    let rhs = [0.0, -p, 0.0];
    let det = |m: [[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let solve_for = |j: usize| {
        let mut mj = m;
        (0..3).for_each(|i| mj[i][j] = rhs[i]);
        det(mj) / det(m)
    };
    let (a, c, g) = (solve_for(0), solve_for(1), solve_for(2));
    assert!(g.abs() > 0.0 && a > 0.0 && c < 0.0);
    assert_uniform(&built, &run, (a, c, g));
    let bottom = reaction(&built, &run, "bottom");
    assert!((bottom[2] - p * AREA).abs() < 1e-9 * p * AREA, "{bottom:?}");
}

/// Bad support tables are errors naming the key and the fix; a body left free to move is
/// refused with its free motions named; a support on a Γ3 node is refused naming the node.
#[test]
fn bad_supports_are_errors_naming_the_key() {
    let error = |extra: &str| build_text(&block([0.0; 3], extra)).err().expect(extra).to_string();
    let table = |body: &str| format!("[[boundary.support]]\n{body}\n");
    let cases = [
        (table("parts = [\"top\"]\nfix = []"), "fix is empty"),
        (table("parts = [\"top\"]\nfix = [\"w\"]"), "fix names 'w'"),
        (table("parts = [\"top\"]\nfix = [\"z\", \"z\"]"), "fix names 'z' twice"),
        (
            table("parts = [\"top\"]\nfix = [\"z\"]\ndisplacement = [1.0, 2.0]"),
            "displacement has 2 values",
        ),
        (table("parts = [\"nowhere\"]\nfix = [\"z\"]"), "boundary.support.parts"),
        (table("parts = []\nfix = [\"z\"]"), "parts is empty"),
        (table("parts = [\"bottom\"]\nfix = [\"x\"]"), "the name 'bottom' is taken"),
        (
            table("name = \"lift\"\nparts = [\"x1\"]\nfix = [\"z\"]\ndisplacement = [0.1]"),
            "fixed to 0 by 'bottom' and to 0.1 by 'lift'",
        ),
    ];
    for (extra, expected) in cases {
        let e = error(&extra);
        assert!(e.contains(expected) && e.contains("block.toml"), "{extra}: {e}");
    }
    // Expressions: an unknown variable, a syntax error, a value that is not finite.
    let e = error(&table(
        "name = \"lift\"\nparts = [\"x1\"]\nfix = [\"x\"]\ndisplacement = [\"2 * w\"]",
    ));
    assert!(e.contains("displacement[0]: \"2 * w\" names 'w'"), "{e}");
    let pull = |f2: &str| format!("[[boundary.traction]]\nparts = [\"x1\"]\nf2 = {f2}\n");
    let e = error(&pull("[\"(x\", 0.0, 0.0]"));
    assert!(e.contains("boundary.traction.f2[0]: \"(x\" does not parse"), "{e}");
    let e = error(&pull("[0.0, \"1 / (x - 2)\", 0.0]"));
    assert!(e.contains("boundary.traction.f2[1]: \"1 / (x - 2)\" is"), "{e}");
    let e = error(&pull("[0.0, 1.0]"));
    assert!(e.contains("must have 3 finite components"), "{e}");
    // Without the side rollers the block slides and spins about z; without one, it slides.
    let x_roller = "[[boundary.support]]\nparts = [\"x0\"]\nfix = [\"x\"]\n";
    let y_roller = "[[boundary.support]]\nparts = [\"y0\"]\nfix = [\"y\"]\n";
    let text = block([0.0; 3], "").replace(x_roller, "");
    let e = build_text(&text).err().unwrap().to_string();
    assert!(e.contains("the body can translate along x: its clamps and supports"), "{e}");
    let e = build_text(&text.replace(y_roller, "")).err().unwrap().to_string();
    let free = "the body can translate along x, translate along y and rotate about z:";
    assert!(e.contains(free), "{e}");
    // A support that fixes Γ3's normal component: contact could never act there.
    let press = "[contact]\ngap = 0.1\n\n[[boundary.support]]\nname = \"press\"\nparts = [\"top\"]\nfix = [\"z\"]\n";
    let e = build_text(
        &block([0.0; 3], press)
            .replace("grounded = [\"bottom\"]", "grounded = [\"bottom\"]\ncontact = [\"top\"]"),
    )
    .err()
    .unwrap()
    .to_string();
    let expected = "the support 'press' fixes u_z at node";
    assert!(e.contains(expected) && e.contains("contact could not act freely"), "{e}");
}

/// A path without contact scales the prescribed displacements with the loads: the block
/// compressed by δ λ_k at step k takes the uniform state of δ λ_k, the press's reaction
/// σ_zz(δ) A λ_k.
#[test]
fn a_path_without_contact_scales_the_prescribed_displacements() {
    let delta = 1e-3;
    let extra = format!(
        "[[boundary.support]]\nname = \"press\"\nparts = [\"top\"]\nfix = [\"z\"]\ndisplacement = [{}]\n[loading]\nload_factors = [0.5, 2.0]\n",
        -delta
    );
    let built = build_text(&block([0.0; 3], &extra)).unwrap();
    let Run::StaticPath(path) = Run::solve(&built, default_solver(), &|_| {}).unwrap() else {
        panic!("not a path without contact");
    };
    let (k0, mu1) = moduli();
    let (c, steps) = (-delta, path.states().collect::<Vec<_>>());
    let a = c * (2.0 * mu1 / 3.0 - k0) / (2.0 * k0 + 2.0 * mu1 / 3.0);
    let sigma_zz = k0 * (2.0 * a + c) + 4.0 * mu1 / 3.0 * (c - a);
    let top = built.problem.support_names().iter().position(|n| n == "press").unwrap();
    let mesh = &built.problem.mesh;
    let dofs = &path.last.solution.dofs;
    for (k, factor) in [0.5, 2.0].into_iter().enumerate() {
        let force = sigma_zz * AREA * factor;
        let reaction = path.curve[k].supports[top][2];
        assert!((reaction - force).abs() < 1e-9 * force.abs(), "{reaction} vs {force}");
        let corner = (0..mesh.n_nodes()).find(|&a| mesh.node(a) == [2.0, 1.0, 1.0]).unwrap();
        let expected = [2.0 * a * factor, a * factor, c * factor];
        for (i, e) in expected.iter().enumerate() {
            let got = steps[k][dofs.u(corner, i)];
            assert!((got - e).abs() < 1e-9 * delta, "step {k} u_{i}: {got} vs {e}");
        }
    }
}

/// On a path, curve.csv has one column per support and component, which sums to the total
/// reaction and carries the load times the step's factor (the bottom roller: p A λ).
#[test]
fn a_path_reports_each_support_s_reaction() {
    let p = 0.5;
    let extra = format!(
        "[[boundary.traction]]\nparts = [\"top\"]\nf2 = [0.0, 0.0, {}]\n[loading]\nload_factors = [1.0, 3.0]\n",
        -p
    );
    let built = build_text(&block([0.0; 3], &extra)).unwrap();
    let run = Run::solve(&built, default_solver(), &|_| {}).unwrap();
    let columns = run.curve(&built);
    let column = |name: &str| match &columns.iter().find(|(n, _)| n == name).expect(name).1 {
        piezocontact::report::Column::Real(v) => v.clone(),
        _ => panic!("{name} is not real"),
    };
    let (bottom, total) = (column("reaction_bottom_z"), column("reaction_z"));
    let sides = [column("reaction_x0_z"), column("reaction_y0_z")];
    for (k, factor) in [1.0, 3.0].into_iter().enumerate() {
        let load = p * AREA * factor;
        assert!((bottom[k] - load).abs() < 1e-9 * load, "{bottom:?}");
        let sum = bottom[k] + sides[0][k] + sides[1][k];
        assert!((sum - total[k]).abs() < 1e-12 * load, "{sum} vs {}", total[k]);
    }
}

/// Pure bending (Saint-Venant): the prism [0,2]×[−½,½]² with σ_xx = −(M/I) y, all other
/// stresses zero, has u_x = −κxy, u_y = κ(x² + ν(y² − z²))/2, u_z = κνyz with κ = M/(EI).
/// The face x = 0 is held by those displacements (a support fixing x, y, z to expressions),
/// the face x = 2 carries the traction (σ_xx, 0, 0) as an expression, the sides are free.
/// Returns the largest nodal error of u relative to the largest |u|, and checks that the
/// moment about z of the assembled nodal forces on x = 2 is M to round-off (the traction is
/// linear, integrated exactly).
fn bending_error(mesh: &str) -> f64 {
    let (young, poisson, m_over_i) = (100.0, 0.3, 1.0);
    let kappa = m_over_i / young;
    let text = format!(
        r#"
[mesh]
file = "{mesh}"

[material]
law = "linear"
young = {young}
poisson = {poisson}
e31 = 0.0
e33 = 0.0
e15 = 0.0
eps0 = {EPS0}
beta11_rel = 916.0
beta33_rel = 830.0

[boundary]
grounded = ["x0"]

[[boundary.support]]
name = "saint-venant"
parts = ["x0"]
fix = ["x", "y", "z"]
displacement = ["-{kappa} * x * y", "{kappa} / 2 * (x^2 + {poisson} * (y^2 - z^2))", "{kappa} * {poisson} * y * z"]

[[boundary.traction]]
parts = ["x1"]
f2 = ["-{m_over_i} * y", 0.0, 0.0]
"#,
        mesh = mesh_file(mesh).display()
    );
    let (built, run) = solve_static(&text);
    let (problem, dofs, x) = (&built.problem, &run.solution.dofs, &run.solution.x);
    let exact = |p: &[f64]| {
        let (x, y, z) = (p[0], p[1], p[2]);
        [-kappa * x * y, kappa / 2.0 * (x * x + poisson * (y * y - z * z)), kappa * poisson * y * z]
    };
    let (mut error, mut size) = (0.0_f64, 0.0_f64);
    for node in 0..problem.mesh.n_nodes() {
        let u = exact(problem.mesh.node(node));
        for k in 0..3 {
            error = error.max((x[dofs.u(node, k)] - u[k]).abs());
            size = size.max(u[k].abs());
        }
    }
    // M_z = Σ (x F_y − y F_x) over the nodal forces; I = 1/12 for the unit square section.
    let forces = piezocontact::assembly::load_vector(problem, dofs, 1.0);
    let moment: f64 = (0..problem.mesh.n_nodes())
        .map(|a| {
            let p = problem.mesh.node(a);
            p[0] * forces[dofs.u(a, 1)] - p[1] * forces[dofs.u(a, 0)]
        })
        .sum();
    let m = m_over_i / 12.0;
    assert!((moment - m).abs() < 1e-12 * m, "{mesh}: moment {moment} vs {m}");
    error / size
}

/// The nodal error of pure bending falls towards h² over three meshes (h = ¼, ⅛, 1/16
/// across).
#[test]
fn pure_bending_converges_towards_second_order() {
    let errors: Vec<f64> =
        ["bending-prism-n4.msh", "bending-prism-n8.msh", "bending-prism-n16.msh"]
            .map(bending_error)
            .to_vec();
    let rates: Vec<f64> = errors.windows(2).map(|e| (e[0] / e[1]).log2()).collect();
    eprintln!("pure bending: relative nodal errors {errors:?}, rates {rates:?}");
    // Measured: errors 0.216, 0.0733, 0.0212 and rates 1.56, 1.79: linear tetrahedra stiffen
    // in bending (locking) on coarse sections, so the rate climbs to 2 from below.
    assert!(errors[2] < 0.025, "{errors:?}");
    assert!(rates[1] > rates[0] && rates[1] > 1.75, "{errors:?}, rates {rates:?}");
}

/// The reactions, the applied loads and the contact forces balance on the committed cases:
/// to round-off where the exact solver solves them (the paper's examples with
/// `solver.method = "newton"`, the 3D indentation), within 100 times the reported
/// equilibrium residual where the paper's Uzawa method stops on its increments; and each
/// clamp's and support's reaction sums to the total.
#[test]
fn the_forces_balance_on_the_committed_cases() {
    let coarse = ["mesh.nx=48", "mesh.ny=8"];
    let exact = [
        ("paper-7.1.toml", &[coarse[0], coarse[1], "solver.method=\"newton\""][..]),
        ("paper-7.2.toml", &[coarse[0], coarse[1], "solver.method=\"newton\""][..]),
        ("indentation-3d.toml", &[][..]),
    ];
    let uzawa = [("paper-7.1.toml", &coarse[..]), ("paper-7.2.toml", &coarse[..])];
    for (case, sets, is_exact) in
        exact.iter().map(|(c, s)| (c, s, true)).chain(uzawa.iter().map(|(c, s)| (c, s, false)))
    {
        let built = super::common::committed_case(case, sets).build().unwrap();
        let run = super::common::contact_run(&built);
        let (balance, kkt) = (&run.solution.balance, &run.solution.kkt);
        // Uzawa stops on its increments (ε = 1e-4), with what equilibrium defect remains:
        // measured, imbalances of 2.0e-7 (7.1) and 1.4e-6 (7.2) with relative equilibrium
        // residuals of 5.0e-9 and 9.6e-8 — the imbalance is a sum of the free rows' defects
        // over the applied loads, the residual their norm over the row scales, 15-40 times
        // smaller here.
        let bound = if is_exact { 1e-10 } else { 100.0 * kkt.equilibrium_u };
        assert!(balance.imbalance < bound, "{case}: {balance:?} {kkt:?}");
        let dim = built.problem.mesh.dim();
        for c in 0..dim {
            let sum: f64 = balance.supports.iter().map(|f| f[c]).sum();
            let size = balance.reaction.iter().map(|f| f.abs()).fold(0.0, f64::max);
            assert!((sum - balance.reaction[c]).abs() <= 1e-12 * size, "{case}: {balance:?}");
        }
    }
}

/// A bar pushed onto a rigid foundation by a displacement prescribed on its top, on a path
/// of load factors: each step equals the single run with the displacement at its factor
/// (the path scales the prescribed displacements as it scales the loads, and lifts them
/// again at each step).
#[test]
fn a_contact_path_scales_the_prescribed_displacements() {
    let case = |displacement: f64, loading: &str| {
        format!(
            r#"
[mesh]
x = [0.0, 4.0]
y = [0.0, 1.0]
nx = 16
ny = 4

[mesh.segments]
left = ["{{0}}x[0,1]"]
top = ["[0,4]x{{1}}"]
bottom = ["[0.5,3.5]x{{0}}"]

[material]
law = "linear"
young = {YOUNG}
poisson = {POISSON}
e32 = -5.4
e33 = 15.8
e24 = 12.3
eps0 = {EPS0}
beta22_rel = 916.0
beta33_rel = 830.0

[boundary]
grounded = ["top"]
contact = ["bottom"]

[[boundary.support]]
parts = ["left"]
fix = ["x"]

[[boundary.support]]
name = "press"
parts = ["top"]
fix = ["y"]
displacement = [{displacement}]

[contact]
gap = 0.001
c_nu = 100.0
{loading}
"#
        )
    };
    let sigma_nu = |run: &piezocontact::run::ContactRun| -> Vec<f64> {
        run.rows.iter().map(|r| r.sigma_nu).collect()
    };
    let path = build_text(&case(-0.004, "[loading]\nload_factors = [0.5, 1.0]\n")).unwrap();
    let Run::Path(path) = Run::solve(&path, default_solver(), &|_| {}).unwrap() else {
        panic!("not a contact path");
    };
    assert!(path.converged(), "{:?}", path.failure);
    for (k, displacement) in [-0.002, -0.004].into_iter().enumerate() {
        let single = super::common::contact_run(&build_text(&case(displacement, "")).unwrap());
        let expected = sigma_nu(&single);
        let got: Vec<f64> = path.rows(k).iter().map(|r| r.sigma_nu).collect();
        let scale = expected.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        assert!(scale > 0.0, "step {k}: nothing touches");
        let error = got.iter().zip(&expected).fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(error < 1e-9 * scale, "step {k}: σ_ν differs by {error} of {scale}");
    }
}
