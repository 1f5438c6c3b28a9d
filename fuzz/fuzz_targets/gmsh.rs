//! Fuzzes the Gmsh reader (what `mesh-info` and case meshes use): any bytes must give a mesh
//! or an error, never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = piezocontact::mesh::gmsh::inspect(data);
    let _ = piezocontact::mesh::gmsh::read(data);
});
