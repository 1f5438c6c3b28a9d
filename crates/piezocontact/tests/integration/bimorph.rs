//! Bimorphs in plane stress: two piezoelectric layers of thickness h/2 poled along ±y on a
//! beam [0, L] × [−h/2, h/2] clamped at x = 0, bent by a voltage through electrodes on the
//! outer faces and on the middle line inside the body, against beam theory.
//!
//! In each layer σ = σ_xx alone (plane stress, beam theory): ε_xx = s11 σ + d31 E_3 and
//! D_3 = d31 σ + ε^T33 E_3. Smits's tip deflection w = 3 d31 V L²/(2 h²) (series, V across
//! both layers) neglects the direct effect; with it, D_3 is constant across each layer (no
//! free charge inside), so E_3 varies with the bending strain and the curvature falls by
//! 1 + k31²/(4(1 − k31²)), k31² = d31²/(s11^E ε^T33) — the expected values below, computed from
//! the material's constants. The curvature is read from the mid-line deflection's second
//! difference at L/4, L/2, 3L/4, away from both ends; the clamp (u = 0 on the end face holds
//! the layers' free strains) and the free end's self-equilibrated stresses add zones of
//! length O(h), which the tip deflection feels as an O(h/L) error.

use super::common::{EPS0, committed_case, run_with, solve_static};
use super::materials::{C, D, E, S, strain_charge};
use piezocontact::linalg::default_solver;
use piezocontact::material::voigt;
use piezocontact::run::Run;

/// A two-layer beam: length L and thickness h [m], the `[material]` body of both layers and
/// the y component of each layer's poling (upper, lower).
struct Beam {
    length: f64,
    thickness: f64,
    material: String,
    poles: [f64; 2],
}

impl Beam {
    /// The case on an nx × ny grid, clamped at x = 0, with the `[boundary]` lines
    /// `electrodes` on the parts top, bottom and middle (the line y = 0, inside the body).
    fn case(&self, (nx, ny): (usize, usize), electrodes: &str) -> String {
        let (l, t) = (self.length, self.thickness / 2.0);
        let b = -t;
        let layer = |name: &str, pole: f64| {
            format!(
                "[[material]]\nname = \"{name}\"\nregions = [\"{name}\"]\npoling = [0.0, {pole}]\n{}\n",
                self.material
            )
        };
        format!(
            "[mesh]\nx = [0.0, {l}]\ny = [{b}, {t}]\nnx = {nx}\nny = {ny}\nplane = \"stress\"\n\
             [mesh.segments]\nclamp = [\"{{0}}x[{b}, {t}]\"]\ntop = [\"[0,{l}]x{{{t}}}\"]\n\
             bottom = [\"[0,{l}]x{{{b}}}\"]\nmiddle = [\"[0,{l}]x{{0}}\"]\n\
             [mesh.regions]\nupper = [\"[0,{l}]x[0,{t}]\"]\nlower = [\"[0,{l}]x[{b},0]\"]\n{}{}\
             [boundary]\nclamped = [\"clamp\"]\n{electrodes}",
            layer("upper", self.poles[0]),
            layer("lower", self.poles[1]),
        )
    }

    /// The curvature κ = −w'' from the mid-line deflection w = u_y at L/4, L/2 and 3L/4, and
    /// the tip's deflection w(L), on an nx × ny grid (nx a multiple of 4, ny even).
    fn bend(&self, grid: (usize, usize), electrodes: &str) -> (f64, f64) {
        let (built, run) = solve_static(&self.case(grid, electrodes));
        let mesh = &built.problem.mesh;
        let w = |x: f64| {
            let near = |n: &usize| (mesh.node(*n)[0] - x).abs() + mesh.node(*n)[1].abs();
            let node = (0..mesh.n_nodes()).find(|n| near(n) < 1e-9 * self.length).unwrap();
            run.solution.x[run.solution.dofs.u(node, 1)]
        };
        let l = self.length;
        let step = l / 4.0;
        (-(w(step) - 2.0 * w(2.0 * step) + w(3.0 * step)) / (step * step), w(l))
    }

    /// κ and the tip deflection on three grids, each halving the last's cells.
    fn refined(&self, coarse: (usize, usize), electrodes: &str) -> [(f64, f64); 3] {
        [1, 2, 4].map(|k| self.bend((coarse.0 * k, coarse.1 * k), electrodes))
    }
}

/// The limit of a quantity on three grids, each halving the last's cells, whose error
/// falls as h^p: the rate p measured from the three, and the limit extrapolated with it.
fn richardson([a, b, c]: [f64; 3]) -> (f64, f64) {
    let p = ((a - b) / (b - c)).log2();
    (p, c + (c - b) / (2f64.powf(p) - 1.0))
}

/// The direct effect's factor on Smits's curvature: 1/(1 + k²/(4(1 − k²))).
fn direct_effect(k2: f64) -> f64 {
    1.0 / (1.0 + k2 / (4.0 * (1.0 - k2)))
}

/// The series connection: the bottom grounded, the top at `volts`, the middle electrode
/// floating with no charge (layers poled opposite).
fn series(volts: f64) -> String {
    format!(
        "grounded = [\"bottom\"]\n[[boundary.electrode]]\nname = \"drive\"\nparts = [\"top\"]\n\
         voltage = {volts}\n[[boundary.electrode]]\nname = \"mid\"\nparts = [\"middle\"]\ncharge = 0.0\n"
    )
}

/// A PZT-5A series bimorph, L/h = 12 and 24: the curvature converges at rate 2 (the P1
/// triangles' bending error, (cell/h)²) to Smits's with the direct effect, k31² = 0.118 here:
/// 3.4 % below Smits's, which the extrapolation tells apart to 0.1 %. The tip deflection
/// differs from the beam's by the clamp's zone, an error that halves as L/h doubles.
#[test]
fn a_series_bimorph_bends_as_smits_with_the_direct_effect() {
    let volts = 1e-3;
    let (d31, s11, eps_t33) = (D[2][0], S[0][0], 1700.0 * EPS0);
    let k2 = d31 * d31 / (s11 * eps_t33);
    let smits = -3.0 * d31 * volts;
    let mut tip_errors = Vec::new();
    for length in [12.0, 24.0] {
        let beam = Beam { length, thickness: 1.0, material: strain_charge(), poles: [1.0, -1.0] };
        let runs = beam.refined((8 * length as usize, 8), &series(volts));
        let (rate, kappa) = richardson(runs.map(|r| r.0));
        assert!((1.8..2.2).contains(&rate), "L/h = {length}: rate {rate}");
        let expected = smits * direct_effect(k2);
        let error = (kappa - expected) / expected;
        assert!(error.abs() < 1e-3, "L/h = {length}: κ {kappa} vs {expected} ({error:e})");
        assert!((kappa - smits).abs() > 0.025 * smits.abs(), "κ {kappa}, Smits {smits}");
        let (_, tip) = richardson(runs.map(|r| r.1));
        let beam_tip = -expected * length * length / 2.0;
        tip_errors.push((tip - beam_tip) / beam_tip);
    }
    let ratio = tip_errors[0] / tip_errors[1];
    assert!((1.7..2.3).contains(&ratio), "the clamp zone's tip errors {tip_errors:?}");
}

/// A PZT-5A parallel bimorph: both layers poled along +y, the outer faces grounded and the
/// middle electrode (inside the body) at V, so that each layer takes V: twice the series
/// curvature, 6 d31 V/h² with the same direct effect.
#[test]
fn a_parallel_bimorph_driven_through_its_middle_electrode_bends_twice_as_much() {
    let volts = 1e-3;
    let (d31, s11, eps_t33) = (D[2][0], S[0][0], 1700.0 * EPS0);
    let k2 = d31 * d31 / (s11 * eps_t33);
    let beam = Beam { length: 12.0, thickness: 1.0, material: strain_charge(), poles: [1.0, 1.0] };
    let parallel = format!(
        "grounded = [\"bottom\", \"top\"]\n[[boundary.electrode]]\nname = \"mid\"\n\
         parts = [\"middle\"]\nvoltage = {volts}\n"
    );
    let runs = beam.refined((96, 8), &parallel);
    let (rate, kappa) = richardson(runs.map(|r| r.0));
    assert!((1.8..2.2).contains(&rate), "rate {rate}");
    let expected = 6.0 * d31 * volts * direct_effect(k2);
    let error = (kappa - expected) / expected;
    assert!(error.abs() < 1e-3, "κ {kappa} vs {expected} ({error:e})");
}

/// The PVDF bimorph of the literature: L = 100 mm, h = 1 mm, d31 = 22 pC/N, 1 V in series,
/// Smits's tip deflection 3 d31 V L²/(2 h²) = 0.330 µm. PVDF's k31² = 0.011 takes 0.29 % off
/// it. The tip deflection extrapolated from three grids (cells h/8 to h/32, rate 1.92) is
/// 0.3289 µm: 0.34 % below Smits's, 0.06 % below the beam's with the direct effect (the
/// clamp's zone, at L/h = 100).
#[test]
fn the_pvdf_bimorph_benchmark_deflects_a_third_of_a_micrometre() {
    let d = "[[0.0, 0.0, 0.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0, 0.0, 0.0], [0.022, 0.003, -0.033, 0.0, 0.0, 0.0]]";
    let (young, eps_t33) = (2.5, 12.0 * EPS0);
    let material = format!(
        "law = \"linear\"\nyoung = {young}\npoisson = 0.34\nd = {d}\neps0 = {EPS0}\neps_rel = [12.0, 12.0, 12.0]"
    );
    let beam = Beam { length: 0.1, thickness: 1e-3, material, poles: [1.0, -1.0] };
    let volts = 1e-9;
    let runs = beam.refined((800, 8), &series(volts));
    let (rate, tip) = richardson(runs.map(|r| r.1));
    assert!((1.8..2.2).contains(&rate), "rate {rate}");
    let k2 = 0.022 * 0.022 * young / eps_t33;
    let beam_tip = 1.5 * 0.022 * volts * 0.1f64.powi(2) / 1e-6 * direct_effect(k2);
    assert!((tip - beam_tip).abs() < 2e-3 * beam_tip, "tip {tip} m vs the beam's {beam_tip}");
    assert!((tip - 0.33e-6).abs() < 5e-3 * 0.33e-6, "tip {tip} m");
}

/// cases/bimorph.toml (Berlincourt's PZT-5A: c^E, e, ε^S, those of this file; 20 mm × 0.5 mm,
/// 100 V): at each step of the ramp the floating middle takes half the drive and no charge,
/// and the last step's tip deflection is the beam's with the direct effect (d31 = (e s^E)31,
/// ε^T33 = ε^S33 + Σ d3k e3k, k31² = 0.12), less 1.9 % of mesh and clamp (asserted within
/// 1.5–2.5 %), in µm.
#[test]
fn the_committed_bimorph_bends_as_beam_theory_says() {
    let built = committed_case("bimorph.toml", &[]).build().unwrap();
    let Run::StaticPath(path) = run_with(&built, default_solver()) else {
        panic!("not a loading path without contact")
    };
    for row in &path.curve {
        let drive = 100.0 * row.load_factor;
        assert!((row.potentials[1] - drive / 2.0).abs() < 1e-4 * drive, "{:?}", row.potentials);
        assert!(row.charges[2].abs() < 1e-9 * row.charges[1].abs(), "{:?}", row.charges);
    }
    let s = voigt::inverse(&C).unwrap();
    let d = voigt::product(&E, &s);
    let eps_t33 = 830.0 * EPS0 + (0..6).map(|k| d[2][k] * E[2][k]).sum::<f64>();
    let (d31, k2) = (d[2][0] * 1e-9, d[2][0] * d[2][0] / (s[0][0] * eps_t33));
    let beam_tip = 1.5 * d31.abs() * 100.0 * 0.02f64.powi(2) / 5e-4f64.powi(2) * 1e6;
    let shortfall = 1.0 - path.last.max_u / (beam_tip * direct_effect(k2));
    assert!((0.015..0.025).contains(&shortfall), "{} µm vs {beam_tip} µm", path.last.max_u);
}
