//! A problem with some parameters tied together: the full problem's
//! parameter `i` takes the reduced one `map[i]` (a symmetric car: the right
//! chain's values are the left's). The reduced Jacobian is `J A` with
//! `A_{i,map[i]} = 1`, its normal equations `Aᵀ JᵀJ A` and `Aᵀ Jᵀr`: a
//! staged search fits the tied problem first and starts the full one from
//! it (issue 44, item 3).
//!
//! ```
//! use bumpsim_estimate::lm::LeastSquares;
//! use bumpsim_estimate::tied::Tied;
//! use nalgebra::DMatrix;
//! struct Two;
//! impl LeastSquares for Two {
//!     fn residual_count(&self) -> usize { 2 }
//!     fn parameter_count(&self) -> usize { 2 }
//!     fn evaluate(&self, p: &[f64], r: &mut [f64], j: Option<&mut DMatrix<f64>>) -> bool {
//!         r[0] = p[0] - 1.0;
//!         r[1] = p[1] - 3.0;
//!         if let Some(j) = j { j.fill(0.0); j[(0, 0)] = 1.0; j[(1, 1)] = 1.0; }
//!         true
//!     }
//! }
//! let tied = Tied::new(Two, vec![0, 0]).unwrap();
//! assert_eq!(tied.parameter_count(), 1);
//! assert_eq!(tied.expand(&[2.0]), vec![2.0, 2.0]);
//! ```

use crate::lm::LeastSquares;
use nalgebra::{DMatrix, DVector};

/// A map that does not fit its problem.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "a tie map of {given} entries for a problem of {count} parameters must cover each and use every reduced index 0..{reduced}"
)]
pub struct TieError {
    /// Entries given.
    pub given: usize,
    /// The problem's parameters.
    pub count: usize,
    /// Reduced parameters the map implies.
    pub reduced: usize,
}

/// The problem `P` with parameters tied by a map (see the module).
#[derive(Debug, Clone)]
pub struct Tied<P> {
    problem: P,
    map: Vec<usize>,
    reduced: usize,
}

impl<P: LeastSquares> Tied<P> {
    /// `problem` whose parameter `i` is the reduced parameter `map[i]`;
    /// every index `0..max(map)` must occur.
    pub fn new(problem: P, map: Vec<usize>) -> Result<Tied<P>, TieError> {
        let reduced = map.iter().max().map_or(0, |m| m + 1);
        let count = problem.parameter_count();
        let error = TieError {
            given: map.len(),
            count,
            reduced,
        };
        if map.len() != count || (0..reduced).any(|j| !map.contains(&j)) {
            return Err(error);
        }
        Ok(Tied {
            problem,
            map,
            reduced,
        })
    }

    /// The map: full parameter `i` is reduced parameter `map[i]`.
    pub fn map(&self) -> &[usize] {
        &self.map
    }

    /// The full parameters of reduced `q`.
    pub fn expand(&self, q: &[f64]) -> Vec<f64> {
        self.map.iter().map(|&j| q[j]).collect()
    }

    /// The reduced parameters of full `p`: each the mean of those tied to it.
    pub fn reduce(&self, p: &[f64]) -> Vec<f64> {
        (0..self.reduced)
            .map(|j| {
                let tied: Vec<f64> = (0..p.len())
                    .filter(|&i| self.map[i] == j)
                    .map(|i| p[i])
                    .collect();
                tied.iter().sum::<f64>() / tied.len() as f64
            })
            .collect()
    }
}

impl<P: LeastSquares> LeastSquares for Tied<P> {
    fn residual_count(&self) -> usize {
        self.problem.residual_count()
    }

    fn parameter_count(&self) -> usize {
        self.reduced
    }

    fn evaluate(&self, q: &[f64], r: &mut [f64], jacobian: Option<&mut DMatrix<f64>>) -> bool {
        let p = self.expand(q);
        let Some(jac) = jacobian else {
            return self.problem.evaluate(&p, r, None);
        };
        let mut full = DMatrix::zeros(r.len(), p.len());
        let ok = self.problem.evaluate(&p, r, Some(&mut full));
        jac.fill(0.0);
        for (i, &j) in self.map.iter().enumerate() {
            let column = full.column(i).clone_owned();
            let mut target = jac.column_mut(j);
            target += column;
        }
        ok
    }

    fn normal(
        &self,
        q: &[f64],
        r: &mut [f64],
        jtj: &mut DMatrix<f64>,
        gradient: &mut DVector<f64>,
    ) -> bool {
        let p = self.expand(q);
        let n = p.len();
        let (mut full, mut g) = (DMatrix::zeros(n, n), DVector::zeros(n));
        let ok = self.problem.normal(&p, r, &mut full, &mut g);
        jtj.fill(0.0);
        gradient.fill(0.0);
        for a in 0..n {
            gradient[self.map[a]] += g[a];
            for b in 0..n {
                jtj[(self.map[a], self.map[b])] += full[(a, b)];
            }
        }
        ok
    }

    /// The full problem's `Jᵀv`, each tied group's entries summed.
    fn transposed(&self, q: &[f64], v: &[f64], product: &mut DVector<f64>) -> bool {
        let p = self.expand(q);
        let mut full = DVector::zeros(p.len());
        if !self.problem.transposed(&p, v, &mut full) {
            return false;
        }
        product.fill(0.0);
        for (a, &j) in self.map.iter().enumerate() {
            product[j] += full[a];
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    struct Quadratic;
    impl LeastSquares for Quadratic {
        fn residual_count(&self) -> usize {
            3
        }
        fn parameter_count(&self) -> usize {
            3
        }
        fn evaluate(&self, p: &[f64], r: &mut [f64], j: Option<&mut DMatrix<f64>>) -> bool {
            r[0] = p[0] * p[1] - 1.0;
            r[1] = p[2] - 2.0;
            r[2] = p[0] + p[2];
            if let Some(j) = j {
                j.fill(0.0);
                j[(0, 0)] = p[1];
                j[(0, 1)] = p[0];
                j[(1, 2)] = 1.0;
                j[(2, 0)] = 1.0;
                j[(2, 2)] = 1.0;
            }
            true
        }
    }

    #[test]
    fn the_tied_jacobian_and_normal_equations_are_the_sums_of_the_columns() {
        let tied = Tied::new(Quadratic, vec![0, 1, 0]).unwrap();
        let q = [0.7, -0.4];
        let mut r = vec![0.0; 3];
        let mut jac = DMatrix::zeros(3, 2);
        assert!(tied.evaluate(&q, &mut r, Some(&mut jac)));
        for j in 0..2 {
            let mut s = q;
            s[j] += 1e-7;
            let mut rs = vec![0.0; 3];
            tied.evaluate(&s, &mut rs, None);
            for i in 0..3 {
                assert_relative_eq!((rs[i] - r[i]) / 1e-7, jac[(i, j)], epsilon = 1e-5);
            }
        }
        let (mut jtj, mut g) = (DMatrix::zeros(2, 2), DVector::zeros(2));
        assert!(tied.normal(&q, &mut r, &mut jtj, &mut g));
        assert_relative_eq!(jtj, jac.transpose() * &jac, epsilon = 1e-12);
        assert_eq!(tied.reduce(&[1.0, 5.0, 3.0]), vec![2.0, 5.0]);
        assert!(Tied::new(Quadratic, vec![0, 2, 0]).is_err());
        assert!(Tied::new(Quadratic, vec![0, 1]).is_err());
    }
}
