//! Structured triangulations of a rectangle, as the paper's Example 7.1 needs
//! (Ω = \[0,12\]×\[0,2\], \[P\] Section 7), with boundary parts given by segments such as
//! `[0,2]x{0}` (the bottom edge from x = 0 to x = 2) or `{12}x[0,2]` (the right side).

use super::{BoundaryPart, Mesh};
use crate::error::{Error, Result};
use std::str::FromStr;

/// How each rectangular cell is split into two triangles.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Diagonal {
    /// Along the lower-left–upper-right diagonal.
    #[default]
    Right,
    /// Along the lower-right–upper-left diagonal.
    Left,
}

/// A rectangle [x0, x1] × [y0, y1] split into nx × ny cells of two triangles each.
#[derive(Clone, Debug)]
pub struct Rectangle {
    /// [x0, x1] \[length\].
    pub x: [f64; 2],
    /// [y0, y1] \[length\].
    pub y: [f64; 2],
    /// Cells along x.
    pub nx: usize,
    /// Cells along y.
    pub ny: usize,
    /// Diagonal direction.
    pub diagonal: Diagonal,
}

/// Boundary parts by name, each the union of the facets its segments hold.
pub type SegmentParts = Vec<(String, Vec<Segment>)>;

/// An axis-aligned box: per axis either an interval `[a,b]` or a point `{a}`.
#[derive(Clone, Debug, PartialEq)]
pub struct Segment {
    spec: String,
    ranges: Vec<(f64, f64)>,
}

impl FromStr for Segment {
    type Err = Error;

    /// Parses `[a,b]x{c}`, `{c}x[a,b]` (2D) or three factors in 3D; `×` may replace `x`.
    fn from_str(spec: &str) -> Result<Self> {
        let bad = |why: &str| Error::Segment { spec: spec.into(), why: why.into() };
        let mut ranges = Vec::new();
        for factor in spec.replace('×', "x").split('x') {
            let f = factor.trim();
            let numbers = |inner: &str| -> Result<Vec<f64>> {
                inner
                    .split(',')
                    .map(|t| {
                        t.trim().parse::<f64>().map_err(|_| bad(&format!("'{t}' is not a number")))
                    })
                    .collect()
            };
            if let Some(inner) = f.strip_prefix('[').and_then(|r| r.strip_suffix(']')) {
                let v = numbers(inner)?;
                if v.len() != 2 || v[0] > v[1] {
                    return Err(bad("an interval is [a,b] with a ≤ b"));
                }
                ranges.push((v[0], v[1]));
            } else if let Some(inner) = f.strip_prefix('{').and_then(|r| r.strip_suffix('}')) {
                let v = numbers(inner)?;
                if v.len() != 1 {
                    return Err(bad("a point is {a}"));
                }
                ranges.push((v[0], v[0]));
            } else {
                return Err(bad("each factor is an interval [a,b] or a point {a}, joined by x"));
            }
        }
        Ok(Self { spec: spec.into(), ranges })
    }
}

impl Segment {
    /// Whether the point p lies in the box, to `tol` on each axis.
    pub fn contains(&self, p: &[f64], tol: f64) -> bool {
        self.ranges.iter().zip(p).all(|(&(a, b), &x)| x >= a - tol && x <= b + tol)
    }
}

impl Rectangle {
    /// Builds the mesh; `parts` maps part names to the segments whose boundary facets they
    /// hold. A facet belongs to a segment when all its nodes lie in it.
    pub fn mesh(&self, parts: &[(String, Vec<Segment>)]) -> Result<Mesh> {
        self.check()?;
        let (nx, ny) = (self.nx, self.ny);
        let id = |i: usize, j: usize| j * (nx + 1) + i;
        let mut coords = Vec::with_capacity(2 * (nx + 1) * (ny + 1));
        for j in 0..=ny {
            for i in 0..=nx {
                coords.push(self.x[0] + (self.x[1] - self.x[0]) * i as f64 / nx as f64);
                coords.push(self.y[0] + (self.y[1] - self.y[0]) * j as f64 / ny as f64);
            }
        }
        let mut cells = Vec::with_capacity(6 * nx * ny);
        for j in 0..ny {
            for i in 0..nx {
                let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
                match self.diagonal {
                    Diagonal::Right => cells.extend_from_slice(&[a, b, c, a, c, d]),
                    Diagonal::Left => cells.extend_from_slice(&[a, b, d, b, c, d]),
                }
            }
        }
        let mut boundary = Vec::new();
        boundary.extend((0..nx).map(|i| [id(i, 0), id(i + 1, 0)]));
        boundary.extend((0..ny).map(|j| [id(nx, j), id(nx, j + 1)]));
        boundary.extend((0..nx).map(|i| [id(i + 1, ny), id(i, ny)]));
        boundary.extend((0..ny).map(|j| [id(0, j + 1), id(0, j)]));
        let mut inside = Vec::new();
        inside.extend((1..ny).flat_map(|j| (0..nx).map(move |i| [id(i, j), id(i + 1, j)])));
        inside.extend((1..nx).flat_map(|i| (0..ny).map(move |j| [id(i, j), id(i, j + 1)])));
        let h = ((self.x[1] - self.x[0]) / nx as f64).min((self.y[1] - self.y[0]) / ny as f64);
        let tol = 1e-9 * h;
        let node = |n: usize| &coords[2 * n..2 * n + 2];
        let mut named = Vec::with_capacity(parts.len());
        for (name, segments) in parts {
            let mut facets = Vec::new();
            let mut taken = vec![false; boundary.len() + inside.len()];
            for segment in segments {
                if segment.ranges.len() != 2 {
                    return Err(Error::Segment {
                        spec: segment.spec.clone(),
                        why: "a segment of a rectangle has two factors, as [0,2]x{0}".into(),
                    });
                }
                let held = |f: &[usize; 2]| f.iter().all(|&n| segment.contains(node(n), tol));
                // A line holding no boundary facet holds the grid's lines inside (an
                // interface, for an electrode).
                let line = segment.ranges.iter().any(|(a, b)| a == b);
                let on_boundary = boundary.iter().any(held);
                let candidates =
                    boundary.iter().chain(inside.iter().filter(|_| line && !on_boundary));
                let mut holds_any = false;
                for (f, taken) in candidates.zip(&mut taken) {
                    if held(f) {
                        holds_any = true;
                        // A part is the union of its segments: a facet counts once.
                        if !std::mem::replace(taken, true) {
                            facets.extend_from_slice(f);
                        }
                    }
                }
                if !holds_any {
                    return Err(Error::Segment {
                        spec: segment.spec.clone(),
                        why: format!(
                            "it holds no facet of the rectangle [{},{}]x[{},{}] on its boundary \
                             or on a grid line inside (part '{name}')",
                            self.x[0], self.x[1], self.y[0], self.y[1]
                        ),
                    });
                }
            }
            named.push(BoundaryPart::new(name.clone(), facets));
        }
        Mesh::new(2, coords, cells, named)
    }

    /// The ends of the segment's intervals that lie inside the rectangle between two node
    /// coordinates: the part holds only the facets wholly inside the segment, so it stops
    /// short of them. Each as (axis, end, the nodes' coordinates on either side).
    pub fn ends_between_nodes(&self, segment: &Segment) -> Vec<(usize, f64, [f64; 2])> {
        let mut found = Vec::new();
        let axes = [(self.x, self.nx), (self.y, self.ny)];
        for (axis, (&(a, b), ([lo, hi], n))) in segment.ranges.iter().zip(axes).enumerate() {
            let h = (hi - lo) / n as f64;
            for end in [a, b].into_iter().filter(|&e| a < b && e > lo && e < hi) {
                let t = (end - lo) / h;
                if (t - t.round()).abs() > 1e-9 {
                    found.push((axis, end, [lo + t.floor() * h, lo + t.ceil() * h]));
                }
            }
        }
        found
    }

    fn check(&self) -> Result<()> {
        let invalid = |name: &str, value: String, requirement: &str| Error::InvalidParameter {
            name: name.into(),
            value,
            requirement: requirement.into(),
        };
        for (name, n) in [("mesh.nx", self.nx), ("mesh.ny", self.ny)] {
            if n == 0 {
                return Err(invalid(name, n.to_string(), "at least 1 cell"));
            }
        }
        for (name, r) in [("mesh.x", self.x), ("mesh.y", self.y)] {
            if !(r[0].is_finite() && r[1].is_finite() && r[0] < r[1]) {
                return Err(invalid(name, format!("{r:?}"), "an interval [a, b] with a < b"));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn paper(diagonal: Diagonal) -> Mesh {
        let seg = |s: &str| s.parse::<Segment>().unwrap();
        let parts = vec![
            ("sides".to_string(), vec![seg("{0}x[0,2]"), seg("{12}×[0,2]")]),
            // Overlapping segments: their union, each facet once.
            ("contact".to_string(), vec![seg("[2,10]x{0}"), seg("[4,6]x{0}")]),
        ];
        Rectangle { x: [0.0, 12.0], y: [0.0, 2.0], nx: 24, ny: 4, diagonal }.mesh(&parts).unwrap()
    }

    #[test]
    fn paper_rectangle_parts() {
        for diagonal in [Diagonal::Right, Diagonal::Left] {
            let mesh = paper(diagonal);
            assert_eq!((mesh.n_nodes(), mesh.n_cells()), (25 * 5, 2 * 24 * 4));
            assert!((mesh.part_measure(0) - 4.0).abs() < 1e-12);
            assert!((mesh.part_measure(1) - 8.0).abs() < 1e-12);
            assert_eq!(mesh.parts()[1].n_facets(), 16);
        }
    }

    /// A line inside the rectangle holding no boundary facet holds the grid's edges on it: a
    /// part inside the body (an electrode between two layers); a line on the boundary holds
    /// the boundary's facets alone.
    #[test]
    fn lines_inside_hold_the_grid_edges_on_them() {
        let r = Rectangle { x: [0.0, 4.0], y: [-1.0, 1.0], nx: 4, ny: 4, diagonal: Diagonal::Left };
        let seg = |s: &str| vec![s.parse::<Segment>().unwrap()];
        let parts = vec![
            ("middle".to_string(), seg("[0,4]x{0}")),
            ("half".to_string(), seg("{2}x[-1,0]")),
            ("bottom".to_string(), seg("[0,4]x{-1}")),
        ];
        let mesh = r.mesh(&parts).unwrap();
        let [middle, half, bottom] = [0, 1, 2].map(|p| &mesh.parts()[p]);
        assert!(middle.is_interior() && half.is_interior() && !bottom.is_interior());
        assert_eq!((middle.n_facets(), half.n_facets(), bottom.n_facets()), (4, 2, 4));
        assert!((mesh.part_measure(0) - 4.0).abs() < 1e-12);
        assert!(mesh.part_nodes(&[0]).iter().all(|&n| mesh.node(n)[1].abs() < 1e-12));
        let e = mesh.part_index("middle").unwrap_err().to_string();
        assert!(e.contains("only an electrode may name it"), "{e}");
        assert_eq!(mesh.any_part_index("middle").unwrap(), 0);
    }

    #[test]
    fn segment_errors() {
        for (spec, needle) in [
            ("[0,2]y{0}", "joined by x"),
            ("[2,0]x{0}", "a ≤ b"),
            ("[0,a]x{0}", "'a' is not a number"),
            ("{1,2}x[0,1]", "a point is {a}"),
        ] {
            let e = spec.parse::<Segment>().unwrap_err().to_string();
            assert!(e.contains(needle), "{spec}: {e}");
        }
        let parts = vec![("far".to_string(), vec!["[0,2]x{5}".parse().unwrap()])];
        let r =
            Rectangle { x: [0.0, 12.0], y: [0.0, 2.0], nx: 4, ny: 2, diagonal: Diagonal::Right };
        let e = r.mesh(&parts).unwrap_err().to_string();
        assert!(e.contains("holds no facet") && e.contains("'far'"), "{e}");
        let r = Rectangle { nx: 0, ..r };
        assert!(r.mesh(&[]).unwrap_err().to_string().contains("mesh.nx = 0"));
    }
}
