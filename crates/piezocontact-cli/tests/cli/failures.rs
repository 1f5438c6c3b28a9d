//! Failure handling end to end: numerical failures write the last finite iterate marked
//! unconverged and exit with their documented code; output directories are never clobbered;
//! a killed run leaves only complete files.

use super::common::{
    TempDir, command, null_paths, piezocontact, root, run_coarse, sweep_coarse, temp_dir, text,
};
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::Duration;

/// The exact solver's cap on Newton steps exits 3 with the last iterate written, marked
/// unconverged; without the cap the same case converges to the KKT tolerance.
#[test]
fn a_newton_cap_exits_3_with_the_last_iterate_written() {
    let out = TempDir::unmade("newton-cap");
    let newton = "solver.method=\"newton\"";
    let o = run_coarse("cases/paper-7.2.toml", &out, &[newton, "solver.max_inner=1"]);
    let t = text(&o);
    assert_eq!(o.status.code(), Some(3), "{t}");
    assert!(
        t.contains("the semismooth Newton method of outer step 1 did not converge in 1"),
        "{t}"
    );
    assert!(t.contains("raise solver.max_inner (now 1)") && t.contains("Newton steps"), "{t}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(
        (summary["converged"].clone(), summary["method"].clone()),
        (false.into(), "newton".into())
    );
    assert_eq!(null_paths(&summary), Vec::<String>::new());
    let o = run_coarse("cases/paper-7.2.toml", &out, &[newton]);
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    assert!(summary["kkt_residual"]["max"].as_f64().unwrap() <= 1e-10, "{summary}");
    assert_eq!(summary["timings_seconds"]["numeric_count"], 1);
}

#[test]
fn a_diverging_fixed_point_exits_4_and_writes_its_last_finite_iterate() {
    let out = TempDir::unmade("diverge");
    let o = run_coarse(
        "cases/paper-7.2.toml",
        &out,
        &["conductivity.ke=1e4", "contact.penetration=0.05"],
    );
    let t = text(&o);
    assert_eq!(o.status.code(), Some(4), "{t}");
    assert!(t.contains("the fixed-point loop (Algorithm 1) diverged at iteration"), "{t}");
    assert!(
        t.contains("criterion history, last values:") && t.contains("reduce conductivity.ke"),
        "{t}"
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["converged"], false);
    assert!(summary["failure"].as_str().unwrap().contains("diverged"));
    assert_eq!(null_paths(&summary), Vec::<String>::new());
    let finite = super::common::finite_vtu(&out.join("solution.vtu"));
    assert!(finite, "solution.vtu holds a non-finite number");
}

#[test]
fn output_directories_are_never_clobbered() {
    let out = temp_dir("clobber");
    std::fs::write(out.join("notes.txt"), "mine").unwrap();
    let case_args = |case: &str, extra: &[&str]| {
        let mut a = vec![
            "run",
            case,
            "--out",
            out.to_str().unwrap(),
            "--set",
            "mesh.nx=12",
            "--set",
            "mesh.ny=2",
        ];
        a.extend_from_slice(extra);
        a.into_iter().map(String::from).collect::<Vec<_>>()
    };
    let args = |extra: &[&str]| case_args("cases/paper-7.1.toml", extra);
    let run = |a: Vec<String>| {
        let output = command().args(&a).output().unwrap();
        super::common::assert_strict_outputs(&out);
        output
    };
    let o = run(args(&[]));
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    assert!(
        text(&o).contains("holds files that piezocontact did not write (notes.txt)")
            && text(&o).contains("--force")
    );
    assert!(!out.join("summary.json").exists());
    // --force writes beside the foreign file and keeps it.
    let o = run(args(&["--force"]));
    assert!(o.status.success(), "{}", text(&o));
    assert_eq!(std::fs::read_to_string(out.join("notes.txt")).unwrap(), "mine");
    assert!(out.join("contact.csv").exists());
    // Rerunning into our own output replaces it whole: a run without contact writes no
    // contact.csv, and the earlier one is gone.
    std::fs::remove_file(out.join("notes.txt")).unwrap();
    let o = run(args(&["--set", "contact.problem=PV1"]));
    assert!(o.status.success(), "{}", text(&o));
    let case = std::fs::read_to_string(root().join("cases/paper-7.1.toml")).unwrap();
    let cases = temp_dir("clobber-case");
    let without_contact = cases.join("case.toml");
    let stripped: String = case.split("\n[contact]").next().unwrap().to_string();
    std::fs::write(&without_contact, stripped).unwrap();
    let o = run(case_args(without_contact.to_str().unwrap(), &[]));
    assert!(o.status.success(), "{}", text(&o));
    assert!(!out.join("contact.csv").exists(), "the earlier contact.csv was not removed");
    assert!(out.join("summary.json").exists() && out.join("solution.vtu").exists());
}

/// Whether a file is complete: PNG with IEND, SVG and VTU closed, JSON parsed, text ending
/// in a newline; marker and temporary names are reported as such.
fn assert_complete(path: &Path) {
    let name = path.file_name().unwrap().to_string_lossy().to_string();
    assert!(
        !name.starts_with('.') || name == ".piezocontact-output",
        "temporary file {name} left behind"
    );
    let bytes = std::fs::read(path).unwrap();
    match path.extension().and_then(|e| e.to_str()) {
        Some("png") => assert!(
            bytes.starts_with(b"\x89PNG") && bytes.ends_with(&[0xae, 0x42, 0x60, 0x82]),
            "{name} is cut"
        ),
        Some("svg") => {
            assert!(String::from_utf8_lossy(&bytes).trim_end().ends_with("</svg>"), "{name} is cut")
        }
        Some("vtu") => assert!(
            String::from_utf8_lossy(&bytes).trim_end().ends_with("</VTKFile>"),
            "{name} is cut"
        ),
        Some("json") => {
            assert!(serde_json::from_slice::<serde_json::Value>(&bytes).is_ok(), "{name} is cut")
        }
        Some("csv") | Some("md") => {
            assert!(bytes.is_empty() || bytes.ends_with(b"\n"), "{name} is cut")
        }
        _ => {}
    }
}

fn assert_all_complete(dir: &Path) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() { assert_all_complete(&path) } else { assert_complete(&path) }
    }
}

#[test]
fn a_killed_run_leaves_only_complete_files() {
    let mut killed_while_running = 0;
    for (k, delay) in [150u64, 600, 1500].into_iter().enumerate() {
        // The killed run's staging directory, beside its output, is inside the test's.
        let parent = TempDir::unmade(&format!("kill{k}"));
        let out = parent.join("run");
        let mut child = command()
            .args(["reproduce", "--out", out.to_str().unwrap(), "--mesh", "96,16", "--jobs", "2"])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(Duration::from_millis(delay));
        if child.try_wait().unwrap().is_none() {
            killed_while_running += 1;
        }
        let _ = child.kill();
        let _ = child.wait();
        if out.exists() {
            assert_all_complete(&out);
            super::common::assert_strict_outputs(&out);
        }
    }
    assert!(killed_while_running >= 2, "the runs ended before they could be killed");
}

/// A factor that does not fit in the memory (capped here by PIEZOCONTACT_MEMORY_LIMIT) is
/// refused after the symbolic analysis, before any numeric work: exit 1, both sizes and the
/// ways out in the message, summary.json written with the failure and nothing else.
#[test]
fn a_factor_too_large_for_the_memory_is_refused_before_it_is_computed() {
    let out = TempDir::unmade("memory");
    let o = command()
        .env("PIEZOCONTACT_MEMORY_LIMIT", "3000000")
        .args(["run", "cases/indentation-3d.toml", "--out", out.to_str().unwrap()])
        .args(["--set", "mesh.file=\"../meshes/indent-3d-h0.05.msh\""])
        .args(["--set", "solver.method=\"uzawa\""]) // no dense condensation to refuse first
        .output()
        .unwrap();
    let t = text(&o);
    assert_eq!(o.status.code(), Some(1), "{t}");
    assert!(
        t.contains("the sparse LDLᵀ factor of")
            && t.contains("would need about")
            && t.contains("more than the 2.9 MiB available")
            && t.contains("use a coarser mesh"),
        "{t}"
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["converged"], false);
    assert!(summary["failure"].as_str().unwrap().contains("would need about"), "{summary}");
    assert_eq!(summary["dim"], 3);
    assert!(!out.join("solution.vtu").exists() && !out.join("contact.csv").exists());
}

/// `check` predicts the exact solver's dense matrices beside the factor, from the condensed
/// set a run starts with: Example 7.2 (PV2) on a 768 × 4 bar condenses both displacement
/// components of its 513 Γ3 nodes (the flat foundation reaches all), m = 1026, so 7 m × m
/// matrices of 8 bytes, and the 32 right-hand sides of a growth (n free unknowns each):
/// 8 (7 m² + 32 n) bytes. A memory limit above the factor but below those matrices is
/// refused by `check` as by `run`, with both numbers.
#[test]
fn check_predicts_the_exact_solver_s_dense_matrices_and_refuses_them_when_too_large() {
    let args = ["check", "cases/paper-7.2.toml", "--set", "solver.method=\"newton\""];
    let mesh = ["--set", "mesh.nx=768", "--set", "mesh.ny=4"];
    let fits = piezocontact(&[&args[..], &mesh[..]].concat());
    let t = text(&fits);
    assert!(fits.status.success(), "{t}");
    let free: f64 =
        t.split(" free (").next().and_then(|s| s.rsplit(' ').next()).unwrap().parse().unwrap();
    let dense = 8.0 * (7.0 * (2.0f64 * 513.0).powi(2) + 32.0 * free) / (1024.0 * 1024.0);
    assert!(t.contains(&format!("dense: {dense:.1} MiB")) && t.contains("(513 Γ3 nodes"), "{t}");
    let refused =
        command().env("PIEZOCONTACT_MEMORY_LIMIT", "50000000").args(args).args(mesh).output();
    let t = text(refused.as_ref().unwrap());
    assert_eq!(refused.unwrap().status.code(), Some(1), "{t}");
    assert!(
        t.contains("the exact solver's dense matrices of 1026 condensed Γ3 unknowns")
            && t.contains(&format!("would need about {dense:.1} MiB, more than the 47.7 MiB")),
        "{t}"
    );
}

/// A loading path whose second step fails (its contact zone outgrows solver.max_condensed)
/// keeps the first step written — its row of curve.csv, solution-0001.vtu in solution.pvd,
/// contact.csv and summary.json — says which step failed and why, and exits 4.
#[test]
fn a_path_that_fails_at_a_step_keeps_the_steps_before_it() {
    let out = TempDir::unmade("path-failure");
    let o = piezocontact(&[
        "run",
        "cases/indentation-curve.toml",
        "--out",
        out.to_str().unwrap(),
        "--set",
        "loading.depths=[0.001, 0.02]",
        "--set",
        "solver.max_condensed=10",
    ]);
    let t = text(&o);
    assert_eq!(o.status.code(), Some(4), "{t}");
    assert!(
        t.contains("step 2 of 2 (depth 2e-2, load factor 1) failed")
            && t.contains("raise solver.max_condensed"),
        "{t}"
    );
    let curve = std::fs::read_to_string(out.join("curve.csv")).unwrap();
    let lines: Vec<&str> = curve.lines().collect();
    assert_eq!(lines.len(), 2, "{curve}");
    assert!(lines[0].starts_with("step,load_factor,depth,force_x,force_y,force_z,contact_measure,contact_radius,max_pressure,phi_center,phi_mean,stick_measure,slip_measure,newton_steps,kkt_residual,converged,charge_bottom,charge_top"), "{}", lines[0]);
    assert!(lines[1].starts_with("1,1e0,1e-3,") && lines[1].contains(",true,"), "{}", lines[1]);
    assert!(out.join("solution-0001.vtu").exists() && !out.join("solution-0002.vtu").exists());
    let pvd = std::fs::read_to_string(out.join("solution.pvd")).unwrap();
    assert!(pvd.contains("file=\"solution-0001.vtu\"") && !pvd.contains("0002"), "{pvd}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["converged"], false);
    assert!(summary["failure"].as_str().unwrap().starts_with("step 2 of 2"), "{summary}");
    assert_eq!(
        (summary["path"]["steps"].clone(), summary["path"]["steps_solved"].clone()),
        (2.into(), 1.into())
    );
}

/// The staging directories beside `out` (a run's temporary files).
fn staging_dirs(out: &Path) -> Vec<String> {
    let name = out.file_name().unwrap().to_string_lossy().into_owned();
    std::fs::read_dir(out.parent().unwrap())
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|f| f.starts_with(&format!(".{name}.piezocontact-staging-")))
        .collect()
}

/// SIGINT and SIGTERM in the middle of a long run (Uzawa with a tolerance it cannot reach):
/// the run stops at its next iteration, writes what it has with "failure": "interrupted",
/// removes its staging directory and exits 128 + the signal.
#[test]
fn a_signal_stops_a_run_at_a_safe_point_with_what_it_has() {
    for (signal, code) in [("INT", 130), ("TERM", 143)] {
        let out = TempDir::unmade(&format!("signal-{signal}"));
        let out = out.join("run");
        let mut child = command()
            .args(["run", "cases/paper-7.2.toml", "--out", out.to_str().unwrap()])
            .args(["--set", "solver.eps=1e-25", "--set", "solver.max_inner=100000000"])
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        std::thread::sleep(Duration::from_millis(2500));
        assert!(child.try_wait().unwrap().is_none(), "the run ended before the signal");
        let sent =
            Command::new("kill").arg(format!("-{signal}")).arg(child.id().to_string()).status();
        assert!(sent.unwrap().success());
        let output = child.wait_with_output().unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(code), "SIG{signal}: {stderr}");
        assert!(stderr.contains("interrupted"), "{stderr}");
        let text = std::fs::read_to_string(out.join("summary.json")).unwrap();
        let summary: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert_eq!(summary["converged"], false);
        assert_eq!(summary["failure"], "interrupted");
        assert!(out.join("contact.csv").exists() && out.join("solution.vtu").exists());
        assert_all_complete(&out);
        assert!(staging_dirs(&out).is_empty(), "left: {:?}", staging_dirs(&out));
    }
}

/// A staging directory left by a process that no longer runs is removed by the next run into
/// the same place; one of a process that still runs is left alone.
#[test]
fn a_stale_staging_directory_is_removed_by_the_next_run() {
    let parent = TempDir::unmade("stale");
    let out = parent.join("run");
    // A pid above Linux's largest (2²²) belongs to no process.
    let dead = parent.join(".run.piezocontact-staging-4194305");
    let alive = parent.join(format!(".run.piezocontact-staging-{}", std::process::id()));
    for dir in [&dead, &alive] {
        std::fs::create_dir_all(dir).unwrap();
        std::fs::write(dir.join("half.csv"), "x,").unwrap();
    }
    let output =
        piezocontact(&["run", "cases/paper-7.1.toml", "-q", "--out", out.to_str().unwrap()]);
    assert!(output.status.success(), "{}", text(&output));
    assert!(!dead.exists(), "the dead process's staging directory is still there");
    assert!(alive.exists(), "a running process's staging directory was removed");
    std::fs::remove_dir_all(&alive).unwrap();
}

/// A sweep with a run that the solver refuses still writes sweep.csv with every row: the
/// refused run's marked unconverged without results, the other's with them; the error names
/// the run, and the sweep exits 1.
#[test]
fn a_sweep_keeps_the_rows_of_the_runs_that_fail() {
    let out = TempDir::unmade("sweep-failed-run");
    let newton = "solver.method=\"newton\"";
    let o =
        sweep_coarse("cases/paper-7.1.toml", "solver.max_condensed=1,100", &[], &out, &[newton]);
    let t = text(&o);
    assert_eq!(o.status.code(), Some(1), "{t}");
    assert!(t.contains("run solver.max_condensed=1: ") && t.contains("1 of 2 runs failed"), "{t}");
    let csv = std::fs::read_to_string(out.join("sweep.csv")).unwrap();
    let rows: Vec<Vec<&str>> = csv.lines().skip(1).map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 2, "{csv}");
    assert!(rows[0][0] == "1" && rows[0][3] == "false", "{csv}");
    assert!(rows[0][1..].iter().filter(|c| c.is_empty()).count() == 9, "{csv}");
    assert!(rows[1][0] == "100" && rows[1][3] == "true", "{csv}");
    assert!(rows[1][4].parse::<f64>().unwrap() > 0.0, "{csv}");
    assert!(out.join("run-01/summary.json").exists() && !out.join("run-00").exists());
}

/// A sweep whose run stops at its cap exits 3 and names that run, why it stopped and where
/// its partial result is; with --quiet that error is all it prints (no progress line).
#[test]
fn a_quiet_sweep_names_the_run_that_did_not_converge() {
    let out = TempDir::unmade("sweep-unconverged");
    let (uzawa, list) = ("solver.method=\"uzawa\"", "solver.max_inner=1,5000");
    let o = sweep_coarse("cases/paper-7.1.toml", list, &["-q"], &out, &[uzawa]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(3), "{}", text(&o));
    assert!(o.stdout.is_empty(), "{}", text(&o));
    let run_00 = out.join("run-00");
    let lines: Vec<&str> = stderr.lines().collect();
    assert_eq!(lines.len(), 1, "{stderr}");
    assert!(lines[0].starts_with("error: run solver.max_inner=1: "), "{stderr}");
    assert!(lines[0].contains("did not converge in 1 iteration"), "{stderr}");
    assert!(lines[0].contains(&format!("in {} (marked", run_00.display())), "{stderr}");
    let summary = std::fs::read_to_string(run_00.join("summary.json")).unwrap();
    assert!(summary.contains("\"converged\": false"), "{summary}");
}

/// A case with a loading path is refused by sweep before any run, at the line of its
/// [loading] table: one run per value would solve the foundation's first position alone.
#[test]
fn a_sweep_refuses_a_loading_path() {
    let out = TempDir::unmade("sweep-path");
    let o = piezocontact(&[
        "sweep",
        "cases/indentation-curve.toml",
        "--set-list",
        "friction.mu=0.1,0.3",
        "--out",
        out.to_str().unwrap(),
    ]);
    let t = text(&o);
    let line = std::fs::read_to_string(root().join("cases/indentation-curve.toml"))
        .unwrap()
        .lines()
        .position(|l| l.starts_with("[loading]"))
        .unwrap()
        + 1;
    assert_eq!(o.status.code(), Some(1), "{t}");
    assert!(
        t.contains(&format!("cases/indentation-curve.toml:{line}: the case has a [loading] path")),
        "{t}"
    );
    assert!(!out.join("run-00").exists() && !out.join("sweep.csv").exists(), "{t}");
}
