//! The trust-region subproblem of Levenberg–Marquardt (Moré 1978).
//!
//! On the free parameters, with the scaling `d_i = √(JᵀJ)_ii` (the column
//! norms of J, floored at 1e-6 of the largest), the step is
//! `δ = D⁻¹ s(λ)` with `s(λ) = −(A + λI)⁻¹ b`, `A = D⁻¹ JᵀJ D⁻¹` and
//! `b = D⁻¹ Jᵀr`: the Gauss–Newton step (λ = 0) when its scaled length
//! `‖s(0)‖` lies within the radius Δ, else the λ > 0 with `‖s(λ)‖ = Δ`
//! (within 10 %, as MINPACK's `lmpar`). With `A = V Λ Vᵀ` and `c = Vᵀ b`,
//! `‖s(λ)‖² = Σ c_i² / (Λ_i + λ)²`; λ is found by Newton's method on
//! `ψ(λ) = 1/‖s(λ)‖ − 1/Δ`, which is concave and increasing, so that the
//! iterates rise monotonically to the root from the lower bound
//! `‖c‖/Δ − max Λ` (Moré & Sorensen 1983). The radius is updated by the
//! caller from the gain ratio ρ: after an accepted step as scipy's
//! `least_squares` does (¼ of the step's length when ρ < ¼, ×2 when ρ > ¾
//! and the step reached the radius); after a refused trial it is halved
//! (Madsen, Nielsen & Tingleff 2004, eq. 2.19), not quartered as scipy's.

use nalgebra::{DMatrix, DVector, SymmetricEigen};

/// One iteration's scaled normal equations, decomposed once for every
/// radius tried.
pub struct Subproblem {
    count: usize,
    free: Vec<usize>,
    scale: Vec<f64>,
    vectors: DMatrix<f64>,
    values: Vec<f64>,
    projected: Vec<f64>,
}

/// Relative accuracy of the step's length on the radius.
const RADIUS_TOLERANCE: f64 = 0.1;

impl Subproblem {
    /// Decomposes the scaled `JᵀJ` and gradient on the `free` parameters.
    pub fn new(jtj: &DMatrix<f64>, g: &DVector<f64>, free: &[usize]) -> Subproblem {
        let largest = free.iter().map(|&i| jtj[(i, i)]).fold(0.0, f64::max);
        let floor = (1e-12 * largest).max(f64::MIN_POSITIVE);
        let scale: Vec<f64> = free
            .iter()
            .map(|&i| jtj[(i, i)].max(floor).sqrt())
            .collect();
        let k = free.len();
        let a = DMatrix::from_fn(k, k, |r, c| jtj[(free[r], free[c])] / (scale[r] * scale[c]));
        let b = DVector::from_iterator(k, (0..k).map(|j| g[free[j]] / scale[j]));
        let eigen = SymmetricEigen::new(a);
        let projected = (eigen.eigenvectors.transpose() * b)
            .iter()
            .copied()
            .collect();
        Subproblem {
            count: g.len(),
            free: free.to_vec(),
            scale,
            values: eigen.eigenvalues.iter().map(|v| v.max(0.0)).collect(),
            vectors: eigen.eigenvectors,
            projected,
        }
    }

    /// The scaled length of `p` (all parameters; only the free ones count).
    pub fn scaled_norm(&self, p: &[f64]) -> f64 {
        self.free
            .iter()
            .zip(&self.scale)
            .map(|(&i, d)| (d * p[i]).powi(2))
            .sum::<f64>()
            .sqrt()
    }

    /// The step within `radius` (scaled), zero on the held parameters;
    /// `None` when it is not finite.
    pub fn step(&self, radius: f64) -> Option<Vec<f64>> {
        let lambda = self.damping(radius);
        let k = self.free.len();
        let weights = DVector::from_iterator(
            k,
            (0..k).map(|j| term(self.projected[j], self.values[j] + lambda)),
        );
        let s = &self.vectors * weights;
        let mut delta = vec![0.0; self.count];
        for (j, &i) in self.free.iter().enumerate() {
            delta[i] = s[j] / self.scale[j];
        }
        delta.iter().all(|d| d.is_finite()).then_some(delta)
    }

    /// `‖s(λ)‖` and `Σ c_i² / (Λ_i + λ)³` (the derivative's sum).
    fn length(&self, lambda: f64) -> (f64, f64) {
        let (mut square, mut cube) = (0.0, 0.0);
        for (&c, v) in self.projected.iter().zip(&self.values) {
            let t = term(c, v + lambda);
            square += t * t;
            cube += t * t / (v + lambda).max(f64::MIN_POSITIVE);
        }
        (square.sqrt(), cube)
    }

    /// The damping λ ≥ 0 whose step is the trust-region step of `radius`.
    fn damping(&self, radius: f64) -> f64 {
        let (gauss_newton, _) = self.length(0.0);
        if gauss_newton.is_finite() && gauss_newton <= radius {
            return 0.0;
        }
        let gradient = self.projected.iter().map(|c| c * c).sum::<f64>().sqrt();
        let largest = self.values.iter().copied().fold(0.0, f64::max);
        let mut lambda = (gradient / radius - largest).max(0.0);
        if !self.length(lambda).0.is_finite() {
            lambda = 1e-15 * largest.max(gradient / radius).max(f64::MIN_POSITIVE);
        }
        for _ in 0..50 {
            let (length, cube) = self.length(lambda);
            if !length.is_finite() || (length - radius).abs() <= RADIUS_TOLERANCE * radius {
                break;
            }
            // Newton on ψ = 1/‖s‖ − 1/Δ: ψ' = Σ c²/(Λ+λ)³ / ‖s‖³
            let next = lambda + (1.0 / radius - 1.0 / length) * length.powi(3) / cube;
            if next.partial_cmp(&lambda) != Some(std::cmp::Ordering::Greater) {
                break;
            }
            lambda = next;
        }
        lambda
    }
}

/// `−c / (Λ + λ)`, zero where the gradient has no component (a direction
/// the data cannot see, Λ = 0, takes no step).
fn term(c: f64, denominator: f64) -> f64 {
    if c == 0.0 { 0.0 } else { -c / denominator }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    /// JᵀJ = diag(4, 1) (scaled: identity), g = (−2, −1): the scaled
    /// Gauss–Newton step is (1, 1), length √2.
    fn example() -> Subproblem {
        let jtj = DMatrix::from_row_slice(2, 2, &[4.0, 0.0, 0.0, 1.0]);
        let g = DVector::from_row_slice(&[-2.0, -1.0]);
        Subproblem::new(&jtj, &g, &[0, 1])
    }

    #[test]
    fn inside_the_radius_the_step_is_gauss_newton() {
        let step = example().step(10.0).unwrap();
        assert_relative_eq!(step[0], 0.5, epsilon = 1e-12);
        assert_relative_eq!(step[1], 1.0, epsilon = 1e-12);
    }

    /// With A = I the step is −b/(1 + λ): its length √2/(1 + λ) meets a
    /// radius of √2/4 at λ = 3, within the 10 % tolerance.
    #[test]
    fn outside_the_radius_the_step_reaches_it() {
        let problem = example();
        let radius = 2f64.sqrt() / 4.0;
        let step = problem.step(radius).unwrap();
        let length = problem.scaled_norm(&step);
        assert!(
            (length - radius).abs() <= RADIUS_TOLERANCE * radius,
            "{length}"
        );
        assert_relative_eq!(step[0] * 2.0, step[1], epsilon = 1e-12);
    }

    /// A zero column (a parameter the data cannot see) gets no step and
    /// the other still moves.
    #[test]
    fn a_parameter_the_data_cannot_see_stays() {
        let jtj = DMatrix::from_row_slice(2, 2, &[1.0, 0.0, 0.0, 0.0]);
        let g = DVector::from_row_slice(&[-1.0, 0.0]);
        let step = Subproblem::new(&jtj, &g, &[0, 1]).step(10.0).unwrap();
        assert_relative_eq!(step[0], 1.0, epsilon = 1e-12);
        assert_eq!(step[1], 0.0);
    }
}
