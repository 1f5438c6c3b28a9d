//! The data of a static piezoelectric problem (\[P\] (2.1)–(2.4)): mesh, material, boundary
//! roles and loads. [`Problem::new`] checks the roles once.

use crate::error::{Error, Result};
use crate::frames::{
    FixedDirection, NO_TABLE, NodeFrame, SAME_DIRECTION_DEGREES, axis, node_frame,
};
use crate::material::{Material, Materials};
use crate::mesh::Mesh;
use crate::mesh::normals::node_normals;
use crate::mesh::rigid::{free_rigid_motions, motions_sentence};
use std::sync::Arc;

/// A vector field x ↦ v(x) with d components (loads, prescribed displacements).
pub type VectorField = Arc<dyn Fn(&[f64]) -> Vec<f64> + Send + Sync>;
/// A scalar field x ↦ s(x).
pub type ScalarField = Arc<dyn Fn(&[f64]) -> f64 + Send + Sync>;

/// A constant vector field.
pub fn constant_vector(v: Vec<f64>) -> VectorField {
    Arc::new(move |_| v.clone())
}

/// A constant scalar field.
pub fn constant_scalar(s: f64) -> ScalarField {
    Arc::new(move |_| s)
}

/// A support: components of u fixed on boundary parts (a roller, a symmetry plane, a
/// prescribed displacement component).
#[derive(Clone)]
pub struct Support {
    /// The name in outputs (reactions).
    pub name: String,
    /// The boundary parts it holds.
    pub parts: Vec<usize>,
    /// The fixed directions, each with its prescribed displacement u·n(x) \[length\].
    pub fixed: Vec<(Direction, ScalarField)>,
}

/// A direction a support fixes u along.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Direction {
    /// A mesh axis (0 = x, 1 = y, 2 = z).
    Axis(usize),
    /// The outward normal of the support's parts at each node (a roller on a face of any
    /// orientation, [`crate::frames`]).
    Normal,
}

impl Direction {
    /// Its name in a case: "x", "y", "z" or "normal".
    pub fn name(&self) -> &'static str {
        match self {
            Direction::Axis(i) => ["x", "y", "z"][*i],
            Direction::Normal => "normal",
        }
    }
}

/// Boundary roles of \[P\] (2.4), each a list of mesh part indices. Parts with no role are
/// traction free and charge free (natural conditions).
#[derive(Clone, Default)]
pub struct Boundary {
    /// Γ1: u = u_D (0 in the model).
    pub clamped: Vec<usize>,
    /// Γa: ϕ = ϕ_D (0 in the model).
    pub grounded: Vec<usize>,
    /// Γ3: the contact surface.
    pub contact: Vec<usize>,
    /// Γ2 with its traction density f2 \[stress\].
    pub traction: Vec<(usize, VectorField)>,
    /// Γb with its surface charge density q2 [charge/length^(d−1)].
    pub charge: Vec<(usize, ScalarField)>,
    /// Prescribed displacement on Γ1 \[length\]; `None` is the model's u = 0. Used by
    /// verification problems (patch tests, manufactured solutions).
    pub clamped_value: Option<VectorField>,
    /// Supports: components of u fixed on parts (with or without a clamp).
    pub supports: Vec<Support>,
    /// Prescribed potential on Γa \[potential\]; `None` is the model's ϕ = 0.
    pub grounded_value: Option<ScalarField>,
    /// Electrodes beyond the grounded parts: at a prescribed potential (part of Γa) or
    /// floating.
    pub electrodes: Vec<Electrode>,
}

/// An electrode: boundary parts at one potential.
#[derive(Clone, Debug, PartialEq)]
pub struct Electrode {
    /// Its name in outputs.
    pub name: String,
    /// The boundary parts it covers.
    pub parts: Vec<usize>,
    /// What holds it.
    pub condition: ElectrodeCondition,
}

/// What holds an electrode, at load factor 1.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ElectrodeCondition {
    /// A prescribed potential \[potential\].
    Voltage(f64),
    /// A floating electrode: one unknown potential over its parts, and its total charge
    /// given \[charge·length^(3−d)\] (0: an open circuit).
    Floating(f64),
}

impl Electrode {
    /// Its prescribed potential at load factor 1, `None` for a floating electrode.
    pub fn voltage(&self) -> Option<f64> {
        match self.condition {
            ElectrodeCondition::Voltage(v) => Some(v),
            ElectrodeCondition::Floating(_) => None,
        }
    }

    /// "voltage" or "floating", as outputs name the kind.
    pub fn kind(&self) -> &'static str {
        match self.condition {
            ElectrodeCondition::Voltage(_) => "voltage",
            ElectrodeCondition::Floating(_) => "floating",
        }
    }
}

/// The factors a step of a loading path puts on a case's loads, supports' displacements
/// and surface charges (`loads`), and on its electrodes' voltages and charges
/// (`electrodes`) [-]; a bare factor is both.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Factors {
    /// On f0, q0, f2, q2 and the prescribed displacements [-].
    pub loads: f64,
    /// On the electrodes' voltages and floating charges [-].
    pub electrodes: f64,
}

impl From<f64> for Factors {
    fn from(factor: f64) -> Self {
        Self { loads: factor, electrodes: factor }
    }
}

/// How a node of an electrode is held: at a potential \[potential\], or on the floating
/// electrode of that index.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Held {
    At(f64),
    Floating(usize),
}

impl std::fmt::Display for Held {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        match self {
            Held::At(v) => write!(f, "at {v}"),
            Held::Floating(_) => write!(f, "floating"),
        }
    }
}

/// Body loads of (2.1).
#[derive(Clone, Default)]
pub struct BodyLoads {
    /// f0: body force density [stress/length].
    pub f0: Option<VectorField>,
    /// q0: volume charge density [charge/length^d].
    pub q0: Option<ScalarField>,
}

/// A checked problem.
#[derive(Clone)]
pub struct Problem {
    /// The mesh.
    pub mesh: Mesh,
    /// The materials of the cells.
    pub materials: Materials,
    /// Boundary roles and data.
    pub boundary: Boundary,
    /// Body loads.
    pub loads: BodyLoads,
    /// Whether the 2D mesh is the meridian section of a body of revolution about the y axis
    /// (x is the radius r ≥ 0): every integral carries 2πr, the hoop strain u_r/r enters the
    /// law, and u_r = 0 at the nodes on the axis ([`Problem::new_axisymmetric`]).
    pub axisymmetric: bool,
}

/// A node within this fraction of the mesh's size of x = 0 lies on the axis of an
/// axisymmetric body [-].
const ON_AXIS: f64 = 1e-12;

impl Problem {
    /// Checks that Γ1 and Γa have positive measure (else the system is singular: Korn's and
    /// Friedrichs' inequalities (2.9) need them), and that Γ3 shares no facet with Γ1 ∪ Γ2 ∪
    /// Γb (it may with Γa: an electrode touching the foundation), nor Γa with Γb, nor Γ1
    /// with Γ2.
    pub fn new(
        mesh: Mesh,
        materials: impl Into<Materials>,
        boundary: Boundary,
        loads: BodyLoads,
    ) -> Result<Self> {
        let materials = materials.into();
        if materials.dim() != mesh.dim() {
            return Err(Error::InvalidParameter {
                name: "material dimension".into(),
                value: materials.dim().to_string(),
                requirement: format!("must equal the mesh dimension {}", mesh.dim()),
            });
        }
        if ![0, mesh.n_cells()].contains(&materials.n_mapped()) {
            return Err(Error::InvalidParameter {
                name: "the cells' materials".into(),
                value: materials.n_mapped().to_string(),
                requirement: format!("one per cell ({})", mesh.n_cells()),
            });
        }
        let problem = Self { mesh, materials, boundary, loads, axisymmetric: false };
        problem.check_roles()?;
        Ok(problem)
    }

    /// As [`Problem::new`], for the meridian section (x = r ≥ 0, y the axis) of a body of
    /// revolution: a 2D mesh with no node at r < 0 (an error naming the node). The nodes on
    /// the axis have u_r = 0 (no support needed), so the clamps and supports need hold only
    /// the translation along y.
    pub fn new_axisymmetric(
        mesh: Mesh,
        materials: impl Into<Materials>,
        boundary: Boundary,
        loads: BodyLoads,
    ) -> Result<Self> {
        if mesh.dim() != 2 {
            return Err(Error::Input(format!(
                "an axisymmetric body is the meridian section of a body of revolution, a 2D mesh; this mesh is {}D",
                mesh.dim()
            )));
        }
        let tolerance = ON_AXIS * mesh_size(&mesh);
        if let Some(node) = (0..mesh.n_nodes()).find(|&a| mesh.node(a)[0] < -tolerance) {
            return Err(Error::Input(format!(
                "node {node} at {:?} has x = r < 0: an axisymmetric mesh is the meridian section at r = x ≥ 0, its axis x = 0; move the mesh to x ≥ 0",
                mesh.node(node)
            )));
        }
        let materials = materials.into();
        let problem = Self { mesh, materials, boundary, loads, axisymmetric: true };
        problem.check_roles()?;
        Ok(problem)
    }

    /// The weight of an integral at point `p` of the mesh: 2πr in an axisymmetric body (the
    /// circumference swept by the point), 1 otherwise.
    pub fn revolution(&self, p: &[f64]) -> f64 {
        if self.axisymmetric { 2.0 * std::f64::consts::PI * p[0] } else { 1.0 }
    }

    /// The nodes on the axis of an axisymmetric body (none otherwise), ascending.
    pub fn axis_nodes(&self) -> Vec<usize> {
        if !self.axisymmetric {
            return Vec::new();
        }
        let tolerance = ON_AXIS * mesh_size(&self.mesh);
        (0..self.mesh.n_nodes()).filter(|&a| self.mesh.node(a)[0].abs() <= tolerance).collect()
    }

    /// Cell c's material.
    pub fn material(&self, c: usize) -> &Material {
        self.materials.of(c)
    }

    fn check_roles(&self) -> Result<()> {
        let b = &self.boundary;
        let measure =
            |parts: &[usize]| parts.iter().map(|&p| self.mesh.part_measure(p)).sum::<f64>();
        let held: Vec<usize> = self.held_parts();
        if measure(&held) <= 0.0 {
            return Err(Error::EmptyRole {
                role: "Γ1 (clamped or supported)",
                why: "the displacement must be fixed on a part of positive measure, or the body \
                      can move freely and the system is singular; name at least one non-empty \
                      boundary part as clamped, or hold parts with [[boundary.support]] tables",
            });
        }
        let potential = self.potential_parts();
        if measure(&self.voltage_parts()) <= 0.0 {
            return Err(Error::EmptyRole {
                role: "Γa (grounded)",
                why: "the potential must be fixed on a part of positive measure, or it is only \
                      known up to a constant and the system is singular; name at least one \
                      non-empty boundary part as grounded, or an electrode with a voltage (a \
                      floating electrode does not fix it)",
            });
        }
        self.check_electrodes()?;
        self.check_pieces()?;
        self.check_rigid_motions()?;
        let traction: Vec<usize> = b.traction.iter().map(|(p, _)| *p).collect();
        let charge: Vec<usize> = b.charge.iter().map(|(p, _)| *p).collect();
        let roles: [(&'static str, &[usize]); 6] = [
            ("Γ1 (clamped)", &b.clamped),
            ("Γ2 (traction)", &traction),
            ("Γ3 (contact)", &b.contact),
            ("Γa (grounded or an electrode)", &potential),
            ("Γb (charge)", &charge),
            ("Γ3 (contact)", &b.contact),
        ];
        // Pairs that must be disjoint: (Γ1, Γ2), (Γ3, all others but Γa: an electrode may
        // touch the foundation), (Γa, Γb).
        for (i, j) in [(0, 1), (2, 0), (2, 1), (2, 4), (3, 4)] {
            self.check_disjoint(roles[i], roles[j])?;
        }
        self.check_contact_parts_apart()
    }

    /// Checks that no two parts of Γ3 (nor one part named twice) share a facet: the facet
    /// would count twice in the nodes' weights, and every contact stress would be halved.
    fn check_contact_parts_apart(&self) -> Result<()> {
        match self.mesh.facet_shared_within(&self.boundary.contact) {
            Some((first, second, nodes)) => Err(Error::Input(format!(
                "boundary parts '{first}' and '{second}' of Γ3 (contact) share the facet with \
                 nodes {nodes:?}: a facet of Γ3 must belong to one contact part (it would count \
                 twice); name each facet in one part only"
            ))),
            None => Ok(()),
        }
    }

    /// Checks that every connected piece of the body touches Γ1 and Γa (directly, or through
    /// a floating electrode that also covers a piece that does): a piece that does not can
    /// move freely (or its potential is known up to a constant), and the system is singular.
    fn check_pieces(&self) -> Result<()> {
        let pieces = self.mesh.pieces();
        let mut held = vec![false; pieces.cells.len()];
        self.part_nodes(&self.held_parts())
            .into_iter()
            .for_each(|a| held[pieces.of_node[a]] = true);
        self.check_held(
            &pieces,
            &held,
            ("Γ1 (clamped)", "boundary.clamped or a [[boundary.support]]"),
        )?;
        let mut held = vec![false; pieces.cells.len()];
        self.part_nodes(&self.voltage_parts())
            .into_iter()
            .for_each(|a| held[pieces.of_node[a]] = true);
        let floating: Vec<Vec<usize>> = (self.boundary.electrodes.iter())
            .filter(|e| e.voltage().is_none())
            .map(|e| self.part_nodes(&e.parts).into_iter().map(|a| pieces.of_node[a]).collect())
            .collect();
        // A floating electrode ties the potentials of the pieces it covers.
        for _ in 0..floating.len() {
            for covered in &floating {
                if covered.iter().any(|&k| held[k]) {
                    covered.iter().for_each(|&k| held[k] = true);
                }
            }
        }
        let key = "boundary.grounded or an electrode with a voltage";
        self.check_held(&pieces, &held, ("Γa (grounded or at a voltage)", key))
    }

    /// An error naming the pieces of the body that are not `held` by `role`.
    fn check_held(
        &self,
        pieces: &crate::mesh::Pieces,
        held: &[bool],
        (role, key): (&str, &str),
    ) -> Result<()> {
        let loose: Vec<String> = (0..held.len())
            .filter(|&k| !held[k] && pieces.cells[k] > 0)
            .map(|k| {
                let (lo, hi) = &pieces.boxes[k];
                format!(
                    "piece {} ({} elements, bounding box {lo:?}–{hi:?})",
                    k + 1,
                    pieces.cells[k]
                )
            })
            .collect();
        if loose.is_empty() {
            return Ok(());
        }
        let count = pieces.cells.iter().filter(|c| **c > 0).count();
        Err(Error::Input(format!(
            "the body has {count} connected pieces and {} of them touch no {role} part: {}; such a piece is not held, and the system is singular: add a boundary part on it to {key}, or remove it from the mesh",
            loose.len(),
            loose.join("; ")
        )))
    }

    fn check_disjoint(
        &self,
        (first_role, first): (&'static str, &[usize]),
        (second_role, second): (&'static str, &[usize]),
    ) -> Result<()> {
        match self.mesh.shared_facet(first, second) {
            Some((first, second, nodes)) => {
                Err(Error::RoleConflict { first, first_role, second, second_role, nodes })
            }
            None => Ok(()),
        }
    }

    /// The parts of Γa, where ϕ is prescribed: the grounded ones, then the electrodes'.
    pub fn potential_parts(&self) -> Vec<usize> {
        let b = &self.boundary;
        b.grounded.iter().chain(b.electrodes.iter().flat_map(|e| &e.parts)).copied().collect()
    }

    /// The parts where ϕ is prescribed: the grounded ones, then the voltage electrodes'.
    pub fn voltage_parts(&self) -> Vec<usize> {
        let b = &self.boundary;
        let voltage = b.electrodes.iter().filter(|e| e.voltage().is_some());
        b.grounded.iter().chain(voltage.flat_map(|e| &e.parts)).copied().collect()
    }

    /// The potential each node of Γa is held at, at load factor 1 (the grounded parts' 0, or
    /// their prescribed field, then each voltage electrode's), ascending by node; an error
    /// where a node is held at two potentials, or on a floating electrode and held otherwise.
    pub fn electrode_potentials(&self) -> Result<Vec<(usize, f64)>> {
        Ok(self
            .electrode_nodes()?
            .into_iter()
            .filter_map(|(node, held)| match held {
                Held::At(value) => Some((node, value)),
                Held::Floating(_) => None,
            })
            .collect())
    }

    /// The nodes of each floating electrode (in the order of the electrodes that float,
    /// ascending) with its charge at load factor 1 \[charge·length^(3−d)\]; an error as
    /// [`Problem::electrode_potentials`].
    pub fn floating_electrodes(&self) -> Result<Vec<(Vec<usize>, f64)>> {
        self.electrode_nodes()?;
        let floating = self.boundary.electrodes.iter().filter_map(|e| match e.condition {
            ElectrodeCondition::Floating(q) => Some((self.part_nodes(&e.parts), q)),
            ElectrodeCondition::Voltage(_) => None,
        });
        Ok(floating.collect())
    }

    /// What holds each node of an electrode or a grounded part, ascending by node; an error
    /// where a node is held twice in different ways.
    fn electrode_nodes(&self) -> Result<Vec<(usize, Held)>> {
        let b = &self.boundary;
        let mesh = &self.mesh;
        let grounded = |node: usize| b.grounded_value.as_ref().map_or(0.0, |f| f(mesh.node(node)));
        let mut held: Vec<(usize, Held, String)> = self
            .part_nodes(&b.grounded)
            .into_iter()
            .map(|node| (node, Held::At(grounded(node)), "the grounded parts".to_string()))
            .collect();
        for (k, e) in b.electrodes.iter().enumerate() {
            let (at, how) = match e.condition {
                ElectrodeCondition::Voltage(v) => {
                    (format!("the electrode '{}'", e.name), Held::At(v))
                }
                ElectrodeCondition::Floating(_) => {
                    (format!("the floating electrode '{}'", e.name), Held::Floating(k))
                }
            };
            held.extend(self.part_nodes(&e.parts).into_iter().map(|node| (node, how, at.clone())));
        }
        held.sort_by_key(|h| h.0);
        let mut nodes: Vec<(usize, Held)> = Vec::with_capacity(held.len());
        for pair in held.chunk_by(|a, b| a.0 == b.0) {
            let (node, how, first) = &pair[0];
            if let Some((_, other, second)) = pair.iter().find(|h| h.1 != *how) {
                return Err(Error::Input(format!(
                    "node {node} at {:?} is on {first} ({how}) and on {second} ({other}): electrodes under different conditions must not touch (they would be shorted); split the parts so that they share no node",
                    mesh.node(*node)
                )));
            }
            nodes.push((*node, *how));
        }
        Ok(nodes)
    }

    /// Refuses electrodes that share a facet with each other or with a grounded part, and
    /// nodes held at two potentials.
    fn check_electrodes(&self) -> Result<()> {
        if let Some((first, second, nodes)) = self.mesh.facet_shared_within(&self.potential_parts())
        {
            return Err(Error::Input(format!(
                "boundary parts '{first}' and '{second}' of Γa (grounded parts and electrodes) share the facet with nodes {nodes:?}: a facet belongs to one electrode; name each part once"
            )));
        }
        self.electrode_potentials().map(|_| ())
    }

    /// The parts that fix displacement components: the clamped ones, then the supports'.
    fn held_parts(&self) -> Vec<usize> {
        let b = &self.boundary;
        b.clamped.iter().chain(b.supports.iter().flat_map(|s| &s.parts)).copied().collect()
    }

    /// How many tables hold the body: the clamp, if there is one, and the supports.
    pub fn n_support_tables(&self) -> usize {
        self.clamp_tables() + self.boundary.supports.len()
    }

    /// 1 with a clamp (the first table), else 0.
    fn clamp_tables(&self) -> usize {
        usize::from(!self.boundary.clamped.is_empty())
    }

    /// The names of the tables that hold the body, in order: the clamp (its parts' names
    /// joined by '+'), if there is one, then each support.
    pub fn support_names(&self) -> Vec<String> {
        let b = &self.boundary;
        let parts = self.mesh.parts();
        let clamp = b.clamped.iter().map(|&p| parts[p].name.as_str()).collect::<Vec<_>>();
        let clamp = (!clamp.is_empty()).then(|| clamp.join("+"));
        clamp.into_iter().chain(b.supports.iter().map(|s| s.name.clone())).collect()
    }

    /// The clamps and supports whose reactions a path's curve.csv reports one by one: all
    /// of [`Problem::support_names`] when the case has supports, none with a clamp alone
    /// (whose reaction is the total).
    pub fn reported_supports(&self) -> Vec<String> {
        match self.boundary.supports.is_empty() {
            true => Vec::new(),
            false => self.support_names(),
        }
    }

    /// The fixed components of every held node in its frame ([`crate::frames`]), ascending
    /// by node: the clamp's directions (every axis of its nodes) first, then the supports'
    /// in order; a component fixed again keeps its first table. The same component fixed to
    /// two values, or a "normal" support on a part that turns at a node by more than
    /// [`SAME_DIRECTION_DEGREES`], is an error naming the node.
    pub fn fixed_displacements(&self) -> Result<Vec<NodeFrame>> {
        let mut entries = self.fixed_directions()?;
        entries.sort_by_key(|e| e.node);
        let names = self.support_names();
        let dim = self.mesh.dim();
        entries.chunk_by(|a, b| a.node == b.node).map(|at| node_frame(dim, at, &names)).collect()
    }

    /// Every direction the clamp and the supports fix, in table order.
    fn fixed_directions(&self) -> Result<Vec<FixedDirection>> {
        let (mesh, b) = (&self.mesh, &self.boundary);
        let mut entries = Vec::new();
        for node in self.part_nodes(&b.clamped) {
            let value = b.clamped_value.as_ref().map(|f| f(mesh.node(node)));
            entries.extend((0..mesh.dim()).map(|i| FixedDirection {
                node,
                direction: axis(i),
                value: value.as_ref().map_or(0.0, |v| v[i]),
                table: 0,
            }));
        }
        // The axis of an axisymmetric body: u_r = 0, a condition of no table.
        entries.extend(self.axis_nodes().into_iter().map(|node| FixedDirection {
            node,
            direction: axis(0),
            value: 0.0,
            table: NO_TABLE,
        }));
        for (k, support) in b.supports.iter().enumerate() {
            let table = k + self.clamp_tables();
            let normals = match support.fixed.iter().any(|(d, _)| *d == Direction::Normal) {
                true => self.support_normals(support)?,
                false => Vec::new(),
            };
            for (j, node) in self.part_nodes(&support.parts).into_iter().enumerate() {
                for (direction, field) in &support.fixed {
                    let direction = match direction {
                        Direction::Axis(i) => axis(*i),
                        Direction::Normal => normals[j].1,
                    };
                    entries.push(FixedDirection {
                        node,
                        direction,
                        value: field(mesh.node(node)),
                        table,
                    });
                }
            }
        }
        Ok(entries)
    }

    /// The outward normal of a support's parts at each of their nodes (in
    /// [`Problem::part_nodes`] order), or an error naming a node where the parts turn.
    fn support_normals(&self, support: &Support) -> Result<Vec<(usize, [f64; 3])>> {
        node_normals(&self.mesh, &support.parts, SAME_DIRECTION_DEGREES).map_err(|corner| {
            Error::Input(format!(
                "the support '{}' fixes the normal component, but its parts turn by {:.3}° at node {} at {:?} (an edge or a corner, where the normal is not one direction): split the parts there into faces of their own, each with its own support, or fix components along the axes",
                support.name,
                corner.degrees,
                corner.node,
                self.mesh.node(corner.node)
            ))
        })
    }

    /// Refuses a body that its clamps and supports leave free to move rigidly, naming the
    /// free motions (per piece when the mesh has several).
    fn check_rigid_motions(&self) -> Result<()> {
        let fixed: Vec<(usize, [f64; 3])> = self
            .fixed_displacements()?
            .iter()
            .flat_map(|f| f.fixed.iter().map(|&(i, ..)| (f.node, f.direction(i))))
            .collect();
        let pieces = self.mesh.pieces();
        let free = match self.axisymmetric {
            // A body of revolution moves rigidly along its axis only.
            true => {
                let mut held = vec![false; pieces.cells.len()];
                fixed.iter().filter(|(_, d)| d[1] != 0.0).for_each(|(a, _)| {
                    held[pieces.of_node[*a]] = true;
                });
                let along = vec!["translate along y (the axis)".to_string()];
                (0..held.len())
                    .filter(|&p| !held[p] && pieces.cells[p] > 0)
                    .map(|p| (p, along.clone()))
                    .collect()
            }
            false => free_rigid_motions(&self.mesh, &pieces, &fixed)?,
        };
        let Some((piece, motions)) = free.first() else { return Ok(()) };
        let body = match pieces.cells.iter().filter(|c| **c > 0).count() {
            1 => "the body".to_string(),
            _ => {
                format!("piece {} of the body (bounding box {:?})", piece + 1, pieces.boxes[*piece])
            }
        };
        Err(Error::Input(format!(
            "{body} can {}: its clamps and supports (boundary.clamped, [[boundary.support]]) do not hold it, and the system is singular; fix more components (a roller on another face, or a clamp)",
            motions_sentence(motions)
        )))
    }

    /// Nodes of the facets of the given parts, sorted and without repetition.
    pub fn part_nodes(&self, parts: &[usize]) -> Vec<usize> {
        self.mesh.part_nodes(parts)
    }
}

/// The diagonal of the mesh's bounding box (1 for a point).
fn mesh_size(mesh: &Mesh) -> f64 {
    let (lo, hi) = mesh.bounding_box();
    let size = lo.iter().zip(&hi).map(|(a, b)| (b - a).powi(2)).sum::<f64>().sqrt();
    if size > 0.0 { size } else { 1.0 }
}
