//! The contact surface Γ3 (model §6): nodal lumped weights, normals and tangents, and the
//! nodal kinematics u_ν, u_τ, ϕ. Contact quantities p_c, p_f, λ_c, λ_f, s live on its nodes.
//!
//! ```text
//! w_i = Σ_{e ∋ i} |e| / d                  (facets e of Γ3)
//! ν_i = Σ_{e ∋ i} |e| ν_e / ‖Σ_{e ∋ i} |e| ν_e‖
//! u_ν = u·ν,  u_τ = u − u_ν ν;  in 2D τ = ν rotated by +90° (ν = (0,−1) ↦ τ = (1,0))
//! ```

use super::foundation::Foundation;
use crate::dofs::{CONSTRAINED, DofMap};
use crate::error::{Error, Result};
use crate::problem::Problem;
use std::collections::BTreeMap;

/// Γ3 with its nodal geometry. Vectors are stored with 3 components (the first d used).
#[derive(Clone, Debug)]
pub struct ContactSurface {
    dim: usize,
    /// Γ3 nodes, ordered along Γ3 in 2D (from one end to the other).
    pub nodes: Vec<usize>,
    /// w_i [length^(d−1)].
    pub weight: Vec<f64>,
    /// ν_i, outward unit normals.
    pub normal: Vec<[f64; 3]>,
    /// g_a,i: the gap at node i \[length\], where compliance and conduction start; the rigid stop
    /// is at g_a,i + g_p. +∞ where the node cannot touch the foundation.
    pub gap: Vec<f64>,
    /// Per node, how many tangential directions are free (d − 1, less those a support fixes:
    /// a node on a symmetry plane across Γ3 slides along the plane only).
    free_tangents: Vec<usize>,
    /// Per node in 3D with one tangential direction fixed: that direction (else 0).
    held: Vec<[f64; 3]>,
    /// Whether Γ3 is the meridian line of a surface of revolution (its weights are areas).
    revolution: bool,
}

impl ContactSurface {
    /// Builds Γ3 from the problem's contact parts. Nodes whose displacement is fully
    /// prescribed (on Γ1) are left out: their contact force would go to the clamp.
    pub fn new(problem: &Problem, dofs: &DofMap) -> Result<Self> {
        let mesh = &problem.mesh;
        let dim = mesh.dim();
        let mut acc: BTreeMap<usize, (f64, [f64; 3])> = BTreeMap::new();
        let mut neighbours: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
        for &p in &problem.boundary.contact {
            for facet in mesh.part_facets(p) {
                let (measure, n) = mesh.facet_frame(facet);
                for (a, &node) in facet.iter().enumerate() {
                    let e = acc.entry(node).or_insert((0.0, [0.0; 3]));
                    e.0 += nodal_weight(problem, facet, a, measure);
                    (0..3).for_each(|i| e.1[i] += measure * n[i]);
                    neighbours
                        .entry(node)
                        .or_default()
                        .extend(facet.iter().filter(|&&m| m != node));
                }
            }
        }
        let free = |node: usize| (0..dim).any(|i| dofs.free_index(dofs.u(node, i)) != CONSTRAINED);
        let mut order: Vec<usize> = if dim == 2 {
            chain_order(&neighbours)
        } else {
            // In 3D, by coordinates: x, then y, then z.
            let mut nodes: Vec<usize> = acc.keys().copied().collect();
            nodes.sort_by(|&a, &b| {
                let (p, q) = (mesh.node(a), mesh.node(b));
                p.iter()
                    .zip(q)
                    .map(|(u, v)| u.total_cmp(v))
                    .find(|o| o.is_ne())
                    .unwrap_or(a.cmp(&b))
            });
            nodes
        };
        if dim == 2
            && order.len() > 1
            && mesh.node(order[0])[0] > mesh.node(order[order.len() - 1])[0]
        {
            order.reverse();
        }
        let mut surface = Self {
            dim,
            nodes: Vec::new(),
            weight: Vec::new(),
            normal: Vec::new(),
            gap: Vec::new(),
            free_tangents: Vec::new(),
            held: Vec::new(),
            revolution: problem.axisymmetric,
        };
        for node in order.into_iter().filter(|&n| free(n)) {
            let (w, mut n) = acc[&node];
            let fixed = supported_directions(problem, dofs, node, &mut n)?;
            let norm = n.iter().map(|v| v * v).sum::<f64>().sqrt();
            if norm <= 0.0 {
                return Err(Error::InvalidParameter {
                    name: "boundary.contact".into(),
                    value: format!("node {node}"),
                    requirement: "the facet normals at a Γ3 node must not cancel (a fold in Γ3?)"
                        .into(),
                });
            }
            surface.nodes.push(node);
            surface.weight.push(w);
            surface.normal.push(n.map(|v| v / norm));
            surface.gap.push(0.0);
            surface.free_tangents.push(dim - 1 - fixed.len());
            let held = match (dim, fixed.as_slice()) {
                (3, &[d]) => d,
                _ => [0.0; 3],
            };
            surface.held.push(held);
        }
        Ok(surface)
    }

    /// Sets the gaps: the distance along ν_i to `foundation` plus `offset` (the constant gap
    /// g_a of the paper when the foundation is [`Foundation::ConstantGap`]).
    pub fn with_gaps(mut self, problem: &Problem, foundation: &Foundation, offset: f64) -> Self {
        self.gap = (0..self.len())
            .map(|i| offset + foundation.distance_along(self.position3(problem, i), self.normal[i]))
            .collect();
        self
    }

    /// Node i's coordinates with 3 components.
    pub fn position3(&self, problem: &Problem, i: usize) -> [f64; 3] {
        let mut x = [0.0; 3];
        x[..self.dim].copy_from_slice(self.position(problem, i));
        x
    }

    /// Number of Γ3 nodes.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether Γ3 has no node.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Space dimension.
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// τ_i = ν_i rotated by +90° (2D); the first tangent τ1 of [`ContactSurface::frame`] in 3D.
    pub fn tangent(&self, i: usize) -> [f64; 3] {
        self.frame(i)[1]
    }

    /// The local frame of node i: rows ν, τ1, τ2, orthonormal. In 2D τ1 = ν turned by +90°
    /// and τ2 = 0. In 3D τ1 is the coordinate axis least aligned with ν, made orthogonal to ν
    /// and normalised, and τ2 = ν × τ1; the tangential columns of contact.csv are along them.
    /// At a node on a support the free tangent comes first: τ1 = d × ν and τ2 = d for the
    /// fixed direction d.
    pub fn frame(&self, i: usize) -> [[f64; 3]; 3] {
        let (nu, d) = (self.normal[i], self.held[i]);
        if d == [0.0; 3] {
            return frame(nu, self.dim);
        }
        let t1 =
            [d[1] * nu[2] - d[2] * nu[1], d[2] * nu[0] - d[0] * nu[2], d[0] * nu[1] - d[1] * nu[0]];
        [nu, t1, d]
    }

    /// Whether Γ3 is the meridian line of a surface of revolution: its weights and measures are
    /// areas of the whole revolution.
    pub fn revolution(&self) -> bool {
        self.revolution
    }

    /// How many tangential directions are free at node i: d − 1, less those a support fixes.
    pub fn free_tangents(&self, i: usize) -> usize {
        self.free_tangents[i]
    }

    /// u at Γ3 node i from a global vector.
    pub fn u(&self, dofs: &DofMap, x: &[f64], i: usize) -> [f64; 3] {
        let mut u = [0.0; 3];
        (0..self.dim).for_each(|k| u[k] = x[dofs.u(self.nodes[i], k)]);
        u
    }

    /// (u_ν, u_τ) at Γ3 node i, u_τ along the free tangential directions only (the part
    /// along a direction a support fixes is the support's, and bears no friction).
    pub fn split(&self, dofs: &DofMap, x: &[f64], i: usize) -> (f64, [f64; 3]) {
        let (u, n) = (self.u(dofs, x, i), self.normal[i]);
        let u_nu: f64 = (0..3).map(|k| u[k] * n[k]).sum();
        let u_tau = [0, 1, 2].map(|k| u[k] - u_nu * n[k]);
        match (self.free_tangents[i], self.dim) {
            (0, _) => (u_nu, [0.0; 3]),
            (1, 3) => {
                let t = self.frame(i)[1];
                let along: f64 = (0..3).map(|k| u_tau[k] * t[k]).sum();
                (u_nu, t.map(|v| along * v))
            }
            _ => (u_nu, u_tau),
        }
    }

    /// ϕ at Γ3 node i.
    pub fn phi(&self, dofs: &DofMap, x: &[f64], i: usize) -> f64 {
        x[dofs.phi(self.nodes[i])]
    }

    /// Γ3 node coordinates.
    pub fn position<'a>(&self, problem: &'a Problem, i: usize) -> &'a [f64] {
        problem.mesh.node(self.nodes[i])
    }
}

/// The share of node `a` of facet `facet` (measure `measure`) in its weight: |e|/d, or in a
/// body of revolution ∫_e 2πr φ_a ds = 2π |e| (2 r_a + r_b)/6 (a positive weight even for a
/// node on the axis).
fn nodal_weight(problem: &Problem, facet: &[usize], a: usize, measure: f64) -> f64 {
    if !problem.axisymmetric {
        return measure / facet.len() as f64;
    }
    let r = |k: usize| problem.mesh.node(facet[k])[0];
    2.0 * std::f64::consts::PI * measure * (2.0 * r(a) + r(1 - a)) / 6.0
}

/// The directions a support fixes at Γ3 node `node` (mesh axes, or the rows of its turned
/// frame), after checking that they are tangential to Γ3 there: `normal` (the sum of the
/// facets' weighted normals) loses its part along them (at most sin 1° of it; a node on a
/// symmetry plane across a curved Γ3 then has the normal of the whole body). An error where a
/// support fixes the contact normal's component: contact could not act freely.
fn supported_directions(
    problem: &Problem,
    dofs: &DofMap,
    node: usize,
    normal: &mut [f64; 3],
) -> Result<Vec<[f64; 3]>> {
    let dim = problem.mesh.dim();
    let fixed: Vec<(usize, [f64; 3])> = (0..dim)
        .filter(|&k| dofs.free_index(dofs.u(node, k)) == CONSTRAINED)
        .map(|k| (k, dofs.direction(node, k)))
        .collect();
    let dot = |a: &[f64; 3], b: &[f64; 3]| (0..3).map(|c| a[c] * b[c]).sum::<f64>();
    let length = dot(normal, normal).sqrt();
    let along = fixed.iter().map(|(_, d)| dot(normal, d).powi(2)).sum::<f64>().sqrt();
    if along > length * crate::frames::SAME_DIRECTION_DEGREES.to_radians().sin() {
        let (k, d) = fixed
            .iter()
            .max_by(|a, b| dot(normal, &a.1).abs().total_cmp(&dot(normal, &b.1).abs()))
            .copied()
            .unwrap_or((0, [0.0; 3]));
        let names = problem.support_names();
        let table = names.get(dofs.support_table(dofs.u(node, k))).cloned().unwrap_or_default();
        let direction = match (0..3).find(|&c| d[c] == 1.0) {
            Some(c) => format!("u_{}", ["x", "y", "z"][c]),
            None => format!("u along {d:?}"),
        };
        let degrees = (along / length).clamp(-1.0, 1.0).asin().to_degrees();
        return Err(Error::Input(format!(
            "the support '{table}' fixes {direction} at node {node} at {:?} of Γ3 (boundary.contact), where Γ3's normal leans {degrees:.3}° into the fixed directions (at most 1°): the support holds the contact normal's component, and contact could not act freely there; hold Γ3's nodes along tangential directions only (a symmetry plane across the contact face), or keep the support off Γ3",
            problem.mesh.node(node),
        )));
    }
    for (_, d) in &fixed {
        let part = dot(normal, d);
        (0..3).for_each(|c| normal[c] -= part * d[c]);
    }
    Ok(fixed.into_iter().map(|(_, d)| d).collect())
}

/// The frame of unit normal ν: rows ν, τ1, τ2 (see [`ContactSurface::frame`]).
pub fn frame(nu: [f64; 3], dim: usize) -> [[f64; 3]; 3] {
    if dim == 2 {
        return [nu, [-nu[1], nu[0], 0.0], [0.0; 3]];
    }
    let axis = (0..3).min_by(|&a, &b| nu[a].abs().total_cmp(&nu[b].abs())).unwrap_or(0);
    let mut t1 = [0.0; 3];
    t1[axis] = 1.0;
    let along = nu[axis];
    (0..3).for_each(|k| t1[k] -= along * nu[k]);
    let norm = t1.iter().map(|v| v * v).sum::<f64>().sqrt();
    t1.iter_mut().for_each(|v| *v /= norm);
    let t2 = [
        nu[1] * t1[2] - nu[2] * t1[1],
        nu[2] * t1[0] - nu[0] * t1[2],
        nu[0] * t1[1] - nu[1] * t1[0],
    ];
    [nu, t1, t2]
}

/// Orders the nodes of a chain of segments from one end to the other (a closed chain from
/// its smallest node); disconnected chains follow each other.
fn chain_order(neighbours: &BTreeMap<usize, Vec<usize>>) -> Vec<usize> {
    let mut order = Vec::with_capacity(neighbours.len());
    let mut visited = std::collections::HashSet::new();
    let degree = |n: &usize| {
        let mut v = neighbours[n].clone();
        v.sort_unstable();
        v.dedup();
        v.len()
    };
    let starts: Vec<usize> =
        neighbours.keys().filter(|n| degree(n) == 1).chain(neighbours.keys()).copied().collect();
    for start in starts {
        if visited.contains(&start) {
            continue;
        }
        let mut current = Some(start);
        while let Some(node) = current {
            visited.insert(node);
            order.push(node);
            current = neighbours[&node].iter().copied().find(|n| !visited.contains(n));
        }
    }
    order
}
