//! The foundation's surface (model §12). The paper's gap ρ is "measured along the outward
//! normal": at Γ3 node i it is the distance from x_i along ν_i to the foundation,
//!
//! ```text
//! plane through p with unit normal n (out of the foundation, toward the body):
//!     g_i = n·(x_i − p) / (−n·ν_i)                    (no hit when −n·ν_i ≤ 0)
//! ball (disk in 2D) of centre c and radius R, the body outside it:
//!     g_i = the first t with |x_i + t ν_i − c| = R     (no hit when the ray misses it)
//! cone (wedge in 2D), apex a, unit axis n into it, half-angle α; flat punch, the centre c of
//! its face, axis n into it, radius b (in 2D a strip of half-width b):
//!     the solid {w·n ≥ |w| cos α, w = p − a}, {w·n ≥ 0, |w − (w·n) n| ≤ b, w = p − c};
//!     the line x_i + t ν_i crosses each in one interval [t_in, t_out]; g_i = t_in
//! ```
//!
//! For the solids (ball, cone, punch) the gap is where the line x_i + t ν_i enters the solid:
//! ahead of the node (t_in > 0) when it is outside, behind it (t_in ≤ 0, the way back out) when
//! it is inside; +∞ when the line misses the solid, the solid lies behind the node, or the way
//! back out never ends. In 2D the cone and the punch are cut by the plane of the body through
//! their axis: a wedge and a flat strip. A negative gap is an initial interpenetration that
//! the solution removes. A node whose
//! normal misses the foundation cannot touch it: its gap is +∞. The case's `contact.gap` is
//! added to the distance as an offset.

/// The foundation's surface.
#[derive(Clone, Debug, Default, PartialEq)]
pub enum Foundation {
    /// The paper's: a constant gap along the normal of every Γ3 node (`contact.gap`).
    #[default]
    ConstantGap,
    /// A rigid half-space.
    Plane {
        /// A point of the plane \[length\] (3 components, the last 0 in 2D).
        point: [f64; 3],
        /// Its unit normal, out of the foundation toward the body.
        normal: [f64; 3],
    },
    /// A rigid ball (a disk in 2D), the body outside it.
    Sphere {
        /// Centre \[length\].
        center: [f64; 3],
        /// Radius \[length\].
        radius: f64,
    },
    /// A rigid cone (a wedge in 2D), the body outside it.
    Cone {
        /// The apex \[length\].
        apex: [f64; 3],
        /// Unit vector from the apex into the cone, away from the body.
        axis: [f64; 3],
        /// The half-angle α \[rad\], in (0, π/2).
        half_angle: f64,
    },
    /// A rigid flat cylindrical punch (a flat strip in 2D) with a sharp edge.
    Punch {
        /// The centre of its flat face \[length\].
        center: [f64; 3],
        /// Unit vector along its axis, from the face into the punch, away from the body.
        axis: [f64; 3],
        /// The radius of its face (in 2D its half-width) \[length\].
        radius: f64,
    },
    /// A rigid closed surface from a file (3D), the solid it bounds the indenter.
    Surface {
        /// The surface.
        surface: Arc<RigidSurface>,
        /// Its rigid displacement from the file's position \[length\].
        shift: [f64; 3],
    },
}

use super::rigid::RigidSurface;
use std::sync::Arc;

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|k| a[k] * b[k]).sum()
}

impl Foundation {
    /// What keeps the foundation from being a body of revolution about the y axis (`None`:
    /// it is one): a plane normal to y, a sphere centred on the axis, a cone or a punch on
    /// the axis along it, or the constant gap.
    pub fn off_the_axis(&self) -> Option<&'static str> {
        let on_axis =
            |p: &[f64; 3]| p[0].abs() <= 1e-12 * p.iter().fold(1.0_f64, |m, v| m.max(v.abs()));
        let along_y = |n: &[f64; 3]| n[0].abs() <= 1e-12 && n[2] == 0.0;
        match self {
            Foundation::ConstantGap => None,
            Foundation::Plane { normal, .. } => {
                (!along_y(normal)).then_some("a plane must be normal to the axis y: normal = [0.0, 1.0]")
            }
            Foundation::Sphere { center, .. } => {
                (!on_axis(center)).then_some("a sphere must be centred on the axis: center = [0.0, y]")
            }
            Foundation::Cone { apex, axis, .. } => (!on_axis(apex) || !along_y(axis))
                .then_some("a cone must have its apex on the axis and its axis along y: apex = [0.0, y], axis = [0.0, 1.0]"),
            Foundation::Punch { center, axis, .. } => (!on_axis(center) || !along_y(axis))
                .then_some("a punch must be centred on the axis along y: center = [0.0, y], axis = [0.0, 1.0]"),
            Foundation::Surface { .. } => Some("a rigid surface from a file is a 3D foundation"),
        }
    }

    /// The distance from x along the unit vector ν to the surface \[length\]: +∞ when the ray
    /// misses it, negative when x is inside the foundation (0 for the constant gap).
    pub fn distance_along(&self, x: [f64; 3], nu: [f64; 3]) -> f64 {
        match *self {
            Self::ConstantGap => 0.0,
            Self::Plane { point, normal } => {
                let facing = -dot(normal, nu);
                if facing <= 0.0 {
                    return f64::INFINITY;
                }
                dot(normal, [0, 1, 2].map(|k| x[k] - point[k])) / facing
            }
            Self::Sphere { center, radius } => {
                let d = [0, 1, 2].map(|k| x[k] - center[k]);
                let (b, c) = (dot(nu, d), dot(d, d) - radius * radius);
                let discriminant = b * b - c;
                if discriminant < 0.0 {
                    return f64::INFINITY;
                }
                let first = -b - discriminant.sqrt();
                // Inside the ball (c < 0) the gap is the way back out; outside, a ball behind
                // the node cannot be reached.
                if c < 0.0 || first >= 0.0 { first } else { f64::INFINITY }
            }
            Self::Cone { .. } | Self::Punch { .. } => self.entry(x, nu),
            Self::Surface { ref surface, shift } => {
                surface.distance_along([0, 1, 2].map(|k| x[k] - shift[k]), nu)
            }
        }
    }

    /// The same surface moved rigidly by `shift` \[length\] (the constant gap does not move).
    pub fn translated(&self, shift: [f64; 3]) -> Self {
        let moved = |p: [f64; 3]| [0, 1, 2].map(|k| p[k] + shift[k]);
        match *self {
            Self::ConstantGap => Self::ConstantGap,
            Self::Plane { point, normal } => Self::Plane { point: moved(point), normal },
            Self::Sphere { center, radius } => Self::Sphere { center: moved(center), radius },
            Self::Cone { apex, axis, half_angle } => {
                Self::Cone { apex: moved(apex), axis, half_angle }
            }
            Self::Punch { center, axis, radius } => {
                Self::Punch { center: moved(center), axis, radius }
            }
            Self::Surface { ref surface, shift } => {
                Self::Surface { surface: surface.clone(), shift: moved(shift) }
            }
        }
    }

    /// For a cone or a punch: the point of the axis the solid starts from (the apex, the
    /// face's centre) and the axis.
    fn axis(&self) -> Option<([f64; 3], [f64; 3])> {
        match *self {
            Self::Cone { apex, axis, .. } => Some((apex, axis)),
            Self::Punch { center, axis, .. } => Some((center, axis)),
            _ => None,
        }
    }

    /// Whether the point p is in the cone or the punch (false for the other surfaces).
    fn contains(&self, p: [f64; 3]) -> bool {
        match *self {
            Self::Cone { apex, axis, half_angle } => {
                let (rho, h) = axial(p, apex, axis);
                h >= rho.hypot(h) * half_angle.cos()
            }
            Self::Punch { center, axis, radius } => {
                let (rho, h) = axial(p, center, axis);
                h >= 0.0 && rho <= radius
            }
            _ => false,
        }
    }

    /// Where the line x + t ν enters a cone or a punch (module docs): the interval of t in the
    /// solid lies between the roots of its boundary's equations along the line, each piece
    /// tested at its middle.
    fn entry(&self, x: [f64; 3], nu: [f64; 3]) -> f64 {
        let Some((origin, axis)) = self.axis() else { return 0.0 };
        let d = [0, 1, 2].map(|k| x[k] - origin[k]);
        let (dn, vn) = (dot(d, axis), dot(nu, axis));
        let mut roots = Vec::new();
        if vn != 0.0 {
            roots.push(-dn / vn); // the plane w·n = 0
        }
        let (a, b, c) = match *self {
            Self::Cone { half_angle, .. } => {
                // (w·n)² − cos²α |w|² = 0
                let c2 = half_angle.cos().powi(2);
                (vn * vn - c2, 2.0 * (dn * vn - c2 * dot(d, nu)), dn * dn - c2 * dot(d, d))
            }
            Self::Punch { radius, .. } => {
                // |w⊥|² − b² = 0, w⊥ = w − (w·n) n
                let dp = [0, 1, 2].map(|k| d[k] - dn * axis[k]);
                let vp = [0, 1, 2].map(|k| nu[k] - vn * axis[k]);
                (dot(vp, vp), 2.0 * dot(dp, vp), dot(dp, dp) - radius * radius)
            }
            _ => (0.0, 0.0, 0.0),
        };
        roots.extend(quadratic_roots(a, b, c));
        roots.sort_by(f64::total_cmp);
        let at = |t: f64| [0, 1, 2].map(|k| x[k] + t * nu[k]);
        let mut pieces = vec![f64::NEG_INFINITY];
        pieces.extend(&roots);
        pieces.push(f64::INFINITY);
        let mut interval: Option<(f64, f64)> = None;
        for pair in pieces.windows(2) {
            let (lo, hi) = (pair[0], pair[1]);
            let middle = match (lo.is_finite(), hi.is_finite()) {
                (true, true) => 0.5 * (lo + hi),
                (true, false) => lo + 1.0 + lo.abs(),
                (false, true) => hi - 1.0 - hi.abs(),
                (false, false) => 0.0,
            };
            if hi > lo && self.contains(at(middle)) {
                interval = Some(interval.map_or((lo, hi), |(start, _)| (start, hi)));
            }
        }
        match interval {
            Some((t_in, t_out)) if t_out >= 0.0 && t_in.is_finite() => t_in,
            _ => f64::INFINITY,
        }
    }

    /// The shortest distance from x to the surface \[length\] (negative inside), for output.
    pub fn distance(&self, x: [f64; 3]) -> f64 {
        match *self {
            Self::ConstantGap => 0.0,
            Self::Plane { point, normal } => dot(normal, [0, 1, 2].map(|k| x[k] - point[k])),
            Self::Sphere { center, radius } => {
                let d = [0, 1, 2].map(|k| x[k] - center[k]);
                dot(d, d).sqrt() - radius
            }
            Self::Cone { apex, axis, half_angle } => {
                let (rho, h) = axial(x, apex, axis);
                let (sin, cos) = half_angle.sin_cos();
                if rho * sin + h * cos <= 0.0 { rho.hypot(h) } else { rho * cos - h * sin }
            }
            Self::Punch { center, axis, radius } => {
                let (rho, h) = axial(x, center, axis);
                if h >= 0.0 && rho <= radius {
                    -h.min(radius - rho)
                } else {
                    (rho - radius).max(0.0).hypot((-h).max(0.0))
                }
            }
            Self::Surface { ref surface, shift } => {
                surface.distance([0, 1, 2].map(|k| x[k] - shift[k]))
            }
        }
    }
}

/// The distance ρ of x from the axis through `origin` along the unit `axis`, and its height
/// h along it.
fn axial(x: [f64; 3], origin: [f64; 3], axis: [f64; 3]) -> (f64, f64) {
    let w = [0, 1, 2].map(|k| x[k] - origin[k]);
    let h = dot(w, axis);
    let radial = [0, 1, 2].map(|k| w[k] - h * axis[k]);
    (dot(radial, radial).sqrt(), h)
}

/// The real roots of a t² + b t + c = 0 (of b t + c = 0 when a = 0).
fn quadratic_roots(a: f64, b: f64, c: f64) -> Vec<f64> {
    if a == 0.0 {
        return if b != 0.0 { vec![-c / b] } else { Vec::new() };
    }
    let discriminant = b * b - 4.0 * a * c;
    if discriminant < 0.0 {
        return Vec::new();
    }
    // The root without cancellation, then the other from their product c/a.
    let q = -0.5 * (b + b.signum() * discriminant.sqrt());
    if q == 0.0 { vec![0.0] } else { vec![q / a, c / q] }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distances_along_the_normal() {
        let plane = Foundation::Plane { point: [0.0, -1.0, 0.0], normal: [0.0, 1.0, 0.0] };
        // Straight down onto a plane 1 below, obliquely, and away from it.
        assert_eq!(plane.distance_along([0.0, 0.0, 0.0], [0.0, -1.0, 0.0]), 1.0);
        let oblique = [0.6, -0.8, 0.0];
        assert!((plane.distance_along([0.0, 0.0, 0.0], oblique) - 1.25).abs() < 1e-15);
        assert_eq!(plane.distance_along([0.0, 0.0, 0.0], [1.0, 0.0, 0.0]), f64::INFINITY);
        // Behind the plane: a negative gap.
        assert_eq!(plane.distance_along([0.0, -1.5, 0.0], [0.0, -1.0, 0.0]), -0.5);
        let ball = Foundation::Sphere { center: [0.0, 0.0, 3.0], radius: 2.0 };
        assert_eq!(ball.distance_along([0.0, 0.0, 0.0], [0.0, 0.0, 1.0]), 1.0);
        // Off the axis: x = 1 meets the sphere at z = 3 − √3.
        let g = ball.distance_along([1.0, 0.0, 0.0], [0.0, 0.0, 1.0]);
        assert!((g - (3.0 - 3f64.sqrt())).abs() < 1e-15);
        assert_eq!(ball.distance_along([2.5, 0.0, 0.0], [0.0, 0.0, 1.0]), f64::INFINITY);
        assert_eq!(ball.distance_along([0.0, 0.0, 0.0], [0.0, 0.0, -1.0]), f64::INFINITY);
        // Inside the ball: back out along −ν.
        assert_eq!(ball.distance_along([0.0, 0.0, 1.5], [0.0, 0.0, 1.0]), -0.5);
        assert_eq!((ball.distance([0.0, 0.0, 0.0]), plane.distance([0.0, 0.0, 0.0])), (1.0, 1.0));
    }

    /// The cone and the punch along the normal of a flat face under them, against the
    /// closed forms: a cone of half-angle α with its apex at height −δ below the face z = 0
    /// (pressed in by δ) is met at radius r at g = r cot α − δ; a punch of radius b at the
    /// same depth at g = −δ inside its radius and nowhere outside.
    #[test]
    fn cones_and_punches_along_the_normal() {
        let up = [0.0, 0.0, 1.0];
        let (alpha, delta) = (60f64.to_radians(), 0.1);
        let cone = Foundation::Cone { apex: [0.0, 0.0, -delta], axis: up, half_angle: alpha };
        for r in [0.0, 0.05, 0.3, 1.0] {
            let x = [r * 0.6, r * 0.8, 0.0];
            let g = cone.distance_along(x, up);
            assert!((g - (r / alpha.tan() - delta)).abs() < 1e-14, "r = {r}: {g}");
            // The shortest distance is the gap times cos α where the node is outside.
            let expected = (r / alpha.tan() - delta) * alpha.sin();
            assert!((cone.distance(x) - expected).abs() < 1e-14, "r = {r}");
        }
        // Looking away from the cone: no hit; sideways into its flank: a finite gap.
        assert_eq!(cone.distance_along([0.5, 0.0, 0.0], [0.0, 0.0, -1.0]), f64::INFINITY);
        let sideways = cone.distance_along([-1.0, 0.0, 0.5], [1.0, 0.0, 0.0]);
        assert!((sideways - (1.0 - 0.6 * alpha.tan())).abs() < 1e-14, "{sideways}");
        let punch = Foundation::Punch { center: [0.0, 0.0, -delta], axis: up, radius: 0.5 };
        assert_eq!(punch.distance_along([0.3, 0.0, 0.0], up), -delta);
        assert_eq!(punch.distance_along([0.0, 0.3, 0.0], up), -delta);
        assert_eq!(punch.distance_along([0.6, 0.0, 0.0], up), f64::INFINITY);
        assert!((punch.distance_along([0.3, 0.0, -0.3], up) - 0.2).abs() < 1e-15);
        assert!((punch.distance([0.45, 0.0, 0.0]) + 0.05).abs() < 1e-15);
        assert!((punch.distance([0.8, 0.0, -0.5]) - 0.5).abs() < 1e-15);
        // In 2D (the plane z = 0, y up): the wedge and the strip.
        let wedge =
            Foundation::Cone { apex: [0.0, -delta, 0.0], axis: [0.0, 1.0, 0.0], half_angle: alpha };
        let g = wedge.distance_along([0.3, 0.0, 0.0], [0.0, 1.0, 0.0]);
        assert!((g - (0.3 / alpha.tan() - delta)).abs() < 1e-14, "{g}");
        let strip =
            Foundation::Punch { center: [0.0, -delta, 0.0], axis: [0.0, 1.0, 0.0], radius: 0.5 };
        assert_eq!(strip.distance_along([-0.4, 0.0, 0.0], [0.0, 1.0, 0.0]), -delta);
        assert_eq!(strip.distance_along([-0.6, 0.0, 0.0], [0.0, 1.0, 0.0]), f64::INFINITY);
        // Moved rigidly 0.02 deeper, the gaps fall by 0.02.
        let deeper = cone.translated([0.0, 0.0, -0.02]);
        let g =
            deeper.distance_along([0.3, 0.0, 0.0], up) - cone.distance_along([0.3, 0.0, 0.0], up);
        assert!((g + 0.02).abs() < 1e-14, "{g}");
    }
}
