//! Load cases and the objective of spec §3.
//!
//! A load case is a force history on m1 (N) and the measured displacement
//! (m) of one output DOF at the same sample times, an initial velocity of
//! the whole car (m/s) and a fit window. The objective is
//! `F(θ) = Σ_l Σ_{k ∈ window_l} (x_l[k](θ) − x̂_l[k])²` (m²), with the model
//! simulated by the exact zoh discretisation from the first sample.
//!
//! [`Objective`] evaluates the residuals and their exact Jacobian with
//! respect to the free log parameters. Simulation, prediction and the
//! Jacobian all run core's one zoh discretisation: the state-space
//! recursion ([`DiscreteModel`], [`bumpsim_core::sensitivity`]), or inside
//! the identification's iterations its modal form
//! ([`bumpsim_core::modal`], `case::modal`) where that is precise enough.

pub use bumpsim_estimate::domain::{Domain, UnknownDomain};
use bumpsim_estimate::lm::LeastSquares;

mod direction;
mod modal;
use bumpsim_core::discrete::{DiscreteModel, DiscretiseError, Method};
use bumpsim_core::model::{MsdModel, parameter_count};
use bumpsim_core::sensitivity::OutputError;
use bumpsim_core::series::UniformSeries;
use bumpsim_core::units::format_number;
use nalgebra::{DMatrix, DMatrixView, DVector, DVectorView};
use std::sync::Mutex;

/// Whether the times `[t0, t1]` s lie within `record` (half a sample's
/// slack at each end): a fit or bias window must (a NaN bound does not).
pub fn within_record(record: &UniformSeries, [t0, t1]: [f64; 2]) -> bool {
    let slack = 0.5 * record.step();
    t0 >= record.start() - slack && t1 <= record.end() + slack
}

/// The first and last sample of the fit window `[t0, t1]` s of case `case`
/// recorded on `record` (its force). Refused, as a study's window is, when
/// it reaches past the record ([`within_record`]: one cut to the record
/// without a word had the fit %, SSE and rating taken over another window
/// than the one given) or holds no sample.
pub fn fit_window(
    case: &str,
    record: &UniformSeries,
    [t0, t1]: [f64; 2],
) -> Result<(usize, usize), CaseError> {
    let invalid = |reason| CaseError::Invalid {
        case: case.into(),
        reason,
    };
    if !within_record(record, [t0, t1]) {
        let (first, last) = (record.start(), record.end());
        return Err(invalid(format!(
            "window [{t0}, {t1}] s: expected times within the record, {} s to {} s ({} s long)",
            format_number(first, 4),
            format_number(last, 4),
            format_number(last - first, 4)
        )));
    }
    let inside = record
        .window(t0, t1)
        .ok_or_else(|| invalid(format!("no sample inside the window [{t0}, {t1}] s")))?;
    Ok((*inside.start(), *inside.end()))
}

/// Why a load case or parameter set is not usable.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum CaseError {
    /// Force and displacement differ in length, or a case is empty.
    #[error("load case '{case}': {reason}")]
    Invalid {
        /// The case name.
        case: String,
        /// What is wrong.
        reason: String,
    },
    /// The model cannot be discretised at the case's sample interval.
    #[error("load case '{case}': {source}")]
    Discretise {
        /// The case name.
        case: String,
        /// Why.
        source: DiscretiseError,
    },
    /// The case does not fit the model (e.g. it measures a mass the model lacks).
    #[error("load case '{case}' with a {dof}-DOF model: {source}")]
    Output {
        /// The case name.
        case: String,
        /// Number of masses of the model.
        dof: usize,
        /// Which buffer or index does not fit.
        source: OutputError,
    },
}

impl CaseError {
    /// What is wrong, without the case's name (for a message that names
    /// the case already).
    pub fn reason(&self) -> String {
        match self {
            CaseError::Invalid { reason, .. } => reason.clone(),
            CaseError::Discretise { source, .. } => source.to_string(),
            CaseError::Output { dof, source, .. } => format!("with a {dof}-DOF model: {source}"),
        }
    }
}

/// One load case, SI, on a uniform time base starting at `start`.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadCase {
    /// Name (e.g. `flat`, `pole`).
    pub name: String,
    /// Time of the first sample, s.
    pub start: f64,
    /// Sample interval, s.
    pub step: f64,
    /// Force on m1, N.
    pub force: Vec<f64>,
    /// Measured displacement of the output DOF, m.
    pub measured: Vec<f64>,
    /// Output DOF, 1-based (1 = m1).
    pub output_dof: usize,
    /// Velocity of every mass at the first sample, m/s.
    pub initial_velocity: f64,
    /// First and last sample of the fit window (inclusive).
    pub window: (usize, usize),
    /// Where and with which weight the case is compared (issue 44).
    pub compare: Comparison,
}

/// Where a case's displacement is compared, and its noise there.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct Comparison {
    /// The domain ([`Domain`]): displacement (the thesis's), velocity or
    /// acceleration.
    pub domain: Domain,
    /// The measurement's noise in that domain (standard deviation, its SI
    /// unit), from the pre-trigger or the study; the residuals are divided
    /// by it. None: not weighted (the thesis's objective in m²).
    pub noise: Option<f64>,
    /// When the measured displacement was integrated from accelerations:
    /// the samples integrated before t = 0 and the bias window (samples
    /// from the integration's start), so that its velocity's error is a
    /// random walk of known start ([`bumpsim_estimate::walk`]). None: a
    /// measured displacement.
    #[serde(default)]
    pub integrated: Option<Walk>,
}

pub use bumpsim_estimate::walk::Walk;

impl Comparison {
    /// The comparison in `domain` with the residuals divided by `noise`.
    pub fn new(domain: Domain, noise: Option<f64>) -> Comparison {
        Comparison {
            domain,
            noise,
            integrated: None,
        }
    }

    /// The same comparison of a displacement integrated from
    /// accelerations as `integrated` says.
    pub fn integrated(self, integrated: Walk) -> Comparison {
        Comparison {
            integrated: Some(integrated),
            ..self
        }
    }

    /// The factor of the case's residuals: 1 / noise, or 1.
    pub fn weight(&self) -> f64 {
        self.noise.map_or(1.0, f64::recip)
    }

    /// Whether this is the thesis's objective (displacement, unweighted).
    pub fn is_thesis(&self) -> bool {
        self.domain == Domain::Displacement && self.noise.is_none()
    }
}

/// The largest initial velocity a case may give, m/s (either sign): far
/// above any crash test's few m/s, so that a mistyped value is refused
/// instead of overflowing every simulation ("all starts failed").
pub const MAX_INITIAL_VELOCITY: f64 = 1000.0;

/// The largest force (N) and displacement (m) a case's measurement may
/// hold, in size: far beyond any crash test (a few MN, a few m), below
/// where the squared residuals overflow. An accelerometer sample of 1e308
/// integrated into a displacement of 1e299 m failed every start ("the
/// model could not be simulated") instead of naming the measurement.
pub const MAX_MEASURED: [f64; 2] = [1e12, 1e6];

impl LoadCase {
    /// Checks lengths, window and values.
    pub fn validate(&self) -> Result<(), CaseError> {
        let invalid = |reason: String| CaseError::Invalid {
            case: self.name.clone(),
            reason,
        };
        let (forces, displacements) = (self.force.len(), self.measured.len());
        if forces != displacements {
            return Err(invalid(format!(
                "{forces} force samples and {displacements} displacement samples: expected the same number"
            )));
        }
        if forces < 2 {
            return Err(invalid(format!(
                "{forces} samples from t = 0 (where force and displacement overlap): at least 2 needed"
            )));
        }
        let (a, b) = self.window;
        if a > b || b >= self.force.len() {
            return Err(invalid(format!(
                "window samples {a}..{b} outside 0..{}",
                self.force.len() - 1
            )));
        }
        if b < self.compare.domain.order() {
            return Err(invalid(format!(
                "window samples {a}..{b}: comparing {} needs a window ending at sample {} or later",
                self.compare.domain.name(),
                self.compare.domain.order()
            )));
        }
        if let Some(noise) = self.compare.noise
            && !(noise.is_finite() && noise > 0.0)
        {
            return Err(invalid(format!(
                "noise {noise} {}: expected a positive finite standard deviation",
                self.compare.domain.unit()
            )));
        }
        if !(self.step.is_finite() && self.step > 0.0) || self.output_dof == 0 {
            return Err(invalid(format!(
                "step {} s and output DOF {} must be positive",
                self.step, self.output_dof
            )));
        }
        let signals = [
            ("force", &self.force, "N", MAX_MEASURED[0]),
            ("displacement", &self.measured, "m", MAX_MEASURED[1]),
        ];
        for (what, values, unit, limit) in signals {
            if let Some(k) = values.iter().position(|v| !v.is_finite()) {
                return Err(invalid(format!(
                    "{what} sample {k} is {}: expected finite values",
                    values[k]
                )));
            }
            if let Some(k) = values.iter().position(|v| v.abs() > limit) {
                // (t = 0 read off a time base that starts at -1e-17 s)
                let t = self.start + k as f64 * self.step;
                let t = if t.abs() < 1e-6 * self.step { 0.0 } else { t };
                return Err(invalid(format!(
                    "{what} sample {k} (t = {} s) is {} {unit}: expected at most {} {unit} in size (check the channels' samples and their scale)",
                    format_number(t, 4),
                    format_number(values[k], 4),
                    format_number(limit, 4)
                )));
            }
        }
        let v = self.initial_velocity;
        if !(v.is_finite() && v.abs() <= MAX_INITIAL_VELOCITY) {
            return Err(invalid(format!(
                "initial velocity {} m/s: expected a finite speed of at most {MAX_INITIAL_VELOCITY} m/s",
                format_number(v, 4)
            )));
        }
        // a constant measured displacement (all zero, say) determines no
        // model: the fit measure divides by its variation
        let window = &self.measured[a..=b];
        let (lo, hi) = window
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
                (l.min(*v), h.max(*v))
            });
        if hi - lo <= 1e-12 * hi.abs().max(lo.abs()) {
            return Err(invalid(format!(
                "the measured displacement is constant ({} m) over the window: it determines no model",
                format_number(lo, 4)
            )));
        }
        Ok(())
    }

    /// Number of samples in the window.
    pub fn window_len(&self) -> usize {
        self.window.1 - self.window.0 + 1
    }

    /// The first sample compared: the window's, or the first at which the
    /// domain's difference has a value.
    pub fn first_compared(&self) -> usize {
        self.window.0.max(self.compare.domain.order())
    }

    /// Number of residuals the case gives (its window's samples that have
    /// a value in its domain).
    pub fn residual_len(&self) -> usize {
        (self.window.1 + 1).saturating_sub(self.first_compared())
    }

    /// The initial state [x; v] of a `dof`-mass chain.
    pub fn initial_state(&self, dof: usize) -> Vec<f64> {
        (0..2 * dof)
            .map(|i| if i < dof { 0.0 } else { self.initial_velocity })
            .collect()
    }

    /// The simulated output of `model` at every sample, by the zoh
    /// discretisation of core (the same as `bumpsim simulate`'s).
    pub fn simulate(&self, model: &MsdModel) -> Result<Vec<f64>, CaseError> {
        if self.output_dof == 0 {
            return Err(CaseError::Invalid {
                case: self.name.clone(),
                reason: "output DOF 0: the masses are numbered from 1".into(),
            });
        }
        let d = DiscreteModel::new(model, Method::Zoh, self.step).map_err(|source| {
            CaseError::Discretise {
                case: self.name.clone(),
                source,
            }
        })?;
        let mut y = vec![0.0; self.force.len()];
        let mut work = vec![0.0; d.work_len()];
        d.output(
            &self.initial_state(model.dof()),
            &self.force,
            self.output_dof - 1,
            &mut y,
            None,
            &mut work,
        )
        .map_err(|source| CaseError::Output {
            case: self.name.clone(),
            dof: model.dof(),
            source,
        })?;
        Ok(y)
    }

    /// Sum of squared errors over the window and the fit %
    /// `100 (1 − ‖y − ŷ‖ / ‖y − ȳ‖)` of a simulated output.
    pub fn fit(&self, simulated: &[f64]) -> (f64, f64) {
        let (a, b) = self.window;
        let measured = &self.measured[a..=b];
        let sse = bumpsim_estimate::fit::sse(&simulated[a..=b], measured);
        let spread = bumpsim_estimate::fit::spread(measured);
        (sse, bumpsim_estimate::fit::from_sums(sse, spread))
    }
}

/// Scratch buffers of one evaluation.
struct Buffers {
    initial: Vec<f64>,
    y: Vec<f64>,
    jac: Vec<f64>,
    /// The Jacobian rows in a case's domain, weighted.
    compared: Vec<f64>,
    work: Vec<f64>,
}

/// The SI values a parameter may take in an identification, whatever its
/// bounds: beyond them the matrix exponential of a sample step is
/// meaningless (and nalgebra's Padé scaling would not end).
pub const VALID_RANGE: std::ops::RangeInclusive<f64> = 1e-12..=1e15;

/// The objective over several cases for a `dof`-mass model, as a function
/// of the free log parameters (fixed parameters held at their values).
pub struct Objective<'a> {
    cases: &'a [LoadCase],
    dof: usize,
    /// Full log-parameter template: fixed entries set, free ones overwritten.
    template: Vec<f64>,
    /// Indices of the free parameters in thesis order.
    free: Vec<usize>,
    residuals: usize,
    buffers: Mutex<Buffers>,
    /// The modal forms of the last point (`case::modal`).
    modal: Mutex<modal::Cache>,
    /// Each case as the modal form takes it.
    inputs: Vec<modal::Input>,
}

impl<'a> Objective<'a> {
    /// The objective of `cases` for `dof` masses; `fixed[i]` holds a fixed
    /// SI value of parameter i.
    pub fn new(cases: &'a [LoadCase], dof: usize, fixed: &[Option<f64>]) -> Objective<'a> {
        let p = parameter_count(dof);
        let template = (0..p)
            .map(|i| fixed.get(i).copied().flatten().map_or(0.0, f64::ln))
            .collect();
        let free = (0..p)
            .filter(|&i| fixed.get(i).copied().flatten().is_none())
            .collect();
        let longest = cases.iter().map(|c| c.force.len()).max().unwrap_or(0);
        let buffers = Buffers {
            initial: vec![0.0; 2 * dof],
            y: vec![0.0; longest],
            jac: vec![0.0; longest * p],
            compared: Vec::new(),
            work: vec![0.0; (p + 2) * 2 * dof],
        };
        let residuals = cases.iter().map(LoadCase::residual_len).sum();
        Objective {
            cases,
            dof,
            template,
            free,
            residuals,
            buffers: Mutex::new(buffers),
            modal: Mutex::new(modal::Cache::default()),
            inputs: cases.iter().map(modal::Input::new).collect(),
        }
    }

    /// Whether every case is compared as the thesis does (displacement,
    /// unweighted): the modal form computes those.
    pub fn is_thesis(&self) -> bool {
        self.cases.iter().all(|c| c.compare.is_thesis())
    }

    /// The residuals' error model: independent for the thesis's objective
    /// (as it always was); a random walk for velocities of displacements
    /// integrated from accelerations (each case's error is the
    /// accelerometers' noise integrated once); else correlated with the
    /// spectral inflation.
    pub fn correlation(&self) -> bumpsim_estimate::uncertainty::Correlation {
        use bumpsim_estimate::uncertainty::Correlation;
        let walks = self
            .cases
            .iter()
            .all(|c| c.compare.domain == Domain::Velocity && c.compare.integrated.is_some());
        match (self.is_thesis(), walks) {
            (true, _) => Correlation::Independent,
            (false, true) => Correlation::RandomWalk,
            (false, false) => Correlation::Spectral,
        }
    }

    /// Each case's random walk from its first residual (the measurement's
    /// integration start, its bias window; [`bumpsim_estimate::walk`]).
    pub fn walks(&self) -> Vec<Walk> {
        self.cases
            .iter()
            .map(|c| {
                let w = c.compare.integrated.unwrap_or_default();
                Walk {
                    lead: w.lead + c.first_compared(),
                    bias: w.bias,
                }
            })
            .collect()
    }

    /// Indices of the free parameters.
    pub fn free(&self) -> &[usize] {
        &self.free
    }

    /// The residual series: one per case, its window, in case order.
    pub fn series(&self) -> Vec<bumpsim_estimate::uncertainty::Series> {
        bumpsim_estimate::uncertainty::Series::contiguous(
            self.cases.iter().map(LoadCase::residual_len),
        )
    }

    /// The full SI parameter vector of free log parameters `p`.
    pub fn theta(&self, p: &[f64]) -> Vec<f64> {
        let mut full = self.template.clone();
        for (j, &i) in self.free.iter().enumerate() {
            full[i] = p[j];
        }
        full.into_iter().map(f64::exp).collect()
    }

    /// The model of free log parameters `p`, if valid: every parameter
    /// within [`VALID_RANGE`].
    pub fn model(&self, p: &[f64]) -> Option<MsdModel> {
        let theta = self.theta(p);
        if theta.iter().any(|t| !VALID_RANGE.contains(t)) {
            return None;
        }
        MsdModel::from_parameters(self.dof, &theta).ok()
    }
}

impl Objective<'_> {
    /// Simulates every case at the free log parameters `p`, writing the
    /// residuals; with `sensitivities`, hands each case's window to
    /// `window(first residual, Jacobian rows, residuals)`: the rows
    /// row-major, one column per parameter of the full set (thesis order).
    /// False when the model cannot be evaluated.
    fn simulate(
        &self,
        p: &[f64],
        residuals: &mut [f64],
        sensitivities: bool,
        window: &mut Window<'_>,
    ) -> bool {
        let Some(model) = self.model(p) else {
            return false;
        };
        let mut guard = self.buffers.lock().unwrap_or_else(|e| e.into_inner());
        let b = &mut *guard;
        let full = parameter_count(self.dof);
        let mut row = 0;
        let mut cached: Option<(f64, DiscreteModel)> = None;
        for case in self.cases {
            if cached.as_ref().is_none_or(|(step, _)| *step != case.step) {
                let d = match sensitivities {
                    true => DiscreteModel::with_sensitivities(&model, case.step),
                    false => DiscreteModel::new(&model, Method::Zoh, case.step),
                };
                let Ok(d) = d else { return false };
                cached = Some((case.step, d));
            }
            let Some((_, d)) = cached.as_ref() else {
                return false;
            };
            // nothing after the window enters the objective
            let n = case.window.1 + 1;
            let jac = sensitivities.then_some(&mut b.jac[..n * full]);
            let (positions, velocities) = b.initial.split_at_mut(self.dof);
            positions.fill(0.0);
            velocities.fill(case.initial_velocity);
            let simulated = d.output(
                &b.initial,
                &case.force[..n],
                case.output_dof - 1,
                &mut b.y[..n],
                jac,
                &mut b.work,
            );
            if simulated.is_err() {
                return false;
            }
            let (a, z) = (case.first_compared(), case.window.1);
            let next = row + z + 1 - a;
            if case.compare.is_thesis() {
                for k in a..=z {
                    residuals[row + k - a] = b.y[k] - case.measured[k];
                }
                if sensitivities {
                    window(row, &b.jac[a * full..(z + 1) * full], &residuals[row..next]);
                }
            } else {
                let (domain, w, h) = (case.compare.domain, case.compare.weight(), case.step);
                for k in a..=z {
                    let (y, m) = (domain.at(&b.y, k, h), domain.at(&case.measured, k, h));
                    residuals[row + k - a] = w * (y - m);
                }
                if sensitivities {
                    b.compared.clear();
                    for k in a..=z {
                        for i in 0..full {
                            let column = |j: usize| b.jac[j * full + i];
                            b.compared.push(w * domain.strided(column, k, h));
                        }
                    }
                    window(row, &b.compared, &residuals[row..next]);
                }
            }
            row = next;
        }
        residuals.iter().all(|r| r.is_finite())
    }
}

/// What [`Objective::simulate`] hands each case's window to: its first
/// residual's index, its Jacobian rows (row-major, full parameter set) and
/// its residuals.
type Window<'a> = dyn FnMut(usize, &[f64], &[f64]) + 'a;

/// Adds `Σ_k j_k j_kᵀ` and `Σ_k j_k r_k` over row-major Jacobian `rows`
/// (`p` columns) to `jtj` (p × p) and `gradient`: the rows read in place as
/// `Jᵀ` (column-major p × m) and as `J` (strided), one matrix product.
fn accumulate(
    rows: &[f64],
    residuals: &[f64],
    jtj: &mut DMatrix<f64>,
    gradient: &mut DVector<f64>,
) {
    let (p, m) = (jtj.nrows(), residuals.len());
    let transposed = DMatrixView::from_slice(rows, p, m);
    let jacobian = DMatrixView::from_slice_with_strides(rows, m, p, p, 1);
    jtj.gemm(1.0, &transposed, &jacobian, 1.0);
    gradient.gemv(
        1.0,
        &transposed,
        &DVectorView::from_slice(residuals, m),
        1.0,
    );
}

impl LeastSquares for Objective<'_> {
    fn residual_count(&self) -> usize {
        self.residuals
    }

    fn parameter_count(&self) -> usize {
        self.free.len()
    }

    fn evaluate(
        &self,
        p: &[f64],
        residuals: &mut [f64],
        jacobian: Option<&mut DMatrix<f64>>,
    ) -> bool {
        let full = parameter_count(self.dof);
        if jacobian.is_none() {
            return self.residuals(p, residuals);
        }
        match jacobian {
            None => self.simulate(p, residuals, false, &mut |_, _, _| {}),
            Some(j) => self.simulate(p, residuals, true, &mut |first, rows, _| {
                for (k, row) in rows.chunks_exact(full).enumerate() {
                    for (col, &i) in self.free.iter().enumerate() {
                        j[(first + k, col)] = row[i];
                    }
                }
            }),
        }
    }

    /// The normal equations of all parameters (`case::modal`: by the modal form
    /// where it is precise enough, else by the state-space recursion, case
    /// by case from its Jacobian rows), then those of the free ones.
    fn normal(
        &self,
        p: &[f64],
        residuals: &mut [f64],
        jtj: &mut DMatrix<f64>,
        gradient: &mut DVector<f64>,
    ) -> bool {
        let full = parameter_count(self.dof);
        let (mut sums, mut g) = (DMatrix::zeros(full, full), DVector::zeros(full));
        let ok = self.normal_equations(p, residuals, &mut sums, &mut g);
        for (a, &i) in self.free.iter().enumerate() {
            gradient[a] = g[i];
            for (b, &j) in self.free.iter().enumerate() {
                jtj[(a, b)] = sums[(i, j)];
            }
        }
        ok
    }

    /// `Jᵀv` by the modal forms of the last normal equations, when the
    /// modal form made them at `p` (about a simulation's cost); false
    /// otherwise: no Jacobian is formed for it, and LM takes its step
    /// without the acceleration.
    fn transposed(&self, p: &[f64], v: &[f64], product: &mut DVector<f64>) -> bool {
        let mut full = vec![0.0; parameter_count(self.dof)];
        if v.len() != self.residuals || !self.modal_transposed(p, v, &mut full) {
            return false;
        }
        for (a, &i) in self.free.iter().enumerate() {
            product[a] = full[i];
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fit window within the record (half a sample's slack at each end)
    /// gives its samples; one reaching past the record, or with a NaN
    /// bound, is refused naming the record's span instead of being cut to
    /// it, and one between two samples holds none.
    #[test]
    fn a_fit_window_past_the_record_is_refused() {
        let record = UniformSeries::new(0.0, 1e-3, vec![0.0; 11]).unwrap();
        assert_eq!(fit_window("c", &record, [0.002, 0.0104]), Ok((2, 10)));
        for window in [[0.002, 0.02], [-0.001, 0.005], [f64::NAN, 0.005]] {
            let refused = fit_window("c", &record, window).unwrap_err().to_string();
            assert!(
                refused.starts_with("load case 'c': window [")
                    && refused.ends_with(
                        "expected times within the record, 0 s to 0.01000 s (0.01000 s long)"
                    ),
                "{refused}"
            );
        }
        let empty = fit_window("c", &record, [0.0021, 0.0029]).unwrap_err();
        assert!(empty.to_string().contains("no sample inside"), "{empty}");
    }
}
