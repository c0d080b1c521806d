//! Leave-one-load-case-out cross-validation of an identified chain (issue
//! 39): each load case in turn is left out, the model is refitted to the
//! others from the optimum of all of them (one bounded LM run, at most
//! [`ITERATIONS`] iterations), and the refit predicts the case left out.
//! The error is the sum of the left-out cases' squared errors over their
//! windows, `CV = Σ_l Σ_k (x̂_l[k] − x_l^{(−l)}[k])²` (m²), where
//! `x^{(−l)}` is the model fitted without case l (Stone 1974; Hastie,
//! Tibshirani & Friedman 2009, sec. 7.10).
//!
//! Errors of different tests are independent even when the samples of one
//! test are strongly correlated (displacements integrated from noisy
//! accelerations drift), so the prediction error of a left-out test judges
//! a model order without an error model: a mass that only fits one test's
//! drift does not predict another test. The DOF table uses it to decide
//! between orders the effective-sample BIC cannot tell apart
//! ([`crate::choice`]).
//!
//! ```
//! use bumpsim_core::model::MsdModel;
//! use bumpsim_ident::{LoadCase, Settings, identify};
//! use bumpsim_ident::crossval::cross_validate;
//! let truth = MsdModel::new(vec![30.0, 900.0], vec![3e3], vec![6e5]).unwrap();
//! let case = |name: &str, peak: f64| {
//!     let force = (0..300).map(|k| peak * (k as f64 * 5e-4 * 40.0).sin().max(0.0)).collect();
//!     let mut c = LoadCase { name: name.into(), start: 0.0, step: 5e-4, force,
//!         measured: vec![], output_dof: 1, initial_velocity: 0.0, window: (0, 299),
//!         compare: Default::default() };
//!     c.measured = c.simulate(&truth).unwrap();
//!     c
//! };
//! let cases = vec![case("a", 2e4), case("b", 3e4)];
//! let settings = Settings::new(2, 4);
//! let result = identify(&cases, &settings, &|| {}).unwrap();
//! let cv = cross_validate(&cases, &settings, &result).unwrap();
//! assert_eq!(cv.folds.len(), 2);
//! assert!(cv.error < 1e-12, "exact data predict exactly: {} m²", cv.error);
//! ```

use crate::case::{LoadCase, Objective};
pub use crate::result::{CrossValidation, Fold};

use crate::result::Identification;
use crate::settings::Settings;
use bumpsim_estimate::lm;
use rayon::prelude::*;

/// The most LM iterations of one refit (it starts at the optimum of all
/// cases, which is near the optimum without one).
pub const ITERATIONS: usize = 200;

/// The leave-one-case-out cross-validation of `result` (identified from
/// `cases` with `settings`); `None` with fewer than two cases or when a
/// refit cannot be simulated.
pub fn cross_validate(
    cases: &[LoadCase],
    settings: &Settings,
    result: &Identification,
) -> Option<CrossValidation> {
    if cases.len() < 2 {
        return None;
    }
    let folds = (0..cases.len())
        .into_par_iter()
        .map(|l| fold(cases, settings, result, l))
        .collect::<Option<Vec<Fold>>>()?;
    let error = folds.iter().map(|f| f.sse).sum();
    f64::is_finite(error).then_some(CrossValidation { error, folds })
}

/// Case `left` predicted by the model refitted to the other cases.
fn fold(
    cases: &[LoadCase],
    settings: &Settings,
    result: &Identification,
    left: usize,
) -> Option<Fold> {
    let training: Vec<LoadCase> = cases
        .iter()
        .enumerate()
        .filter(|(j, _)| *j != left)
        .map(|(_, c)| c.clone())
        .collect();
    let objective = Objective::new(&training, settings.dof, &settings.bounds.fixed);
    let free = objective.free().to_vec();
    let log = |v: &[f64]| -> Vec<f64> { free.iter().map(|&i| v[i].ln()).collect() };
    let theta = result.model.parameters();
    let (lower, upper) = (log(&settings.bounds.lower), log(&settings.bounds.upper));
    let solver = lm::Settings {
        max_iterations: settings.solver.max_iterations.min(ITERATIONS),
        ..settings.solver
    };
    let refit = lm::minimise(&objective, &log(&theta), &lower, &upper, &solver);
    let model = objective.model(&refit.parameters)?;
    let case = &cases[left];
    let (sse, fit_percent) = case.fit(&case.simulate(&model).ok()?);
    Some(Fold {
        case: case.name.clone(),
        sse,
        fit_percent,
    })
}
