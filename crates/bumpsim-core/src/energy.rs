//! Exact energy terms over one sample step.
//!
//! Within a step the hold-augmented state z = [X; f] (zoh) or [X; f; Δf] (foh)
//! obeys z' = G z (see [`crate::discrete`]). Any power that is a quadratic
//! form of z, P = zᵀ Q z, then integrates exactly over the step as
//!
//! ```text
//! ∫₀ᵀ P dt = z_kᵀ W z_k,   W = ∫₀ᵀ e^(Gᵀs) Q e^(Gs) ds
//! ```
//!
//! W comes from Van Loan's block exponential (Van Loan, "Computing integrals
//! involving the matrix exponential", IEEE TAC 1978) at a sub-interval
//! h = T / 2^s small enough that the block is well conditioned, then by
//! doubling, `W(2h) = W(h) + E(h)ᵀ W(h) E(h)`, `E(2h) = E(h)²`. The doubling
//! avoids the growth of e^(−Gᵀ T) that makes the plain Van Loan block lose all
//! digits for stiff models (the thesis's 3-DOF car has λ ≈ −3.7e6 1/s).
//!
//! Two powers are integrated: the damper dissipation Σ c_j (v_j − v_(j+1))²
//! = vᵀ C v, and the power of the external force f·v1. With the kinetic and
//! spring energies at the samples, they close the balance
//! `ΔE_kin + ΔE_spring + E_dissipated = W_force` to rounding for zoh and foh.

use crate::discrete::Method;
use crate::exponential::hold_generator;
use crate::model::MsdModel;
use crate::state_space::StateSpace;
use nalgebra::DMatrix;

/// Per-step quadratic integrals of the dissipated power and the force's power.
#[derive(Debug, Clone, PartialEq)]
pub struct StepIntegrals {
    /// Size of the augmented state z.
    size: usize,
    /// W for the damper dissipation, row-major.
    dissipation: Vec<f64>,
    /// W for the work of the force on m1, row-major.
    work: Vec<f64>,
}

impl StepIntegrals {
    /// Builds the integrals for a model, a hold (zoh or foh; taylor1 uses zoh)
    /// and a step T (s).
    pub fn new(model: &MsdModel, method: Method, step: f64) -> Self {
        let hold = method.hold();
        let ss = StateSpace::from_model(model);
        let generator = hold_generator(&ss, hold, step);
        let n = model.dof();
        let size = generator.nrows();
        let mut q_dissipation = DMatrix::zeros(size, size);
        q_dissipation
            .view_mut((n, n), (n, n))
            .copy_from(&model.damping_matrix());
        let mut q_work = DMatrix::zeros(size, size);
        // f is augmented state 2n, v1 is state n: P = f v1 = zᵀ Q z with Q symmetric
        q_work[(n, 2 * n)] = 0.5;
        q_work[(2 * n, n)] = 0.5;
        let to_rows = |w: DMatrix<f64>| w.transpose().as_slice().to_vec();
        Self {
            size,
            dissipation: to_rows(step_integral(&generator, &q_dissipation, step)),
            work: to_rows(step_integral(&generator, &q_work, step)),
        }
    }

    /// Size of the augmented state z.
    pub fn size(&self) -> usize {
        self.size
    }

    /// Energy dissipated by the dampers over the step that starts at z (J).
    pub fn dissipated(&self, z: &[f64]) -> f64 {
        quadratic_form(&self.dissipation, z)
    }

    /// Work done by the force on m1 over the step that starts at z (J).
    pub fn work(&self, z: &[f64]) -> f64 {
        quadratic_form(&self.work, z)
    }
}

fn quadratic_form(w: &[f64], z: &[f64]) -> f64 {
    w.chunks_exact(z.len())
        .zip(z)
        .map(|(row, zi)| zi * row.iter().zip(z).map(|(a, b)| a * b).sum::<f64>())
        .sum()
}

/// `∫₀ᵀ e^(Gᵀs) Q e^(Gs) ds` by Van Loan's block exponential and doubling.
pub fn step_integral(generator: &DMatrix<f64>, q: &DMatrix<f64>, step: f64) -> DMatrix<f64> {
    let size = generator.nrows();
    let norm = generator.abs().column_sum().max() * step;
    // at most 1100 doublings: a norm of f64::MAX needs 1026, and an
    // infinite one (a mass of 1e-308) would otherwise ask for u32::MAX
    // squarings, a quarter of an hour of them, for a result that is not
    // finite anyway (the simulation's own check then names it)
    let doublings = if norm > 0.25 {
        ((norm / 0.25).log2().ceil().min(1100.0)) as u32
    } else {
        0
    };
    let h = step / 2f64.powi(doublings as i32);
    let mut block = DMatrix::zeros(2 * size, 2 * size);
    block
        .view_mut((0, 0), (size, size))
        .copy_from(&(-generator.transpose() * h));
    block.view_mut((0, size), (size, size)).copy_from(&(q * h));
    block
        .view_mut((size, size), (size, size))
        .copy_from(&(generator * h));
    let exp = block.exp();
    let mut e = exp.view((size, size), (size, size)).clone_owned();
    let mut w = e.transpose() * exp.view((0, size), (size, size));
    for _ in 0..doublings {
        w = &w + e.transpose() * &w * &e;
        e = &e * &e;
    }
    (&w + w.transpose()) * 0.5
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    /// An infinite generator (a mass of 1e-308) ends at once instead of
    /// squaring for a quarter of an hour.
    #[test]
    fn an_infinite_generator_ends() {
        let g = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -f64::INFINITY, 0.0]);
        let q = DMatrix::identity(2, 2);
        let started = std::time::Instant::now();
        let _ = step_integral(&g, &q, 1e-4);
        assert!(started.elapsed().as_secs() < 5);
    }

    #[test]
    fn integral_of_a_scalar_decay() {
        // ∫₀ᵀ e^(2as) ds = (e^(2aT) − 1) / 2a
        let a = -3.0;
        let g = DMatrix::from_element(1, 1, a);
        let q = DMatrix::from_element(1, 1, 1.0);
        for step in [1e-3, 0.5, 20.0] {
            let w = step_integral(&g, &q, step);
            let exact = ((2.0 * a * step).exp() - 1.0) / (2.0 * a);
            assert_relative_eq!(w[(0, 0)], exact, max_relative = 1e-12);
        }
    }

    #[test]
    fn work_of_a_constant_force_on_a_free_mass() {
        // from rest, F const: work over T = F · F T²/(2m)
        let car = MsdModel::new(vec![2.0], vec![], vec![]).unwrap();
        let integrals = StepIntegrals::new(&car, Method::Zoh, 0.1);
        let z = [0.0, 0.0, 3.0];
        assert_relative_eq!(
            integrals.work(&z),
            3.0 * 3.0 * 0.01 / 4.0,
            max_relative = 1e-12
        );
        assert_relative_eq!(integrals.dissipated(&z), 0.0);
    }
}
