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

/// Diagonal similarity `D` that balances `[[0, I], [−K/M, −C/M]]`: velocities
/// scaled by `w = sqrt(max K_ii / M_ii)` and the input by `w² m1`, so that the
/// exponential of a stiff chain is computed without the cancellation of a
/// badly scaled (non-normal) matrix: `exp(M) = D exp(D⁻¹ M D) D⁻¹`.
fn balance(model: &MsdModel, m: &DMatrix<f64>) -> Vec<f64> {
    let dof = model.dof();
    let w = (0..dof)
        .map(|i| m[(dof + i, i)].abs())
        .fold(0.0_f64, f64::max)
        .sqrt()
        .max(1.0);
    let mut d = vec![1.0; 2 * dof + 1];
    d[dof..2 * dof].iter_mut().for_each(|v| *v = w);
    d[2 * dof] = w * w * model.masses()[0];
    d
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
        let d = balance(model, &continuous);
        let similar = |x: &DMatrix<f64>| {
            DMatrix::from_fn(x.nrows(), x.ncols(), |r, c| x[(r, c)] * d[c] / d[r])
        };
        let back = |x: f64, r: usize, c: usize| x * d[r] / d[c];
        let m = similar(&continuous) * step;
        let size = m.nrows();
        let n = size - 1;
        let base = m.clone().exp();
        let mut phi = Vec::with_capacity(n * n);
        for c in 0..n {
            phi.extend((0..n).map(|r| back(base[(r, c)], r, c)));
        }
        let gamma = (0..n).map(|r| back(base[(r, n)], r, n)).collect();
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
            // Scale the direction to the size of M (Higham 2008, sec. 10.6):
            // the block exponential is linear in it, and its accuracy is
            // relative to the norm of the whole block.
            let direction = similar(&dm) * step;
            let scale = m.amax() / direction.amax().max(f64::MIN_POSITIVE);
            block
                .view_mut((0, size), (size, size))
                .copy_from(&(direction * scale));
            let e = block.exp();
            for c in 0..n {
                dphi.extend((0..n).map(|r| back(e[(r, size + c)], r, c) / scale));
            }
            dgamma.extend((0..n).map(|r| back(e[(r, size + n)], r, n) / scale));
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
    /// of length `(p + 2) * 2N`; nothing is allocated. Models of 1 to 5 DOF
    /// run a fixed-size loop the compiler unrolls and vectorises.
    pub fn simulate(
        &self,
        force: &[f64],
        initial: &[f64],
        output: usize,
        y: &mut [f64],
        jacobian: Option<&mut [f64]>,
        work: &mut [f64],
    ) {
        match (self.n, jacobian) {
            (2, Some(j)) => self.fixed::<2, 1>(force, initial, output, y, j),
            (4, Some(j)) => self.fixed::<4, 4>(force, initial, output, y, j),
            (6, Some(j)) => self.fixed::<6, 7>(force, initial, output, y, j),
            (8, Some(j)) => self.fixed::<8, 10>(force, initial, output, y, j),
            (10, Some(j)) => self.fixed::<10, 13>(force, initial, output, y, j),
            (2, None) => self.fixed::<2, 0>(force, initial, output, y, &mut []),
            (4, None) => self.fixed::<4, 0>(force, initial, output, y, &mut []),
            (6, None) => self.fixed::<6, 0>(force, initial, output, y, &mut []),
            (8, None) => self.fixed::<8, 0>(force, initial, output, y, &mut []),
            (10, None) => self.fixed::<10, 0>(force, initial, output, y, &mut []),
            (_, jacobian) => self.dynamic(force, initial, output, y, jacobian, work),
        }
    }

    /// The sensitivity recursion on fixed-size arrays: N states, P parameters.
    #[allow(clippy::needless_range_loop)] // column-major index arithmetic reads clearer
    fn fixed<const N: usize, const P: usize>(
        &self,
        force: &[f64],
        initial: &[f64],
        output: usize,
        y: &mut [f64],
        jac: &mut [f64],
    ) {
        let column = |m: &[f64], c: usize| -> [f64; N] { std::array::from_fn(|r| m[c * N + r]) };
        let phi: [[f64; N]; N] = std::array::from_fn(|c| column(&self.phi, c));
        let gamma: [f64; N] = std::array::from_fn(|r| self.gamma[r]);
        let dphi: [[[f64; N]; N]; P] =
            std::array::from_fn(|i| std::array::from_fn(|c| column(&self.dphi[i * N * N..], c)));
        let dgamma: [[f64; N]; P] =
            std::array::from_fn(|i| std::array::from_fn(|r| self.dgamma[i * N + r]));
        let mut x: [f64; N] = std::array::from_fn(|r| initial[r]);
        let mut s = [[0.0; N]; P];
        for (k, &f) in force.iter().enumerate() {
            y[k] = x[output];
            if P > 0 {
                let row = &mut jac[k * P..(k + 1) * P];
                for i in 0..P {
                    row[i] = s[i][output];
                }
            }
            for i in 0..P {
                let mut next = dgamma[i].map(|g| g * f);
                for c in 0..N {
                    let (sc, xc) = (s[i][c], x[c]);
                    for r in 0..N {
                        next[r] += phi[c][r] * sc + dphi[i][c][r] * xc;
                    }
                }
                s[i] = next;
            }
            let mut next = gamma.map(|g| g * f);
            for c in 0..N {
                for r in 0..N {
                    next[r] += phi[c][r] * x[c];
                }
            }
            x = next;
        }
    }

    fn dynamic(
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
    #[allow(clippy::needless_range_loop)] // column-major index arithmetic reads clearer
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
    #[allow(clippy::needless_range_loop)] // column-major index arithmetic reads clearer
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
            for (k, &value) in y.iter().enumerate() {
                assert_relative_eq!(
                    value,
                    core.displacement[output][k],
                    epsilon = 1e-12,
                    max_relative = 1e-10
                );
            }
        }
    }
}
