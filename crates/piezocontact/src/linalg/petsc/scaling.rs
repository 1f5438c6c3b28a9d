//! D, the backend's symmetric scaling: the distributed matrix holds S D K D, S −1 on the ϕ
//! rows on the iterative route (both diagonal blocks then positive definite) and 1 elsewhere.

/// D of the last filled matrix.
#[derive(Debug)]
pub enum Scaling {
    /// |a_ii|^{-1/2} of each unknown, so that u and ϕ meet on equal terms in MUMPS's pivoting
    /// (the direct route; empty before the first fill).
    Unknowns(Vec<f64>),
    /// One constant per field, u then ϕ, 1/√(mean |a_ii|) over the field's rows (the
    /// iterative route): u and ϕ meet on equal terms in the Krylov norms whatever the units,
    /// the rigid-body modes of the elastic field stay those of the unscaled matrix, and no
    /// process holds a vector of the unknowns for it.
    Fields([f64; 2]),
}

impl Default for Scaling {
    fn default() -> Self {
        Self::Unknowns(Vec::new())
    }
}

impl Scaling {
    /// The iterative route's constants from each field's sum of |a_ii| and count of rows
    /// (u then ϕ, over every process); a field without rows gets 1.
    pub fn fields(sums: [f64; 2], counts: [f64; 2]) -> Self {
        let constant = |f: usize| match counts[f] > 0.0 {
            true => 1.0 / (sums[f] / counts[f]).sqrt(),
            false => 1.0,
        };
        Self::Fields([constant(0), constant(1)])
    }

    /// D's entry of unknown k, whose pivot sign is `sign` (−1: ϕ).
    pub fn of(&self, k: usize, sign: i8) -> f64 {
        match self {
            Self::Unknowns(d) => d[k],
            Self::Fields([u, phi]) => match sign < 0 {
                true => *phi,
                false => *u,
            },
        }
    }
}

/// How a matrix is written as the backend holds it: scaled by D, and on the iterative route
/// its ϕ rows negated.
#[derive(Clone, Copy, Debug)]
pub struct Scaled<'a> {
    pub scaling: &'a Scaling,
    /// +1 for u rows, −1 for ϕ rows.
    pub signs: &'a [i8],
    pub iterative: bool,
}

impl Scaled<'_> {
    /// S_i: −1 on a ϕ row on the iterative route, else 1.
    pub fn sign(&self, i: usize) -> f64 {
        if self.iterative && self.signs[i] < 0 { -1.0 } else { 1.0 }
    }

    /// The factor on unknown i's row: S_i D_i.
    pub fn row(&self, i: usize) -> f64 {
        self.sign(i) * self.column(i)
    }

    /// The factor on unknown j's column: D_j.
    pub fn column(&self, j: usize) -> f64 {
        self.scaling.of(j, self.signs[j])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_field_is_scaled_to_a_mean_diagonal_of_one() {
        // u rows with |a_ii| 4 and 16 (mean 10), ϕ rows with 0.25 (mean 0.25).
        let scaling = Scaling::fields([20.0, 0.5], [2.0, 2.0]);
        let signs = [1, 1, -1, -1];
        let scaled = Scaled { scaling: &scaling, signs: &signs, iterative: true };
        assert!((scaled.column(0).powi(2) * 10.0 - 1.0).abs() < 1e-15);
        assert_eq!(scaled.column(1), scaled.column(0), "one constant per field");
        assert!((scaled.column(3).powi(2) * 0.25 - 1.0).abs() < 1e-15);
        assert_eq!(scaled.row(3), -scaled.column(3));
        assert_eq!(Scaling::fields([1.0, 0.0], [1.0, 0.0]).of(0, -1), 1.0);
        let direct = Scaled {
            scaling: &Scaling::Unknowns(vec![0.5, 2.0]),
            signs: &[1, -1],
            iterative: false,
        };
        assert_eq!((direct.row(1), direct.column(0)), (2.0, 0.5));
    }
}
