//! Constitutive law of the piezoelectric body, \[P\] (2.2)–(2.3):
//!
//! ```text
//! σ = F ε(u) + Eᵀ∇ϕ,        D = E ε(u) − β∇ϕ,
//! F ε = k0 tr(ε) I + 2 g(‖ε^D‖²) ε^D,        ε^D = ε − (tr ε / d) I,
//! (Eε)_i = e_ijk ε_jk,        (Eᵀ∇ϕ)_jk = e_ijk ∂_iϕ.
//! ```
//!
//! F is Hencky's isotropic law, or a linear anisotropic one, F ε = c^E : ε, from a full
//! stiffness. A material's constants ([`Constants`]) are given in its own axes, in Voigt
//! notation ([`voigt`]); [`Material::from_constants`] turns them into the tensors of the mesh's
//! axes. In 2D (the paper's continuum) the plane holds material axes 2 (x) and 3 (y), so
//! e_{y,xx} = e32, e_{y,yy} = e33, e_{x,xy} = e24, β = diag(β22, β33) (model §2).

pub mod library;
pub mod orientation;
pub mod plane;
pub mod voigt;

use crate::error::{Error, Result};
use voigt::{Coupling, Matrix3, Tensor3, Tensor4, Voigt};

/// The function g of Hencky's law (2.3): the secant shear modulus as a function of
/// t = ‖ε^D‖² \[stress\].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ElasticLaw {
    /// Linear elasticity, g ≡ µ1.
    Linear,
    /// The paper's Hencky law (Section 7): g(t) = µ1 for t ≤ t0,
    /// g(t) = µ1 (t0/t)(1 + ln(t/t0)) for t > t0.
    Hencky {
        /// t0: elasticity limit on ‖ε^D‖² \[dimensionless\].
        t0: f64,
    },
}

/// The elasticity operator F of (2.3).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Elasticity {
    /// k0 = E/(3 − 6ν): bulk coefficient \[stress\].
    pub k0: f64,
    /// µ1 = E/(2 + 2ν): shear modulus at small strain \[stress\].
    pub mu1: f64,
    /// The law g.
    pub law: ElasticLaw,
}

impl Elasticity {
    /// Young's modulus E = 9 k0 µ1 / (3 k0 + µ1) \[stress\].
    pub fn young(&self) -> f64 {
        9.0 * self.k0 * self.mu1 / (3.0 * self.k0 + self.mu1)
    }

    /// Poisson's ratio ν = (3 k0 − 2 µ1) / (6 k0 + 2 µ1) [-].
    pub fn poisson(&self) -> f64 {
        (3.0 * self.k0 - 2.0 * self.mu1) / (6.0 * self.k0 + 2.0 * self.mu1)
    }

    /// From Young's modulus E \[stress\] and Poisson's ratio ν, as in \[P\] Section 7:
    /// µ1 = E/(2 + 2ν), k0 = E/(3 − 6ν).
    pub fn from_young_poisson(young: f64, poisson: f64, law: ElasticLaw) -> Result<Self> {
        if !(young.is_finite() && young > 0.0) {
            return Err(invalid("material.young", young, "Young's modulus E must be > 0"));
        }
        if !(poisson > -1.0 && poisson < 0.5) {
            return Err(invalid(
                "material.poisson",
                poisson,
                "Poisson's ratio must satisfy −1 < ν < 0.5 so that k0 = E/(3 − 6ν) is finite",
            ));
        }
        if let ElasticLaw::Hencky { t0 } = law
            && !(t0.is_finite() && t0 > 0.0)
        {
            return Err(invalid("material.t0", t0, "the elasticity limit t0 must be > 0"));
        }
        Ok(Self { k0: young / (3.0 - 6.0 * poisson), mu1: young / (2.0 + 2.0 * poisson), law })
    }

    /// g(t) \[stress\], t = ‖ε^D‖².
    pub fn g(&self, t: f64) -> f64 {
        match self.law {
            ElasticLaw::Hencky { t0 } if t > t0 => self.mu1 * (t0 / t) * (1.0 + (t / t0).ln()),
            _ => self.mu1,
        }
    }

    /// g'(t) \[stress\], for a Newton method: −µ1 t0 ln(t/t0)/t² above t0, 0 below.
    pub fn dg(&self, t: f64) -> f64 {
        match self.law {
            ElasticLaw::Hencky { t0 } if t > t0 => -self.mu1 * t0 * (t / t0).ln() / (t * t),
            _ => 0.0,
        }
    }
}

/// Engineering piezoelectric constants of a poled ceramic [charge/length²].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PiezoConstants {
    /// e31 = e32: transverse coefficient.
    pub e31: f64,
    /// e33: longitudinal coefficient.
    pub e33: f64,
    /// e15 = e24: shear coefficient.
    pub e15: f64,
}

impl PiezoConstants {
    /// The coupling matrix e_iJ of a ceramic poled along material axis 3.
    pub fn coupling(&self) -> Coupling {
        let mut e = [[0.0; 6]; 3];
        (e[2][0], e[2][1], e[2][2]) = (self.e31, self.e31, self.e33);
        (e[0][4], e[1][3]) = (self.e15, self.e15);
        e
    }
}

/// Permittivity along and across the poling axis [charge/(potential·length)].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PermittivityConstants {
    /// β11 = β22: across the poling axis.
    pub beta11: f64,
    /// β33: along the poling axis.
    pub beta33: f64,
}

/// The elastic constants of a material, in its own axes.
#[derive(Clone, Debug, PartialEq)]
pub enum ElasticConstants {
    /// Hencky's isotropic law (linear when g ≡ µ1).
    Isotropic(Elasticity),
    /// A linear law with the stiffness c^E in Voigt order \[stress\].
    Stiffness(Box<Voigt>),
}

impl ElasticConstants {
    /// c^E in Voigt order \[stress\] (isotropic: from k0 and µ1, with g ≡ µ1).
    pub fn stiffness(&self) -> Voigt {
        match self {
            ElasticConstants::Isotropic(el) => voigt::isotropic_stiffness(el.k0, el.mu1),
            ElasticConstants::Stiffness(c) => **c,
        }
    }
}

/// A material's constants in its own axes, in the stress-charge form.
#[derive(Clone, Debug, PartialEq)]
pub struct Constants {
    /// The elastic law.
    pub elastic: ElasticConstants,
    /// e_iJ [charge/length²] (zero for a dielectric).
    pub e: Coupling,
    /// ε^S = β, symmetric positive definite [charge/(potential·length)].
    pub permittivity: Matrix3,
}

impl Constants {
    /// The modulus a default scales with \[stress\]: E of an isotropic law, 1/s^E_33 of a
    /// stiffness (material axes).
    pub fn reference_modulus(&self) -> Result<f64> {
        Ok(match &self.elastic {
            ElasticConstants::Isotropic(el) => el.young(),
            ElasticConstants::Stiffness(c) => 1.0 / voigt::inverse(c)?[2][2],
        })
    }
}

/// The elastic law of a material in the mesh's axes.
#[derive(Clone, Debug, PartialEq)]
pub enum Elastic {
    /// Hencky's isotropic law, the same in every axes.
    Isotropic(Elasticity),
    /// A linear law: c_ijkl \[stress\] in the mesh's axes.
    Anisotropic(Box<Tensor4>),
}

/// The complete material of the body in dimension `dim`.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// Space dimension d.
    pub dim: usize,
    /// F of (2.3).
    pub elastic: Elastic,
    /// e_ijk [charge/length²], only the first d indices used.
    pub e: Tensor3,
    /// β_ij [charge/(potential·length)], symmetric positive definite.
    pub beta: Matrix3,
    /// The modulus defaults scale with \[stress\] ([`Constants::reference_modulus`]).
    pub reference_modulus: f64,
    /// The material's axes in mesh coordinates, the columns of a rotation ([`orientation`]).
    pub axes: Matrix3,
    /// The dimension m of Hencky's deviator ε^D = ε − (tr ε / m) I: the body's own, but 3 in
    /// plane strain (ε_zz = 0 enters the 3D deviator as −tr ε / 3).
    pub deviator_dim: usize,
}

impl Material {
    /// Builds the tensors of a transversely isotropic ceramic poled along the last axis.
    pub fn new(
        dim: usize,
        elasticity: Elasticity,
        piezo: PiezoConstants,
        permittivity: PermittivityConstants,
    ) -> Result<Self> {
        for (name, value) in
            [("material.e31", piezo.e31), ("material.e33", piezo.e33), ("material.e15", piezo.e15)]
        {
            if !value.is_finite() {
                return Err(invalid(name, value, "a finite number"));
            }
        }
        for (name, value) in
            [("material.beta11", permittivity.beta11), ("material.beta33", permittivity.beta33)]
        {
            if !(value.is_finite() && value > 0.0) {
                return Err(invalid(name, value, "permittivity must be > 0 (β positive definite)"));
            }
        }
        let (b11, b33) = (permittivity.beta11, permittivity.beta33);
        let constants = Constants {
            elastic: ElasticConstants::Isotropic(elasticity),
            e: piezo.coupling(),
            permittivity: [[b11, 0.0, 0.0], [0.0, b11, 0.0], [0.0, 0.0, b33]],
        };
        Self::from_constants(dim, &constants, &orientation::IDENTITY)
    }

    /// The tensors of `constants` in the mesh's axes, the material's axes being the columns of
    /// `axes` ([`orientation`]; the identity leaves every number as it is). In 2D the plane
    /// holds material axes 2 and 3 (module docs), the axes must be the identity and the law
    /// isotropic.
    pub fn from_constants(dim: usize, constants: &Constants, axes: &Matrix3) -> Result<Self> {
        let mut e = voigt::coupling_tensor(&constants.e);
        let mut beta = constants.permittivity;
        let reference_modulus = constants.reference_modulus()?;
        let mut elastic = match &constants.elastic {
            ElasticConstants::Isotropic(el) => Elastic::Isotropic(*el),
            ElasticConstants::Stiffness(c) => {
                Elastic::Anisotropic(Box::new(voigt::stiffness_tensor(c)))
            }
        };
        if *axes != orientation::IDENTITY {
            if dim != 3 {
                return Err(invalid_text(
                    "material.poling",
                    "a turned material",
                    "the 2D continuum model is poled along y: turned materials need a 3D mesh",
                ));
            }
            e = orientation::rotate_coupling(&e, axes);
            beta = orientation::rotate_matrix(&beta, axes);
            if let Elastic::Anisotropic(c) = &mut elastic {
                **c = orientation::rotate_stiffness(c, axes);
            }
        }
        if dim == 3 {
            return Ok(Self {
                dim,
                elastic,
                e,
                beta,
                reference_modulus,
                axes: *axes,
                deviator_dim: dim,
            });
        }
        if matches!(elastic, Elastic::Anisotropic(_)) {
            return Err(invalid_text(
                "material.c",
                "a stiffness tensor",
                "the 2D continuum model takes isotropic elasticity (young, poisson): use a 3D mesh for a full tensor",
            ));
        }
        let (mut e2, mut beta2) = ([[[0.0; 3]; 3]; 3], [[0.0; 3]; 3]);
        for i in 0..2 {
            for j in 0..2 {
                beta2[i][j] = beta[i + 1][j + 1];
                for k in 0..2 {
                    e2[i][j][k] = e[i + 1][j + 1][k + 1];
                }
            }
        }
        Ok(Self {
            dim,
            elastic,
            e: e2,
            beta: beta2,
            reference_modulus,
            axes: *axes,
            deviator_dim: dim,
        })
    }

    /// The poling, material axis 3, in mesh coordinates padded to 3 (y in 2D).
    pub fn poling(&self) -> [f64; 3] {
        // The continuum keeps the identity: its plane holds material axes 2 and 3.
        if self.dim == 2 && self.axes == orientation::IDENTITY {
            [0.0, 1.0, 0.0]
        } else {
            self.axes.map(|row| row[2])
        }
    }

    /// Whether the tensors are transversely isotropic about the last axis (unchanged by a turn
    /// about it, to 1e-9 of their largest entries): a ceramic poled along ±z, AlN, ZnO; always
    /// in 2D, whose continuum has no turn.
    pub fn is_transversely_isotropic(&self) -> bool {
        self.dim == 2 || self.invariant_under(&orientation::axes_from_euler([37.0, 0.0, 0.0]))
    }

    /// Whether the 3D tensors are unchanged (to 1e−9 of their largest entry) when turned to
    /// the axes `turn` (columns).
    pub fn invariant_under(&self, turn: &Matrix3) -> bool {
        let turn = *turn;
        let near = |a: &[f64], b: &[f64]| {
            let scale = a.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            a.iter().zip(b).all(|(x, y)| (x - y).abs() <= 1e-9 * scale)
        };
        let flat3 = |t: &Tensor3| t.iter().flatten().flatten().copied().collect::<Vec<f64>>();
        let flat2 = |t: &Matrix3| t.iter().flatten().copied().collect::<Vec<f64>>();
        let elastic = match &self.elastic {
            Elastic::Isotropic(_) => true,
            Elastic::Anisotropic(c) => {
                let flat4 = |t: &Tensor4| {
                    t.iter().flatten().flatten().flatten().copied().collect::<Vec<f64>>()
                };
                near(&flat4(c), &flat4(&orientation::rotate_stiffness(c, &turn)))
            }
        };
        elastic
            && near(&flat3(&self.e), &flat3(&orientation::rotate_coupling(&self.e, &turn)))
            && near(&flat2(&self.beta), &flat2(&orientation::rotate_matrix(&self.beta, &turn)))
    }

    /// Hencky's law, where the material is isotropic.
    pub fn elasticity(&self) -> Option<&Elasticity> {
        match &self.elastic {
            Elastic::Isotropic(el) => Some(el),
            Elastic::Anisotropic(_) => None,
        }
    }

    /// Whether the elastic law is linear (g ≡ µ1, or a stiffness tensor).
    pub fn is_linear(&self) -> bool {
        self.elasticity().is_none_or(|el| el.law == ElasticLaw::Linear)
    }

    /// The secant modulus g(t) \[stress\], t = ‖ε^D‖², of an isotropic law; 0 for a stiffness
    /// tensor, whose element matrices take no modulus.
    pub fn modulus(&self, t: f64) -> f64 {
        self.elasticity().map_or(0.0, |el| el.g(t))
    }

    /// g'(t) \[stress\] of an isotropic law; 0 for a stiffness tensor (a linear law).
    pub fn modulus_slope(&self, t: f64) -> f64 {
        self.elasticity().map_or(0.0, |el| el.dg(t))
    }

    /// σ = F ε + Eᵀ∇ϕ \[stress\], (2.2), with a given secant modulus g \[stress\] for Hencky's
    /// law (a stiffness tensor ignores it).
    pub fn stress<const D: usize>(
        &self,
        eps: &[[f64; D]; D],
        grad_phi: &[f64; D],
        g: f64,
    ) -> [[f64; D]; D] {
        let tr: f64 = (0..D).map(|i| eps[i][i]).sum();
        let mut sigma = [[0.0; D]; D];
        for j in 0..D {
            for k in 0..D {
                let elastic = match &self.elastic {
                    Elastic::Isotropic(el) => {
                        let dev =
                            eps[j][k] - if j == k { tr / self.deviator_dim as f64 } else { 0.0 };
                        2.0 * g * dev + if j == k { el.k0 * tr } else { 0.0 }
                    }
                    Elastic::Anisotropic(c) => (0..D)
                        .flat_map(|l| (0..D).map(move |m| (l, m)))
                        .map(|(l, m)| c[j][k][l][m] * eps[l][m])
                        .sum(),
                };
                sigma[j][k] = elastic + (0..D).map(|i| self.e[i][j][k] * grad_phi[i]).sum::<f64>();
            }
        }
        sigma
    }

    /// D = Eε − β∇ϕ [charge/length²], (2.2).
    pub fn displacement_field<const D: usize>(
        &self,
        eps: &[[f64; D]; D],
        grad_phi: &[f64; D],
    ) -> [f64; D] {
        let mut d = [0.0; D];
        for i in 0..D {
            for j in 0..D {
                d[i] -= self.beta[i][j] * grad_phi[j];
                for k in 0..D {
                    d[i] += self.e[i][j][k] * eps[j][k];
                }
            }
        }
        d
    }

    /// σ with the true law g(‖ε^D‖²).
    pub fn true_stress<const D: usize>(
        &self,
        eps: &[[f64; D]; D],
        grad_phi: &[f64; D],
    ) -> [[f64; D]; D] {
        self.stress(eps, grad_phi, self.modulus(self.deviator_norm_squared(eps)))
    }

    /// ‖ε^D‖² of this material's deviator ([`Material::deviator_dim`]): in plane strain the
    /// out-of-plane entry −tr ε / 3 counts too.
    pub fn deviator_norm_squared<const D: usize>(&self, eps: &[[f64; D]; D]) -> f64 {
        let m = self.deviator_dim;
        if m == D {
            return deviator_norm_squared(eps);
        }
        let tr: f64 = (0..D).map(|i| eps[i][i]).sum::<f64>() / m as f64;
        let mut s = (m - D) as f64 * tr * tr;
        for i in 0..D {
            for j in 0..D {
                let dev = eps[i][j] - if i == j { tr } else { 0.0 };
                s += dev * dev;
            }
        }
        s
    }
}

/// A material with its name.
#[derive(Clone, Debug, PartialEq)]
pub struct NamedMaterial {
    /// Its name in outputs.
    pub name: String,
    /// Its tensors.
    pub material: Material,
}

/// The body's materials: a list of named materials and the material of each cell.
#[derive(Clone, Debug, PartialEq)]
pub struct Materials {
    list: Vec<NamedMaterial>,
    /// The index into `list` of each cell; empty for one material.
    of_cell: Vec<u16>,
}

impl Materials {
    /// Several materials, `of_cell[c]` the index of cell c's: an error when the list is empty
    /// or longer than 65535, an index is out of range or the dimensions differ.
    pub fn new(list: Vec<NamedMaterial>, of_cell: Vec<usize>) -> Result<Self> {
        let dims = list.first().map(|m| m.material.dim);
        if list.is_empty() || list.len() > usize::from(u16::MAX) {
            return Err(invalid_text("material", &list.len().to_string(), "1 to 65535 materials"));
        }
        if let Some(m) = list.iter().find(|m| Some(m.material.dim) != dims) {
            return Err(invalid_text(&m.name, "a material of another dimension", "one dimension"));
        }
        if let Some(c) = of_cell.iter().position(|&k| k >= list.len()) {
            let cell = format!("cell {c}");
            return Err(invalid_text(
                &cell,
                "a material out of the list",
                "every cell one of the list's",
            ));
        }
        Ok(Self { list, of_cell: of_cell.into_iter().map(|k| k as u16).collect() })
    }

    /// The materials, in their order.
    pub fn list(&self) -> &[NamedMaterial] {
        &self.list
    }

    /// The index of cell c's material.
    pub fn index_of(&self, c: usize) -> usize {
        self.of_cell.get(c).map_or(0, |&k| usize::from(k))
    }

    /// Cell c's material.
    pub fn of(&self, c: usize) -> &Material {
        &self.list[self.index_of(c)].material
    }

    /// The number of cells per material, for `n_cells` cells.
    pub fn cell_counts(&self, n_cells: usize) -> Vec<usize> {
        let mut counts = vec![0; self.list.len()];
        (0..n_cells).for_each(|c| counts[self.index_of(c)] += 1);
        counts
    }

    /// The number of cells mapped to a material: 0 when one material covers the body, else
    /// every cell's.
    pub fn n_mapped(&self) -> usize {
        self.of_cell.len()
    }

    /// The space dimension.
    pub fn dim(&self) -> usize {
        self.list[0].material.dim
    }

    /// Whether every material's law is linear.
    pub fn is_linear(&self) -> bool {
        self.list.iter().all(|m| m.material.is_linear())
    }

    /// The largest reference modulus over the materials \[stress\].
    pub fn reference_modulus(&self) -> f64 {
        self.list.iter().map(|m| m.material.reference_modulus).fold(0.0, f64::max)
    }
}

impl From<Material> for Materials {
    /// One material over the whole body, named "material".
    fn from(material: Material) -> Self {
        Self {
            list: vec![NamedMaterial { name: "material".into(), material }],
            of_cell: Vec::new(),
        }
    }
}

/// ‖ε^D‖² with the deviator of the body's own dimension (model §1).
pub fn deviator_norm_squared<const D: usize>(eps: &[[f64; D]; D]) -> f64 {
    let tr: f64 = (0..D).map(|i| eps[i][i]).sum();
    let mut s = 0.0;
    for i in 0..D {
        for j in 0..D {
            let dev = eps[i][j] - if i == j { tr / D as f64 } else { 0.0 };
            s += dev * dev;
        }
    }
    s
}

fn invalid_text(name: &str, value: &str, requirement: &str) -> Error {
    Error::InvalidParameter {
        name: name.into(),
        value: value.into(),
        requirement: requirement.into(),
    }
}

fn invalid(name: &str, value: f64, requirement: &str) -> Error {
    Error::InvalidParameter {
        name: name.into(),
        value: value.to_string(),
        requirement: requirement.into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pzt(dim: usize) -> Material {
        let el = Elasticity::from_young_poisson(58.7102, 0.3912, ElasticLaw::Hencky { t0: 1.8 })
            .unwrap();
        let eps0 = 8.885e-3;
        Material::new(
            dim,
            el,
            PiezoConstants { e31: -5.4, e33: 15.8, e15: 12.3 },
            PermittivityConstants { beta11: 916.0 * eps0, beta33: 830.0 * eps0 },
        )
        .unwrap()
    }

    #[test]
    fn hencky_g_is_continuous_and_satisfies_h1() {
        let el = *pzt(2).elasticity().unwrap();
        let t0 = 1.8;
        assert_eq!(el.g(t0), el.mu1);
        assert!((el.g(t0 * (1.0 + 1e-12)) - el.mu1).abs() < 1e-9);
        // g' against central differences; g + 2 g' t = µ1 (t0/t)(1 − ln(t/t0)), so the paper's
        // g satisfies (h1)(b) (g + 2g't ≥ α1 > 0) only for t < e·t0.
        for t in [2.0, 4.0, 5.0, 50.0, 1e3] {
            let h = 1e-6 * t;
            let fd = (el.g(t + h) - el.g(t - h)) / (2.0 * h);
            assert!((fd - el.dg(t)).abs() < 1e-6 * el.mu1, "t = {t}");
            let a = el.g(t) + 2.0 * el.dg(t) * t;
            let expected = el.mu1 * (t0 / t) * (1.0 - (t / t0).ln());
            assert!((a - expected).abs() < 1e-12 * el.mu1, "t = {t}");
            assert_eq!(a > 0.0, t < std::f64::consts::E * t0, "t = {t}");
        }
    }

    #[test]
    fn plane_mapping_of_the_paper() {
        let m = pzt(2);
        // (Eε)_x = 2 e24 ε_xy, (Eε)_y = e32 ε_xx + e33 ε_yy (model §2), with ∇ϕ = 0.
        let eps = [[0.1, 0.2], [0.2, 0.3]];
        let d = m.displacement_field(&eps, &[0.0, 0.0]);
        assert!((d[0] - 2.0 * 12.3 * 0.2).abs() < 1e-12);
        assert!((d[1] - (-5.4 * 0.1 + 15.8 * 0.3)).abs() < 1e-12);
        let m3 = pzt(3);
        assert_eq!(m3.e[2][0][0], -5.4);
        assert_eq!(m3.e[1][1][2], 12.3);
        assert_eq!(m3.beta[1][1], m3.beta[0][0]);
    }

    #[test]
    fn a_ceramic_is_transversely_isotropic_about_its_poling_only() {
        let m = pzt(3);
        assert!(m.is_transversely_isotropic() && pzt(2).is_transversely_isotropic());
        let el = *m.elasticity().unwrap();
        let mut constants = Constants {
            elastic: ElasticConstants::Isotropic(el),
            e: PiezoConstants { e31: -5.4, e33: 15.8, e15: 12.3 }.coupling(),
            permittivity: m.beta,
        };
        let along_x = orientation::axes_from_poling([1.0, 0.0, 0.0]);
        assert!(
            !Material::from_constants(3, &constants, &along_x).unwrap().is_transversely_isotropic()
        );
        let down = orientation::axes_from_poling([0.0, 0.0, -1.0]);
        assert!(
            Material::from_constants(3, &constants, &down).unwrap().is_transversely_isotropic()
        );
        // A stiffness with c11 ≠ c22 is not, even poled along z.
        let mut c = voigt::isotropic_stiffness(el.k0, el.mu1);
        c[1][1] *= 1.1;
        constants.elastic = ElasticConstants::Stiffness(Box::new(c));
        let identity = orientation::IDENTITY;
        assert!(
            !Material::from_constants(3, &constants, &identity)
                .unwrap()
                .is_transversely_isotropic()
        );
    }

    #[test]
    fn parameter_errors() {
        let e = Elasticity::from_young_poisson(1.0, 0.5, ElasticLaw::Linear).unwrap_err();
        assert!(e.to_string().contains("material.poisson = 0.5"), "{e}");
        let e = Elasticity::from_young_poisson(-1.0, 0.3, ElasticLaw::Linear).unwrap_err();
        assert!(e.to_string().contains("material.young = -1"), "{e}");
        let e =
            Elasticity::from_young_poisson(1.0, 0.3, ElasticLaw::Hencky { t0: 0.0 }).unwrap_err();
        assert!(e.to_string().contains("material.t0 = 0"), "{e}");
        let el = Elasticity::from_young_poisson(1.0, 0.3, ElasticLaw::Linear).unwrap();
        let e = Material::new(
            2,
            el,
            PiezoConstants { e31: 0.0, e33: 0.0, e15: 0.0 },
            PermittivityConstants { beta11: 0.0, beta33: 1.0 },
        )
        .unwrap_err();
        assert!(e.to_string().contains("material.beta11"), "{e}");
    }
}
