//! `check`'s data sheet of each material: both forms of its constants in its own axes, g, and
//! for a material transversely isotropic about its poling the coupling factors and the
//! indentation moduli of its half-space indented along the poling.

use crate::print::indentation_moduli;
use crate::say;
use piezocontact::case::{Built, Case};
use piezocontact::material::voigt::{self, Matrix3};
use piezocontact::material::{Constants, Material, NamedMaterial, orientation};

/// Prints the data sheet of every material of `case`, in the case's units.
pub fn data_sheets(case: &Case, built: &Built) -> piezocontact::Result<()> {
    let u = &built.units;
    let (s, q, v, l) = (&u.stress, &u.charge, &u.potential, &u.length);
    let names = built.problem.materials.list();
    for (named, constants) in names.iter().zip(case.material_constants()?) {
        say!(
            "material '{}' in its own axes (Voigt order xx, yy, zz, yz, xz, xy; engineering shear strains):",
            named.name
        );
        let c = constants.elastic.stiffness();
        let (compliance, d, eps_t) =
            voigt::strain_charge(&c, &constants.e, &constants.permittivity)?;
        let permittivity = format!("{q}/({v}·{l})");
        rows(&format!("c^E [{s}]"), &c);
        rows(&format!("e [{q}/{l}²]"), &constants.e);
        rows(&format!("ε^S [{permittivity}]"), &constants.permittivity);
        rows(&format!("s^E [1/{s}]"), &compliance);
        rows(&format!("d [{q}/({s}·{l}²)]"), &d);
        rows(&format!("ε^T [{permittivity}]"), &eps_t);
        let g = voigt::product(&voigt::inverse(&eps_t)?, &d);
        rows(&format!("g = (ε^T)⁻¹ d [{v}·{l}/({s}·{l}²)]"), &g);
        coupling_and_moduli(named, &constants, (&compliance, &d, &eps_t), built)?;
    }
    Ok(())
}

/// k33, k31, k15 and the indentation moduli along the poling, where the material is
/// transversely isotropic about its axis 3.
fn coupling_and_moduli(
    named: &NamedMaterial,
    constants: &Constants,
    (s, d, eps_t): (&voigt::Voigt, &voigt::Coupling, &Matrix3),
    built: &Built,
) -> piezocontact::Result<()> {
    let own = Material::from_constants(3, constants, &orientation::IDENTITY)?;
    if !own.is_transversely_isotropic() {
        say!(
            "  no closed form is given: the material is not transversely isotropic about its axis 3"
        );
        return Ok(());
    }
    let k = |d: f64, s: f64, eps: f64| if d == 0.0 { 0.0 } else { d / (s * eps).sqrt() };
    say!(
        "  coupling factors: k33 = {:.4}, k31 = {:.4}, k15 = {:.4}",
        k(d[2][2], s[2][2], eps_t[2][2]),
        k(d[2][0], s[0][0], eps_t[2][2]),
        k(d[0][4], s[4][4], eps_t[0][0])
    );
    let along_poling = NamedMaterial { name: named.name.clone(), material: own };
    indentation_moduli(&along_poling, &built.units);
    Ok(())
}

/// Prints a matrix under its label, one row per line.
fn rows<const R: usize, const C: usize>(label: &str, m: &[[f64; C]; R]) {
    say!("  {label}:");
    for row in m {
        let cells: Vec<String> = row.iter().map(|x| format!("{x:>12.5e}")).collect();
        say!("    {}", cells.join(" "));
    }
}
