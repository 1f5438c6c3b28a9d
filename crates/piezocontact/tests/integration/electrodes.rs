//! Electrodes at a voltage or floating (`[[boundary.electrode]]`): uniform fields of a PZT-5A
//! block, which P1 elements give to round-off, with the expected charges, potentials and
//! strains computed here from the material's constants (c^E, e, ε^S; d = e s^E and ε^T = ε^S +
//! d eᵀ); the outputs; bad tables.

use super::common::{EPS0, build_text, mesh_file, solve_static};
use super::materials::{C, E, stress_charge};
use piezocontact::case::Built;
use piezocontact::linalg::default_solver;
use piezocontact::material::voigt;
use piezocontact::run::{ContactRun, Run};

/// The box [0,2]×[0,1]×[0,1] (top area 2, thickness 1) of PZT-5A poled along z, its bottom
/// grounded, its top an electrode at `volts`, held by `held` tables.
fn block(volts: f64, held: &str) -> String {
    format!(
        "[mesh]\nfile = \"{}\"\n[material]\n{}\n[boundary]\ngrounded = [\"bottom\"]\n{held}\n[[boundary.electrode]]\nname = \"drive\"\nparts = [\"top\"]\nvoltage = {volts}\n",
        mesh_file("box-faces.msh").display(),
        stress_charge()
    )
}

/// ε^S33 of the block [charge/(potential·length)].
fn eps_s33() -> f64 {
    830.0 * EPS0
}

/// A block clamped on every face (u = 0) under V: E = −V/t e_z, D_z = −ε^S33 V/t, so the
/// electrode at +V holds Q = ε^S33 A V / t and the grounded one −Q.
#[test]
fn a_clamped_block_under_a_voltage_holds_the_clamped_capacitance_s_charge() {
    let volts = 0.2;
    let clamp = "clamped = [\"x0\", \"x1\", \"y0\", \"y1\", \"bottom\", \"top\"]";
    let text = block(volts, "")
        .replace("grounded = [\"bottom\"]", &format!("grounded = [\"bottom\"]\n{clamp}"));
    let (built, run) = solve_static(&text);
    let q = eps_s33() * 2.0 * volts / 1.0;
    let charges = &run.reactions.charges;
    assert!((charges[1] - q).abs() < 1e-9 * q, "drive: {} vs {q}", charges[1]);
    assert!((charges[0] + q).abs() < 1e-9 * q, "bottom: {} vs {}", charges[0], -q);
    let summary = run.summary(&built);
    let drive = &summary["electrodes"][1];
    assert_eq!(drive["name"], "drive");
    assert_eq!(drive["kind"], "voltage");
    assert!((drive["potential"].as_f64().unwrap() - volts).abs() < 1e-15);
    assert!((drive["charge"].as_f64().unwrap() - q).abs() < 1e-9 * q);
    assert_eq!(summary["electrodes"][0]["name"], "bottom");
}

/// The same block on rollers (free to deform, σ = 0): ε = dᵀ E_f with E_f = −V/t e_z, so
/// Δt = −d33 V, the lateral strain −d31 V/t, and the electrode at +V holds ε^T33 A V / t.
#[test]
fn a_free_block_under_a_voltage_strains_by_d_and_holds_the_free_capacitance_s_charge() {
    let volts = 0.2;
    let (built, run) = solve_static(&block(volts, ROLLERS));
    let (d, eps_t33) = free_constants();
    let (d31, d33) = (d[2][0], d[2][2]);
    let field = -volts;
    let (lateral, through) = (d31 * field, d33 * field);
    super::common::assert_displacements(
        &built,
        &run,
        |p| vec![lateral * p[0], lateral * p[1], through * p[2]],
        1e-9 * through.abs(),
    );
    let q = eps_t33 * 2.0 * volts;
    let charges = &run.reactions.charges;
    assert!((charges[1] - q).abs() < 1e-9 * q, "drive: {} vs {q}", charges[1]);
}

/// The rollers of a free block: x0 along x, y0 along y, the bottom along z.
const ROLLERS: &str = "[[boundary.support]]\nparts = [\"x0\"]\nfix = [\"x\"]\n[[boundary.support]]\nparts = [\"y0\"]\nfix = [\"y\"]\n[[boundary.support]]\nname = \"floor\"\nparts = [\"bottom\"]\nfix = [\"z\"]\n";

/// The blocked force of the block on rollers driven to |V| = `volts` against a stop at the
/// gap `gap`: max(0, d33 |V| − g) A/(s33^E t), A = 2, t = 1 (σ_xx = σ_yy = 0, E_z = V/t).
fn blocked_force(volts: f64, gap: f64) -> f64 {
    let s = voigt::inverse(&C).unwrap();
    let d33 = voigt::product(&E, &s)[2][2];
    (d33 * volts - gap).max(0.0) * 2.0 / s[2][2]
}

/// d = e s^E and ε^T33 = ε^S33 + Σ d3k e3k of the block's PZT-5A.
fn free_constants() -> ([[f64; 6]; 3], f64) {
    let s = voigt::inverse(&C).unwrap();
    let d = voigt::product(&E, &s);
    let eps_t33 = eps_s33() + (0..6).map(|k| d[2][k] * E[2][k]).sum::<f64>();
    (d, eps_t33)
}

/// The block on rollers under a uniform pressure p on top (σ_zz = −p, the other stresses 0),
/// its top electrode floating with no charge (an open circuit): D_z = d33 σ_zz + ε^T33 E_z = 0,
/// so the top rises to V = −E_z t = d33 σ_zz t / ε^T33, |V| = g33 p t with g33 = d33/ε^T33.
/// Short-circuited (the top at 0 V), E = 0 and the top holds Q = −D_z A = −d33 σ_zz A.
#[test]
fn an_open_circuit_block_under_pressure_reads_g33_and_a_short_circuit_d33() {
    let (d, eps_t33) = free_constants();
    let (d33, p) = (d[2][2], 0.01);
    let pressed = |condition: &str| {
        let text = block(0.0, ROLLERS).replace("voltage = 0", condition)
            + &format!("[[boundary.traction]]\nparts = [\"top\"]\nf2 = [0.0, 0.0, {}]\n", -p);
        solve_static(&text)
    };
    let (built, open) = pressed("charge = 0.0");
    let volts = d33 * -p / eps_t33;
    let potential = open.reactions.potentials[0];
    assert!((potential - volts).abs() < 1e-9 * volts.abs(), "{potential} vs {volts}");
    assert!(open.reactions.charges[1].abs() < 1e-9 * eps_t33 * 2.0 * volts.abs());
    let summary = open.summary(&built);
    assert_eq!(summary["electrodes"][1]["kind"], "floating");
    let phi_top = summary["electrodes"][1]["potential"].as_f64().unwrap();
    assert!((phi_top - volts).abs() < 1e-9 * volts.abs(), "{phi_top}");
    let (_, short) = pressed("voltage = 0.0");
    let q = -d33 * -p * 2.0;
    let charge = short.reactions.charges[1];
    assert!((charge - q).abs() < 1e-9 * q.abs(), "{charge} vs {q}");
}

/// A free block whose top electrode floats with a given charge Q: V = Q t / (ε^T33 A), of
/// Q's sign, and the grounded bottom holds −Q; on a loading path the charge, and so the
/// potential in curve.csv, scale with the load factor.
#[test]
fn a_floating_electrode_with_a_charge_rises_to_q_over_the_free_capacitance() {
    let (_, eps_t33) = free_constants();
    let charge = -3e-12;
    let text = block(0.0, ROLLERS).replace("voltage = 0", &format!("charge = {charge}"));
    let (_, run) = solve_static(&text);
    let volts = charge * 1.0 / (eps_t33 * 2.0);
    let (potential, charges) = (run.reactions.potentials[0], &run.reactions.charges);
    assert!((potential - volts).abs() < 1e-9 * volts.abs(), "{potential} vs {volts}");
    assert!((charges[1] - charge).abs() < 1e-9 * charge.abs(), "{charges:?}");
    assert!((charges[0] + charge).abs() < 1e-9 * charge.abs(), "{charges:?}");
    let path = text + "[loading]\nload_factors = [0.5, 1.0]\n";
    let built = build_text(&path).unwrap();
    let Run::StaticPath(run) = super::common::run_with(&built, default_solver()) else {
        panic!("not a loading path without contact")
    };
    let columns = run.columns(&built);
    let column = |name: &str| match &columns.iter().find(|c| c.0 == name).unwrap().1 {
        piezocontact::report::Column::Real(v) => v.clone(),
        other => panic!("{other:?}"),
    };
    let (phi, q) = (column("phi_drive"), column("charge_drive"));
    for (k, factor) in [0.5, 1.0].iter().enumerate() {
        assert!((phi[k] - factor * volts).abs() < 1e-9 * volts.abs(), "{phi:?}");
        assert!((q[k] - factor * charge).abs() < 1e-9 * charge.abs(), "{q:?}");
    }
}

/// A two-layer stack: the block of meshes/box-layers.msh, its layers poled opposite (lower
/// +z, upper −z), the outer faces grounded and the plane z = t/2 between the layers (a group
/// inside the body) an electrode at V. Both layers see E_3 = −2V/t along their poling, so on
/// rollers the block strains uniformly as one free layer under twice the field: Δt = −2 d33 V
/// and the lateral strain −2 d31 V/t; the middle holds the two layers' free capacitances,
/// 2 ε^T33 A V/(t/2), each outer face −ε^T33 A V/(t/2). A role other than an electrode's
/// refuses the inside group.
#[test]
fn a_two_layer_stack_driven_through_its_middle_electrode_strains_twice() {
    let volts = 0.2;
    let layer = |name: &str, pole: f64| {
        format!(
            "[[material]]\nname = \"{name}\"\nregions = [\"{name}\"]\npoling = [0.0, 0.0, {pole}]\n{}",
            stress_charge()
        )
    };
    let text = format!(
        "[mesh]\nfile = \"{}\"\n{}{}[boundary]\ngrounded = [\"bottom\", \"top\"]\n{ROLLERS}\
         [[boundary.electrode]]\nname = \"mid\"\nparts = [\"middle\"]\nvoltage = {volts}\n",
        mesh_file("box-layers.msh").display(),
        layer("lower", 1.0),
        layer("upper", -1.0)
    );
    let (built, run) = solve_static(&text);
    let (d, eps_t33) = free_constants();
    let field = -2.0 * volts;
    let (lateral, through) = (d[2][0] * field, d[2][2] * field);
    super::common::assert_displacements(
        &built,
        &run,
        |p| vec![lateral * p[0], lateral * p[1], through * p[2]],
        1e-9 * through.abs(),
    );
    let layer_charge = eps_t33 * 2.0 * volts / 0.5;
    let charges = &run.reactions.charges;
    for (k, want) in [-layer_charge, -layer_charge, 2.0 * layer_charge].into_iter().enumerate() {
        assert!((charges[k] - want).abs() < 1e-9 * layer_charge, "{charges:?}");
    }
    let e =
        build_text(&text.replace("grounded = [\"bottom\", \"top\"]", "grounded = [\"middle\"]"))
            .err()
            .expect("an error")
            .to_string();
    assert!(
        e.contains("'middle' is a group of facets inside the body")
            && e.contains("only an electrode"),
        "{e}"
    );
}

/// Bad tables: both or neither of voltage and charge, a name of a curve.csv column, two
/// electrodes on one facet, electrodes under different conditions that touch, and a body
/// whose potential only a floating electrode holds.
#[test]
fn bad_electrodes_are_errors_naming_the_table() {
    let error = |text: &str| build_text(text).err().expect("an error").to_string();
    let base = block(0.2, "clamped = [\"x0\"]");
    let e = error(&base.replace("voltage = 0.2", "voltage = 0.2\ncharge = 0.0"));
    assert!(
        e.contains("[[boundary.electrode]] number 1") && e.contains("not both or neither"),
        "{e}"
    );
    let e = error(&base.replace("name = \"drive\"", "name = \"mean\""));
    assert!(e.contains("the name 'mean' is taken"), "{e}");
    let twice = format!(
        "{base}[[boundary.electrode]]\nname = \"again\"\nparts = [\"top\"]\nvoltage = 0.2\n"
    );
    let e = error(&twice);
    assert!(e.contains("share the facet"), "{e}");
    let side =
        format!("{base}[[boundary.electrode]]\nname = \"side\"\nparts = [\"x1\"]\nvoltage = 0.5\n");
    let e = error(&side);
    assert!(e.contains("electrodes under different conditions must not touch"), "{e}");
    let e = error(&side.replace("voltage = 0.5", "charge = 0.0"));
    assert!(e.contains("the floating electrode 'side'") && e.contains("must not touch"), "{e}");
    let alone =
        base.replace("voltage = 0.2", "charge = 0.0").replace("grounded = [\"bottom\"]", "");
    let e = error(&alone);
    assert!(e.contains("a floating electrode does not fix it"), "{e}");
}

/// An actuator against a stop: the block on rollers, its top face both the electrode (driven
/// to −λ V0, so that the field V/t points along the poling and the block extends by d33 V)
/// and Γ3 below a rigid plane at the gap g = d33 V0 (PV1, no penetration). On a path over
/// λ = 0.5, 1, 1.5, 2: no contact force up to the onset at λ = 1, then the stop holds the top
/// at g and presses with (d33 V − g) A / (s33^E t) (σ_xx = σ_yy = 0, E_z = V/t).
#[test]
fn an_actuator_driven_against_a_stop_presses_with_the_blocked_force() {
    let (d, _) = free_constants();
    let gap = 1e-3;
    let v0 = gap / d[2][2];
    let contact = format!(
        "[contact]\nproblem = \"PV1\"\ngap = 0.0\n[foundation]\nkind = \"plane\"\npoint = [0.0, 0.0, {}]\nnormal = [0.0, 0.0, -1.0]\n[loading]\nload_factors = [0.5, 1.0, 1.5, 2.0]\n[solver]\nmethod = \"newton\"\n",
        1.0 + gap
    );
    let text = block(-v0, ROLLERS)
        .replace("grounded = [\"bottom\"]", "grounded = [\"bottom\"]\ncontact = [\"top\"]")
        + &contact;
    let path = super::common::path_run(&build_text(&text).unwrap());
    assert!(path.converged(), "{:?}", path.failure);
    let largest = blocked_force(2.0 * v0, gap);
    for row in &path.curve {
        let (lambda, force) = (row.load_factor, row.force[2]);
        let blocked = blocked_force(lambda * v0, gap);
        assert!((force - blocked).abs() < 1e-8 * largest, "λ = {lambda}: {force} vs {blocked}");
    }
}

/// A sensor pressed by a stop: the block on rollers, its top face Γ3 and an open-circuit
/// floating electrode, pushed down by a rigid plane (PV1, no penetration) to a uniform state.
/// Whatever the depth, D_z = 0 ties the top's potential to the contact force F:
/// V = d33 σ_zz t / ε^T33 with σ_zz = −F/A — the exact solver and Uzawa alike.
#[test]
fn a_sensor_pressed_by_a_stop_reads_g33_times_the_contact_pressure() {
    let (d, eps_t33) = free_constants();
    for (method, _, run) in pressed_sensor("[contact]\nproblem = \"PV1\"\ngap = 0.0\n") {
        let balance = &run.solution.balance;
        let sigma_zz = -balance.contact[2].abs() / 2.0;
        let volts = d[2][2] * sigma_zz / eps_t33;
        let potential = balance.potentials[0];
        // Uzawa stops on the change of its multipliers (8e-8 relative here).
        let tolerance = if method == "newton" { 1e-9 } else { 1e-6 };
        assert!(
            (potential - volts).abs() < tolerance * volts.abs(),
            "{method}: {potential} vs {volts}"
        );
        assert!(balance.charges[1].abs() < tolerance * eps_t33 * 2.0 * volts.abs(), "{method}");
    }
}

/// A sensor pressed by a conductive stop: as above, but PV2 with normal compliance (a finite
/// penetration) and a foundation at ϕ0 that conducts (k_e > 0), so that the conduction flux
/// q = ψ(u_ν − g_a) φ_L(V − ϕ0) enters the open-circuit electrode's balance. The state stays
/// uniform, and the electrode's equation (no charge given) is D_z = q on its face, with
/// D_z = d33 σ_zz + ε^T33 E_z, σ_zz = −F/A, E_z = −V/t: the exact solver (which condenses the
/// electrode's one potential with every node's flux in its row) and Uzawa alike.
#[test]
fn a_sensor_pressed_by_a_conductive_stop_balances_its_charge_with_the_flux() {
    let (d, eps_t33) = free_constants();
    let contact = "[contact]\nproblem = \"PV2\"\npenetration = 0.01\nc_nu = 10.0\nalpha_nu = 2.0\nn_nu = 1.0\nh_nu_range = 1.0\n[friction]\nmu = 0.0\n[conductivity]\nke = 1000.0\nphi0 = 1e-3\ndelta = 1.0\nL = 1.0\n";
    for (method, built, run) in pressed_sensor(contact) {
        let (balance, model) = (&run.solution.balance, built.model.as_ref().unwrap());
        let (force, potential) = (balance.contact[2].abs(), balance.potentials[0]);
        let (x, dofs) = (&run.solution.x, &run.solution.dofs);
        let top = built.problem.mesh.part_nodes(&[built.problem.mesh.part_index("top").unwrap()]);
        let u_nu = x[dofs.u(top[0], 2)];
        let spread = top.iter().map(|&a| (x[dofs.u(a, 2)] - u_nu).abs()).fold(0.0, f64::max);
        // Uniform to round-off with the exact solver; Uzawa's stopping rule leaves 4e-5.
        let uniform = if method == "newton" { 1e-9 } else { 1e-4 };
        assert!(spread < uniform * u_nu.abs(), "{method}: the top is not uniform ({spread:e})");
        let q = model.flux(u_nu, potential, -0.001);
        let d_z = d[2][2] * -force / 2.0 + eps_t33 * -potential;
        // D_z's terms, of which q is a part: Uzawa's stopping rule (the change of its
        // multipliers, 1e-4 by default) leaves 1e-5 of them.
        let scale = (d[2][2] * force / 2.0).abs();
        assert!(q.abs() > 0.1 * scale, "the conduction acts: q {q}, terms {scale}");
        let tolerance = if method == "newton" { 1e-12 } else { 3e-5 };
        assert!((d_z - q).abs() < tolerance * scale, "{method}: D_z {d_z} vs q {q}");
    }
}

/// The block on rollers, its top face Γ3 and an open-circuit floating electrode, pressed by
/// the rigid plane z = 0.999 under the `[contact]` (and friction, conductivity) tables
/// `contact`: the converged runs of the exact solver and Uzawa, each with its case.
fn pressed_sensor(contact: &str) -> Vec<(&'static str, Built, ContactRun)> {
    let plane =
        "[foundation]\nkind = \"plane\"\npoint = [0.0, 0.0, 0.999]\nnormal = [0.0, 0.0, -1.0]\n";
    let text = block(0.0, ROLLERS)
        .replace("voltage = 0", "charge = 0.0")
        .replace("grounded = [\"bottom\"]", "grounded = [\"bottom\"]\ncontact = [\"top\"]")
        + contact
        + plane;
    let solved = |method: &'static str| {
        let built = build_text(&format!("{text}[solver]\nmethod = \"{method}\"\n")).unwrap();
        let run = super::common::contact_run(&built);
        assert!(run.solution.converged(), "{method}");
        (method, built, run)
    };
    vec![solved("newton"), solved("uzawa")]
}

/// cases/actuator-stop.toml: the stop's force at every step of the voltage ramp is the
/// blocked force ([`blocked_force`]) from the preset's constants (Berlincourt's PZT-5A, those
/// of this file), the onset at d33 V = g.
#[test]
fn the_committed_actuator_meets_its_stop_at_d33_v_equal_to_the_gap() {
    let ramp: Vec<f64> = (1..=10).map(|k| 0.1 * k as f64).collect();
    assert_committed_actuator(&[], &ramp);
}

/// cases/actuator-stop.toml with `sets`, its electrode driven to −λ V0 at the steps' factors
/// λ in `factors` (V0 = 1e-3 GV, g = 0.25 mm): at each, the stop presses with the blocked
/// force of λ V0, to 1e-8 of the largest.
fn assert_committed_actuator(sets: &[&str], factors: &[f64]) {
    let built = super::common::committed_case("actuator-stop.toml", sets).build().unwrap();
    let path = super::common::path_run(&built);
    assert!(path.converged() && path.curve.len() == factors.len(), "{:?}", path.failure);
    let (v0, gap) = (1e-3, 2.5e-4);
    let largest = blocked_force(v0, gap);
    assert!(largest > 0.0);
    for (row, lambda) in path.curve.iter().zip(factors) {
        let (force, blocked) = (row.force[2], blocked_force(lambda * v0, gap));
        assert!((force - blocked).abs() < 1e-8 * largest, "λ = {lambda}: {force} vs {blocked}");
        assert!((row.potentials[0] + lambda * v0).abs() < 1e-15, "{:?}", row.potentials);
    }
}

/// cases/force-sensor.toml: an open circuit, so no charge flows to either electrode while
/// the ball presses harder and the floating top's potential grows with the force (negative:
/// compression along the poling).
#[test]
fn the_committed_force_sensor_reads_a_voltage_and_no_charge() {
    let built = super::common::committed_case("force-sensor.toml", &[]).build().unwrap();
    let path = super::common::path_run(&built);
    assert!(path.converged(), "{:?}", path.failure);
    let last = path.curve.last().unwrap();
    let scale = eps_s33() * std::f64::consts::PI * 4.0 * last.potentials[0].abs();
    let mut previous = (0.0, 0.0);
    for row in &path.curve {
        let (force, phi) = (row.force[1], row.potentials[0]);
        assert!(force > previous.0 && phi < previous.1, "{force} {phi} after {previous:?}");
        assert!(row.charges.iter().all(|q| q.abs() < 1e-9 * scale), "{:?}", row.charges);
        previous = (force, phi);
    }
}

/// `loading.electrode_factors` scale the electrodes apart from the loads. Without contact:
/// the block on rollers under a constant pressure p (σ_zz = −p), its top floating with the
/// charge λ_e Q, rises to V = (λ_e Q/A + d33 σ_zz) t/ε^T33 (D_z = −λ_e Q/A). With contact:
/// the committed actuator held at load factor 1 while only its voltage ramps presses with
/// the blocked force of each voltage.
#[test]
fn electrode_factors_scale_the_electrodes_apart_from_the_loads() {
    let (d, eps_t33) = free_constants();
    // Q comparable with the charge the pressure displaces, d33 p A.
    let (p, charge) = (0.01, 5e-3);
    let text = block(0.0, ROLLERS).replace("voltage = 0", &format!("charge = {charge}"))
        + &format!("[[boundary.traction]]\nparts = [\"top\"]\nf2 = [0.0, 0.0, {}]\n", -p)
        + "[loading]\nload_factors = [1.0, 1.0, 1.0]\nelectrode_factors = [0.0, 0.5, 1.0]\n";
    let built = build_text(&text).unwrap();
    let Run::StaticPath(run) = super::common::run_with(&built, default_solver()) else {
        panic!("not a loading path without contact")
    };
    for (row, lambda) in run.curve.iter().zip([0.0, 0.5, 1.0]) {
        let volts = (lambda * charge / 2.0 + d[2][2] * -p) / eps_t33;
        let potential = row.potentials[0];
        assert!((potential - volts).abs() < 1e-9 * volts.abs(), "λ = {lambda}: {potential}");
        assert!((row.charges[1] - lambda * charge).abs() < 1e-9 * charge, "{:?}", row.charges);
    }
    let ramp =
        ["loading.load_factors=[1.0, 1.0, 1.0]", "loading.electrode_factors=[0.5, 0.8, 1.0]"];
    assert_committed_actuator(&ramp, &[0.5, 0.8, 1.0]);
    let e = build_text(
        &(block(0.2, ROLLERS)
            + "[loading]\nload_factors = [1.0]\nelectrode_factors = [0.5, 1.0]\n"),
    )
    .err()
    .unwrap()
    .to_string();
    assert!(e.contains("loading.electrode_factors has 2 steps and the path 1"), "{e}");
}
