//! The case file's schema: the raw serde view of a TOML case (ripgrep's "low args"), every
//! key documented, unknown keys rejected; and every default in one table, [`DEFAULTS`].

use super::expression::Quantity;
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::PathBuf;

/// Every default of a case file, in one table: the keys a file leaves out take these values.
pub struct Defaults {
    /// `[units]`: length, stress, charge, potential.
    pub units: [&'static str; 4],
    /// material.law of the isotropic form.
    pub law: LawKey,
    /// material.t0: Hencky's elasticity limit (the paper's 1.8) [-].
    pub t0: f64,
    /// contact.c_nu [stress/length].
    pub c_nu: f64,
    /// contact.alpha_nu [-].
    pub alpha_nu: f64,
    /// contact.n_nu \[length\].
    pub n_nu: f64,
    /// contact.h_nu_range (the paper's 128) \[potential\].
    pub h_nu_range: f64,
    /// conductivity.delta [1/length].
    pub delta: f64,
    /// conductivity.L \[potential\].
    pub truncation: f64,
    /// solver.method.
    pub method: MethodKey,
    /// solver.r as a multiple of Young's modulus E (the paper's 0.25 E).
    pub r_per_young: f64,
    /// solver.eps (the paper's 1e−4).
    pub eps: f64,
    /// solver.eps_fp (the paper's 1e−4).
    pub eps_fp: f64,
    /// solver.tol: round-off for the exact solver.
    pub tol: f64,
    /// solver.max_inner under uzawa.
    pub max_uzawa: usize,
    /// solver.max_inner under newton.
    pub max_newton: usize,
    /// solver.max_outer.
    pub max_outer: usize,
    /// The most Γ3 nodes of the exact solver's first condensed set without
    /// solver.max_condensed \[nodes\].
    pub first_condensed: usize,
    /// solver.ordering.
    pub ordering: OrderingKey,
    /// solver.backend.
    pub backend: BackendKey,
}

/// The defaults: the paper's values for its constants and for Uzawa, round-off for Newton,
/// and generous caps.
pub const DEFAULTS: Defaults = Defaults {
    units: ["m", "Pa", "C", "V"],
    law: LawKey::Hencky,
    t0: 1.8,
    c_nu: 1.0,
    alpha_nu: 2.0,
    n_nu: 1.0,
    h_nu_range: 128.0,
    delta: 1.0,
    truncation: 1e3,
    method: MethodKey::Newton,
    r_per_young: 0.25,
    eps: 1e-4,
    eps_fp: 1e-4,
    tol: 1e-10,
    max_uzawa: 10_000,
    max_newton: 100,
    max_outer: 100,
    first_condensed: 2000,
    ordering: OrderingKey::Auto,
    backend: BackendKey::Faer,
};

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
    DEFAULTS.units[0].into()
}
fn default_stress() -> String {
    DEFAULTS.units[1].into()
}
fn default_charge() -> String {
    DEFAULTS.units[2].into()
}
fn default_potential() -> String {
    DEFAULTS.units[3].into()
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
    /// Rectangle: [x0, x1] \[length\].
    pub x: Option<[f64; 2]>,
    /// Rectangle: [y0, y1] \[length\].
    pub y: Option<[f64; 2]>,
    /// Rectangle: cells along x.
    pub nx: Option<usize>,
    /// Rectangle: cells along y.
    pub ny: Option<usize>,
    /// The 2D model: "continuum" (the paper's, the default), "strain" (plane strain) or
    /// "stress" (plane stress), slices of a 3D body.
    pub plane: Option<PlaneKey>,
    /// Rectangle: "right" (lower-left–upper-right diagonal, default) or "left".
    pub diagonal: Option<DiagonalKey>,
    /// Rectangle: boundary part name → segments such as "\[0,2\]x{0}".
    #[serde(default)]
    pub segments: BTreeMap<String, Vec<String>>,
    /// Region name → boxes such as "\[0,12\]x\[1,2\]" (the cells whose centroid lies in
    /// one), for `[[material]]` regions, beside a mesh file's volume groups.
    #[serde(default)]
    pub regions: BTreeMap<String, Vec<String>>,
}

/// The 2D model in the case file.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq)]
#[serde(rename_all = "lowercase")]
pub enum PlaneKey {
    Continuum,
    Strain,
    Stress,
    Axisymmetric,
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

/// `[material]`: the body's elastic, piezoelectric and dielectric constants, in the material's
/// axes (poled along its axis 3, the mesh's last axis), Voigt order xx, yy, zz, yz, xz, xy with
/// engineering shear strains. One form of each group: elastic `young`/`poisson` (Hencky's law),
/// `c` or `s`; piezoelectric `e31`/`e33`/`e15`, `e` or `d` (none: a dielectric); dielectric
/// `beta11_rel`/`beta33_rel` or `eps_rel`, times `eps0`. Its axes in the mesh: `poling` or
/// `euler`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSection {
    /// Its name in outputs and overrides (required when there are several).
    pub name: Option<String>,
    /// The regions it fills: physical groups of dimension d of the mesh file, or the
    /// rectangle's `[mesh.regions]` (required when there are several).
    pub regions: Option<Vec<String>>,
    /// A material of the library (`piezocontact materials` lists them), in SI converted to the
    /// case's units: it fills every group the table does not give.
    pub preset: Option<String>,
    /// "hencky" (the paper's g, the default of the isotropic form) or "linear" (g ≡ µ1, the
    /// only law of `c` and `s`).
    pub law: Option<LawKey>,
    /// E: Young's modulus \[stress\].
    pub young: Option<f64>,
    /// ν: Poisson's ratio [-].
    pub poisson: Option<f64>,
    /// t0: Hencky elasticity limit on ‖ε^D‖² [-] (paper: 1.8).
    #[serde(default = "default_t0")]
    pub t0: f64,
    /// c^E: the 6 × 6 stiffness \[stress\].
    pub c: Option<Vec<Vec<f64>>>,
    /// s^E: the 6 × 6 compliance \[1/stress\].
    pub s: Option<Vec<Vec<f64>>>,
    /// e31 = e32 [charge/length²].
    #[serde(alias = "e32")]
    pub e31: Option<f64>,
    /// e33 [charge/length²].
    pub e33: Option<f64>,
    /// e15 = e24 [charge/length²].
    #[serde(alias = "e24")]
    pub e15: Option<f64>,
    /// e: the 3 × 6 piezoelectric stress constants [charge/length²].
    pub e: Option<Vec<Vec<f64>>>,
    /// d: the 3 × 6 piezoelectric strain constants [charge/force].
    pub d: Option<Vec<Vec<f64>>>,
    /// ε0: vacuum permittivity [charge/(potential·length)].
    pub eps0: Option<f64>,
    /// β11/ε0 = β22/ε0: relative permittivity across the poling axis [-].
    #[serde(alias = "beta22_rel")]
    pub beta11_rel: Option<f64>,
    /// β33/ε0: relative permittivity along the poling axis [-].
    pub beta33_rel: Option<f64>,
    /// The relative permittivity, 3 × 3 or its diagonal: ε^T/ε0 with `d`, else ε^S/ε0 [-].
    pub eps_rel: Option<Vec<NumberOrRow>>,
    /// The poling: material axis 3 in mesh coordinates (3D; default +z).
    pub poling: Option<Vec<f64>>,
    /// The material's axes by Euler angles [φ1, Φ, φ2] in degrees: the columns of
    /// Rz(φ1)·Rx(Φ)·Rz(φ2) (3D).
    pub euler: Option<Vec<f64>>,
}

/// `[material]` (one table) or `[[material]]` (a table per material).
#[derive(Clone, Debug)]
pub enum MaterialTables {
    /// `[material]`.
    One(Box<MaterialSection>),
    /// `[[material]]`.
    Many(Vec<MaterialSection>),
}

impl MaterialTables {
    /// The tables, in the file's order.
    pub fn tables(&self) -> &[MaterialSection] {
        match self {
            Self::One(table) => std::slice::from_ref(table),
            Self::Many(tables) => tables,
        }
    }
}

impl<'de> Deserialize<'de> for MaterialTables {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Visitor;
        impl<'de> serde::de::Visitor<'de> for Visitor {
            type Value = MaterialTables;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a [material] table or [[material]] tables")
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(
                self,
                map: A,
            ) -> Result<Self::Value, A::Error> {
                let table = MaterialSection::deserialize(
                    serde::de::value::MapAccessDeserializer::new(map),
                )?;
                Ok(MaterialTables::One(Box::new(table)))
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                seq: A,
            ) -> Result<Self::Value, A::Error> {
                let tables = Vec::deserialize(serde::de::value::SeqAccessDeserializer::new(seq))?;
                Ok(MaterialTables::Many(tables))
            }
        }
        deserializer.deserialize_any(Visitor)
    }
}

/// An entry of a list that is a vector (numbers) or a matrix (rows of numbers).
#[derive(Clone, Debug, PartialEq)]
pub enum NumberOrRow {
    /// A number.
    Number(f64),
    /// A row of numbers.
    Row(Vec<f64>),
}

impl<'de> Deserialize<'de> for NumberOrRow {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Visitor;
        impl<'de> serde::de::Visitor<'de> for Visitor {
            type Value = NumberOrRow;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a number or a row of numbers")
            }
            fn visit_f64<E>(self, v: f64) -> Result<NumberOrRow, E> {
                Ok(NumberOrRow::Number(v))
            }
            fn visit_i64<E>(self, v: i64) -> Result<NumberOrRow, E> {
                Ok(NumberOrRow::Number(v as f64))
            }
            fn visit_u64<E>(self, v: u64) -> Result<NumberOrRow, E> {
                Ok(NumberOrRow::Number(v as f64))
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                seq: A,
            ) -> Result<NumberOrRow, A::Error> {
                let row =
                    Vec::<f64>::deserialize(serde::de::value::SeqAccessDeserializer::new(seq))?;
                Ok(NumberOrRow::Row(row))
            }
        }
        deserializer.deserialize_any(Visitor)
    }
}

fn default_t0() -> f64 {
    DEFAULTS.t0
}

/// A traction load on Γ2 parts.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TractionLoad {
    /// Boundary parts carrying it.
    pub parts: Vec<String>,
    /// f2: traction density, d components \[stress\], each a number or an expression of
    /// x, y, z.
    pub f2: Vec<Quantity>,
}

/// `[[boundary.support]]`: components of u fixed on boundary parts (rollers, symmetry planes,
/// a prescribed displacement component).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SupportTable {
    /// The name in outputs (reactions); default: its parts' names joined by '+'.
    pub name: Option<String>,
    /// Boundary parts it holds.
    pub parts: Vec<String>,
    /// The fixed components: "x", "y", "z", or "normal" (the outward normal of the parts at
    /// each node: a roller on a face of any orientation).
    pub fix: Vec<String>,
    /// The prescribed displacement of each entry of `fix` \[length\], each a number or an
    /// expression of x, y, z; default 0.
    pub displacement: Option<Vec<Quantity>>,
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

/// `[boundary]`: boundary part names by role (\[P\] (2.4)).
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
    /// Supports: components of u fixed on parts.
    #[serde(default)]
    pub support: Vec<SupportTable>,
    /// Γb: surface charges.
    #[serde(default)]
    pub charge: Vec<ChargeLoad>,
    /// Electrodes: parts at a prescribed potential, or floating.
    #[serde(default)]
    pub electrode: Vec<ElectrodeTable>,
}

/// `[[boundary.electrode]]`: an electrode, boundary parts at one potential.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ElectrodeTable {
    /// Its name in outputs (`phi_<name>`, `charge_<name>`).
    pub name: String,
    /// The boundary parts it covers.
    pub parts: Vec<String>,
    /// Its potential \[potential\], scaled by a loading path's factors.
    pub voltage: Option<f64>,
    /// The total charge on a floating electrode \[charge\] (0: an open circuit), scaled by a
    /// loading path's factors.
    pub charge: Option<f64>,
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
    /// g_a: gap, where compliance and conduction start (the paper's ρ) \[length\].
    #[serde(default)]
    pub gap: f64,
    /// g_p ≥ 0: penetration before the rigid stop at u_ν = g_a + g_p \[length\].
    #[serde(default)]
    pub penetration: f64,
    /// c_ν > 0 of h_ν [stress/length].
    #[serde(default = "default_c_nu")]
    pub c_nu: f64,
    /// α_ν > 1 of h_ν [-].
    #[serde(default = "default_alpha_nu")]
    pub alpha_nu: f64,
    /// n_ν > 0: saturation of p_ν \[length\].
    #[serde(default = "default_n_nu")]
    pub n_nu: f64,
    /// The potential difference at which h_ν saturates (the paper's 128) \[potential\].
    #[serde(default = "default_h_nu_range")]
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
    /// Radius a of the mollifier \[length\].
    #[serde(default)]
    pub radius: f64,
    /// On a loading path: "static" (the paper's law at every step, default) or "incremental"
    /// (the slip since the previous step; model §14).
    #[serde(default)]
    pub path: FrictionPathKey,
}

/// `friction.path` in the case file.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum FrictionPathKey {
    /// The paper's static law at every step.
    #[default]
    Static,
    /// Quasistatic Coulomb: the slip since the previous step.
    Incremental,
}

impl From<FrictionPathKey> for crate::contact::law::FrictionPath {
    fn from(key: FrictionPathKey) -> Self {
        match key {
            FrictionPathKey::Static => Self::Static,
            FrictionPathKey::Incremental => Self::Incremental,
        }
    }
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
    /// ϕ0: potential of the foundation \[potential\].
    #[serde(default)]
    pub phi0: f64,
    /// δ > 0 of ψ0 [1/length].
    #[serde(default = "default_delta")]
    pub delta: f64,
    /// L > 0: truncation of φ_L \[potential\].
    #[serde(default = "default_truncation", rename = "L")]
    pub truncation: f64,
}

impl Default for ConductivitySection {
    /// k_e = 0 (no conduction) and the defaults of the other keys.
    fn default() -> Self {
        Self { ke: 0.0, phi0: 0.0, delta: default_delta(), truncation: default_truncation() }
    }
}

fn default_c_nu() -> f64 {
    DEFAULTS.c_nu
}
fn default_alpha_nu() -> f64 {
    DEFAULTS.alpha_nu
}
fn default_n_nu() -> f64 {
    DEFAULTS.n_nu
}
fn default_h_nu_range() -> f64 {
    DEFAULTS.h_nu_range
}
fn default_delta() -> f64 {
    DEFAULTS.delta
}
fn default_truncation() -> f64 {
    DEFAULTS.truncation
}

/// The kind of foundation surface in the case file.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum FoundationKind {
    /// A rigid half-space: `point` and `normal`.
    Plane,
    /// A rigid ball (a disk in 2D), the body outside it: `center` and `radius`.
    Sphere,
    /// A rigid cone (a wedge in 2D): `apex`, `axis` and `half_angle`.
    Cone,
    /// A rigid flat cylindrical punch (a flat strip in 2D): `center`, `axis` and `radius`.
    Punch,
    /// A rigid closed surface from a Gmsh or STL file (3D): `file`.
    Surface,
}

/// `[foundation]`: the foundation's surface (model §12); without it, the gap `contact.gap`
/// is the same at every Γ3 node, as in the paper. With it, the gap of node i is the distance
/// along ν_i to the surface, plus `contact.gap`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FoundationSection {
    /// "plane", "sphere", "cone", "punch" or "surface".
    pub kind: FoundationKind,
    /// Plane: a point of it, d components \[length\].
    pub point: Option<Vec<f64>>,
    /// Plane: its normal, d components, out of the foundation toward the body (normalised).
    pub normal: Option<Vec<f64>>,
    /// Sphere: its centre; punch: the centre of its flat face; d components \[length\].
    pub center: Option<Vec<f64>>,
    /// Sphere: its radius; punch: the radius of its face (the half-width in 2D) \[length\].
    pub radius: Option<f64>,
    /// Cone: its apex, d components \[length\].
    pub apex: Option<Vec<f64>>,
    /// Cone, punch: the axis, d components, from the apex (the face) into the indenter, away
    /// from the body (normalised).
    pub axis: Option<Vec<f64>>,
    /// Cone: the half-angle between the axis and the flank \[degrees\], in (0, 90).
    pub half_angle: Option<f64>,
    /// Surface: a closed triangulated surface, a Gmsh .msh or an .stl file relative to the
    /// case file, in the mesh's units.
    pub file: Option<String>,
}

/// `[loading]`: a loading path (model §14), one static solve per step: the foundation moved
/// rigidly by `depth · direction` from its `[foundation]` position, and/or every applied
/// load multiplied by the step's factor.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadingSection {
    /// The way the indenter travels, d components (normalised), e.g. [0.0, 0.0, -1.0].
    pub direction: Option<Vec<f64>>,
    /// The foundation's displacements along `direction`, one per step \[length\]: a list, or
    /// `{ from = a, to = b, steps = n }` for the n depths a + (b − a) k/n, k = 1…n.
    pub depths: Option<Depths>,
    /// The factors on f0, q0, f2 and q2, one per step [-].
    pub load_factors: Option<Vec<f64>>,
    /// The factors on the electrodes' voltages and charges, one per step [-] (else the load
    /// factors'); alone, steps at load factor 1.
    pub electrode_factors: Option<Vec<f64>>,
}

/// `loading.depths`: a list, or a range.
#[derive(Clone, Debug, Deserialize)]
#[serde(
    untagged,
    expecting = "a list of depths, or an inline table { from = ..., to = ..., steps = ... }"
)]
pub enum Depths {
    /// The depths of the steps, in order.
    List(Vec<f64>),
    /// `steps` equal increments from `from` (excluded) to `to`.
    Range {
        /// The depth before the first step \[length\].
        from: f64,
        /// The depth of the last step \[length\].
        to: f64,
        /// The number of steps.
        steps: usize,
    },
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

/// The fill-reducing ordering of the sparse factorisation in the case file.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum OrderingKey {
    /// The default: one analysis with the ordering the pattern calls for
    /// ([`crate::linalg::Ordering::Auto`]).
    #[default]
    Auto,
    /// METIS's nested dissection of the mesh nodes.
    Nd,
    /// Approximate minimum degree.
    Amd,
}

/// The linear-solver backend in the case file.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum BackendKey {
    /// faer's sparse LDLᵀ on this machine's threads (the default; pure Rust).
    #[default]
    Faer,
    /// PETSc's distributed matrix and MUMPS's LDLᵀ, on the processes of `mpirun` (a build
    /// with the cargo feature `petsc`).
    Petsc,
}

/// How the linear systems are solved, in the case file.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum LinearKey {
    /// A sparse factorisation (the default).
    #[default]
    Direct,
    /// PETSc's Krylov solvers with a field-split multigrid preconditioner
    /// (`solver.backend = "petsc"`; Uzawa's method or a run without contact).
    Iterative,
}

/// `[solver]`: the algorithms' parameters (model §7). Defaults: [`DEFAULTS`].
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
    /// Cap on Uzawa iterations per outer step (default 10000), or on Newton steps per
    /// condensed problem (default 100; a stage of the continuation in k_e at most 30).
    pub max_inner: Option<usize>,
    /// Cap on fixed-point iterations; default 100.
    pub max_outer: Option<usize>,
    /// The most Γ3 nodes the exact solver condenses into its dense problem (newton only);
    /// default: no cap but memory, from a first set of at most 2000 nodes.
    pub max_condensed: Option<usize>,
    /// The fill-reducing ordering of the factorisation: "auto" (default: nested dissection
    /// on a 3D mesh; in 2D AMD, or nested dissection from 100k unknowns on a numbering
    /// without locality: one analysis, model §13), "nd" or "amd".
    pub ordering: Option<OrderingKey>,
    /// The linear-solver backend: "faer" (default) or "petsc" (PETSc + MUMPS under
    /// mpirun; a build with the feature `petsc`).
    pub backend: Option<BackendKey>,
    /// How the linear systems are solved: "direct" (default: a factorisation) or
    /// "iterative" (PETSc's GMRES with a field split over u and ϕ and algebraic multigrid on
    /// each; with solver.backend = "petsc", and solver.method = "uzawa" where there is
    /// contact).
    pub linear: Option<LinearKey>,
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
    pub material: MaterialTables,
    pub boundary: BoundarySection,
    #[serde(default)]
    pub loads: LoadsSection,
    pub contact: Option<ContactSection>,
    pub friction: Option<FrictionSection>,
    pub conductivity: Option<ConductivitySection>,
    pub foundation: Option<FoundationSection>,
    pub loading: Option<LoadingSection>,
    #[serde(default)]
    pub solver: SolverSection,
}
