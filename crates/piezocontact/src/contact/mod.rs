//! The contact surface Γ3 (model §6): nodal lumped weights, normals and tangents, and the
//! nodal kinematics u_ν, u_τ, ϕ. Contact quantities p_c, p_f, λ_c, λ_f, s live on its nodes.
//!
//! ```text
//! w_i = Σ_{e ∋ i} |e| / d                  (facets e of Γ3)
//! ν_i = Σ_{e ∋ i} |e| ν_e / ‖Σ_{e ∋ i} |e| ν_e‖
//! u_ν = u·ν,  u_τ = u − u_ν ν;  in 2D τ = ν rotated by +90° (ν = (0,−1) ↦ τ = (1,0))
//! ```

pub mod law;

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
                for &node in facet {
                    let e = acc.entry(node).or_insert((0.0, [0.0; 3]));
                    e.0 += measure / dim as f64;
                    (0..3).for_each(|i| e.1[i] += measure * n[i]);
                    neighbours
                        .entry(node)
                        .or_default()
                        .extend(facet.iter().filter(|&&m| m != node));
                }
            }
        }
        let free = |node: usize| (0..dim).any(|i| dofs.free_index(dofs.u(node, i)) != CONSTRAINED);
        let mut order: Vec<usize> =
            if dim == 2 { chain_order(&neighbours) } else { acc.keys().copied().collect() };
        if dim == 2
            && order.len() > 1
            && mesh.node(order[0])[0] > mesh.node(order[order.len() - 1])[0]
        {
            order.reverse();
        }
        let mut surface = Self { dim, nodes: Vec::new(), weight: Vec::new(), normal: Vec::new() };
        for node in order.into_iter().filter(|&n| free(n)) {
            let (w, n) = acc[&node];
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
        }
        Ok(surface)
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

    /// τ_i = ν_i rotated by +90° (2D only; zero in 3D, where u_τ is a vector).
    pub fn tangent(&self, i: usize) -> [f64; 3] {
        let n = self.normal[i];
        if self.dim == 2 { [-n[1], n[0], 0.0] } else { [0.0; 3] }
    }

    /// u at Γ3 node i from a global vector.
    pub fn u(&self, dofs: &DofMap, x: &[f64], i: usize) -> [f64; 3] {
        let mut u = [0.0; 3];
        (0..self.dim).for_each(|k| u[k] = x[dofs.u(self.nodes[i], k)]);
        u
    }

    /// (u_ν, u_τ) at Γ3 node i.
    pub fn split(&self, dofs: &DofMap, x: &[f64], i: usize) -> (f64, [f64; 3]) {
        let (u, n) = (self.u(dofs, x, i), self.normal[i]);
        let u_nu: f64 = (0..3).map(|k| u[k] * n[k]).sum();
        (u_nu, [0, 1, 2].map(|k| u[k] - u_nu * n[k]))
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
