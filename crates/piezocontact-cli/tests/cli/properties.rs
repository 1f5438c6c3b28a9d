//! Property: any case that validates either solves or fails with a typed error — never a
//! panic, never a NaN or infinity in an output file.

use piezocontact::case::Case;
use piezocontact::run::ContactRun;
use proptest::prelude::*;
use proptest::test_runner::{RngAlgorithm, TestRng, TestRunner};
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};

const PAPER_72: &str = include_str!("../../../../cases/paper-7.2.toml");

/// Overrides that span the valid (and some invalid) ranges of the case's parameters.
fn overrides() -> impl Strategy<Value = Vec<String>> {
    (
        (1usize..4, 1usize..4, 1e-2f64..1e3, -0.9f64..0.49, 1e-3f64..10.0),
        (-20.0f64..20.0, -20.0f64..20.0, -20.0f64..20.0, 1.0f64..3000.0),
        (-10.0f64..10.0, -0.5f64..1.0, 0.0f64..0.2, 0.0f64..1.5, 0.0f64..2.0),
        (1e-6f64..1e-2, 1usize..300, 1usize..15, prop::bool::ANY, prop::bool::ANY),
    )
        .prop_map(
            |(
                (nx, ny, young, poisson, t0),
                (e31, e33, e15, beta),
                (f2, gap, penetration, mu, ke),
                (eps, max_inner, max_outer, linear, pv1),
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
                o
            },
        )
}

fn finite_json(value: &serde_json::Value) -> bool {
    match value {
        serde_json::Value::Null => false,
        serde_json::Value::Array(a) => a.iter().all(finite_json),
        serde_json::Value::Object(o) => o.iter().all(|(k, v)| k == "failure" || finite_json(v)),
        _ => true,
    }
}

/// Solves one random case; returns whether it passed validation.
fn check(o: &[String]) -> Result<bool, TestCaseError> {
    // Every override names a real key with a value of the right type: the case parses.
    let case = Case::from_text(Path::new("cases/paper-7.2.toml"), PAPER_72, o)
        .map_err(|e| TestCaseError::fail(format!("{e}")))?;
    if case.problem().is_err() {
        return Ok(false); // a typed validation error
    }
    let result = std::panic::catch_unwind(|| {
        ContactRun::solve(&case).map(|run| {
            let out =
                std::env::temp_dir().join(format!("piezocontact-prop-{}", std::process::id()));
            run.write(&case, &out).map(|_| out)
        })
    });
    let Ok(outcome) = result else { return Err(TestCaseError::fail(format!("panic on {o:?}"))) };
    if let Ok(Ok(out)) = outcome {
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap())
                .unwrap();
        prop_assert!(finite_json(&summary), "non-finite number in summary.json for {o:?}");
        for file in ["contact.csv", "solution.vtu"] {
            let text = std::fs::read_to_string(out.join(file)).unwrap();
            prop_assert!(
                !text.contains("NaN") && !text.contains("inf"),
                "non-finite number in {file} for {o:?}"
            );
        }
    }
    Ok(true)
}

/// 32 random cases from a fixed seed (reproducible); most of them must pass validation, so
/// that the property is not vacuous.
#[test]
fn valid_cases_solve_or_fail_cleanly() {
    let config =
        ProptestConfig { cases: 32, failure_persistence: None, ..ProptestConfig::default() };
    let mut runner =
        TestRunner::new_with_rng(config, TestRng::deterministic_rng(RngAlgorithm::ChaCha));
    let solved = AtomicUsize::new(0);
    runner
        .run(&overrides(), |o| {
            if check(&o)? {
                solved.fetch_add(1, Ordering::SeqCst);
            }
            Ok(())
        })
        .unwrap();
    let solved = solved.load(Ordering::SeqCst);
    assert!(solved >= 24, "only {solved} of 32 random cases passed validation");
}
