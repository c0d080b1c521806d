//! Discretisation of the state-space model at a sample interval T (spec §2).
//!
//! Every method gives one update `X[k+1] = Φ X[k] + Γ0 f[k] + Γ1 f[k+1]`:
//!
//! - [`Method::Zoh`] (default): exact for a force held constant over each
//!   step. `Φ = e^(AT)`, `Γ0 = ∫₀ᵀ e^(As) ds B`, `Γ1 = 0`, both from one matrix
//!   exponential of the augmented matrix `[[A, B], [0, 0]] T` (Van Loan 1978).
//!   Unconditionally stable.
//! - [`Method::Foh`]: exact for a force linear between samples (first-order
//!   hold). With the augmented state [X; f; Δf] and generator
//!   `[[A, B, 0], [0, 0, 1/T], [0, 0, 0]]`, `e^(·T)` has first block row
//!   `[Φ, Γa, Γb]`; then `Γ0 = Γa − Γb` and `Γ1 = Γb`.
//! - [`Method::Taylor1`]: the thesis's eq. (10), explicit Euler,
//!   `Φ = I + AT`, `Γ0 = (IT + AT²/2) B`. Its eigenvalues are `1 + λT`; it is
//!   refused when any elastic mode has `|1 + λT| > 1`, with the largest stable
//!   step `T_max = min(−2 Re λ / |λ|²)`. Optional sub-steps `h = T/m` (force
//!   held over the sample) make it usable; they are combined by binary
//!   powering, so m may be large.
//!
//! The exact methods take Φ and Γ from one balanced matrix exponential
//! (the private `exponential` module, the only place that computes them);
//! [`DiscreteModel::with_sensitivities`] adds their exact derivatives with
//! respect to the log parameters, for identification.
//!
//! The update loop ([`DiscreteModel::propagate`]) allocates nothing and runs
//! on fixed-size arrays for n = 1..10 masses (N = 2..20), so the compiler
//! unrolls the small matrix–vector product. [`DiscreteModel::output`]
//! ([`crate::sensitivity`]) runs the same update for one output and its
//! sensitivities.
//!
//! ```
//! use bumpsim_core::{discrete::{DiscreteModel, Method}, model::MsdModel};
//! let car = MsdModel::new(vec![1.8, 74.8, 1670.0], vec![6.46e6, 1.97e5], vec![4.75e5, 5.0e5]).unwrap();
//! assert!(DiscreteModel::new(&car, Method::Zoh, 1e-4).is_ok());
//! let refused = DiscreteModel::new(&car, Method::Taylor1, 1e-4).unwrap_err();
//! assert!(refused.to_string().contains("largest stable step"));
//! ```

use crate::exponential::{Exponential, Hold, hold_exponential};
use crate::model::MsdModel;
use crate::state_space::{Mode, ModeError, StateSpace, elastic_modes};
use nalgebra::DMatrix;
use std::fmt;
use std::str::FromStr;

/// Discretisation method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Method {
    /// Zero-order hold: exact for a force constant over each step (default).
    #[default]
    Zoh,
    /// First-order hold: exact for a force linear between samples.
    Foh,
    /// The thesis's eq. (10), explicit Euler: conditionally stable.
    Taylor1,
}

impl Method {
    /// The name used on the command line and in files.
    pub fn name(self) -> &'static str {
        match self {
            Method::Zoh => "zoh",
            Method::Foh => "foh",
            Method::Taylor1 => "taylor1",
        }
    }

    /// How the force is held between samples: first order for foh, zero
    /// order otherwise (taylor1's energies use the zero-order hold).
    pub(crate) fn hold(self) -> Hold {
        match self {
            Method::Foh => Hold::First,
            _ => Hold::Zero,
        }
    }

    /// One line for people.
    pub fn description(self) -> &'static str {
        match self {
            Method::Zoh => "exact for a force held constant over each step",
            Method::Foh => "exact for a force linear between samples",
            Method::Taylor1 => "thesis eq. (10), explicit Euler, conditionally stable",
        }
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A method name that is not zoh, foh or taylor1.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown method '{0}': expected zoh, foh or taylor1")]
pub struct UnknownMethod(pub String);

impl FromStr for Method {
    type Err = UnknownMethod;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "zoh" => Ok(Method::Zoh),
            "foh" => Ok(Method::Foh),
            "taylor1" => Ok(Method::Taylor1),
            other => Err(UnknownMethod(other.to_string())),
        }
    }
}

/// Sub-steps per sample (only for [`Method::Taylor1`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Substeps {
    /// Exactly this many (at least 1).
    Count(u32),
    /// The fewest that make every mode stable, with a 10 % margin.
    Auto,
}

impl Default for Substeps {
    fn default() -> Self {
        Substeps::Count(1)
    }
}

/// Most sub-steps allowed per sample.
pub const MAX_SUBSTEPS: u64 = 100_000_000;

/// Why a model cannot be discretised.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum DiscretiseError {
    /// The sample interval is not positive and finite.
    #[error("sample interval {step} s must be positive and finite")]
    Step {
        /// The interval given, s.
        step: f64,
    },
    /// Sub-steps asked of an exact method.
    #[error("sub-steps apply to taylor1 only; {method} is exact at any step")]
    SubstepsOfExact {
        /// The exact method.
        method: Method,
    },
    /// Zero sub-steps.
    #[error("sub-steps must be at least 1")]
    NoSubsteps,
    /// More sub-steps than [`MAX_SUBSTEPS`].
    #[error("{count} sub-steps per sample exceed the limit of {MAX_SUBSTEPS}: use method zoh")]
    TooManySubsteps {
        /// Sub-steps asked or needed.
        count: u64,
    },
    /// Explicit Euler amplifies a mode at this step.
    #[error(
        "taylor1 (explicit Euler, thesis eq. 10) is unstable at T = {step:e} s: {mode} has |1 + λh| = {radius:.4} > 1 \
         (h = T / {substeps}). The largest stable step is {max_stable_step:.4e} s: use at least {needed} sub-steps \
         (--substeps {needed} or auto), or method zoh (exact, unconditionally stable)"
    )]
    Unstable {
        /// Sample interval, s.
        step: f64,
        /// Sub-steps used.
        substeps: u64,
        /// The most amplified mode.
        mode: Mode,
        /// Its |1 + λh|.
        radius: f64,
        /// The largest stable sub-step, s.
        max_stable_step: f64,
        /// Sub-steps needed per sample.
        needed: u64,
    },
    /// The modes could not be computed.
    #[error(transparent)]
    Modes(#[from] ModeError),
    /// A mode with no damping: explicit Euler amplifies it at every step.
    #[error(
        "taylor1 (explicit Euler, thesis eq. 10) is unstable at every step for the undamped {mode}: \
         use method zoh or foh"
    )]
    NoStableStep {
        /// The undamped mode.
        mode: Mode,
    },
}

/// A discretised model: `X[k+1] = Φ X[k] + Γ0 f[k] + Γ1 f[k+1]`.
#[derive(Debug, Clone, PartialEq)]
pub struct DiscreteModel {
    method: Method,
    step: f64,
    substeps: u64,
    order: usize,
    /// Φ, column-major N × N.
    pub(crate) phi: Vec<f64>,
    pub(crate) gamma0: Vec<f64>,
    pub(crate) gamma1: Vec<f64>,
    /// dΦ/dp_i for the propagated log parameters p = ln θ (m2..mn, then
    /// k1..k(n−1); [`crate::sensitivity`]), stacked, column-major each
    /// (empty without sensitivities).
    pub(crate) dphi: Vec<f64>,
    /// dΓ0/dp_i of the same parameters stacked, 2(n−1) × N.
    pub(crate) dgamma: Vec<f64>,
    /// `c_j / k_j` of each link, for the damper sensitivities (empty
    /// without sensitivities).
    pub(crate) ratios: Vec<f64>,
    /// Whether it was built with sensitivities.
    pub(crate) sensitive: bool,
}

impl DiscreteModel {
    /// Discretises `model` at sample interval `step` (s), one sub-step.
    pub fn new(model: &MsdModel, method: Method, step: f64) -> Result<Self, DiscretiseError> {
        Self::with_substeps(model, method, step, Substeps::default())
    }

    /// Discretises with sub-steps (only [`Method::Taylor1`] accepts more than one).
    pub fn with_substeps(
        model: &MsdModel,
        method: Method,
        step: f64,
        substeps: Substeps,
    ) -> Result<Self, DiscretiseError> {
        if !(step.is_finite() && step > 0.0) {
            return Err(DiscretiseError::Step { step });
        }
        match (method, substeps) {
            (Method::Taylor1, _) => taylor1(
                &StateSpace::from_model(model),
                &elastic_modes(model)?,
                step,
                substeps,
            ),
            (_, Substeps::Count(1)) => Ok(Self::exact(model, method, step, false)),
            _ => Err(DiscretiseError::SubstepsOfExact { method }),
        }
    }

    /// Discretises `model` by zoh at sample interval `step` (s) with the exact
    /// derivatives of Φ and Γ with respect to the log parameters
    /// `p = ln θ`, thesis order `[m.., c.., k..]`, for
    /// [`DiscreteModel::output`]'s Jacobian.
    ///
    /// ```
    /// use bumpsim_core::{discrete::DiscreteModel, model::MsdModel};
    /// let car = MsdModel::new(vec![100.0, 900.0], vec![2e3], vec![5e5]).unwrap();
    /// let d = DiscreteModel::with_sensitivities(&car, 1e-4).unwrap();
    /// assert_eq!(d.parameter_count(), 4);
    /// ```
    pub fn with_sensitivities(model: &MsdModel, step: f64) -> Result<Self, DiscretiseError> {
        if !(step.is_finite() && step > 0.0) {
            return Err(DiscretiseError::Step { step });
        }
        Ok(Self::exact(model, Method::Zoh, step, true))
    }

    fn exact(model: &MsdModel, method: Method, step: f64, sensitivities: bool) -> Self {
        let Exponential {
            phi,
            gamma0,
            gamma1,
            dphi,
            dgamma,
        } = hold_exponential(model, method.hold(), step, sensitivities);
        let ratios = match sensitivities {
            true => model
                .dampers()
                .iter()
                .zip(model.springs())
                .map(|(c, k)| c / k)
                .collect(),
            false => Vec::new(),
        };
        DiscreteModel {
            method,
            step,
            substeps: 1,
            order: gamma0.len(),
            phi,
            gamma0,
            gamma1,
            dphi,
            dgamma,
            ratios,
            sensitive: sensitivities,
        }
    }

    /// Number of log parameters with sensitivities, `3n − 2` for n masses
    /// (0 unless built by [`DiscreteModel::with_sensitivities`]).
    pub fn parameter_count(&self) -> usize {
        match self.sensitive {
            true => 3 * self.order / 2 - 2,
            false => 0,
        }
    }

    /// The method used.
    pub fn method(&self) -> Method {
        self.method
    }

    /// Sample interval T, s.
    pub fn step(&self) -> f64 {
        self.step
    }

    /// Sub-steps per sample (1 for the exact methods).
    pub fn substeps(&self) -> u64 {
        self.substeps
    }

    /// State dimension N = 2n.
    pub fn order(&self) -> usize {
        self.order
    }

    /// Φ as a matrix.
    pub fn phi(&self) -> DMatrix<f64> {
        DMatrix::from_column_slice(self.order, self.order, &self.phi)
    }

    /// Γ0, the weight of `f[k]`.
    pub fn gamma0(&self) -> &[f64] {
        &self.gamma0
    }

    /// Γ1, the weight of f[k+1] (zero except for foh).
    pub fn gamma1(&self) -> &[f64] {
        &self.gamma1
    }

    /// Runs the update over a force history. `states` receives one row of N
    /// values per force sample (row 0 is `initial`); it must hold exactly
    /// `force.len() × N` values. Allocates nothing.
    pub fn propagate(
        &self,
        initial: &[f64],
        force: &[f64],
        states: &mut [f64],
    ) -> Result<(), LengthError> {
        let n = self.order;
        if initial.len() != n || states.len() != force.len() * n || force.is_empty() {
            return Err(LengthError {
                order: n,
                initial: initial.len(),
                samples: force.len(),
                states: states.len(),
            });
        }
        macro_rules! fixed {
            ($($size:literal),*) => {
                match n {
                    $($size => propagate_fixed::<$size>(self, initial, force, states),)*
                    _ => propagate_dynamic(self, initial, force, states),
                }
            };
        }
        fixed!(2, 4, 6, 8, 10, 12, 14, 16, 18, 20);
        Ok(())
    }
}

/// Buffer lengths that do not fit [`DiscreteModel::propagate`].
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "propagate needs an initial state of {order} values and {samples} × {order} state values, \
     got {initial} and {states}"
)]
pub struct LengthError {
    /// State dimension N.
    pub order: usize,
    /// Length of the initial state given.
    pub initial: usize,
    /// Number of force samples.
    pub samples: usize,
    /// Length of the state buffer given.
    pub states: usize,
}

fn propagate_fixed<const N: usize>(
    model: &DiscreteModel,
    initial: &[f64],
    force: &[f64],
    states: &mut [f64],
) {
    let (phi, g0, g1) = model.fixed::<N>();
    let mut x: [f64; N] = std::array::from_fn(|r| initial[r]);
    states[..N].copy_from_slice(&x);
    for (out, f) in states[N..].chunks_exact_mut(N).zip(force.windows(2)) {
        x = advance(&phi, &g0, g1.as_ref(), &x, f[0], f[1]);
        out.copy_from_slice(&x);
    }
}

/// One update `Φ x + Γ0 f0 + Γ1 f1` on fixed-size arrays, Φ by columns: the
/// product accumulates column by column, so the N rows are independent lanes
/// the compiler vectorises. `g1` is `None` for the holds without a Γ1 term
/// (zoh, taylor1), which skips N products per step. Every simulation path
/// runs this update.
#[inline(always)]
pub(crate) fn advance<const N: usize>(
    phi: &[[f64; N]; N],
    g0: &[f64; N],
    g1: Option<&[f64; N]>,
    x: &[f64; N],
    f0: f64,
    f1: f64,
) -> [f64; N] {
    let mut next = g0.map(|a| a * f0);
    if let Some(g1) = g1 {
        for (value, b) in next.iter_mut().zip(g1) {
            *value += b * f1;
        }
    }
    for (column, xj) in phi.iter().zip(x) {
        for (value, p) in next.iter_mut().zip(column) {
            *value += p * xj;
        }
    }
    next
}

/// One update on slices (any N), in the same order as [`advance`].
pub(crate) fn advance_dynamic(
    model: &DiscreteModel,
    x: &[f64],
    f0: f64,
    f1: f64,
    next: &mut [f64],
) {
    let n = model.order;
    for (value, a) in next.iter_mut().zip(&model.gamma0) {
        *value = a * f0;
    }
    if model.method == Method::Foh {
        for (value, b) in next.iter_mut().zip(&model.gamma1) {
            *value += b * f1;
        }
    }
    for (column, xj) in model.phi.chunks_exact(n).zip(x) {
        for (value, p) in next.iter_mut().zip(column) {
            *value += p * xj;
        }
    }
}

fn propagate_dynamic(model: &DiscreteModel, initial: &[f64], force: &[f64], states: &mut [f64]) {
    let n = model.order;
    states[..n].copy_from_slice(initial);
    for (k, f) in force.windows(2).enumerate() {
        let (done, rest) = states.split_at_mut((k + 1) * n);
        advance_dynamic(model, &done[k * n..], f[0], f[1], &mut rest[..n]);
    }
}

impl DiscreteModel {
    /// Φ by columns, Γ0 and (for foh) Γ1 as fixed-size arrays (N must be
    /// the order).
    #[allow(clippy::type_complexity)] // the three parts of the update, named at the call
    pub(crate) fn fixed<const N: usize>(&self) -> ([[f64; N]; N], [f64; N], Option<[f64; N]>) {
        (
            std::array::from_fn(|c| std::array::from_fn(|r| self.phi[c * N + r])),
            std::array::from_fn(|r| self.gamma0[r]),
            (self.method == Method::Foh).then(|| std::array::from_fn(|r| self.gamma1[r])),
        )
    }
}

fn build(
    method: Method,
    step: f64,
    substeps: u64,
    phi: DMatrix<f64>,
    gamma0: Vec<f64>,
    gamma1: Vec<f64>,
) -> DiscreteModel {
    DiscreteModel {
        method,
        step,
        substeps,
        order: phi.nrows(),
        phi: phi.as_slice().to_vec(),
        gamma0,
        gamma1,
        dphi: Vec::new(),
        dgamma: Vec::new(),
        ratios: Vec::new(),
        sensitive: false,
    }
}

/// The smallest sub-step count that makes explicit Euler stable, or the reason there is none.
fn substeps_needed(
    modes: &[Mode],
    step: f64,
) -> Result<(u64, Option<(Mode, f64)>), DiscretiseError> {
    let mut limit: Option<(Mode, f64)> = None;
    for &mode in modes {
        // undamped within rounding: |1 + λh| > 1 for every h
        if mode.re >= -1e-9 * mode.natural_frequency() {
            return Err(DiscretiseError::NoStableStep { mode });
        }
        let max_step = -2.0 * mode.re / (mode.natural_frequency() * mode.natural_frequency());
        if limit.is_none_or(|(_, best)| max_step < best) {
            limit = Some((mode, max_step));
        }
    }
    let needed = limit.map_or(1, |(_, max_step)| {
        (step / (0.9 * max_step)).ceil().max(1.0) as u64
    });
    Ok((needed, limit))
}

fn taylor1(
    ss: &StateSpace,
    modes: &[Mode],
    step: f64,
    substeps: Substeps,
) -> Result<DiscreteModel, DiscretiseError> {
    let (needed, limit) = substeps_needed(modes, step)?;
    let count = match substeps {
        Substeps::Auto => needed,
        Substeps::Count(0) => return Err(DiscretiseError::NoSubsteps),
        Substeps::Count(c) => u64::from(c),
    };
    if count > MAX_SUBSTEPS {
        return Err(DiscretiseError::TooManySubsteps { count });
    }
    let h = step / count as f64;
    if let Some((mode, radius)) = most_amplified(modes, h) {
        let max_stable_step = limit.map_or(0.0, |(_, s)| s);
        return Err(DiscretiseError::Unstable {
            step,
            substeps: count,
            mode,
            radius,
            max_stable_step,
            needed,
        });
    }
    let n = ss.order();
    let identity = DMatrix::<f64>::identity(n, n);
    let phi_h = &identity + ss.a() * h;
    let gamma_h = (&identity * h + ss.a() * (h * h / 2.0)) * ss.b();
    let (phi, gamma) = power(&phi_h, gamma_h.as_slice(), count);
    Ok(build(
        Method::Taylor1,
        step,
        count,
        phi,
        gamma,
        vec![0.0; n],
    ))
}

/// The mode with the largest |1 + λh| above 1, if any.
fn most_amplified(modes: &[Mode], h: f64) -> Option<(Mode, f64)> {
    modes
        .iter()
        .map(|&m| (m, (1.0 + m.re * h).hypot(m.im * h)))
        .filter(|&(_, radius)| radius > 1.0 + 1e-12)
        .max_by(|a, b| a.1.total_cmp(&b.1))
}

/// `count` repetitions of the affine update (Φ, Γ) with the input held: binary powering.
fn power(phi: &DMatrix<f64>, gamma: &[f64], mut count: u64) -> (DMatrix<f64>, Vec<f64>) {
    let n = phi.nrows();
    let mut result = (DMatrix::identity(n, n), nalgebra::DVector::zeros(n));
    let mut base = (phi.clone(), nalgebra::DVector::from_column_slice(gamma));
    while count > 0 {
        if count & 1 == 1 {
            // apply `result` first, then `base`
            result = (&base.0 * &result.0, &base.0 * &result.1 + &base.1);
        }
        base = (&base.0 * &base.0, &base.0 * &base.1 + &base.1);
        count >>= 1;
    }
    (result.0, result.1.as_slice().to_vec())
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn thesis_model() -> MsdModel {
        MsdModel::new(
            vec![1.8, 74.8, 1670.0],
            vec![6.46e6, 1.97e5],
            vec![4.75e5, 5.0e5],
        )
        .unwrap()
    }

    #[test]
    fn zoh_of_a_free_mass_is_the_exact_double_integrator() {
        let car = MsdModel::new(vec![2.0], vec![], vec![]).unwrap();
        let d = DiscreteModel::new(&car, Method::Zoh, 0.1).unwrap();
        assert_relative_eq!(
            d.phi(),
            DMatrix::from_row_slice(2, 2, &[1.0, 0.1, 0.0, 1.0]),
            epsilon = 1e-15
        );
        // x = T²/(2m), v = T/m per unit force
        assert_relative_eq!(d.gamma0()[0], 0.01 / 4.0, max_relative = 1e-12);
        assert_relative_eq!(d.gamma0()[1], 0.05, max_relative = 1e-12);
    }

    #[test]
    fn foh_of_a_free_mass_weights_both_samples() {
        let car = MsdModel::new(vec![1.0], vec![], vec![]).unwrap();
        let d = DiscreteModel::new(&car, Method::Foh, 1.0).unwrap();
        // force linear from f0 to f1 over T = 1: x = f0/2 + (f1 - f0)/6, v = (f0 + f1)/2
        assert_relative_eq!(d.gamma0()[0], 1.0 / 3.0, max_relative = 1e-12);
        assert_relative_eq!(d.gamma1()[0], 1.0 / 6.0, max_relative = 1e-12);
        assert_relative_eq!(d.gamma0()[1], 0.5, max_relative = 1e-12);
        assert_relative_eq!(d.gamma1()[1], 0.5, max_relative = 1e-12);
    }

    #[test]
    fn taylor1_refuses_the_thesis_model_and_names_the_cure() {
        let err = DiscreteModel::new(&thesis_model(), Method::Taylor1, 1e-4).unwrap_err();
        let DiscretiseError::Unstable {
            needed,
            max_stable_step,
            mode,
            ..
        } = err.clone()
        else {
            panic!("expected Unstable, got {err}");
        };
        assert!(mode.is_real());
        assert!((150..250).contains(&needed), "needed {needed}");
        assert!(
            max_stable_step > 4e-7 && max_stable_step < 7e-7,
            "{max_stable_step}"
        );
        assert!(err.to_string().contains("overdamped mode"), "{err}");
    }

    #[test]
    fn taylor1_with_enough_substeps_is_stable() {
        let d =
            DiscreteModel::with_substeps(&thesis_model(), Method::Taylor1, 1e-4, Substeps::Auto)
                .unwrap();
        assert!(d.substeps() > 150);
        let ok = DiscreteModel::with_substeps(
            &thesis_model(),
            Method::Taylor1,
            1e-4,
            Substeps::Count(d.substeps() as u32),
        );
        assert!(ok.is_ok());
    }

    #[test]
    fn taylor1_refuses_undamped_models() {
        let car = MsdModel::new(vec![1.0, 1.0], vec![0.0], vec![1.0]).unwrap();
        let err = DiscreteModel::new(&car, Method::Taylor1, 1e-3).unwrap_err();
        assert!(matches!(err, DiscretiseError::NoStableStep { .. }), "{err}");
    }

    #[test]
    fn substeps_are_refused_for_exact_methods() {
        let err =
            DiscreteModel::with_substeps(&thesis_model(), Method::Zoh, 1e-4, Substeps::Count(4))
                .unwrap_err();
        assert!(err.to_string().contains("taylor1 only"));
    }

    #[test]
    fn binary_powering_equals_repeated_steps() {
        let phi = DMatrix::from_row_slice(2, 2, &[0.9, 0.1, -0.2, 0.8]);
        let gamma = [0.3, 0.7];
        let (p, g) = power(&phi, &gamma, 13);
        let mut x = nalgebra::DVector::from_column_slice(&[1.0, -1.0]);
        for _ in 0..13 {
            x = &phi * x + nalgebra::DVector::from_column_slice(&gamma) * 2.0;
        }
        let y = p * nalgebra::DVector::from_column_slice(&[1.0, -1.0])
            + nalgebra::DVector::from_vec(g) * 2.0;
        assert_relative_eq!(x, y, max_relative = 1e-12);
    }
}
