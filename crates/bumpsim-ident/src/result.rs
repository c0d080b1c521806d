//! What a chain identification finds: the model, the fits per case, the
//! information criteria, the uncertainty, the starts and the warnings
//! (serialised as `bumpsim identify --json` writes it). Each case's fit
//! carries its ISO/TS 18571 rating ([`bumpsim_signal::rating`]).

use crate::case::LoadCase;
use crate::stats::Uncertainty;
use bumpsim_core::model::MsdModel;
use bumpsim_estimate::effective::Effective;
use bumpsim_estimate::lm::Stop;
use bumpsim_estimate::multistart::Starts;
use bumpsim_signal::rating::{Rating, rate};
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
    /// ISO/TS 18571 rating of the simulated displacement against the
    /// measured one in the window ([`bumpsim_signal::rating`]); `None`
    /// (JSON `null`) when the window cannot be rated (under 1 ms, over 2 s
    /// at 10 kHz, or a measurement zero throughout).
    pub rating: Option<Rating>,
    /// Times of the window's first and last sample, s of the test's time
    /// (`start + k·step`): the span the fit, SSE and rating are taken over.
    pub window: [f64; 2],
}

impl CaseFit {
    /// The fit of `simulated` (the case's output, m) to the case's
    /// measurement: SSE and fit % ([`LoadCase::fit`]) and the ISO/TS 18571
    /// rating, all over the case's window.
    pub fn of(case: &LoadCase, simulated: &[f64]) -> CaseFit {
        let (sse, fit_percent) = case.fit(simulated);
        let (a, b) = case.window;
        let rating = rate(&case.measured[a..=b], &simulated[a..=b], case.step).ok();
        CaseFit {
            name: case.name.clone(),
            sse,
            fit_percent,
            samples: case.window_len(),
            rating,
            window: [a, b].map(|k| case.start + k as f64 * case.step),
        }
    }
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
    /// `F = Σ (x − x̂)²` over all cases, m² (the thesis's objective); or
    /// in the study's other domain, weighted ([`Identification::compared`]).
    pub objective: f64,
    /// How the cases were compared when not as the thesis (displacement,
    /// unweighted; then absent): their domain and whether each case's
    /// residuals were divided by its noise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub compared: Option<Compared>,
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
    /// The effective sample size of the residuals at the optimum
    /// (spectral, [`bumpsim_estimate::effective`]): the DOF table's
    /// criteria and the posterior's noise model count it.
    pub effective_samples: Effective,
    /// Leave-one-load-case-out cross-validation, when a DOF table ran it
    /// ([`crate::crossval`]).
    pub cross_validation: Option<CrossValidation>,
    /// The stated priors ([`crate::priors`]), each with how far the data
    /// moved its parameter; absent without priors.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub priors: Vec<bumpsim_estimate::prior::Moved>,
    /// The noise of one residual the priors weigh against
    /// ([`bumpsim_estimate::prior::noise`]); absent without priors.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub prior_noise: Option<f64>,
    /// The stated priors themselves (their terms: free parameters), for
    /// the posterior.
    #[serde(skip)]
    pub stated: Vec<bumpsim_estimate::prior::Prior>,
}

/// How an identification compared its cases beyond the thesis's objective.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, serde::Deserialize)]
pub struct Compared {
    /// The domain ([`crate::case::Domain`]).
    pub domain: crate::case::Domain,
    /// Whether the residuals were divided by each case's noise (then the
    /// objective is dimensionless).
    pub weighted: bool,
    /// Whether some cases were weighted and others not (a case without a
    /// noise given or a pre-trigger to estimate it from): the objective
    /// then sums dimensionless terms and terms in the domain's unit squared.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub partly: bool,
}

impl Compared {
    /// The unit of the objective of cases compared so
    /// ([`Identification::objective_unit`]).
    pub fn objective_unit(self) -> String {
        let squared = self.domain.squared_unit();
        match (self.weighted, self.partly) {
            (false, _) => squared.into(),
            (true, false) => "dimensionless".into(),
            (true, true) => format!("dimensionless + {squared}"),
        }
    }

    /// How `cases` are compared; None for the thesis's objective.
    pub fn of(cases: &[LoadCase]) -> Option<Compared> {
        if cases.iter().all(|c| c.compare.is_thesis()) {
            return None;
        }
        let weighted = cases.iter().filter(|c| c.compare.noise.is_some()).count();
        Some(Compared {
            domain: cases.first().map(|c| c.compare.domain).unwrap_or_default(),
            weighted: weighted > 0,
            partly: weighted > 0 && weighted < cases.len(),
        })
    }
}

impl Identification {
    /// The unit of [`Identification::objective`] as printed after it, what
    /// it sums: `m²`, `(m/s)²` or `(m/s²)²` (the domain's unit squared),
    /// `dimensionless` when every case's residuals are divided by its noise
    /// (the line had no unit then), `dimensionless + (m/s)²` when only some
    /// are.
    pub fn objective_unit(&self) -> String {
        self.compared
            .map_or_else(|| "m²".into(), |c| c.objective_unit())
    }

    /// What the objective compares, as a phrase (`acceleration, each case
    /// weighted by its noise`); empty for the thesis's.
    pub fn objective_phrase(&self) -> String {
        match self.compared {
            None => String::new(),
            Some(c) if c.partly => format!(
                "{}, the cases with a noise weighted by it, the others not",
                c.domain
            ),
            Some(c) if c.weighted => format!("{}, each case weighted by its noise", c.domain),
            Some(c) => c.domain.to_string(),
        }
    }
}

/// The leave-one-load-case-out cross-validation of one model order
/// ([`crate::crossval`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CrossValidation {
    /// `Σ` of the left-out cases' squared errors, m².
    pub error: f64,
    /// One fold per load case, in case order.
    pub folds: Vec<Fold>,
}

/// One load case left out and predicted.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Fold {
    /// The case left out.
    pub case: String,
    /// Its squared error over its window, predicted by the model fitted
    /// to the other cases, m².
    pub sse: f64,
    /// Its fit %.
    pub fit_percent: f64,
}

impl Identification {
    /// The identified model.
    pub fn model(&self) -> &MsdModel {
        &self.model
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn case(measured: Vec<f64>, window: (usize, usize)) -> LoadCase {
        LoadCase {
            name: "flat".into(),
            start: 0.0,
            step: 1e-4,
            force: vec![0.0; measured.len()],
            measured,
            output_dof: 1,
            initial_velocity: 0.0,
            window,
            compare: Default::default(),
        }
    }

    #[test]
    fn a_case_fit_carries_the_iso_18571_rating_of_its_window() {
        let x: Vec<f64> = (0..600).map(|k| 0.1 * (k as f64 * 0.005).sin()).collect();
        let flat = case(x.clone(), (100, 499));
        assert_eq!(CaseFit::of(&flat, &x).rating.unwrap().overall, 1.0);
        // the window's times: samples 100 and 499 at 0.1 ms from t = 0
        assert_eq!(CaseFit::of(&flat, &x).window, [100.0 * 1e-4, 499.0 * 1e-4]);
        let low: Vec<f64> = x.iter().map(|v| 0.9 * v).collect();
        let fit = CaseFit::of(&flat, &low);
        let expected = rate(&x[100..=499], &low[100..=499], 1e-4).unwrap();
        assert_eq!(fit.rating, Some(expected));
        assert!(expected.magnitude < 1.0 && expected.slope < 1.0);
        let short = case(x.clone(), (100, 104));
        assert_eq!(
            CaseFit::of(&short, &x).rating,
            None,
            "5 samples are under 1 ms"
        );
        let json = serde_json::to_value(&fit).unwrap();
        assert!(json["rating"]["corridor"].is_number() && json["fit_percent"].is_number());
    }

    /// What the objective sums: the domain's unit squared, or nothing
    /// (dimensionless) when each residual is divided by its case's noise.
    #[test]
    fn the_objective_s_unit_is_what_it_sums() {
        use crate::case::{Comparison, Domain};
        let compared = |domain: Domain, noises: &[Option<f64>]| {
            let cases: Vec<LoadCase> = noises
                .iter()
                .map(|&noise| LoadCase {
                    compare: Comparison::new(domain, noise),
                    ..case(vec![0.0; 10], (0, 9))
                })
                .collect();
            Compared::of(&cases).map_or_else(|| "m²".into(), |c| c.objective_unit())
        };
        assert_eq!(compared(Domain::Displacement, &[None, None]), "m²");
        assert_eq!(compared(Domain::Velocity, &[None]), "(m/s)²");
        assert_eq!(compared(Domain::Acceleration, &[None]), "(m/s²)²");
        let weighted = [Some(0.01), Some(0.02)];
        for domain in [Domain::Displacement, Domain::Velocity, Domain::Acceleration] {
            assert_eq!(compared(domain, &weighted), "dimensionless", "{domain}");
        }
        assert_eq!(
            compared(Domain::Velocity, &[Some(0.01), None]),
            "dimensionless + (m/s)²"
        );
    }
}
