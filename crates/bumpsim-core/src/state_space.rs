//! Continuous state-space form of the chain MSD model (spec §2).
//!
//! With the state X = [x; x'] (N = 2n):
//!
//! ```text
//! X' = A X + B f,   A = [[0, I], [-M⁻¹K, -M⁻¹C]],   B = [0; M⁻¹ e1]
//! ```
//!
//! The free chain always has a double eigenvalue λ = 0 (rigid-body translation,
//! x'' = 0 for the whole car). [`elastic_modes`] returns the other,
//! elastic modes: one entry per complex-conjugate pair (Im λ > 0) and one per
//! real (overdamped) eigenvalue.
//!
//! ```
//! use bumpsim_core::{model::MsdModel, state_space::elastic_modes};
//! let car = MsdModel::new(vec![1.0, 1.0], vec![0.0], vec![2.0]).unwrap();
//! let modes = elastic_modes(&car).unwrap();
//! // undamped 2-DOF: omega = sqrt(k (1/m1 + 1/m2)) = 2 rad/s
//! assert!((modes[0].natural_frequency() - 2.0).abs() < 1e-9);
//! ```

use crate::model::MsdModel;
use nalgebra::{DMatrix, DVector};
use std::fmt;

/// The continuous system matrices of a chain MSD model.
#[derive(Debug, Clone, PartialEq)]
pub struct StateSpace {
    a: DMatrix<f64>,
    b: DVector<f64>,
}

/// An elastic eigenmode of the continuous system: eigenvalue λ = re + i·im.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mode {
    /// Real part of λ, 1/s (negative: decaying).
    pub re: f64,
    /// Imaginary part of λ, rad/s (0 for an overdamped mode, > 0 otherwise).
    pub im: f64,
}

impl Mode {
    /// |λ|, rad/s: the undamped natural angular frequency of an oscillating mode.
    pub fn natural_frequency(&self) -> f64 {
        self.re.hypot(self.im)
    }

    /// Damping ratio ζ = −Re λ / |λ| (1 and above for real modes).
    pub fn damping_ratio(&self) -> f64 {
        -self.re / self.natural_frequency()
    }

    /// Whether the eigenvalue is real (an overdamped, non-oscillating mode).
    pub fn is_real(&self) -> bool {
        self.im == 0.0
    }
}

impl fmt::Display for Mode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.is_real() {
            write!(
                f,
                "overdamped mode λ = {:.4e} 1/s (time constant {:.3e} s)",
                self.re,
                -1.0 / self.re
            )
        } else {
            write!(
                f,
                "mode λ = {:.4e} ± {:.4e}i 1/s ({:.4} Hz, damping ratio {:.3e})",
                self.re,
                self.im,
                self.im / std::f64::consts::TAU,
                self.damping_ratio()
            )
        }
    }
}

impl StateSpace {
    /// Builds A and B of a model.
    pub fn from_model(model: &MsdModel) -> Self {
        let n = model.dof();
        let inverse_mass = DVector::from_iterator(n, model.masses().iter().map(|m| 1.0 / m));
        let mut a = DMatrix::zeros(2 * n, 2 * n);
        a.view_mut((0, n), (n, n)).fill_with_identity();
        let stiffness = model.stiffness_matrix();
        let damping = model.damping_matrix();
        for i in 0..n {
            for j in 0..n {
                a[(n + i, j)] = -inverse_mass[i] * stiffness[(i, j)];
                a[(n + i, n + j)] = -inverse_mass[i] * damping[(i, j)];
            }
        }
        let mut b = DVector::zeros(2 * n);
        b[n] = inverse_mass[0];
        Self { a, b }
    }

    /// The system matrix A (2n × 2n).
    pub fn a(&self) -> &DMatrix<f64> {
        &self.a
    }

    /// The input vector B (2n).
    pub fn b(&self) -> &DVector<f64> {
        &self.b
    }

    /// State dimension N = 2n.
    pub fn order(&self) -> usize {
        self.b.len()
    }
}

/// The eigenvalue iteration did not converge.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("the eigenvalues of the {size} × {size} relative-coordinate system did not converge")]
pub struct ModeError {
    /// Size of the matrix.
    pub size: usize,
}

/// The system matrix of the relative coordinates `u_j = x_j − x_(j+1)`,
/// state `[u; u']` (2(n−1) × 2(n−1)), which excludes the free chain's
/// rigid-body pair exactly:
///
/// ```text
/// u'' = −R (D_k u + D_c u') + (f/m1) e1,   R = L M⁻¹ Lᵀ
/// ```
///
/// (L: the (n−1) × n difference matrix; R tridiagonal, symmetric positive
/// definite: `R_jj = 1/m_j + 1/m_(j+1)`, `R_j,j+1 = −1/m_(j+1)`).
pub(crate) fn relative_system(model: &MsdModel) -> DMatrix<f64> {
    let links = model.dof() - 1;
    let m = model.masses();
    let mut reduced = DMatrix::zeros(2 * links, 2 * links);
    reduced
        .view_mut((0, links), (links, links))
        .fill_with_identity();
    for i in 0..links {
        for j in i.saturating_sub(1)..(i + 2).min(links) {
            let r = relative_inverse_mass(m, i, j);
            reduced[(links + i, j)] = -r * model.springs()[j];
            reduced[(links + i, links + j)] = -r * model.dampers()[j];
        }
    }
    reduced
}

/// Entry (i, j) of `R = L M⁻¹ Lᵀ` of [`relative_system`]: tridiagonal,
/// `R_ii = 1/m_i + 1/m_(i+1)`, `R_i,i±1 = −1/m_shared`.
pub(crate) fn relative_inverse_mass(m: &[f64], i: usize, j: usize) -> f64 {
    match i.abs_diff(j) {
        0 => 1.0 / m[i] + 1.0 / m[i + 1],
        1 => -1.0 / m[i.max(j)],
        _ => 0.0,
    }
}

/// The elastic modes of a model (rigid-body pair excluded), sorted by |λ|.
///
/// The free chain's double eigenvalue 0 is a Jordan block that slows or
/// stalls a QR iteration on A, so the modes are taken from the relative
/// coordinates u_j = x_j − x_(j+1), which exclude it exactly:
///
/// ```text
/// u'' = −R (D_k u + D_c u'),   R = L M⁻¹ Lᵀ   (L: the (n−1) × n difference matrix)
/// ```
///
/// whose 2(n−1) eigenvalues are the elastic eigenvalues of A.
pub fn elastic_modes(model: &MsdModel) -> Result<Vec<Mode>, ModeError> {
    let links = model.dof() - 1;
    if links == 0 {
        return Ok(Vec::new());
    }
    let reduced = relative_system(model);
    let size = 2 * links;
    let schur = nalgebra::linalg::Schur::try_new(reduced, f64::EPSILON, 10_000)
        .ok_or(ModeError { size })?;
    let mut modes: Vec<Mode> = schur
        .complex_eigenvalues()
        .iter()
        .filter(|z| z.im >= 0.0)
        .map(|z| Mode { re: z.re, im: z.im })
        .collect();
    modes.sort_by(|p, q| p.natural_frequency().total_cmp(&q.natural_frequency()));
    Ok(modes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn single_mass_is_a_double_integrator() {
        let car = MsdModel::new(vec![4.0], vec![], vec![]).unwrap();
        let ss = StateSpace::from_model(&car);
        assert_eq!(
            ss.a(),
            &DMatrix::from_row_slice(2, 2, &[0.0, 1.0, 0.0, 0.0])
        );
        assert_relative_eq!(ss.b()[1], 0.25);
        assert!(elastic_modes(&car).unwrap().is_empty());
    }

    #[test]
    fn damped_oscillator_mode() {
        // relative coordinate: mu = m1 m2 / (m1 + m2) = 0.5; omega0^2 = k / mu = 8, 2 zeta omega0 = c / mu = 2
        let car = MsdModel::new(vec![1.0, 1.0], vec![1.0], vec![4.0]).unwrap();
        let modes = elastic_modes(&car).unwrap();
        assert_eq!(modes.len(), 1);
        assert_relative_eq!(
            modes[0].natural_frequency(),
            8f64.sqrt(),
            max_relative = 1e-10
        );
        assert_relative_eq!(
            modes[0].damping_ratio(),
            1.0 / 8f64.sqrt(),
            max_relative = 1e-10
        );
    }

    #[test]
    fn stiff_thesis_model_has_a_fast_real_mode() {
        let car = MsdModel::new(
            vec![1.8, 74.8, 1670.0],
            vec![6.46e6, 1.97e5],
            vec![4.75e5, 5.0e5],
        )
        .unwrap();
        let modes = elastic_modes(&car).unwrap();
        let fastest = modes.last().unwrap();
        assert!(fastest.is_real());
        // dominated by c1 (1/m1 + 1/m2)
        assert_relative_eq!(
            -fastest.re,
            6.46e6 * (1.0 / 1.8 + 1.0 / 74.8),
            max_relative = 0.02
        );
    }
}
