//! The foundation's surface (model §12). The paper's gap ρ is "measured along the outward
//! normal": at Γ3 node i it is the distance from x_i along ν_i to the foundation,
//!
//! ```text
//! plane through p with unit normal n (out of the foundation, toward the body):
//!     g_i = n·(x_i − p) / (−n·ν_i)                    (no hit when −n·ν_i ≤ 0)
//! ball (disk in 2D) of centre c and radius R, the body outside it:
//!     g_i = the first t with |x_i + t ν_i − c| = R     (no hit when the ray misses it)
//! ```
//!
//! A negative gap is an initial interpenetration that the solution removes. A node whose
//! normal misses the foundation cannot touch it: its gap is +∞. The case's `contact.gap` is
//! added to the distance as an offset.

/// The foundation's surface.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Foundation {
    /// The paper's: a constant gap along the normal of every Γ3 node (`contact.gap`).
    #[default]
    ConstantGap,
    /// A rigid half-space.
    Plane {
        /// A point of the plane [length] (3 components, the last 0 in 2D).
        point: [f64; 3],
        /// Its unit normal, out of the foundation toward the body.
        normal: [f64; 3],
    },
    /// A rigid ball (a disk in 2D), the body outside it.
    Sphere {
        /// Centre [length].
        center: [f64; 3],
        /// Radius [length].
        radius: f64,
    },
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|k| a[k] * b[k]).sum()
}

impl Foundation {
    /// The distance from x along the unit vector ν to the surface [length]: +∞ when the ray
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
        }
    }

    /// The shortest distance from x to the surface [length] (negative inside), for output.
    pub fn distance(&self, x: [f64; 3]) -> f64 {
        match *self {
            Self::ConstantGap => 0.0,
            Self::Plane { point, normal } => dot(normal, [0, 1, 2].map(|k| x[k] - point[k])),
            Self::Sphere { center, radius } => {
                let d = [0, 1, 2].map(|k| x[k] - center[k]);
                dot(d, d).sqrt() - radius
            }
        }
    }
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
}
