use piezocontact::material::{
    ElasticLaw, Elasticity, Material, PermittivityConstants, PiezoConstants,
};
use piezocontact::mesh::{Mesh, gmsh};
use std::path::PathBuf;

/// ε0 in the paper cases' units (m, GPa, C, GV): 8.885e−12 C/(V m) = 8.885e−3 C/(GV m).
pub const EPS0: f64 = 8.885e-3;

/// The paper's PZT-5A (Table 1) in dimension `dim`.
pub fn pzt(dim: usize, law: ElasticLaw) -> Material {
    let elasticity = Elasticity::from_young_poisson(58.7102, 0.3912, law).unwrap();
    Material::new(
        dim,
        elasticity,
        PiezoConstants { e31: -5.4, e33: 15.8, e15: 12.3 },
        PermittivityConstants { beta11: 916.0 * EPS0, beta33: 830.0 * EPS0 },
    )
    .unwrap()
}

/// A committed test mesh from `meshes/`.
pub fn mesh_file(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../meshes").join(name)
}

pub fn read_mesh(name: &str) -> Mesh {
    gmsh::read(&std::fs::read(mesh_file(name)).unwrap()).unwrap()
}

/// The unit square on an n × n grid with interior nodes moved by up to 30 % of h
/// (deterministically), parts left, right, bottom, top.
pub fn perturbed_square(n: usize, amplitude: f64) -> Mesh {
    let h = 1.0 / n as f64;
    let id = |i: usize, j: usize| j * (n + 1) + i;
    let mut coords = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let interior = i > 0 && i < n && j > 0 && j < n;
            let (a, b) = if interior {
                (((i * 7 + j * 13) as f64).sin(), ((i * 11 + j * 5) as f64).cos())
            } else {
                (0.0, 0.0)
            };
            coords.push(i as f64 * h + amplitude * h * a);
            coords.push(j as f64 * h + amplitude * h * b);
        }
    }
    let mut cells = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if (i + j) % 2 == 0 {
                cells.extend_from_slice(&[a, b, c, a, c, d]);
            } else {
                cells.extend_from_slice(&[a, b, d, b, c, d]);
            }
        }
    }
    let side = |f: &dyn Fn(usize) -> [usize; 2]| (0..n).flat_map(f).collect::<Vec<_>>();
    let parts = vec![
        piezocontact::mesh::BoundaryPart::new("left", side(&|j| [id(0, j), id(0, j + 1)])),
        piezocontact::mesh::BoundaryPart::new("right", side(&|j| [id(n, j), id(n, j + 1)])),
        piezocontact::mesh::BoundaryPart::new("bottom", side(&|i| [id(i, 0), id(i + 1, 0)])),
        piezocontact::mesh::BoundaryPart::new("top", side(&|i| [id(i, n), id(i + 1, n)])),
    ];
    Mesh::new(2, coords, cells, parts).unwrap()
}
