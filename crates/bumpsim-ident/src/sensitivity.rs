//! The zoh-discretised chain model and its exact parameter sensitivities.
//!
//! With `M = [[A, B], [0, 0]]` (state X = [x; v], input f held over a
//! sample), `exp(M T) = [[Φ, Γ], [0, 1]]` and `X[k+1] = Φ X[k] + Γ f[k]`
//! (spec §2, the exact zoh discretisation). The derivative of `exp(M T)`
//! along `dM` is the upper-right block of
//! `exp([[M, dM], [0, M]] T)` (Van Loan 1978), which gives `dΦ/dp` and
//! `dΓ/dp` exactly. The output sensitivities then follow the forward
//! recursion `S[k+1] = Φ S[k] + dΦ X[k] + dΓ f[k]`, `S[0] = 0` (the initial
//! state does not depend on the parameters).
//!
//! Parameters are logarithmic, `p = ln θ`, so `∂/∂p = θ ∂/∂θ`: for a mass
//! `dA/dp_i = −(row N+i of A)`, `dB/dp_i = −B_i e_{N+i}`; for a damper or
//! spring between masses j and j+1, `dA = −M⁻¹ (θ e eᵀ)` in the velocity or
//! position columns, `e = e_j − e_{j+1}`.
//!
//! ```
//! use bumpsim_core::model::MsdModel;
//! use bumpsim_ident::sensitivity::Discretised;
//! let car = MsdModel::new(vec![100.0, 900.0], vec![2e3], vec![5e5]).unwrap();
//! let d = Discretised::new(&car, 1e-4);
//! assert_eq!(d.parameter_count(), 4);
//! ```

use bumpsim_core::model::MsdModel;
use bumpsim_core::state_space::StateSpace;
use nalgebra::DMatrix;

/// Φ, Γ and their derivatives with respect to the log parameters.
#[derive(Debug, Clone)]
pub struct Discretised {
    n: usize,
    /// Φ, n × n, column-major.
    phi: Vec<f64>,
    /// Γ, n.
    gamma: Vec<f64>,
    /// dΦ/dp_i stacked, p × n × n, column-major each.
    dphi: Vec<f64>,
    /// dΓ/dp_i stacked, p × n.
    dgamma: Vec<f64>,
}

/// The augmented continuous matrix `[[A, B], [0, 0]]`, (n+1) × (n+1).
fn augmented(model: &MsdModel) -> DMatrix<f64> {
    let space = StateSpace::from_model(model);
    let n = space.order();
    let mut m = DMatrix::zeros(n + 1, n + 1);
    m.view_mut((0, 0), (n, n)).copy_from(space.a());
    m.view_mut((0, n), (n, 1)).copy_from(space.b());
    m
}

/// `dM/dp` for every log parameter, thesis order `[m.., c.., k..]`.
fn derivatives(model: &MsdModel, m: &DMatrix<f64>) -> Vec<DMatrix<f64>> {
    let dof = model.dof();
    let n = 2 * dof;
    let mut out = Vec::with_capacity(3 * dof - 2);
    for i in 0..dof {
        let mut d = DMatrix::zeros(n + 1, n + 1);
        let row = -m.row(dof + i);
        d.row_mut(dof + i).copy_from(&row);
        out.push(d);
    }
    for (values, offset) in [(model.dampers(), dof), (model.springs(), 0)] {
        for (j, &theta) in values.iter().enumerate() {
            let mut d = DMatrix::zeros(n + 1, n + 1);
            for (a, sa) in [(j, 1.0), (j + 1, -1.0)] {
                for (b, sb) in [(j, 1.0), (j + 1, -1.0)] {
                    d[(dof + a, offset + b)] = -sa * sb * theta / model.masses()[a];
                }
            }
            out.push(d);
        }
    }
    out
}

impl Discretised {
    /// Discretises `model` with sample interval `step` s, with sensitivities.
    pub fn new(model: &MsdModel, step: f64) -> Discretised {
        Self::build(model, step, true)
    }

    /// Discretises `model` without sensitivities (only [`Discretised::simulate`]
    /// without a Jacobian may be used).
    pub fn plain(model: &MsdModel, step: f64) -> Discretised {
        Self::build(model, step, false)
    }

    fn build(model: &MsdModel, step: f64, sensitivities: bool) -> Discretised {
        let continuous = augmented(model);
        let m = &continuous * step;
        let size = m.nrows();
        let n = size - 1;
        let base = m.clone().exp();
        let mut phi = Vec::with_capacity(n * n);
        for c in 0..n {
            phi.extend((0..n).map(|r| base[(r, c)]));
        }
        let gamma = (0..n).map(|r| base[(r, n)]).collect();
        let mut dphi = Vec::new();
        let mut dgamma = Vec::new();
        let wanted = if sensitivities {
            derivatives(model, &continuous)
        } else {
            Vec::new()
        };
        for dm in wanted {
            let mut block = DMatrix::zeros(2 * size, 2 * size);
            block.view_mut((0, 0), (size, size)).copy_from(&m);
            block.view_mut((size, size), (size, size)).copy_from(&m);
            block
                .view_mut((0, size), (size, size))
                .copy_from(&(dm * step));
            let e = block.exp();
            for c in 0..n {
                dphi.extend((0..n).map(|r| e[(r, size + c)]));
            }
            dgamma.extend((0..n).map(|r| e[(r, size + n)]));
        }
        Discretised {
            n,
            phi,
            gamma,
            dphi,
            dgamma,
        }
    }

    /// Number of log parameters with sensitivities (0 for [`Discretised::plain`]).
    pub fn parameter_count(&self) -> usize {
        self.dgamma.len() / self.n
    }

    /// State dimension 2N.
    pub fn order(&self) -> usize {
        self.n
    }

    /// Simulates the output `x_out` (displacement of DOF `output`, 0-based)
    /// from the initial state `initial` under `force`, writing the output into
    /// `y` and, when `jacobian` is given, its derivatives into
    /// `jacobian[k * p + i]` (row-major, p columns). `work` is scratch space
    /// of length `(p + 2) * 2N`; nothing is allocated.
    pub fn simulate(
        &self,
        force: &[f64],
        initial: &[f64],
        output: usize,
        y: &mut [f64],
        mut jacobian: Option<&mut [f64]>,
        work: &mut [f64],
    ) {
        let (n, p) = (self.n, self.parameter_count());
        let (x, rest) = work.split_at_mut(n);
        let (next, s) = rest.split_at_mut(n);
        x.copy_from_slice(initial);
        let s = &mut s[..n * p];
        s.iter_mut().for_each(|v| *v = 0.0);
        for (k, &f) in force.iter().enumerate() {
            y[k] = x[output];
            if let Some(jac) = jacobian.as_deref_mut() {
                for i in 0..p {
                    jac[k * p + i] = s[i * n + output];
                }
                self.step_sensitivities(x, f, s, next);
            }
            self.step_state(x, f, next);
        }
    }

    /// `x ← Φ x + Γ f`, using `next` as scratch.
    fn step_state(&self, x: &mut [f64], f: f64, next: &mut [f64]) {
        let n = self.n;
        for r in 0..n {
            next[r] = self.gamma[r] * f;
        }
        for c in 0..n {
            let xc = x[c];
            let col = &self.phi[c * n..(c + 1) * n];
            for r in 0..n {
                next[r] += col[r] * xc;
            }
        }
        x.copy_from_slice(next);
    }

    /// `S_i ← Φ S_i + dΦ_i x + dΓ_i f` for every parameter i.
    fn step_sensitivities(&self, x: &[f64], f: f64, s: &mut [f64], next: &mut [f64]) {
        let n = self.n;
        for i in 0..self.parameter_count() {
            let dphi = &self.dphi[i * n * n..(i + 1) * n * n];
            let dgamma = &self.dgamma[i * n..(i + 1) * n];
            for r in 0..n {
                next[r] = dgamma[r] * f;
            }
            let si = &s[i * n..(i + 1) * n];
            for c in 0..n {
                let (xc, sc) = (x[c], si[c]);
                let (pc, dc) = (&self.phi[c * n..(c + 1) * n], &dphi[c * n..(c + 1) * n]);
                for r in 0..n {
                    next[r] += pc[r] * sc + dc[r] * xc;
                }
            }
            s[i * n..(i + 1) * n].copy_from_slice(&next[..n]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use bumpsim_core::prelude::*;

    #[test]
    fn output_equals_the_core_zoh_simulation() {
        let car =
            MsdModel::new(vec![80.0, 400.0, 900.0], vec![3e3, 2e4], vec![6e5, 1.2e6]).unwrap();
        let force: Vec<f64> = (0..300)
            .map(|k| 4e4 * (k as f64 * 0.01).sin().max(0.0))
            .collect();
        let series = UniformSeries::new(0.0, 1e-4, force.clone()).unwrap();
        let core = simulate(
            &car,
            &series,
            Method::Zoh,
            &InitialState::UniformVelocity(2.0),
        )
        .unwrap();
        let d = Discretised::new(&car, 1e-4);
        let mut y = vec![0.0; 300];
        let mut work = vec![0.0; (d.parameter_count() + 2) * 6];
        let initial = [0.0, 0.0, 0.0, 2.0, 2.0, 2.0];
        for output in 0..3 {
            d.simulate(&force, &initial, output, &mut y, None, &mut work);
            for k in 0..300 {
                assert_relative_eq!(
                    y[k],
                    core.displacement[output][k],
                    epsilon = 1e-12,
                    max_relative = 1e-10
                );
            }
        }
    }
}
