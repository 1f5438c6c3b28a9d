//! Degrees of freedom: numbering, Dirichlet constraints and the block order [u; ϕ].
//!
//! Global numbering (before elimination): u_i at node a is `a·d + i`, ϕ at node a is
//! `n_nodes·d + a`. Dirichlet rows (u on Γ1, ϕ on Γa) are eliminated: the free unknowns are
//! renumbered with every free u before every free ϕ, so the matrix is `[K_uu G; Gᵀ −K_ϕϕ]`
//! and the LDLᵀ pivot signs are +1 then −1.
//!
//! A floating electrode's nodes share one ϕ unknown (the electrode's potential): each
//! element sums into its row and column, and its equation is the sum of the ϕ rows of its
//! nodes, which balances the electrode's given charge ([`DofMap::floating`]).
//!
//! At a node with a turned frame ([`crate::frames`]: a roller on a face of any orientation)
//! the d u unknowns are the components in that frame, ũ = R u (R's rows the frame's unit
//! vectors); global vectors outside the system (x, forces) are in mesh components, and
//! [`DofMap::expand`] and [`DofMap::to_frames`] turn them.

use crate::error::Result;
use crate::problem::{Factors, Problem};

/// Marks a constrained global DOF in [`DofMap::free_index`].
pub const CONSTRAINED: usize = usize::MAX;

/// Marks a u DOF that no clamp or support fixes, in [`DofMap::support_table`].
pub use crate::frames::NO_TABLE;

/// Free numbering and prescribed values of all DOFs.
#[derive(Clone, Debug, Default)]
pub struct DofMap {
    dim: usize,
    n_nodes: usize,
    free: Vec<usize>,
    n_free_u: usize,
    n_free: usize,
    /// Prescribed values of constrained DOFs (0 on free ones), global numbering.
    prescribed: Vec<f64>,
    /// The prescribed displacements of the case (u DOFs, at load factor 1), of which
    /// `prescribed` holds the multiple a loading path's step asks for
    /// ([`DofMap::scale_displacements`]); empty when they are all 0.
    displacements: Vec<f64>,
    /// Per u DOF, the clamp or support that fixes it ([`crate::frames::NodeFrame`]'s
    /// table), [`NO_TABLE`] where free.
    table: Vec<usize>,
    /// The turned frames (rows R in mesh components), by node.
    frames: Vec<(usize, [[f64; 3]; 3])>,
    /// Per node, its index in `frames` ([`NO_TABLE`] for the mesh axes); empty without frames.
    frame_of: Vec<usize>,
    /// The floating electrodes.
    floating: Vec<Floating>,
}

/// A floating electrode in the free numbering.
#[derive(Clone, Debug, PartialEq)]
pub struct Floating {
    /// Its potential's free unknown, which the ϕ of every node of it is.
    pub unknown: usize,
    /// Its nodes, ascending.
    pub nodes: Vec<usize>,
    /// Its given total charge at load factor 1 \[charge·length^(3−d)\].
    pub charge: f64,
}

/// The free numbering of the DOFs whose first `u_count` are u's: each DOF not `constrained`
/// in order, but the ϕ of all the nodes of a floating electrode (`given`: its nodes and
/// charge) one unknown, numbered where its first DOF comes. Returns the free index of each
/// DOF ([`CONSTRAINED`] for the others), the numbers of free u DOFs and of all free DOFs, and
/// the floating electrodes.
fn number(
    constrained: &[bool],
    u_count: usize,
    given: Vec<(Vec<usize>, f64)>,
) -> (Vec<usize>, usize, usize, Vec<Floating>) {
    let mut floating_of = vec![NO_TABLE; constrained.len() - u_count];
    for (k, (nodes, _)) in given.iter().enumerate() {
        nodes.iter().for_each(|&a| floating_of[a] = k);
    }
    let mut unknowns: Vec<Option<usize>> = vec![None; given.len()];
    let mut free = vec![CONSTRAINED; constrained.len()];
    let (mut next, mut n_free_u) = (0, 0);
    for (g, c) in constrained.iter().enumerate() {
        let electrode = g.checked_sub(u_count).map_or(NO_TABLE, |a| floating_of[a]);
        if let Some(&Some(unknown)) = unknowns.get(electrode) {
            free[g] = unknown;
        } else if !c {
            free[g] = next;
            if let Some(slot) = unknowns.get_mut(electrode) {
                *slot = Some(next);
            }
            next += 1;
        }
        if g + 1 == u_count {
            n_free_u = next;
        }
    }
    let floating = given
        .into_iter()
        .zip(unknowns)
        .map(|((nodes, charge), unknown)| Floating {
            unknown: unknown.unwrap_or(CONSTRAINED),
            nodes,
            charge,
        })
        .collect();
    (free, n_free_u, next, floating)
}

impl DofMap {
    /// Numbers the DOFs of `problem`: u fixed on Γ1, ϕ fixed on Γa.
    pub fn new(problem: &Problem) -> Result<Self> {
        let mesh = &problem.mesh;
        let (dim, n_nodes) = (mesh.dim(), mesh.n_nodes());
        let total = n_nodes * (dim + 1);
        let mut prescribed = vec![0.0; total];
        let mut constrained = vec![false; total];
        let mut table = vec![NO_TABLE; n_nodes * dim];
        let mut frames = Vec::new();
        for f in problem.fixed_displacements()? {
            for &(i, value, t) in &f.fixed {
                let g = f.node * dim + i;
                (constrained[g], prescribed[g], table[g]) = (true, value, t);
            }
            frames.extend(f.rows.map(|rows| (f.node, rows)));
        }
        let mut frame_of = Vec::new();
        if !frames.is_empty() {
            frame_of = vec![NO_TABLE; n_nodes];
            frames.iter().enumerate().for_each(|(k, (node, _))| frame_of[*node] = k);
        }
        let mut electrodes = vec![0.0; n_nodes];
        for (node, value) in problem.electrode_potentials()? {
            constrained[n_nodes * dim + node] = true;
            prescribed[n_nodes * dim + node] = value;
            if !problem.boundary.electrodes.is_empty() {
                electrodes[node] = value;
            }
        }
        let (free, n_free_u, n_free, floating) =
            number(&constrained, n_nodes * dim, problem.floating_electrodes()?);
        // What a loading path scales: the prescribed displacements and the electrodes' voltages
        // (the grounded parts' prescribed field of a verification problem stays).
        let mut scaled = prescribed[..n_nodes * dim].to_vec();
        if electrodes.iter().any(|v| *v != 0.0) {
            scaled.extend(electrodes);
        }
        let nonzero = scaled.iter().any(|v| *v != 0.0);
        let displacements = if nonzero { scaled } else { Vec::new() };
        Ok(Self {
            dim,
            n_nodes,
            free,
            n_free_u,
            n_free,
            prescribed,
            displacements,
            table,
            frames,
            frame_of,
            floating,
        })
    }

    /// The floating electrodes.
    pub fn floating(&self) -> &[Floating] {
        &self.floating
    }

    /// The floating electrode `node` is on, if any.
    pub fn floating_of(&self, node: usize) -> Option<&Floating> {
        let k = self.free[self.phi(node)];
        self.floating.iter().find(|f| f.unknown == k)
    }

    /// The node whose ϕ stands for the floating electrode of `node` (its first), `node`
    /// itself off them: nodes with the same one share their ϕ unknown.
    pub fn phi_owner(&self, node: usize) -> usize {
        self.floating_of(node).map_or(node, |f| f.nodes[0])
    }

    /// Sums, for each floating electrode, the ϕ rows of its nodes of a global `residual`
    /// R = F_int − f − F_c, with its given charge times `electrode_factor` [-], into the row
    /// of its first node (the others 0): the electrode's equation (Σ R + Q = 0). `scale` (the
    /// row scales) alike, with |Q|.
    pub fn sum_floating(&self, residual: &mut [f64], scale: &mut [f64], electrode_factor: f64) {
        for f in &self.floating {
            let charge = electrode_factor * f.charge;
            let (mut r, mut s) = (charge, charge.abs());
            for &a in &f.nodes {
                let g = self.phi(a);
                r += std::mem::take(&mut residual[g]);
                s += std::mem::take(&mut scale[g]);
            }
            (residual[self.phi(f.nodes[0])], scale[self.phi(f.nodes[0])]) = (r, s);
        }
    }

    /// The turned frame of `node` (rows R: its unit vectors in mesh components), `None` for
    /// the mesh axes.
    pub fn frame(&self, node: usize) -> Option<&[[f64; 3]; 3]> {
        match self.frame_of.get(node) {
            Some(&k) if k != NO_TABLE => Some(&self.frames[k].1),
            _ => None,
        }
    }

    /// The unit vector of u component `i` at `node` in mesh components (3 entries).
    pub fn direction(&self, node: usize, i: usize) -> [f64; 3] {
        self.frame(node).map_or_else(|| crate::frames::axis(i), |rows| rows[i])
    }

    /// Whether some node has a turned frame.
    pub fn has_frames(&self) -> bool {
        !self.frames.is_empty()
    }

    /// Turns the u entries of a global vector (displacements or forces) from mesh
    /// components to the nodes' frames: ũ = R u.
    pub fn to_frames(&self, global: &mut [f64]) {
        self.turn(global, false);
    }

    /// Turns the u entries of a global vector from the nodes' frames to mesh components:
    /// u = Rᵀ ũ.
    pub fn to_mesh(&self, global: &mut [f64]) {
        self.turn(global, true);
    }

    /// Adds `force` (mesh components, d used) at `node`'s u rows to the free vector `free`,
    /// turned to the node's frame; constrained components take nothing.
    pub fn add_at_node(&self, node: usize, force: &[f64; 3], free: &mut [f64]) {
        let turned = self.turned(node, force);
        for (i, f) in turned.iter().enumerate().take(self.dim) {
            let k = self.free_index(self.u(node, i));
            if k != CONSTRAINED {
                free[k] += f;
            }
        }
    }

    /// A vector at `node` (mesh components) in the node's frame: R v (v itself without one).
    pub fn turned(&self, node: usize, v: &[f64; 3]) -> [f64; 3] {
        match self.frame(node) {
            Some(rows) => std::array::from_fn(|i| (0..3).map(|j| rows[i][j] * v[j]).sum()),
            None => *v,
        }
    }

    /// Turns the u entries of a vector of row scales (sizes of the terms of each row) to the
    /// nodes' frames: Σ_j |R_ij| s_j bounds the terms of row i of the turned rows.
    pub fn frame_bound(&self, scale: &mut [f64]) {
        let d = self.dim;
        for (node, rows) in &self.frames {
            let v = &mut scale[node * d..node * d + d];
            let out: [f64; 3] =
                std::array::from_fn(|i| (0..d).map(|j| rows[i][j].abs() * v[j]).sum());
            v.copy_from_slice(&out[..d]);
        }
    }

    fn turn(&self, global: &mut [f64], transposed: bool) {
        let d = self.dim;
        for (node, rows) in &self.frames {
            let v = &mut global[node * d..node * d + d];
            let mut out = [0.0; 3];
            for (i, o) in out.iter_mut().enumerate().take(d) {
                *o = (0..d).map(|j| if transposed { rows[j][i] } else { rows[i][j] } * v[j]).sum();
            }
            v.copy_from_slice(&out[..d]);
        }
    }

    /// The component of each free unknown: i for u_i (in the node's frame, where it has one),
    /// d for ϕ.
    pub fn free_components(&self) -> Vec<u8> {
        let mut components = vec![0; self.n_free()];
        let u_end = self.n_nodes * self.dim;
        for (g, &k) in self.free.iter().enumerate().filter(|(_, k)| **k != CONSTRAINED) {
            components[k] = if g < u_end { g % self.dim } else { self.dim } as u8;
        }
        components
    }

    /// The free unknowns of each node (u components and ϕ).
    pub fn free_per_node(&self) -> Vec<usize> {
        let mut count = vec![0; self.n_nodes];
        for (g, &k) in self.free.iter().enumerate() {
            if k != CONSTRAINED {
                let node = if g < self.n_nodes * self.dim {
                    g / self.dim
                } else {
                    g - self.n_nodes * self.dim
                };
                count[node] += 1;
            }
        }
        count
    }

    /// Global index of u_i at `node`.
    pub fn u(&self, node: usize, i: usize) -> usize {
        node * self.dim + i
    }

    /// Global index of ϕ at `node`.
    pub fn phi(&self, node: usize) -> usize {
        self.n_nodes * self.dim + node
    }

    /// Total number of DOFs, n_nodes·(d + 1).
    pub fn n_total(&self) -> usize {
        self.free.len()
    }

    /// Number of free DOFs (the order of the linear system).
    pub fn n_free(&self) -> usize {
        self.n_free
    }

    /// Number of free u DOFs; free ϕ DOFs follow them.
    pub fn n_free_u(&self) -> usize {
        self.n_free_u
    }

    /// The clamp or support that fixes global u DOF `g` (an index into
    /// [`crate::problem::Problem::support_names`]), [`NO_TABLE`] for a free DOF or a ϕ DOF.
    pub fn support_table(&self, g: usize) -> usize {
        self.table.get(g).copied().unwrap_or(NO_TABLE)
    }

    /// Free index of global DOF `g`, or [`CONSTRAINED`].
    pub fn free_index(&self, g: usize) -> usize {
        self.free[g]
    }

    /// Prescribed value of global DOF `g` (0 for a free DOF), a u DOF's in its node's frame.
    pub fn prescribed(&self, g: usize) -> f64 {
        self.prescribed[g]
    }

    /// Whether some prescribed displacement is not 0 (a loading path scales them).
    pub fn has_prescribed_displacements(&self) -> bool {
        !self.displacements.is_empty()
    }

    /// Sets the prescribed displacements to `factors.loads` [-] times the case's and the
    /// electrodes' voltages to `factors.electrodes` times theirs (a step of a loading path);
    /// the grounded parts stay at their potential.
    pub fn scale_displacements(&mut self, factors: Factors) {
        let u = self.n_nodes * self.dim;
        for (g, unit) in self.displacements.iter().enumerate() {
            let factor = if g < u { factors.loads } else { factors.electrodes };
            self.prescribed[g] = factor * unit;
        }
    }

    /// Pivot signs of the free DOFs: +1 for u, −1 for ϕ.
    pub fn signs(&self) -> Vec<i8> {
        (0..self.n_free).map(|k| if k < self.n_free_u { 1 } else { -1 }).collect()
    }

    /// The full global vector (in mesh components) from free values and prescribed values.
    pub fn expand(&self, free_values: &[f64]) -> Vec<f64> {
        let mut global: Vec<f64> = (0..self.n_total())
            .map(|g| match self.free[g] {
                CONSTRAINED => self.prescribed[g],
                k => free_values[k],
            })
            .collect();
        self.to_mesh(&mut global);
        global
    }
}
