//! Case files: TOML, every key documented, unknown keys rejected with their name and line.
//! Every default lives here, once; every error names the file, the line of the key and the fix
//! ([`Error::Input`]).
//!
//! [`CaseFile`] is the raw serde view of the file (ripgrep's "low args"); [`Case::problem`]
//! turns it into a checked [`Problem`]. `--set dotted.key=value` edits the document before it
//! is read, so an override is checked exactly like the file.

use crate::algorithm::{ContactModel, Method, Settings};
use crate::contact::Foundation;
use crate::contact::law::{Conduction, Friction, NormalCompliance, Regularization};
use crate::error::{Error, Result};
use crate::material::{ElasticLaw, Elasticity, Material, PermittivityConstants, PiezoConstants};
use crate::mesh::rectangle::{Diagonal, Rectangle, Segment};
use crate::mesh::{Mesh, gmsh};
use crate::problem::{BodyLoads, Boundary, Problem, constant_scalar, constant_vector};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// An [`Error::Input`] with a formatted message.
macro_rules! input {
    ($($arg:tt)*) => { Error::Input(format!($($arg)*)) };
}

/// The case's consistent unit system, used for labels only (model §9): the numbers in the file
/// are in these units and no conversion happens.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Units {
    /// Unit of length (coordinates, displacements), e.g. "m".
    #[serde(default = "default_length")]
    pub length: String,
    /// Unit of stress (E, σ, tractions), e.g. "GPa".
    #[serde(default = "default_stress")]
    pub stress: String,
    /// Unit of electric charge, e.g. "C".
    #[serde(default = "default_charge")]
    pub charge: String,
    /// Unit of electric potential (ϕ, ϕ0), e.g. "GV".
    #[serde(default = "default_potential")]
    pub potential: String,
}

fn default_length() -> String {
    "m".into()
}
fn default_stress() -> String {
    "Pa".into()
}
fn default_charge() -> String {
    "C".into()
}
fn default_potential() -> String {
    "V".into()
}

impl Default for Units {
    fn default() -> Self {
        Self {
            length: default_length(),
            stress: default_stress(),
            charge: default_charge(),
            potential: default_potential(),
        }
    }
}

/// `[mesh]`: a structured rectangle (x, y, nx, ny, diagonal, segments) or a Gmsh file.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshSection {
    /// Gmsh MSH 4.1 file, relative to the case file; replaces the rectangle.
    pub file: Option<PathBuf>,
    /// Rectangle: [x0, x1] [length].
    pub x: Option<[f64; 2]>,
    /// Rectangle: [y0, y1] [length].
    pub y: Option<[f64; 2]>,
    /// Rectangle: cells along x.
    pub nx: Option<usize>,
    /// Rectangle: cells along y.
    pub ny: Option<usize>,
    /// Rectangle: "right" (lower-left–upper-right diagonal, default) or "left".
    pub diagonal: Option<DiagonalKey>,
    /// Rectangle: boundary part name → segments such as "[0,2]x{0}".
    #[serde(default)]
    pub segments: BTreeMap<String, Vec<String>>,
}

/// Diagonal direction in the case file.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum DiagonalKey {
    Right,
    Left,
}

/// Elastic law in the case file.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum LawKey {
    Hencky,
    Linear,
}

/// `[material]`: Hencky elasticity and the piezoelectric ceramic, poled along the last axis.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSection {
    /// "hencky" (the paper's g, default) or "linear" (g ≡ µ1).
    #[serde(default = "default_law")]
    pub law: LawKey,
    /// E: Young's modulus [stress].
    pub young: f64,
    /// ν: Poisson's ratio [-].
    pub poisson: f64,
    /// t0: Hencky elasticity limit on ‖ε^D‖² [-] (paper: 1.8).
    #[serde(default = "default_t0")]
    pub t0: f64,
    /// e31 = e32 [charge/length²].
    #[serde(alias = "e32")]
    pub e31: f64,
    /// e33 [charge/length²].
    pub e33: f64,
    /// e15 = e24 [charge/length²].
    #[serde(alias = "e24")]
    pub e15: f64,
    /// ε0: vacuum permittivity [charge/(potential·length)].
    pub eps0: f64,
    /// β11/ε0 = β22/ε0: relative permittivity across the poling axis [-].
    #[serde(alias = "beta22_rel")]
    pub beta11_rel: f64,
    /// β33/ε0: relative permittivity along the poling axis [-].
    pub beta33_rel: f64,
}

fn default_law() -> LawKey {
    LawKey::Hencky
}
fn default_t0() -> f64 {
    1.8
}

/// A traction load on Γ2 parts.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TractionLoad {
    /// Boundary parts carrying it.
    pub parts: Vec<String>,
    /// f2: traction density, d components [stress].
    pub f2: Vec<f64>,
}

/// A surface charge on Γb parts.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ChargeLoad {
    /// Boundary parts carrying it.
    pub parts: Vec<String>,
    /// q2: surface charge density [charge/length^(d−1)].
    pub q2: f64,
}

/// `[boundary]`: boundary part names by role ([P] (2.4)).
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoundarySection {
    /// Γ1: u = 0.
    #[serde(default)]
    pub clamped: Vec<String>,
    /// Γa: ϕ = 0.
    #[serde(default)]
    pub grounded: Vec<String>,
    /// Γ3: contact surface.
    #[serde(default)]
    pub contact: Vec<String>,
    /// Γ2: tractions.
    #[serde(default)]
    pub traction: Vec<TractionLoad>,
    /// Γb: surface charges.
    #[serde(default)]
    pub charge: Vec<ChargeLoad>,
}

/// `[loads]`: body loads of (2.1).
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadsSection {
    /// f0: body force density, d components [stress/length].
    pub f0: Option<Vec<f64>>,
    /// q0: volume charge density [charge/length^d].
    pub q0: Option<f64>,
}

/// Which problem of the paper a case solves.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
pub enum ProblemKey {
    /// Frictionless contact, nonconductive foundation (Algorithms 3–4).
    PV1,
    /// Regularised Coulomb friction, conductive foundation (Algorithms 1–2).
    PV2,
}

/// `[contact]`: normal compliance with finite penetration, (2.5) and model §9.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSection {
    /// "PV1" or "PV2"; default PV2 when `[friction]` or `[conductivity]` is present, else PV1.
    pub problem: Option<ProblemKey>,
    /// g_a: gap, where compliance and conduction start (the paper's ρ) [length].
    #[serde(default)]
    pub gap: f64,
    /// g_p ≥ 0: penetration before the rigid stop at u_ν = g_a + g_p [length].
    #[serde(default)]
    pub penetration: f64,
    /// c_ν > 0 of h_ν [stress/length].
    #[serde(default = "one")]
    pub c_nu: f64,
    /// α_ν > 1 of h_ν [-].
    #[serde(default = "two")]
    pub alpha_nu: f64,
    /// n_ν > 0: saturation of p_ν [length].
    #[serde(default = "one")]
    pub n_nu: f64,
    /// The potential difference at which h_ν saturates (the paper's 128) [potential].
    #[serde(default = "h_nu_range")]
    pub h_nu_range: f64,
}

/// `[friction]`: regularised Coulomb friction of (2.7); µ = 0 switches it off (PV1).
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FrictionSection {
    /// µ ≥ 0: friction coefficient [-].
    #[serde(default)]
    pub mu: f64,
    /// µ on particular Γ3 parts: part name → µ (a node on several parts takes their mean).
    #[serde(default)]
    pub mu_parts: BTreeMap<String, f64>,
    /// R: "identity" (local Coulomb, default) or "mollifier" (nonlocal, radius `radius`).
    #[serde(default)]
    pub regularization: RegularizationKey,
    /// Radius a of the mollifier [length].
    #[serde(default)]
    pub radius: f64,
}

/// The regularisation operator R in the case file.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum RegularizationKey {
    /// Local Coulomb friction.
    #[default]
    Identity,
    /// Nonlocal: a mollifier average over `friction.radius`.
    Mollifier,
}

/// `[conductivity]`: conductive foundation of (2.7)–(2.8); k_e = 0 switches it off (PV1).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConductivitySection {
    /// k_e ≥ 0: conductivity coefficient [charge/(potential·length^d)].
    #[serde(default)]
    pub ke: f64,
    /// ϕ0: potential of the foundation [potential].
    #[serde(default)]
    pub phi0: f64,
    /// δ > 0 of ψ0 [1/length].
    #[serde(default = "one")]
    pub delta: f64,
    /// L > 0: truncation of φ_L [potential].
    #[serde(default = "truncation", rename = "L")]
    pub truncation: f64,
}

impl Default for ConductivitySection {
    /// k_e = 0 (no conduction) and the defaults of the other keys.
    fn default() -> Self {
        Self { ke: 0.0, phi0: 0.0, delta: one(), truncation: truncation() }
    }
}

fn one() -> f64 {
    1.0
}
fn two() -> f64 {
    2.0
}
fn h_nu_range() -> f64 {
    128.0
}
fn truncation() -> f64 {
    1e3
}

/// The kind of foundation surface in the case file.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum FoundationKind {
    /// A rigid half-space: `point` and `normal`.
    Plane,
    /// A rigid ball (a disk in 2D), the body outside it: `center` and `radius`.
    Sphere,
}

/// `[foundation]`: the foundation's surface (model §12); without it, the gap `contact.gap`
/// is the same at every Γ3 node, as in the paper. With it, the gap of node i is the distance
/// along ν_i to the surface, plus `contact.gap`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FoundationSection {
    /// "plane" or "sphere".
    pub kind: FoundationKind,
    /// Plane: a point of it, d components [length].
    pub point: Option<Vec<f64>>,
    /// Plane: its normal, d components, out of the foundation toward the body (normalised).
    pub normal: Option<Vec<f64>>,
    /// Sphere: its centre, d components [length].
    pub center: Option<Vec<f64>>,
    /// Sphere: its radius [length].
    pub radius: Option<f64>,
}

/// The inner contact method in the case file.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum MethodKey {
    /// The exact solver: semismooth Newton on the condensed Γ3 problem (the default).
    #[default]
    Newton,
    /// Algorithms 2 and 4: augmented Lagrangian Uzawa block relaxation (the paper's).
    Uzawa,
}

/// `[solver]`: the algorithms' parameters (model §7). Defaults: [`SolverSection::DEFAULTS`].
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolverSection {
    /// The inner method: "newton" (the exact solver, default) or "uzawa" (the paper's).
    pub method: Option<MethodKey>,
    /// r > 0: Uzawa's augmented Lagrangian parameter, or Newton's complementarity constant c
    /// (which does not change the answer) [stress/length]; default 0.25 E.
    pub r: Option<f64>,
    /// ε of the Uzawa stopping rule (6.12) [-]; default 1e−4 (uzawa only).
    pub eps: Option<f64>,
    /// ε_fp of the fixed-point stopping rules (6.13), (6.15) [-]; default 1e−4 (uzawa only).
    pub eps_fp: Option<f64>,
    /// The largest KKT residual accepted [-]; default 1e−10 (newton only).
    pub tol: Option<f64>,
    /// Cap on Uzawa iterations (default 10000) or Newton steps (default 100) per outer step.
    pub max_inner: Option<usize>,
    /// Cap on fixed-point iterations; default 100.
    pub max_outer: Option<usize>,
    /// The most Γ3 nodes the exact solver condenses into its dense problem; default 2000
    /// (newton only).
    pub max_condensed: Option<usize>,
}

/// The defaults of `[solver]`, in one place.
struct SolverDefaults {
    /// r as a multiple of Young's modulus E (the paper's 0.25 E).
    r_per_young: f64,
    eps: f64,
    eps_fp: f64,
    tol: f64,
    max_uzawa: usize,
    max_newton: usize,
    max_outer: usize,
    max_condensed: usize,
}

impl SolverSection {
    /// The paper's values for Uzawa (r = 0.25 E, ε = ε_fp = 1e−4), round-off for Newton, and
    /// generous caps.
    const DEFAULTS: SolverDefaults = SolverDefaults {
        r_per_young: 0.25,
        eps: 1e-4,
        eps_fp: 1e-4,
        tol: 1e-10,
        max_uzawa: 10_000,
        max_newton: 100,
        max_outer: 100,
        max_condensed: 2000,
    };
}

/// The largest magnitude of a number in a case file, and the smallest nonzero one: the model
/// multiplies and squares its inputs, and beyond these bounds double precision overflows or
/// underflows. Every physical constant lies well inside them in any sensible units.
pub const MAGNITUDE: f64 = 1e30;
/// The smallest magnitude of a nonzero number in a case file (1/[`MAGNITUDE`]).
pub const MIN_MAGNITUDE: f64 = 1e-30;

/// `key.name`, or `name` at the top.
fn dotted(key: &str, name: &str) -> String {
    if key.is_empty() { name.to_string() } else { format!("{key}.{name}") }
}

/// A whole case file.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CaseFile {
    /// Free-text title.
    #[serde(default)]
    pub title: String,
    #[serde(default)]
    pub units: Units,
    pub mesh: MeshSection,
    pub material: MaterialSection,
    pub boundary: BoundarySection,
    #[serde(default)]
    pub loads: LoadsSection,
    pub contact: Option<ContactSection>,
    pub friction: Option<FrictionSection>,
    pub conductivity: Option<ConductivitySection>,
    pub foundation: Option<FoundationSection>,
    #[serde(default)]
    pub solver: SolverSection,
}

/// A case read from a file, with the source text kept for error locations.
#[derive(Clone, Debug)]
pub struct Case {
    /// The file it came from.
    pub path: PathBuf,
    /// The document after overrides.
    pub source: String,
    /// The parsed case.
    pub file: CaseFile,
}

impl Case {
    /// Reads `path`, applies `--set` overrides, and parses.
    pub fn load(path: &Path, overrides: &[String]) -> Result<Self> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::Io {
            what: format!("cannot read the case file {}", path.display()),
            cause: e.to_string(),
        })?;
        Self::from_text(path, &text, overrides)
    }

    /// Parses a case from text (`path` names it in messages and anchors relative mesh files).
    pub fn from_text(path: &Path, text: &str, overrides: &[String]) -> Result<Self> {
        let mut doc: toml_edit::DocumentMut =
            text.parse().map_err(|e| input!("{}: {e}", path.display()))?;
        for o in overrides {
            apply_override(&mut doc, o)?;
        }
        let source = doc.to_string();
        let file: CaseFile = toml::from_str(&source).map_err(|e| {
            let note = if overrides.is_empty() {
                String::new()
            } else {
                format!(" (after --set {})", overrides.join(", --set "))
            };
            input!("{}{note}: {e}", path.display())
        })?;
        let case = Self { path: path.to_path_buf(), source, file };
        case.check_magnitudes("", doc.as_item())?;
        Ok(case)
    }

    /// Refuses every float of `item` (at dotted key `key`) that is not finite, or whose
    /// magnitude lies outside [MIN_MAGNITUDE, MAGNITUDE] without being zero.
    fn check_magnitudes(&self, key: &str, item: &toml_edit::Item) -> Result<()> {
        let tables = |t: &toml_edit::Table| {
            t.iter().try_for_each(|(k, v)| self.check_magnitudes(&dotted(key, k), v))
        };
        match item {
            toml_edit::Item::Table(table) => tables(table),
            toml_edit::Item::Value(value) => self.check_value(key, value),
            toml_edit::Item::ArrayOfTables(array) => array.iter().try_for_each(tables),
            toml_edit::Item::None => Ok(()),
        }
    }

    /// [`Case::check_magnitudes`] for one value (arrays and inline tables too).
    fn check_value(&self, key: &str, value: &toml_edit::Value) -> Result<()> {
        match value {
            toml_edit::Value::Float(f) => {
                let v = *f.value();
                if v == 0.0 || (v.abs() <= MAGNITUDE && v.abs() >= MIN_MAGNITUDE) {
                    return Ok(());
                }
                Err(input!(
                    "{}: {key} = {v:e} is out of range: a number must be finite, and 0 or of magnitude between {MIN_MAGNITUDE:e} and {MAGNITUDE:e} (the model multiplies and squares its inputs, which would overflow or underflow double precision beyond); express it in units that make it moderate ([units])",
                    self.locate(key)
                ))
            }
            toml_edit::Value::Array(array) => {
                array.iter().try_for_each(|v| self.check_value(key, v))
            }
            toml_edit::Value::InlineTable(table) => {
                table.iter().try_for_each(|(k, v)| self.check_value(&dotted(key, k), v))
            }
            _ => Ok(()),
        }
    }

    /// "file:line" of a dotted key, for messages.
    pub fn locate(&self, dotted: &str) -> String {
        match key_line(&self.source, dotted) {
            Some(line) => format!("{}:{line}", self.path.display()),
            None => self.path.display().to_string(),
        }
    }

    /// Places an error in this case: at the line of the key it names, else in the file.
    pub fn context(&self, e: Error) -> Error {
        let location = match &e {
            Error::InvalidParameter { name, .. } => self.locate(name),
            _ => self.path.display().to_string(),
        };
        Error::Located { location, error: Box::new(e) }
    }

    /// Builds the mesh: the rectangle or the Gmsh file.
    pub fn mesh(&self) -> Result<Mesh> {
        let m = &self.file.mesh;
        if let Some(file) = &m.file {
            for (key, set) in [
                ("mesh.x", m.x.is_some()),
                ("mesh.y", m.y.is_some()),
                ("mesh.nx", m.nx.is_some()),
                ("mesh.ny", m.ny.is_some()),
                ("mesh.segments", !m.segments.is_empty()),
            ] {
                if set {
                    return Err(input!(
                        "{}: {key} describes the built-in rectangle; remove it when mesh.file is given",
                        self.locate(key)
                    ));
                }
            }
            let full = self.path.parent().unwrap_or(Path::new(".")).join(file);
            let bytes = std::fs::read(&full).map_err(|e| Error::Io {
                what: format!(
                    "{}: cannot read mesh.file {}",
                    self.locate("mesh.file"),
                    full.display()
                ),
                cause: e.to_string(),
            })?;
            return gmsh::read(&bytes).map_err(|e| input!("{}: {e}", full.display()));
        }
        let need = |key: &str| {
            input!(
                "{}: {key} is missing: give the rectangle (mesh.x, mesh.y, mesh.nx, mesh.ny) or mesh.file",
                self.path.display()
            )
        };
        let rectangle = Rectangle {
            x: m.x.ok_or_else(|| need("mesh.x"))?,
            y: m.y.ok_or_else(|| need("mesh.y"))?,
            nx: m.nx.ok_or_else(|| need("mesh.nx"))?,
            ny: m.ny.ok_or_else(|| need("mesh.ny"))?,
            diagonal: match m.diagonal {
                Some(DiagonalKey::Left) => Diagonal::Left,
                _ => Diagonal::Right,
            },
        };
        self.check_memory(rectangle.nx, rectangle.ny)?;
        let mut parts = Vec::new();
        for (name, specs) in &m.segments {
            let segments: Result<Vec<Segment>, _> = specs.iter().map(|s| s.parse()).collect();
            parts.push((
                name.clone(),
                segments.map_err(|e| {
                    input!("{}: {e}", self.locate(&format!("mesh.segments.{name}")))
                })?,
            ));
        }
        rectangle.mesh(&parts).map_err(|e| self.context(e))
    }

    /// Refuses a rectangle whose solve would not fit in memory, before allocating anything.
    /// The estimate, about 12 KB per node growing like log n with the fill of the factor, is
    /// measured on the paper's bar (1536 × 256 cells: 3.5 GB).
    fn check_memory(&self, nx: usize, ny: usize) -> Result<()> {
        let nodes = (nx as f64 + 1.0) * (ny as f64 + 1.0);
        let bytes = nodes * 12e3 * (nodes.log2() / 18.0).max(1.0);
        let available = crate::limits::available_memory();
        if bytes > available {
            return Err(input!(
                "{}: mesh.nx × mesh.ny = {nx} × {ny} cells ({nodes:.3e} nodes, {:.3e} unknowns) would need about {:.3e} GiB, and this machine has {:.1} GiB available; reduce mesh.nx and mesh.ny",
                self.locate("mesh.nx"),
                3.0 * nodes,
                bytes / 2f64.powi(30),
                available / 2f64.powi(30)
            ));
        }
        Ok(())
    }

    /// The material in dimension `dim`.
    pub fn material(&self, dim: usize) -> Result<Material> {
        let m = &self.file.material;
        let law = match m.law {
            LawKey::Hencky => ElasticLaw::Hencky { t0: m.t0 },
            LawKey::Linear => ElasticLaw::Linear,
        };
        let elasticity =
            Elasticity::from_young_poisson(m.young, m.poisson, law).map_err(|e| self.context(e))?;
        if !(m.eps0.is_finite() && m.eps0 > 0.0) {
            return Err(input!(
                "{}: material.eps0 = {} must be > 0",
                self.locate("material.eps0"),
                m.eps0
            ));
        }
        Material::new(
            dim,
            elasticity,
            PiezoConstants { e31: m.e31, e33: m.e33, e15: m.e15 },
            PermittivityConstants { beta11: m.beta11_rel * m.eps0, beta33: m.beta33_rel * m.eps0 },
        )
        .map_err(|e| self.context(e))
    }

    /// Checks the ranges of the contact, friction, conductivity and solver keys, and returns
    /// them as `(key, value)` lines for reports. The contact algorithms use them.
    pub fn contact_settings(&self) -> Result<Vec<(String, f64)>> {
        let f = &self.file;
        let mut rules: Vec<Rule> = Vec::new();
        if let Some(c) = &f.contact {
            rules.extend([
                Rule("contact.gap", c.gap, f64::is_finite, "a finite length"),
                Rule("contact.penetration", c.penetration, nonnegative, "g_p ≥ 0"),
                Rule("contact.c_nu", c.c_nu, positive, "c_ν > 0"),
                Rule("contact.alpha_nu", c.alpha_nu, |v| v.is_finite() && v > 1.0, "α_ν > 1"),
                Rule("contact.n_nu", c.n_nu, positive, "n_ν > 0"),
                Rule("contact.h_nu_range", c.h_nu_range, positive, "a positive potential"),
            ]);
        }
        if let Some(fr) = &f.friction {
            rules.push(Rule("friction.mu", fr.mu, nonnegative, "µ ≥ 0"));
            if fr.regularization == RegularizationKey::Mollifier {
                rules.push(Rule(
                    "friction.radius",
                    fr.radius,
                    positive,
                    "a mollifier radius a > 0",
                ));
            }
            for (name, &mu) in &fr.mu_parts {
                if !nonnegative(mu) {
                    return Err(input!(
                        "{}: friction.mu_parts.{name} = {mu} is not allowed: µ ≥ 0",
                        self.locate(&format!("friction.mu_parts.{name}"))
                    ));
                }
            }
        }
        if let Some(c) = &f.conductivity {
            rules.extend([
                Rule("conductivity.ke", c.ke, nonnegative, "k_e ≥ 0"),
                Rule("conductivity.phi0", c.phi0, f64::is_finite, "a finite potential"),
                Rule("conductivity.delta", c.delta, positive, "δ > 0"),
                Rule("conductivity.L", c.truncation, positive, "L > 0"),
            ]);
        }
        let settings = self.settings_unchecked();
        match settings.method {
            Method::Uzawa { r, eps, max_inner } => rules.extend([
                Rule("solver.r", r, positive, "r > 0"),
                Rule("solver.eps", eps, positive, "ε > 0"),
                Rule("solver.eps_fp", settings.eps_fp, positive, "ε_fp > 0"),
                Rule("solver.max_inner", max_inner as f64, |v| v >= 1.0, "at least 1"),
            ]),
            Method::Newton { r, tol, max_inner, max_condensed } => rules.extend([
                Rule("solver.r", r, positive, "r > 0"),
                Rule("solver.tol", tol, positive, "a tolerance > 0"),
                Rule("solver.max_inner", max_inner as f64, |v| v >= 1.0, "at least 1"),
                Rule("solver.max_condensed", max_condensed as f64, |v| v >= 1.0, "at least 1"),
            ]),
        }
        rules.push(Rule("solver.max_outer", settings.max_outer as f64, |v| v >= 1.0, "at least 1"));
        let mut lines = Vec::new();
        for Rule(key, value, ok, requirement) in rules {
            if !ok(value) {
                return Err(input!(
                    "{}: {key} = {value} is not allowed: {requirement}",
                    self.locate(key)
                ));
            }
            lines.push((key.to_string(), value));
        }
        Ok(lines)
    }

    /// The paper's hypotheses (h1)–(h6) checked on this case's data, as warnings with the
    /// numbers (Section 2 of [P]); an empty list when all hold.
    pub fn hypothesis_warnings(&self, material: &Material) -> Vec<String> {
        let el = material.elasticity;
        let d = material.dim as f64;
        let mut warnings = Vec::new();
        if el.mu1 > 0.5 * d * el.k0 {
            warnings.push(format!(
                "(h1)(a) fails: g(0) = µ1 = {:.4e} exceeds d·k0/2 = {:.4e} (Poisson's ratio {} is below the bound of (h1)(a) in {}D)",
                el.mu1, 0.5 * d * el.k0, self.file.material.poisson, material.dim
            ));
        }
        if let ElasticLaw::Hencky { t0 } = el.law {
            let e = std::f64::consts::E;
            warnings.push(format!(
                "(h1)(b) holds only for ‖ε^D‖² < e·t0 = {:.4e}: beyond it g + 2g't = µ1 (t0/t)(1 − ln(t/t0)) < 0 (the law softens), and g(t) → 0 as t → ∞ (g(100 t0) = {:.4e}), so (h1)(a) has no g0 > 0 for unbounded strains; results whose strains exceed e·t0 are outside the paper's theory",
                e * t0,
                el.g(100.0 * t0)
            ));
        }
        warnings
    }

    /// Keys of `[solver]` that the chosen method does not read, as warnings.
    pub fn setting_warnings(&self) -> Vec<String> {
        let s = &self.file.solver;
        let (method, other, unused) = match s.method.unwrap_or_default() {
            MethodKey::Newton => {
                ("newton", "uzawa", [("eps", s.eps.is_some()), ("eps_fp", s.eps_fp.is_some())])
            }
            MethodKey::Uzawa => (
                "uzawa",
                "newton",
                [("tol", s.tol.is_some()), ("max_condensed", s.max_condensed.is_some())],
            ),
        };
        unused
            .iter()
            .filter(|(_, set)| *set)
            .map(|(key, _)| {
                format!(
                    "{}: solver.{key} is not used by solver.method = \"{method}\" (only {other} reads it; newton stops on solver.tol, uzawa on solver.eps and solver.eps_fp)",
                    self.locate(&format!("solver.{key}"))
                )
            })
            .collect()
    }

    /// The bounds and Lipschitz constants of p_ν and h_ν ((h5), (h6)) and the quantity that
    /// Theorem 3.1 needs small for uniqueness.
    pub fn uniqueness_note(&self) -> Option<String> {
        let c = self.file.contact.as_ref()?;
        let (m_h, l_h) = (c.c_nu * c.alpha_nu, c.c_nu * (c.alpha_nu - 1.0) / c.h_nu_range);
        let (m_p, l_p) = (c.n_nu, 1.0);
        let psi = match (&self.file.conductivity, self.problem_kind()) {
            (Some(k), ProblemKey::PV2) => format!(
                "; ψ is bounded by M_ψ = k_e = {} with Lipschitz constant k_e·δ = {} and φ_L by L = {}",
                k.ke,
                k.ke * k.delta,
                k.truncation
            ),
            _ => String::new(),
        };
        Some(format!(
            "p_ν is bounded by M_p = {m_p} with Lipschitz constant {l_p}, h_ν by M_h = {m_h} with {l_h:.4e}: M_h·L_p + L_h·M_p = {:.4e} must be below the L* of Theorem 3.1 for uniqueness (the paper does not give L*){psi}",
            m_h * l_p + l_h * m_p
        ))
    }

    /// PV1 or PV2, as the case says or as its sections imply.
    pub fn problem_kind(&self) -> ProblemKey {
        let f = &self.file;
        let implied = if f.friction.is_some() || f.conductivity.is_some() {
            ProblemKey::PV2
        } else {
            ProblemKey::PV1
        };
        f.contact.as_ref().and_then(|c| c.problem).unwrap_or(implied)
    }

    /// The contact model of [P] on `problem`'s Γ3, or `None` without a `[contact]` table.
    pub fn contact_model(&self, problem: &Problem) -> Result<Option<ContactModel>> {
        self.contact_settings()?;
        let f = &self.file;
        let Some(c) = &f.contact else { return Ok(None) };
        let conduction = f.conductivity.as_ref();
        let phi0 = conduction.map_or(0.0, |k| k.phi0);
        let compliance = NormalCompliance {
            gap: c.gap,
            penetration: c.penetration,
            c_nu: c.c_nu,
            alpha_nu: c.alpha_nu,
            n_nu: c.n_nu,
            h_nu_range: c.h_nu_range,
            phi0,
        };
        let pv2 = match self.problem_kind() {
            ProblemKey::PV1 => None,
            ProblemKey::PV2 => {
                let fr = f.friction.clone().unwrap_or_default();
                let mut mu_parts = Vec::new();
                for (name, &mu) in &fr.mu_parts {
                    let part = problem.mesh.part_index(name).map_err(|e| {
                        input!(
                            "{}: friction.mu_parts: {e}",
                            self.locate(&format!("friction.mu_parts.{name}"))
                        )
                    })?;
                    if !problem.boundary.contact.contains(&part) {
                        return Err(input!(
                            "{}: friction.mu_parts.{name}: part '{name}' is not a contact part (boundary.contact)",
                            self.locate(&format!("friction.mu_parts.{name}"))
                        ));
                    }
                    mu_parts.push((part, mu));
                }
                let regularization = match fr.regularization {
                    RegularizationKey::Identity => Regularization::Identity,
                    RegularizationKey::Mollifier => Regularization::Mollifier { radius: fr.radius },
                };
                let k = conduction
                    .cloned()
                    .unwrap_or(ConductivitySection { phi0, ..ConductivitySection::default() });
                Some((
                    Friction { mu: fr.mu, mu_parts, regularization },
                    Conduction { ke: k.ke, phi0: k.phi0, delta: k.delta, truncation: k.truncation },
                ))
            }
        };
        let foundation = self.foundation(problem.mesh.dim())?;
        Ok(Some(ContactModel { compliance, pv2, foundation }))
    }

    /// The foundation of `[foundation]`, checked for a d-dimensional body.
    pub fn foundation(&self, dim: usize) -> Result<Foundation> {
        let Some(f) = &self.file.foundation else { return Ok(Foundation::ConstantGap) };
        let vector = |key: &str, v: &Option<Vec<f64>>| -> Result<[f64; 3]> {
            let full = format!("foundation.{key}");
            let v = v.as_ref().ok_or_else(|| {
                input!(
                    "{}: {full} is missing: kind = \"{}\" needs it",
                    self.locate("foundation"),
                    kind_name(f.kind)
                )
            })?;
            if v.len() != dim || v.iter().any(|x| !x.is_finite()) {
                return Err(input!(
                    "{}: {full} = {v:?} must have {dim} finite components (the mesh is {dim}D)",
                    self.locate(&full)
                ));
            }
            let mut out = [0.0; 3];
            out[..dim].copy_from_slice(v);
            Ok(out)
        };
        let misplaced = match f.kind {
            FoundationKind::Plane => {
                [("center", f.center.is_some()), ("radius", f.radius.is_some())]
            }
            FoundationKind::Sphere => {
                [("point", f.point.is_some()), ("normal", f.normal.is_some())]
            }
        };
        if let Some((key, _)) = misplaced.iter().find(|(_, set)| *set) {
            return Err(input!(
                "{}: foundation.{key} does not belong to kind = \"{}\"; remove it (a plane has point and normal, a sphere center and radius)",
                self.locate(&format!("foundation.{key}")),
                kind_name(f.kind)
            ));
        }
        match f.kind {
            FoundationKind::Plane => {
                let (point, normal) = (vector("point", &f.point)?, vector("normal", &f.normal)?);
                let norm = normal.iter().map(|v| v * v).sum::<f64>().sqrt();
                if !(norm > 0.0 && norm.is_finite()) {
                    return Err(input!(
                        "{}: foundation.normal = {:?} is not allowed: a nonzero vector, out of the foundation toward the body",
                        self.locate("foundation.normal"),
                        f.normal.as_deref().unwrap_or_default()
                    ));
                }
                Ok(Foundation::Plane { point, normal: normal.map(|v| v / norm) })
            }
            FoundationKind::Sphere => {
                let center = vector("center", &f.center)?;
                let radius = f.radius.ok_or_else(|| {
                    input!(
                        "{}: foundation.radius is missing: kind = \"sphere\" needs it",
                        self.locate("foundation")
                    )
                })?;
                if !positive(radius) {
                    return Err(input!(
                        "{}: foundation.radius = {radius} is not allowed: a radius > 0",
                        self.locate("foundation.radius")
                    ));
                }
                Ok(Foundation::Sphere { center, radius })
            }
        }
    }

    /// The algorithms' parameters, checked, with the defaults of [`SolverSection::DEFAULTS`].
    pub fn settings(&self) -> Result<Settings> {
        self.contact_settings()?;
        Ok(self.settings_unchecked())
    }

    /// The algorithms' parameters with their defaults, before the range checks.
    fn settings_unchecked(&self) -> Settings {
        let (s, d) = (&self.file.solver, SolverSection::DEFAULTS);
        let r = s.r.unwrap_or(d.r_per_young * self.file.material.young);
        let method = match s.method.unwrap_or_default() {
            MethodKey::Uzawa => Method::Uzawa {
                r,
                eps: s.eps.unwrap_or(d.eps),
                max_inner: s.max_inner.unwrap_or(d.max_uzawa),
            },
            MethodKey::Newton => Method::Newton {
                r,
                tol: s.tol.unwrap_or(d.tol),
                max_inner: s.max_inner.unwrap_or(d.max_newton),
                max_condensed: s.max_condensed.unwrap_or(d.max_condensed),
            },
        };
        Settings {
            method,
            eps_fp: s.eps_fp.unwrap_or(d.eps_fp),
            max_outer: s.max_outer.unwrap_or(d.max_outer),
        }
    }

    /// The checked problem.
    pub fn problem(&self) -> Result<Problem> {
        self.contact_settings()?;
        let mesh = self.mesh()?;
        let dim = mesh.dim();
        let material = self.material(dim)?;
        let b = &self.file.boundary;
        let parts = |key: &str, names: &[String]| -> Result<Vec<usize>> {
            names
                .iter()
                .map(|n| mesh.part_index(n).map_err(|e| input!("{}: {key}: {e}", self.locate(key))))
                .collect()
        };
        let vector = |key: &str, v: &[f64]| -> Result<Vec<f64>> {
            if v.len() != dim || v.iter().any(|x| !x.is_finite()) {
                return Err(input!(
                    "{}: {key} = {v:?} must have {dim} finite components (the mesh is {dim}D)",
                    self.locate(key)
                ));
            }
            Ok(v.to_vec())
        };
        let mut traction = Vec::new();
        for t in &b.traction {
            let f2 = vector("boundary.traction.f2", &t.f2)?;
            for p in parts("boundary.traction.parts", &t.parts)? {
                traction.push((p, constant_vector(f2.clone())));
            }
        }
        let mut charge = Vec::new();
        for c in &b.charge {
            if !c.q2.is_finite() {
                return Err(input!(
                    "{}: boundary.charge.q2 = {} must be a finite number",
                    self.locate("boundary.charge"),
                    c.q2
                ));
            }
            for p in parts("boundary.charge.parts", &c.parts)? {
                charge.push((p, constant_scalar(c.q2)));
            }
        }
        let boundary = Boundary {
            clamped: parts("boundary.clamped", &b.clamped)?,
            grounded: parts("boundary.grounded", &b.grounded)?,
            contact: parts("boundary.contact", &b.contact)?,
            traction,
            charge,
            ..Boundary::default()
        };
        let loads = BodyLoads {
            f0: self
                .file
                .loads
                .f0
                .as_ref()
                .map(|f| vector("loads.f0", f))
                .transpose()?
                .map(constant_vector),
            q0: match self.file.loads.q0 {
                Some(q) if !q.is_finite() => {
                    return Err(input!(
                        "{}: loads.q0 = {q} must be a finite number",
                        self.locate("loads.q0")
                    ));
                }
                q => q.map(constant_scalar),
            },
        };
        Problem::new(mesh, material, boundary, loads).map_err(|e| self.context(e))
    }
}

/// The case-file name of a foundation kind.
fn kind_name(kind: FoundationKind) -> &'static str {
    match kind {
        FoundationKind::Plane => "plane",
        FoundationKind::Sphere => "sphere",
    }
}

/// A range rule: key, value, test, and the requirement stated in the error.
struct Rule(&'static str, f64, fn(f64) -> bool, &'static str);

fn positive(v: f64) -> bool {
    v.is_finite() && v > 0.0
}

fn nonnegative(v: f64) -> bool {
    v.is_finite() && v >= 0.0
}

/// Applies one `dotted.key=value` override to the document; the value is read as TOML
/// (numbers, booleans, quoted strings, arrays) or else taken as a bare string.
fn apply_override(doc: &mut toml_edit::DocumentMut, setting: &str) -> Result<()> {
    let (key, value) = setting.split_once('=').ok_or_else(|| {
        input!("--set {setting}: expected dotted.key=value, e.g. --set mesh.nx=192")
    })?;
    let path: Vec<&str> = key.trim().split('.').collect();
    if path.iter().any(|k| k.is_empty()) {
        return Err(input!("--set {setting}: '{key}' is not a dotted key such as solver.r"));
    }
    let value: toml_edit::Value =
        value.trim().parse().unwrap_or_else(|_| toml_edit::Value::from(value.trim()));
    let mut table = doc.as_table_mut();
    for (depth, k) in path[..path.len() - 1].iter().enumerate() {
        let entry = table.entry(k).or_insert_with(toml_edit::table);
        table = entry.as_table_mut().ok_or_else(|| {
            input!("--set {setting}: '{}' is not a table", path[..=depth].join("."))
        })?;
    }
    let last = path[path.len() - 1];
    // An override replaces the key under whichever of its spellings the file uses.
    for &(section, a, b) in ALIASES {
        if path[..path.len() - 1] == [section] && (last == a || last == b) {
            table.remove(if last == a { b } else { a });
        }
    }
    table[last] = toml_edit::value(value);
    Ok(())
}

/// Keys with two spellings (serde aliases): (table, key, alias).
const ALIASES: &[(&str, &str, &str)] = &[
    ("material", "e31", "e32"),
    ("material", "e15", "e24"),
    ("material", "beta11_rel", "beta22_rel"),
];

/// Line (1-based) of a dotted key in a TOML text.
pub fn key_line(source: &str, dotted: &str) -> Option<usize> {
    let doc = toml_edit::Document::parse(source).ok()?;
    let mut item = doc.as_item();
    let mut span = None;
    for k in dotted.split('.') {
        let table = item.as_table_like()?;
        let (key, next) = table.get_key_value(k)?;
        span = key.span().or(span);
        item = next;
    }
    span.map(|s| source[..s.start].matches('\n').count() + 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    const PAPER_71: &str = include_str!("../../../../cases/paper-7.1.toml");
    const MINIMAL: &str = r#"
[mesh]
x = [0.0, 4.0]
y = [0.0, 1.0]
nx = 8
ny = 2
[mesh.segments]
left = ["{0}x[0,1]"]
bottom = ["[0,4]x{0}"]
[material]
young = 100.0
poisson = 0.25
e31 = -5.4
e33 = 15.8
e15 = 12.3
eps0 = 8.885e-3
beta11_rel = 916.0
beta33_rel = 830.0
[boundary]
clamped = ["left"]
grounded = ["left"]
contact = ["bottom"]
[contact]
gap = 0.1
[solver]
"#;

    fn case(text: &str, overrides: &[&str]) -> Result<Case> {
        let overrides: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
        Case::from_text(Path::new("case.toml"), text, &overrides)
    }

    fn error(text: &str, overrides: &[&str]) -> String {
        let checked = case(text, overrides).and_then(|c| {
            let problem = c.problem()?;
            c.settings()?;
            c.contact_model(&problem)
        });
        checked.map(|_| String::new()).unwrap_or_else(|e| e.to_string())
    }

    #[test]
    fn defaults_live_in_one_place_and_follow_e() {
        let c = case(MINIMAL, &[]).unwrap();
        let s = c.settings().unwrap();
        let d = SolverSection::DEFAULTS;
        let newton = Method::Newton {
            r: 0.25 * 100.0,
            tol: d.tol,
            max_inner: d.max_newton,
            max_condensed: d.max_condensed,
        };
        assert_eq!(s, Settings { method: newton, eps_fp: d.eps_fp, max_outer: d.max_outer });
        let uzawa = case(MINIMAL, &["solver.method=\"uzawa\""]).unwrap().settings().unwrap();
        let expected = Method::Uzawa { r: 25.0, eps: d.eps, max_inner: d.max_uzawa };
        assert_eq!(uzawa.method, expected);
        // The values `check` prints are those the solver uses.
        let lines = c.contact_settings().unwrap();
        let value = |key: &str| lines.iter().find(|(k, _)| k == key).map(|(_, v)| *v);
        assert_eq!(value("solver.r"), Some(25.0));
        assert_eq!(value("solver.max_outer"), Some(d.max_outer as f64));
        let with = case(MINIMAL, &["solver.r=3", "solver.method=\"uzawa\""]).unwrap();
        assert!(matches!(with.settings().unwrap().method, Method::Uzawa { r: 3.0, .. }));
        // Keys of the other method are reported, not silently dropped.
        let unused = case(MINIMAL, &["solver.eps=1e-6"]).unwrap().setting_warnings();
        assert!(unused[0].contains("solver.eps is not used by solver.method = \"newton\""));
        let overrides = ["solver.method=\"uzawa\"", "solver.max_condensed=10"];
        let unused = case(MINIMAL, &overrides).unwrap().setting_warnings();
        assert!(
            unused[0].contains("solver.max_condensed is not used by solver.method = \"uzawa\"")
        );
    }

    #[test]
    fn the_paper_case_gives_the_paper_model() {
        let c = case(PAPER_71, &["mesh.nx=12", "mesh.ny=2"]).unwrap();
        let problem = c.problem().unwrap();
        let model = c.contact_model(&problem).unwrap().unwrap();
        assert_eq!(c.problem_kind(), ProblemKey::PV1);
        assert!(model.pv2.is_none());
        assert_eq!((model.compliance.gap, model.compliance.phi0), (0.5, 32.0));
        // The paper's cases ask for the paper's algorithm.
        assert_eq!(c.settings().unwrap().method.name(), "uzawa");
        assert_eq!(c.file.units.potential, "GV");
        // PV2 is implied by a [friction] table; conduction then takes its defaults.
        let pv2 = case(MINIMAL, &["friction.mu=0.3"]).unwrap();
        let problem = pv2.problem().unwrap();
        let (friction, conduction) = pv2.contact_model(&problem).unwrap().unwrap().pv2.unwrap();
        assert_eq!(friction.mu, 0.3);
        assert_eq!(conduction, {
            let d = ConductivitySection::default();
            Conduction { ke: 0.0, phi0: 0.0, delta: d.delta, truncation: d.truncation }
        });
    }

    #[test]
    fn errors_name_the_file_the_line_the_key_and_the_fix() {
        let line = |key: &str| {
            MINIMAL.lines().position(|l| l.starts_with(key)).map(|k| k + 1).unwrap_or(0)
        };
        for (overrides, pieces) in [
            (vec!["solver.r=-1"], vec!["case.toml:", "solver.r = -1 is not allowed: r > 0"]),
            (vec!["solver.max_inner=0"], vec!["solver.max_inner = 0", "at least 1"]),
            (vec!["solver.method=\"simplex\""], vec!["unknown variant `simplex`", "uzawa"]),
            (vec!["solver.tol=0"], vec!["solver.tol = 0 is not allowed: a tolerance > 0"]),
            (vec!["solver.max_condensed=0"], vec!["solver.max_condensed = 0", "at least 1"]),
            (vec!["contact.alpha_nu=1"], vec!["contact.alpha_nu = 1", "α_ν > 1"]),
            (
                vec!["material.poisson=0.5"],
                vec![&format!("case.toml:{}", line("poisson")), "poisson"],
            ),
            (
                vec!["boundary.contact=[\"nowhere\"]"],
                vec!["'nowhere' is not in the mesh", "bottom"],
            ),
            (
                vec!["friction.mu_parts.left=0.2"],
                vec!["friction.mu_parts.left", "not a contact part"],
            ),
            (vec!["mesh.file=\"x.msh\""], vec!["mesh.x describes the built-in rectangle"]),
            (vec!["solver.nonsense=1"], vec!["unknown field `nonsense`"]),
            (vec!["solver"], vec!["--set solver: expected dotted.key=value"]),
            (vec!["mesh.nx.deep=1"], vec!["'mesh.nx' is not a table"]),
            (
                vec!["mesh.nx=2000000000", "mesh.ny=2000000000"],
                vec!["would need about", "reduce mesh.nx"],
            ),
        ] {
            let e = error(MINIMAL, &overrides);
            for piece in pieces {
                assert!(e.contains(piece), "{overrides:?}: '{e}' lacks '{piece}'");
            }
        }
        let e = error("[mesh]\nnx = 'a'\n", &[]);
        assert!(e.starts_with("case.toml: TOML parse error at line 2"), "{e}");
    }

    #[test]
    fn the_foundation_table_is_read_and_checked() {
        let with = |sets: &[&str]| {
            let c = case(MINIMAL, sets)?;
            c.foundation(2)
        };
        let plane = with(&[
            "foundation.kind=\"plane\"",
            "foundation.point=[0.0, -0.5]",
            "foundation.normal=[0.0, 2.0]",
        ])
        .unwrap();
        assert_eq!(plane, Foundation::Plane { point: [0.0, -0.5, 0.0], normal: [0.0, 1.0, 0.0] });
        let ball = with(&[
            "foundation.kind=\"sphere\"",
            "foundation.center=[2.0, -1.0]",
            "foundation.radius=0.5",
        ])
        .unwrap();
        assert_eq!(ball, Foundation::Sphere { center: [2.0, -1.0, 0.0], radius: 0.5 });
        assert_eq!(with(&[]).unwrap(), Foundation::ConstantGap);
        for (sets, piece) in [
            (
                vec!["foundation.kind=\"plane\"", "foundation.point=[0.0, 0.0]"],
                "foundation.normal is missing",
            ),
            (
                vec![
                    "foundation.kind=\"plane\"",
                    "foundation.point=[0.0]",
                    "foundation.normal=[0.0, 1.0]",
                ],
                "foundation.point = [0.0] must have 2 finite components",
            ),
            (
                vec![
                    "foundation.kind=\"plane\"",
                    "foundation.point=[0.0, 0.0]",
                    "foundation.normal=[0.0, 0.0]",
                ],
                "a nonzero vector",
            ),
            (
                vec![
                    "foundation.kind=\"sphere\"",
                    "foundation.center=[0.0, 0.0]",
                    "foundation.radius=-1",
                ],
                "foundation.radius = -1 is not allowed: a radius > 0",
            ),
            (
                vec![
                    "foundation.kind=\"sphere\"",
                    "foundation.center=[0.0, 0.0]",
                    "foundation.normal=[0.0, 1.0]",
                ],
                "foundation.normal does not belong to kind = \"sphere\"",
            ),
            (vec!["foundation.kind=\"cone\""], "unknown variant `cone`"),
        ] {
            let e = with(&sets).unwrap_err().to_string();
            assert!(e.contains(piece) && e.starts_with("case.toml"), "{sets:?}: {e}");
        }
    }

    #[test]
    fn overrides_replace_a_key_under_either_spelling() {
        let c = case(PAPER_71, &["material.e31=-1.5", "material.beta11_rel=100"]).unwrap();
        assert_eq!((c.file.material.e31, c.file.material.beta11_rel), (-1.5, 100.0));
        assert_eq!(c.locate("material.e32"), "case.toml");
        assert!(c.locate("material.e31").starts_with("case.toml:"));
    }

    #[test]
    fn the_hypotheses_are_reported_with_their_numbers() {
        let c = case(MINIMAL, &["material.poisson=0.05"]).unwrap();
        let problem = c.problem().unwrap();
        let warnings = c.hypothesis_warnings(&problem.material);
        assert!(warnings.iter().any(|w| w.starts_with("(h1)(a) fails")), "{warnings:?}");
        assert!(warnings.iter().any(|w| w.contains("e·t0 = 4.8929e0")), "{warnings:?}");
        let linear = case(MINIMAL, &["material.law=\"linear\""]).unwrap();
        assert!(linear.hypothesis_warnings(&linear.problem().unwrap().material).is_empty());
        assert!(c.uniqueness_note().unwrap().contains("M_h·L_p + L_h·M_p"));
    }
}
