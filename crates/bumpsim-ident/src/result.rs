//! What a chain identification finds: the model, the fits per case, the
//! information criteria, the uncertainty, the starts and the warnings
//! (serialised as `bumpsim identify --json` writes it).

use crate::stats::Uncertainty;
use bumpsim_core::model::MsdModel;
use bumpsim_estimate::lm::Stop;
use bumpsim_estimate::multistart::Starts;
use serde::Serialize;

/// Fit of one load case.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CaseFit {
    /// Case name.
    pub name: String,
    /// Sum of squared errors in the window, m².
    pub sse: f64,
    /// `100 (1 − ‖y − ŷ‖ / ‖y − ȳ‖)`, %.
    pub fit_percent: f64,
    /// Samples in the window.
    pub samples: usize,
}

/// The identified model and everything said about it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Identification {
    /// Number of masses.
    pub dof: usize,
    /// The identified model; serialised as its `masses` (kg), `dampers`
    /// (N·s/m) and `springs` (N/m) at the top level of the result.
    #[serde(flatten)]
    pub model: MsdModel,
    /// `F = Σ (x − x̂)²` over all cases, m².
    pub objective: f64,
    /// Per-case fit.
    pub cases: Vec<CaseFit>,
    /// Overall fit %, from all windows together.
    pub fit_percent: f64,
    /// Akaike information criterion `n ln(F/n) + 2q`.
    pub aic: f64,
    /// Bayesian information criterion `n ln(F/n) + q ln n`.
    pub bic: f64,
    /// Residuals n.
    pub residuals: usize,
    /// Uncertainty of the estimate.
    pub uncertainty: Uncertainty,
    /// Starts.
    pub starts: Starts,
    /// Solver iterations of the best start (screening and polishing).
    pub iterations: usize,
    /// Where the best start began, SI, thesis order (free and fixed
    /// parameters): the user's, the data-derived, a continuation or a
    /// random start.
    pub start: Vec<f64>,
    /// Why the best start stopped.
    pub stop: Stop,
    /// Wall-clock time, s.
    pub run_time: f64,
    /// Warnings for the user.
    pub warnings: Vec<String>,
    /// A simpler model that fits as well, when a spring is undetermined
    /// ([`crate::reduce`]).
    pub reduction: Option<bumpsim_estimate::reduce::Reduction<MsdModel>>,
}

impl Identification {
    /// The identified model.
    pub fn model(&self) -> &MsdModel {
        &self.model
    }
}
