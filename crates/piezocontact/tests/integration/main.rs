//! Integration tests of the piezocontact library, one binary (fast linking on 2 cores).

/// Axisymmetric bodies: uniform states of a cylinder, totals over the revolution, bad input.
mod axisymmetric;
/// The linear-solver seam: a dense LU backend from outside the library.
mod backend;
/// Bimorphs: electrodes inside the body, against Smits's beam theory.
mod bimorph;
/// Shared builders: the PZT-5A material, meshes, exact fields.
mod common;
/// Algorithms 1–4: KKT conditions, balances, limits, counts.
mod contact;
/// Manufactured solutions: convergence rates of the coupled system.
mod convergence;
/// Electrodes at a voltage: uniform fields, charges, outputs, bad tables.
mod electrodes;
/// The exact solver against tight Uzawa, r independence, Hencky active, the Schur complement.
mod exact;
/// Foundation surfaces: planes, tilted planes, negative gaps.
mod foundation;
/// Gmsh import: round trip of physical names, errors.
mod gmsh_io;
/// Hertz contact in 2D and 3D through the foundation's sphere.
mod hertz;
/// Indentation experiments: electrode charges, loading paths, cones and punches.
mod indentation;
/// The code's own rules: function lengths, an outer loop that names no method.
mod layout;
/// Materials by full tensors: uniform states, the two forms, bad tables.
mod materials;
/// Orderings and threads of the factorisation: same solutions, smaller factors.
mod orderings;
/// Patch tests: linear fields reproduced to round-off, 2D and 3D.
mod patch;
/// The quarter model on symmetry planes against the whole block, node for node.
mod quarter;
/// Rollers on faces of any orientation: turned frames, uniform states, bad tables.
mod rollers;
/// Supports along the axes: uniform states on rollers, reactions, bad tables.
mod supports;
/// The assembled system: symmetry, definiteness of the blocks, factorisation reuse.
mod system;
