//! From a validated case file to what a run takes ([`Built`]): the mesh, the material, the
//! problem, the contact model, the loading path and the settings of the algorithms, with the
//! case's title, units, backend and origin.

use super::expression::Quantity;
use super::file::{Case, Linear, Origin};
use super::schema::{
    DEFAULTS, DiagonalKey, FrictionPathKey, MethodKey, ProblemKey, RegularizationKey, Units,
};
use crate::algorithm::Settings;
use crate::algorithm::condensed::Guess;
use crate::algorithm::newton::{self, Newton};
use crate::algorithm::uzawa::{self, Uzawa};
use crate::contact::law::{Conduction, Friction, NormalCompliance, Regularization};
use crate::contact::{ContactModel, Loading};
use crate::error::{Error, Result};
use crate::linalg::LinearSolver;
use crate::material::plane::Plane;
use crate::mesh::rectangle::{Diagonal, Rectangle, Segment, SegmentParts};
use crate::mesh::{Mesh, gmsh};
use crate::problem::{
    BodyLoads, Boundary, Direction, Electrode, ElectrodeCondition, Problem, ScalarField, Support,
    VectorField, constant_scalar, constant_vector,
};
use std::path::Path;
use std::sync::Arc;

/// The parameters of each inner method the case file can name.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum MethodParameters {
    /// solver.method = "uzawa".
    Uzawa(uzawa::Parameters),
    /// solver.method = "newton".
    Newton(newton::Parameters),
}

/// What a list of parts names: the parts of a role (clamped, grounded, contact, a support),
/// of a load (at least one, sharing no facet), or of an electrode (which may lie inside the
/// body).
#[derive(Clone, Copy, Debug, PartialEq)]
enum PartList {
    Role,
    Load,
    Electrode,
}

/// A validated case: everything a run takes.
pub struct Built {
    /// The checked problem.
    pub problem: Problem,
    /// Its contact model: `None` without a `[contact]` table; with one, Γ3 names a part.
    pub model: Option<ContactModel>,
    /// The loading path of `[loading]`, `None` for a single solve (with a contact model).
    pub loading: Option<Loading>,
    /// The algorithms' settings.
    pub settings: Settings,
    /// The linear solver the case asks for.
    pub linear: Linear,
    /// The paper's hypotheses that fail and the keys the method does not read.
    pub warnings: Vec<String>,
    /// The case's title (may be empty).
    pub title: String,
    /// The case's units, which every number it reads and writes is in.
    pub units: Units,
    /// The case's file and text, for the locations in messages.
    pub origin: Origin,
    /// The plane model of a 2D slice of a 3D body (`mesh.plane`); `None` for a 3D body or the
    /// paper's 2D continuum.
    pub plane: Option<Plane>,
    /// The time the build took: reading or building the mesh and checking the case \[s\].
    pub seconds: f64,
    /// When the run began, from which summary.json's `total` counts: the start of the build,
    /// or earlier where the caller sets it (the command line: its process's start).
    pub started: std::time::Instant,
}

impl Built {
    /// A new linear solver of the case's choice.
    pub fn linear_solver(&self) -> Result<Box<dyn LinearSolver>> {
        self.linear.solver()
    }

    /// The inner method's name (`solver.method`).
    pub fn method_name(&self) -> &'static str {
        self.settings.method.name()
    }

    /// Places an error in the case: at the line of the key it names, else in the file.
    pub fn context(&self, e: Error) -> Error {
        self.origin.context(e)
    }
}

impl Case {
    /// Validates the case once and builds everything a run takes.
    pub fn build(&self) -> Result<Built> {
        let start = std::time::Instant::now();
        self.check_backend()?;
        self.contact_settings()?;
        let problem = self.problem_checked()?;
        let model = self.contact_model(&problem)?;
        if let (true, Some(model)) = (problem.axisymmetric, &model)
            && let Some(why) = model.foundation.off_the_axis()
        {
            return Err(input!(
                "{}: the foundation of an axisymmetric body (mesh.plane = \"axisymmetric\") must be a body of revolution about its axis y: {why}",
                self.locate("foundation")
            ));
        }
        let loading = self.loading(problem.mesh.dim())?;
        if let Some(model) = &model {
            self.check_reach(&problem, model, loading.as_ref())?;
        }
        let mut warnings = self.hypothesis_warnings(&problem.materials);
        warnings.extend(self.setting_warnings());
        let problem_dim = problem.mesh.dim();
        Ok(Built {
            problem,
            model,
            loading,
            settings: self.settings_checked()?,
            linear: self.linear(),
            warnings,
            title: self.file.title.clone(),
            units: self.file.units.clone(),
            origin: self.origin.clone(),
            plane: self.plane_model(problem_dim)?,
            seconds: start.elapsed().as_secs_f64(),
            started: start,
        })
    }

    /// The checked problem alone (for a case without contact).
    pub fn problem(&self) -> Result<Problem> {
        self.check_backend()?;
        self.contact_settings()?;
        self.problem_checked()
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
            let full = self.path().parent().unwrap_or(Path::new(".")).join(file);
            let bytes = std::fs::read(&full).map_err(|e| Error::Io {
                what: format!(
                    "{}: cannot read mesh.file {}",
                    self.locate("mesh.file"),
                    full.display()
                ),
                cause: e.to_string(),
            })?;
            let mesh = gmsh::read(&bytes).map_err(|e| input!("{}: {e}", full.display()))?;
            return self.with_box_regions(mesh);
        }
        let (rectangle, parts) = self.rectangle()?;
        self.check_memory(rectangle.nx, rectangle.ny)?;
        let mesh = rectangle.mesh(&parts).map_err(|e| self.context(e))?;
        self.with_box_regions(mesh)
    }

    /// The built-in rectangle of `[mesh]` and its parts' segments.
    pub(super) fn rectangle(&self) -> Result<(Rectangle, SegmentParts)> {
        let m = &self.file.mesh;
        let need = |key: &str| {
            input!(
                "{}: {key} is missing: give the rectangle (mesh.x, mesh.y, mesh.nx, mesh.ny) or mesh.file",
                self.path().display()
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
        let mut parts = Vec::new();
        for (name, specs) in &m.segments {
            let key = format!("mesh.segments.{name}");
            if specs.is_empty() {
                return Err(input!(
                    "{}: {key} is empty: give the part its segments, e.g. [\"[0,1]x{{0}}\"], or remove it",
                    self.locate(&key)
                ));
            }
            let segments: Result<Vec<Segment>, _> = specs.iter().map(|s| s.parse()).collect();
            parts.push((name.clone(), segments.map_err(|e| input!("{}: {e}", self.locate(&key)))?));
        }
        Ok((rectangle, parts))
    }

    /// Refuses a rectangle whose solve would not fit in memory, before allocating anything.
    /// The estimate, about 12 KB per node growing like log n with the fill of the factor, is
    /// measured on the paper's bar (1536 × 256 cells: 3.5 GB).
    fn check_memory(&self, nx: usize, ny: usize) -> Result<()> {
        let nodes = (nx as f64 + 1.0) * (ny as f64 + 1.0);
        let bytes = nodes * 12e3 * (nodes.log2() / 18.0).max(1.0);
        crate::limits::check_memory(
            bytes,
            crate::limits::available_memory(),
            &format!(
                "{}: mesh.nx × mesh.ny = {nx} × {ny} cells ({nodes:.3e} nodes, {:.3e} unknowns)",
                self.locate("mesh.nx"),
                3.0 * nodes
            ),
            "reduce mesh.nx and mesh.ny",
        )
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

    /// The contact model of [P] on `problem`'s Γ3, or `None` without a `[contact]` table;
    /// refused when the table is given and no boundary part is Γ3.
    pub(super) fn contact_model(&self, problem: &Problem) -> Result<Option<ContactModel>> {
        let f = &self.file;
        let Some(c) = &f.contact else { return Ok(None) };
        if problem.boundary.contact.is_empty() {
            return Err(input!(
                "{}: [contact] is given but boundary.contact names no boundary part",
                self.locate("boundary")
            ));
        }
        let conduction = f.conductivity.as_ref();
        let phi0 = conduction.map_or(0.0, |k| k.phi0);
        let compliance = NormalCompliance {
            gap: c.gap,
            penetration: c.penetration,
            c_nu: c.c_nu,
            alpha_nu: c.alpha_nu,
            n_nu: c.n_nu,
            h_nu_range: c.h_nu_range,
        };
        let (friction, conduction) = match self.problem_kind() {
            ProblemKey::PV1 => (None, None),
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
                if fr.path == FrictionPathKey::Incremental && self.method_name() == "uzawa" {
                    return Err(input!(
                        "{}: friction.path = \"incremental\" is solved by the exact solver only: set solver.method = \"newton\", or friction.path = \"static\"",
                        self.locate("friction.path")
                    ));
                }
                let k = conduction.cloned().unwrap_or_default();
                (
                    Some(Friction { mu: fr.mu, mu_parts, regularization, path: fr.path.into() }),
                    Some(Conduction { ke: k.ke, delta: k.delta, truncation: k.truncation }),
                )
            }
        };
        let foundation = self.foundation(problem.mesh.dim())?;
        Ok(Some(ContactModel { compliance, friction, conduction, foundation, phi0 }))
    }

    /// The algorithms' parameters with their [`DEFAULTS`], after [`Case::contact_settings`]
    /// has checked their ranges.
    pub(super) fn settings_checked(&self) -> Result<Settings> {
        let max_outer = self.max_outer();
        Ok(match self.method_parameters()? {
            MethodParameters::Uzawa(parameters) => Settings::new(Uzawa::new(parameters), max_outer),
            MethodParameters::Newton(parameters) => {
                Settings::new(Newton::new(parameters), max_outer)
            }
        })
    }

    /// The `solver.method` table: the chosen method's parameters from `[solver]` with the
    /// defaults, before the range checks.
    pub(super) fn method_parameters(&self) -> Result<MethodParameters> {
        let (s, d) = (&self.file.solver, DEFAULTS);
        let r = match s.r {
            Some(r) => r,
            None => d.r_per_young * self.reference_modulus()?,
        };
        Ok(match s.method.unwrap_or(d.method) {
            MethodKey::Uzawa => MethodParameters::Uzawa(uzawa::Parameters {
                r,
                eps: s.eps.unwrap_or(d.eps),
                eps_fp: s.eps_fp.unwrap_or(d.eps_fp),
                max_inner: s.max_inner.unwrap_or(d.max_uzawa),
            }),
            MethodKey::Newton => MethodParameters::Newton(newton::Parameters {
                r,
                tol: s.tol.unwrap_or(d.tol),
                max_inner: s.max_inner.unwrap_or(d.max_newton),
                max_condensed: s.max_condensed,
                // A cap the file names is the first set's size; without one the solver
                // guesses, and the set grows as far as the contact zone.
                guess: match s.max_condensed {
                    Some(n) => Guess::Nearest(n),
                    None => Guess::Interpenetration(d.first_condensed),
                },
            }),
        })
    }

    /// solver.max_outer with its default.
    pub(super) fn max_outer(&self) -> usize {
        self.file.solver.max_outer.unwrap_or(DEFAULTS.max_outer)
    }

    /// The indices in `mesh` of the parts `names` that the list at `key` gives, each named
    /// once (a facet named twice would count twice). A load's list holds at least one part,
    /// for a load on no part would be dropped without a word, and its parts share no facet, on
    /// which it would act twice; only an electrode's may name groups inside the body.
    fn part_indices(
        &self,
        mesh: &Mesh,
        key: &str,
        names: &[String],
        list: PartList,
    ) -> Result<Vec<usize>> {
        let load = list == PartList::Load;
        if load && names.is_empty() {
            return Err(input!(
                "{}: {key} is empty: name the boundary parts the load acts on, or remove the table",
                self.locate(key)
            ));
        }
        if let Some(name) =
            names.iter().enumerate().find_map(|(k, n)| names[..k].contains(n).then_some(n))
        {
            return Err(input!(
                "{}: {key} names '{name}' twice: name each part once (its facets would count \
                 twice)",
                self.locate(key)
            ));
        }
        let index = |n: &String| match list {
            PartList::Electrode => mesh.any_part_index(n),
            PartList::Role | PartList::Load => mesh.part_index(n),
        };
        let indices: Vec<usize> = names
            .iter()
            .map(|n| index(n).map_err(|e| input!("{}: {key}: {e}", self.locate(key))))
            .collect::<Result<_>>()?;
        let shared = if load { mesh.facet_shared_within(&indices) } else { None };
        if let Some((first, second, nodes)) = shared {
            return Err(input!(
                "{}: {key}: parts '{first}' and '{second}' share the facet with nodes {nodes:?}, \
                 on which the load would act twice; name each facet in one part",
                self.locate(key)
            ));
        }
        Ok(indices)
    }

    /// The traction density f2 of a `[[boundary.traction]]` table on `parts` of `mesh`:
    /// constant when every component is a number, else a field of the position checked at
    /// the parts' nodes.
    fn traction_field(&self, mesh: &Mesh, f2: &[Quantity], parts: &[usize]) -> Result<VectorField> {
        let dim = mesh.dim();
        let key = "boundary.traction.f2";
        let numbers: Option<Vec<f64>> = f2
            .iter()
            .map(|q| match q {
                Quantity::Number(v) => Some(*v),
                Quantity::Expression(_) => None,
            })
            .collect();
        if f2.len() != dim || numbers.as_ref().is_some_and(|v| v.iter().any(|x| !x.is_finite())) {
            return Err(input!(
                "{}: {key} = [{}] must have {dim} finite components, numbers or expressions of the position (the mesh is {dim}D)",
                self.locate(key),
                f2.iter().map(Quantity::text).collect::<Vec<_>>().join(", ")
            ));
        }
        if let Some(v) = numbers {
            return Ok(constant_vector(v));
        }
        let nodes = part_points(mesh, parts);
        let fields = f2
            .iter()
            .enumerate()
            .map(|(k, q)| q.field(&format!("{}: {key}[{k}]", self.locate(key)), dim, &nodes))
            .collect::<Result<Vec<_>>>()?;
        Ok(Arc::new(move |x: &[f64]| fields.iter().map(|f| f(x)).collect()))
    }

    /// The `[[boundary.support]]` tables, checked, on `mesh` whose clamped parts are
    /// `clamped` (whose name the reactions use too).
    fn supports(&self, mesh: &Mesh, clamped: &[usize]) -> Result<Vec<Support>> {
        let key = "boundary.support";
        let dim = mesh.dim();
        let clamp: Vec<&str> = clamped.iter().map(|&p| mesh.parts()[p].name.as_str()).collect();
        let mut names: Vec<String> =
            (!clamp.is_empty()).then(|| clamp.join("+")).into_iter().collect();
        let mut supports = Vec::new();
        for (k, table) in self.file.boundary.support.iter().enumerate() {
            let at = format!("{} ([[boundary.support]] number {})", self.locate(key), k + 1);
            if table.parts.is_empty() {
                return Err(input!(
                    "{at}: parts is empty: name the boundary parts the support holds"
                ));
            }
            let parts =
                self.part_indices(mesh, "boundary.support.parts", &table.parts, PartList::Role)?;
            let points = part_points(mesh, &parts);
            let fixed = support_components(&at, (&table.fix, table.displacement.as_deref()), dim)
                .and_then(|fixed| displacement_fields(&at, fixed, dim, &points))?;
            let name = table.name.clone().unwrap_or_else(|| table.parts.join("+"));
            if names.contains(&name) {
                return Err(input!(
                    "{at}: the name '{name}' is taken by another clamp or support (reactions are reported by name): give it a name of its own with name = \"...\""
                ));
            }
            names.push(name.clone());
            supports.push(Support { name, parts, fixed });
        }
        Ok(supports)
    }

    /// The `[[boundary.electrode]]` tables, checked, on `mesh` whose grounded parts are
    /// `grounded` (whose `charge_<part>` columns the electrodes' names must not repeat).
    fn electrodes(&self, mesh: &Mesh, grounded: &[usize]) -> Result<Vec<Electrode>> {
        let key = "boundary.electrode";
        let mut taken: Vec<String> = ["center", "mean"].map(String::from).to_vec();
        taken.extend(grounded.iter().map(|&p| mesh.parts()[p].name.clone()));
        let mut electrodes = Vec::new();
        for (k, table) in self.file.boundary.electrode.iter().enumerate() {
            let at = format!("{} ([[boundary.electrode]] number {})", self.locate(key), k + 1);
            let name = table.name.clone();
            if taken.contains(&name) || name.is_empty() {
                return Err(input!(
                    "{at}: the name '{name}' is taken (curve.csv has phi_center, phi_mean and a charge_<part> column per grounded part, and each electrode its phi_<name> and charge_<name>): give the electrode a name of its own"
                ));
            }
            taken.push(name.clone());
            if table.parts.is_empty() {
                return Err(input!(
                    "{at}: parts is empty: name the boundary parts the electrode covers"
                ));
            }
            let parts = self.part_indices(
                mesh,
                "boundary.electrode.parts",
                &table.parts,
                PartList::Electrode,
            )?;
            let condition = match (table.voltage, table.charge) {
                (Some(v), None) if v.is_finite() => ElectrodeCondition::Voltage(v),
                (None, Some(q)) if q.is_finite() => ElectrodeCondition::Floating(q),
                (Some(v), None) | (None, Some(v)) => {
                    let key = if table.voltage.is_some() { "voltage" } else { "charge" };
                    return Err(input!("{at}: {key} = {v} must be a finite number"));
                }
                _ => {
                    return Err(input!(
                        "{at}: give the electrode one of voltage (its potential) or charge (a floating electrode's total charge; 0 for an open circuit), not both or neither"
                    ));
                }
            };
            electrodes.push(Electrode { name, parts, condition });
        }
        Ok(electrodes)
    }

    /// The problem, after [`Case::contact_settings`] has checked the ranges.
    pub(super) fn problem_checked(&self) -> Result<Problem> {
        let mesh = self.mesh()?;
        let dim = mesh.dim();
        let materials = self.materials(&mesh)?;
        let b = &self.file.boundary;
        let parts =
            |key: &str, names: &[String]| self.part_indices(&mesh, key, names, PartList::Role);
        let load_parts =
            |key: &str, names: &[String]| self.part_indices(&mesh, key, names, PartList::Load);
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
            let parts = load_parts("boundary.traction.parts", &t.parts)?;
            let f2 = self.traction_field(&mesh, &t.f2, &parts)?;
            traction.extend(parts.into_iter().map(|p| (p, f2.clone())));
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
            for p in load_parts("boundary.charge.parts", &c.parts)? {
                charge.push((p, constant_scalar(c.q2)));
            }
        }
        let clamped = parts("boundary.clamped", &b.clamped)?;
        let grounded = parts("boundary.grounded", &b.grounded)?;
        let boundary = Boundary {
            supports: self.supports(&mesh, &clamped)?,
            electrodes: self.electrodes(&mesh, &grounded)?,
            clamped,
            grounded,
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
        let problem = match self.plane_model(mesh.dim())? {
            Some(Plane::Axisymmetric) => {
                Problem::new_axisymmetric(mesh, materials, boundary, loads)
            }
            _ => Problem::new(mesh, materials, boundary, loads),
        };
        problem.map_err(|e| self.context(e))
    }
}

/// The fixed directions of a support table, `fix` (names of axes, or "normal") with their
/// `displacement` (default 0), in a d-dimensional mesh; `at` locates the table in errors.
fn support_components<'a>(
    at: &str,
    (fix, displacement): (&[String], Option<&'a [Quantity]>),
    dim: usize,
) -> Result<Vec<(Direction, Option<&'a Quantity>)>> {
    if fix.is_empty() {
        return Err(input!("{at}: fix is empty: name the components it fixes, e.g. fix = [\"z\"]"));
    }
    let axes = &["x", "y", "z"][..dim];
    let mut components = Vec::new();
    for name in fix {
        let direction = match axes.iter().position(|a| a == name) {
            Some(c) => Direction::Axis(c),
            None if name == "normal" => Direction::Normal,
            None => {
                return Err(input!(
                    "{at}: fix names '{name}', which is no component of the {dim}D mesh's displacement: use {axes:?} or \"normal\" (the outward normal of the parts)"
                ));
            }
        };
        if components.contains(&direction) {
            return Err(input!("{at}: fix names '{name}' twice: name each component once"));
        }
        components.push(direction);
    }
    match displacement {
        None => Ok(components.into_iter().map(|c| (c, None)).collect()),
        Some(d) if d.len() != fix.len() => Err(input!(
            "{at}: displacement has {} values and fix {} components: give one value per entry of fix",
            d.len(),
            fix.len()
        )),
        Some(d) => Ok(components.into_iter().zip(d.iter().map(Some)).collect()),
    }
}

/// The prescribed displacement of each fixed component (0 where none is given), as fields
/// checked at `points`; `at` locates the table in errors.
fn displacement_fields(
    at: &str,
    fixed: Vec<(Direction, Option<&Quantity>)>,
    dim: usize,
    points: &[&[f64]],
) -> Result<Vec<(Direction, ScalarField)>> {
    let zero = Quantity::Number(0.0);
    fixed
        .into_iter()
        .enumerate()
        .map(|(k, (c, q))| {
            let key = format!("{at}: displacement[{k}]");
            Ok((c, q.unwrap_or(&zero).field(&key, dim, points)?))
        })
        .collect()
}

/// The coordinates of the nodes of `parts` of `mesh`, each once.
fn part_points<'a>(mesh: &'a Mesh, parts: &[usize]) -> Vec<&'a [f64]> {
    mesh.part_nodes(parts).into_iter().map(|a| mesh.node(a)).collect()
}
