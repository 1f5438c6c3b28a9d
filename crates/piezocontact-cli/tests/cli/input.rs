//! Bad input and failure, round 2: a reader that stops reading, meshes that cannot be used,
//! numbers out of double precision's range, loose pieces of the body, progress and --quiet.
//! Each asserts the message and the exit code.

use super::common::{command, piezocontact, root, temp_dir, text};
use std::io::Read;
use std::process::Stdio;

/// Runs `args` with stdout a pipe whose reading end is closed before the command starts (so
/// its first line meets a broken pipe); returns the exit code and stderr.
fn with_closed_stdout(args: &[&str]) -> (Option<i32>, String) {
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let mut child = command().args(args).stdout(writer).stderr(Stdio::piped()).spawn().unwrap();
    let mut stderr = String::new();
    child.stderr.take().unwrap().read_to_string(&mut stderr).unwrap();
    (child.wait().unwrap().code(), stderr)
}

#[test]
fn a_reader_that_stops_reading_ends_the_output_quietly() {
    for args in [
        vec!["mesh-info", "meshes/cube.msh"],
        vec!["check", "cases/paper-7.1.toml"],
        vec!["check", "cases/indentation-3d.toml"],
    ] {
        let (code, stderr) = with_closed_stdout(&args);
        assert_eq!(code, Some(0), "{args:?}: {stderr}");
        assert!(stderr.is_empty(), "{args:?} wrote to stderr: {stderr}");
    }
    // The exit code is the command's own: an unusable mesh still exits 1.
    let dir = temp_dir("closed-pipe");
    let bad = dir.join("bad.msh");
    std::fs::write(&bad, "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n").unwrap();
    let (code, stderr) = with_closed_stdout(&["mesh-info", bad.to_str().unwrap()]);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("cannot be used as a mesh") && !stderr.contains("panicked"));
}

#[test]
fn mesh_info_exits_1_when_the_mesh_cannot_be_used() {
    let dir = temp_dir("mesh-info");
    let bad = dir.join("no-elements.msh");
    std::fs::write(&bad, "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n").unwrap();
    let o = piezocontact(&["mesh-info", bad.to_str().unwrap()]);
    let t = text(&o);
    assert_eq!(o.status.code(), Some(1), "{t}");
    assert!(t.contains("usable: no") && t.contains("cannot be used as a mesh"), "{t}");
    let o = piezocontact(&["mesh-info", "meshes/cube.msh"]);
    assert!(o.status.success() && text(&o).contains("usable: yes (3D"), "{}", text(&o));
}

/// ϕ0 = 1e308 (finite, but its products overflow) and a tiny Young's modulus are refused
/// before any work, naming the key, its line and the bound.
#[test]
fn numbers_beyond_double_precision_s_range_are_refused_with_the_bound() {
    for (set, key) in [
        ("conductivity.phi0=1e308", "conductivity.phi0 = 1e308"),
        ("material.young=1e-40", "material.young = 1e-40"),
        ("foundation.center=[6.0, -1e31]", "foundation.center = -1e31"),
    ] {
        let mut args = vec!["check", "cases/paper-7.2.toml", "--set", set];
        if set.starts_with("foundation") {
            args.extend(["--set", "foundation.kind=\"sphere\"", "--set", "foundation.radius=1.0"]);
        }
        let o = piezocontact(&args);
        let t = text(&o);
        assert_eq!(o.status.code(), Some(1), "{t}");
        assert!(t.contains(key) && t.contains("is out of range") && t.contains("1e30"), "{t}");
        assert!(!t.contains("NaN") && !t.contains("solver.r"), "{t}");
    }
    let o = piezocontact(&["check", "cases/paper-7.2.toml", "--set", "conductivity.phi0=1e308"]);
    assert!(text(&o).contains("cases/paper-7.2.toml:"), "no line: {}", text(&o));
}

/// A case on meshes/two-bodies.msh: a rectangle clamped and grounded on its left side, and
/// a loose square [5,6]×[0,1].
fn two_bodies_case(dir: &std::path::Path) -> std::path::PathBuf {
    let case = dir.join("two-bodies.toml");
    let mesh = root().join("meshes/two-bodies.msh");
    let text = format!(
        r#"[mesh]
file = {mesh:?}
[material]
young = 100.0
poisson = 0.25
e31 = -5.4
e33 = 15.8
e15 = 12.3
eps0 = 8.885e-3
beta11_rel = 916.0
beta33_rel = 830.0
[boundary]
clamped = ["left"]
grounded = ["left"]
"#
    );
    std::fs::write(&case, text).unwrap();
    case
}

#[test]
fn a_piece_of_the_body_that_is_not_held_is_named_before_any_work() {
    let dir = temp_dir("two-bodies");
    let case = two_bodies_case(&dir);
    let out = dir.join("out");
    for args in [
        vec!["check", case.to_str().unwrap()],
        vec!["run", case.to_str().unwrap(), "--out", out.to_str().unwrap()],
    ] {
        let o = piezocontact(&args);
        let t = text(&o);
        assert_eq!(o.status.code(), Some(1), "{t}");
        assert!(
            t.contains("2 connected pieces")
                && t.contains("touch no Γ1 (clamped) part")
                && t.contains("bounding box [5.0, 0.0]–[6.0, 1.0]")
                && t.contains("boundary.clamped"),
            "{t}"
        );
        let elements = t.split("piece 2 (").nth(1).and_then(|r| r.split(' ').next());
        assert!(elements.is_some_and(|n| n.parse::<usize>().is_ok_and(|n| n > 0)), "{t}");
    }
    assert!(!out.join("summary.json").exists());
}

/// Progress: plain lines on stderr when stdout is not a terminal (here every event, with
/// --progress-interval 0), none with --quiet, which also drops the report.
#[test]
fn progress_shows_on_long_runs_and_quiet_silences_it() {
    let dir = temp_dir("progress");
    let out = dir.join("out");
    let base = ["run", "cases/paper-7.2.toml", "--out", out.to_str().unwrap()];
    let coarse = ["--set", "mesh.nx=24", "--set", "mesh.ny=4"];
    let mut args: Vec<&str> = base.iter().chain(&coarse).copied().collect();
    args.extend(["--progress-interval", "0"]);
    let o = piezocontact(&args);
    assert!(o.status.success(), "{}", text(&o));
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(stderr.contains("progress: outer step 1 (of at most"), "{stderr}");
    assert!(stderr.contains("progress: outer step 1: factorising B̌ ("), "{stderr}");
    assert!(stderr.contains("Uzawa iteration 1: criterion"), "{stderr}");
    assert!(stderr.contains("(stops below 1.0e-4)"), "{stderr}");
    let mut quiet: Vec<&str> = base.iter().chain(&coarse).copied().collect();
    quiet.extend(["--progress-interval", "0", "--quiet"]);
    let o = piezocontact(&quiet);
    assert!(o.status.success(), "{}", text(&o));
    assert!(o.stdout.is_empty() && o.stderr.is_empty(), "{}", text(&o));
    assert!(out.join("summary.json").exists());
    // The exact solver's steps.
    let mut newton: Vec<&str> = base.iter().chain(&coarse).copied().collect();
    newton.extend(["--set", "solver.method=\"newton\"", "--progress-interval", "0"]);
    let o = piezocontact(&newton);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success() && stderr.contains("Newton step 1: criterion"), "{stderr}");
    // A 3D factorisation sends no event while it runs: a line every interval says how long.
    let out3 = dir.join("out3");
    let long = ["run", "cases/indentation-3d.toml", "--progress-interval", "0.05", "--out"];
    let o = piezocontact(&[&long[..], &[out3.to_str().unwrap()]].concat());
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    let ticks = stderr.lines().filter(|l| l.contains("factorising B̌") && l.ends_with(" s so far"));
    assert!(ticks.count() >= 1, "no line while the factorisation ran: {stderr}");
}

/// The newer keys — [foundation], solver.method, solver.tol, solver.max_condensed,
/// solver.ordering — are
/// checked by `check` as by `run`, with file:line:key and the fix.
#[test]
fn check_validates_the_foundation_and_the_exact_solver_s_keys() {
    for (set, pieces) in [
        (
            "foundation.radius=-1.0",
            vec!["indentation-3d.toml:", "foundation.radius = -1", "a length > 0"],
        ),
        (
            "foundation.normal=[0.0, 0.0, 1.0]",
            vec!["foundation.normal does not belong to kind = \"sphere\""],
        ),
        ("foundation.center=[0.0, 1.0]", vec!["foundation.center", "3 finite components"]),
        ("solver.tol=-1", vec!["indentation-3d.toml:", "solver.tol = -1", "a tolerance > 0"]),
        ("solver.max_condensed=0", vec!["solver.max_condensed = 0", "at least 1"]),
        ("solver.method=\"simplex\"", vec!["unknown variant `simplex`", "newton", "uzawa"]),
        ("solver.ordering=\"metis\"", vec!["unknown variant `metis`", "auto", "nd", "amd"]),
    ] {
        let o = piezocontact(&["check", "cases/indentation-3d.toml", "--set", set]);
        let t = text(&o);
        assert_eq!(o.status.code(), Some(1), "{set}: {t}");
        assert!(pieces.iter().all(|p| t.contains(p)), "{set}: {t}");
    }
    let o = piezocontact(&["check", "cases/indentation-3d.toml"]);
    assert!(o.status.success() && text(&o).contains("foundation: Sphere"), "{}", text(&o));
}

/// A build without the PETSc backend refuses it where it is asked for, with the command that
/// builds it: the case key (before any work), bench's --backend and --petsc-options.
#[cfg(not(feature = "petsc"))]
#[test]
fn the_petsc_backend_is_refused_by_a_build_without_it() {
    let backend = "solver.backend=\"petsc\"";
    let out = temp_dir("petsc-refused");
    let out = out.join("run");
    for args in [
        vec!["check", "cases/paper-7.2.toml", "--set", backend],
        vec!["run", "cases/paper-7.2.toml", "--set", backend, "--out", out.to_str().unwrap()],
        vec!["bench", "--mesh", "meshes/cube.msh", "--backend", "petsc"],
        vec!["check", "cases/paper-7.2.toml", "--petsc-options", "-mat_mumps_icntl_14 60"],
    ] {
        let output = piezocontact(&args);
        let stderr = text(&output);
        assert_eq!(output.status.code(), Some(1), "{args:?}: {stderr}");
        assert!(stderr.contains("--features petsc"), "{args:?}: {stderr}");
        if args.contains(&backend) {
            assert!(stderr.contains("solver.backend"), "{args:?}: {stderr}");
        }
    }
}

/// solver.linear = "iterative" runs on PETSc: refused elsewhere, before any work, naming the
/// key and what to set instead (in any build).
#[test]
fn the_iterative_route_is_refused_where_it_cannot_run() {
    let iterative = ["--set", "solver.linear=\"iterative\""];
    let check = ["check", "cases/paper-7.2.toml"];
    let cases: [(Vec<&str>, &str); 2] = [
        ([&check[..], &iterative].concat(), "set solver.backend = \"petsc\" too"),
        ([&check[..], &["--set", "solver.linear=\"krylov\""]].concat(), "iterative"),
    ];
    for (args, expected) in cases {
        let output = piezocontact(&args);
        let stderr = text(&output);
        assert_eq!(output.status.code(), Some(1), "{args:?}: {stderr}");
        assert!(
            stderr.contains("solver.linear") && stderr.contains(expected),
            "{args:?}: {stderr}"
        );
    }
    // bench's routes are the PETSc backend's.
    let output = piezocontact(&["bench", "--mesh", "meshes/cube.msh", "--linear", "iterative"]);
    assert_eq!(output.status.code(), Some(1), "{}", text(&output));
    assert!(text(&output).contains("--linear goes with --backend petsc"), "{}", text(&output));
}

/// solver.ordering is faer's: with the PETSc backend the case is warned that MUMPS orders
/// the matrix itself.
#[test]
fn an_ordering_with_the_petsc_backend_is_reported_unused() {
    let file = root().join("cases/paper-7.2.toml");
    let sets = ["solver.backend=\"petsc\"".to_string(), "solver.ordering=\"nd\"".to_string()];
    let case = piezocontact::case::Case::load(&file, &sets).unwrap();
    let warnings = case.setting_warnings();
    assert!(warnings.iter().any(|w| w.contains("solver.ordering") && w.contains("MUMPS")));
    let faer = piezocontact::case::Case::load(&file, &sets[1..]).unwrap();
    assert!(faer.setting_warnings().iter().all(|w| !w.contains("solver.ordering")));
}

/// `run` says on stderr, also when quiet, which keys of the case nothing reads (here µ under
/// PV1, which is frictionless) — before, they were in summary.json alone — and the run goes
/// on; `check` prints them too.
#[test]
fn run_and_check_warn_of_keys_nothing_reads() {
    let dir = temp_dir("unused-keys");
    let sets = ["--set", "mesh.nx=24", "--set", "mesh.ny=4", "--set", "contact.problem=\"PV1\""];
    let case = ["cases/paper-7.2.toml"];
    let out = ["--out", dir.to_str().unwrap()];
    let o = piezocontact(&[&["-q", "run"][..], &case, &sets, &out].concat());
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    let line = "warning: cases/paper-7.2.toml:70: friction is not used: contact.problem = \"PV1\"";
    assert!(stderr.contains(line) && stderr.contains("conductivity.ke is not used"), "{stderr}");
    assert!(o.stdout.is_empty());
    let o = piezocontact(&[&["check"][..], &case, &sets].concat());
    assert!(String::from_utf8_lossy(&o.stdout).contains(line), "{}", text(&o));
}

/// `run` of a case without `[contact]` warns of its case as a contact run does (here a
/// segment's end between two nodes; before, only `check` said it).
#[test]
fn a_run_without_contact_warns_of_its_segments() {
    let dir = temp_dir("static-warnings");
    let case = dir.join("case.toml");
    let material = "[material]\nyoung = 100.0\npoisson = 0.25\ne31 = -5.4\ne33 = 15.8\n\
                    e15 = 12.3\neps0 = 8.885e-3\nbeta11_rel = 916.0\nbeta33_rel = 830.0\n";
    let text = format!(
        "[mesh]\nx = [0.0, 4.0]\ny = [0.0, 1.0]\nnx = 8\nny = 2\n[mesh.segments]\n\
         left = [\"{{0}}x[0,1]\"]\ntop = [\"[0,1.1]x{{1}}\"]\n{material}[boundary]\n\
         clamped = [\"left\"]\ngrounded = [\"left\"]\n[[boundary.traction]]\nparts = [\"top\"]\n\
         f2 = [0.0, -1.0]\n"
    );
    std::fs::write(&case, text).unwrap();
    let out = dir.join("out");
    let o = piezocontact(&["-q", "run", case.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    let warning = "mesh.segments.top: '[0,1.1]x{1}' ends between two nodes at x = 1.1";
    assert!(stderr.contains(warning), "{stderr}");
}
