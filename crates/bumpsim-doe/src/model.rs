//! Model files (JSON) and prediction in physical units (spec §7).
//!
//! A model file names the factors with their low and high levels (physical
//! units) and, per response, the coded coefficients by term name
//! (`intercept`, `A`, `A*B`, `A^2`). `bumpsim doe fit` writes the full form
//! (standard errors, intervals, R², Q², PRESS, σ and (XᵀX)⁻¹); a file written
//! by hand from published coefficients needs only `factors` and, per
//! response, `name` and `coefficients` (docs/doe.md). Prediction converts
//! physical values to coded ones, `z = (X − centre) / (high − centre)`,
//! evaluates the model and, where σ and (XᵀX)⁻¹ are known, gives the 95 %
//! confidence interval of the mean `ŷ ± t s sqrt(x₀ᵀ(XᵀX)⁻¹x₀)` and the
//! prediction interval `ŷ ± t s sqrt(1 + x₀ᵀ(XᵀX)⁻¹x₀)`. A point outside the
//! design region (|z| > 1 for a factor) is flagged.
//!
//! ```
//! use bumpsim_doe::model::ModelFile;
//! let text = r#"{"factors": [{"name": "M", "low": 1375, "high": 1681}],
//!   "responses": [{"name": "m2", "coefficients": {"intercept": 1987, "M": 215.63}}]}"#;
//! let model: ModelFile = serde_json::from_str(text).unwrap();
//! let p = model.predict(&[("M".into(), 1681.0)]).unwrap();
//! assert!((p.values[0].value - 2202.63).abs() < 1e-9);
//! ```

use crate::regression::Term;
use serde::{Deserialize, Serialize};
use statrs::distribution::{ContinuousCDF, StudentsT};
use std::collections::BTreeMap;

/// Why a prediction cannot be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ModelError {
    /// A factor value is missing or unknown.
    #[error("{0}")]
    Input(String),
}

/// A factor with its physical range.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Factor {
    /// Name.
    pub name: String,
    /// Low level (coded −1), physical units.
    pub low: f64,
    /// High level (coded +1), physical units.
    pub high: f64,
    /// Unit, for people.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub unit: Option<String>,
}

impl Factor {
    /// Coded value of a physical one.
    pub fn coded(&self, value: f64) -> f64 {
        (value - 0.5 * (self.low + self.high)) / (0.5 * (self.high - self.low))
    }

    /// Physical value of a coded one.
    pub fn physical(&self, coded: f64) -> f64 {
        0.5 * (self.low + self.high) + coded * 0.5 * (self.high - self.low)
    }
}

/// One response's model.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Response {
    /// Name.
    pub name: String,
    /// Unit, for people.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub unit: Option<String>,
    /// Coded coefficients by term name, with `intercept`.
    pub coefficients: BTreeMap<String, f64>,
    /// Standard errors by term.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub std_errors: Option<BTreeMap<String, Option<f64>>>,
    /// 95 % intervals by term.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ci95: Option<BTreeMap<String, Option<[f64; 2]>>>,
    /// R².
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub r2: Option<f64>,
    /// Adjusted R².
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub r2_adjusted: Option<f64>,
    /// Q² (`null` when undefined).
    #[serde(default)]
    pub q2: Option<f64>,
    /// Why Q² is undefined.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub q2_note: Option<String>,
    /// PRESS.
    #[serde(default)]
    pub press: Option<f64>,
    /// Residual standard deviation.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub residual_sd: Option<f64>,
    /// n − p.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dof_residual: Option<usize>,
    /// Term order of `xtx_inverse`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub terms: Option<Vec<String>>,
    /// (XᵀX)⁻¹ in the order of `terms`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub xtx_inverse: Option<Vec<Vec<f64>>>,
}

/// A model file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelFile {
    /// The factors.
    pub factors: Vec<Factor>,
    /// The responses.
    pub responses: Vec<Response>,
}

/// One predicted response.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Predicted {
    /// Response name.
    pub name: String,
    /// Unit, if known.
    pub unit: Option<String>,
    /// Predicted mean.
    pub value: f64,
    /// 95 % confidence interval of the mean.
    pub ci95: Option<[f64; 2]>,
    /// 95 % prediction interval of a new observation.
    pub pi95: Option<[f64; 2]>,
}

/// A prediction at one point.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Prediction {
    /// Coded factor values.
    pub coded: Vec<f64>,
    /// Per response.
    pub values: Vec<Predicted>,
    /// Warnings (outside the design region).
    pub warnings: Vec<String>,
}

impl ModelFile {
    /// Predicts every response at physical factor values `(name, value)`.
    pub fn predict(&self, at: &[(String, f64)]) -> Result<Prediction, ModelError> {
        for (name, _) in at {
            if !self.factors.iter().any(|f| &f.name == name) {
                let known: Vec<&str> = self.factors.iter().map(|f| f.name.as_str()).collect();
                return Err(ModelError::Input(format!(
                    "unknown factor '{name}'; the model's factors: {}",
                    known.join(", ")
                )));
            }
        }
        let mut coded = Vec::new();
        let mut warnings = Vec::new();
        for f in &self.factors {
            let value = at
                .iter()
                .find(|(n, _)| n == &f.name)
                .map(|(_, v)| *v)
                .ok_or_else(|| {
                    ModelError::Input(format!(
                        "no value for factor '{}': give {}=VALUE",
                        f.name, f.name
                    ))
                })?;
            let z = f.coded(value);
            if z.abs() > 1.0 + 1e-9 {
                warnings.push(format!("{} = {value} is outside the design region {}..{} (coded {z:.3}): extrapolation", f.name, f.low, f.high));
            }
            coded.push(z);
        }
        let names: Vec<String> = self.factors.iter().map(|f| f.name.clone()).collect();
        let values = self
            .responses
            .iter()
            .map(|r| r.predict(&coded, &names))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Prediction {
            coded,
            values,
            warnings,
        })
    }
}

impl Response {
    fn predict(&self, z: &[f64], factors: &[String]) -> Result<Predicted, ModelError> {
        let mut value = 0.0;
        for (name, c) in &self.coefficients {
            let term = Term::parse(name, factors).ok_or_else(|| {
                ModelError::Input(format!(
                    "response '{}': term '{name}' names no factor ({})",
                    self.name,
                    factors.join(", ")
                ))
            })?;
            value += c * term.value(z);
        }
        let (ci95, pi95) = self.intervals(z, factors, value).unzip();
        Ok(Predicted {
            name: self.name.clone(),
            unit: self.unit.clone(),
            value,
            ci95,
            pi95,
        })
    }

    fn intervals(&self, z: &[f64], factors: &[String], value: f64) -> Option<([f64; 2], [f64; 2])> {
        let (terms, inverse, sd, df) = (
            self.terms.as_ref()?,
            self.xtx_inverse.as_ref()?,
            self.residual_sd?,
            self.dof_residual?,
        );
        let x: Vec<f64> = terms
            .iter()
            .map(|t| Term::parse(t, factors).map(|t| t.value(z)))
            .collect::<Option<_>>()?;
        let quadratic: f64 = (0..x.len())
            .map(|a| {
                (0..x.len())
                    .map(|b| x[a] * inverse[a][b] * x[b])
                    .sum::<f64>()
            })
            .sum();
        let t = StudentsT::new(0.0, 1.0, df as f64).ok()?.inverse_cdf(0.975);
        let (c, p) = (t * sd * quadratic.sqrt(), t * sd * (1.0 + quadratic).sqrt());
        Some(([value - c, value + c], [value - p, value + p]))
    }
}

impl Response {
    /// The model file entry of a fitted response.
    pub fn from_fit(name: &str, unit: Option<String>, fit: &crate::regression::Fit) -> Response {
        let by_term = |values: &[Option<f64>]| {
            fit.terms
                .iter()
                .cloned()
                .zip(values.iter().copied())
                .collect::<BTreeMap<_, _>>()
        };
        Response {
            name: name.to_string(),
            unit,
            coefficients: fit
                .terms
                .iter()
                .cloned()
                .zip(fit.coefficients.iter().copied())
                .collect(),
            std_errors: Some(by_term(&fit.std_errors)),
            ci95: Some(
                fit.terms
                    .iter()
                    .cloned()
                    .zip(fit.ci95.iter().copied())
                    .collect(),
            ),
            r2: Some(fit.r2),
            r2_adjusted: fit.r2_adjusted,
            q2: fit.q2,
            q2_note: fit.q2_note.clone(),
            press: fit.press,
            residual_sd: fit.residual_sd,
            dof_residual: Some(fit.dof_residual),
            terms: Some(fit.terms.clone()),
            xtx_inverse: Some(fit.xtx_inverse.clone()),
        }
    }
}
