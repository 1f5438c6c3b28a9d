//! Replays the committed fuzz seeds and the inputs the fuzzers found (`fuzz/seeds/`) through
//! the same entry points as the fuzz targets: each must end in a value or an error, never a
//! panic. `fuzz/README.md` says how to run the fuzzers longer.

use std::path::PathBuf;

fn seeds(target: &str) -> Vec<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../fuzz/seeds").join(target);
    let mut files: Vec<PathBuf> =
        std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().path()).collect();
    files.sort();
    assert!(files.len() >= 10, "{}: too few seeds", dir.display());
    files
}

#[test]
fn case_reader_corpus() {
    let mut built = Vec::new();
    for path in seeds("case_toml") {
        let bytes = std::fs::read(&path).unwrap();
        let Ok(text) = std::str::from_utf8(&bytes) else { continue };
        let (toml, overrides) = text.split_once("\n---\n").unwrap_or((text, ""));
        let overrides: Vec<String> = overrides.lines().map(str::to_string).collect();
        let result = std::panic::catch_unwind(|| piezocontact_cli::fuzzing::case(toml, &overrides));
        assert!(result.is_ok(), "{} panics", path.display());
        if let Ok(Some(dim)) = result {
            built.push((path.file_name().unwrap().to_string_lossy().into_owned(), dim));
        }
    }
    // The valid seeds build their problems, 3D meshes from files among them; the invalid
    // ones do not.
    for (name, dim) in [
        ("indentation-3d.toml", 3),
        ("cube-pv1.toml", 3),
        ("paper-7.1.toml", 2),
        ("foundation-cone.toml", 3),
        ("foundation-punch.toml", 3),
        ("foundation-surface-stl.toml", 3),
        ("loading-path.toml", 3),
        ("materials-two-layers.toml", 3),
        ("materials-strain-charge.toml", 3),
        ("materials-preset-units.toml", 3),
    ] {
        assert!(built.contains(&(name.to_string(), dim)), "{name} was not built: {built:?}");
    }
    for name in [
        "two-bodies.toml",
        "mesh-path-traversal.toml",
        "phi0-1e308.toml",
        "max-condensed-zero.toml",
        "foundation-surface-path.toml",
        "foundation-cone-half-angle-90.toml",
        "loading-zero-steps.toml",
        "friction-incremental-uzawa.toml",
    ] {
        assert!(!built.iter().any(|(n, _)| n == name), "{name} was built");
    }
}

#[test]
fn gmsh_reader_corpus() {
    let mut errors = 0;
    for path in seeds("gmsh") {
        let bytes = std::fs::read(&path).unwrap();
        let result = std::panic::catch_unwind(|| {
            let info = piezocontact::mesh::gmsh::inspect(&bytes);
            let mesh = piezocontact::mesh::gmsh::read(&bytes);
            (info.is_ok(), mesh.map(|m| m.n_cells()))
        });
        match result {
            Ok((_, Err(e))) => {
                errors += 1;
                assert!(!e.to_string().is_empty());
            }
            Ok(_) => {}
            Err(_) => panic!("{} panics", path.display()),
        }
    }
    assert!(errors >= 8, "the malformed seeds must be refused ({errors} errors)");
}
