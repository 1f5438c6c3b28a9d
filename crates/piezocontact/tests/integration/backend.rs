//! The linear-solver seam from outside the library: a dense LU backend written here, with
//! the Schur-complement capability, gives the same contact solutions as the default sparse
//! LDLᵀ; a backend without that capability is refused by the exact solver when the run is
//! set up, before any factorisation.

use super::common::{PAPER_UNITS, paper_model, paper_problem, paper_settings};
use faer::Mat;
use faer::linalg::solvers::{PartialPivLu, Solve};
use piezocontact::algorithm::condensed::Guess;
use piezocontact::algorithm::newton::{self, Newton};
use piezocontact::algorithm::{ContactSolution, Settings, solve_contact, solve_contact_with};
use piezocontact::linalg::{
    DenseMatrix, LinearSolver, SchurComplement, SolverStats, SymmetricMatrix, SymmetricPattern,
};
use piezocontact::material::ElasticLaw;
use piezocontact::{Error, Result};
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Dense LU with partial pivoting of the whole matrix: slow, simple and independent of the
/// library's factorisation.
#[derive(Debug, Default)]
struct DenseLu {
    n: usize,
    matrix: Option<Mat<f64>>,
    lu: Option<PartialPivLu<f64>>,
    last: Vec<usize>,
    stats: SolverStats,
    /// Numeric factorisations asked of it, seen from outside.
    factorisations: Arc<AtomicUsize>,
}

impl LinearSolver for DenseLu {
    fn name(&self) -> &str {
        "dense-lu"
    }

    fn analyze(&mut self, pattern: &SymmetricPattern, _signs: &[i8]) -> Result<()> {
        (self.n, self.last) = (pattern.n(), Vec::new());
        Ok(())
    }

    fn factorize(&mut self, matrix: &SymmetricMatrix) -> Result<()> {
        let mut a = Mat::<f64>::zeros(self.n, self.n);
        for (i, j, v) in matrix.lower_entries() {
            (a[(i, j)], a[(j, i)]) = (v, v);
        }
        self.lu = Some(a.partial_piv_lu());
        self.matrix = Some(a);
        self.stats.numeric_count += 1;
        self.factorisations.fetch_add(1, Ordering::SeqCst);
        Ok(())
    }

    fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<()> {
        let lu = self.lu.as_ref().ok_or_else(|| Error::LinearAlgebra("not factorised".into()))?;
        lu.solve_in_place(faer::MatMut::from_column_major_slice_mut(rhs, self.n, 1));
        self.stats.solve_count += 1;
        Ok(())
    }

    fn stats(&self) -> SolverStats {
        self.stats
    }

    fn schur(&mut self) -> Option<&mut dyn SchurComplement> {
        Some(self)
    }
}

impl SchurComplement for DenseLu {
    fn analyze_with_last(
        &mut self,
        pattern: &SymmetricPattern,
        signs: &[i8],
        last: &[usize],
    ) -> Result<()> {
        self.analyze(pattern, signs)?;
        self.last = last.to_vec();
        Ok(())
    }

    /// S = A_cc − A_ci A_ii⁻¹ A_ic, straight from the definition.
    fn schur_complement(&self) -> Result<DenseMatrix> {
        let a = self.matrix.as_ref().ok_or_else(|| Error::LinearAlgebra("no matrix".into()))?;
        let mut is_last = vec![false; self.n];
        self.last.iter().for_each(|&k| is_last[k] = true);
        let interior: Vec<usize> = (0..self.n).filter(|&k| !is_last[k]).collect();
        let (c, m) = (&self.last, self.last.len());
        let a_ii = Mat::<f64>::from_fn(interior.len(), interior.len(), |p, q| {
            a[(interior[p], interior[q])]
        });
        let mut a_ic = Mat::<f64>::from_fn(interior.len(), m, |p, q| a[(interior[p], c[q])]);
        a_ii.partial_piv_lu().solve_in_place(a_ic.as_mut());
        let mut schur = DenseMatrix::zeros(m);
        for p in 0..m {
            for q in 0..m {
                let coupling: f64 =
                    (0..interior.len()).map(|k| a[(c[p], interior[k])] * a_ic[(k, q)]).sum();
                schur.set(p, q, a[(c[p], c[q])] - coupling);
            }
        }
        Ok(schur)
    }
}

/// The same backend without the Schur-complement capability.
#[derive(Debug, Default)]
struct WithoutSchur(DenseLu);

impl LinearSolver for WithoutSchur {
    fn name(&self) -> &str {
        "dense-lu without Schur complements"
    }
    fn analyze(&mut self, pattern: &SymmetricPattern, signs: &[i8]) -> Result<()> {
        self.0.analyze(pattern, signs)
    }
    fn factorize(&mut self, matrix: &SymmetricMatrix) -> Result<()> {
        self.0.factorize(matrix)
    }
    fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<()> {
        self.0.solve_in_place(rhs)
    }
    fn stats(&self) -> SolverStats {
        self.0.stats()
    }
}

fn newton_settings() -> Settings {
    let r = 0.25 * PAPER_UNITS.stress(58.7102);
    let parameters = newton::Parameters {
        r,
        tol: 1e-10,
        max_inner: 100,
        max_condensed: Some(2000),
        guess: Guess::Nearest(2000),
    };
    Settings::new(Newton::new(parameters), 20)
}

/// The largest differences of two solutions in u and in ϕ, each relative to the largest value
/// of its field.
fn difference(a: &ContactSolution, b: &ContactSolution, n_u: usize) -> f64 {
    let relative = |p: &[f64], q: &[f64]| {
        let size = p.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        p.iter().zip(q).map(|(p, q)| (p - q).abs()).fold(0.0, f64::max) / size
    };
    let (u_a, phi_a) = a.x.split_at(n_u);
    let (u_b, phi_b) = b.x.split_at(n_u);
    relative(u_a, u_b).max(relative(phi_a, phi_b))
}

#[test]
fn a_backend_from_outside_gives_the_default_solution() {
    let problem = paper_problem(24, 4, PAPER_UNITS, ElasticLaw::Hencky { t0: 1.8 });
    for (name, model) in [
        ("PV1", paper_model(None, 0.05, PAPER_UNITS)),
        ("PV2", paper_model(Some((0.6, 1.0)), 0.05, PAPER_UNITS)),
    ] {
        for settings in [newton_settings(), paper_settings(PAPER_UNITS, 1e-8)] {
            let method = settings.method.name();
            let default = solve_contact(&problem, &model, &settings).unwrap();
            let backend = DenseLu::default();
            let counter = backend.factorisations.clone();
            let outside =
                solve_contact_with(&problem, &model, &settings, Box::new(backend), &|_| {})
                    .unwrap();
            assert!(default.converged() && outside.converged(), "{name} {method}");
            assert_eq!(default.outer_iterations(), outside.outer_iterations(), "{name} {method}");
            assert_eq!(outside.timings.solver.numeric_count, counter.load(Ordering::SeqCst));
            assert!(outside.timings.solver.numeric_count >= 1);
            let d = difference(&default, &outside, 2 * problem.mesh.n_nodes());
            println!("{name} {method}: relative difference {d:.1e}");
            assert!(d < 1e-9, "{name} {method}: the backends differ by {d:e}");
            let (k_default, k_outside) = (default.kkt.max, outside.kkt.max);
            assert!(
                (k_default - k_outside).abs() <= 1e-12 + 1e-3 * k_default,
                "{name} {method}: KKT {k_default:e} against {k_outside:e}"
            );
        }
    }
}

/// On a backend without the Schur-complement capability the exact solver runs on the whole
/// system (model §11), its Newton steps solved by a sparse LU: the default backend's solution
/// (condensed onto Γ3) to 1e−9, with the KKT residual within the tolerance; Uzawa, which needs
/// no Schur complement, runs on it as before.
#[test]
fn a_backend_without_schur_complements_runs_the_exact_solver_on_the_whole_system() {
    let problem = paper_problem(24, 4, PAPER_UNITS, ElasticLaw::Hencky { t0: 1.8 });
    for (name, model) in [
        ("PV1", paper_model(None, 0.05, PAPER_UNITS)),
        ("PV2", paper_model(Some((0.6, 1.0)), 0.05, PAPER_UNITS)),
    ] {
        let settings = newton_settings();
        let default = solve_contact(&problem, &model, &settings).unwrap();
        let backend = WithoutSchur::default();
        let whole =
            solve_contact_with(&problem, &model, &settings, Box::new(backend), &|_| {}).unwrap();
        assert!(default.converged() && whole.converged(), "{name}: {:?}", whole.failure);
        assert!(whole.kkt.max <= 1e-10, "{name}: KKT {:?}", whole.kkt);
        let d = difference(&default, &whole, 2 * problem.mesh.n_nodes());
        assert!(d < 1e-9, "{name}: the whole system's solution differs by {d:e}");
    }
    let model = paper_model(Some((0.6, 1.0)), 0.0, PAPER_UNITS);
    let problem = paper_problem(24, 4, PAPER_UNITS, ElasticLaw::Linear);
    let settings = paper_settings(PAPER_UNITS, 1e-6);
    let solution =
        solve_contact_with(&problem, &model, &settings, Box::new(WithoutSchur::default()), &|_| {})
            .unwrap();
    assert!(solution.converged() && solution.kkt.max < 1e-4, "{:?}", solution.kkt);
}
