//! `[material]` or `[[material]]` read into materials: each table's constants ([`Constants`],
//! in its own axes: one form of each group — elastic, piezoelectric, dielectric — checked, the
//! strain-charge form converted once into the stress-charge form the solver uses), its axes in
//! the mesh, and the regions it fills.

use super::file::Case;
use super::schema::{DEFAULTS, LawKey, MaterialSection, MaterialTables, NumberOrRow, PlaneKey};
use crate::error::{Error, Result};
use crate::material::library::{self, EPS0_SI, Preset, UnitScale};
use crate::material::plane::{Plane, plane_material};
use crate::material::voigt::{self, Coupling, Matrix3, PiezoForm, Voigt};
use crate::material::{
    Constants, ElasticConstants, ElasticLaw, Elasticity, Material, NamedMaterial, PiezoConstants,
    orientation,
};

/// One material table with the dotted key that names it in messages and overrides:
/// `material` for `[material]` (or a lone unnamed `[[material]]`), `material.<name>` for a
/// named one.
pub(super) struct Table<'a> {
    case: &'a Case,
    /// The key of the table.
    pub key: String,
    /// The table.
    pub table: &'a MaterialSection,
}

impl Case {
    /// The material tables, each with its key.
    pub(super) fn material_tables(&self) -> Vec<Table<'_>> {
        let many = matches!(self.file.material, MaterialTables::Many(_));
        let tables = self.file.material.tables();
        tables
            .iter()
            .map(|table| {
                let key = match (&table.name, many) {
                    (Some(name), true) => format!("material.{name}"),
                    _ => "material".to_string(),
                };
                Table { case: self, key, table }
            })
            .collect()
    }

    /// Every material table's constants, checked.
    pub fn material_constants(&self) -> Result<Vec<Constants>> {
        self.material_tables().iter().map(Table::constants).collect()
    }

    /// The modulus a default scales with \[stress\]: the largest over the materials of
    /// [`Constants::reference_modulus`], an isotropic material's E as the file gives it.
    pub fn reference_modulus(&self) -> Result<f64> {
        let mut largest = 0.0_f64;
        for table in self.material_tables() {
            let modulus = match (table.constants()?, table.table.young) {
                (Constants { elastic: ElasticConstants::Isotropic(_), .. }, Some(young)) => young,
                (constants, _) => constants.reference_modulus()?,
            };
            largest = largest.max(modulus);
        }
        Ok(largest)
    }
}

impl Case {
    /// The plane model of `mesh.plane` for a mesh of dimension `dim` (None: the 3D body or
    /// the paper's 2D continuum).
    pub fn plane_model(&self, dim: usize) -> Result<Option<Plane>> {
        let plane = self.file.mesh.plane.unwrap_or(PlaneKey::Continuum);
        match (plane, dim) {
            (PlaneKey::Continuum, _) => Ok(None),
            (_, 3) => Err(input!(
                "{}: mesh.plane = {plane:?} is for 2D meshes: remove it for a 3D body",
                self.locate("mesh.plane")
            )),
            (PlaneKey::Strain, _) => Ok(Some(Plane::Strain)),
            (PlaneKey::Stress, _) => Ok(Some(Plane::Stress)),
            (PlaneKey::Axisymmetric, _) => Ok(Some(Plane::Axisymmetric)),
        }
    }
}

impl Table<'_> {
    /// "file:line" of the key `sub` of this table (of the table itself for "").
    fn locate(&self, sub: &str) -> String {
        if sub.is_empty() {
            self.case.locate(&self.key)
        } else {
            self.case.locate(&format!("{}.{sub}", self.key))
        }
    }

    /// Places an error of the material module at this table's key.
    fn context(&self, e: Error) -> Error {
        match e {
            Error::InvalidParameter { name, value, requirement } => {
                let sub = name.strip_prefix("material.").unwrap_or(&name);
                let location = self.locate(sub);
                let name = format!("{}.{sub}", self.key);
                let error = Error::InvalidParameter { name, value, requirement };
                Error::Located { location, error: Box::new(error) }
            }
            e => self.case.context(e),
        }
    }

    /// The material in dimension `dim`, named.
    pub fn material(&self, dim: usize) -> Result<NamedMaterial> {
        let m = self.table;
        let name = m.name.clone().unwrap_or_else(|| "material".into());
        if let Some(plane) = self.case.plane_model(dim)? {
            let constants = self.constants()?;
            let solid = Material::from_constants(3, &constants, &self.plane_axes()?)
                .map_err(|e| self.context(e))?;
            let material =
                plane_material(&solid, &constants.elastic, plane).map_err(|e| self.context(e))?;
            return Ok(NamedMaterial { name, material });
        }
        let tensors = [
            ("c", m.c.is_some()),
            ("s", m.s.is_some()),
            ("e", m.e.is_some()),
            ("d", m.d.is_some()),
        ];
        if dim == 2
            && let Some(key) = tensors.into_iter().find_map(|(k, given)| given.then_some(k))
        {
            return Err(input!(
                "{}: {}.{key}: the 2D continuum model takes young and poisson with the ceramic shorthand (e31, e33, e15): full tensors need a 3D mesh",
                self.locate(key),
                self.key
            ));
        }
        let axes = self.axes(dim)?;
        let material = Material::from_constants(dim, &self.constants()?, &axes)
            .map_err(|e| self.context(e))?;
        Ok(NamedMaterial { name, material })
    }

    /// The material's axes in a plane model: `poling` a vector of the plane (default +y);
    /// axis 1 is the poling turned by −90° in the plane and axis 2 = −e_z.
    fn plane_axes(&self) -> Result<Matrix3> {
        let k = &self.key;
        if self.table.euler.is_some() {
            return Err(input!(
                "{}: {k}.euler: the plane models turn a material in the plane only: give poling, a vector of the plane",
                self.locate("euler")
            ));
        }
        let Some(p) = &self.table.poling else {
            return Ok(orientation::axes_from_poling([0.0, 1.0, 0.0]));
        };
        let at = self.locate("poling");
        let in_plane = match p[..] {
            [x, y] | [x, y, 0.0] => [x, y],
            _ => {
                return Err(input!(
                    "{at}: {k}.poling = {p:?} must be a vector of the plane, [x, y]"
                ));
            }
        };
        if in_plane.iter().any(|v| !v.is_finite()) || in_plane == [0.0, 0.0] {
            return Err(input!("{at}: {k}.poling = {p:?} must be a finite, nonzero vector"));
        }
        Ok(orientation::axes_from_poling([in_plane[0], in_plane[1], 0.0]))
    }

    /// The material's axes in the mesh ([`orientation`]): from `poling` or `euler`, else the
    /// mesh's own.
    fn axes(&self, dim: usize) -> Result<Matrix3> {
        let (k, m) = (&self.key, self.table);
        let (key, given) = match (&m.poling, &m.euler) {
            (None, None) => return Ok(orientation::IDENTITY),
            (Some(_), Some(_)) => {
                return Err(input!(
                    "{}: {k} gives both poling and euler: keep one (euler fixes all three axes, poling axis 3 with a rule for the others)",
                    self.locate("euler")
                ));
            }
            (Some(p), None) => ("poling", p),
            (None, Some(e)) => ("euler", e),
        };
        let at = self.locate(key);
        if dim != 3 {
            return Err(input!(
                "{at}: {k}.{key}: the 2D continuum model is poled along y; a turned material needs a 3D mesh"
            ));
        }
        let [a, b, c] = given[..] else {
            return Err(input!("{at}: {k}.{key} = {given:?} must have 3 numbers"));
        };
        if given.iter().any(|v| !v.is_finite()) {
            return Err(input!("{at}: {k}.{key} = {given:?} must be finite numbers"));
        }
        if key == "euler" {
            return Ok(orientation::axes_from_euler([a, b, c]));
        }
        if a == 0.0 && b == 0.0 && c == 0.0 {
            return Err(input!(
                "{at}: {k}.poling = {given:?} has zero length: give the direction of the poling, e.g. [0, 0, 1]"
            ));
        }
        Ok(orientation::axes_from_poling([a, b, c]))
    }

    /// The preset the table names, with the case's units to convert it to; an error naming
    /// the presets for an unknown one, or the unit label that is not converted.
    fn preset(&self) -> Result<Option<(Preset, UnitScale)>> {
        let Some(name) = &self.table.preset else { return Ok(None) };
        let at = self.locate("preset");
        let preset = library::find(name).map_err(|names| {
            input!("{at}: {}.preset = \"{name}\" is no preset of the library ({names}; `piezocontact materials` lists them)", self.key)
        })?;
        let u = &self.case.file.units;
        let scale = UnitScale::of_labels(&u.length, &u.stress, &u.charge, &u.potential).map_err(|label| {
            input!(
                "{at}: the preset {name} is in SI and the case's unit '{label}' is none piezocontact converts (m, mm, µm; Pa, MPa, GPa; C, µC, nC, pC; V, kV, GV …): give the constants in the case's units instead"
            )
        })?;
        Ok(Some((preset, scale)))
    }

    /// The constants in the material's own axes, every group checked.
    pub fn constants(&self) -> Result<Constants> {
        let preset = self.preset()?;
        let elastic = self.elastic_constants(preset)?;
        let c = elastic.stiffness();
        let piezo = self.piezo_form(preset)?;
        let given = self.permittivity(preset)?;
        let (e, permittivity) = piezo.stress_charge(&c, &given);
        let smallest = voigt::smallest_eigenvalue(&permittivity)?;
        if smallest.is_nan() || smallest <= 0.0 {
            let strain = matches!(piezo, PiezoForm::Strain(_));
            let what = if strain { "ε^S = ε^T − d c^E dᵀ" } else { "the permittivity ε^S" };
            return Err(input!(
                "{}: {}: {what} is not positive definite (smallest eigenvalue {smallest:e}): check the dielectric constants{}",
                self.locate("eps0"),
                self.key,
                if strain { " (ε^T with d) and d" } else { "" }
            ));
        }
        Ok(Constants { elastic, e, permittivity })
    }

    /// The elastic group: young and poisson (Hencky's law), c or s.
    fn elastic_constants(&self, preset: Option<(Preset, UnitScale)>) -> Result<ElasticConstants> {
        let (k, m) = (&self.key, self.table);
        let isotropic = m.young.is_some() || m.poisson.is_some();
        let forms = [("young and poisson", isotropic), ("c", m.c.is_some()), ("s", m.s.is_some())];
        let given: Vec<&str> = forms.iter().filter(|f| f.1).map(|f| f.0).collect();
        let at = self.locate("");
        match given.as_slice() {
            [] => {
                if let Some((preset, scale)) = preset {
                    let c = preset.stiffness.map(|row| row.map(|v| v * scale.stress()));
                    return Ok(ElasticConstants::Stiffness(Box::new(c)));
                }
                return Err(input!(
                    "{at}: {k} has no elastic constants: give young and poisson (isotropic), c (the 6 × 6 stiffness), s (the 6 × 6 compliance) or a preset"
                ));
            }
            [_] => {}
            _ => {
                return Err(input!(
                    "{at}: {k} gives the elastic constants twice ({}): keep one form",
                    given.join(", ")
                ));
            }
        }
        if isotropic {
            let (Some(young), Some(poisson)) = (m.young, m.poisson) else {
                let missing = if m.young.is_none() { "young" } else { "poisson" };
                return Err(input!(
                    "{at}: {k}.{missing} is missing: the isotropic form takes young and poisson"
                ));
            };
            let law = match m.law.unwrap_or(DEFAULTS.law) {
                LawKey::Hencky => ElasticLaw::Hencky { t0: m.t0 },
                LawKey::Linear => ElasticLaw::Linear,
            };
            let elasticity = Elasticity::from_young_poisson(young, poisson, law);
            return elasticity.map(ElasticConstants::Isotropic).map_err(|e| self.context(e));
        }
        if let Some(LawKey::Hencky) = m.law {
            return Err(input!(
                "{}: {k}.law = \"hencky\": Hencky's law needs the isotropic form (young, poisson); a stiffness tensor is linear",
                self.locate("law")
            ));
        }
        let (key, matrix) = match (&m.c, &m.s) {
            (Some(c), _) => ("c", c),
            (_, Some(s)) => ("s", s),
            _ => unreachable!("one elastic form was given"),
        };
        let given: Voigt = self.matrix(key, matrix)?;
        let name = if key == "c" { "the stiffness c^E" } else { "the compliance s^E" };
        let given = self.positive_definite(key, name, &given)?;
        Ok(ElasticConstants::Stiffness(Box::new(if key == "c" {
            given
        } else {
            voigt::inverse(&given)?
        })))
    }

    /// The piezoelectric group: the ceramic shorthand, e or d; none for a dielectric.
    fn piezo_form(&self, preset: Option<(Preset, UnitScale)>) -> Result<PiezoForm> {
        let (k, m) = (&self.key, self.table);
        let shorthand = [("e31", m.e31), ("e33", m.e33), ("e15", m.e15)];
        let any_shorthand = shorthand.iter().any(|s| s.1.is_some());
        let forms = [("e31, e33, e15", any_shorthand), ("e", m.e.is_some()), ("d", m.d.is_some())];
        let given: Vec<&str> = forms.iter().filter(|f| f.1).map(|f| f.0).collect();
        if given.len() > 1 {
            return Err(input!(
                "{}: {k} gives the piezoelectric constants twice ({}): keep one form",
                self.locate(""),
                given.join(" and ")
            ));
        }
        if any_shorthand {
            let mut values = [0.0; 3];
            for (value, (key, given)) in values.iter_mut().zip(shorthand) {
                *value = given.ok_or_else(|| {
                    input!(
                        "{}: {k}.{key} is missing: the ceramic shorthand takes e31, e33 and e15",
                        self.locate("")
                    )
                })?;
                self.finite(key, *value)?;
            }
            let [e31, e33, e15] = values;
            return Ok(PiezoForm::Stress(PiezoConstants { e31, e33, e15 }.coupling()));
        }
        let scaled = |x: Coupling, f: f64| x.map(|row| row.map(|v| v * f));
        Ok(match (&m.e, &m.d, preset) {
            (Some(e), _, _) => PiezoForm::Stress(self.matrix("e", e)?),
            (_, Some(d), _) => PiezoForm::Strain(self.matrix("d", d)?),
            (None, None, Some((preset, scale))) => match preset.piezo {
                PiezoForm::Stress(e) => PiezoForm::Stress(scaled(e, scale.piezo_stress())),
                PiezoForm::Strain(d) => PiezoForm::Strain(scaled(d, scale.piezo_strain())),
                PiezoForm::None => PiezoForm::None,
            },
            _ => PiezoForm::None,
        })
    }

    /// The dielectric group times ε0: beta11_rel and beta33_rel, or eps_rel (3 × 3 or its
    /// diagonal) [charge/(potential·length)].
    fn permittivity(&self, preset: Option<(Preset, UnitScale)>) -> Result<Matrix3> {
        let (k, m) = (&self.key, self.table);
        let shorthand = m.beta11_rel.is_some() || m.beta33_rel.is_some();
        if let (None, false, Some((preset, scale))) = (&m.eps_rel, shorthand, preset) {
            // The preset's relative permittivity, times eps0 where given, else the vacuum's.
            let eps0 = m.eps0.unwrap_or(EPS0_SI * scale.permittivity());
            let [a, b, c] = preset.permittivity.map(|v| v * eps0);
            return Ok([[a, 0.0, 0.0], [0.0, b, 0.0], [0.0, 0.0, c]]);
        }
        // Beside a preset, whose units are known, eps0 defaults to the vacuum's.
        let vacuum = preset.map(|(_, scale)| EPS0_SI * scale.permittivity());
        let eps0 = m.eps0.or(vacuum).ok_or_else(|| {
            input!(
                "{}: {k}.eps0 is missing: the vacuum permittivity in the case's units (8.854e-12 F/m in SI)",
                self.locate("")
            )
        })?;
        let relative = match (&m.eps_rel, shorthand) {
            (Some(_), true) => {
                return Err(input!(
                    "{}: {k} gives the permittivity twice (beta11_rel/beta33_rel and eps_rel): keep one form",
                    self.locate("eps_rel")
                ));
            }
            (Some(rows), false) => self.relative_permittivity(rows)?,
            (None, _) => {
                let mut diagonal = [0.0; 3];
                for (k, key) in [(0, "beta11_rel"), (2, "beta33_rel")] {
                    diagonal[k] = if key == "beta11_rel" { m.beta11_rel } else { m.beta33_rel }
                        .ok_or_else(|| {
                            input!(
                                "{}: {k}.{key} is missing: give beta11_rel and beta33_rel, or eps_rel",
                                self.locate("")
                            )
                        })?;
                }
                diagonal[1] = diagonal[0];
                [[diagonal[0], 0.0, 0.0], [0.0, diagonal[1], 0.0], [0.0, 0.0, diagonal[2]]]
            }
        };
        if !(eps0.is_finite() && eps0 > 0.0) {
            return Err(input!(
                "{}: {k}.eps0 = {eps0} must be > 0 (the vacuum permittivity)",
                self.locate("eps0")
            ));
        }
        if shorthand {
            for (key, value) in [("beta11_rel", relative[0][0]), ("beta33_rel", relative[2][2])] {
                if !(value.is_finite() && value > 0.0) {
                    return Err(input!(
                        "{}: {k}.{key} = {value} must be > 0 (the permittivity β = β_rel ε0 is positive definite)",
                        self.locate(key)
                    ));
                }
            }
        }
        Ok(relative.map(|row| row.map(|v| v * eps0)))
    }

    /// eps_rel: three numbers (a diagonal) or three rows of three.
    fn relative_permittivity(&self, rows: &[NumberOrRow]) -> Result<Matrix3> {
        let k = &self.key;
        let numbers: Option<Vec<f64>> = rows
            .iter()
            .map(|r| if let NumberOrRow::Number(v) = r { Some(*v) } else { None })
            .collect();
        if let Some(d) = numbers.filter(|d| d.len() == 3) {
            for v in &d {
                self.finite("eps_rel", *v)?;
            }
            let diagonal = [[d[0], 0.0, 0.0], [0.0, d[1], 0.0], [0.0, 0.0, d[2]]];
            return self.positive_definite("eps_rel", "the relative permittivity", &diagonal);
        }
        let matrix: Option<Vec<Vec<f64>>> = rows
            .iter()
            .map(|r| if let NumberOrRow::Row(v) = r { Some(v.clone()) } else { None })
            .collect();
        let Some(matrix) = matrix else {
            return Err(input!(
                "{}: {k}.eps_rel must be three numbers (the diagonal) or three rows of three numbers",
                self.locate("eps_rel")
            ));
        };
        let relative: Matrix3 = self.matrix("eps_rel", &matrix)?;
        self.positive_definite("eps_rel", "the relative permittivity", &relative)
    }

    /// An R × C matrix of finite numbers from the rows at `key`, or an error naming its shape.
    fn matrix<const R: usize, const C: usize>(
        &self,
        key: &str,
        rows: &[Vec<f64>],
    ) -> Result<[[f64; C]; R]> {
        let k = &self.key;
        if rows.len() != R || rows.iter().any(|r| r.len() != C) {
            let shape: Vec<String> = rows.iter().map(|r| r.len().to_string()).collect();
            return Err(input!(
                "{}: {k}.{key} must be {R} rows of {C} numbers (Voigt order xx, yy, zz, yz, xz, xy where a row or column has 6); it has {} rows of [{}] numbers",
                self.locate(key),
                rows.len(),
                shape.join(", ")
            ));
        }
        let mut matrix = [[0.0; C]; R];
        for (row, given) in matrix.iter_mut().zip(rows) {
            for (v, &g) in row.iter_mut().zip(given) {
                *v = self.finite(key, g)?;
            }
        }
        Ok(matrix)
    }

    /// A square matrix checked symmetric (to 1e-12 of its largest entry) and positive
    /// definite, made exactly symmetric.
    fn positive_definite<const N: usize>(
        &self,
        key: &str,
        name: &str,
        a: &[[f64; N]; N],
    ) -> Result<[[f64; N]; N]> {
        let k = &self.key;
        let asymmetry = voigt::asymmetry(a);
        if asymmetry > 1e-12 {
            return Err(input!(
                "{}: {k}.{key}: {name} must be symmetric; entries (i, j) and (j, i) differ by {asymmetry:.1e} of its largest entry",
                self.locate(key)
            ));
        }
        let smallest = voigt::smallest_eigenvalue(a)?;
        if smallest.is_nan() || smallest <= 0.0 {
            return Err(input!(
                "{}: {k}.{key}: {name} is not positive definite (smallest eigenvalue {smallest:e}): check its entries and units",
                self.locate(key)
            ));
        }
        let mut symmetric = *a;
        for i in 0..N {
            for j in 0..i {
                let mean = 0.5 * (a[i][j] + a[j][i]);
                (symmetric[i][j], symmetric[j][i]) = (mean, mean);
            }
        }
        Ok(symmetric)
    }

    /// `value`, or an error when it is not finite.
    fn finite(&self, key: &str, value: f64) -> Result<f64> {
        let k = &self.key;
        if value.is_finite() {
            Ok(value)
        } else {
            Err(input!("{}: {k}.{key} = {value} must be a finite number", self.locate(key)))
        }
    }
}
