//! The classical solutions of indentation (model §14), for tests and for users who compare:
//! a rigid axisymmetric indenter pressed a depth δ into an elastic half-space with the
//! indentation modulus E* (E/(1 − ν²) for an isotropic solid).
//!
//! ```text
//! Hertz (ball, radius R):         a = √(Rδ),            P = (4/3) E* √R δ^{3/2},  p0 = 3P/(2πa²)
//! Sneddon (cone, half-angle α):   a = (2/π) δ tan α,    P = (2/π) E* tan α δ²
//! Boussinesq (flat punch, b):     a = b,                P = 2 b E* δ
//! ```
//!
//! A transversely isotropic solid whose axis is normal to its surface has, in place of E*,
//! the modulus of Delafargue and Ulm:
//!
//! ```text
//! M = 2 √( (c11 c33 − c13²)/c11 / (1/c44 + 2/(√(c11 c33) + c13)) )
//! ```
//!
//! A transversely isotropic **piezoelectric** half-space poled along its axis keeps Hertz's
//! form P = (4/3) C* √R δ^{3/2} (Giannakopoulos and Suresh; Karapetian, Kachanov and
//! Kalinin): its surface Green's function in Fourier space is M/|k|, a constant 2 × 2 matrix
//! relating (u_z, ϕ) to (p, q) at the surface. With p the pressure and q the surface charge,
//!
//! ```text
//! insulating indenter (q = 0):         C* = 2/M11,       ϕ = (M21/M11) u_z on the surface
//! conducting, grounded indenter (ϕ=0): C* = 2 (M⁻¹)11
//! ```
//!
//! M comes from the plane problem e^{ikx − k s z} in the half-space z ≥ 0 (z the depth): the
//! equilibrium and Gauss's law give K(s) a = 0 for a = (u_x/i, u_z, ϕ), det K(s) a cubic in
//! s²; its three roots with Re s > 0, their null vectors, and the surface conditions
//! σ_xz = 0, σ_zz = −p, D_z = q fix the combination.

use crate::error::{Error, Result};
use crate::material::{Elastic, Material};
use faer::c64;
use std::f64::consts::PI;

/// A force–depth point of a classical solution.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Indentation {
    /// The force P [stress·length²].
    pub force: f64,
    /// The radius a of the contact disc \[length\].
    pub radius: f64,
    /// The mean pressure P/(πa²) \[stress\].
    pub mean_pressure: f64,
}

impl Indentation {
    fn new(force: f64, radius: f64) -> Self {
        Self { force, radius, mean_pressure: force / (PI * radius * radius) }
    }
}

/// E* = E/(1 − ν²) of an isotropic solid \[stress\].
pub fn plane_strain_modulus(young: f64, poisson: f64) -> f64 {
    young / (1.0 - poisson * poisson)
}

/// Hertz: a rigid ball of radius `radius` pressed `depth` into a half-space of modulus
/// `modulus` (E*). The largest pressure is 3/2 of the mean.
pub fn hertz(modulus: f64, radius: f64, depth: f64) -> Indentation {
    let a = (radius * depth).sqrt();
    Indentation::new(4.0 / 3.0 * modulus * radius.sqrt() * depth.powf(1.5), a)
}

/// Sneddon: a rigid cone of half-angle `half_angle` \[rad\] pressed `depth` into a half-space
/// of modulus `modulus` (E*).
pub fn sneddon(modulus: f64, half_angle: f64, depth: f64) -> Indentation {
    let tan = half_angle.tan();
    Indentation::new(2.0 / PI * modulus * tan * depth * depth, 2.0 / PI * depth * tan)
}

/// Boussinesq: a rigid flat punch of radius `radius` pressed `depth` into a half-space of
/// modulus `modulus` (E*).
pub fn boussinesq(modulus: f64, radius: f64, depth: f64) -> Indentation {
    Indentation::new(2.0 * radius * modulus * depth, radius)
}

/// Delafargue and Ulm's indentation modulus of a transversely isotropic solid whose axis (3)
/// is normal to the surface, from its stiffnesses c11, c13, c33, c44 \[stress\].
pub fn transversely_isotropic_modulus(c11: f64, c13: f64, c33: f64, c44: f64) -> f64 {
    let stiffness = (c11 * c33 - c13 * c13) / c11;
    let compliance = 1.0 / c44 + 2.0 / ((c11 * c33).sqrt() + c13);
    2.0 * (stiffness / compliance).sqrt()
}

/// A transversely isotropic piezoelectric solid, its axis normal to the indented surface
/// and its poling along the surface's outward normal (out of the body) — a block poled along
/// z indented on its top face [stress, charge/length², charge/(potential·length)].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Piezoelectric {
    pub c11: f64,
    pub c13: f64,
    pub c33: f64,
    pub c44: f64,
    pub e31: f64,
    pub e33: f64,
    pub e15: f64,
    pub eps11: f64,
    pub eps33: f64,
}

/// The indentation moduli of a piezoelectric half-space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PiezoelectricIndentation {
    /// C* under an insulating indenter \[stress\].
    pub insulating: f64,
    /// C* under a conducting, grounded indenter \[stress\].
    pub conducting: f64,
    /// ϕ/δ on the surface under an insulating indenter, δ the displacement into the body
    /// [potential/length].
    pub potential_ratio: f64,
    /// The Green's matrix M: (u_z, ϕ) = M (p, q)/|k| [length/stress ...].
    pub green: [[f64; 2]; 2],
}

impl Piezoelectric {
    /// The constants of `material` (isotropic elasticity at small strain, µ1 and k0, or the
    /// stiffness tensor's c11, c13, c33, c44; the piezoelectric and dielectric constants of its
    /// poling axis, the last), read as those of a material transversely isotropic about it.
    pub fn of(material: &Material) -> Self {
        let (p, e, beta) = (material.dim - 1, &material.e, &material.beta);
        let [c11, c13, c33, c44] = match &material.elastic {
            Elastic::Isotropic(el) => {
                let (k0, mu) = (el.k0, el.mu1);
                [k0 + 4.0 / 3.0 * mu, k0 - 2.0 / 3.0 * mu, k0 + 4.0 / 3.0 * mu, mu]
            }
            Elastic::Anisotropic(c) => [c[0][0][0][0], c[0][0][p][p], c[p][p][p][p], c[0][p][0][p]],
        };
        Self {
            c11,
            c13,
            c33,
            c44,
            e31: e[p][0][0],
            e33: e[p][p][p],
            e15: e[0][0][p],
            eps11: beta[0][0],
            eps33: beta[p][p],
        }
    }

    /// The equations K(s) a = 0 of the mode e^{ikx − k s z}, z the depth, for the constants
    /// in that frame (`e` with the poling along +z, into the body).
    fn modes(&self, e: [f64; 3], s: c64) -> [[c64; 3]; 3] {
        let Self { c11, c13, c33, c44, eps11, eps33, .. } = *self;
        let [e31, e33, e15] = e;
        let r = |v: f64| c64::new(v, 0.0);
        let s2 = s * s;
        [
            [r(c44) * s2 - r(c11), -s * r(c13 + c44), -s * r(e31 + e15)],
            [s * r(c13 + c44), r(c33) * s2 - r(c44), r(e33) * s2 - r(e15)],
            [s * r(e15 + e31), r(e33) * s2 - r(e15), r(eps11) - r(eps33) * s2],
        ]
    }

    /// det K(s) as a cubic in t = s²: its coefficients, highest first, by interpolation at
    /// t = 0, 1, 2, 3.
    fn characteristic(&self, e: [f64; 3]) -> [f64; 4] {
        let det = |t: f64| det3(self.modes(e, c64::new(t, 0.0).sqrt())).re;
        let y = [det(0.0), det(1.0), det(2.0), det(3.0)];
        // Newton's forward differences of a cubic on 0, 1, 2, 3.
        let d1 = [y[1] - y[0], y[2] - y[1], y[3] - y[2]];
        let d2 = [d1[1] - d1[0], d1[2] - d1[1]];
        let d3 = d2[1] - d2[0];
        let a = d3 / 6.0;
        let b = d2[0] / 2.0 - 3.0 * a;
        let c = d1[0] - a - b;
        [a, b, c, y[0]]
    }

    /// The indentation moduli (module docs). An error when the roots of the characteristic
    /// equation are not three distinct ones with Re s > 0 (an isotropic elasticity without
    /// coupling has a double root: perturb it slightly).
    pub fn indentation(&self) -> Result<PiezoelectricIndentation> {
        // The poling out of the body is −z in the frame of the depth z.
        let e = [-self.e31, -self.e33, -self.e15];
        let [a, b, c, d] = self.characteristic(e);
        let roots = cubic_roots([a, b, c, d])?;
        let s: Vec<c64> = roots
            .iter()
            .map(|t| {
                let s = t.sqrt();
                if s.re < 0.0 { -s } else { s }
            })
            .collect();
        let fail = |what: &str| Error::InvalidParameter {
            name: "piezoelectric constants".into(),
            value: format!("{self:?}"),
            requirement: format!("a half-space whose characteristic roots are {what}"),
        };
        if s.iter().any(|v| v.re <= 0.0) {
            return Err(fail("all off the imaginary axis"));
        }
        let distinct =
            (0..3).all(|i| (i + 1..3).all(|j| (s[i] - s[j]).norm() > 1e-6 * s[i].norm()));
        if !distinct {
            return Err(fail("distinct"));
        }
        let vectors: Vec<[c64; 3]> = s.iter().map(|&sj| null_vector(self.modes(e, sj))).collect();
        let (c13, c33, c44) =
            (c64::new(self.c13, 0.0), c64::new(self.c33, 0.0), c64::new(self.c44, 0.0));
        let [e31, e33, e15] = e.map(|v| c64::new(v, 0.0));
        let eps33 = c64::new(self.eps33, 0.0);
        // Rows: σ_xz/(ik), σ_zz/k, D_z/k at z = 0 per unit amplitude of each mode.
        let mut surface = [[c64::new(0.0, 0.0); 3]; 3];
        for (j, (&sj, v)) in s.iter().zip(&vectors).enumerate() {
            let [vx, uz, phi] = *v;
            surface[0][j] = -c44 * sj * vx + c44 * uz + e15 * phi;
            surface[1][j] = -c13 * vx - c33 * sj * uz - e33 * sj * phi;
            surface[2][j] = -e31 * vx - e33 * sj * uz + eps33 * sj * phi;
        }
        // (u_z, ϕ) for a unit p (σ_zz = −p) and a unit q (D_z = q), per 1/k.
        let mut green = [[0.0; 2]; 2];
        for (column, rhs) in [[0.0, -1.0, 0.0], [0.0, 0.0, 1.0]].iter().enumerate() {
            let amplitudes = solve3(surface, rhs.map(|v| c64::new(v, 0.0)));
            for (row, k) in [1, 2].into_iter().enumerate() {
                let value: c64 = (0..3).map(|j| amplitudes[j] * vectors[j][k]).sum();
                green[row][column] = value.re;
            }
        }
        let [[m11, m12], [m21, m22]] = green;
        let inverse11 = m22 / (m11 * m22 - m12 * m21);
        Ok(PiezoelectricIndentation {
            insulating: 2.0 / m11,
            conducting: 2.0 * inverse11,
            potential_ratio: m21 / m11,
            green,
        })
    }
}

/// The determinant of a complex 3 × 3 matrix.
fn det3(m: [[c64; 3]; 3]) -> c64 {
    m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
}

/// x with m x = b, by Cramer's rule.
fn solve3(m: [[c64; 3]; 3], b: [c64; 3]) -> [c64; 3] {
    let det = det3(m);
    [0, 1, 2].map(|k| {
        let mut mk = m;
        (0..3).for_each(|i| mk[i][k] = b[i]);
        det3(mk) / det
    })
}

/// A null vector of a singular 3 × 3 matrix: the largest cross product of two of its rows.
fn null_vector(m: [[c64; 3]; 3]) -> [c64; 3] {
    let cross = |a: [c64; 3], b: [c64; 3]| {
        [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
    };
    let size = |v: &[c64; 3]| v.iter().map(|x| x.norm_sqr()).sum::<f64>();
    [cross(m[0], m[1]), cross(m[1], m[2]), cross(m[0], m[2])]
        .into_iter()
        .max_by(|a, b| size(a).total_cmp(&size(b)))
        .unwrap_or_default()
}

/// The roots of a t³ + b t² + c t + d, the eigenvalues of its companion matrix.
fn cubic_roots([a, b, c, d]: [f64; 4]) -> Result<Vec<c64>> {
    let companion = faer::mat![[-b / a, -c / a, -d / a], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    companion
        .eigenvalues()
        .map_err(|e| Error::LinearAlgebra(format!("the characteristic roots: {e:?}")))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The three laws against their relations in terms of the contact radius: Hertz's
    /// P = 4E*a³/(3R) with a = √(Rδ), Sneddon's P = (π/2) E* a² cot α, Boussinesq's stiffness
    /// dP/dδ = 2aE*, and their powers of δ; the transversely isotropic modulus reduces to
    /// E/(1 − ν²) for isotropic stiffnesses.
    #[test]
    fn the_classical_solutions_hold_their_relations() {
        let (e_star, r, d) = (70.0, 2.0, 0.01);
        let h = hertz(e_star, r, d);
        assert!((h.radius - (r * d).sqrt()).abs() < 1e-15);
        assert!((hertz(e_star, r, 4.0 * d).force / h.force - 8.0).abs() < 1e-12);
        // Hertz: P = 4 E* a³ / (3R).
        assert!((h.force - 4.0 * e_star * h.radius.powi(3) / (3.0 * r)).abs() < 1e-12 * h.force);
        let alpha = 70f64.to_radians();
        let s = sneddon(e_star, alpha, d);
        // Sneddon: P = (π/2) E* a² cot α.
        let p = PI / 2.0 * e_star * s.radius.powi(2) / alpha.tan();
        assert!((s.force - p).abs() < 1e-12 * p);
        assert!((sneddon(e_star, alpha, 2.0 * d).force / s.force - 4.0).abs() < 1e-12);
        let b = boussinesq(e_star, 0.3, d);
        assert!((b.force / d - 2.0 * 0.3 * e_star).abs() < 1e-12);
        // Isotropic stiffnesses: c11 = c33 = λ + 2µ, c13 = λ, c44 = µ.
        let (young, poisson) = (58.7, 0.39);
        let lambda = young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
        let mu = young / (2.0 * (1.0 + poisson));
        let m = transversely_isotropic_modulus(lambda + 2.0 * mu, lambda, lambda + 2.0 * mu, mu);
        let e = plane_strain_modulus(young, poisson);
        assert!((m - e).abs() < 1e-12 * e, "{m} against {e}");
    }

    /// PZT-5A of the paper's Table 1 (GPa, C/m², C/(GV·m)) with its isotropic elasticity
    /// made transversely isotropic by `stiffer` on c33.
    fn pzt(stiffer: f64, coupling: f64) -> Piezoelectric {
        let (young, poisson) = (58.7102, 0.3912);
        let lambda = young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
        let mu = young / (2.0 * (1.0 + poisson));
        Piezoelectric {
            c11: lambda + 2.0 * mu,
            c13: lambda,
            c33: (lambda + 2.0 * mu) * stiffer,
            c44: mu,
            e31: -5.4 * coupling,
            e33: 15.8 * coupling,
            e15: 12.3 * coupling,
            eps11: 916.0 * 8.885e-3,
            eps33: 830.0 * 8.885e-3,
        }
    }

    /// The characteristic cubic det K(s) equals, up to a factor, the closed form a t³ − b t²
    /// + c t − d of the literature (t = s²) for every coefficient.
    #[test]
    fn the_characteristic_equation_is_the_literature_s() {
        let m = pzt(1.3, 1.0);
        let (c11, c13, c33, c44) = (m.c11, m.c13, m.c33, m.c44);
        let (e31, e33, e15, eps11, eps33) = (m.e31, m.e33, m.e15, m.eps11, m.eps33);
        let a = c44 * (c33 * eps33 + e33 * e33);
        let b = c11 * (c33 * eps33 + e33 * e33)
            + c44 * (c33 * eps11 - 2.0 * e31 * e33)
            + c33 * (e15 + e31).powi(2)
            - 2.0 * c13 * e33 * (e15 + e31)
            - c13 * (c13 + 2.0 * c44) * eps33;
        let c = c11 * c33 * eps11 + c11 * c44 * eps33 + 2.0 * c11 * e15 * e33
            - c13 * (c13 + 2.0 * c44) * eps11
            - 2.0 * c13 * e15 * (e15 + e31)
            + c44 * e31 * e31;
        let d = c11 * (c44 * eps11 + e15 * e15);
        let ours = m.characteristic([m.e31, m.e33, m.e15]);
        let factor = ours[0] / a;
        for (k, theirs) in [a, -b, c, -d].iter().enumerate() {
            let relative = (ours[k] - factor * theirs).abs() / (factor * theirs).abs();
            assert!(relative < 1e-10, "coefficient {k}: {} against {}", ours[k], factor * theirs);
        }
    }

    /// Without coupling: the insulating and the conducting moduli are Delafargue and Ulm's
    /// (and E/(1 − ν²) for a nearly isotropic elasticity), ϕ does not follow u_z, and the
    /// dielectric part of M is 1/√(ε11 ε33). With PZT-5A's coupling: the insulating indenter
    /// meets a stiffer solid than the grounded one, and both exceed the uncoupled modulus.
    #[test]
    fn the_piezoelectric_moduli_reduce_to_the_elastic_ones() {
        let uncoupled = pzt(1.3, 0.0);
        let i = uncoupled.indentation().unwrap();
        let m = transversely_isotropic_modulus(
            uncoupled.c11,
            uncoupled.c13,
            uncoupled.c33,
            uncoupled.c44,
        );
        assert!(
            (i.insulating / m - 1.0).abs() < 1e-9 && (i.conducting / m - 1.0).abs() < 1e-9,
            "{i:?} against {m}"
        );
        assert!(i.potential_ratio.abs() < 1e-12 && i.green[0][1].abs() < 1e-12, "{i:?}");
        let dielectric = 1.0 / (uncoupled.eps11 * uncoupled.eps33).sqrt();
        assert!((i.green[1][1] / dielectric - 1.0).abs() < 1e-9, "{i:?}");
        let isotropic = pzt(1.0 + 1e-7, 0.0).indentation().unwrap();
        let e_star = plane_strain_modulus(58.7102, 0.3912);
        assert!(
            (isotropic.insulating / e_star - 1.0).abs() < 1e-5,
            "{isotropic:?} against {e_star}"
        );
        let coupled = pzt(1.0, 1.0).indentation().unwrap();
        println!("PZT-5A: {coupled:?}, E* = {e_star}");
        assert!(
            coupled.insulating > coupled.conducting && coupled.conducting > e_star,
            "{coupled:?}"
        );
    }
}
