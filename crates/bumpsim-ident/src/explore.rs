//! Looking at an identified model: predictions of load cases (validation on
//! a test not used for fitting) and the one-at-a-time sensitivity of the
//! objective (paper B figure 6: each parameter alone scaled by 1 + δ,
//! δ ∈ [−3 %, +3 %]).

use crate::case::{CaseError, LoadCase};
use crate::result::CaseFit;
use bumpsim_core::model::{MsdModel, parameter_count, parameter_name};
use serde::Serialize;

/// A simulated load case next to its measurement.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Prediction {
    /// Fit in the window.
    pub fit: CaseFit,
    /// Sample times, s.
    pub time: Vec<f64>,
    /// Measured displacement, m.
    pub measured: Vec<f64>,
    /// Simulated displacement, m.
    pub simulated: Vec<f64>,
    /// Window start and end, s.
    pub window: [f64; 2],
}

impl Prediction {
    /// The warning of a negative fit (the model follows the displacement
    /// worse than its mean does), if any.
    pub fn warning(&self) -> Option<String> {
        bumpsim_estimate::fit::negative_fit(&self.fit.name, "displacement", self.fit.fit_percent)
    }
}

/// Simulates each case with `model` (core's zoh, as `simulate` and
/// `identify` do); an error names a case the model cannot simulate.
pub fn predict(cases: &[LoadCase], model: &MsdModel) -> Result<Vec<Prediction>, CaseError> {
    cases
        .iter()
        .map(|c| {
            let simulated = c.simulate(model)?;
            let fit = CaseFit::of(c, &simulated);
            let time = (0..c.force.len())
                .map(|k| c.start + k as f64 * c.step)
                .collect::<Vec<_>>();
            let window = fit.window;
            Ok(Prediction {
                fit,
                time,
                measured: c.measured.clone(),
                simulated,
                window,
            })
        })
        .collect()
}

/// The objective along one parameter.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Sweep {
    /// Parameter name.
    pub name: String,
    /// Relative changes δ.
    pub relative_change: Vec<f64>,
    /// Objective at each δ: the thesis's, the displacement's squared
    /// errors summed over the windows ([`objective`]), m², whatever domain
    /// the cases are compared in.
    pub objective: Vec<f64>,
}

/// The objective of `cases` when each parameter of `model` alone is scaled
/// by `1 + δ` for `points` values of δ evenly over `[−fraction, fraction]`.
/// A scaled model that is not a model (δ ≤ −100 %) has objective NaN; a case
/// the model cannot simulate is an error.
pub fn sensitivity(
    cases: &[LoadCase],
    model: &MsdModel,
    fraction: f64,
    points: usize,
) -> Result<Vec<Sweep>, CaseError> {
    let dof = model.dof();
    let theta = model.parameters();
    let deltas: Vec<f64> = (0..points.max(2))
        .map(|j| fraction * (2.0 * j as f64 / (points.max(2) - 1) as f64 - 1.0))
        .collect();
    (0..parameter_count(dof))
        .map(|i| {
            let objective = deltas
                .iter()
                .map(|d| {
                    let mut t = theta.clone();
                    t[i] *= 1.0 + d;
                    MsdModel::from_parameters(dof, &t)
                        .map_or(Ok(f64::NAN), |m| objective(cases, &m))
                })
                .collect::<Result<_, _>>()?;
            Ok(Sweep {
                name: parameter_name(dof, i),
                relative_change: deltas.clone(),
                objective,
            })
        })
        .collect()
}

/// `F = Σ (x − x̂)²` over the windows of `cases`, m²: the thesis's
/// displacement objective, also for cases compared in another domain (their
/// identification minimised that domain's, [`crate::case::Comparison`]).
pub fn objective(cases: &[LoadCase], model: &MsdModel) -> Result<f64, CaseError> {
    cases.iter().map(|c| Ok(c.fit(&c.simulate(model)?).0)).sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::case::{Comparison, Domain};

    /// The sweep's objective is the displacement's squared errors in m²
    /// (what `--sensitivity`'s `[m^2]` header says) also for a case the
    /// identification compares in velocity, weighted: at δ = 0 it is the
    /// case's SSE, not the weighted velocity objective.
    #[test]
    fn the_sweep_is_of_the_displacement_error_in_any_domain() {
        let truth = MsdModel::from_parameters(1, &[1000.0]).unwrap();
        let force: Vec<f64> = (0..200).map(|k| (k as f64 * 0.03).sin() * 1e4).collect();
        let mut case = LoadCase {
            name: "c".into(),
            start: 0.0,
            step: 1e-3,
            force,
            measured: vec![0.0; 200],
            output_dof: 1,
            initial_velocity: 0.0,
            window: (0, 199),
            compare: Comparison::new(Domain::Velocity, Some(1e-6)),
        };
        let simulated = case.simulate(&truth).unwrap();
        case.measured = simulated.iter().map(|x| 1.01 * x + 1e-4).collect();
        let model = MsdModel::from_parameters(1, &[1000.0]).unwrap();
        let sweeps = sensitivity(std::slice::from_ref(&case), &model, 0.03, 13).unwrap();
        let sse = CaseFit::of(&case, &case.simulate(&model).unwrap()).sse;
        assert!(sse > 0.0);
        assert_eq!(sweeps[0].relative_change[6], 0.0);
        assert_eq!(sweeps[0].objective[6], sse);
    }
}
