//! The `piezocontact` command end to end: runs, outputs (read back with an independent VTU
//! reader), and one test per error message.

use super::common::{piezocontact, read_vtu, root, run_coarse, temp_dir, text};
use std::path::{Path, PathBuf};

/// Writes a variant of the paper case with `from` replaced by `to`.
fn variant(dir: &Path, from: &str, to: &str) -> PathBuf {
    let case = std::fs::read_to_string(root().join("cases/paper-7.1.toml")).unwrap();
    assert!(case.contains(from), "the paper case has no '{from}'");
    let path = dir.join("case.toml");
    std::fs::write(&path, case.replacen(from, to, 1)).unwrap();
    path
}

/// `run --vtu ascii` writes the text form of the default binary file: every array equal bit
/// for bit (the binary read by this file's own reader of appended raw data, the text by
/// vtkio), the binary file the smaller.
#[test]
fn the_binary_vtu_holds_the_ascii_one_s_numbers_bit_for_bit() {
    let dir = temp_dir("vtu-encodings");
    let (binary, ascii) = (dir.join("binary"), dir.join("ascii"));
    let o = run_coarse("cases/paper-7.2.toml", &binary, &[]);
    assert!(o.status.success(), "{}", text(&o));
    let o = super::common::coarse(&["run", "cases/paper-7.2.toml", "--vtu", "ascii"], &ascii, &[]);
    assert!(o.status.success(), "{}", text(&o));
    let file = |dir: &Path| dir.join("solution.vtu");
    let (b, a) = (read_vtu(&file(&binary)), read_vtu(&file(&ascii)));
    assert!(b.binary && !a.binary);
    assert_eq!((b.points, b.cells), (a.points, a.cells));
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&b.coordinates), bits(&a.coordinates));
    assert_eq!(b.connectivity, a.connectivity);
    for (x, y) in
        b.point_data.iter().chain(&b.cell_data).zip(a.point_data.iter().chain(&a.cell_data))
    {
        assert_eq!(x.0, y.0);
        assert_eq!(bits(&x.1), bits(&y.1), "{}", x.0);
    }
    let size = |dir: &Path| std::fs::metadata(file(dir)).unwrap().len();
    assert!(size(&binary) < size(&ascii), "{} vs {} bytes", size(&binary), size(&ascii));
}

#[test]
fn run_writes_a_summary_a_contact_table_and_a_vtu_that_a_reader_accepts() {
    let out = temp_dir("run");
    let o = run_coarse("cases/paper-7.1.toml", &out, &[]);
    assert!(o.status.success(), "{}", text(&o));
    assert!(text(&o).contains("max |sigma_nu|") && text(&o).contains(" GPa\n"), "{}", text(&o));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["problem"], "PV1");
    assert_eq!(summary["converged"], true);
    assert_eq!(summary["nodes"], 25 * 5);
    assert_eq!(summary["elements"], 2 * 24 * 4);
    assert_eq!(summary["dofs"]["total"], 3 * 125);
    assert_eq!(summary["units"]["stress"], "GPa");
    // The lone material of the paper's case, poled along y.
    let material = &summary["materials"][0];
    assert_eq!(summary["materials"].as_array().map(Vec::len), Some(1));
    assert_eq!((&material["name"], &material["law"]), (&"material".into(), &"hencky".into()));
    assert_eq!(material["cells"], summary["elements"]);
    assert_eq!(material["piezoelectric"], true);
    assert_eq!(material["poling"], serde_json::json!([0.0, 1.0, 0.0]));
    let outer = summary["outer_iterations"].as_u64().unwrap() as usize;
    assert_eq!(summary["inner_iterations"].as_array().unwrap().len(), outer);
    assert_eq!(summary["outer_criterion_history"].as_array().unwrap().len(), outer);
    assert!(summary["kkt_residual"]["max"].as_f64().unwrap() < 0.1);
    assert!(summary["balance"]["relative_imbalance"].as_f64().unwrap() < 1e-4);
    for key in ["assembly", "symbolic", "numeric", "solve", "dense", "assessment", "total"] {
        assert!(summary["timings_seconds"][key].as_f64().unwrap() >= 0.0, "{key}");
    }
    // Building the case (the rectangle's mesh, the checks) takes time, outside the solve's.
    assert!(summary["timings_seconds"]["case"].as_f64().unwrap() > 0.0);
    let direct = serde_json::json!({
        "kind": "direct", "krylov": "none", "preconditioner": "none", "krylov_iterations": [],
    });
    assert_eq!(summary["linear"], direct, "a factorisation, no Krylov solves");
    // contact.csv: the fixed header, one row per free Γ3 node (x = 2.5 … 9.5), ordered in x.
    let csv = std::fs::read_to_string(out.join("contact.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("x,y,u_nu,u_tau,sigma_nu,sigma_tau,phi,s,status"));
    let rows: Vec<Vec<String>> =
        lines.map(|l| l.split(',').map(str::to_string).collect()).collect();
    assert_eq!(rows.len(), 17);
    let x: Vec<f64> = rows.iter().map(|r| r[0].parse().unwrap()).collect();
    assert!(x.windows(2).all(|w| w[0] < w[1]) && (x[0] - 2.0).abs() < 1e-12);
    assert!(rows.iter().all(|r| r[8] == "contact" || r[8] == "separated"));
    let max_sigma = rows.iter().map(|r| r[4].parse::<f64>().unwrap().abs()).fold(0.0, f64::max);
    assert!(
        (max_sigma - summary["gamma3"]["max_abs_sigma_nu"].as_f64().unwrap()).abs()
            <= 1e-9 * max_sigma
    );
    // solution.vtu, read back by an independent reader.
    let vtu = read_vtu(&out.join("solution.vtu"));
    assert_eq!((vtu.points, vtu.cells), (125, 192));
    let names: Vec<&str> = vtu.point_data.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(
        names,
        ["u", "phi", "contact_status", "contact_pressure", "friction_traction", "gap"]
    );
    let cell_names: Vec<&str> = vtu.cell_data.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(cell_names, ["sigma", "D", "material", "poling"]);
    // The gap on Γ3 is the paper's constant 0.5 m; PV1 has no friction traction.
    let on_gamma3 = vtu.point_data[2].1.iter().filter(|s| **s > 0.0).count();
    assert_eq!(vtu.point_data[5].1.iter().filter(|g| **g == 0.5).count(), on_gamma3);
    assert!(vtu.point_data[4].1.iter().all(|t| *t == 0.0));
    let pressure = vtu.point_data[3].1.iter().copied().fold(0.0, f64::max);
    assert!((pressure - max_sigma).abs() <= 1e-9 * max_sigma);
    let leftovers: Vec<_> = std::fs::read_dir(&out)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
        .collect();
    assert!(leftovers.is_empty(), "temporary files left behind");
}

#[test]
fn an_iteration_cap_is_an_error_with_the_partial_result_written() {
    let out = temp_dir("cap");
    let o = run_coarse("cases/paper-7.2.toml", &out, &["solver.max_inner=3"]);
    let t = text(&o);
    assert_eq!(o.status.code(), Some(3), "{t}");
    assert!(
        t.contains("the Uzawa loop (Algorithm 2) of outer step 1 did not converge in 3 iterations"),
        "{t}"
    );
    assert!(t.contains("last criterion") && t.contains("marked \"converged\": false"), "{t}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["converged"], false);
    assert!(summary["failure"].as_str().unwrap().contains("Uzawa loop"));
    assert!(out.join("contact.csv").exists() && out.join("solution.vtu").exists());
    let o = run_coarse("cases/paper-7.2.toml", &out, &["solver.max_outer=2"]);
    let t = text(&o);
    assert_eq!(o.status.code(), Some(3), "{t}");
    assert!(
        t.contains("the fixed-point loop (Algorithm 1) did not converge in 2 iterations"),
        "{t}"
    );
}

/// The 3D example: the 3D contact table, the VTU vectors, the contact map, and the physics
/// of indentation — pressure under the ball, stick at the centre, slip around it, and a
/// potential on the insulated face that the compression induces.
#[test]
fn the_3d_indentation_example_writes_3d_outputs() {
    let out = temp_dir("indentation");
    let o = piezocontact(&["run", "cases/indentation-3d.toml", "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", text(&o));
    assert!(text(&o).contains("contact / stick / slip measure") && text(&o).contains("m^2"));
    let csv = std::fs::read_to_string(out.join("contact.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next().unwrap(),
        "x,y,z,u_nu,u_tau1,u_tau2,sigma_nu,sigma_tau1,sigma_tau2,phi,s,status"
    );
    let rows: Vec<Vec<String>> =
        lines.map(|l| l.split(',').map(str::to_string).collect()).collect();
    let value = |r: &Vec<String>, k: usize| r[k].parse::<f64>().unwrap();
    // Ordered by coordinates.
    assert!(rows.windows(2).all(|w| value(&w[0], 0) <= value(&w[1], 0)));
    let centre = rows
        .iter()
        .min_by(|a, b| value(a, 0).hypot(value(a, 1)).total_cmp(&value(b, 0).hypot(value(b, 1))))
        .unwrap();
    assert_eq!(centre[11], "stick");
    assert!(rows.iter().any(|r| r[11] == "slip") && rows.iter().any(|r| r[11] == "separated"));
    let peak = rows.iter().map(|r| -value(r, 6)).fold(0.0, f64::max);
    assert!(-value(centre, 6) > 0.9 * peak, "the pressure does not peak under the ball");
    // On slip nodes |σ_τ| = µ|σ_ν|.
    for r in rows.iter().filter(|r| r[11] == "slip") {
        let tangential = value(r, 7).hypot(value(r, 8));
        assert!((tangential - 0.3 * value(r, 6).abs()).abs() <= 1e-8 * peak, "{r:?}");
    }
    let vtu = read_vtu(&out.join("solution.vtu"));
    let field = |name: &str| &vtu.point_data.iter().find(|(n, _)| n == name).unwrap().1;
    assert_eq!(field("friction_traction").len(), 3 * vtu.points);
    assert!(field("gap").iter().any(|g| *g < 0.0), "the ball starts inside the block");
    assert!(field("phi").iter().any(|p| p.abs() > 0.0), "no induced potential");
    for file in ["contact_map.png", "contact_map.svg"] {
        assert!(std::fs::metadata(out.join(file)).unwrap().len() > 1000, "{file}");
    }
    // The factor the symbolic analysis predicted was held at the measured peak.
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let predicted = summary["memory"]["factor_predicted_bytes"].as_f64().unwrap();
    let peak = summary["memory"]["peak_resident_bytes"].as_f64().unwrap();
    assert!(predicted > 1e6 && peak >= predicted, "predicted {predicted}, peak {peak}");
    // The exact solver's dense matrices: 7 of m × m, m = 3 u components (and ϕ where the
    // laws read it) of each condensed node; and a growth's 32 right-hand sides of n free
    // unknowns.
    let dense = summary["memory"]["dense_predicted_bytes"].as_f64().unwrap();
    let nodes = summary["gamma3"]["condensed_nodes"].as_f64().unwrap();
    let free = summary["dofs"]["free"].as_f64().unwrap();
    let at = |per_node: f64| 8.0 * (7.0 * (per_node * nodes).powi(2) + 32.0 * free);
    assert!(nodes > 0.0 && dense >= at(3.0) && dense <= at(4.0), "{dense} for {nodes} nodes");
}

#[test]
fn a_gmsh_case_runs_and_mesh_info_describes_the_file() {
    let dir = temp_dir("gmsh");
    let case = format!(
        "[units]\nstress = \"GPa\"\npotential = \"GV\"\n[mesh]\nfile = \"{}\"\n[material]\nyoung = 58.7\npoisson = 0.39\ne31 = -5.4\ne33 = 15.8\ne15 = 12.3\neps0 = 8.885e-3\nbeta11_rel = 916\nbeta33_rel = 830\n[boundary]\nclamped = [\"clamp\"]\ngrounded = [\"top\"]\ncontact = [\"contact\"]\n[[boundary.traction]]\nparts = [\"top\"]\nf2 = [0.0, -1.0]\n",
        root().join("meshes/arch.msh").display()
    );
    std::fs::write(dir.join("arch.toml"), case).unwrap();
    let o = piezocontact(&[
        "run",
        dir.join("arch.toml").to_str().unwrap(),
        "--out",
        dir.join("out").to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", text(&o));
    let o = piezocontact(&["mesh-info", "meshes/arch.msh"]);
    let t = text(&o);
    assert!(
        o.status.success()
            && t.contains("binary")
            && t.contains("\"contact\"")
            && t.contains("Tri3")
            && t.contains("usable: yes"),
        "{t}"
    );
}

/// `materials` lists every preset with its source and constants.
#[test]
fn materials_lists_the_library() {
    let o = piezocontact(&["materials"]);
    let t = text(&o);
    assert!(o.status.success(), "{t}");
    for name in [
        "PZT-4",
        "PZT-5A",
        "PZT-5H",
        "BaTiO3",
        "AlN",
        "ZnO",
        "LiNbO3",
        "quartz",
        "PVDF",
        "silicon",
        "alumina",
        "fused-silica",
        "epoxy",
    ] {
        assert!(t.contains(&format!("{name} — ")), "{name}: {t}");
    }
    assert!(
        t.contains("c33=110.9000") && t.contains("e33=15.8000") && t.contains("d33=-33.0000"),
        "{t}"
    );
}

/// `check`'s data sheet of the library's PZT-5A (Berlincourt's stress-charge form) gives the
/// coupling factors that Berlincourt publishes, k33 = 0.705, k31 = −0.34, k15 = 0.685, to 2 %
/// (the constants are rounded to three figures); quartz, not transversely isotropic, has none.
#[test]
fn check_prints_each_material_s_data_sheet() {
    let dir = temp_dir("sheet");
    let case = |preset: &str| {
        format!(
            "[units]\nstress = \"GPa\"\npotential = \"GV\"\n[mesh]\nfile = \"{}\"\n[material]\npreset = \"{preset}\"\n[boundary]\nclamped = [\"bottom\"]\ngrounded = [\"bottom\"]\n",
            root().join("meshes/box-faces.msh").display()
        )
    };
    std::fs::write(dir.join("pzt.toml"), case("PZT-5A")).unwrap();
    let o = piezocontact(&["check", dir.join("pzt.toml").to_str().unwrap()]);
    let t = text(&o);
    assert!(o.status.success() && t.contains("s^E [1/GPa]:") && t.contains("g = (ε^T)⁻¹ d"), "{t}");
    let line = t.lines().find(|l| l.contains("coupling factors")).unwrap_or_else(|| panic!("{t}"));
    let value = |name: &str| -> f64 {
        let after = line.split(&format!("{name} = ")).nth(1).unwrap();
        after.split(',').next().unwrap().trim().parse().unwrap()
    };
    for (name, published) in [("k33", 0.705), ("k31", -0.34), ("k15", 0.685)] {
        assert!((value(name) - published).abs() < 0.02 * published.abs(), "{name}: {line}");
    }
    assert!(t.contains("C* insulating tip"), "{t}");
    std::fs::write(dir.join("quartz.toml"), case("quartz")).unwrap();
    let t = text(&piezocontact(&["check", dir.join("quartz.toml").to_str().unwrap()]));
    assert!(t.contains("no closed form is given") && !t.contains("coupling factors"), "{t}");
}

/// Every committed case is valid: `check` reads it and its mesh and says so.
#[test]
fn every_committed_case_checks() {
    let mut cases: Vec<String> = std::fs::read_dir(root().join("cases"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|name| name.ends_with(".toml"))
        .collect();
    cases.sort();
    assert!(cases.len() >= 6, "{cases:?}");
    for case in cases.iter().map(|name| format!("cases/{name}")) {
        let o = piezocontact(&["check", &case]);
        let t = text(&o);
        assert!(o.status.success() && t.contains(&format!("{case}: valid")), "{t}");
    }
}

#[test]
fn contact_overrides_reach_the_solver() {
    let o = piezocontact(&[
        "check",
        "cases/paper-7.2.toml",
        "--set",
        "friction.mu=0.2",
        "--set",
        "conductivity.ke=0.3",
        "--set",
        "conductivity.phi0=10",
        "--set",
        "contact.problem=PV2",
    ]);
    let t = text(&o);
    assert!(o.status.success(), "{t}");
    for line in [
        "friction.mu            = 0.2",
        "conductivity.ke        = 0.3",
        "conductivity.phi0      = 10",
        "problem: PV2",
    ] {
        assert!(t.contains(line), "{line}: {t}");
    }
    // The same case with friction and conduction switched off is PV1, and gives Example 7.1.
    let out = temp_dir("pv1");
    let table = |case: &str, sets: &[&str]| {
        let o = run_coarse(case, &out, sets);
        assert!(o.status.success(), "{}", text(&o));
        std::fs::read_to_string(out.join("contact.csv")).unwrap()
    };
    let switched_off = table("cases/paper-7.2.toml", &["contact.problem=PV1"]);
    let pv1 = table("cases/paper-7.1.toml", &[]);
    assert_eq!(switched_off, pv1);
}

#[test]
fn check_prints_the_mesh_and_dof_summary() {
    let o = piezocontact(&[
        "check",
        "cases/paper-7.1.toml",
        "--set",
        "mesh.nx=12",
        "--set",
        "mesh.ny=2",
    ]);
    let t = text(&o);
    assert!(o.status.success(), "{t}");
    assert!(
        t.contains("39 nodes, 48 elements") && t.contains("measure 8.000000 m  (Γ3 contact)"),
        "{t}"
    );
    assert!(t.contains("dofs: 117 in all"), "{t}");
    assert!(t.contains("factor: ") && t.contains(" Gflop for the factorisation;"), "{t}");
    assert!(t.contains(" available"), "{t}");
    assert!(t.contains("warning: (h1)(b) holds only for ‖ε^D‖² < e·t0 = 4.8929e0"), "{t}");
    assert!(t.contains("note: p_ν is bounded by M_p = 1"), "{t}");
}

/// `check` of a loading path prints its steps and the material's indentation moduli: for
/// PZT-5A, E/(1 − ν²) from its E and ν, and C* for both tips (the insulating one the stiffer,
/// both above E*: the coupling stiffens the contact).
#[test]
fn check_prints_the_path_and_the_indentation_moduli() {
    let o = piezocontact(&[
        "check",
        "cases/indentation-curve.toml",
        "--set",
        "loading.depths=[0.01, 0.02]",
    ]);
    let t = text(&o);
    assert!(o.status.success(), "{t}");
    assert!(
        t.contains("loading path: 2 steps along [0.0, 0.0, -1.0], depths [0.01, 0.02] m"),
        "{t}"
    );
    let e_star = 58.7102 / (1.0 - 0.3912f64.powi(2));
    assert!(t.contains(&format!("E/(1 − ν²)          = {e_star:.6} GPa")), "{t}");
    let value = |label: &str| -> f64 {
        let line = t.lines().find(|l| l.contains(label)).unwrap_or_else(|| panic!("{label}: {t}"));
        line.split('=').nth(1).unwrap().split_whitespace().next().unwrap().parse().unwrap()
    };
    let (insulating, grounded) = (value("C* insulating tip"), value("C* grounded tip"));
    assert!(insulating > grounded && grounded > e_star, "{t}");
    assert!(t.contains("GV/m (surface potential per indentation into the body)"), "{t}");
}

/// summary.json's timings cover the whole run: the case, the solver (its phases within it),
/// each file written (a path's steps summed under one name) and the rest add up to `total`,
/// which lies between the phases' sum and the process's wall time measured outside it;
/// `run -v` prints them as a table.
#[test]
fn the_timings_cover_the_run_and_each_file() {
    let out = temp_dir("timings");
    let start = std::time::Instant::now();
    let case = "cases/cantilever-load-factors.toml";
    let o = piezocontact(&["-v", "run", case, "--out", out.to_str().unwrap()]);
    let wall = start.elapsed().as_secs_f64();
    assert!(o.status.success(), "{}", text(&o));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let t = &summary["timings_seconds"];
    let seconds = |key: &str| t[key].as_f64().unwrap_or_else(|| panic!("{key}: {t}"));
    let files = t["files"].as_object().unwrap();
    let mut names: Vec<&str> = files.keys().map(String::as_str).collect();
    names.sort_unstable();
    let expected = ["curve", "curve.csv", "solution-NNNN.vtu", "solution.pvd", "solution.vtu"];
    assert_eq!(names, expected);
    let written: f64 = files.values().map(|s| s.as_f64().unwrap()).sum();
    assert!(files.values().all(|s| s.as_f64().unwrap() > 0.0), "{t}");
    let phases = ["pattern", "assembly", "symbolic", "numeric", "solve", "dense", "assessment"];
    let solver: f64 = phases.iter().map(|k| seconds(k)).sum();
    assert!(solver <= seconds("solver") && seconds("assessment") > 0.0, "{t}");
    let (total, other) = (seconds("total"), seconds("other"));
    let named = seconds("case") + seconds("solver") + written;
    assert!((named + other - total).abs() <= 1e-12 * total && other >= 0.0, "{t}");
    assert!(named <= total && total <= wall, "{t}: the process took {wall} s");
    let printed = text(&o);
    for line in ["writing solution-NNNN.vtu", "assessment", "total"] {
        assert!(printed.contains(line), "{line}: {printed}");
    }
}

/// 1-based line of the first line of the paper case that starts with `prefix`.
fn line_of(prefix: &str) -> usize {
    let case = std::fs::read_to_string(root().join("cases/paper-7.1.toml")).unwrap();
    case.lines().position(|l| l.starts_with(prefix)).unwrap() + 1
}

/// Each error: the command fails with exit code 1 and a message with the given pieces.
fn assert_error(args: &[&str], pieces: &[&str]) {
    let o = piezocontact(args);
    let t = text(&o);
    assert_eq!(o.status.code(), Some(1), "{args:?}: {t}");
    for p in pieces {
        assert!(t.contains(p), "{args:?}: expected '{p}' in:\n{t}");
    }
    assert!(!t.contains("panicked"), "{t}");
}

#[test]
fn error_messages() {
    let dir = temp_dir("errors");
    let unknown = variant(&dir, "nx = 96", "nx = 96\nnz = 3");
    assert_error(
        &["check", unknown.to_str().unwrap()],
        &["case.toml", &format!("line {}", line_of("nx = ") + 1), "unknown field `nz`"],
    );
    assert_error(
        &["check", "cases/paper-7.1.toml", "--set", "solver.rr=1"],
        &["unknown field `rr`", "with the overrides solver.rr=1"],
    );
    assert_error(
        &["check", "cases/paper-7.1.toml", "--set", "nonsense"],
        &["expected dotted.key=value"],
    );
    assert_error(
        &["check", "cases/paper-7.1.toml", "--set", "mesh.nx=0"],
        &["mesh.nx = 0", "at least 1 cell"],
    );
    assert_error(
        &["check", "cases/paper-7.1.toml", "--set", "material.young=-1"],
        &[
            &format!("paper-7.1.toml:{}", line_of("young = ")),
            "material.young = -1",
            "Young's modulus",
        ],
    );
    assert_error(
        &["check", "cases/paper-7.1.toml", "--set", "friction.mu=-0.5"],
        &[&format!("paper-7.1.toml:{}", line_of("mu = ")), "friction.mu = -0.5", "µ ≥ 0"],
    );
    assert_error(
        &["check", "cases/paper-7.1.toml", "--set", "mesh.diagonal=up"],
        &["unknown variant `up`"],
    );
    let missing = variant(&dir, "clamped = [\"ends\"]", "clamped = [\"end\"]");
    assert_error(
        &["check", missing.to_str().unwrap()],
        &["boundary.clamped", "'end' is not a boundary part of the mesh", "contact, ends, load"],
    );
    // A volume group is not a boundary part: the message says what parts are, and what
    // 'body' is.
    assert_error(
        &["check", "cases/indentation-3d.toml", "--set", "boundary.contact=[\"body\"]"],
        &[
            "'body' is not a boundary part of the mesh",
            "groups of facets",
            "surfaces in 3D",
            "'body' is a physical group of volumes (dimension 3) in the mesh file",
        ],
    );
    let empty = variant(&dir, "clamped = [\"ends\"]", "clamped = []");
    assert_error(&["check", empty.to_str().unwrap()], &["Γ1 (clamped or supported) is empty"]);
    let grounded = variant(&dir, "grounded = [\"load\"]", "grounded = []");
    assert_error(&["check", grounded.to_str().unwrap()], &["Γa (grounded) is empty"]);
    let overlap = variant(&dir, "contact = [\"contact\"]       # Γ3", "contact = [\"ends\"]");
    assert_error(
        &["check", overlap.to_str().unwrap()],
        &["'ends' (Γ3 (contact)) and 'ends' (Γ1 (clamped))", "must be disjoint"],
    );
    let syntax = variant(&dir, "nx = 96", "nx = = 96");
    assert_error(
        &["check", syntax.to_str().unwrap()],
        &["case.toml", &format!("line {}", line_of("nx = "))],
    );
    let segment = variant(&dir, "[2,10]x{0}", "[2,10]x{7}");
    assert_error(&["check", segment.to_str().unwrap()], &["[2,10]x{7}", "holds no facet"]);
    assert_error(
        &["check", "cases/paper-7.1.toml", "--set", "mesh.file=missing.msh"],
        &["mesh.x describes the built-in rectangle"],
    );
    assert_error(
        &["check", "does-not-exist.toml"],
        &["cannot read the case file does-not-exist.toml"],
    );
    std::fs::write(dir.join("bad.msh"), b"\x00\x01garbage").unwrap();
    assert_error(
        &["mesh-info", dir.join("bad.msh").to_str().unwrap()],
        &["bad.msh", "no $MeshFormat section"],
    );
    // A case file given to mesh-info: the command that reads it is named.
    assert_error(
        &["mesh-info", "cases/paper-7.1.toml"],
        &["no $MeshFormat section", "a case file: `piezocontact check"],
    );
    assert_error(&["bench", "--sizes", "12by3"], &["'12by3' is not NXxNY"]);
    // No runs at a time is a usage error (--jobs 0 ran on every core), as --threads 0 is.
    for command in
        [&["sweep", "cases/paper-7.2.toml", "--set-list", "friction.mu=0.1"][..], &["reproduce"]]
    {
        let o = piezocontact(&[command, &["--jobs", "0", "--out", "unused"]].concat());
        let t = text(&o);
        assert!(o.status.code() == Some(2) && t.contains("invalid value '0' for '--jobs"), "{t}");
    }
    // A bad size is refused before the table's header is printed.
    let o = piezocontact(&["bench", "--sizes", "12x2,4x"]);
    let t = text(&o);
    assert!(o.status.code() == Some(1) && t.contains("'4x' is not NXxNY"), "{t}");
    assert!(!t.contains("numeric_s"), "{t}");
    // Two meshes for bench --contact: the message names both ways, not only --contact.
    assert_error(
        &["bench", "--contact", "--mesh", "meshes/cube.msh", "--case", "cases/bar-3d.toml"],
        &["from --case or from --mesh, not both"],
    );
    // A loading path is not one contact problem: bench --contact would time the unloaded
    // state (one Newton step, no contact).
    let o = piezocontact(&["bench", "--contact", "--case", "cases/indentation-curve.toml"]);
    let t = text(&o);
    assert!(o.status.code() == Some(1) && !t.contains("kkt_residual"), "{t}");
    assert!(t.contains("[loading] path") && t.contains("bench --path --case"), "{t}");
}

#[test]
fn bench_prints_the_phases() {
    let o = piezocontact(&["bench", "--sizes", "12x2,24x4", "--lu"]);
    let t = text(&o);
    assert!(o.status.success(), "{t}");
    for column in ["assembly_s", "symbolic_s", "numeric_s", "solve_s", "faer sparse LU"] {
        assert!(t.contains(column), "{column}: {t}");
    }
}

/// `bench --materials` prints both sides and their ratio; on the box every quadrant holds
/// cells.
#[test]
fn bench_materials_prints_both_sides() {
    let o = piezocontact(&["bench", "--materials", "--mesh", "meshes/box-faces.msh"]);
    let t = text(&o);
    assert!(o.status.success(), "{t}");
    assert!(
        t.contains("one material") && t.contains("four materials") && t.contains("four / one"),
        "{t}"
    );
    let counts = t.lines().find(|l| l.contains("four materials")).unwrap();
    assert!(!counts.contains(" 0,") && !counts.contains(", 0]"), "{counts}");
}

/// Width and height from a PNG's IHDR chunk, after checking the signature.
fn png_size(bytes: &[u8]) -> (u32, u32) {
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "not a PNG");
    assert_eq!(&bytes[12..16], b"IHDR");
    let be = |k: usize| u32::from_be_bytes([bytes[k], bytes[k + 1], bytes[k + 2], bytes[k + 3]]);
    (be(16), be(20))
}

#[test]
fn reproduce_writes_every_file_of_the_report() {
    let out = temp_dir("reproduce");
    let o = piezocontact(&[
        "reproduce",
        "--out",
        out.to_str().unwrap(),
        "--mesh",
        "24,4",
        "--jobs",
        "2",
    ]);
    assert!(o.status.success(), "{}", text(&o));
    let report = std::fs::read_to_string(out.join("REPORT.md")).unwrap();
    for figure in [
        "figure1a",
        "figure1b",
        "figure2a",
        "figure2b",
        "figure3a",
        "figure3b",
        "figure4",
        "theorem41",
    ] {
        let png = std::fs::read(out.join(format!("{figure}.png"))).unwrap();
        let (w, h) = png_size(&png);
        assert!(
            w >= 800 && h >= 400 && png.len() > 10_000,
            "{figure}.png: {w}×{h}, {} bytes",
            png.len()
        );
        let svg = std::fs::read_to_string(out.join(format!("{figure}.svg"))).unwrap();
        assert!(
            svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>") && svg.contains("<text"),
            "{figure}.svg"
        );
        assert!(report.contains(&format!("({figure}.png)")), "REPORT.md does not show {figure}");
    }
    for section in [
        "## Example 7.1",
        "## Example 7.2",
        "## Table 2",
        "## Figures 3 and 4",
        "## Theorem 4.1",
        "## Mesh convergence",
        "## Accuracy of the paper's stopping rule",
        "**Units.**",
    ] {
        assert!(report.contains(section), "REPORT.md lacks {section}");
    }
    let table = std::fs::read_to_string(out.join("table2.csv")).unwrap();
    let mut lines = table.lines();
    assert_eq!(
        lines.next(),
        Some(
            "mu,ke,paper_outer_iterations,outer_iterations,inner_iterations,converged,max_abs_sigma_nu,max_abs_sigma_tau,distance_to_pv1,wall_seconds"
        )
    );
    assert_eq!(lines.count(), 8);
    for csv in ["mesh_convergence.csv", "stopping_rule.csv"] {
        assert!(std::fs::read_to_string(out.join(csv)).unwrap().lines().count() >= 3, "{csv}");
    }
}

/// Table 2's trend on the default mesh: outer iterations fall monotonically as µ = k_e
/// decreases and reach the paper's 2 at the small values.
#[test]
fn table2_trend() {
    let out = temp_dir("table2");
    let o = piezocontact(&[
        "sweep",
        "cases/paper-7.2.toml",
        "--set-list",
        "friction.mu=conductivity.ke=0.6,0.2,6.8e-2,5.1e-3,6.2e-4,1.4e-5,3.5e-6,8.5e-7",
        "--reference",
        "contact.problem=PV1",
        "--out",
        out.to_str().unwrap(),
        "--jobs",
        "2",
    ]);
    assert!(o.status.success(), "{}", text(&o));
    let units = "max_abs_sigma_tau in GPa; contact_length, stick_length, slip_length: lengths of the zones on Γ3 in m;";
    assert!(text(&o).contains(units), "{}", text(&o));
    let csv = std::fs::read_to_string(out.join("sweep.csv")).unwrap();
    let rows: Vec<Vec<String>> =
        csv.lines().skip(1).map(|l| l.split(',').map(str::to_string).collect()).collect();
    let outer: Vec<usize> = rows.iter().map(|r| r[2].parse().unwrap()).collect();
    assert!(outer.windows(2).all(|w| w[1] <= w[0]), "{outer:?}");
    assert_eq!(outer[outer.len() - 1], 2, "{outer:?}");
    let paper = [7, 5, 4, 3, 2, 2, 2, 2];
    let within_one = outer.iter().zip(paper).filter(|(o, p)| o.abs_diff(*p) <= 1).count();
    assert_eq!(within_one, 8, "{outer:?} against the paper's {paper:?}");
    let distance: Vec<f64> = rows.iter().map(|r| r[10].parse().unwrap()).collect();
    assert!(distance[0] > distance[3] && distance[3] > distance[7], "{distance:?}");
}

/// Values of --set-list that hold commas or `=` — arrays, tables — are whole values: each
/// run takes its own (its max |σ_ν| that of `run` with the same value), and sweep.csv quotes
/// them. Before, `loads.f0=[0.0,0.0],[0.0,-1.0]` was split into "[0.0" and "0.0]" and refused.
#[test]
fn a_sweep_takes_arrays_and_tables_as_values() {
    let out = temp_dir("sweep-arrays");
    let coarse = ["cases/paper-7.2.toml", "--set", "mesh.nx=24", "--set", "mesh.ny=4"];
    let values = ["loads.f0=[0.0,0.0],[0.0,-1.0]", "solver={eps=1e-3, eps_fp=1e-3},{eps=1e-6}"];
    let mut rows = Vec::new();
    for (k, list) in values.iter().enumerate() {
        let dir = out.join(format!("sweep-{k}"));
        let args = [&["sweep"][..], &coarse, &["--set-list", list, "--out", dir.to_str().unwrap()]];
        let o = piezocontact(&args.concat());
        assert!(o.status.success(), "{}", text(&o));
        let csv = std::fs::read_to_string(dir.join("sweep.csv")).unwrap();
        rows.extend(csv.lines().skip(1).map(str::to_string));
    }
    let quoted =
        ["\"[0.0,0.0]\",", "\"[0.0,-1.0]\",", "\"{eps=1e-3, eps_fp=1e-3}\",", "{eps=1e-6},"];
    assert_eq!(rows.len(), 4, "{rows:?}");
    for (row, start) in rows.iter().zip(quoted) {
        assert!(row.starts_with(start), "{row} does not start with {start}");
    }
    // The second value's run: the same max |σ_ν| as `run` with it, and not the first's.
    let run = out.join("run");
    let set = ["--set", "loads.f0=[0.0,-1.0]", "--out", run.to_str().unwrap()];
    let o = piezocontact(&[&["-q", "run"][..], &coarse, &set].concat());
    assert!(o.status.success(), "{}", text(&o));
    let summary = std::fs::read_to_string(run.join("summary.json")).unwrap();
    let summary: serde_json::Value = serde_json::from_str(&summary).unwrap();
    let sigma = |row: &str| row.rsplit(',').nth(6).unwrap().parse::<f64>().unwrap();
    assert_eq!(sigma(&rows[1]), summary["gamma3"]["max_abs_sigma_nu"].as_f64().unwrap());
    assert_ne!(sigma(&rows[0]), sigma(&rows[1]));
}

/// A sweep of a 3D case says that its zone measures are areas, in the case's length unit
/// squared; their columns keep the names of the 2D lengths.
#[test]
fn a_3d_sweep_measures_its_zones_as_areas() {
    let out = temp_dir("sweep-3d");
    let o = piezocontact(&[
        "sweep",
        "cases/indentation-3d.toml",
        "--set",
        "mesh.file=\"../meshes/indent-3d-h0.05.msh\"",
        "--set-list",
        "friction.mu=0.1,0.3",
        "--out",
        out.to_str().unwrap(),
    ]);
    let t = text(&o);
    assert!(o.status.success(), "{t}");
    assert!(t.contains("stick_length, slip_length: areas of the zones on Γ3 in m²;"), "{t}");
    let csv = std::fs::read_to_string(out.join("sweep.csv")).unwrap();
    let header = csv.lines().next().unwrap();
    assert!(header.contains(",contact_length,stick_length,slip_length,"), "{header}");
}

/// --threads bounds a run (summary.json says so) and leaves its answer alone to the last bit:
/// the 3D indentation (its factorisation on faer's parallel kernels) on one thread and on two
/// gives the same contact table and the same fields, byte for byte (faer's work is split by
/// the machine's cores, not by the threads that run it; before that, one thread and two
/// differed in the 13th digit). PIEZOCONTACT_THREADS does the same; a bad value is refused
/// with the variable's name.
#[test]
fn threads_bound_a_run_and_leave_its_answer_to_the_last_bit() {
    let dir = temp_dir("threads");
    let mut answers = Vec::new();
    for (k, threads) in ["1", "2"].iter().enumerate() {
        let out = dir.join(format!("run{k}"));
        let args = ["run", "cases/indentation-3d.toml", "-q", "--threads", threads];
        let output = piezocontact(&[&args[..], &["--out", out.to_str().unwrap()]].concat());
        assert!(output.status.success(), "{}", text(&output));
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap())
                .unwrap();
        assert_eq!(summary["threads"].to_string(), *threads);
        let read = |name: &str| std::fs::read(out.join(name)).unwrap();
        answers.push((read("contact.csv"), read("solution.vtu")));
    }
    assert!(answers[0].0 == answers[1].0, "contact.csv differs between 1 and 2 threads");
    assert!(answers[0].1 == answers[1].1, "solution.vtu differs between 1 and 2 threads");
    let bad = super::common::command()
        .args(["check", "cases/paper-7.1.toml"])
        .env("PIEZOCONTACT_THREADS", "0")
        .output()
        .unwrap();
    assert_eq!(bad.status.code(), Some(1));
    assert!(text(&bad).contains("PIEZOCONTACT_THREADS"), "{}", text(&bad));
}

/// A loading path without `[contact]` solves each step without contact, the loads scaled by
/// its factor: curve.csv has the path's columns and no contact columns; the clamp's reaction
/// balances the tip traction times the factor (f2 × the tip's length, read from the case), the
/// charges grow linearly with the factor and sum to zero (no free charge), and the last step
/// is the run of the case without `[loading]` at its factor. Depths without a foundation to
/// move are refused, naming the key.
#[test]
fn a_path_without_contact_scales_the_loads_step_by_step() {
    let dir = temp_dir("path-without-contact");
    let case = "cases/cantilever-load-factors.toml";
    let o = piezocontact(&["run", case, "--out", &dir.join("path").display().to_string(), "-q"]);
    assert!(o.status.success(), "{}", text(&o));
    let curve = std::fs::read_to_string(dir.join("path/curve.csv")).unwrap();
    let mut lines = curve.lines();
    let header = "step,load_factor,reaction_x,reaction_y,charge_root,charge_top";
    assert_eq!(lines.next(), Some(header));
    let rows: Vec<Vec<f64>> =
        lines.map(|l| l.split(',').map(|v| v.parse().unwrap()).collect()).collect();
    assert_eq!(rows.iter().map(|r| r[1]).collect::<Vec<_>>(), [0.5, 1.0, 1.5, 2.0]);
    let (f2, tip_length) = (-0.001, 2.0);
    let unit_charge = rows[1][4];
    for r in &rows {
        let applied = f2 * tip_length * r[1];
        assert!((r[3] + applied).abs() < 1e-9 * applied.abs(), "{r:?}");
        assert!(r[2].abs() < 1e-9 * applied.abs(), "{r:?}");
        assert!((r[4] - r[1] * unit_charge).abs() < 1e-9 * unit_charge.abs(), "{r:?}");
        assert!((r[4] + r[5]).abs() < 1e-9 * r[4].abs(), "{r:?}");
    }
    assert!(unit_charge.abs() > 0.0, "the bending draws no charge: {curve}");
    for k in 1..=4 {
        assert!(dir.join(format!("path/solution-{k:04}.vtu")).is_file());
    }
    let text_of = std::fs::read_to_string(root().join(case)).unwrap();
    let single = dir.join("single.toml");
    let without =
        text_of.replace("[loading]", "").replace("load_factors = [0.5, 1.0, 1.5, 2.0]", "");
    std::fs::write(&single, without.replace("f2 = [0.0, -0.001]", "f2 = [0.0, -0.002]")).unwrap();
    let out = dir.join("single").display().to_string();
    let o = piezocontact(&["run", &single.display().to_string(), "--out", &out, "-q"]);
    assert!(o.status.success(), "{}", text(&o));
    let summary = |p: &str| -> serde_json::Value {
        serde_json::from_str(&std::fs::read_to_string(dir.join(p)).unwrap()).unwrap()
    };
    let (path, single) = (summary("path/summary.json"), summary("single/summary.json"));
    let max_u = |s: &serde_json::Value| s["norms"]["max_abs_u"].as_f64().unwrap();
    assert!((max_u(&path) - max_u(&single)).abs() < 1e-12 * max_u(&single), "{path} {single}");
    assert_eq!(path["path"]["steps_solved"], 4);
    let depths = ["check", case, "--set", "loading.depths=[0.1]"];
    let o = piezocontact(&depths);
    assert!(!o.status.success() && text(&o).contains("loading.depths moves the foundation"));
}

/// Secant steps of Hencky's law that reach their cap without contact (t0 far below the
/// strains) end the run with exit code 3 and a message naming the step, and still write what
/// they have: summary.json marked unconverged with the failure, curve.csv up to that step.
#[test]
fn a_solve_without_contact_that_does_not_meet_hencky_s_law_says_so() {
    let dir = temp_dir("hencky-cap");
    let out = dir.join("out").display().to_string();
    let law = ["--set", "material.law=\"hencky\"", "--set", "material.t0=1e-16"];
    let args = [&["run", "cases/cantilever-load-factors.toml", "--out", &out][..], &law].concat();
    let o = piezocontact(&args);
    let t = text(&o);
    assert_eq!(o.status.code(), Some(3), "{t}");
    assert!(t.contains("step 1 (load factor 0.5) did not converge: the secant steps"), "{t}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("out/summary.json")).unwrap())
            .unwrap();
    assert_eq!(summary["converged"], false);
    assert!(summary["failure"].as_str().unwrap().contains("Hencky's law"), "{summary}");
    let curve = std::fs::read_to_string(dir.join("out/curve.csv")).unwrap();
    assert_eq!(curve.lines().count(), 2, "{curve}");
}
