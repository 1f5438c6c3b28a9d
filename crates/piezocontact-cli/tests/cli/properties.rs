//! Property: any case that validates either solves or fails with a typed error — never a
//! panic, never a NaN or infinity in an output file.

use piezocontact::Error;
use piezocontact::case::Case;
use piezocontact::run::Run;
use proptest::prelude::*;
use proptest::test_runner::{RngAlgorithm, TestRng, TestRunner};
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};

const PAPER_72: &str = include_str!("../../../../cases/paper-7.2.toml");
/// Random 2D cases (of 32) and 3D cases (of 12) that must converge, so that the property is
/// not vacuous (30 and 11 do on the fixed seed).
const MIN_2D: usize = 24;
const MIN_3D: usize = 8;
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

/// The three indenters of the 3D foundations — ball, cone, flat punch — pressed into the
/// block of cases/indentation-3d.toml (coarse mesh) by a random depth, with random size,
/// friction, problem and method. The base case's foundation keeps only its kind, so that each
/// kind's keys come from here.
fn indenters_3d() -> impl Strategy<Value = Vec<String>> {
    (0usize..3, 0.0f64..0.04, 0.1f64..1.0, 0.0f64..1.0, prop::bool::ANY, prop::bool::ANY).prop_map(
        |(kind, depth, size, mu, pv1, uzawa)| {
            let mut o = vec![
                "mesh.file=\"../meshes/indent-3d-h0.05.msh\"".to_string(),
                format!("friction.mu={mu}"),
            ];
            o.extend(match kind {
                0 => vec![
                    "foundation.kind=\"sphere\"".to_string(),
                    format!("foundation.center=[0.0, 0.0, {}]", size - depth),
                    format!("foundation.radius={size}"),
                ],
                1 => vec![
                    "foundation.kind=\"cone\"".to_string(),
                    format!("foundation.apex=[0.0, 0.0, {}]", -depth),
                    "foundation.axis=[0.0, 0.0, 1.0]".to_string(),
                    format!("foundation.half_angle={}", 45.0 + 40.0 * size),
                ],
                _ => vec![
                    "foundation.kind=\"punch\"".to_string(),
                    format!("foundation.center=[0.0, 0.0, {}]", -depth / 4.0),
                    "foundation.axis=[0.0, 0.0, 1.0]".to_string(),
                    format!("foundation.radius={}", 0.25 * size),
                ],
            });
            if pv1 {
                o.push("contact.problem=\"PV1\"".into());
            }
            if uzawa {
                o.extend(["solver.method=\"uzawa\"".into(), "solver.max_inner=2000".into()]);
            }
            o
        },
    )
}

/// How a random case ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Outcome {
    /// Refused by validation (`Case::build`), with a typed error.
    Invalid,
    /// Solved: both loops met their stopping rules.
    Converged,
    /// Run to the end and written, marked unconverged: a cap, a divergence or a numerical
    /// failure, as `solution.failure` says.
    Unconverged,
    /// Refused by the solver with an error of an allowed class: a case it cannot solve on
    /// this machine (`Input`: a contact zone larger than `solver.max_condensed`, memory), a
    /// singular or non-finite solve.
    Refused,
}

/// The class of an error, under its file location.
fn class(e: &Error) -> &Error {
    match e {
        Error::Located { error, .. } => class(error),
        e => e,
    }
}

/// Solves one random case of `path` (text `base`) and says how it ended; a panic, a NaN in
/// an output or an error of another class fails the property.
fn check(path: &str, base: &str, o: &[String]) -> Result<Outcome, TestCaseError> {
    // Every override names a real key with a value of the right type: the case parses.
    let case = Case::from_text(&super::common::root().join(path), base, o)
        .map_err(|e| TestCaseError::fail(format!("{e}")))?;
    let Ok(built) = case.build() else { return Ok(Outcome::Invalid) };
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        let solved = built.linear_solver().and_then(|solver| Run::solve(&built, solver, &|_| {}));
        solved.and_then(|run| {
            static RUN: AtomicUsize = AtomicUsize::new(0);
            let k = RUN.fetch_add(1, Ordering::SeqCst);
            let out =
                std::env::temp_dir().join(format!("piezocontact-prop-{}-{k}", std::process::id()));
            run.write(&built, &out, Default::default()).map(|_| (out, run.error().cloned()))
        })
    }));
    let Ok(outcome) = result else { return Err(TestCaseError::fail(format!("panic on {o:?}"))) };
    let (out, failure) = match outcome {
        Ok(written) => written,
        Err(e) => {
            let allowed = matches!(
                class(&e),
                Error::Input(_) | Error::SingularSystem { .. } | Error::NonFinite { .. }
            );
            prop_assert!(allowed, "an error of an unexpected class for {o:?}: {e:?}");
            return Ok(Outcome::Refused);
        }
    };
    let checked = check_written(&out, failure, o);
    if checked.is_ok() {
        let _ = std::fs::remove_dir_all(&out); // kept for a look when the property fails
    }
    checked
}

/// Checks the files of one random case written into `out` (no NaN, strict outputs, the
/// convergence flag that matches `failure`) and says how it ended.
fn check_written(
    out: &Path,
    failure: Option<Error>,
    o: &[String],
) -> Result<Outcome, TestCaseError> {
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let nulls = super::common::null_paths(&summary);
    prop_assert!(nulls.is_empty(), "non-finite numbers in summary.json at {nulls:?} for {o:?}");
    super::common::assert_strict_outputs(out); // and contact.csv
    let finite = super::common::finite_vtu(&out.join("solution.vtu"));
    prop_assert!(finite, "NaN in solution.vtu: {o:?}");
    prop_assert_eq!(summary["converged"].as_bool(), Some(failure.is_none()));
    let Some(failure) = failure else { return Ok(Outcome::Converged) };
    let allowed = matches!(
        failure,
        Error::NotConverged { .. } | Error::Diverged { .. } | Error::NumericalFailure { .. }
    );
    prop_assert!(allowed, "an unconverged run with a failure of another class: {failure:?}");
    Ok(Outcome::Unconverged)
}

/// Runs `cases` random cases of `strategy` on the case `path` (text `base`) from a fixed
/// seed (reproducible); returns how many ended each way.
fn run_random(
    path: &str,
    base: &str,
    cases: u32,
    strategy: impl Strategy<Value = Vec<String>>,
) -> Vec<(Outcome, usize)> {
    let config = ProptestConfig { cases, failure_persistence: None, ..ProptestConfig::default() };
    let mut runner =
        TestRunner::new_with_rng(config, TestRng::deterministic_rng(RngAlgorithm::ChaCha));
    let outcomes = std::sync::Mutex::new(Vec::new());
    runner
        .run(&strategy, |o| {
            let outcome = check(path, base, &o)?;
            outcomes.lock().unwrap().push(outcome);
            Ok(())
        })
        .unwrap();
    let outcomes = outcomes.into_inner().unwrap();
    let tally = [Outcome::Invalid, Outcome::Converged, Outcome::Unconverged, Outcome::Refused]
        .map(|kind| (kind, outcomes.iter().filter(|o| **o == kind).count()));
    println!("{path}: {tally:?}");
    tally.to_vec()
}

/// The number of cases that ended as `kind`.
fn count(tally: &[(Outcome, usize)], kind: Outcome) -> usize {
    tally.iter().find(|(k, _)| *k == kind).map_or(0, |(_, n)| *n)
}

/// 32 random 2D cases, Uzawa and Newton; most of them must be solved, so that the property is
/// not vacuous.
#[test]
fn valid_cases_solve_or_fail_cleanly() {
    let tally = run_random("cases/paper-7.2.toml", PAPER_72, 32, overrides());
    let converged = count(&tally, Outcome::Converged);
    assert!(converged >= MIN_2D, "only {converged} of 32 random cases converged: {tally:?}");
}

/// 12 random indentations by a ball, a cone or a punch, Uzawa and Newton.
#[test]
fn valid_3d_indenters_solve_or_fail_cleanly() {
    let dropped =
        |l: &&str| l.starts_with("center = [0.0, 0.0, 0.98]") || l.starts_with("radius = ");
    let base: String =
        INDENTATION.lines().filter(|l| !dropped(l)).map(|l| format!("{l}\n")).collect();
    assert_eq!(base.lines().count() + 2, INDENTATION.lines().count(), "the base case changed");
    let tally = run_random("cases/indentation-3d.toml", &base, 12, indenters_3d());
    let converged = count(&tally, Outcome::Converged);
    assert!(converged >= MIN_3D, "only {converged} of 12 random indenters converged: {tally:?}");
}

/// 12 random 3D indentations (sphere foundation), Uzawa and Newton.
#[test]
fn valid_3d_cases_solve_or_fail_cleanly() {
    let tally = run_random("cases/indentation-3d.toml", INDENTATION, 12, overrides_3d());
    let converged = count(&tally, Outcome::Converged);
    assert!(converged >= MIN_3D, "only {converged} of 12 random 3D cases converged: {tally:?}");
}
