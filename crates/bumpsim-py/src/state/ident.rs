//! The pickled state of an `Identification`: the result (bumpsim-ident)
//! with its uncertainty (bumpsim-estimate) and per-case ratings
//! (bumpsim-signal), the load cases it predicts, the selection notes, the
//! study file and the seed.

use super::{remote_option, remote_seq};
use bumpsim_core::model::MsdModel;
use bumpsim_estimate::bounds::Bounds;
use bumpsim_estimate::effective::{Effective, Method};
use bumpsim_estimate::lm::Stop;
use bumpsim_estimate::multistart::Starts;
use bumpsim_estimate::posterior::{Noise, Posterior};
use bumpsim_estimate::prior::{Moved, Prior};
use bumpsim_estimate::reduce::Reduction;
use bumpsim_estimate::sampler::{Diagnostics, Ensemble};
use bumpsim_estimate::uncertainty::{Correlation, Scale, Share, Uncertainty};
use bumpsim_ident::case::LoadCase;
use bumpsim_ident::crossval::{CrossValidation, Fold};
use bumpsim_ident::estimate::Identification;
use bumpsim_ident::result::CaseFit;
use bumpsim_signal::rating::Rating;
use serde::{Deserialize, Serialize};
use std::path::PathBuf;

/// What an `Identification` holds.
#[derive(Serialize, Deserialize, PartialEq)]
pub struct IdentificationState {
    /// The result.
    #[serde(with = "IdentificationDef")]
    pub result: Identification,
    /// The load cases, as identified.
    #[serde(with = "load_cases")]
    pub cases: Vec<LoadCase>,
    /// The selection notes.
    pub notes: Vec<String>,
    /// The study file, when identified from one.
    pub study: Option<PathBuf>,
    /// The seed of the starts.
    pub seed: u64,
    /// The bounds and fixed values it was identified within (the
    /// posterior's prior).
    #[serde(with = "BoundsDef")]
    pub bounds: Bounds,
}

/// What a `Posterior` holds: the sampled posterior and the identification
/// it was sampled around (its local intervals are printed beside it).
#[derive(Serialize, Deserialize)]
pub struct PosteriorState {
    /// The posterior.
    #[serde(with = "PosteriorDef")]
    pub posterior: Posterior,
    /// The identification.
    #[serde(with = "IdentificationDef")]
    pub result: Identification,
}

/// What a `Prediction` holds.
#[derive(Serialize, Deserialize, PartialEq)]
pub struct PredictionState {
    /// Case name.
    pub name: String,
    /// Sum of squared errors in the window, m².
    pub sse: f64,
    /// Fit in the window, %.
    pub fit_percent: f64,
    /// Window start and end, s.
    pub window: (f64, f64),
    /// Sample times, s.
    pub time: Vec<f64>,
    /// Measured displacement, m.
    pub measured: Vec<f64>,
    /// Simulated displacement, m.
    pub simulated: Vec<f64>,
    /// ISO/TS 18571 rating in the window.
    #[serde(with = "rating")]
    pub rating: Option<Rating>,
}

/// What a `DofTable` holds.
#[derive(Serialize, Deserialize, PartialEq)]
pub struct DofTableState {
    /// The orders identified.
    pub results: Vec<IdentificationState>,
    /// The orders that failed, with why.
    pub failed: Vec<(usize, String)>,
    /// The selection notes.
    pub notes: Vec<String>,
}

/// What a `LoadCase` holds.
#[derive(Serialize, Deserialize, PartialEq)]
pub struct LoadCaseState(#[serde(with = "LoadCaseDef")] pub LoadCase);

/// A load case (public fields, validated when it was made).
#[derive(Serialize, Deserialize)]
#[serde(remote = "LoadCase")]
pub struct LoadCaseDef {
    name: String,
    start: f64,
    step: f64,
    force: Vec<f64>,
    measured: Vec<f64>,
    output_dof: usize,
    initial_velocity: f64,
    window: (usize, usize),
    compare: bumpsim_ident::case::Comparison,
}

remote_seq!(load_cases, LoadCase, "LoadCaseDef");

/// A chain model as its masses, dampers and springs (validated again).
mod model {
    use super::*;
    type Parts = (Vec<f64>, Vec<f64>, Vec<f64>);

    pub fn parts(m: &MsdModel) -> Parts {
        (
            m.masses().to_vec(),
            m.dampers().to_vec(),
            m.springs().to_vec(),
        )
    }
    pub fn serialize<S: serde::Serializer>(m: &MsdModel, s: S) -> Result<S::Ok, S::Error> {
        parts(m).serialize(s)
    }
    pub fn deserialize<'de, D: serde::Deserializer<'de>>(d: D) -> Result<MsdModel, D::Error> {
        let (m, c, k) = Parts::deserialize(d)?;
        MsdModel::new(m, c, k).map_err(serde::de::Error::custom)
    }
}

#[derive(Serialize, Deserialize)]
#[serde(remote = "Rating")]
struct RatingDef {
    overall: f64,
    corridor: f64,
    phase: f64,
    magnitude: f64,
    slope: f64,
}

remote_option!(rating, Rating, "RatingDef");

#[derive(Serialize, Deserialize)]
#[serde(remote = "CaseFit")]
struct CaseFitDef {
    name: String,
    sse: f64,
    fit_percent: f64,
    samples: usize,
    #[serde(with = "rating")]
    rating: Option<Rating>,
    window: [f64; 2],
}

remote_seq!(case_fits, CaseFit, "CaseFitDef");

#[derive(Serialize, Deserialize)]
#[serde(remote = "Share")]
struct ShareDef {
    parameter: String,
    share: f64,
    component: f64,
}

remote_seq!(shares, Share, "ShareDef");

#[derive(Serialize, Deserialize)]
#[serde(remote = "Scale")]
enum ScaleDef {
    Log,
    Linear(f64),
}

remote_seq!(scales, Scale, "ScaleDef");

#[derive(Serialize, Deserialize)]
#[serde(remote = "Correlation")]
enum CorrelationDef {
    Independent,
    Ar1,
    Spectral,
    RandomWalk,
}

#[derive(Serialize, Deserialize)]
#[serde(remote = "Uncertainty")]
struct UncertaintyDef {
    names: Vec<String>,
    standard_errors: Vec<Option<f64>>,
    ci95: Vec<Option<[f64; 2]>>,
    at_bound: Vec<bool>,
    fixed: Vec<bool>,
    correlation: Vec<Vec<Option<f64>>>,
    residual_std: f64,
    degrees_of_freedom: usize,
    singular_values: Vec<f64>,
    condition: f64,
    #[serde(with = "scales")]
    scales: Vec<Scale>,
    determined: Vec<Option<bool>>,
    #[serde(with = "shares")]
    weakest_direction: Vec<Share>,
    #[serde(with = "CorrelationDef")]
    error_model: Correlation,
    residual_correlation: f64,
    inflation: f64,
    warnings: Vec<String>,
}

#[derive(Serialize, Deserialize)]
#[serde(remote = "Starts")]
struct StartsDef {
    total: usize,
    converged: usize,
    failed: usize,
    reached_best: usize,
    reached_best_alone: usize,
    reached_best_fit: usize,
    reached_best_fit_alone: usize,
    #[serde(default)]
    reached_correlated: usize,
    #[serde(default)]
    explored_correlated: usize,
    #[serde(default = "unit_inflation")]
    inflation: f64,
    abandoned: usize,
    merged: usize,
    unpolished: usize,
    refined: usize,
    explored_best_fit: usize,
    best: usize,
}

/// An identification pickled before the correlated counts: κ 1, whose
/// counts are the white ones ([`starts_state`]).
fn unit_inflation() -> f64 {
    1.0
}

/// [`Starts`] through [`StartsDef`]; where κ is 1 (none stated, or a
/// pickle from before the correlated counts) the correlated counts are the
/// white ones, as the tally sets them.
mod starts_state {
    use super::*;

    pub fn serialize<S: serde::Serializer>(s: &Starts, serializer: S) -> Result<S::Ok, S::Error> {
        StartsDef::serialize(s, serializer)
    }

    pub fn deserialize<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Starts, D::Error> {
        let mut s = StartsDef::deserialize(d)?;
        if s.inflation <= 1.0 {
            s.reached_correlated = s.reached_best_fit;
            s.explored_correlated = s.explored_best_fit;
        }
        Ok(s)
    }
}

/// The simpler model, its chain model as parts.
mod reduction {
    use super::*;
    type Parts = (
        String,
        String,
        (Vec<f64>, Vec<f64>, Vec<f64>),
        f64,
        f64,
        f64,
    );

    pub fn serialize<S: serde::Serializer>(
        r: &Option<Reduction<MsdModel>>,
        s: S,
    ) -> Result<S::Ok, S::Error> {
        let parts: Option<Parts> = r.as_ref().map(|r| {
            let Reduction {
                parameter,
                statement,
                model,
                objective,
                relative_objective,
                p_value,
            } = r;
            let model = super::model::parts(model);
            let numbers = (*objective, *relative_objective, *p_value);
            (
                parameter.clone(),
                statement.clone(),
                model,
                numbers.0,
                numbers.1,
                numbers.2,
            )
        });
        parts.serialize(s)
    }
    pub fn deserialize<'de, D: serde::Deserializer<'de>>(
        d: D,
    ) -> Result<Option<Reduction<MsdModel>>, D::Error> {
        let parts: Option<Parts> = Option::deserialize(d)?;
        parts
            .map(
                |(parameter, statement, (m, c, k), objective, relative_objective, p_value)| {
                    Ok(Reduction {
                        parameter,
                        statement,
                        model: MsdModel::new(m, c, k).map_err(serde::de::Error::custom)?,
                        objective,
                        relative_objective,
                        p_value,
                    })
                },
            )
            .transpose()
    }
}

#[derive(Serialize, Deserialize)]
#[serde(remote = "Method")]
enum MethodDef {
    Independent,
    Ar1,
    Spectral,
}

#[derive(Serialize, Deserialize)]
#[serde(remote = "Effective")]
struct EffectiveDef {
    #[serde(with = "MethodDef")]
    method: Method,
    samples: usize,
    effective: f64,
    time: f64,
    lag_one: f64,
    window: usize,
    reliable: bool,
}

#[derive(Serialize, Deserialize)]
#[serde(remote = "Fold")]
struct FoldDef {
    case: String,
    sse: f64,
    fit_percent: f64,
}

remote_seq!(folds, Fold, "FoldDef");

#[derive(Serialize, Deserialize)]
#[serde(remote = "CrossValidation")]
struct CrossValidationDef {
    error: f64,
    #[serde(with = "folds")]
    folds: Vec<Fold>,
}

remote_option!(cross_validation, CrossValidation, "CrossValidationDef");

#[derive(Serialize, Deserialize)]
#[serde(remote = "Identification")]
struct IdentificationDef {
    dof: usize,
    #[serde(with = "model")]
    model: MsdModel,
    objective: f64,
    compared: Option<bumpsim_ident::result::Compared>,
    #[serde(with = "case_fits")]
    cases: Vec<CaseFit>,
    fit_percent: f64,
    aic: f64,
    bic: f64,
    residuals: usize,
    #[serde(with = "UncertaintyDef")]
    uncertainty: Uncertainty,
    #[serde(with = "starts_state")]
    starts: Starts,
    iterations: usize,
    start: Vec<f64>,
    stop: Stop,
    run_time: f64,
    warnings: Vec<String>,
    #[serde(with = "reduction")]
    reduction: Option<Reduction<MsdModel>>,
    #[serde(with = "EffectiveDef")]
    effective_samples: Effective,
    #[serde(with = "cross_validation")]
    cross_validation: Option<CrossValidation>,
    #[serde(with = "moved_priors", default)]
    priors: Vec<Moved>,
    #[serde(default)]
    prior_noise: Option<f64>,
    #[serde(with = "stated_priors", default)]
    stated: Vec<Prior>,
}

#[derive(Serialize, Deserialize)]
#[serde(remote = "Moved")]
struct MovedDef {
    name: String,
    centre: f64,
    spread: f64,
    source: String,
    estimate: f64,
    z: f64,
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    ratio: bool,
}

remote_seq!(moved_priors, Moved, "MovedDef");

#[derive(Serialize, Deserialize)]
#[serde(remote = "Prior")]
struct PriorDef {
    name: String,
    terms: Vec<usize>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    less: Vec<usize>,
    centre: f64,
    spread: f64,
    source: String,
}

remote_seq!(stated_priors, Prior, "PriorDef");

#[derive(Serialize, Deserialize)]
#[serde(remote = "Bounds")]
struct BoundsDef {
    lower: Vec<f64>,
    upper: Vec<f64>,
    fixed: Vec<Option<f64>>,
}

#[derive(Serialize, Deserialize)]
#[serde(remote = "Noise")]
enum NoiseDef {
    Effective(f64),
    Known(f64),
    Whitened,
}

#[derive(Serialize, Deserialize)]
#[serde(remote = "Ensemble")]
struct EnsembleDef {
    walkers: usize,
    steps: usize,
    burn: usize,
    seed: u64,
}

#[derive(Serialize, Deserialize)]
#[serde(remote = "Diagnostics")]
struct DiagnosticsDef {
    autocorrelation_time: Vec<f64>,
    time_reliable: Vec<bool>,
    effective_draws: Vec<f64>,
    r_hat: Vec<f64>,
    acceptance: f64,
    converged: bool,
    warnings: Vec<String>,
}

#[derive(Serialize, Deserialize)]
#[serde(remote = "Posterior")]
struct PosteriorDef {
    names: Vec<String>,
    mean: Vec<f64>,
    median: Vec<f64>,
    sd: Vec<f64>,
    ci90: Vec<Option<[f64; 2]>>,
    ci95: Vec<Option<[f64; 2]>>,
    fixed: Vec<bool>,
    #[serde(with = "NoiseDef")]
    noise: Noise,
    #[serde(with = "EnsembleDef")]
    ensemble: Ensemble,
    #[serde(with = "DiagnosticsDef")]
    diagnostics: Diagnostics,
    draws: Vec<Vec<f64>>,
}
