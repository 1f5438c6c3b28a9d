//! The quarter model: the ball indentation of cases/indentation-quarter.toml on a quarter of
//! the block, on rollers on its two symmetry planes (Γ3 nodes on a plane slide along it
//! only), against the whole block meshed by mirroring the quarter mesh node for node
//! (meshes/mirror-quarter.py): the exact solver gives the whole block's nodal fields at the
//! quarter's nodes, PV1 and PV2 with local friction.

use super::common::{contact_run, mesh_file};
use piezocontact::case::Case;
use piezocontact::run::ContactRun;
use std::collections::HashMap;
use std::path::PathBuf;

/// The committed quarter case on the mesh `mesh`, with the overrides `sets`; without its
/// symmetry supports when `whole`; with rollers that fix the normal on them when `turned`.
fn indentation(mesh: &str, whole: bool, sets: &[&str]) -> (piezocontact::case::Built, ContactRun) {
    indentation_on(mesh, (whole, false), sets)
}

fn indentation_on(
    mesh: &str,
    (whole, turned): (bool, bool),
    sets: &[&str],
) -> (piezocontact::case::Built, ContactRun) {
    let file =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../cases/indentation-quarter.toml");
    let mut text = std::fs::read_to_string(&file).unwrap();
    if whole {
        let start = text.find("[[boundary.support]]").unwrap();
        let end = text.find("[contact]").unwrap();
        text.replace_range(start..end, "");
    }
    if turned {
        text = text
            .replace("fix = [\"x\"]", "fix = [\"normal\"]")
            .replace("fix = [\"y\"]", "fix = [\"normal\"]");
    }
    let mut overrides: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    overrides.push(format!("mesh.file={:?}", mesh_file(mesh).display().to_string()));
    let built = Case::from_text(&file, &text, &overrides).unwrap().build().unwrap();
    let run = contact_run(&built);
    let exact = !sets.iter().any(|s| s.contains("uzawa"));
    let kkt = run.solution.kkt.max;
    assert!(run.solution.converged() && (kkt < 1e-10 || !exact), "{:?}", run.solution.kkt);
    (built, run)
}

/// The largest difference of u and of ϕ between the quarter and the whole block at the
/// quarter's nodes, each relative to the field's largest value on the whole block.
fn differences(sets: &[&str]) -> (f64, f64) {
    let (quarter, q) = indentation("indent-quarter-h0.05.msh", false, sets);
    let (whole, w) = indentation("indent-full-h0.05.msh", true, sets);
    let key = |p: &[f64]| p.iter().map(|c| c.to_bits()).collect::<Vec<_>>();
    let whole_mesh = &whole.problem.mesh;
    let at: HashMap<Vec<u64>, usize> =
        (0..whole_mesh.n_nodes()).map(|a| (key(whole_mesh.node(a)), a)).collect();
    let (qd, wd) = (&q.solution.dofs, &w.solution.dofs);
    let u_max = (0..whole_mesh.n_nodes() * 3).map(|g| w.solution.x[g].abs()).fold(0.0, f64::max);
    let phi_max =
        (0..whole_mesh.n_nodes()).map(|a| w.solution.x[wd.phi(a)].abs()).fold(0.0, f64::max);
    let (mut du, mut dphi) = (0.0f64, 0.0f64);
    let mesh = &quarter.problem.mesh;
    for a in 0..mesh.n_nodes() {
        let b = at[&key(mesh.node(a))];
        for k in 0..3 {
            du = du.max((q.solution.x[qd.u(a, k)] - w.solution.x[wd.u(b, k)]).abs());
        }
        dphi = dphi.max((q.solution.x[qd.phi(a)] - w.solution.x[wd.phi(b)]).abs());
    }
    assert!(u_max > 0.01 && phi_max > 0.0, "{u_max} {phi_max}");
    (du / u_max, dphi / phi_max)
}

#[test]
fn the_quarter_model_gives_the_whole_block_s_fields_with_friction() {
    let (du, dphi) = differences(&[]);
    assert!(du < 1e-8 && dphi < 1e-8, "PV2: u {du:e}, ϕ {dphi:e}");
}

#[test]
fn the_quarter_model_gives_the_whole_block_s_fields_without_friction() {
    let (du, dphi) = differences(&["contact.problem=\"PV1\""]);
    assert!(du < 1e-8 && dphi < 1e-8, "PV1: u {du:e}, ϕ {dphi:e}");
}

#[test]
fn uzawa_on_the_quarter_model_follows_uzawa_on_the_whole_block() {
    let (du, dphi) = differences(&["solver.method=\"uzawa\""]);
    assert!(du < 1e-8 && dphi < 1e-8, "Uzawa: u {du:e}, ϕ {dphi:e}");
}

/// The quarter turned by 30° about z (meshes/mirror-quarter.py --turn 30): its symmetry
/// planes lie along no axis, and rollers that fix their normal hold them (turned frames at
/// their nodes, Γ3's among them). The ball, the block and the material are symmetric about z,
/// so u(R p) = R u(p) and ϕ(R p) = ϕ(p), to 1e−8 of each field's largest value, with
/// friction (exact solver and Uzawa) and without.
#[test]
fn the_turned_quarter_on_normal_rollers_is_the_quarter_turned() {
    let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
    for sets in [&[][..], &["contact.problem=\"PV1\""], &["solver.method=\"uzawa\""]] {
        let (quarter, q) = indentation("indent-quarter-h0.05.msh", false, sets);
        let (turned, t) = indentation_on("indent-quarter-turned-h0.05.msh", (false, true), sets);
        let on_planes =
            t.solution.surface.nodes.iter().filter(|&&n| t.solution.dofs.frame(n).is_some());
        assert!(on_planes.count() > 5, "Γ3 nodes in turned frames");
        let (mesh, turned_mesh) = (&quarter.problem.mesh, &turned.problem.mesh);
        let (qd, td) = (&q.solution.dofs, &t.solution.dofs);
        let u_max = (0..mesh.n_nodes() * 3).map(|g| q.solution.x[g].abs()).fold(0.0, f64::max);
        let phi_max =
            (0..mesh.n_nodes()).map(|a| q.solution.x[qd.phi(a)].abs()).fold(0.0, f64::max);
        let (mut du, mut dphi) = (0.0f64, 0.0f64);
        for a in 0..mesh.n_nodes() {
            let p = mesh.node(a);
            let rp = [c * p[0] - s * p[1], s * p[0] + c * p[1], p[2]];
            let distance =
                |b: usize| (0..3).map(|k| (turned_mesh.node(b)[k] - rp[k]).powi(2)).sum::<f64>();
            let b = (0..turned_mesh.n_nodes())
                .min_by(|&i, &j| distance(i).total_cmp(&distance(j)))
                .unwrap();
            assert!(distance(b) < 1e-20, "no node at {rp:?}");
            let u = |k: usize| q.solution.x[qd.u(a, k)];
            let ru = [c * u(0) - s * u(1), s * u(0) + c * u(1), u(2)];
            for k in 0..3 {
                du = du.max((t.solution.x[td.u(b, k)] - ru[k]).abs());
            }
            dphi = dphi.max((t.solution.x[td.phi(b)] - q.solution.x[qd.phi(a)]).abs());
        }
        let (du, dphi) = (du / u_max, dphi / phi_max);
        assert!(du < 1e-8 && dphi < 1e-8, "{sets:?}: u {du:e}, ϕ {dphi:e}");
    }
}
