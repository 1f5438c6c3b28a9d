//! Where the foundation is and where a loading path moves it: `[foundation]` and `[loading]`
//! checked for a d-dimensional body (model §12, §14).

use super::file::Case;
use super::schema::{Depths, FoundationKind, FoundationSection, LoadingSection};
use super::validate::positive;
use crate::contact::rigid::RigidSurface;
use crate::contact::{ContactModel, ContactSurface, Foundation};
use crate::contact::{LoadStep, Loading};
use crate::dofs::DofMap;
use crate::error::Result;
use crate::problem::Problem;
use std::path::Path;
use std::sync::Arc;

/// The keys of one table, read for a d-dimensional body: each error names the key.
struct Keys<'a> {
    case: &'a Case,
    /// "foundation" or "loading".
    table: &'a str,
    /// What needs a missing key, e.g. `kind = "cone"`.
    needs: String,
    dim: usize,
}

impl Keys<'_> {
    fn locate(&self, key: &str) -> String {
        self.case.locate(&format!("{}.{key}", self.table))
    }

    fn present<T>(&self, key: &str, v: Option<T>) -> Result<T> {
        v.ok_or_else(|| {
            input!(
                "{}: {}.{key} is missing: {} needs it",
                self.case.locate(self.table),
                self.table,
                self.needs
            )
        })
    }

    /// A point of d finite components.
    fn vector(&self, key: &str, v: &Option<Vec<f64>>) -> Result<[f64; 3]> {
        let (v, dim) = (self.present(key, v.as_ref())?, self.dim);
        if v.len() != dim || v.iter().any(|x| !x.is_finite()) {
            return Err(input!(
                "{}: {}.{key} = {v:?} must have {dim} finite components (the mesh is {dim}D)",
                self.locate(key),
                self.table
            ));
        }
        let mut out = [0.0; 3];
        out[..dim].copy_from_slice(v);
        Ok(out)
    }

    /// A nonzero vector of d finite components, normalised; `what` says which way it points.
    fn direction(&self, key: &str, v: &Option<Vec<f64>>, what: &str) -> Result<[f64; 3]> {
        let d = self.vector(key, v)?;
        let norm = d.iter().map(|v| v * v).sum::<f64>().sqrt();
        if !(norm > 0.0 && norm.is_finite()) {
            return Err(input!(
                "{}: {}.{key} = {:?} is not allowed: a nonzero vector, {what}",
                self.locate(key),
                self.table,
                v.as_deref().unwrap_or_default()
            ));
        }
        Ok(d.map(|v| v / norm))
    }

    /// A length > 0.
    fn length(&self, key: &str, v: Option<f64>) -> Result<f64> {
        let v = self.present(key, v)?;
        if !positive(v) {
            return Err(input!(
                "{}: {}.{key} = {v} is not allowed: a length > 0",
                self.locate(key),
                self.table
            ));
        }
        Ok(v)
    }

    /// A list of at least one finite number.
    fn finite(&self, key: &str, values: &[f64]) -> Result<()> {
        if values.is_empty() {
            return Err(input!(
                "{}: {}.{key} is empty: give at least one step",
                self.locate(key),
                self.table
            ));
        }
        match values.iter().position(|v| !v.is_finite()) {
            Some(k) => Err(input!(
                "{}: {}.{key}[{k}] is not a finite number",
                self.locate(key),
                self.table
            )),
            None => Ok(()),
        }
    }
}

/// The case-file name of a foundation kind.
fn kind_name(kind: FoundationKind) -> &'static str {
    match kind {
        FoundationKind::Plane => "plane",
        FoundationKind::Sphere => "sphere",
        FoundationKind::Cone => "cone",
        FoundationKind::Punch => "punch",
        FoundationKind::Surface => "surface",
    }
}

/// The `[foundation]` keys of a kind.
fn kind_keys(kind: FoundationKind) -> &'static [&'static str] {
    match kind {
        FoundationKind::Plane => &["point", "normal"],
        FoundationKind::Sphere => &["center", "radius"],
        FoundationKind::Cone => &["apex", "axis", "half_angle"],
        FoundationKind::Punch => &["center", "axis", "radius"],
        FoundationKind::Surface => &["file"],
    }
}

/// The key of `f` that its kind does not read, if any.
fn misplaced_key(f: &FoundationSection) -> Option<&'static str> {
    let keys = [
        ("point", f.point.is_some()),
        ("normal", f.normal.is_some()),
        ("center", f.center.is_some()),
        ("radius", f.radius.is_some()),
        ("apex", f.apex.is_some()),
        ("axis", f.axis.is_some()),
        ("half_angle", f.half_angle.is_some()),
        ("file", f.file.is_some()),
    ];
    let belongs = kind_keys(f.kind);
    keys.into_iter().find(|(key, set)| *set && !belongs.contains(key)).map(|(key, _)| key)
}

impl Case {
    /// The foundation of `[foundation]`, checked for a d-dimensional body.
    pub fn foundation(&self, dim: usize) -> Result<Foundation> {
        let Some(f) = &self.file.foundation else { return Ok(Foundation::ConstantGap) };
        if let Some(key) = misplaced_key(f) {
            return Err(input!(
                "{}: foundation.{key} does not belong to kind = \"{}\"; remove it (a plane has point and normal, a sphere center and radius, a cone apex, axis and half_angle, a punch center, axis and radius, a surface file)",
                self.locate(&format!("foundation.{key}")),
                kind_name(f.kind)
            ));
        }
        let needs = format!("kind = \"{}\"", kind_name(f.kind));
        let keys = Keys { case: self, table: "foundation", needs, dim };
        let away = "from the indenter's tip into it, away from the body";
        Ok(match f.kind {
            FoundationKind::Plane => Foundation::Plane {
                point: keys.vector("point", &f.point)?,
                normal: keys.direction(
                    "normal",
                    &f.normal,
                    "out of the foundation toward the body",
                )?,
            },
            FoundationKind::Sphere => Foundation::Sphere {
                center: keys.vector("center", &f.center)?,
                radius: keys.length("radius", f.radius)?,
            },
            FoundationKind::Cone => {
                let degrees = keys.present("half_angle", f.half_angle)?;
                if !(degrees.is_finite() && degrees > 0.0 && degrees < 90.0) {
                    return Err(input!(
                        "{}: foundation.half_angle = {degrees} is not allowed: degrees between the axis and the flank, in (0, 90)",
                        self.locate("foundation.half_angle")
                    ));
                }
                Foundation::Cone {
                    apex: keys.vector("apex", &f.apex)?,
                    axis: keys.direction("axis", &f.axis, away)?,
                    half_angle: degrees.to_radians(),
                }
            }
            FoundationKind::Punch => Foundation::Punch {
                center: keys.vector("center", &f.center)?,
                axis: keys.direction("axis", &f.axis, away)?,
                radius: keys.length("radius", f.radius)?,
            },
            FoundationKind::Surface => {
                let file = keys.present("file", f.file.as_ref())?;
                if dim != 3 {
                    return Err(input!(
                        "{}: kind = \"surface\" is a rigid surface in 3D; this mesh is {dim}D: use a plane, a sphere, a cone (a wedge) or a punch (a strip)",
                        self.locate("foundation.kind")
                    ));
                }
                let full = self.path().parent().unwrap_or(Path::new(".")).join(file);
                let surface = RigidSurface::read(&full).map_err(|e| {
                    input!("{}: foundation.file: {e}", self.locate("foundation.file"))
                })?;
                Foundation::Surface { surface: Arc::new(surface), shift: [0.0; 3] }
            }
        })
    }

    /// Refuses a foundation that no Γ3 normal meets — where the case puts it, or at any step
    /// of its loading path: nothing could touch it, and the run would end with no contact
    /// (mostly an axis or a normal the wrong way round). Refuses too a path that carries the
    /// foundation through Γ3: a step where no Γ3 normal meets it but a reversed one does, so
    /// that it lies behind the contact face, inside or beyond the body, where no gap along
    /// the outward normals sees it and the step would end without contact (depths of
    /// millimetres given in metres, say). A step that neither meets, beside Γ3, is a path
    /// that carries the foundation away sideways, and passes.
    pub(super) fn check_reach(
        &self,
        problem: &Problem,
        model: &ContactModel,
        loading: Option<&Loading>,
    ) -> Result<()> {
        // Γ3 built once here also refuses a support that holds its normal component.
        let dofs = DofMap::new(problem)?;
        let gamma3 = ContactSurface::new(problem, &dofs)?;
        let Some((key, hint)) = reach_hint(&model.foundation) else { return Ok(()) };
        if gamma3.is_empty() {
            return Ok(());
        }
        // Whether some Γ3 normal (sign 1) or reversed normal (sign −1) meets the foundation.
        let meets = |foundation: &Foundation, sign: f64| {
            (0..gamma3.len()).any(|i| {
                let nu = gamma3.normal[i].map(|v| sign * v);
                foundation.distance_along(gamma3.position3(problem, i), nu).is_finite()
            })
        };
        let steps = loading.map_or(&[][..], |path| &path.steps[..]);
        let positions: Vec<Foundation> = match loading {
            Some(path) if !steps.is_empty() => {
                steps.iter().map(|step| path.foundation_at(&model.foundation, step)).collect()
            }
            _ => vec![model.foundation.clone()],
        };
        let reached: Vec<bool> = positions.iter().map(|f| meets(f, 1.0)).collect();
        let through = (0..positions.len()).find(|&k| !reached[k] && meets(&positions[k], -1.0));
        // A foundation in reach where the case puts it that every step carries through Γ3
        // is a path too deep, not a foundation misplaced.
        let deep = through.is_some() && loading.is_some() && meets(&model.foundation, 1.0);
        if !reached.contains(&true) && !deep {
            let at = if positions.len() > 1 { " at any step of the loading path" } else { "" };
            return Err(input!(
                "{}: no normal of the {} Γ3 nodes meets the foundation{at}: {hint}",
                self.locate(key),
                gamma3.len()
            ));
        }
        through.map_or(Ok(()), |k| {
            Err(input!(
                "{}: loading.depths: at step {} (depth {} {}) the foundation has passed through Γ3: no Γ3 normal meets it and the reversed normals do, so it lies behind the contact face, where no gap can see it; keep the depths within the foundation's reach, in the case's unit of length ([units] length)",
                self.locate("loading.depths"),
                k + 1,
                steps[k].depth,
                self.file.units.length
            ))
        })
    }

    /// The loading path of `[loading]` for a d-dimensional body, `None` without the table;
    /// without `[contact]`, load factors only (a path of solves without contact).
    pub fn loading(&self, dim: usize) -> Result<Option<Loading>> {
        let Some(l) = &self.file.loading else { return Ok(None) };
        if self.file.contact.is_none() && l.depths.is_some() {
            return Err(input!(
                "{}: loading.depths moves the foundation, which only a case with a [contact] table has: add [contact], or scale the loads with loading.load_factors alone",
                self.locate("loading.depths")
            ));
        }
        let needs = "loading.depths (it moves the foundation along it)".to_string();
        let keys = Keys { case: self, table: "loading", needs, dim };
        let depths = self.depths(&keys, l)?;
        let mut direction = [0.0; 3];
        if depths.is_some() {
            let what = "the way the indenter travels";
            direction = keys.direction("direction", &l.direction, what)?;
        } else if l.direction.is_some() {
            return Err(input!(
                "{}: loading.direction without loading.depths moves nothing: give the depths, or remove it",
                keys.locate("direction")
            ));
        }
        if let Some(f) = &l.load_factors {
            keys.finite("load_factors", f)?;
        }
        let mut steps = match (depths, &l.load_factors) {
            (None, None) if l.electrode_factors.is_some() => Vec::new(),
            (None, None) => {
                return Err(input!(
                    "{}: [loading] needs loading.depths (the foundation's path), loading.load_factors (the loads' factors) or loading.electrode_factors (the electrodes')",
                    self.locate("loading")
                ));
            }
            (Some(d), Some(f)) if d.len() != f.len() => {
                return Err(input!(
                    "{}: loading.depths has {} steps and loading.load_factors {}: give both the same number of steps",
                    keys.locate("load_factors"),
                    d.len(),
                    f.len()
                ));
            }
            (Some(d), f) => d
                .iter()
                .enumerate()
                .map(|(k, &depth)| LoadStep {
                    depth,
                    load_factor: f.as_ref().map_or(1.0, |f| f[k]),
                    electrode_factor: f.as_ref().map_or(1.0, |f| f[k]),
                })
                .collect(),
            (None, Some(f)) => f
                .iter()
                .map(|&load_factor| LoadStep {
                    depth: 0.0,
                    load_factor,
                    electrode_factor: load_factor,
                })
                .collect(),
        };
        if let Some(e) = &l.electrode_factors {
            self.electrode_factors(&keys, e, &mut steps)?;
        }
        Ok(Some(Loading { direction, steps }))
    }

    /// Puts `loading.electrode_factors` (`factors`) on the `steps` of the depths or load
    /// factors (steps at load factor 1 without either), one per step.
    fn electrode_factors(
        &self,
        keys: &Keys,
        factors: &[f64],
        steps: &mut Vec<LoadStep>,
    ) -> Result<()> {
        keys.finite("electrode_factors", factors)?;
        if self.file.boundary.electrode.is_empty() {
            return Err(input!(
                "{}: loading.electrode_factors scales the electrodes' voltages and charges, and the case has no [[boundary.electrode]]: add one, or remove the key",
                keys.locate("electrode_factors")
            ));
        }
        if steps.is_empty() {
            let step = LoadStep { depth: 0.0, load_factor: 1.0, electrode_factor: 1.0 };
            steps.resize(factors.len(), step);
        }
        if factors.len() != steps.len() {
            return Err(input!(
                "{}: loading.electrode_factors has {} steps and the path {} (its depths or load_factors): give one factor per step",
                keys.locate("electrode_factors"),
                factors.len(),
                steps.len()
            ));
        }
        steps.iter_mut().zip(factors).for_each(|(s, &f)| s.electrode_factor = f);
        Ok(())
    }

    /// The depths of `[loading]`, checked, `None` without them; a case with depths needs a
    /// foundation to move.
    fn depths(&self, keys: &Keys, l: &LoadingSection) -> Result<Option<Vec<f64>>> {
        let depths = match &l.depths {
            None => return Ok(None),
            Some(Depths::List(list)) => list.clone(),
            Some(Depths::Range { from, to, steps }) => {
                if *steps == 0 {
                    return Err(input!(
                        "{}: loading.depths has steps = 0: at least 1",
                        keys.locate("depths")
                    ));
                }
                (1..=*steps).map(|k| from + (to - from) * k as f64 / *steps as f64).collect()
            }
        };
        keys.finite("depths", &depths)?;
        if self.file.foundation.is_none() {
            return Err(input!(
                "{}: loading.depths moves the foundation, and the case has none: add a [foundation] table (plane, sphere, cone or punch), or scale the loads with loading.load_factors",
                keys.locate("depths")
            ));
        }
        Ok(Some(depths))
    }
}

/// The key to point at and what to check in a foundation that no Γ3 normal meets; `None` for
/// the paper's constant gap, which every normal meets.
fn reach_hint(foundation: &Foundation) -> Option<(&'static str, String)> {
    let (key, hint) = match foundation {
        Foundation::ConstantGap => return None,
        Foundation::Plane { .. } => (
            "foundation.normal",
            "foundation.normal points out of the foundation toward the body; check its sign and foundation.point".into(),
        ),
        Foundation::Sphere { .. } => (
            "foundation.center",
            "move foundation.center in front of the contact parts, or enlarge foundation.radius".into(),
        ),
        Foundation::Cone { .. } => (
            "foundation.axis",
            "foundation.axis points from the apex into the cone, away from the body; check its sign and foundation.apex".into(),
        ),
        Foundation::Punch { .. } => (
            "foundation.axis",
            "foundation.axis points from the punch's face into the punch, away from the body; check its sign and foundation.center".into(),
        ),
        Foundation::Surface { surface, .. } => (
            "foundation.file",
            format!(
                "foundation.file: {}: move it (it is read in the mesh's coordinates) in front of the contact parts",
                surface.file.display()
            ),
        ),
    };
    Some((key, hint))
}
