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
use bumpsim_core::units::short;
use serde::{Deserialize, Serialize};
use statrs::distribution::{ContinuousCDF, StudentsT};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::str::FromStr;

/// Why a prediction cannot be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
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

/// Why a factor's range is unusable.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum FactorError {
    /// A `NAME:LOW:HIGH` specification that does not parse.
    #[error(
        "'{spec}': expected NAME:LOW:HIGH with finite LOW < HIGH (HIGH - LOW finite, and LOW + HIGH: the levels are the centre ± half the span)"
    )]
    Spec {
        /// The text as given.
        spec: String,
    },
    /// A name the files and terms cannot hold.
    #[error("factor '{name}': {reason}")]
    Name {
        /// The name as given.
        name: String,
        /// What is wrong.
        reason: &'static str,
    },
    /// A range whose low level is not below its high level.
    #[error(
        "factor '{name}': low {low} must be finite and below high {high}, their span and their sum finite numbers (a factor that does not vary cannot be fitted; the design's levels are centre ± half the span)"
    )]
    Range {
        /// Factor name.
        name: String,
        /// Low level.
        low: f64,
        /// High level.
        high: f64,
    },
}

/// Parses `NAME:LOW:HIGH` (physical units, finite LOW < HIGH).
///
/// ```
/// use bumpsim_doe::model::Factor;
/// let f: Factor = "Kax:20000:26000".parse().unwrap();
/// assert_eq!((f.name.as_str(), f.low, f.high), ("Kax", 20000.0, 26000.0));
/// assert!("Kax:5:1".parse::<Factor>().is_err());
/// ```
impl FromStr for Factor {
    type Err = FactorError;

    fn from_str(spec: &str) -> Result<Factor, FactorError> {
        let bad = || FactorError::Spec { spec: spec.into() };
        let parts: Vec<&str> = spec.split(':').collect();
        let [name, low, high] = parts[..] else {
            return Err(bad());
        };
        let low: f64 = low.trim().parse().map_err(|_| bad())?;
        let high: f64 = high.trim().parse().map_err(|_| bad())?;
        Factor::new(name.trim(), low, high, None).map_err(|e| match e {
            FactorError::Name { .. } => e,
            _ => bad(),
        })
    }
}

/// Characters a factor name cannot hold: they separate the fields of the
/// command line (`,` `:` `=`), of model terms (`*` `^`) and of CSV headers
/// (`[` `]` `"`).
pub const RESERVED: [char; 8] = [',', ':', '=', '*', '^', '[', ']', '"'];

/// Checks a factor name: not empty, no surrounding spaces, no control or
/// [`RESERVED`] character, and not `intercept` (a model term of its own).
pub fn check_name(name: &str) -> Result<(), FactorError> {
    let bad = |reason| {
        Err(FactorError::Name {
            name: name.escape_debug().to_string(),
            reason,
        })
    };
    if name.trim().is_empty() {
        return bad("an empty name");
    }
    if name.trim() != name {
        return bad("spaces around the name");
    }
    if name
        .chars()
        .any(|c| c.is_control() || RESERVED.contains(&c))
    {
        return bad("a control character or one of , : = * ^ [ ] \" in the name");
    }
    if name.eq_ignore_ascii_case("intercept") {
        return bad("'intercept' is the model's constant term; name the factor otherwise");
    }
    Ok(())
}

impl Factor {
    /// A factor whose finite low level lies below its finite high level.
    pub fn new(
        name: &str,
        low: f64,
        high: f64,
        unit: Option<String>,
    ) -> Result<Factor, FactorError> {
        check_name(name)?;
        if !(low < high && (high - low).is_finite() && (low + high).is_finite()) {
            return Err(FactorError::Range {
                name: name.into(),
                low,
                high,
            });
        }
        Ok(Factor {
            name: name.into(),
            low,
            high,
            unit,
        })
    }

    /// A factor over the levels given, each defaulting to the extreme of
    /// the observed `values` (the data's minimum and maximum).
    pub fn spanning(
        name: &str,
        values: &[f64],
        low: Option<f64>,
        high: Option<f64>,
        unit: Option<String>,
    ) -> Result<Factor, FactorError> {
        let low = low.unwrap_or_else(|| values.iter().copied().fold(f64::INFINITY, f64::min));
        let high = high.unwrap_or_else(|| values.iter().copied().fold(f64::NEG_INFINITY, f64::max));
        Factor::new(name, low, high, unit)
    }

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
    /// A fit weighted by the response's standard errors (`doe fit --se`):
    /// its intervals come from τ² and the covariance, not `residual_sd`
    /// and `xtx_inverse`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub weighted: Option<Weighted>,
}

/// How a response was weighted by its standard errors
/// ([`crate::weighted`]): what prediction needs and what a reader checks.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Weighted {
    /// The column of standard errors.
    pub column: String,
    /// `REML`, or `OLS` when every standard error is zero.
    pub method: String,
    /// τ² (unit²); `null` when not estimable (saturated).
    pub tau2: Option<f64>,
    /// The coefficients' covariance (XᵀWX)⁻¹ (unit²) in the order of
    /// `terms`; `null` without τ².
    pub covariance: Option<Vec<Vec<f64>>>,
    /// Each run's weight 1/(τ² + s²) (1/unit²).
    pub weights: Vec<f64>,
    /// Residual heterogeneity (Cochran's Q_E), when every SE is positive.
    #[serde(default)]
    pub heterogeneity: Option<crate::weighted::Heterogeneity>,
    /// The OLS standard errors by term, for comparison.
    pub ols_std_errors: BTreeMap<String, Option<f64>>,
    /// Notes (τ² at 0, not estimable).
    #[serde(default)]
    pub notes: Vec<String>,
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

/// Why a model file cannot be read.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ModelFileError {
    /// The file cannot be read.
    #[error("cannot read {}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The reason.
        source: std::io::Error,
    },
    /// Not a regular file, too large or not text.
    #[error(transparent)]
    Read(#[from] bumpsim_core::files::ReadError),
    /// The file is not a model file's JSON.
    #[error("{}: not a DOE model file", path.display())]
    Json {
        /// The file.
        path: PathBuf,
        /// The reason.
        source: serde_json::Error,
    },
}

impl ModelFile {
    /// Reads a model file (JSON, as `doe fit` writes it or by hand).
    pub fn read(path: &Path) -> Result<ModelFile, ModelFileError> {
        let text = bumpsim_core::files::read_text(path)?;
        serde_json::from_str(&text).map_err(|source| ModelFileError::Json {
            path: path.into(),
            source,
        })
    }

    /// Checks a model read from a file: finite factor ranges with low < high,
    /// finite coefficients, a non-negative finite `residual_sd`, and an
    /// `xtx_inverse` that is square with one row per term.
    pub fn validate(&self) -> Result<(), ModelError> {
        let bad = |what: String| Err(ModelError::Input(format!("model file: {what}")));
        for (i, f) in self.factors.iter().enumerate() {
            if let Err(e) = check_name(&f.name) {
                return bad(e.to_string());
            }
            if self.factors[..i].iter().any(|g| g.name == f.name) {
                return bad(format!("factor '{}' is listed twice", f.name));
            }
            if !(f.low < f.high && (f.high - f.low).is_finite()) {
                return bad(format!(
                    "factor '{}': need finite low < high with a finite span, got {}..{}",
                    f.name, f.low, f.high
                ));
            }
        }
        for (i, r) in self.responses.iter().enumerate() {
            if r.name.trim().is_empty() || self.responses[..i].iter().any(|s| s.name == r.name) {
                return bad(format!(
                    "response '{}': a response needs a name of its own (empty or listed twice)",
                    r.name
                ));
            }
            if let Some((term, c)) = r.coefficients.iter().find(|(_, c)| !c.is_finite()) {
                return bad(format!(
                    "response '{}': coefficient of '{term}' is {c}",
                    r.name
                ));
            }
            if let Some(sd) = r.residual_sd.filter(|sd| !(sd.is_finite() && *sd >= 0.0)) {
                return bad(format!(
                    "response '{}': residual_sd = {sd}, expected a finite value ≥ 0",
                    r.name
                ));
            }
            let n = r.terms.as_ref().map_or(0, Vec::len);
            let square = |m: &Vec<Vec<f64>>| {
                r.terms.is_some()
                    && m.len() == n
                    && m.iter()
                        .all(|row| row.len() == n && row.iter().all(|v| v.is_finite()))
            };
            let weighted = r.weighted.as_ref();
            for (what, matrix) in [
                ("xtx_inverse", r.xtx_inverse.as_ref()),
                (
                    "weighted.covariance",
                    weighted.and_then(|w| w.covariance.as_ref()),
                ),
            ] {
                if matrix.is_some_and(|m| !square(m)) {
                    return bad(format!(
                        "response '{}': {what} must be {n} × {n} finite values (one row and column per term)",
                        r.name
                    ));
                }
            }
            if let Some(t) = weighted
                .and_then(|w| w.tau2)
                .filter(|t| !(t.is_finite() && *t >= 0.0))
            {
                return bad(format!(
                    "response '{}': weighted.tau2 = {t}, expected a finite value ≥ 0",
                    r.name
                ));
            }
        }
        Ok(())
    }

    /// Predicts every response at physical factor values `(name, value)`.
    pub fn predict(&self, at: &[(String, f64)]) -> Result<Prediction, ModelError> {
        self.validate()?;
        if let Some((name, value)) = at.iter().find(|(_, v)| !v.is_finite()) {
            return Err(ModelError::Input(format!(
                "{name} = {value}: a factor value must be a finite number"
            )));
        }
        for (i, (name, _)) in at.iter().enumerate() {
            if at[..i].iter().any(|(n, _)| n == name) {
                return Err(ModelError::Input(format!(
                    "factor '{name}' is given twice: give each factor once"
                )));
            }
            if !self.factors.iter().any(|f| &f.name == name) {
                let known: Vec<&str> = self.factors.iter().map(|f| f.name.as_str()).collect();
                return Err(ModelError::Input(format!(
                    "unknown factor '{name}'; the model's factors: {}",
                    known.join(", ")
                )));
            }
        }
        let mut coded = Vec::new();
        let (mut warnings, mut outside) = (Vec::new(), Vec::new());
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
                outside.push(format!("{} = {}", f.name, short(value)));
            }
            coded.push(z);
        }
        let names: Vec<String> = self.factors.iter().map(|f| f.name.clone()).collect();
        let values = self
            .responses
            .iter()
            .map(|r| r.predict(&coded, &names, &outside))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Prediction {
            coded,
            values,
            warnings,
        })
    }
}

impl Response {
    /// The prediction at coded `z`; `outside` names the factor values
    /// beyond the design region, for the refusal of an overflow.
    fn predict(
        &self,
        z: &[f64],
        factors: &[String],
        outside: &[String],
    ) -> Result<Predicted, ModelError> {
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
        let finite = |i: Option<[f64; 2]>| i.is_none_or(|[a, b]| a.is_finite() && b.is_finite());
        if !(value.is_finite() && finite(ci95) && finite(pi95)) {
            let far = match outside.is_empty() {
                true => "the factor values lie".to_string(),
                false => outside.join(", ") + if outside.len() > 1 { " lie" } else { " lies" },
            };
            return Err(ModelError::Input(format!(
                "response '{}': the prediction is {value} (beyond the largest number): {far} too far outside the design region",
                self.name
            )));
        }
        Ok(Predicted {
            name: self.name.clone(),
            unit: self.unit.clone(),
            value,
            ci95,
            pi95,
        })
    }

    /// The 95 % intervals at coded `z`: of the mean, `ŷ ± t f sqrt(x₀ᵀMx₀)`,
    /// and of a new observation, `ŷ ± t f sqrt(a + x₀ᵀMx₀)`, t on n − p
    /// degrees of freedom. OLS: M = (XᵀX)⁻¹, f = σ, a = 1. A weighted fit:
    /// M = its covariance (XᵀWX)⁻¹, f = 1, a = τ² (the interval of a new
    /// car's true value, without a new identification's own error).
    fn intervals(&self, z: &[f64], factors: &[String], value: f64) -> Option<([f64; 2], [f64; 2])> {
        let (terms, df) = (self.terms.as_ref()?, self.dof_residual?);
        let (matrix, f, a) = match &self.weighted {
            Some(w) => (w.covariance.as_ref()?, 1.0, w.tau2?),
            None => (self.xtx_inverse.as_ref()?, self.residual_sd?, 1.0),
        };
        let quadratic = quadratic_form(terms, matrix, z, factors)?;
        let t = StudentsT::new(0.0, 1.0, df as f64).ok()?.inverse_cdf(0.975);
        let (c, p) = (t * f * quadratic.sqrt(), t * f * (a + quadratic).sqrt());
        Some(([value - c, value + c], [value - p, value + p]))
    }
}

/// `x₀ᵀ M x₀` with x₀ the model terms at coded `z`.
fn quadratic_form(terms: &[String], m: &[Vec<f64>], z: &[f64], factors: &[String]) -> Option<f64> {
    let x: Vec<f64> = terms
        .iter()
        .map(|t| Term::parse(t, factors).map(|t| t.value(z)))
        .collect::<Option<_>>()?;
    Some(
        (0..x.len())
            .map(|a| (0..x.len()).map(|b| x[a] * m[a][b] * x[b]).sum::<f64>())
            .sum(),
    )
}

impl Response {
    /// The model file entry of a response fitted with its standard errors
    /// in `column`.
    pub fn from_weighted(
        name: &str,
        unit: Option<String>,
        fitted: &crate::weighted::WeightedFit,
        column: &str,
    ) -> Response {
        let (fit, w) = (&fitted.fit, &fitted.weighting);
        let mut response = Response::from_fit(name, unit, fit);
        let reml = w.method != "OLS";
        if reml {
            response.xtx_inverse = None;
        }
        let covariance = match reml {
            true => Some(fit.xtx_inverse.clone()),
            false => w.tau2.map(|t| {
                let scaled = |row: &Vec<f64>| row.iter().map(|v| v * t).collect();
                fit.xtx_inverse.iter().map(scaled).collect()
            }),
        };
        response.weighted = Some(Weighted {
            column: column.into(),
            method: w.method.clone(),
            tau2: w.tau2,
            covariance: w.tau2.and(covariance),
            weights: w.weights.clone(),
            heterogeneity: w.heterogeneity,
            ols_std_errors: fit
                .terms
                .iter()
                .cloned()
                .zip(w.ols_std_errors.iter().copied())
                .collect(),
            notes: w.notes.clone(),
        });
        response
    }

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
            weighted: None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// A finite value of either sign from 1e-300 to 1e300, or zero.
    fn value() -> impl Strategy<Value = f64> {
        let magnitude = (1.0..10.0f64, -300..300i32).prop_map(|(m, e)| m * 10f64.powi(e));
        prop_oneof![Just(0.0), magnitude.clone(), magnitude.prop_map(|v| -v)]
    }

    fn response() -> impl Strategy<Value = Response> {
        let coefficients = prop::collection::btree_map("[a-z]{1,3}(\\*[a-z]{1,3})?", value(), 1..6);
        let unit = proptest::option::of("[a-zA-Z/\"\\\\ \u{e9}\u{b2}]{0,6}");
        (
            ("[a-zA-Z_][a-zA-Z0-9_]{0,8}"),
            unit,
            coefficients,
            proptest::option::of(value()),
            proptest::option::of(weighted()),
        )
            .prop_map(|(name, unit, coefficients, q2, weighted)| Response {
                name,
                unit,
                std_errors: Some(
                    coefficients
                        .keys()
                        .map(|k| (k.clone(), Some(1.5)))
                        .collect(),
                ),
                coefficients,
                ci95: None,
                r2: Some(0.97),
                r2_adjusted: None,
                q2,
                q2_note: None,
                press: q2,
                residual_sd: Some(2.5e-3),
                dof_residual: Some(4),
                terms: Some(vec!["intercept".into()]),
                xtx_inverse: Some(vec![vec![0.125]]),
                weighted,
            })
    }

    /// A weighting as `doe fit --se` writes it, τ² and the covariance
    /// possibly left out (a saturated model).
    fn weighted() -> impl Strategy<Value = Weighted> {
        let heterogeneity = (value(), 1..50usize, value())
            .prop_map(|(q, df, p)| crate::weighted::Heterogeneity { q, df, p });
        (
            "[a-zA-Z_.][a-zA-Z0-9_. \u{e9}]{0,8}",
            proptest::option::of(value()),
            proptest::option::of(value()),
            prop::collection::vec(value(), 1..6),
            proptest::option::of(heterogeneity),
            proptest::option::of(value()),
            prop::collection::vec("[ -~\u{3c4}\u{b2}]{0,20}", 0..3),
        )
            .prop_map(
                |(column, tau2, c, weights, heterogeneity, ols, notes)| Weighted {
                    column,
                    method: "REML".into(),
                    tau2,
                    covariance: c.map(|c| vec![vec![c]]),
                    weights,
                    heterogeneity,
                    ols_std_errors: [("intercept".to_string(), ols)].into(),
                    notes,
                },
            )
    }

    fn model() -> impl Strategy<Value = ModelFile> {
        let factor = (
            "[a-zA-Z_][a-zA-Z0-9_]{0,8}",
            value(),
            value(),
            proptest::option::of("[a-z]{0,3}"),
        )
            .prop_map(|(name, low, high, unit)| Factor {
                name,
                low,
                high,
                unit,
            });
        (
            prop::collection::vec(factor, 1..5),
            prop::collection::vec(response(), 1..4),
        )
            .prop_map(|(factors, responses)| ModelFile { factors, responses })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// Issue 34: whatever model file `doe fit --json` writes
        /// (`serde_json::to_string_pretty`), [`ModelFile::read`] reads back
        /// equal, every float bit for bit.
        #[test]
        fn whatever_model_file_is_written_reads_back_equal(model in model()) {
            let dir = std::env::temp_dir().join(format!("bumpsim-doe-model-{}", std::process::id()));
            std::fs::create_dir_all(&dir).unwrap();
            let path = dir.join("model.json");
            std::fs::write(&path, serde_json::to_string_pretty(&model).unwrap()).unwrap();
            prop_assert_eq!(ModelFile::read(&path).unwrap(), model);
        }
    }
}
