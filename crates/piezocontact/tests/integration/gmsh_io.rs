//! Gmsh MSH 4.1 import: physical names round-trip (ASCII and binary, 2D and 3D), and every
//! malformed or unsupported input is an error with a message, never a panic.

use super::common::mesh_file;
use piezocontact::mesh::gmsh;

#[test]
fn physical_group_names_round_trip() {
    for (file, binary, dim, names) in [
        ("paper-rectangle.msh", false, 2, vec!["clamp", "load", "contact"]),
        ("arch.msh", true, 2, vec!["clamp", "top", "contact"]),
        ("cube.msh", false, 3, vec!["bottom", "top", "sides"]),
    ] {
        let bytes = std::fs::read(mesh_file(file)).unwrap();
        let mesh = gmsh::read(&bytes).unwrap();
        assert_eq!(mesh.dim(), dim);
        let mut got: Vec<&str> = mesh.parts().iter().map(|p| p.name.as_str()).collect();
        let mut want = names.clone();
        got.sort_unstable();
        want.sort_unstable();
        assert_eq!(got, want, "{file}");
        let info = gmsh::inspect(&bytes).unwrap();
        assert_eq!(info.binary, binary);
        assert!(
            info.groups
                .iter()
                .any(|g| g.name == "body" && g.dim == dim as i32 && g.elements == mesh.n_cells())
        );
    }
    // Measures of the parts of the paper's rectangle.
    let mesh = gmsh::read(&std::fs::read(mesh_file("paper-rectangle.msh")).unwrap()).unwrap();
    let measure = |name: &str| mesh.part_measure(mesh.part_index(name).unwrap());
    assert!((measure("clamp") - 4.0).abs() < 1e-12);
    assert!((measure("load") - 16.0).abs() < 1e-12);
    assert!((measure("contact") - 8.0).abs() < 1e-12);
    // The arch's contact face is the circular arc of radius 4.25 over the angle 2 asin(2/4.25).
    let arch = gmsh::read(&std::fs::read(mesh_file("arch.msh")).unwrap()).unwrap();
    let arc = 4.25 * 2.0 * (2.0_f64 / 4.25).asin();
    let contact = arch.part_measure(arch.part_index("contact").unwrap());
    assert!((contact - arc).abs() < 2e-3 * arc, "{contact} vs {arc}");
}

fn data(name: &str) -> String {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    std::fs::read_to_string(dir.join(name)).unwrap()
}

fn error_of(bytes: &[u8]) -> String {
    match gmsh::read(bytes) {
        Ok(_) => panic!("accepted malformed input"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn malformed_and_unsupported_files_are_errors() {
    let good = std::fs::read_to_string(mesh_file("paper-rectangle.msh")).unwrap();
    let cases: Vec<(String, &str)> = vec![
        ("hello".into(), "no $MeshFormat section"),
        ("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n".into(), "MSH version 2.2"),
        ("$MeshFormat\n4.1 1 9\n$EndMeshFormat\n".into(), "data-size 4 or 8"),
        (good[..good.len() / 2].to_string(), "cannot read the Gmsh file"),
        (good.replacen("$Elements", "$Elementz", 1), "cannot read the Gmsh file"),
        (good.replace("1 3 \"contact\"", "1 x \"contact\""), "malformed $PhysicalNames line '1 x"),
        (good.replacen("\n2 1 2 250\n", "\n2 1 2 251\n", 1), "cannot read the Gmsh file"),
        (data("quads.msh"), "Qua4 elements of dimension 2"),
        (data("msh22.msh"), "MSH version 2.2"),
        (data("no-volume.msh"), "add a Physical Volume for the body"),
    ];
    for (text, needle) in cases {
        let e = error_of(text.as_bytes());
        assert!(e.contains(needle), "expected '{needle}' in: {e}");
    }
    // An element naming a node that does not exist; a 2D mesh off the plane z = 0.
    let missing_node =
        good.replace("306 98 139 154 \n$EndElements", "306 98 139 99999 \n$EndElements");
    let e = error_of(missing_node.as_bytes());
    assert!(e.contains("node tag 99999"), "{e}");
    let lines: Vec<&str> = good.lines().collect();
    let nodes_start = lines.iter().position(|l| *l == "$Nodes").unwrap();
    let first_coordinates =
        (nodes_start..lines.len()).find(|&i| lines[i].trim() == "0 0 0").unwrap();
    let mut lifted = lines.clone();
    lifted[first_coordinates] = "0 0 0.5";
    let e = error_of(lifted.join("\n").as_bytes());
    assert!(e.contains("must lie in the plane z = 0"), "{e}");
    let e = error_of(&[0xff, 0x00, 0x13]);
    assert!(e.contains("no $MeshFormat"), "{e}");
    // Only curves (no surface): no cells.
    let curves_only = std::fs::read_to_string(mesh_file("paper-rectangle.msh")).unwrap();
    let start = curves_only.find("$Elements").unwrap();
    let truncated =
        format!("{}$Elements\n1 1 1 1\n1 1 1 1\n1 1 2\n$EndElements\n", &curves_only[..start]);
    let e = error_of(truncated.as_bytes());
    assert!(e.contains("highest element dimension is 1"), "{e}");
}
