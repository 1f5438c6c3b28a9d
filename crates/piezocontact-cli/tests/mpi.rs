//! `piezocontact run` under `mpirun` with the PETSc backend: the same files as the serial
//! run on faer, to 1e−9; one process that fails ends them all with one message.
//! Run with `cargo test --workspace --features piezocontact-cli/petsc --test mpi` (Open
//! MPI's mpirun on PATH).

use piezocontact::linalg::{max_distance, max_norm};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::Mutex;
use std::time::{Duration, Instant};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn out_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("piezocontact-mpi-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// `mpirun -n N piezocontact ARGS` from the repository's root (N = 0: without mpirun).
fn run(n: usize, args: &[&str]) -> Output {
    let exe = env!("CARGO_BIN_EXE_piezocontact");
    if n == 0 {
        return Command::new(exe).current_dir(root()).args(args).output().unwrap();
    }
    mpirun(&[&["-n", &n.to_string(), exe][..], args].concat())
}

/// `mpirun ARGS` from the repository's root, one MPI job at a time: Open MPI's jobs on one
/// machine share its session directory, and jobs started together can fail to make theirs
/// (Open MPI's issue 8510); this file's tests run on parallel threads.
fn mpirun(args: &[&str]) -> Output {
    static ONE_JOB: Mutex<()> = Mutex::new(());
    let _job = ONE_JOB.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    Command::new("mpirun")
        .args(["--allow-run-as-root", "--oversubscribe", "--timeout", "300"])
        .args(args)
        .current_dir(root())
        .output()
        .expect("mpirun (Open MPI) on PATH")
}

/// The numeric columns of a contact.csv.
fn columns(file: &Path) -> Vec<Vec<f64>> {
    let text = std::fs::read_to_string(file).unwrap();
    let mut lines = text.lines();
    let width = lines.next().unwrap().split(',').count();
    let mut columns = vec![Vec::new(); width];
    for line in lines {
        for (k, cell) in line.split(',').enumerate() {
            if let Ok(v) = cell.trim().parse::<f64>() {
                columns[k].push(v);
            }
        }
    }
    columns
}

/// Every column of `a` equals `b`'s within `tolerance` of the column's largest magnitude.
fn assert_same_csv(a: &Path, b: &Path, tolerance: f64) {
    let (a, b) = (columns(a), columns(b));
    assert_eq!(a.len(), b.len());
    for (k, (x, y)) in a.iter().zip(&b).enumerate() {
        assert_eq!(x.len(), y.len(), "column {k}");
        let worst = max_distance(x, y) / max_norm(y).max(f64::MIN_POSITIVE);
        assert!(worst <= tolerance, "column {k}: relative difference {worst:e}");
    }
}

fn summary(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap()
}

/// `run cases/paper-7.2.toml` on the iterative route (PETSc's GMRES with its field split)
/// into `out`, with the arguments `extra` before `--out`.
fn iterative_example_7_2<'a>(out: &'a Path, extra: &[&'a str]) -> Vec<&'a str> {
    let route = ["--set", "solver.backend=\"petsc\"", "--set", "solver.linear=\"iterative\""];
    let out = ["--out", out.to_str().unwrap()];
    [&["run", "cases/paper-7.2.toml"][..], &route, extra, &out].concat()
}

/// The case run serially on faer and under mpirun on PETSc with 1, 2, 3 processes.
fn same_as_serial(case: &str, sets: &[&str], name: &str, counts: &[usize]) {
    let serial = out_dir(&format!("{name}-faer"));
    let mut args = vec!["run", case, "-q"];
    sets.iter().for_each(|s| args.extend(["--set", s]));
    let faer = run(0, &[&args[..], &["--out", serial.to_str().unwrap()]].concat());
    assert!(faer.status.success(), "{}", String::from_utf8_lossy(&faer.stderr));
    for &n in counts {
        let out = out_dir(&format!("{name}-petsc-{n}"));
        let petsc =
            [&args[..], &["--set", "solver.backend=\"petsc\"", "--out", out.to_str().unwrap()]];
        let result = run(n, &petsc.concat());
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert!(result.status.success(), "mpirun -n {n}: {stderr}");
        assert_same_csv(&out.join("contact.csv"), &serial.join("contact.csv"), 1e-9);
        let (s, f) = (summary(&out), summary(&serial));
        assert_eq!(s["backend"]["processes"], n, "processes in summary.json");
        assert_eq!(s["backend"]["name"], "petsc");
        assert_eq!(s["converged"], true);
        if f["method"] == "newton" {
            let kkt = s["kkt_residual"]["max"].as_f64().unwrap();
            assert!(kkt <= 1e-10, "mpirun -n {n}: KKT residual {kkt:e}");
        }
        let files = std::fs::read_dir(&out).unwrap().count();
        assert_eq!(files, std::fs::read_dir(&serial).unwrap().count(), "the same files");
        let _ = std::fs::remove_dir_all(&out);
    }
    let _ = std::fs::remove_dir_all(&serial);
}

#[test]
fn example_7_2_under_mpirun_is_the_serial_run() {
    same_as_serial("cases/paper-7.2.toml", &["solver.method=\"newton\""], "7.2-newton", &[1, 2, 3]);
    same_as_serial("cases/paper-7.2.toml", &[], "7.2-uzawa", &[2]);
}

/// Under mpirun every process sees a terminal (Open MPI's pseudo-terminals) though mpirun's
/// output goes to a pipe here: progress comes as plain lines on stderr all the same, never
/// as a spinner's control sequences.
#[test]
fn progress_under_mpirun_is_plain_lines() {
    let out = out_dir("progress");
    let coarse = ["--set", "mesh.nx=24", "--set", "mesh.ny=4", "--progress-interval", "0"];
    let base = ["run", "cases/paper-7.2.toml", "--out", out.to_str().unwrap()];
    let result = run(2, &[&base[..], &coarse].concat());
    assert!(result.status.success(), "{}", String::from_utf8_lossy(&result.stderr));
    let [stdout, stderr] = [&result.stdout, &result.stderr].map(|s| String::from_utf8_lossy(s));
    assert!(stderr.contains("progress: outer step 1 (of at most"), "{stderr}");
    assert!(!stdout.contains('\u{1b}') && !stderr.contains('\u{1b}'), "{stdout:?}");
    let _ = std::fs::remove_dir_all(&out);
}

/// A loading path of the exact solver on MUMPS's Schur complement: the drive voltage on Γ3
/// (prescribed ϕ) changes from step to step, each step a new factorisation.
#[test]
fn the_actuator_path_under_mpirun_is_the_serial_run() {
    same_as_serial("cases/actuator-stop.toml", &[], "actuator", &[2]);
}

#[test]
fn indentation_3d_under_mpirun_is_the_serial_run() {
    same_as_serial("cases/indentation-3d.toml", &[], "indentation", &[2]);
}

#[test]
fn a_process_that_fails_ends_every_process_with_one_message() {
    // Process 1 reads a case that does not exist, process 0 a good one (Open MPI's
    // colon syntax gives each its own arguments).
    let exe = env!("CARGO_BIN_EXE_piezocontact");
    // The aborted run's staging directory, beside its output, is inside `dir`.
    let dir = out_dir("failing");
    let out = dir.join("run");
    let out = out.to_str().unwrap();
    let backend = "solver.backend=\"petsc\"";
    let start = Instant::now();
    let result = mpirun(
        &[
            &["-n", "1", exe, "run", "cases/paper-7.2.toml", "--set", backend, "--out", out][..],
            &[":", "-n", "1", exe, "run", "cases/missing.toml", "--set", backend, "--out", out],
        ]
        .concat(),
    );
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(!result.status.success());
    assert!(start.elapsed() < Duration::from_secs(100), "ended by mpirun's timeout: {stderr}");
    assert_eq!(stderr.matches("error: ").count(), 1, "one message: {stderr}");
    assert!(
        stderr.contains("cases/missing.toml") && stderr.contains("(process 1 of 2)"),
        "{stderr}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_mumps_error_ends_the_run_with_mumps_s_diagnosis() {
    // A memory cap of 1 MB (MUMPS's ICNTL(23)) that no factor fits in.
    let out = out_dir("mumps-error");
    let args = [
        "run",
        "cases/paper-7.2.toml",
        "--set",
        "solver.backend=\"petsc\"",
        "--petsc-options",
        "-mat_mumps_icntl_23 1",
        "--out",
        out.to_str().unwrap(),
    ];
    let result = run(2, &args);
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert_eq!(result.status.code(), Some(4), "{stderr}");
    assert_eq!(stderr.matches("INFOG(1) = -19").count(), 1, "one message: {stderr}");
    assert!(stderr.contains("-mat_mumps_icntl_23"), "{stderr}");
    assert_eq!(summary(&out)["converged"], false);
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn the_quarter_model_under_mpirun_is_the_serial_run() {
    same_as_serial("cases/indentation-quarter.toml", &[], "quarter", &[2]);
}

#[test]
fn the_axisymmetric_path_under_mpirun_is_the_serial_run() {
    same_as_serial("cases/indentation-axisym.toml", &[], "axisym", &[2]);
}

/// Uzawa's method on the iterative route (GMRES, field split, GAMG) under mpirun -n 1 and 2:
/// Example 7.2's Γ3 table as the serial run on faer's factor to 1e−7 of each column's
/// largest value (the Krylov tolerance carried through Uzawa's iterations), and summary.json's
/// `linear` naming the route with one Krylov count per linear solve.
#[test]
fn the_iterative_route_under_mpirun_is_the_serial_run() {
    let serial = out_dir("iterative-faer");
    let faer = run(0, &["run", "cases/paper-7.2.toml", "-q", "--out", serial.to_str().unwrap()]);
    assert!(faer.status.success(), "{}", String::from_utf8_lossy(&faer.stderr));
    let direct = &summary(&serial)["linear"];
    assert_eq!(direct["kind"], "direct");
    assert_eq!((&direct["krylov"], &direct["preconditioner"]), (&"none".into(), &"none".into()));
    assert_eq!(direct["krylov_iterations"], serde_json::json!([]));
    for n in [1, 2] {
        let out = out_dir(&format!("iterative-{n}"));
        let result = run(n, &iterative_example_7_2(&out, &["-q"]));
        assert!(result.status.success(), "-n {n}: {}", String::from_utf8_lossy(&result.stderr));
        assert_same_csv(&out.join("contact.csv"), &serial.join("contact.csv"), 1e-7);
        let s = summary(&out);
        let linear = &s["linear"];
        assert_eq!(linear["kind"], "iterative");
        assert_eq!(linear["krylov"], "gmres");
        assert_eq!(linear["preconditioner"], "fieldsplit (u: gamg, phi: gamg)");
        let counts = linear["krylov_iterations"].as_array().unwrap();
        assert_eq!(counts.len() as u64, s["timings_seconds"]["solve_count"].as_u64().unwrap());
        assert!(counts.iter().all(|k| k.as_u64().unwrap() > 0), "{counts:?}");
        let _ = std::fs::remove_dir_all(&out);
    }
    let _ = std::fs::remove_dir_all(&serial);
}

/// The exact solver on the iterative route (the semismooth Newton method on the whole
/// system, its steps solved by GMRES to a forcing tolerance) under mpirun -n 1 and -n 2: the
/// 3D indentation's Γ3 table (PV2, µ = 0.3) as the serial exact solver's on faer's factor to
/// 1e−8 of each column's largest value, KKT residual within solver.tol, one Krylov count per
/// linear solve.
#[test]
fn the_exact_solver_on_the_iterative_route_is_the_serial_exact_solver() {
    let mesh = "mesh.file=\"../meshes/indent-3d-h0.05.msh\"";
    let serial = out_dir("newton-faer");
    let args = ["run", "cases/indentation-3d.toml", "-q", "--set", mesh, "--out"];
    let faer = run(0, &[&args[..], &[serial.to_str().unwrap()]].concat());
    assert!(faer.status.success(), "{}", String::from_utf8_lossy(&faer.stderr));
    let iterative = ["--set", "solver.backend=\"petsc\"", "--set", "solver.linear=\"iterative\""];
    for processes in [1, 2] {
        let out = out_dir(&format!("newton-iterative-{processes}"));
        let result = run(processes, &[&args[..], &[out.to_str().unwrap()], &iterative].concat());
        assert!(
            result.status.success(),
            "-n {processes}: {}",
            String::from_utf8_lossy(&result.stderr)
        );
        assert_same_csv(&out.join("contact.csv"), &serial.join("contact.csv"), 1e-8);
        let s = summary(&out);
        assert!(s["kkt_residual"]["max"].as_f64().unwrap() <= 1e-10, "{}", s["kkt_residual"]);
        let counts = s["linear"]["krylov_iterations"].as_array().unwrap();
        assert_eq!(counts.len() as u64, s["timings_seconds"]["solve_count"].as_u64().unwrap());
        assert!(counts.len() > 3, "-n {processes}: the Newton steps' solves: {counts:?}");
        let _ = std::fs::remove_dir_all(&out);
    }
    let _ = std::fs::remove_dir_all(&serial);
}

/// The multigrid's setups (PETSc's `PCSetUp_GAMG` event, its count in `-log_view`'s table).
fn gamg_setups(stdout: &str) -> usize {
    let line = stdout.lines().find(|l| l.starts_with("PCSetUp_GAMG"));
    let count = line.and_then(|l| l.split_whitespace().nth(1)).and_then(|c| c.parse().ok());
    count.unwrap_or_else(|| panic!("no PCSetUp_GAMG count in -log_view's table: {stdout}"))
}

/// The Newton steps of the exact solver on the iterative route keep the preconditioner of an
/// earlier step while its iterations per decade of relative tolerance stay within the ratio
/// (`-piezocontact_pc_rebuild_ratio`, 2 by default) under mpirun -n 2: fewer setups of the
/// multigrid than with the ratio 0 (a setup at every step), the same Γ3 table to 1e−8 and a
/// KKT residual within solver.tol; a ratio that is not a number ≥ 0 is refused, naming the
/// option.
#[test]
fn newton_steps_keep_the_preconditioner_while_its_iterations_hold() {
    let mesh = "mesh.file=\"../meshes/indent-3d-h0.05.msh\"";
    let iterative = ["--set", "solver.backend=\"petsc\"", "--set", "solver.linear=\"iterative\""];
    let args =
        [&["run", "cases/indentation-3d.toml", "-q", "--set", mesh][..], &iterative].concat();
    let mut setups = Vec::new();
    for (name, options) in
        [("lagged", "-log_view"), ("every", "-log_view -piezocontact_pc_rebuild_ratio 0")]
    {
        let out = out_dir(&format!("lag-{name}"));
        let extra = ["--petsc-options", options, "--out", out.to_str().unwrap()];
        let result = run(2, &[&args[..], &extra].concat());
        let stdout = String::from_utf8_lossy(&result.stdout);
        assert!(result.status.success(), "{name}: {}", String::from_utf8_lossy(&result.stderr));
        let kkt = summary(&out)["kkt_residual"]["max"].as_f64().unwrap();
        assert!(kkt <= 1e-10, "{name}: KKT residual {kkt:e}");
        setups.push((gamg_setups(&stdout), out));
    }
    let [(lagged, kept), (every, set_up)] = <[_; 2]>::try_from(setups).unwrap();
    assert!(lagged < every, "GAMG's setups: {lagged} lagged against {every} at every step");
    assert_same_csv(&kept.join("contact.csv"), &set_up.join("contact.csv"), 1e-8);
    let out = out_dir("lag-bad");
    let option = "-piezocontact_pc_rebuild_ratio x";
    let extra = ["--petsc-options", option, "--out", out.to_str().unwrap()];
    let bad = run(1, &[&args[..], &extra].concat());
    let stderr = String::from_utf8_lossy(&bad.stderr);
    assert_eq!(bad.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains(&format!("{option}: give a number")), "{stderr}");
    [kept, set_up, out].iter().for_each(|dir| drop(std::fs::remove_dir_all(dir)));
}

/// `--petsc-options "-log_view -memory_view"` prints PETSc's performance summary at exit,
/// with the Krylov solver's and the multigrid's events, and its memory summary (the largest
/// resident set of the processes), though the options reach PETSc after it started; the run
/// ends normally on every process (before, -memory_view's report failed and left MPI
/// unfinalised).
#[test]
fn log_view_prints_petsc_s_performance_summary() {
    let out = out_dir("log-view");
    let options = ["-q", "--petsc-options", "-log_view -memory_view"];
    let result = run(2, &iterative_example_7_2(&out, &options));
    let stdout = String::from_utf8_lossy(&result.stdout);
    assert!(result.status.success(), "{}", String::from_utf8_lossy(&result.stderr));
    assert!(stdout.contains("PETSc Performance Summary"), "{stdout}");
    assert!(stdout.lines().any(|l| l.starts_with("KSPSolve ")), "{stdout}");
    assert!(stdout.lines().any(|l| l.starts_with("PCSetUp_GAMG")), "{stdout}");
    let memory = stdout.lines().find(|l| l.starts_with("Maximum (over computational time)"));
    assert!(memory.is_some_and(|l| l.contains("max")), "{stdout}");
    let _ = std::fs::remove_dir_all(&out);
}

/// A Krylov solve capped below what it needs ends the run with exit 4, the reason on stderr
/// and an unconverged summary.json that lists the iterations made (the last at the cap).
#[test]
fn a_krylov_solve_short_of_its_tolerance_ends_the_run_unconverged() {
    let out = out_dir("krylov-short");
    let result = run(2, &iterative_example_7_2(&out, &["--petsc-options", "-ksp_max_it 3"]));
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert_eq!(result.status.code(), Some(4), "{stderr}");
    assert_eq!(stderr.matches("stopped after 3 iterations").count(), 1, "one message: {stderr}");
    assert!(!stderr.contains("solver.r"), "no advice on Uzawa's r for the solver's failure");
    let s = summary(&out);
    assert_eq!(s["converged"], false);
    assert!(s["failure"].as_str().unwrap().contains("-ksp_max_it"), "{s}");
    assert_eq!(s["linear"]["krylov_iterations"], serde_json::json!([3]), "{s}");
    let _ = std::fs::remove_dir_all(&out);
}

/// `bench --contact --backend petsc --linear direct,iterative` under mpirun -n 1 on the 3D
/// indentation's coarse mesh: PV1 and PV2 by both routes, each converged, the iterative
/// route's answers the direct route's to 1e−8 with its GMRES iterations.
#[test]
fn the_contact_bench_times_the_exact_solver_on_both_routes() {
    let args = ["bench", "--contact", "--mesh", "meshes/indent-3d-h0.05.msh", "--backend"];
    let result = run(1, &[&args[..], &["petsc", "--linear", "direct,iterative"]].concat());
    let stdout = String::from_utf8_lossy(&result.stdout);
    assert!(result.status.success(), "{stdout}{}", String::from_utf8_lossy(&result.stderr));
    for problem in ["PV1", "PV2 mu=0.3"] {
        // The fields after the problem's words: route, DOFs, newton, solves, krylov_max (and
        // its mean on the iterative route), run_s, kkt, KB/DOF, du, dphi, the peaks.
        let words = problem.split_whitespace().count();
        let row = |route: &str| -> Vec<String> {
            let line = stdout.lines().find(|l| {
                let fields: Vec<&str> = l.split_whitespace().collect();
                fields.len() > words
                    && fields[..words].join(" ") == problem
                    && fields[words] == route
            });
            let line = line.unwrap_or_else(|| panic!("no {problem} {route} row: {stdout}"));
            line.split_whitespace().skip(words).map(String::from).collect()
        };
        let (direct, iterative) = (row("direct"), row("iterative"));
        assert!(!stdout.contains("NOT CONVERGED") && !stdout.contains("did not run"), "{stdout}");
        assert_eq!(direct[1], iterative[1], "{problem}: the same unknowns");
        let krylov: usize = iterative[4].parse().unwrap();
        assert!(krylov > 0, "{problem}: {iterative:?}");
        let (du, dphi): (f64, f64) =
            (iterative[9].parse().unwrap(), iterative[10].parse().unwrap());
        assert!(du < 1e-8 && dphi < 1e-8, "{problem}: {iterative:?}");
    }
}

/// `bench --backend petsc --linear direct,iterative` under mpirun -n 2 on the 3D indentation's
/// coarse mesh (its patch pressed down): a row per route and faer's, the iterative solve's
/// GMRES iterations; a mesh without the patch is refused on the iterative route.
#[test]
fn the_backend_bench_times_both_routes() {
    let args = ["bench", "--mesh", "meshes/indent-3d-h0.05.msh", "--backend", "petsc"];
    let result = run(2, &[&args[..], &["--linear", "direct,iterative"]].concat());
    let stdout = String::from_utf8_lossy(&result.stdout);
    assert!(result.status.success(), "{stdout}{}", String::from_utf8_lossy(&result.stderr));
    let row = |name: &str| -> Vec<String> {
        let line = stdout.lines().find(|l| l.trim_start().starts_with(name));
        line.unwrap_or_else(|| panic!("no {name} row: {stdout}"))
            .split_whitespace()
            .map(String::from)
            .collect()
    };
    let (direct, iterative) = (row("petsc direct"), row("petsc iterative"));
    assert_eq!(direct[2], "2", "processes");
    assert_eq!(direct[3], iterative[3], "the same unknowns");
    let krylov: usize = iterative[10].parse().unwrap();
    let most = piezocontact::linalg::petsc::KRYLOV_MAX_ITERATIONS;
    assert!((1..most).contains(&krylov), "{stdout}");
    assert_eq!(direct[10], "0", "no Krylov iteration on the direct route");
    assert_eq!(row("faer")[1], "1");
    assert!(stdout.contains("petsc iterative / petsc direct: all phases"), "{stdout}");
    let cube =
        ["bench", "--mesh", "meshes/cube.msh", "--backend", "petsc", "--linear", "iterative"];
    // The iterative route alone: no faer row.
    let alone = run(1, &[&args[..], &["--linear", "iterative"]].concat());
    let stdout = String::from_utf8_lossy(&alone.stdout);
    assert!(alone.status.success() && stdout.contains("petsc iterative"), "{stdout}");
    assert!(!stdout.lines().any(|l| l.trim_start().starts_with("faer")), "{stdout}");
    let refused = run(1, &cube);
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert!(!refused.status.success());
    assert!(stderr.contains("\"bottom\" and \"contact\""), "{stderr}");
}
