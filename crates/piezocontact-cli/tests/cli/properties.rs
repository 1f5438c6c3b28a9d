//! Property: any case that validates either solves or fails with a typed error — never a
//! panic, never a NaN or infinity in an output file.

use piezocontact::case::Case;
use piezocontact::run::ContactRun;
use proptest::prelude::*;
use proptest::test_runner::{RngAlgorithm, TestRng, TestRunner};
use std::sync::atomic::{AtomicUsize, Ordering};

const PAPER_72: &str = include_str!("../../../../cases/paper-7.2.toml");
const INDENTATION: &str = include_str!("../../../../cases/indentation-3d.toml");

/// Overrides that span the valid (and some invalid) ranges of the case's parameters.
fn overrides() -> impl Strategy<Value = Vec<String>> {
    (
        (1usize..4, 1usize..4, 1e-2f64..1e3, -0.9f64..0.49, 1e-3f64..10.0),
        (-20.0f64..20.0, -20.0f64..20.0, -20.0f64..20.0, 1.0f64..3000.0),
        (-10.0f64..10.0, -0.5f64..1.0, 0.0f64..0.2, 0.0f64..1.5, 0.0f64..2.0),
        (1e-6f64..1e-2, 1usize..300, 1usize..15, prop::bool::ANY, prop::bool::ANY),
        prop::bool::ANY,
    )
        .prop_map(
            |(
                (nx, ny, young, poisson, t0),
                (e31, e33, e15, beta),
                (f2, gap, penetration, mu, ke),
                (eps, max_inner, max_outer, linear, pv1),
                newton,
            )| {
                let mut o = vec![
                    format!("mesh.nx={}", 6 * nx), // nodes at x = 2 and 10, the ends of Γ3
                    format!("mesh.ny={ny}"),
                    format!("material.young={young}"),
                    format!("material.poisson={poisson}"),
                    format!("material.t0={t0}"),
                    format!("material.e31={e31}"),
                    format!("material.e33={e33}"),
                    format!("material.e15={e15}"),
                    format!("material.beta11_rel={beta}"),
                    format!("boundary.traction=[{{parts=[\"load\"], f2=[0.0, {f2}]}}]"),
                    format!("contact.gap={gap}"),
                    format!("contact.penetration={penetration}"),
                    format!("friction.mu={mu}"),
                    format!("conductivity.ke={ke}"),
                    format!("solver.eps={eps}"),
                    format!("solver.eps_fp={eps}"),
                    format!("solver.max_inner={max_inner}"),
                    format!("solver.max_outer={max_outer}"),
                    format!("solver.r={}", 0.25 * young),
                ];
                if linear {
                    o.push("material.law=\"linear\"".into());
                }
                if pv1 {
                    o.push("contact.problem=\"PV1\"".into());
                }
                if newton {
                    o.push("solver.method=\"newton\"".into());
                }
                o
            },
        )
}

/// Overrides of cases/indentation-3d.toml on its coarse mesh: material, ball (depth and
/// radius), friction, penetration, problem, law and method.
fn overrides_3d() -> impl Strategy<Value = Vec<String>> {
    (
        (1e-1f64..1e3, -0.9f64..0.49, -20.0f64..20.0, -20.0f64..20.0, 1.0f64..3000.0),
        (-0.05f64..0.1, 0.2f64..3.0, 0.0f64..1.5, 0.0f64..0.05),
        (prop::bool::ANY, prop::bool::ANY, prop::bool::ANY, 1usize..40),
    )
        .prop_map(
            |(
                (young, poisson, e33, e15, beta),
                (depth, radius, mu, penetration),
                (linear, pv1, uzawa, max_inner),
            )| {
                let mut o = vec![
                    "mesh.file=\"../meshes/indent-3d-h0.05.msh\"".to_string(),
                    format!("material.young={young}"),
                    format!("material.poisson={poisson}"),
                    format!("material.e33={e33}"),
                    format!("material.e15={e15}"),
                    format!("material.beta33_rel={beta}"),
                    format!("foundation.center=[0.0, 0.0, {}]", radius - depth),
                    format!("foundation.radius={radius}"),
                    format!("friction.mu={mu}"),
                    format!("contact.penetration={penetration}"),
                    format!("solver.max_inner={}", if uzawa { 100 * max_inner } else { max_inner }),
                ];
                if linear {
                    o.push("material.law=\"linear\"".into());
                }
                if pv1 {
                    o.push("contact.problem=\"PV1\"".into());
                }
                if uzawa {
                    o.push("solver.method=\"uzawa\"".into());
                }
                o
            },
        )
}

/// Solves one random case of `path` (text `base`); returns whether it passed validation.
fn check(path: &str, base: &str, o: &[String]) -> Result<bool, TestCaseError> {
    // Every override names a real key with a value of the right type: the case parses.
    let case = Case::from_text(&super::common::root().join(path), base, o)
        .map_err(|e| TestCaseError::fail(format!("{e}")))?;
    if case.problem().is_err() {
        return Ok(false); // a typed validation error
    }
    let result = std::panic::catch_unwind(|| {
        ContactRun::solve(&case).map(|run| {
            static RUN: AtomicUsize = AtomicUsize::new(0);
            let k = RUN.fetch_add(1, Ordering::SeqCst);
            let out =
                std::env::temp_dir().join(format!("piezocontact-prop-{}-{k}", std::process::id()));
            run.write(&case, &out).map(|_| out)
        })
    });
    let Ok(outcome) = result else { return Err(TestCaseError::fail(format!("panic on {o:?}"))) };
    if let Ok(Ok(out)) = outcome {
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap())
                .unwrap();
        let nulls = super::common::null_paths(&summary);
        prop_assert!(nulls.is_empty(), "non-finite numbers in summary.json at {nulls:?} for {o:?}");
        super::common::assert_strict_outputs(&out); // and contact.csv
        let vtu = std::fs::read_to_string(out.join("solution.vtu")).unwrap();
        prop_assert!(!vtu.contains("NaN") && !vtu.contains("inf"), "NaN in solution.vtu: {o:?}");
    }
    Ok(true)
}

/// Runs `cases` random cases of `strategy` on the case `path` (text `base`) from a fixed
/// seed (reproducible); returns how many passed validation.
fn run_random(
    path: &str,
    base: &str,
    cases: u32,
    strategy: impl Strategy<Value = Vec<String>>,
) -> usize {
    let config = ProptestConfig { cases, failure_persistence: None, ..ProptestConfig::default() };
    let mut runner =
        TestRunner::new_with_rng(config, TestRng::deterministic_rng(RngAlgorithm::ChaCha));
    let solved = AtomicUsize::new(0);
    runner
        .run(&strategy, |o| {
            if check(path, base, &o)? {
                solved.fetch_add(1, Ordering::SeqCst);
            }
            Ok(())
        })
        .unwrap();
    solved.load(Ordering::SeqCst)
}

/// 32 random 2D cases, Uzawa and Newton; most of them must pass validation, so that the
/// property is not vacuous.
#[test]
fn valid_cases_solve_or_fail_cleanly() {
    let solved = run_random("cases/paper-7.2.toml", PAPER_72, 32, overrides());
    assert!(solved >= 24, "only {solved} of 32 random cases passed validation");
}

/// 12 random 3D indentations (sphere foundation), Uzawa and Newton.
#[test]
fn valid_3d_cases_solve_or_fail_cleanly() {
    let solved = run_random("cases/indentation-3d.toml", INDENTATION, 12, overrides_3d());
    assert!(solved >= 8, "only {solved} of 12 random 3D cases passed validation");
}
