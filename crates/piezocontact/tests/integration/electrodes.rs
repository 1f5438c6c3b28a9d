//! Electrodes at a voltage (`[[boundary.electrode]]`): uniform fields of a PZT-5A block, which
//! P1 elements give to round-off, with the expected charges and strains computed here from
//! the material's constants (c^E, e, ε^S; d = e s^E and ε^T = ε^S + d eᵀ); the outputs; bad
//! tables.

use super::common::{EPS0, build_text, mesh_file, solve_static};
use super::materials::{C, E, stress_charge};
use piezocontact::material::voigt;

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
    let rollers = "[[boundary.support]]\nparts = [\"x0\"]\nfix = [\"x\"]\n[[boundary.support]]\nparts = [\"y0\"]\nfix = [\"y\"]\n[[boundary.support]]\nname = \"floor\"\nparts = [\"bottom\"]\nfix = [\"z\"]\n";
    let (built, run) = solve_static(&block(volts, rollers));
    let s = voigt::inverse(&C).unwrap();
    let d = voigt::product(&E, &s);
    let (d31, d33) = (d[2][0], d[2][2]);
    let eps_t33 = eps_s33() + (0..6).map(|k| d[2][k] * E[2][k]).sum::<f64>();
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

/// Bad tables: both or neither of voltage and charge, a floating electrode (not available
/// yet), a name of a curve.csv column, two electrodes on one facet, and electrodes at two
/// potentials that touch.
#[test]
fn bad_electrodes_are_errors_naming_the_table() {
    let error = |text: &str| build_text(text).err().expect("an error").to_string();
    let base = block(0.2, "clamped = [\"x0\"]");
    let e = error(&base.replace("voltage = 0.2", "voltage = 0.2\ncharge = 0.0"));
    assert!(
        e.contains("[[boundary.electrode]] number 1") && e.contains("not both or neither"),
        "{e}"
    );
    let e = error(&base.replace("voltage = 0.2", "charge = 0.0"));
    assert!(e.contains("floating electrodes") && e.contains("not available yet"), "{e}");
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
    assert!(e.contains("electrodes at different potentials must not touch"), "{e}");
}

/// An actuator against a stop: the block on rollers, its top face both the electrode (driven
/// to −λ V0, so that the field V/t points along the poling and the block extends by d33 V)
/// and Γ3 below a rigid plane at the gap g = d33 V0 (PV1, no penetration). On a path over
/// λ = 0.5, 1, 1.5, 2: no contact force up to the onset at λ = 1, then the stop holds the top
/// at g and presses with (d33 V − g) A / (s33^E t) (σ_xx = σ_yy = 0, E_z = V/t).
#[test]
fn an_actuator_driven_against_a_stop_presses_with_the_blocked_force() {
    let s = voigt::inverse(&C).unwrap();
    let d33 = voigt::product(&E, &s)[2][2];
    let gap = 1e-3;
    let v0 = gap / d33;
    let rollers = "[[boundary.support]]\nparts = [\"x0\"]\nfix = [\"x\"]\n[[boundary.support]]\nparts = [\"y0\"]\nfix = [\"y\"]\n[[boundary.support]]\nname = \"floor\"\nparts = [\"bottom\"]\nfix = [\"z\"]\n";
    let contact = format!(
        "[contact]\nproblem = \"PV1\"\ngap = 0.0\n[foundation]\nkind = \"plane\"\npoint = [0.0, 0.0, {}]\nnormal = [0.0, 0.0, -1.0]\n[loading]\nload_factors = [0.5, 1.0, 1.5, 2.0]\n[solver]\nmethod = \"newton\"\n",
        1.0 + gap
    );
    let text = block(-v0, rollers)
        .replace("grounded = [\"bottom\"]", "grounded = [\"bottom\"]\ncontact = [\"top\"]")
        + &contact;
    let path = super::common::path_run(&build_text(&text).unwrap());
    assert!(path.converged(), "{:?}", path.failure);
    for row in &path.curve {
        let lambda = row.load_factor;
        let blocked = ((lambda - 1.0) * d33 * v0).max(0.0) * 2.0 / s[2][2];
        let force = row.force[2];
        assert!(
            (force - blocked).abs() < 1e-8 * (d33 * v0 * 2.0 / s[2][2]),
            "λ = {lambda}: {force} vs {blocked}"
        );
    }
}
