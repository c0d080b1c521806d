//! The zoh response of one mass in modal coordinates, with its exact
//! parameter sensitivities: the same sampled model as [`crate::discrete`]'s
//! zoh, at a cost per sample that does not grow with the number of
//! parameters (issue 19: identification's inner loop).
//!
//! **The response.** The free chain's rigid motion and its elastic motion
//! separate exactly: the centre of mass moves as `M x_cm'' = f`, and the
//! relative coordinates `u_j = x_j − x_(j+1)` follow the 2(n−1)-state system
//! `[u; u']' = A [u; u'] + b f` of [`crate::state_space`] (no rigid-body
//! eigenvalue). The output mass is `x_o = x_cm + wᵀu` with
//! `w_l = Σ_(j>l) m_j / M` for links at or behind the output and
//! `w_l = −Σ_(j≤l) m_j / M` before it. With the eigenvalues λ_i of A
//! (complex pairs or real) and the residues `r_i = (c v_i)(u_i b)`
//! (`c = [wᵀ, 0]`, right and left eigenvectors `v_i`, `u_i`, `U V = I`):
//!
//! ```text
//! x_o(t) = v0 t + ρ(t)/M + Σ_i r_i z_i(t),   ρ'' = f,   z_i' = λ_i z_i + f
//! ```
//!
//! Held constant over each step T (zoh), each term is sampled exactly:
//! `ρ[k+1] = ρ[k] + T ρ'[k] + T²/2 f[k]`, `ρ'[k+1] = ρ'[k] + T f[k]`,
//! `z[k+1] = e^(λT) z[k] + T φ1(λT) f[k]` with `φ1(x) = (eˣ − 1)/x`: the
//! zoh of [`crate::discrete`] in the eigenvector basis, so both give the
//! same samples up to rounding (tested to 1e-12 of the peak).
//!
//! **Sensitivities.** `∂x_o/∂p = ∂(1/M)/∂p ρ + Σ_i (∂r_i/∂p z_i + r_i
//! ∂λ_i/∂p w_i)`, where `w_i = ∂z_i/∂λ_i` is sampled exactly by the
//! derivative of the same recursion,
//! `w[k+1] = e^(λT) (w[k] + T z[k]) + T² φ1'(λT) f[k]`. So every
//! parameter's sensitivity is a fixed combination of 4(n−1) + 1 real
//! signals, the *basis*: ρ and, per *slot* (a complex pair, or two real
//! eigenvalues), `[Re z, Im z, Re w, Im w]` or `[z_a, z_b, w_a, w_b]`
//! (stored by component, slots innermost).
//! [`ModalForm::coefficients`] gives the combinations; [`ModalForm::normal`]
//! sums the basis's Gram matrix `G = BᵀB` and moments `Bᵀr` in the same
//! pass as the residuals, so that `JᵀJ = Cᵀ G C` and `Jᵀr = Cᵀ (Bᵀr)`.
//! The derivatives of eigenvalues and residues are the classical ones
//! (Nelson 1976; Magnus & Neudecker 1985, ch. 8) for `F = U (∂A/∂p) V`:
//! `∂λ_i = F_ii` and, with `γ = cV`, `β = Ub`,
//! `∂r_i = (c'V)_i β_i + γ_i (U b')_i + Σ_(j≠i) (γ_j F_ji β_i + γ_i F_ij β_j)/(λ_i − λ_j)`.
//! For the log parameters `p = ln θ` of a chain every `∂A/∂p` is of rank
//! one (`∂R/∂ln m_i = −q_i q_iᵀ / m_i` with `q_i` the i-th column of the
//! difference matrix), so `F` is an outer product and all of this costs
//! O(n²) per parameter, nothing per sample.
//!
//! **When it is used.** The sums over `1/(λ_i − λ_j)` and the residues of
//! nearly equal eigenvalues cancel, so the modal form is refused
//! ([`ModalError`]) when two eigenvalues lie closer than [`SEPARATION`]
//! (relative), when the eigenvectors do not reproduce A to [`ACCURACY`] (a
//! mode at critical damping, two equal links), or for more than
//! [`MAX_DOF`] masses. The caller then runs the state-space recursion of
//! [`crate::sensitivity`], which has no such limit.
//!
//! ```
//! use bumpsim_core::{discrete::{DiscreteModel, Method}, modal::ModalForm, model::MsdModel};
//! let car = MsdModel::new(vec![30.0, 250.0, 1170.0], vec![8e3, 2.5e4], vec![1.5e6, 6e5]).unwrap();
//! let force: Vec<f64> = (0..400).map(|k| 4e4 * (k as f64 * 0.01).sin().max(0.0)).collect();
//! let modal = ModalForm::new(&car, 0, false).unwrap();
//! let mut y = vec![0.0; 400];
//! modal.simulate(2e-4, 1.0, &force, &mut y).unwrap();
//! // the same samples as the state-space zoh
//! let d = DiscreteModel::new(&car, Method::Zoh, 2e-4).unwrap();
//! let (mut x, mut work) = (vec![0.0; 400], vec![0.0; d.work_len()]);
//! d.output(&[0.0, 0.0, 0.0, 1.0, 1.0, 1.0], &force, 0, &mut x, None, &mut work).unwrap();
//! assert!(y.iter().zip(&x).all(|(a, b)| (a - b).abs() < 1e-12 * 0.1));
//! ```

mod eigen;
mod kernels;
mod propagator;
mod residues;
pub mod sweep;

use crate::model::{MsdModel, parameter_count};
use crate::sensitivity::OutputError;
use nalgebra::Complex;
use residues::{Chain, Modes};
use std::cell::RefCell;
use sweep::{Precision, Run, Scratch};

type C = Complex<f64>;

/// Two eigenvalues closer than this (relative to the larger) make the
/// modal form refused: its residues and their derivatives divide by the
/// difference. Closer pairs than about 1e-3 are usually refused by the
/// precision estimate of a run already (their terms cancel); this bound
/// keeps the coefficients finite.
pub const SEPARATION: f64 = 1e-6;

/// The eigen-decomposition must reproduce the balanced matrix to this
/// (relative `‖A V − V Λ‖`, `‖U V − I‖`) for the modal form to be used.
pub const ACCURACY: f64 = 1e-11;

/// Largest model in modal form (its loops run on fixed-size arrays);
/// larger ones run the state-space recursion.
pub const MAX_DOF: usize = 10;

/// Why the modal form is not used at this model (the caller falls back on
/// the state-space recursion).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ModalError {
    /// The output mass does not exist.
    #[error("output mass {output} (0-based) of a {dof}-mass model")]
    Output {
        /// The output asked for, 0-based.
        output: usize,
        /// Number of masses.
        dof: usize,
    },
    /// More masses than [`MAX_DOF`].
    #[error("{dof} masses: the modal form takes at most {MAX_DOF}")]
    TooLarge {
        /// Number of masses.
        dof: usize,
    },
    /// The eigenvalue iteration did not converge.
    #[error("the eigenvalues of the {size} × {size} relative system did not converge")]
    Eigenvalues {
        /// Size of the matrix.
        size: usize,
    },
    /// Two eigenvalues too close to separate (see [`SEPARATION`]).
    #[error(
        "eigenvalues {first} and {second} 1/s are closer than {SEPARATION} (relative): \
         the modal form would lose accuracy"
    )]
    Close {
        /// One eigenvalue, 1/s.
        first: C,
        /// The other, 1/s.
        second: C,
    },
    /// The eigenvectors do not reproduce the matrix (see [`ACCURACY`]).
    #[error("the eigenvectors reproduce the system to {error:.1e} only (need {ACCURACY:e})")]
    Inaccurate {
        /// The relative error found.
        error: f64,
    },
    /// The output or its sensitivities would be less precise than
    /// [`OUTPUT_PRECISION`] or [`JACOBIAN_PRECISION`] in this run.
    #[error(
        "the {what} would be precise to {error:.1e} only (need {limit:e}): the modal form \
         would lose accuracy"
    )]
    Imprecise {
        /// `output` or `Jacobian`.
        what: &'static str,
        /// The estimated relative error.
        error: f64,
        /// The precision needed.
        limit: f64,
    },
    /// A buffer, window or step that does not fit.
    #[error(transparent)]
    Buffer(#[from] OutputError),
}

impl ModalError {
    /// Whether the run's *output* was refused as imprecise (a far mass
    /// that barely moves, a stiff chain): the Jacobian of the same run may
    /// still be precise enough for [`ModalForm::jacobian`] on residuals
    /// computed elsewhere.
    pub fn output_imprecise(&self) -> bool {
        matches!(self, ModalError::Imprecise { what: "output", .. })
    }
}

/// The relative precision a run's output must have (estimated) for the
/// modal form to be used. The estimate is an upper bound, about ten
/// times the error found against 40-digit arithmetic; the state-space zoh
/// itself errs by about 1e-11 on stiff chains.
pub const OUTPUT_PRECISION: f64 = 1e-11;

/// The precision the Jacobian must have, relative to its largest column.
pub const JACOBIAN_PRECISION: f64 = 1e-8;

/// One slot of the basis: a complex pair (one eigenvalue, Im > 0) or two
/// real eigenvalues, 1/s.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Slot {
    Complex(C),
    Real(f64, f64),
}

/// The modal form of a chain model for one output mass: its slots, the
/// output's basis coefficients and, on request, every log parameter's
/// (see the module).
#[derive(Debug, Clone, PartialEq)]
pub struct ModalForm {
    slots: Vec<Slot>,
    /// Per slot and eigenvalue (a complex slot's twice the same): the
    /// eigenvector rounding (relative: backward error over gap), the
    /// eigenvalue error (1/s) and the decay rate `−Re λ` (1/s) (see
    /// [`eigen::Decomposition`]).
    rounding: Vec<[(f64, f64, f64); 2]>,
    /// The output's coefficients on the basis: `x_o − v0 t = basis · output`.
    output: Vec<f64>,
    /// Basis × parameters, row-major (empty without sensitivities).
    coefficients: Vec<f64>,
}

impl ModalForm {
    /// The modal form of `model` for the displacement of mass `output`
    /// (0-based); with `sensitivities`, the coefficients of the
    /// derivatives with respect to all log parameters, thesis order
    /// `[m.., c.., k..]`. Refused (for the state-space recursion to take
    /// over) when the eigenvalues cannot be separated accurately.
    pub fn new(model: &MsdModel, output: usize, sensitivities: bool) -> Result<Self, ModalError> {
        let dof = model.dof();
        if output >= dof {
            return Err(ModalError::Output { output, dof });
        }
        if dof > MAX_DOF {
            return Err(ModalError::TooLarge { dof });
        }
        let chain = Chain::new(model, output);
        let modes = Modes::new(eigen::Decomposition::new(model)?, &chain);
        let d = &modes.decomposition;
        let (complex, representatives) = (d.complex, d.representatives());
        let slots = (0..complex)
            .map(|i| Slot::Complex(d.lambda[i]))
            .chain(
                (complex..representatives)
                    .step_by(2)
                    .map(|i| Slot::Real(d.lambda[i].re, d.lambda[i + 1].re)),
            )
            .collect();
        let rounding_of = |i: usize| {
            let vectors = (d.errors[i] / d.gaps[i]).max(f64::EPSILON);
            (vectors, d.errors[i], -d.lambda[i].re)
        };
        let rounding = (0..complex)
            .map(|i| [rounding_of(i); 2])
            .chain(
                (complex..representatives)
                    .step_by(2)
                    .map(|i| [rounding_of(i), rounding_of(i + 1)]),
            )
            .collect();
        let residues: Vec<(C, C)> = (0..representatives)
            .map(|i| (modes.residue[i], C::ZERO))
            .collect();
        let output = combination(complex, chain.total.recip(), &residues);
        let columns: Vec<Vec<f64>> = match sensitivities {
            true => (0..parameter_count(dof))
                .map(|p| {
                    let (rigid, terms) = modes.derivatives(model, &chain, p);
                    combination(complex, rigid, &terms)
                })
                .collect(),
            false => Vec::new(),
        };
        let coefficients = (0..output.len())
            .flat_map(|row| columns.iter().map(move |column| column[row]))
            .collect();
        Ok(ModalForm {
            slots,
            rounding,
            output,
            coefficients,
        })
    }

    /// Number of basis signals, 4(n−1) + 1.
    pub fn basis_len(&self) -> usize {
        self.output.len()
    }

    /// Number of log parameters with coefficients (0 without sensitivities).
    pub fn parameter_count(&self) -> usize {
        self.coefficients.len() / self.basis_len()
    }

    /// The elastic eigenvalues, 1/s: one of each complex pair (Im > 0),
    /// then the real ones.
    pub fn eigenvalues(&self) -> Vec<C> {
        let complex = self.slots.iter().filter_map(|s| match s {
            Slot::Complex(l) => Some(*l),
            Slot::Real(..) => None,
        });
        let real = self.slots.iter().flat_map(|s| match s {
            Slot::Complex(_) => Vec::new(),
            Slot::Real(a, b) => vec![C::from(*a), C::from(*b)],
        });
        complex.chain(real).collect()
    }

    /// Basis × parameters, row-major: the sensitivity `∂x_o/∂ln θ_p` (m)
    /// at a sample is the basis row there times column p.
    pub fn coefficients(&self) -> &[f64] {
        &self.coefficients
    }

    /// The output's coefficients on the basis (`x_o − v0 t`, m).
    pub fn output_coefficients(&self) -> &[f64] {
        &self.output
    }

    /// Simulates the output (m) at every sample of `force` (N, held over
    /// each `step`, s) from a chain in rigid motion at `initial_velocity`
    /// (m/s), displacements zero, into `y`. Allocates nothing. Refused
    /// ([`ModalError::Imprecise`]) when the output's estimated error
    /// exceeds [`OUTPUT_PRECISION`]: each term's rounding (its mode's
    /// eigenvector `ε ‖A‖ / gap`, the eigenvalue's `ε ‖A‖` over the run's
    /// duration, the recursion's `ε √N`) times its size, over the output's
    /// (a far mass that barely moves is the difference of rigid and
    /// elastic parts much larger than itself).
    pub fn simulate(
        &self,
        step: f64,
        initial_velocity: f64,
        force: &[f64],
        y: &mut [f64],
    ) -> Result<(), ModalError> {
        check(step, force, y)?;
        let run = Run {
            step,
            initial_velocity,
            force,
        };
        self.dispatch(&run, y, None).accept()
    }

    /// The residuals of a fit window and its normal equations in one
    /// pass: simulates as [`ModalForm::simulate`], writes `x_o − measured`
    /// (m) of the last `measured.len()` samples of `force` (the window ends
    /// with the force given) into `residuals`, and adds `JᵀJ` (row-major
    /// P × P, P = 3n − 2 log parameters) to `jtj` and `Jᵀr` to `gradient`,
    /// J being the window's sensitivities (m). Needs the sensitivities.
    /// Allocates nothing once a thread has run a window this long.
    /// Refused, adding nothing, when the output's estimated error exceeds
    /// [`OUTPUT_PRECISION`] or the Jacobian's, relative to its largest
    /// column, [`JACOBIAN_PRECISION`].
    #[allow(clippy::too_many_arguments)]
    pub fn normal(
        &self,
        step: f64,
        initial_velocity: f64,
        force: &[f64],
        measured: &[f64],
        residuals: &mut [f64],
        jtj: &mut [f64],
        gradient: &mut [f64],
    ) -> Result<(), ModalError> {
        let run = Run {
            step,
            initial_velocity,
            force,
        };
        let (found, expected) = (residuals.len(), measured.len());
        OutputError::fits("residuals", found, expected, found == expected)?;
        self.normal_equations(&run, (measured, false), residuals, jtj, gradient)
    }

    /// The normal equations of a fit window for residuals (m) computed
    /// elsewhere, e.g. by the state-space zoh where this form's output is
    /// refused: adds `JᵀJ` and `Jᵀr` as [`ModalForm::normal`] for the last
    /// `residuals.len()` samples of `force`. Refused, adding nothing, when
    /// the Jacobian's estimated error exceeds [`JACOBIAN_PRECISION`].
    pub fn jacobian(
        &self,
        step: f64,
        force: &[f64],
        residuals: &[f64],
        jtj: &mut [f64],
        gradient: &mut [f64],
    ) -> Result<(), ModalError> {
        let run = Run {
            step,
            initial_velocity: 0.0,
            force,
        };
        self.normal_equations(&run, (residuals, true), &mut [], jtj, gradient)
    }

    /// `Jᵀv` of a fit window for a vector `v` other than its residuals
    /// (m; LM's geodesic acceleration projects the residuals' second
    /// derivative so): adds to `product` (P) the sensitivities of the last
    /// `v.len()` samples of `force` times `v`. By the basis recursion alone,
    /// without the Gram matrix of [`ModalForm::normal`]: about the cost of
    /// [`ModalForm::simulate`]. Needs the sensitivities. Not checked for
    /// precision: the caller uses it at a form whose Jacobian
    /// [`ModalForm::normal`] or [`ModalForm::jacobian`] accepted.
    pub fn transposed(
        &self,
        step: f64,
        force: &[f64],
        v: &[f64],
        product: &mut [f64],
    ) -> Result<(), ModalError> {
        check(step, force, force)?;
        let fits = OutputError::fits;
        let (n, p) = (v.len(), self.parameter_count());
        fits("window", n, force.len(), n <= force.len())?;
        fits("sensitivities", p, 1, p > 0)?;
        fits("Jᵀv", product.len(), p, product.len() == p)?;
        let run = Run {
            step,
            initial_velocity: 0.0,
            force,
        };
        let b = self.basis_len();
        SCRATCH.with_borrow_mut(|(basis, _)| {
            basis.resize(n * b, 0.0);
            macro_rules! sizes {
                ($($l:literal => $b:literal);*) => {
                    match self.slots.len() {
                        $($l => sweep::transposed::<$l, $b>(self, &run, v, basis, product),)*
                        _ => unreachable!("at most MAX_DOF − 1 slots"),
                    }
                };
            }
            sizes!(0 => 1; 1 => 5; 2 => 9; 3 => 13; 4 => 17; 5 => 21; 6 => 25; 7 => 29;
                8 => 33; 9 => 37);
        });
        Ok(())
    }

    /// [`ModalForm::normal`] (`window.1` false: `window.0` is measured) or
    /// [`ModalForm::jacobian`] (true: it holds the residuals).
    fn normal_equations(
        &self,
        run: &Run,
        window: (&[f64], bool),
        residuals: &mut [f64],
        jtj: &mut [f64],
        gradient: &mut [f64],
    ) -> Result<(), ModalError> {
        check(run.step, run.force, run.force)?;
        let fits = OutputError::fits;
        let (measured, given) = window;
        let (n, p) = (measured.len(), self.parameter_count());
        fits("measured window", n, run.force.len(), n <= run.force.len())?;
        fits("sensitivities", p, 1, p > 0)?;
        fits("JᵀJ", jtj.len(), p * p, jtj.len() == p * p)?;
        fits("Jᵀr", gradient.len(), p, gradient.len() == p)?;
        let (b, blocks) = (self.basis_len(), (p + 1).div_ceil(8));
        SCRATCH.with_borrow_mut(|(basis, rows)| {
            basis.resize(n * b, 0.0);
            rows.resize(n * blocks, [0.0; 8]);
            let scratch = Scratch {
                basis,
                rows,
                measured,
                given,
                jtj,
                gradient,
            };
            self.dispatch(run, residuals, Some(scratch)).accept()
        })
    }

    /// Runs [`sweep::simulate`] (without scratch) or [`sweep::normal`] at
    /// the fixed size of this model.
    fn dispatch(&self, run: &Run, out: &mut [f64], scratch: Option<Scratch>) -> Precision {
        macro_rules! sizes {
            ($($l:literal => $b:literal, $p:literal, $w:literal);*) => {
                match (self.slots.len(), scratch) {
                    $(($l, None) => sweep::simulate::<$l, $b>(self, run, out),)*
                    $(($l, Some(s)) => sweep::normal::<$l, $b, $p, $w>(self, run, out, s),)*
                    _ => unreachable!("at most MAX_DOF − 1 slots"),
                }
            };
        }
        // L slots => B = 4L + 1 basis signals, P = 3L + 1 parameters, rows of
        // P + 1 in V blocks of eight
        sizes!(0 => 1, 1, 1; 1 => 5, 4, 1; 2 => 9, 7, 1; 3 => 13, 10, 2; 4 => 17, 13, 2;
            5 => 21, 16, 3; 6 => 25, 19, 3; 7 => 29, 22, 3; 8 => 33, 25, 4; 9 => 37, 28, 4)
    }
}

/// Buffer and step checks of the public runs: a force, an output buffer
/// as long as it, a positive finite step.
fn check(step: f64, force: &[f64], out: &[f64]) -> Result<(), OutputError> {
    if force.is_empty() || out.len() != force.len() {
        let buffer = if force.is_empty() {
            "force"
        } else {
            "output buffer"
        };
        let found = if force.is_empty() { 0 } else { out.len() };
        return Err(OutputError::Buffer {
            buffer,
            found,
            expected: force.len().max(1),
        });
    }
    match step.is_finite() && step > 0.0 {
        true => Ok(()),
        false => Err(OutputError::Step { step }),
    }
}

thread_local! {
    /// The basis and Jacobian rows of [`ModalForm::normal`], kept per
    /// thread so that an identification allocates them once.
    static SCRATCH: RefCell<(Vec<f64>, Vec<[f64; 8]>)> = const { RefCell::new((Vec::new(), Vec::new())) };
}

/// The basis row of a rigid coefficient and, per representative
/// eigenvalue, the pair `(a, b)` of `a z + b w`: `2 Re(a z + b w)` on a
/// complex slot's `[Re z, Im z, Re w, Im w]`, `a z + b w` on each real one.
///
/// The layout is by component, slots innermost (structure of arrays):
/// `[ρ | s0 of every slot | s1 ... | w0 ... | w1 ...]`, so that the
/// recursion runs the same operation across slots.
fn combination(complex: usize, rigid: f64, terms: &[(C, C)]) -> Vec<f64> {
    let mut slots: Vec<[f64; 4]> = terms[..complex]
        .iter()
        .map(|&(a, b)| [2.0 * a.re, -2.0 * a.im, 2.0 * b.re, -2.0 * b.im])
        .collect();
    for pair in terms[complex..].chunks_exact(2) {
        slots.push([pair[0].0.re, pair[1].0.re, pair[0].1.re, pair[1].1.re]);
    }
    let mut row = vec![rigid];
    for component in 0..4 {
        row.extend(slots.iter().map(|slot| slot[component]));
    }
    row
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::discrete::DiscreteModel;
    use proptest::prelude::*;

    const STEP: f64 = 2e-4;

    fn chain(dof: usize) -> MsdModel {
        let masses = (0..dof).map(|i| 30.0 + 170.0 * i as f64).collect();
        let dampers = (1..dof).map(|i| 2e3 + 3e3 * i as f64).collect();
        let springs = (1..dof).map(|i| 1.5e6 / i as f64).collect();
        MsdModel::new(masses, dampers, springs).unwrap()
    }

    fn force(len: usize) -> Vec<f64> {
        (0..len)
            .map(|k| 4e4 * (k as f64 * 0.012).sin().max(0.0))
            .collect()
    }

    /// The state-space zoh output and Jacobian (row-major, 3n − 2 columns).
    fn reference(model: &MsdModel, output: usize, v0: f64, f: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let d = DiscreteModel::with_sensitivities(model, STEP).unwrap();
        let dof = model.dof();
        let initial: Vec<f64> = (0..2 * dof)
            .map(|i| if i < dof { 0.0 } else { v0 })
            .collect();
        let p = d.parameter_count();
        let (mut y, mut jac) = (vec![0.0; f.len()], vec![0.0; f.len() * p]);
        let mut work = vec![0.0; d.work_len()];
        d.output(&initial, f, output, &mut y, Some(&mut jac), &mut work)
            .unwrap();
        (y, jac)
    }

    /// Largest difference of `a` and `b` relative to the largest |b|.
    fn relative(a: &[f64], b: &[f64]) -> f64 {
        let scale = b.iter().fold(1e-300_f64, |m, v| m.max(v.abs()));
        difference(a, b) / scale
    }

    fn difference(a: &[f64], b: &[f64]) -> f64 {
        a.iter()
            .zip(b)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max)
    }

    /// Output, `JᵀJ = Cᵀ G C` and `Jᵀr = Cᵀ (Bᵀr)` of the modal form
    /// against the state-space zoh and its exact Jacobian; returns the
    /// largest differences relative to the largest value (output; normal
    /// equations: `JᵀJ` to its largest entry, `Jᵀr` to `‖J‖ ‖r‖`), None
    /// when the modal form refuses.
    fn compare(
        model: &MsdModel,
        output: usize,
        v0: f64,
        f: &[f64],
        first: usize,
    ) -> Option<(f64, f64)> {
        let (y_ref, jac_ref) = reference(model, output, v0, f);
        let form = ModalForm::new(model, output, true).ok()?;
        let (b, p) = (form.basis_len(), form.parameter_count());
        assert_eq!((b, p), (4 * model.dof() - 3, 3 * model.dof() - 2));
        let mut y = vec![0.0; f.len()];
        form.simulate(STEP, v0, f, &mut y).ok()?;
        // a "measurement" 1 % off the model
        let measured: Vec<f64> = y_ref[first..].iter().map(|v| 0.99 * v).collect();
        let mut residuals = vec![0.0; measured.len()];
        let (mut jtj, mut jtr) = (vec![0.0; p * p], vec![0.0; p]);
        form.normal(STEP, v0, f, &measured, &mut residuals, &mut jtj, &mut jtr)
            .ok()?;
        let windowed: Vec<f64> = residuals
            .iter()
            .zip(&measured)
            .map(|(r, m)| r + m)
            .collect();
        let (mut jtj_ref, mut jtr_ref) = (vec![0.0; p * p], vec![0.0; p]);
        for i in 0..p {
            jtr_ref[i] = (first..f.len())
                .map(|k| jac_ref[k * p + i] * residuals[k - first])
                .sum();
            for j in 0..p {
                jtj_ref[i * p + j] = (first..f.len())
                    .map(|k| jac_ref[k * p + i] * jac_ref[k * p + j])
                    .sum();
            }
        }
        // Jᵀr against ‖J‖ ‖r‖: it is small where J and r are nearly orthogonal
        let largest = jtj_ref.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let r_norm = residuals.iter().map(|r| r * r).sum::<f64>().sqrt();
        let gradient = difference(&jtr, &jtr_ref) / (largest.sqrt() * r_norm);
        let normal = relative(&jtj, &jtj_ref).max(gradient);
        let output = relative(&y, &y_ref).max(relative(&windowed, &y_ref[first..]));
        Some((output, normal))
    }

    #[test]
    fn output_and_normal_equations_equal_the_state_space_ones() {
        for dof in 1..=6 {
            for output in [0, dof - 1] {
                let (y, normal) = compare(&chain(dof), output, 1.3, &force(700), 100).unwrap();
                assert!(y < 1e-12, "{dof} masses, output {output}: output {y:.1e}");
                assert!(
                    normal < 1e-9,
                    "{dof} masses, output {output}: JᵀJ, Jᵀr {normal:.1e}"
                );
            }
        }
    }

    /// `Jᵀv` by the basis alone equals the state-space sensitivities' for
    /// a vector that is not the residuals, relative to `‖J‖ ‖v‖`; a buffer
    /// of the wrong length is refused.
    #[test]
    fn the_transposed_product_equals_the_state_space_one() {
        let (f, first) = (force(700), 100);
        for dof in 1..=6 {
            let model = chain(dof);
            let (_, jac) = reference(&model, dof - 1, 1.3, &f);
            let form = ModalForm::new(&model, dof - 1, true).unwrap();
            let p = form.parameter_count();
            let v: Vec<f64> = (first..f.len()).map(|k| (k as f64 * 0.37).sin()).collect();
            let mut product = vec![0.0; p];
            form.transposed(STEP, &f, &v, &mut product).unwrap();
            let expected: Vec<f64> = (0..p)
                .map(|i| {
                    (first..f.len())
                        .map(|k| jac[k * p + i] * v[k - first])
                        .sum()
                })
                .collect();
            let j_norm = jac.iter().map(|x| x * x).sum::<f64>().sqrt();
            let v_norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
            let error = difference(&product, &expected) / (j_norm * v_norm);
            assert!(error < 1e-9, "{dof} masses: Jᵀv {error:.1e}");
        }
        let form = ModalForm::new(&chain(3), 0, true).unwrap();
        assert!(
            form.transposed(STEP, &f, &[0.0; 10], &mut [0.0; 3])
                .is_err()
        );
        assert!(
            form.transposed(STEP, &f[..5], &[0.0; 10], &mut [0.0; 7])
                .is_err()
        );
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(500))]
        /// Models across the identification's range (masses 1 kg–10 t,
        /// dampers 1–1e6 N·s/m, springs 1–1e9 N/m, all at the lower bound
        /// of 1 SI included): the modal form either refuses or agrees with
        /// the state-space zoh. On stiff chains the state-space reference
        /// itself errs by about 1e-11 (masses of 1–9 kg on 2e8 N/m springs:
        /// 40-digit arithmetic gives the modal output to 1e-16 and the
        /// state-space one to 1.1e-11), hence 1e-10.
        #[test]
        fn the_modal_form_agrees_or_refuses(
            dof in 2usize..=5,
            logs in proptest::collection::vec(0.0f64..1.0, 13),
            output_last in any::<bool>(),
        ) {
            let draw = |u: f64, lo: f64, hi: f64| lo * (hi / lo).powf(u);
            let masses = (0..dof).map(|i| draw(logs[i], 1.0, 1e4)).collect();
            let dampers = (0..dof - 1).map(|i| draw(logs[5 + i], 1.0, 1e6)).collect();
            let springs = (0..dof - 1).map(|i| draw(logs[9 + i], 1.0, 1e9)).collect();
            let model = MsdModel::new(masses, dampers, springs).unwrap();
            let output = if output_last { dof - 1 } else { 0 };
            if let Some((y, normal)) = compare(&model, output, 0.0, &force(400), 50) {
                prop_assert!(y < 1e-10, "{model:?}: output {y:.1e}");
                prop_assert!(normal < 1e-7, "{model:?}: normal equations {normal:.1e}");
            }
        }
    }

    #[test]
    fn a_mode_at_critical_damping_is_refused() {
        // relative coordinate of two 50 kg masses: μ = 25 kg, c_crit = 2 √(k μ)
        let k = 1e6;
        let critical = 2.0 * (k * 25.0_f64).sqrt();
        let model = MsdModel::new(vec![50.0, 50.0], vec![critical], vec![k]).unwrap();
        let err = ModalForm::new(&model, 0, true).unwrap_err();
        assert!(matches!(err, ModalError::Close { .. }), "{err}");
        // 1 % away it is accepted and right
        let model = MsdModel::new(vec![50.0, 50.0], vec![1.01 * critical], vec![k]).unwrap();
        let (y, normal) = compare(&model, 1, 0.5, &force(300), 0).unwrap();
        assert!(y < 1e-11 && normal < 1e-8, "{y:.1e} {normal:.1e}");
    }

    #[test]
    fn bad_buffers_steps_and_sizes_are_refused() {
        let form = ModalForm::new(&chain(3), 0, true).unwrap();
        let f = force(10);
        let err = form.simulate(STEP, 0.0, &f, &mut [0.0; 9]).unwrap_err();
        assert!(err.to_string().contains("output buffer"), "{err}");
        let err = form
            .simulate(f64::NAN, 0.0, &f, &mut [0.0; 10])
            .unwrap_err();
        assert!(err.to_string().contains("sample interval"), "{err}");
        let (mut r, mut g, mut m) = ([0.0; 11], [0.0; 49], [0.0; 7]);
        let err = form
            .normal(STEP, 0.0, &f, &[0.0; 11], &mut r, &mut g, &mut m)
            .unwrap_err();
        assert!(err.to_string().contains("measured window"), "{err}");
        let err = form
            .normal(STEP, 0.0, &f, &[0.0; 4], &mut r[..4], &mut g[..3], &mut m)
            .unwrap_err();
        assert!(err.to_string().contains("JᵀJ"), "{err}");
        let plain = ModalForm::new(&chain(3), 0, false).unwrap();
        let err = plain
            .normal(STEP, 0.0, &f, &[0.0; 4], &mut r[..4], &mut g, &mut m)
            .unwrap_err();
        assert!(err.to_string().contains("sensitivities"), "{err}");
        let big = chain(MAX_DOF + 1);
        assert!(matches!(
            ModalForm::new(&big, 0, false),
            Err(ModalError::TooLarge { .. })
        ));
        assert!(matches!(
            ModalForm::new(&chain(2), 2, false),
            Err(ModalError::Output { .. })
        ));
    }
}
