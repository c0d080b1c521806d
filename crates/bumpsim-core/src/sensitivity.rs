//! One output of a discretised model and its exact parameter sensitivities.
//!
//! The states follow the update of [`crate::discrete`],
//! `X[k+1] = Φ X[k] + Γ0 f[k] + Γ1 f[k+1]` (the same arithmetic as
//! [`DiscreteModel::propagate`], so both give identical responses), and the
//! output is the displacement of one mass, `y[k] = x_out[k]` (m). With the
//! sensitivities of [`DiscreteModel::with_sensitivities`], the derivatives
//! `S_i[k] = ∂X[k]/∂p_i` of the log parameters `p = ln θ` follow the forward
//! recursion `S[k+1] = Φ S[k] + dΦ X[k] + dΓ f[k]`, `S[0] = 0` (the initial
//! state does not depend on the parameters), and `∂y[k]/∂p_i` is the output
//! entry of `S_i[k]`.
//!
//! **Only 2(n−1) of the 3n−2 are propagated** (m2..mn and the springs); the
//! other n are exact identities of a chain that starts in rigid motion
//! (equal displacements x0, equal velocities v0; a car at rest or moving
//! as one before the impact, spec §3), which the Jacobian requires:
//!
//! - **Dampers.** In `Ṡ = A S + ∂A/∂p X` the forcing of `ln k_j` is
//!   `k_j a_j Δx_j(t)` and that of `ln c_j` is `c_j a_j Δv_j(t)`, with the
//!   same direction `a_j = −M⁻¹(e_j − e_{j+1})` in the velocity rows and
//!   `Δv_j = d/dt Δx_j`, `Δx_j(0) = 0`. So `S_c = (c_j/k_j) d/dt S_k`, and
//!   the displacement rows of `d/dt S_k` are its velocity rows:
//!   `∂y/∂ln c_j = (c_j/k_j) ∂v_out/∂ln k_j`. The zoh model is the exact
//!   sampled continuous one, so this holds at the samples exactly.
//! - **m1, by scaling.** Scaling every mass, damper and spring by α leaves
//!   the rigid motion `x0 + v0 t` and divides the forced response by α, so
//!   `Σ_i ∂y/∂ln θ_i = −(y − x0 − v0 t)`; the m1 column is that sum less
//!   the other columns (m1, directly forced, has the largest column, so the
//!   difference loses least).
//!
//! Both are checked against central differences of the full model below.
//! Models of 1 to 5 masses run a fixed-size loop the compiler unrolls and
//! vectorises; nothing is allocated in either loop.
//!
//! ```
//! use bumpsim_core::{discrete::DiscreteModel, model::MsdModel};
//! let car = MsdModel::new(vec![100.0, 900.0], vec![2e3], vec![5e5]).unwrap();
//! let d = DiscreteModel::with_sensitivities(&car, 1e-4).unwrap();
//! let force = vec![1e3; 50];
//! let (mut y, mut jacobian) = (vec![0.0; 50], vec![0.0; 50 * 4]);
//! let mut work = vec![0.0; d.work_len()];
//! d.output(&[0.0; 4], &force, 0, &mut y, Some(&mut jacobian), &mut work).unwrap();
//! // a heavier m1 moves less: ∂x1/∂ln m1 < 0
//! assert!(jacobian[49 * 4] < 0.0);
//! ```

use crate::discrete::{DiscreteModel, advance, advance_dynamic};

/// A buffer or initial state that does not fit [`DiscreteModel::output`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum OutputError {
    /// A buffer of the wrong length, or an index out of range.
    #[error("output: the {buffer} has {found} values, expected {expected}")]
    Buffer {
        /// Which buffer or index (`initial state`, `output`, ...).
        buffer: &'static str,
        /// Its length (or the index given).
        found: usize,
        /// The length needed (or one past the largest index).
        expected: usize,
    },
    /// A sample interval that is not positive and finite.
    #[error("output: sample interval {step} s must be positive and finite")]
    Step {
        /// The interval given, s.
        step: f64,
    },
    /// The Jacobian was asked for from an initial state that is not a rigid
    /// motion of the chain.
    #[error(
        "output: initial state {state} differs from the first {kind}: the exact sensitivities \
         need a chain in rigid motion (all displacements equal, all velocities equal)"
    )]
    NotRigid {
        /// Index of the first differing state ([x; v], 0-based).
        state: usize,
        /// `displacement` or `velocity`.
        kind: &'static str,
    },
}

impl OutputError {
    /// `Ok` when `ok`, else the [`OutputError::Buffer`] naming `buffer` with
    /// the length `found` and the one `expected`.
    pub(crate) fn fits(
        buffer: &'static str,
        found: usize,
        expected: usize,
        ok: bool,
    ) -> Result<(), Self> {
        match ok {
            true => Ok(()),
            false => Err(Self::Buffer {
                buffer,
                found,
                expected,
            }),
        }
    }
}

impl DiscreteModel {
    /// Scratch length [`DiscreteModel::output`] needs: `(q + 2) N` for the
    /// q propagated sensitivities.
    pub fn work_len(&self) -> usize {
        (self.propagated() + 2) * self.order()
    }

    /// Number of propagated sensitivities, 2(n−1) (0 without them).
    fn propagated(&self) -> usize {
        self.dgamma.len() / self.order()
    }

    /// Simulates the displacement of mass `output` (0-based) from `initial`
    /// ([x; v], m and m/s) under `force` (N, one value per sample), writing it
    /// (m) into `y` and, when `jacobian` is given, its derivatives with
    /// respect to the log parameters into `jacobian[k * p + i]` (row-major,
    /// p = 3n − 2 columns, thesis order `[m.., c.., k..]`; needs
    /// [`DiscreteModel::with_sensitivities`] and an initial state in rigid
    /// motion). `work` holds at least [`DiscreteModel::work_len`] values.
    /// Allocates nothing.
    pub fn output(
        &self,
        initial: &[f64],
        force: &[f64],
        output: usize,
        y: &mut [f64],
        mut jacobian: Option<&mut [f64]>,
        work: &mut [f64],
    ) -> Result<(), OutputError> {
        self.check_output(initial, force, output, y, jacobian.as_deref(), work)?;
        let jac = jacobian.as_deref_mut();
        match (self.order(), jac) {
            (2, Some(j)) => self.output_fixed::<2, 0>(initial, force, output, y, Some(j)),
            (4, Some(j)) => self.output_fixed::<4, 2>(initial, force, output, y, Some(j)),
            (6, Some(j)) => self.output_fixed::<6, 4>(initial, force, output, y, Some(j)),
            (8, Some(j)) => self.output_fixed::<8, 6>(initial, force, output, y, Some(j)),
            (10, Some(j)) => self.output_fixed::<10, 8>(initial, force, output, y, Some(j)),
            (2, None) => self.output_fixed::<2, 0>(initial, force, output, y, None),
            (4, None) => self.output_fixed::<4, 0>(initial, force, output, y, None),
            (6, None) => self.output_fixed::<6, 0>(initial, force, output, y, None),
            (8, None) => self.output_fixed::<8, 0>(initial, force, output, y, None),
            (10, None) => self.output_fixed::<10, 0>(initial, force, output, y, None),
            (_, jac) => self.output_dynamic(initial, force, output, y, jac, work),
        }
        if let Some(jac) = jacobian {
            self.mass_by_scaling(initial, y, jac);
        }
        Ok(())
    }

    fn check_output(
        &self,
        initial: &[f64],
        force: &[f64],
        output: usize,
        y: &[f64],
        jacobian: Option<&[f64]>,
        work: &[f64],
    ) -> Result<(), OutputError> {
        let n = self.order();
        let p = self.parameter_count();
        let fits = OutputError::fits;
        fits("initial state", initial.len(), n, initial.len() == n)?;
        fits("force", force.len(), 1, !force.is_empty())?;
        fits("output mass index", output, n / 2, output < n / 2)?;
        fits(
            "output buffer",
            y.len(),
            force.len(),
            y.len() == force.len(),
        )?;
        fits(
            "work buffer",
            work.len(),
            self.work_len(),
            work.len() >= self.work_len(),
        )?;
        match jacobian {
            Some(_) if p == 0 => fits("sensitivity set (not built with them)", 0, 1, false),
            Some(j) => {
                fits(
                    "jacobian",
                    j.len(),
                    force.len() * p,
                    j.len() == force.len() * p,
                )?;
                rigid(initial)
            }
            None => Ok(()),
        }
    }

    /// The output and sensitivity recursion on fixed-size arrays: N states,
    /// Q propagated sensitivities (Q = N − 2 with a Jacobian, else 0),
    /// compiled for the widest vector unit the processor has (pulp's
    /// runtime dispatch: AVX-512, AVX2 or the x86-64 baseline); the sums
    /// run in the same order on each, so every machine gives the same bits.
    fn output_fixed<const N: usize, const Q: usize>(
        &self,
        initial: &[f64],
        force: &[f64],
        output: usize,
        y: &mut [f64],
        jac: Option<&mut [f64]>,
    ) {
        pulp::Arch::new().dispatch(Recursion::<N, Q> {
            model: self,
            initial,
            force,
            output,
            y,
            jac,
        });
    }

    #[inline(always)]
    fn recursion_fixed<const N: usize, const Q: usize>(
        &self,
        initial: &[f64],
        force: &[f64],
        output: usize,
        y: &mut [f64],
        mut jac: Option<&mut [f64]>,
    ) {
        let (phi, g0, g1) = self.fixed::<N>();
        // dΦ by column c and row r, the Q parameters innermost: the update
        // of one state for all parameters is one vector operation
        let dphi: [[[f64; Q]; N]; N] = std::array::from_fn(|c| {
            std::array::from_fn(|r| std::array::from_fn(|i| self.dphi[(i * N + c) * N + r]))
        });
        let dgamma: [[f64; Q]; N] =
            std::array::from_fn(|r| std::array::from_fn(|i| self.dgamma[i * N + r]));
        let p = self.parameter_count();
        let mut x: [f64; N] = std::array::from_fn(|r| initial[r]);
        // two buffers, used in turn: s[r][i] = ∂X_r/∂p_i
        let mut buffers = [[[0.0; Q]; N]; 2];
        for (k, &f) in force.iter().enumerate() {
            let (first, second) = buffers.split_at_mut(1);
            let (s, next) = match k % 2 {
                0 => (&first[0], &mut second[0]),
                _ => (&second[0], &mut first[0]),
            };
            y[k] = x[output];
            if let Some(jac) = jac.as_deref_mut() {
                self.fill_row(|q, r| s[r][q], output, &mut jac[k * p..(k + 1) * p]);
            }
            let Some(&f1) = force.get(k + 1) else { break };
            if Q > 0 {
                step_fixed(&phi, &dphi, &dgamma, s, &x, f, next);
            }
            x = advance(&phi, &g0, g1.as_ref(), &x, f, f1);
        }
    }

    /// The same recursion on slices, for any order; `work` holds x, the next
    /// state and the q propagated sensitivity vectors.
    fn output_dynamic(
        &self,
        initial: &[f64],
        force: &[f64],
        output: usize,
        y: &mut [f64],
        mut jacobian: Option<&mut [f64]>,
        work: &mut [f64],
    ) {
        let (n, p, q) = (self.order(), self.parameter_count(), self.propagated());
        let (x, rest) = work.split_at_mut(n);
        let (next, s) = rest.split_at_mut(n);
        let s = &mut s[..n * q];
        x.copy_from_slice(initial);
        s.iter_mut().for_each(|v| *v = 0.0);
        for (k, &f) in force.iter().enumerate() {
            y[k] = x[output];
            if let Some(jac) = jacobian.as_deref_mut() {
                self.fill_row(|q, r| s[q * n + r], output, &mut jac[k * p..(k + 1) * p]);
            }
            let Some(&f1) = force.get(k + 1) else { break };
            if jacobian.is_some() {
                self.step_sensitivities(x, f, s, next);
            }
            advance_dynamic(self, x, f, f1, next);
            x.copy_from_slice(next);
        }
    }

    /// `S_i ← Φ S_i + dΦ_i x + dΓ_i f` for every propagated parameter i.
    fn step_sensitivities(&self, x: &[f64], f: f64, s: &mut [f64], next: &mut [f64]) {
        let n = self.order();
        for (i, si) in s.chunks_exact_mut(n).enumerate() {
            let dphi = &self.dphi[i * n * n..(i + 1) * n * n];
            for (value, g) in next.iter_mut().zip(&self.dgamma[i * n..(i + 1) * n]) {
                *value = g * f;
            }
            let columns = self.phi.chunks_exact(n).zip(dphi.chunks_exact(n));
            for ((pc, dc), (xc, sc)) in columns.zip(x.iter().zip(si.iter())) {
                for ((value, p), d) in next.iter_mut().zip(pc).zip(dc) {
                    *value += p * sc + d * xc;
                }
            }
            si.copy_from_slice(next);
        }
    }

    /// Writes one Jacobian row from the propagated sensitivities,
    /// `entry(q, r) = ∂X_r/∂p_q`: their output entries, and each damper's
    /// `(c_j/k_j) ∂v_out/∂ln k_j`. Column 0 (m1) is left for
    /// [`DiscreteModel::mass_by_scaling`].
    #[inline(always)]
    fn fill_row(&self, entry: impl Fn(usize, usize) -> f64, output: usize, row: &mut [f64]) {
        let dof = self.order() / 2;
        for q in 0..self.propagated() {
            let column = if q + 1 < dof { q + 1 } else { q + dof };
            row[column] = entry(q, output);
        }
        for (j, ratio) in self.ratios.iter().enumerate() {
            row[dof + j] = ratio * entry(dof - 1 + j, dof + output);
        }
    }

    /// The m1 column of every row by the scaling identity
    /// `Σ_i ∂y/∂ln θ_i = −(y − x0 − v0 t)`.
    fn mass_by_scaling(&self, initial: &[f64], y: &[f64], jac: &mut [f64]) {
        let dof = self.order() / 2;
        let (x0, v0) = (initial[0], initial[dof]);
        let p = self.parameter_count();
        for (k, row) in jac.chunks_exact_mut(p).enumerate() {
            let forced = y[k] - x0 - v0 * (k as f64 * self.step());
            row[0] = -forced - row[1..].iter().sum::<f64>();
        }
    }
}

/// The arguments of [`DiscreteModel::output_fixed`], for pulp's dispatch:
/// `with_simd` is inlined into the function compiled for the vector unit
/// (a closure is not always, and then runs on the baseline).
struct Recursion<'a, const N: usize, const Q: usize> {
    model: &'a DiscreteModel,
    initial: &'a [f64],
    force: &'a [f64],
    output: usize,
    y: &'a mut [f64],
    jac: Option<&'a mut [f64]>,
}

impl<const N: usize, const Q: usize> pulp::WithSimd for Recursion<'_, N, Q> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) {
        let Recursion {
            model,
            initial,
            force,
            output,
            y,
            jac,
        } = self;
        model.recursion_fixed::<N, Q>(initial, force, output, y, jac);
    }
}

/// One sensitivity update `out = Φ S + dΦ x + dΓ f` of all Q parameters on
/// fixed-size arrays, Φ and dΦ by columns; the Q parameters of a state are
/// independent lanes. Each entry sums in the same order as
/// [`DiscreteModel::step_sensitivities`].
#[inline(always)]
fn step_fixed<const N: usize, const Q: usize>(
    phi: &[[f64; N]; N],
    dphi: &[[[f64; Q]; N]; N],
    dgamma: &[[f64; Q]; N],
    s: &[[f64; Q]; N],
    x: &[f64; N],
    f: f64,
    out: &mut [[f64; Q]; N],
) {
    // plain loops: `array::from_fn` and `map` closures are not always
    // inlined, and then run outside the vector unit pulp chose
    for r in 0..N {
        // one row for all parameters: Q accumulators held in registers
        let mut next = [0.0; Q];
        for i in 0..Q {
            next[i] = dgamma[r][i] * f;
        }
        for c in 0..N {
            let (p, d, sc, xc) = (phi[c][r], &dphi[c][r], &s[c], x[c]);
            for i in 0..Q {
                next[i] += p * sc[i] + d[i] * xc;
            }
        }
        out[r] = next;
    }
}

/// Whether `initial` ([x; v]) is a rigid motion: every displacement equal
/// to the first, every velocity equal to the first.
fn rigid(initial: &[f64]) -> Result<(), OutputError> {
    let dof = initial.len() / 2;
    let (x, v) = initial.split_at(dof);
    let differs = |part: &[f64]| part.iter().position(|value| *value != part[0]);
    if let Some(i) = differs(x) {
        return Err(OutputError::NotRigid {
            state: i,
            kind: "displacement",
        });
    }
    match differs(v) {
        Some(i) => Err(OutputError::NotRigid {
            state: dof + i,
            kind: "velocity",
        }),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use crate::discrete::{DiscreteModel, Method};
    use crate::model::MsdModel;
    use approx::assert_relative_eq;

    fn chain(dof: usize) -> MsdModel {
        let masses = (0..dof).map(|i| 80.0 + 300.0 * i as f64).collect();
        let dampers = (1..dof).map(|i| 3e3 * i as f64).collect();
        let springs = (1..dof).map(|i| 6e5 * i as f64).collect();
        MsdModel::new(masses, dampers, springs).unwrap()
    }

    fn force(len: usize) -> Vec<f64> {
        (0..len)
            .map(|k| 4e4 * (k as f64 * 0.01).sin().max(0.0))
            .collect()
    }

    fn initial(dof: usize) -> Vec<f64> {
        (0..2 * dof)
            .map(|i| if i < dof { 0.0 } else { 2.0 })
            .collect()
    }

    #[test]
    fn output_equals_the_propagated_states_fixed_and_dynamic() {
        for dof in [3, 6, 11] {
            let d = DiscreteModel::new(&chain(dof), Method::Zoh, 1e-4).unwrap();
            let f = force(300);
            let mut states = vec![0.0; 300 * 2 * dof];
            d.propagate(&initial(dof), &f, &mut states).unwrap();
            let mut y = vec![0.0; 300];
            let mut work = vec![0.0; d.work_len()];
            for out in 0..dof {
                d.output(&initial(dof), &f, out, &mut y, None, &mut work)
                    .unwrap();
                for (k, value) in y.iter().enumerate() {
                    assert_eq!(*value, states[k * 2 * dof + out], "dof {dof} k {k}");
                }
            }
        }
    }

    /// Central differences of the output in each log parameter agree with the
    /// exact sensitivities (fixed-size and dynamic loops).
    #[test]
    fn sensitivities_match_central_differences() {
        for dof in [1, 2, 3, 5, 6] {
            let car = chain(dof);
            let d = DiscreteModel::with_sensitivities(&car, 1e-4).unwrap();
            let p = d.parameter_count();
            let (f, len) = (force(200), 200);
            let (mut y, mut jac) = (vec![0.0; len], vec![0.0; len * p]);
            let mut work = vec![0.0; d.work_len()];
            d.output(&initial(dof), &f, 0, &mut y, Some(&mut jac), &mut work)
                .unwrap();
            let theta = car.parameters();
            let scale = y.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            for i in 0..p {
                let shifted = |h: f64| {
                    let mut t = theta.clone();
                    t[i] *= h.exp();
                    let m = MsdModel::from_parameters(dof, &t).unwrap();
                    let dm = DiscreteModel::new(&m, Method::Zoh, 1e-4).unwrap();
                    let mut out = vec![0.0; len];
                    let mut w = vec![0.0; dm.work_len()];
                    dm.output(&initial(dof), &f, 0, &mut out, None, &mut w)
                        .unwrap();
                    out
                };
                let (up, down) = (shifted(1e-6), shifted(-1e-6));
                for k in 0..len {
                    let numeric = (up[k] - down[k]) / 2e-6;
                    assert_relative_eq!(jac[k * p + i], numeric, epsilon = 1e-6 * scale);
                }
            }
        }
    }

    /// The damper and m1 identities need a chain in rigid motion; any other
    /// initial state is refused, naming the state.
    #[test]
    fn a_jacobian_from_a_strained_chain_is_refused() {
        let d = DiscreteModel::with_sensitivities(&chain(2), 1e-4).unwrap();
        let mut work = vec![0.0; d.work_len()];
        let (mut y, mut jac) = (vec![0.0; 3], vec![0.0; 3 * 4]);
        for (initial, state) in [([0.0, 1e-3, 2.0, 2.0], 1), ([0.0, 0.0, 2.0, 1.0], 3)] {
            let err = d
                .output(&initial, &[1.0; 3], 0, &mut y, Some(&mut jac), &mut work)
                .unwrap_err();
            assert!(
                matches!(err, super::OutputError::NotRigid { state: s, .. } if s == state),
                "{err}"
            );
        }
        // without the Jacobian any initial state is simulated
        d.output(
            &[0.0, 1e-3, 2.0, 1.0],
            &[1.0; 3],
            0,
            &mut y,
            None,
            &mut work,
        )
        .unwrap();
    }

    #[test]
    fn mismatched_buffers_are_refused() {
        let d = DiscreteModel::new(&chain(2), Method::Zoh, 1e-4).unwrap();
        let mut work = vec![0.0; d.work_len()];
        let mut y = vec![0.0; 3];
        let err = d
            .output(&[0.0; 4], &[1.0; 4], 0, &mut y, None, &mut work)
            .unwrap_err();
        assert!(err.to_string().contains("output buffer"), "{err}");
        let err = d
            .output(&[0.0; 4], &[1.0; 3], 2, &mut y, None, &mut work)
            .unwrap_err();
        assert!(err.to_string().contains("output mass index"), "{err}");
        let mut jac = vec![0.0; 3];
        let err = d
            .output(&[0.0; 4], &[1.0; 3], 0, &mut y, Some(&mut jac), &mut work)
            .unwrap_err();
        assert!(err.to_string().contains("sensitivit"), "{err}");
    }
}
