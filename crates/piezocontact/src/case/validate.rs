//! The checks of a case: every number finite and of moderate magnitude, every key within its
//! range (with the file, the line, the key and the requirement in the message), and the
//! paper's hypotheses and unused keys reported as warnings.

use super::build::MethodParameters;
use super::file::Case;
use super::schema::{
    BackendKey, FrictionPathKey, LinearKey, MethodKey, ProblemKey, RegularizationKey,
};
use crate::error::Result;
use crate::material::{ElasticLaw, Material, Materials};

/// The largest magnitude of a number in a case file, and the smallest nonzero one: the model
/// multiplies and squares its inputs, and beyond these bounds double precision overflows or
/// underflows. Every physical constant lies well inside them in any sensible units.
pub const MAGNITUDE: f64 = 1e30;
/// The smallest magnitude of a nonzero number in a case file (1/[`MAGNITUDE`]).
pub const MIN_MAGNITUDE: f64 = 1e-30;

/// `key.name`, or `name` at the top.
pub(super) fn dotted(key: &str, name: &str) -> String {
    if key.is_empty() { name.to_string() } else { format!("{key}.{name}") }
}

impl Case {
    /// Refuses every float of `item` (at dotted key `key`) that is not finite, or whose
    /// magnitude lies outside [MIN_MAGNITUDE, MAGNITUDE] without being zero.
    pub(super) fn check_magnitudes(&self, key: &str, item: &toml_edit::Item) -> Result<()> {
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

    /// Checks the ranges of the contact, friction, conductivity and solver keys, and returns
    /// them as `(key, value)` lines for reports. The contact algorithms use them.
    pub fn contact_settings(&self) -> Result<Vec<(String, f64)>> {
        // The default r is a multiple of E: the material's constants first, by their own check.
        self.material_constants()?;
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
                    "friction.regularization = \"mollifier\" needs its radius a > 0",
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
        let at_least_one = |v: f64| v >= 1.0;
        match self.method_parameters()? {
            MethodParameters::Uzawa(p) => rules.extend([
                Rule("solver.r", p.r, positive, "r > 0"),
                Rule("solver.eps", p.eps, positive, "ε > 0"),
                Rule("solver.eps_fp", p.eps_fp, positive, "ε_fp > 0"),
                Rule("solver.max_inner", p.max_inner as f64, at_least_one, "at least 1"),
            ]),
            MethodParameters::Newton(p) => {
                rules.extend([
                    Rule("solver.r", p.r, positive, "r > 0"),
                    Rule("solver.tol", p.tol, positive, "a tolerance > 0"),
                    Rule("solver.max_inner", p.max_inner as f64, at_least_one, "at least 1"),
                ]);
                if let Some(cap) = p.max_condensed {
                    rules.push(Rule(
                        "solver.max_condensed",
                        cap as f64,
                        at_least_one,
                        "at least 1",
                    ));
                }
            }
        }
        rules.push(Rule("solver.max_outer", self.max_outer() as f64, at_least_one, "at least 1"));
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
    /// numbers (Section 2 of \[P\]); an empty list when all hold.
    pub fn hypothesis_warnings(&self, materials: &Materials) -> Vec<String> {
        let several = materials.list().len() > 1;
        let mut warnings = Vec::new();
        for named in materials.list() {
            let prefix =
                if several { format!("material '{}': ", named.name) } else { String::new() };
            let of_one = Self::material_warnings(&named.material);
            warnings.extend(of_one.into_iter().map(|w| format!("{prefix}{w}")));
        }
        warnings
    }

    /// [`Case::hypothesis_warnings`] of one material.
    fn material_warnings(material: &Material) -> Vec<String> {
        let Some(el) = material.elasticity() else {
            return Vec::new(); // (h1) is about Hencky's isotropic law.
        };
        let d = material.dim as f64;
        let mut warnings = Vec::new();
        if el.mu1 > 0.5 * d * el.k0 {
            warnings.push(format!(
                "(h1)(a) fails: g(0) = µ1 = {:.4e} exceeds d·k0/2 = {:.4e} (Poisson's ratio {:.4} is below the bound of (h1)(a) in {}D)",
                el.mu1,
                0.5 * d * el.k0,
                el.poisson(),
                material.dim
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
        // One warning for all of them, at the first: a case written for one method and run
        // with the other (`--set solver.method=...`) sets both of its keys.
        let keys: Vec<String> =
            unused.iter().filter(|(_, set)| *set).map(|(key, _)| format!("solver.{key}")).collect();
        let mut warnings = Vec::new();
        if let Some(first) = keys.first() {
            let (is, it) = if keys.len() == 1 { ("is", "it") } else { ("are", "them") };
            warnings.push(format!(
                "{}: {} {is} not used by solver.method = \"{method}\" (only {other} reads {it}; newton stops on solver.tol, uzawa on solver.eps and solver.eps_fp)",
                self.locate(first),
                keys.join(", ")
            ));
        }
        if s.backend == Some(BackendKey::Petsc) && s.ordering.is_some() {
            warnings.push(format!(
                "{}: solver.ordering is faer's; with solver.backend = \"petsc\" MUMPS chooses its own ordering (PETSc option -mat_mumps_icntl_7)",
                self.locate("solver.ordering")
            ));
        }
        let whole = s.linear == Some(LinearKey::Iterative) && method == "newton";
        if whole && s.max_condensed.is_some() {
            warnings.push(format!(
                "{}: solver.max_condensed is not used with solver.linear = \"iterative\": the exact solver runs on the whole system there, every Γ3 node that can touch the foundation in it",
                self.locate("solver.max_condensed")
            ));
        }
        warnings.extend(self.model_warnings());
        warnings.extend(self.segment_warnings());
        warnings
    }

    /// Segments of the built-in rectangle whose ends fall between two nodes, as warnings:
    /// the part holds only the facets wholly inside the segment and stops short of the end
    /// (`[2,10]x{0}` with 100 cells over 12 m holds 7.92 m).
    fn segment_warnings(&self) -> Vec<String> {
        // A Gmsh mesh (no rectangle), or a rectangle the checks refuse: nothing to warn of.
        let Ok((rectangle, parts)) = self.rectangle() else { return Vec::new() };
        // Coordinates to 12 significant digits: 1.92, not 1.9200000000000002.
        let tidy = |v: f64| format!("{v:.11e}").parse::<f64>().unwrap_or(v);
        let mut warnings = Vec::new();
        for (name, segments) in &parts {
            let key = format!("mesh.segments.{name}");
            for (spec, segment) in self.file.mesh.segments[name].iter().zip(segments) {
                let ends = rectangle.ends_between_nodes(segment);
                let Some(&(axis, _, _)) = ends.first() else { continue };
                let between: Vec<String> = ends
                    .iter()
                    .map(|&(axis, end, [below, above])| {
                        let c = ["x", "y"][axis];
                        format!("{c} = {end} (nodes at {} and {})", tidy(below), tidy(above))
                    })
                    .collect();
                warnings.push(format!(
                    "{}: {key}: '{spec}' ends between two nodes at {}: the part holds only the facets wholly inside the segment; choose {} so that its ends are nodes",
                    self.locate(&key),
                    between.join(" and "),
                    ["mesh.nx", "mesh.ny"][axis]
                ));
            }
        }
        warnings
    }

    /// Keys of `[friction]` and `[conductivity]` that the problem does not read, as warnings:
    /// friction and k_e under PV1 (frictionless, a nonconductive foundation), a mollifier's
    /// radius without the mollifier, an incremental friction path without a loading path.
    fn model_warnings(&self) -> Vec<String> {
        let f = &self.file;
        let pv1 = self.problem_kind() == ProblemKey::PV1;
        let mut warnings = Vec::new();
        let mut unused = |key: &str, why: &str| {
            warnings.push(format!("{}: {key} is not used: {why}", self.locate(key)));
        };
        if let Some(friction) = f.friction.as_ref() {
            let mollifier = friction.regularization == RegularizationKey::Mollifier;
            if pv1 && (friction.mu != 0.0 || !friction.mu_parts.is_empty() || mollifier) {
                unused(
                    "friction",
                    "contact.problem = \"PV1\" is frictionless (set \"PV2\" for friction)",
                );
            }
            if friction.radius != 0.0 && !mollifier {
                unused("friction.radius", "only friction.regularization = \"mollifier\" reads it");
            }
            if friction.path == FrictionPathKey::Incremental && f.loading.is_none() {
                unused(
                    "friction.path",
                    "\"incremental\" measures the slip from the previous step of a [loading] path, and the case has none (one run is static)",
                );
            }
        }
        if pv1 && f.conductivity.as_ref().is_some_and(|k| k.ke != 0.0) {
            unused(
                "conductivity.ke",
                "contact.problem = \"PV1\" has a nonconductive foundation (it reads conductivity.phi0 alone; set \"PV2\" for conduction)",
            );
        }
        warnings
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
}

/// A range rule: key, value, test, and the requirement stated in the error.
struct Rule(&'static str, f64, fn(f64) -> bool, &'static str);

pub(super) fn positive(v: f64) -> bool {
    v.is_finite() && v > 0.0
}

pub(super) fn nonnegative(v: f64) -> bool {
    v.is_finite() && v >= 0.0
}
