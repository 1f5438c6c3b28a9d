//! A rigid surface from a file (model §12): a closed triangulated surface — a real tip's
//! shape — read from a Gmsh MSH 4.1 or an STL file, the solid it bounds being the indenter.
//! Gaps are found by casting rays along the Γ3 normals against a bounding-volume hierarchy
//! of its triangles (parry3d).

use crate::error::{Error, Result};
use crate::mesh::gmsh::{self, Triangulation};
use parry3d_f64::math::Vector;
use parry3d_f64::query::{PointQuery, Ray, RayCast};
use parry3d_f64::shape::{TriMesh, TriMeshFlags};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// A closed triangulated surface, its triangles oriented outward.
pub struct RigidSurface {
    /// The file it was read from, for messages.
    pub file: PathBuf,
    mesh: TriMesh,
}

impl std::fmt::Debug for RigidSurface {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "RigidSurface({}, {} triangles)", self.file.display(), self.mesh.num_triangles())
    }
}

impl PartialEq for RigidSurface {
    fn eq(&self, other: &Self) -> bool {
        self.file == other.file && self.mesh.indices() == other.mesh.indices()
    }
}

impl RigidSurface {
    /// Reads `file` (.msh: its 3-node triangles; .stl: ASCII or binary) and checks that it is
    /// a closed surface; each error names the file.
    pub fn read(file: &Path) -> Result<Self> {
        let fail = |why: String| Error::Input(format!("{}: {why}", file.display()));
        let bytes =
            std::fs::read(file).map_err(|e| fail(format!("cannot read the surface: {e}")))?;
        let extension =
            file.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
        let (points, triangles) = match extension.as_str() {
            "msh" => gmsh::read_triangles(&bytes).map_err(|e| fail(e.to_string()))?,
            "stl" => read_stl(&bytes).map_err(fail)?,
            _ => return Err(fail("a rigid surface is a Gmsh .msh or an .stl file".into())),
        };
        Self::new(file, points, triangles)
    }

    /// The surface of `triangles` over `points`, checked closed (every edge in two
    /// triangles, in opposite directions) and oriented outward (positive enclosed volume).
    pub fn new(file: &Path, points: Vec<[f64; 3]>, mut triangles: Vec<[usize; 3]>) -> Result<Self> {
        let fail = |why: String| Error::Input(format!("{}: {why}", file.display()));
        if triangles.is_empty() {
            return Err(fail("the surface has no triangles".into()));
        }
        closed(&triangles).map_err(fail)?;
        let volume: f64 = triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|k| points[k]);
                a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                    + a[2] * (b[0] * c[1] - b[1] * c[0])
            })
            .sum();
        if volume < 0.0 {
            triangles.iter_mut().for_each(|t| t.swap(1, 2));
        }
        let vertices = points.iter().map(|p| Vector::new(p[0], p[1], p[2])).collect();
        let indices = triangles.iter().map(|t| t.map(|k| k as u32)).collect();
        let mesh = TriMesh::with_flags(vertices, indices, TriMeshFlags::ORIENTED).map_err(|e| {
            fail(format!("the surface is not a closed, consistently oriented triangulation: {e:?}"))
        })?;
        Ok(Self { file: file.to_path_buf(), mesh })
    }

    /// The gap along the unit ν from x (module docs of `contact::foundation`): where the
    /// line enters the solid — ahead from outside, behind (negative) from inside; +∞ when the
    /// ray misses it.
    pub fn distance_along(&self, x: [f64; 3], nu: [f64; 3]) -> f64 {
        let (origin, direction) = (Vector::new(x[0], x[1], x[2]), Vector::new(nu[0], nu[1], nu[2]));
        if self.mesh.contains_local_point(origin) {
            let back = Ray::new(origin, -direction);
            return self.mesh.cast_local_ray(&back, f64::MAX, false).map_or(f64::INFINITY, |t| -t);
        }
        let ray = Ray::new(origin, direction);
        self.mesh.cast_local_ray(&ray, f64::MAX, false).unwrap_or(f64::INFINITY)
    }

    /// The shortest distance from x to the surface, negative inside.
    pub fn distance(&self, x: [f64; 3]) -> f64 {
        let point = Vector::new(x[0], x[1], x[2]);
        let projection = self.mesh.project_local_point(point, false);
        let d = (projection.point - point).length();
        if self.mesh.contains_local_point(point) { -d } else { d }
    }
}

/// Checks that every edge belongs to exactly two triangles that cross it in opposite
/// directions.
fn closed(triangles: &[[usize; 3]]) -> std::result::Result<(), String> {
    let mut edges: HashMap<(usize, usize), i32> = HashMap::new();
    for t in triangles {
        for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            let key = (a.min(b), a.max(b));
            *edges.entry(key).or_default() += if a < b { 1 } else { -1 };
            if a == b {
                return Err(format!("a triangle repeats the point {a}"));
            }
        }
    }
    let mut count: HashMap<(usize, usize), usize> = HashMap::new();
    for t in triangles {
        for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            *count.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    if let Some(((a, b), n)) = count.iter().find(|(_, n)| **n != 2) {
        return Err(format!(
            "the surface is not closed: the edge between points {a} and {b} belongs to {n} triangle(s), a closed surface has two at every edge"
        ));
    }
    if let Some(((a, b), _)) = edges.iter().find(|(_, s)| **s != 0) {
        return Err(format!(
            "the triangles on both sides of the edge between points {a} and {b} are oriented alike: orient the surface consistently"
        ));
    }
    Ok(())
}

/// The points and triangles of an STL file, equal points merged.
fn read_stl(bytes: &[u8]) -> std::result::Result<Triangulation, String> {
    let mesh = stl_io::read_stl(&mut std::io::Cursor::new(bytes))
        .map_err(|e| format!("not a readable STL file: {e}"))?;
    let points = mesh.vertices.iter().map(|v| [v[0] as f64, v[1] as f64, v[2] as f64]).collect();
    let triangles = mesh.faces.iter().map(|f| f.vertices).collect();
    Ok((points, triangles))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::Foundation;

    fn ball() -> RigidSurface {
        let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../meshes/ball-tip.stl");
        RigidSurface::read(&file).unwrap()
    }

    /// The triangulated ball of meshes/ball-tip.stl against the analytic one: gaps along the
    /// normal of a face just below it, outside and inside, and shortest distances, within the
    /// sagitta of its triangles near the contact point (h²/8R ≈ 2e−6) and f32 rounding.
    #[test]
    fn a_triangulated_ball_has_the_ball_s_gaps() {
        let (surface, sphere) =
            (ball(), Foundation::Sphere { center: [0.0, 0.0, 1.0], radius: 1.0 });
        let up = [0.0, 0.0, 1.0];
        for (r, z) in [(0.0, -0.001), (0.02, -0.001), (0.05, 0.0), (0.0, 0.002), (0.03, 0.001)] {
            let x = [r * 0.8, r * 0.6, z];
            let (ours, exact) = (surface.distance_along(x, up), sphere.distance_along(x, up));
            assert!((ours - exact).abs() < 1e-5, "x = {x:?}: {ours} against {exact}");
            let (ours, exact) = (surface.distance(x), sphere.distance(x));
            assert!((ours - exact).abs() < 1e-5, "x = {x:?}: {ours} against {exact}");
        }
        assert_eq!(surface.distance_along([3.0, 0.0, 0.0], up), f64::INFINITY);
        assert_eq!(surface.distance_along([0.0, 0.0, -1.0], [0.0, 0.0, -1.0]), f64::INFINITY);
    }

    /// An empty or an open surface, a mixed orientation, and an unknown file kind are refused
    /// with the file's name and the reason.
    #[test]
    fn open_and_empty_surfaces_are_refused() {
        let file = Path::new("tip.stl");
        let points = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let closed = vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]];
        assert!(RigidSurface::new(file, points.clone(), closed.clone()).is_ok());
        // Inward triangles are turned outward: the same solid.
        let inward: Vec<[usize; 3]> = closed.iter().map(|t| [t[0], t[2], t[1]]).collect();
        let turned = RigidSurface::new(file, points.clone(), inward).unwrap();
        assert!(turned.distance([0.1, 0.1, 0.1]) < 0.0 && turned.distance([1.0, 1.0, 1.0]) > 0.0);
        let error = |triangles: Vec<[usize; 3]>| {
            RigidSurface::new(file, points.clone(), triangles).unwrap_err().to_string()
        };
        let e = error(Vec::new());
        assert!(e.starts_with("tip.stl: ") && e.contains("no triangles"), "{e}");
        let e = error(closed[..3].to_vec());
        assert!(e.contains("not closed") && e.contains("belongs to 1 triangle"), "{e}");
        let mixed = vec![[0, 2, 1], [0, 3, 1], [1, 2, 3], [0, 3, 2]];
        assert!(error(mixed).contains("oriented alike"));
        let e = RigidSurface::read(Path::new("tip.obj")).unwrap_err().to_string();
        assert!(e.starts_with("tip.obj: cannot read"), "{e}");
    }

    /// The triangles of a Gmsh file: a tetrahedron's surface in MSH 4.1 ASCII.
    #[test]
    fn a_gmsh_surface_is_read() {
        let text = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 4 1 4\n2 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n$EndNodes\n$Elements\n1 4 1 4\n2 1 2 4\n1 1 3 2\n2 1 2 4\n3 2 3 4\n4 1 4 3\n$EndElements\n";
        let (points, triangles) = gmsh::read_triangles(text.as_bytes()).unwrap();
        assert_eq!((points.len(), triangles.len()), (4, 4));
        let surface = RigidSurface::new(Path::new("tet.msh"), points, triangles).unwrap();
        let g = surface.distance_along([0.2, 0.2, -0.5], [0.0, 0.0, 1.0]);
        assert!((g - 0.5).abs() < 1e-15, "{g}");
    }
}
