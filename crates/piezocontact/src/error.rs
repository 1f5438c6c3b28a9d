//! The library's one error type. Every variant carries the data a user needs to find and fix
//! the problem (element, node, part name, parameter); the CLI adds the file name.

/// Result alias used throughout the library.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// Everything that can go wrong in piezocontact's numerics and input handling.
#[derive(Clone, Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// An element refers to a node that does not exist.
    #[error("element {element} refers to node {node}, but the mesh has only {n_nodes} nodes")]
    NodeOutOfRange { element: usize, node: usize, n_nodes: usize },

    /// A node coordinate is NaN or infinite.
    #[error("node {node} has a non-finite coordinate {coords:?}")]
    NonFiniteCoordinate { node: usize, coords: Vec<f64> },

    /// Elements of both orientations: some element is folded over its neighbours.
    #[error(
        "element {element} (nodes {nodes:?}) is inverted: its signed measure {measure:.3e} has \
         the opposite sign of the other elements; fix the mesh (reorder the element's nodes or \
         remesh the region)"
    )]
    InvertedElement { element: usize, nodes: Vec<usize>, measure: f64 },

    /// An element of (nearly) zero measure.
    #[error(
        "element {element} (nodes {nodes:?}) is degenerate: measure {measure:.3e} against \
         longest edge {edge:.3e}; remove it or remesh (collapsed nodes?)"
    )]
    DegenerateElement { element: usize, nodes: Vec<usize>, measure: f64, edge: f64 },

    /// Two elements with the same node set.
    #[error("element {element} duplicates element {first} (nodes {nodes:?}); remove one of them")]
    DuplicateElement { element: usize, first: usize, nodes: Vec<usize> },

    /// A node that no element uses: its unknowns would make the system singular.
    #[error(
        "node {node} at {coords:?} belongs to no element ({count} unused nodes in all); remove \
         unused nodes (in Gmsh: do not save geometry points outside the meshed region)"
    )]
    UnusedNode { node: usize, coords: Vec<f64>, count: usize },

    /// The mesh has no cells of the body's dimension.
    #[error("the mesh has no {dim}D cells ({what})")]
    NoCells { dim: usize, what: String },

    /// A facet of a boundary part is not a boundary facet of the body (or, of a part inside
    /// the body, no face of an element).
    #[error(
        "boundary part '{part}': facet with nodes {nodes:?} is not on the boundary of the body \
         (it is not a face of exactly one element); a group of facets is either wholly on the \
         boundary or wholly inside the body (faces of two elements, for an electrode)"
    )]
    FacetNotOnBoundary { part: String, nodes: Vec<usize> },

    /// A boundary part holds a facet twice.
    #[error(
        "boundary part '{part}' holds the facet with nodes {nodes:?} twice: it would count twice \
         in every integral over the part; remove the duplicate from the mesh"
    )]
    DuplicateFacet { part: String, nodes: Vec<usize> },

    /// A case names a boundary part that the mesh does not have.
    #[error(
        "'{name}' is not a boundary part of the mesh (its boundary parts are its groups of \
         facets on the boundary: physical curves in 2D, surfaces in 3D, or a rectangle's \
         segments); the mesh has: {available}{what}"
    )]
    UnknownBoundaryPart {
        name: String,
        available: String,
        /// What `name` is when the mesh file has it as a group of another dimension, as
        /// "; 'body' is a physical group of volumes …"; else empty.
        what: String,
    },

    /// A boundary role (Γ1, Γa, ...) has no facet although the model needs it.
    #[error("{role} is empty: {why}")]
    EmptyRole { role: &'static str, why: &'static str },

    /// Two roles that must be disjoint share a facet.
    #[error(
        "boundary parts '{first}' ({first_role}) and '{second}' ({second_role}) share the facet \
         with nodes {nodes:?}, but {first_role} and {second_role} must be disjoint"
    )]
    RoleConflict {
        first: String,
        first_role: &'static str,
        second: String,
        second_role: &'static str,
        nodes: Vec<usize>,
    },

    /// A parameter outside its physical range.
    #[error("{name} = {value} is not allowed: {requirement}")]
    InvalidParameter { name: String, value: String, requirement: String },

    /// A Gmsh file that cannot be read.
    #[error("cannot read the Gmsh file: {0}")]
    Gmsh(String),

    /// A Gmsh file that can be read but holds something piezocontact does not support.
    #[error("unsupported Gmsh content: {0}")]
    GmshUnsupported(String),

    /// A boundary segment specification that cannot be parsed.
    #[error("cannot read the boundary segment '{spec}': {why}")]
    Segment { spec: String, why: String },

    /// The factorisation met a zero, tiny or wrongly signed pivot: the system is singular or
    /// not quasi-definite.
    #[error(
        "the linear system is singular or not quasi-definite ({detail}); check that the body is \
         clamped (Γ1) and grounded (Γa) on parts of positive measure and that the material \
         constants are physical"
    )]
    SingularSystem { detail: String },

    /// A non-finite number appeared in a computed quantity.
    #[error("{what} is not finite (NaN or infinity)")]
    NonFinite { what: String },

    /// The linear algebra back-end failed for another reason (out of memory, ...).
    #[error("linear algebra failure: {0}")]
    LinearAlgebra(String),

    /// An iteration cap was hit before the stopping rule held.
    #[error(
        "{what} did not converge in {iterations} iteration{}: last criterion {criterion:.3e}, \
         tolerance {tolerance:e} (criterion history, last values: {history}); {hint}",
        if *.iterations == 1 { "" } else { "s" }
    )]
    NotConverged {
        what: String,
        iterations: usize,
        criterion: f64,
        tolerance: f64,
        history: String,
        hint: String,
    },

    /// The run was asked to stop ([`crate::interrupt`]) and stopped at a safe point.
    #[error("interrupted")]
    Interrupted {
        /// The signal that asked (2: SIGINT, 15: SIGTERM).
        signal: i32,
    },

    /// A loop's criterion grew instead of falling.
    #[error(
        "{what} diverged at iteration {iteration} (criterion history, last values: {history}); {hint}"
    )]
    Diverged { what: String, iteration: usize, history: String, hint: String },

    /// A factorisation or an iterate failed numerically (singular matrix, NaN, infinity).
    #[error("{what} failed at iteration {iteration}: {cause}; {hint}")]
    NumericalFailure { what: String, iteration: usize, cause: String, hint: String },

    /// A case file, an override or an output request that cannot be used: the message names
    /// the file, the line and the key where known, and the fix.
    #[error("{0}")]
    Input(String),

    /// An error placed in a case file: `location` is "file" or "file:line". (Its message
    /// holds the error's, so the error is not also a `source`: chains print it once.)
    #[error("{location}: {error}")]
    Located { location: String, error: Box<Error> },

    /// An output directory that holds files piezocontact did not write.
    #[error(
        "the output directory {dir} holds files that piezocontact did not write ({}); choose \
         another output directory, or allow writing into this one",
        shown(files)
    )]
    ForeignOutput { dir: String, files: Vec<String> },

    /// A file that cannot be read or written.
    #[error("{what}: {cause}")]
    Io { what: String, cause: String },

    /// A vector or field of the wrong length.
    #[error("{what}: expected length {expected}, got {got}")]
    Length { what: String, expected: usize, got: usize },
}

/// The first five names, then "…".
fn shown(names: &[String]) -> String {
    let mut text = names.iter().take(5).cloned().collect::<Vec<_>>().join(", ");
    if names.len() > 5 {
        text.push_str(", …");
    }
    text
}
