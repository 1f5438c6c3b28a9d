//! The 2D models that are slices of a 3D body (beyond the paper), from a material's 3D
//! tensors in the mesh's axes: plane strain (ε_zz = γ_yz = γ_xz = 0 and E_z = 0: the in-plane
//! components of the 3D law) and plane stress (σ_zz = σ_yz = σ_xz = 0 and D_z = 0: the
//! out-of-plane strains and E_z condensed out of the 3D law).

use super::voigt::{self, Coupling, Matrix3, Tensor3, Tensor4, Voigt};
use super::{Elastic, ElasticConstants, Material, invalid_text};
use crate::error::Result;

/// A 2D model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Plane {
    /// The paper's 2D continuum (tr ε and the deviator in two dimensions).
    Continuum,
    /// Plane strain.
    Strain,
    /// Plane stress.
    Stress,
    /// The meridian section of a body of revolution about y (x = r).
    Axisymmetric,
}

impl Plane {
    /// Its name in outputs.
    pub fn name(&self) -> &'static str {
        match self {
            Plane::Continuum => "continuum",
            Plane::Strain => "plane strain",
            Plane::Stress => "plane stress",
            Plane::Axisymmetric => "axisymmetric",
        }
    }
}

/// The 2D material of `plane` (strain or stress) from the 3D material `solid` (mesh axes) and
/// the elastic constants it was made of. Hencky's law stays in plane strain, with the 3D
/// deviator ([`Material::deviator_dim`] 3); plane stress refuses it (its condensation is
/// nonlinear).
pub fn plane_material(
    solid: &Material,
    elastic: &ElasticConstants,
    plane: Plane,
) -> Result<Material> {
    if plane == Plane::Axisymmetric {
        return axisymmetric_material(solid);
    }
    if let ElasticConstants::Isotropic(el) = elastic
        && el.law != super::ElasticLaw::Linear
    {
        if plane == Plane::Stress {
            return Err(invalid_text(
                "material.law",
                "hencky",
                "plane stress takes a linear law (the condensation of Hencky's law is nonlinear): set law = \"linear\", or use plane strain",
            ));
        }
        // The in-plane components of the 3D tensors are those of `solid`: the kernels read
        // the first two indices.
        return Ok(Material { dim: 2, deviator_dim: 3, ..solid.clone() });
    }
    let c = match &solid.elastic {
        Elastic::Isotropic(el) => voigt::isotropic_stiffness(el.k0, el.mu1),
        Elastic::Anisotropic(c) => voigt::stiffness_voigt(c),
    };
    let e = voigt::coupling_voigt(&solid.e);
    let (c, e, beta) = match plane {
        Plane::Strain | Plane::Continuum | Plane::Axisymmetric => in_plane(&c, &e, &solid.beta),
        Plane::Stress => condensed(&c, &e, &solid.beta)?,
    };
    Ok(Material {
        dim: 2,
        elastic: Elastic::Anisotropic(Box::new(c)),
        e,
        beta,
        reference_modulus: solid.reference_modulus,
        axes: solid.axes,
        deviator_dim: 2,
    })
}

/// The material of a body of revolution about y: the 3D tensors in the mesh's axes, x = r,
/// y the axis and z the hoop direction θ (the kernel reads all three), Hencky's law with the
/// 3D deviator. The law must be symmetric about the axis: poled along ±y, and unchanged by
/// a turn about y (to 1e−9 relative).
fn axisymmetric_material(solid: &Material) -> Result<Material> {
    let p = solid.poling();
    if (p[1].abs() - 1.0).abs() > 1e-9 {
        return Err(invalid_text(
            "material.poling",
            &format!("{p:?}"),
            "along the axis in an axisymmetric body: poling = [0.0, 1.0] or [0.0, -1.0] (y is the axis)",
        ));
    }
    let (c, s) = (37f64.to_radians().cos(), 37f64.to_radians().sin());
    let about_y = [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]];
    if !solid.invariant_under(&about_y) {
        return Err(invalid_text(
            "material",
            "a law that a turn about the axis changes",
            "a law transversely isotropic about the axis y in an axisymmetric body (a ceramic poled along y, or an isotropic material)",
        ));
    }
    Ok(Material { dim: 2, deviator_dim: 3, ..solid.clone() })
}

/// The in-plane Voigt index of (i, j) < 2: xx 0, yy 1, xy 2.
fn plane_index(i: usize, j: usize) -> usize {
    if i == j { i } else { 2 }
}

/// The in-plane part of the 3D law (plane strain).
fn in_plane(c: &Voigt, e: &Coupling, beta: &Matrix3) -> (Tensor4, Tensor3, Matrix3) {
    let pick = [0, 1, 5];
    let mut c2 = [[0.0; 3]; 3];
    let mut e2 = [[0.0; 3]; 2];
    for (a, &p) in pick.iter().enumerate() {
        for (b, &q) in pick.iter().enumerate() {
            c2[a][b] = c[p][q];
        }
        for i in 0..2 {
            e2[i][a] = e[i][p];
        }
    }
    let beta2 = [[beta[0][0], beta[0][1]], [beta[1][0], beta[1][1]]];
    tensors(&c2, &e2, &beta2)
}

/// The 3D law with σ_zz = σ_yz = σ_xz = 0 and D_z = 0 (plane stress): the symmetric matrix H
/// of [σ; −D] = H [ε; E_field] over the in-plane (ε_xx, ε_yy, γ_xy, E_x, E_y) and out-of-plane
/// (ε_zz, γ_yz, γ_xz, E_z) unknowns, condensed: H_r = H_ii − H_io H_oo⁻¹ H_oi.
fn condensed(c: &Voigt, e: &Coupling, beta: &Matrix3) -> Result<(Tensor4, Tensor3, Matrix3)> {
    // Unknowns: strains by Voigt index, then fields by axis (6 + axis).
    let inner = [0, 1, 5, 6, 7];
    let outer = [2, 3, 4, 8];
    let h = |p: usize, q: usize| match (p < 6, q < 6) {
        (true, true) => c[p][q],
        (true, false) => -e[q - 6][p],
        (false, true) => -e[p - 6][q],
        (false, false) => -beta[p - 6][q - 6],
    };
    let mut h_oo = [[0.0; 4]; 4];
    for (a, &p) in outer.iter().enumerate() {
        for (b, &q) in outer.iter().enumerate() {
            h_oo[a][b] = h(p, q);
        }
    }
    let inverse = voigt::general_inverse(&h_oo).ok_or_else(|| {
        invalid_text(
            "material",
            "a singular out-of-plane law",
            "an invertible law for plane stress",
        )
    })?;
    let mut reduced = [[0.0; 5]; 5];
    for (a, &p) in inner.iter().enumerate() {
        for (b, &q) in inner.iter().enumerate() {
            let mut v = h(p, q);
            for (k, &r) in outer.iter().enumerate() {
                for (l, &s) in outer.iter().enumerate() {
                    v -= h(p, r) * inverse[k][l] * h(s, q);
                }
            }
            reduced[a][b] = v;
        }
    }
    let mut c2 = [[0.0; 3]; 3];
    let mut e2 = [[0.0; 3]; 2];
    let mut beta2 = [[0.0; 2]; 2];
    for a in 0..3 {
        c2[a][..3].copy_from_slice(&reduced[a][..3]);
    }
    for i in 0..2 {
        for a in 0..3 {
            e2[i][a] = -reduced[3 + i][a];
        }
        for j in 0..2 {
            beta2[i][j] = -reduced[3 + i][3 + j];
        }
    }
    Ok(tensors(&c2, &e2, &beta2))
}

/// The 2D tensors (padded to 3) of in-plane Voigt matrices.
fn tensors(
    c: &[[f64; 3]; 3],
    e: &[[f64; 3]; 2],
    beta: &[[f64; 2]; 2],
) -> (Tensor4, Tensor3, Matrix3) {
    let mut c4 = [[[[0.0; 3]; 3]; 3]; 3];
    let mut e3 = [[[0.0; 3]; 3]; 3];
    let mut b = [[0.0; 3]; 3];
    for i in 0..2 {
        for j in 0..2 {
            b[i][j] = beta[i][j];
            for k in 0..2 {
                e3[i][j][k] = e[i][plane_index(j, k)];
                for l in 0..2 {
                    c4[i][j][k][l] = c[plane_index(i, j)][plane_index(k, l)];
                }
            }
        }
    }
    (c4, e3, b)
}
