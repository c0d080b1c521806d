//! A car's uncertain parameters (issue 39, items 3 and 4): log-normal and
//! correlated, or uniform over a range, read from an identification's
//! JSON or a TOML table of relative spreads and ranges, drawn with a
//! seed; for the 1-D chain car here
//! ([`Chain`]) and for any car model that names its parameters
//! ([`Model`]; the planar car's is `bumpsim_planar::uncertainty`).
//!
//! The parameters are log-normal around the car file's values:
//! `ln θᵢ = ln θ̂ᵢ + σᵢ zᵢ`, `z ~ N(0, R)`, with `σᵢ` the standard
//! deviation of `ln θᵢ` and `R` their correlation. Two sources:
//!
//! - an identification's JSON (`bumpsim identify --json`): `σᵢ = SEᵢ/θ̂ᵢ`,
//!   its delta-method standard error over its estimate (the estimation
//!   layer's `Cov(ln θ) = σ² (JᵀJ)⁻¹`, AR(1) inflated;
//!   `bumpsim_estimate::uncertainty`), and `R` its correlation of the log
//!   parameters. The spreads are applied to the car file's values (the
//!   identified car's, usually). Parameters without a standard error
//!   (fixed, at a bound, not determined) are left out, and said;
//! - a TOML file of relative standard deviations, independent:
//!   `[uncertainty]` then `"masses[0]" = 0.02`, one key per parameter;
//!   and/or of **ranges**: `[ranges]` then `"springs[0]" = [0.8, 1.2]`,
//!   the parameter uniform on `[0.8 θ̂, 1.2 θ̂]`, independent of all
//!   others (factors within [`RANGE_FACTORS`]; a parameter in both tables
//!   is refused). An identification's JSON has no ranges.
//!
//! Each parameter's law is one [`Marginal`]; [`Marginal::law`] is the law
//! of its log factor `ln(θᵢ/θ̂ᵢ)` (normal, or the logarithm of a uniform
//! factor), which both the Monte Carlo draws and the Sobol' inputs
//! ([`Uncertainty::inputs`]) use. A draw is `z = L u`, `L` the Cholesky
//! factor of `R` and `u` standard normal from the stream of the seed and
//! the draw's index (`bumpsim_estimate::search::Draws`), so any thread
//! count gives the same draws; the factor is `exp(σᵢ zᵢ)` for a
//! log-normal parameter and `low + (high − low) Φ(zᵢ)` for a ranged one
//! (its `zᵢ = uᵢ`: independent).
//!
//! The chain car's names: `masses[i]`, `dampers[i]`, `springs[i]` (from 0,
//! as in the car file; an identification's `m1`, `c1`, `k1` are
//! `masses[0]`, `dampers[0]`, `springs[0]`) and `bumper.force` (the
//! bumper's force scaled at every compression).

use crate::bumper::Bumper;
use bumpsim_core::model::MsdModel;
use bumpsim_estimate::posterior::gaussian;
use bumpsim_estimate::search::Draws;
use bumpsim_estimate::sobol::{Input, Law};
use serde::Serialize;
use std::marker::PhantomData;
use std::path::Path;

/// Why an uncertainty cannot be read or used.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum UncertaintyError {
    /// The file cannot be read, is of the wrong kind or names an unknown
    /// parameter.
    #[error("{path}: {message}")]
    File {
        /// The file.
        path: String,
        /// What is wrong.
        message: String,
    },
    /// A spread or correlation out of range.
    #[error("{key} = {} {unit}: {expected}", bumpsim_core::units::short(*value))]
    Value {
        /// The parameter.
        key: String,
        /// The value given.
        value: f64,
        /// Its unit.
        unit: &'static str,
        /// What is allowed.
        expected: String,
    },
    /// An identification's spreads on a car that is not the one it
    /// identified: a parameter's value differs beyond [`SAME_CAR`].
    #[error("{path}: {}", foreign(key, *car, *identified))]
    Foreign {
        /// The identification's JSON.
        path: String,
        /// The parameter.
        key: String,
        /// Its value in the car file, SI.
        car: f64,
        /// Its value where the spreads were identified, SI.
        identified: f64,
    },
    /// A parameter the car does not have.
    #[error("{path}: {key} is missing: {expected}")]
    Missing {
        /// The uncertainty file.
        path: String,
        /// The parameter.
        key: String,
        /// What the car has.
        expected: String,
    },
}

/// How far (relative) a car file's parameter may lie from the value an
/// identification's spreads belong to and still be that car: 0.1 %, room
/// for a value rounded by hand to four digits; the identified car file
/// (`identify --car`) carries the values exactly.
pub const SAME_CAR: f64 = 1e-3;

/// The message of [`UncertaintyError::Foreign`]: the parameter, both
/// values, and the ways to go on.
pub fn foreign(key: &str, car: f64, identified: f64) -> String {
    let number = |v: f64| bumpsim_core::units::format_number(v, 6);
    format!(
        "these spreads belong to another car: {key} is {} in the car file but {} where they were identified (SI units; {:+.1} %); an identification's spreads (SE/value) hold for the car it identified: run the identified car (identify --car, with its [damageability] merged: docs/verdict.md), or give this car's spreads as a TOML [uncertainty] table of relative standard deviations",
        number(car),
        number(identified),
        100.0 * (car / identified - 1.0)
    )
}

/// The spreads an identification's JSON gives: names, spreads of the
/// logarithms, their correlation and what was left out.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Identified {
    /// Car-file names.
    pub names: Vec<String>,
    /// The identified values the spreads belong to, SI (in the order of
    /// `names`; empty when the source does not say).
    pub values: Vec<f64>,
    /// Standard deviations of the logarithms.
    pub log_sd: Vec<f64>,
    /// Their correlation.
    pub correlation: Vec<Vec<f64>>,
    /// Parameters not propagated, and why.
    pub left_out: Vec<String>,
}

/// A car model whose parameters can be uncertain.
pub trait Model: Clone + std::fmt::Debug + PartialEq + Send + Sync {
    /// The car.
    type Car: Sync;
    /// Where a parameter lives in the car.
    type Part: Copy + Send + Sync + PartialEq + std::fmt::Debug;
    /// Some names, for messages (`masses[0], ..., bumper.force`).
    const NAMES: &'static str;
    /// The part a name denotes (`None`: not a parameter).
    fn part(name: &str) -> Option<Self::Part>;
    /// The names a car's parameters go by.
    fn known(car: &Self::Car) -> String;
    /// `car` with each part multiplied by its factor; `None` when that is
    /// not a valid car.
    fn scaled(car: &Self::Car, parts: &[Self::Part], factors: &[f64]) -> Option<Self::Car>;
    /// The spreads of an identification's JSON document; `source` names
    /// the file in messages.
    fn identified(doc: &serde_json::Value, source: &str) -> Result<Identified, UncertaintyError>;
    /// A parameter's value in a car, SI (`None`: not a single value, as a
    /// scale of the bumper's force; or not compared).
    fn value(_car: &Self::Car, _part: Self::Part) -> Option<f64> {
        None
    }
}

/// Fewest and most factors of a range: a ranged parameter lies within
/// `[1e-3 θ̂, 1e3 θ̂]` of the car file's value `θ̂`.
pub const RANGE_FACTORS: [f64; 2] = [1e-3, 1e3];

/// How a parameter is distributed around the car file's value `θ̂`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "law", rename_all = "snake_case")]
pub enum Marginal {
    /// Log-normal: `ln θ = ln θ̂ + σ z`.
    LogNormal {
        /// `σ`, the standard deviation of `ln θ`.
        log_sd: f64,
    },
    /// Uniform on `[low θ̂, high θ̂]`, independent of the others.
    Uniform {
        /// The lower factor.
        low: f64,
        /// The upper factor.
        high: f64,
    },
}

impl Marginal {
    /// The law of the log factor `ln(θ/θ̂)`: the Sobol' input's and, at a
    /// standard normal draw ([`Law::of_normal`]), the Monte Carlo draw's.
    pub fn law(&self) -> Law {
        match *self {
            Marginal::LogNormal { log_sd } => Law::Normal {
                mean: 0.0,
                sd: log_sd,
            },
            Marginal::Uniform { low, high } => Law::LogOfUniform { low, high },
        }
    }

    /// The standard deviation of `ln(θ/θ̂)` (a uniform factor's by the
    /// midpoint rule on 4096 points).
    pub fn log_sd(&self) -> f64 {
        match *self {
            Marginal::LogNormal { log_sd } => log_sd,
            Marginal::Uniform { low, high } => {
                let n = 4096;
                let at = |k: usize| (low + (high - low) * (k as f64 + 0.5) / n as f64).ln();
                let logs: Vec<f64> = (0..n).map(at).collect();
                let mean = logs.iter().sum::<f64>() / n as f64;
                let square = |l: &f64| (l - mean).powi(2);
                (logs.iter().map(square).sum::<f64>() / n as f64).sqrt()
            }
        }
    }

    /// As printed: `bumper.force 20.0 %` (log-normal), `springs[0] ×0.8 ..
    /// ×1.2` (uniform).
    fn named(&self, name: &str) -> String {
        let short = bumpsim_core::units::short;
        match *self {
            Marginal::LogNormal { log_sd } => format!("{name} {:.1} %", 100.0 * log_sd),
            Marginal::Uniform { low, high } => {
                format!("{name} ×{} .. ×{}", short(low), short(high))
            }
        }
    }
}

/// What the laws are, for headers: `log-normal`, `uniform` or
/// `log-normal and uniform`.
pub fn kinds(laws: &[Marginal]) -> &'static str {
    let uniform = laws
        .iter()
        .filter(|m| matches!(m, Marginal::Uniform { .. }));
    match (uniform.count(), laws.len()) {
        (0, _) => "log-normal",
        (u, n) if u == n => "uniform",
        _ => "log-normal and uniform",
    }
}

/// The parameters' laws as printed: `log-normal spreads bumper.force
/// 20.0 %, masses[0] 10.0 %`; with ranges `uniform ranges springs[0] ×0.8
/// .. ×1.2` or `log-normal spreads and uniform ranges ...`.
pub fn described(names: &[String], laws: &[Marginal]) -> String {
    let what = match kinds(laws) {
        "log-normal" => "log-normal spreads",
        "uniform" => "uniform ranges",
        _ => "log-normal spreads and uniform ranges",
    };
    let named: Vec<String> = names.iter().zip(laws).map(|(n, m)| m.named(n)).collect();
    format!("{what} {}", named.join(", "))
}

/// A car's uncertain parameters: log-normal and correlated, or uniform
/// over a range and independent.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(bound = "")]
pub struct Uncertainty<M> {
    /// Where it comes from (the file).
    pub source: String,
    /// The parameters, by their car-file names.
    pub names: Vec<String>,
    /// Standard deviation of each parameter's logarithm, 1 (of its law).
    pub log_sd: Vec<f64>,
    /// Their correlation (identity when independent).
    pub correlation: Vec<Vec<f64>>,
    /// Parameters of the source not propagated, and why.
    pub left_out: Vec<String>,
    /// Each parameter's law.
    pub laws: Vec<Marginal>,
    /// The identified values the spreads belong to, SI (an
    /// identification's JSON; empty for relative spreads, which apply to
    /// any car).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub estimates: Vec<f64>,
    #[serde(skip)]
    model: PhantomData<M>,
}

/// The identity matrix of order `n`.
fn identity(n: usize) -> Vec<Vec<f64>> {
    let one = |i: usize, j: usize| f64::from(u8::from(i == j));
    (0..n)
        .map(|i| (0..n).map(|j| one(i, j)).collect())
        .collect()
}

impl<M: Model> Uncertainty<M> {
    /// Independent log-normal parameters: (car-file name, standard
    /// deviation of its logarithm, in (0, 3]).
    ///
    /// ```
    /// use bumpsim_impact::uncertainty::ChainUncertainty;
    /// let u = ChainUncertainty::independent("spreads", vec![("masses[0]".into(), 0.02)]).unwrap();
    /// assert_eq!(u.correlation, vec![vec![1.0]]);
    /// assert!(ChainUncertainty::independent("spreads", vec![("masses[0]".into(), f64::NAN)]).is_err());
    /// ```
    pub fn independent(
        source: &str,
        spreads: Vec<(String, f64)>,
    ) -> Result<Uncertainty<M>, UncertaintyError> {
        Uncertainty::ranged(source, spreads, vec![])
    }

    /// Independent log-normal parameters (as [`Uncertainty::independent`])
    /// and uniform ones: (car-file name, [low, high] factors of its value,
    /// within [`RANGE_FACTORS`], low < high); a name in both is refused.
    ///
    /// ```
    /// use bumpsim_impact::uncertainty::{ChainUncertainty, Marginal};
    /// let u = ChainUncertainty::ranged("u.toml", vec![], vec![("springs[0]".into(), [0.8, 1.2])]).unwrap();
    /// assert_eq!(u.laws, [Marginal::Uniform { low: 0.8, high: 1.2 }]);
    /// assert!(ChainUncertainty::ranged("u.toml", vec![], vec![("springs[0]".into(), [1.2, 0.8])]).is_err());
    /// ```
    pub fn ranged(
        source: &str,
        spreads: Vec<(String, f64)>,
        ranges: Vec<(String, [f64; 2])>,
    ) -> Result<Uncertainty<M>, UncertaintyError> {
        let mut laws: Vec<Marginal> = spreads
            .iter()
            .map(|&(_, log_sd)| Marginal::LogNormal { log_sd })
            .collect();
        let (mut names, _): (Vec<String>, Vec<f64>) = spreads.into_iter().unzip();
        for (name, [low, high]) in ranges {
            range(source, &name, [low, high])?;
            if names.contains(&name) {
                let message = format!(
                    "'{name}' is in both [uncertainty] and [ranges]: give each parameter one law, a relative standard deviation or a range"
                );
                return Err(unreadable(source, message));
            }
            names.push(name);
            laws.push(Marginal::Uniform { low, high });
        }
        let found = Identified {
            values: vec![],
            log_sd: laws.iter().map(Marginal::log_sd).collect(),
            correlation: identity(names.len()),
            names,
            left_out: vec![],
        };
        Uncertainty::new(source, found, laws)
    }

    fn new(
        source: &str,
        found: Identified,
        laws: Vec<Marginal>,
    ) -> Result<Uncertainty<M>, UncertaintyError> {
        let file = |message| UncertaintyError::File {
            path: source.into(),
            message,
        };
        for (name, law) in found.names.iter().zip(&laws) {
            if let Marginal::LogNormal { log_sd } = law {
                spread(&format!("{source}: {name}"), *log_sd)?;
            }
            if M::part(name).is_none() {
                let names = M::NAMES;
                return Err(file(format!(
                    "'{name}' is not a parameter of the car: {names}"
                )));
            }
        }
        if found.names.is_empty() {
            let message = "no parameter to propagate: give at least one with its spread";
            return Err(file(message.into()));
        }
        let u = Uncertainty {
            source: source.into(),
            names: found.names,
            log_sd: found.log_sd,
            correlation: found.correlation,
            left_out: found.left_out,
            laws,
            estimates: found.values,
            model: PhantomData,
        };
        u.cholesky()?;
        Ok(u)
    }

    /// Reads an uncertainty file: an identification's JSON (`{` first) or
    /// a TOML `[uncertainty]` table of relative standard deviations and/or
    /// a `[ranges]` table of uniform ranges.
    pub fn read(path: &Path) -> Result<Uncertainty<M>, UncertaintyError> {
        let source = path.display().to_string();
        let text = bumpsim_core::files::read_text(path).map_err(|e| {
            let message = e.to_string();
            let message = message
                .strip_prefix(&format!("{source}: "))
                .unwrap_or(&message);
            UncertaintyError::File {
                path: source.clone(),
                message: message.into(),
            }
        })?;
        Uncertainty::parse(&text, path)
    }

    /// [`Uncertainty::read`] of a file's text; `path` names it in messages.
    ///
    /// ```
    /// use bumpsim_impact::uncertainty::ChainUncertainty;
    /// let u = ChainUncertainty::parse("[uncertainty]\n\"springs[0]\" = 0.15\n", "u.toml".as_ref()).unwrap();
    /// assert_eq!((u.names[0].as_str(), u.log_sd[0]), ("springs[0]", 0.15));
    /// let e = ChainUncertainty::parse("[uncertainty]\n\"wheel.size\" = 0.1\n", "u.toml".as_ref()).unwrap_err();
    /// assert!(e.to_string().contains("wheel.size"));
    /// ```
    pub fn parse(text: &str, path: &Path) -> Result<Uncertainty<M>, UncertaintyError> {
        let source = path.display().to_string();
        let error = |message: String| unreadable(&source, message);
        if text.trim_start().starts_with('{') {
            let doc: serde_json::Value =
                serde_json::from_str(text).map_err(|e| error(format!("not valid JSON: {e}")))?;
            let found = M::identified(&doc, &source)?;
            let laws = found
                .log_sd
                .iter()
                .map(|&log_sd| Marginal::LogNormal { log_sd });
            let laws = laws.collect();
            return Uncertainty::new(&source, found, laws);
        }
        let table: toml::Table =
            toml::from_str(text).map_err(|e| error(format!("not valid TOML: {}", e.message())))?;
        let (spreads, ranges) = tables::<M>(&table, &source)?;
        Uncertainty::ranged(&source, spreads, ranges)
    }

    /// Each parameter as a Sobol' input: its log factor `ln(θᵢ/θ̂ᵢ)` of
    /// its law ([`Marginal::law`]), independent.
    pub fn inputs(&self) -> Vec<Input> {
        let input = |(name, m): (&String, &Marginal)| Input {
            name: name.clone(),
            law: m.law(),
        };
        self.names.iter().zip(&self.laws).map(input).collect()
    }

    /// [`described`] of these parameters.
    pub fn described(&self) -> String {
        described(&self.names, &self.laws)
    }

    /// The lower Cholesky factor of the correlation.
    pub fn cholesky(&self) -> Result<Vec<Vec<f64>>, UncertaintyError> {
        let r = &self.correlation;
        let n = self.names.len();
        let mut l = vec![vec![0.0; n]; n];
        for i in 0..n {
            for j in 0..=i {
                let s = r[i][j] - (0..j).map(|k| l[i][k] * l[j][k]).sum::<f64>();
                l[i][j] = match i == j {
                    true if s > 1e-12 => s.sqrt(),
                    true => return Err(self.indefinite(i, s)),
                    false => s / l[j][j],
                };
            }
        }
        Ok(l)
    }

    fn indefinite(&self, i: usize, s: f64) -> UncertaintyError {
        UncertaintyError::Value {
            key: format!("{}: correlation of {}", self.source, self.names[i]),
            value: s,
            unit: "1",
            expected: "a positive definite correlation of the parameters' logarithms".into(),
        }
    }

    /// The factors of draw `index` (`lower`: [`Uncertainty::cholesky`]):
    /// `exp(σ z)` of a log-normal parameter, `low + (high − low) Φ(z)` of a
    /// ranged one (the exponential of its law at `z`, [`Marginal::law`]).
    pub fn factors(&self, lower: &[Vec<f64>], seed: u64, index: u64) -> Vec<f64> {
        let mut draws = Draws::new(seed, index);
        let u: Vec<f64> = (0..self.names.len())
            .map(|_| gaussian(&mut draws))
            .collect();
        let z = |row: &Vec<f64>| row.iter().zip(&u).map(|(l, u)| l * u).sum::<f64>();
        lower
            .iter()
            .zip(&self.laws)
            .map(|(row, m)| m.law().of_normal(z(row)).exp())
            .collect()
    }

    /// Whether any two parameters are correlated.
    pub fn correlated(&self) -> bool {
        let r = self.correlation.iter().enumerate();
        r.flat_map(|(i, row)| row.iter().enumerate().filter(move |(j, _)| *j != i))
            .any(|(_, &c)| c != 0.0)
    }

    /// The parts the names denote, in order.
    pub fn parts(&self) -> Vec<M::Part> {
        self.names.iter().filter_map(|n| M::part(n)).collect()
    }

    /// Checks that every parameter exists in `car` and, for an
    /// identification's spreads, that `car` is the car they were
    /// identified on: each value within [`SAME_CAR`] of the identified one
    /// (the spreads are relative to it: another car's would be applied
    /// without a word otherwise).
    pub fn check(&self, car: &M::Car) -> Result<(), UncertaintyError> {
        for (name, p) in self.names.iter().zip(self.parts()) {
            if M::scaled(car, &[p], &[1.0]).is_none() {
                return Err(UncertaintyError::Missing {
                    path: self.source.clone(),
                    key: name.clone(),
                    expected: format!("a parameter of the car: {}", M::known(car)),
                });
            }
        }
        let values = self.names.iter().zip(self.parts()).zip(&self.estimates);
        for ((name, p), &identified) in values {
            let Some(value) = M::value(car, p) else {
                continue;
            };
            if (value / identified - 1.0).abs() > SAME_CAR {
                return Err(UncertaintyError::Foreign {
                    path: self.source.clone(),
                    key: name.clone(),
                    car: value,
                    identified,
                });
            }
        }
        Ok(())
    }
}

/// `Ok` when a spread of a logarithm is within (0, 3].
fn spread(name: &str, s: f64) -> Result<(), UncertaintyError> {
    match s.is_finite() && s > 0.0 && s <= 3.0 {
        true => Ok(()),
        false => Err(UncertaintyError::Value {
            key: name.into(),
            value: s,
            unit: "1",
            expected: "the standard deviation of the parameter's logarithm (about its relative standard deviation), in (0, 3]: a larger spread is not determined well enough to propagate".into(),
        }),
    }
}

/// `Ok` when a range's factors are finite, within [`RANGE_FACTORS`] and
/// `low < high`.
fn range(source: &str, name: &str, [low, high]: [f64; 2]) -> Result<(), UncertaintyError> {
    let [least, most] = RANGE_FACTORS;
    match least <= low && low < high && high <= most {
        true => Ok(()),
        false => {
            let short = bumpsim_core::units::short;
            let message = format!(
                "ranges.\"{name}\" = [{}, {}]: expected two factors of the car file's value, {} <= low < high <= {} (the parameter is uniform on [low, high] times its value)",
                short(low),
                short(high),
                short(least),
                short(most)
            );
            Err(unreadable(source, message))
        }
    }
}

/// A number of a TOML value (an integer as a float).
fn number(v: &toml::Value) -> Option<f64> {
    v.as_float().or_else(|| v.as_integer().map(|i| i as f64))
}

/// The relative spreads of a TOML `[uncertainty]` table and the ranges of
/// a `[ranges]` table (at least one of them).
type Tables = (Vec<(String, f64)>, Vec<(String, [f64; 2])>);

/// The `[uncertainty]` and `[ranges]` tables of an uncertainty file.
fn tables<M: Model>(table: &toml::Table, source: &str) -> Result<Tables, UncertaintyError> {
    let example = M::NAMES.split(',').next().unwrap_or("");
    let expected = || {
        unreadable(
            source,
            format!(
                "expected an [uncertainty] table (\"{example}\" = 0.02, one relative standard deviation per parameter) and/or a [ranges] table (\"{example}\" = [0.8, 1.2], factors of the car file's value; docs/uncertainty.md)"
            ),
        )
    };
    let sub = |key: &str| match table.get(key) {
        None => Ok(None),
        Some(v) => v.as_table().map(Some).ok_or_else(expected),
    };
    let (spreads, ranges) = (sub("uncertainty")?, sub("ranges")?);
    if spreads.is_none() && ranges.is_none() {
        return Err(expected());
    }
    let spread = |(k, v): (&String, &toml::Value)| {
        let s = number(v).ok_or_else(|| unreadable(source, format!("uncertainty.\"{k}\" = {v}: expected a number, the parameter's relative standard deviation")))?;
        Ok((k.clone(), s))
    };
    let range = |(k, v): (&String, &toml::Value)| {
        let pair = v.as_array().filter(|a| a.len() == 2);
        let pair = pair.and_then(|a| Some([number(&a[0])?, number(&a[1])?]));
        let pair = pair.ok_or_else(|| unreadable(source, format!("ranges.\"{k}\" = {v}: expected [low, high], two numbers: factors of the car file's value")))?;
        Ok((k.clone(), pair))
    };
    let spreads = spreads.into_iter().flatten().map(spread);
    let ranges = ranges.into_iter().flatten().map(range);
    Ok((
        spreads.collect::<Result<_, _>>()?,
        ranges.collect::<Result<_, _>>()?,
    ))
}

/// A file error of `source`.
pub fn unreadable(source: &str, message: impl Into<String>) -> UncertaintyError {
    UncertaintyError::File {
        path: source.into(),
        message: message.into(),
    }
}

/// The correlation of the parameters kept (their indices) from a
/// matrix of `null`able cells at `pointer` (a JSON pointer, for messages)
/// of the file `source`.
pub fn kept_correlation(
    matrix: &[serde_json::Value],
    kept: &[usize],
    pointer: &str,
    source: &str,
) -> Result<Vec<Vec<f64>>, UncertaintyError> {
    let cell = |i: usize, j: usize| {
        let value = matrix.get(i).and_then(|r| r.as_array()?.get(j)?.as_f64());
        value.ok_or_else(|| unreadable(source, format!("{pointer}[{i}][{j}] is not a number")))
    };
    let row = |i: usize| kept.iter().map(|&j| cell(i, j)).collect();
    kept.iter().map(|&i| row(i)).collect()
}

/// The 1-D chain car and its bumper (`bumpsim_io::car::Car`'s model and a
/// [`Bumper`]).
#[derive(Debug, Clone, PartialEq)]
pub struct ChainCar {
    /// The chain.
    pub model: MsdModel,
    /// The bumper.
    pub bumper: Bumper,
}

/// The chain car's parameters ([`Model`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Chain;

/// A parameter of the chain car.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ChainPart {
    /// `masses[i]`.
    Mass(usize),
    /// `dampers[i]`.
    Damper(usize),
    /// `springs[i]`.
    Spring(usize),
    /// `bumper.force`.
    BumperForce,
}

/// The chain car's uncertainty.
pub type ChainUncertainty = Uncertainty<Chain>;

const KINDS: [&str; 3] = ["masses", "dampers", "springs"];

impl Model for Chain {
    type Car = ChainCar;
    type Part = ChainPart;
    const NAMES: &'static str = "masses[0], ..., dampers[0], ..., springs[0], ..., bumper.force";

    fn part(name: &str) -> Option<ChainPart> {
        if name == "bumper.force" {
            return Some(ChainPart::BumperForce);
        }
        let (what, index) = name.strip_suffix(']')?.split_once('[')?;
        let index: usize = index.parse().ok()?;
        let kinds = [ChainPart::Mass, ChainPart::Damper, ChainPart::Spring];
        Some(kinds[KINDS.iter().position(|k| *k == what)?](index))
    }

    fn known(car: &ChainCar) -> String {
        let m = car.model.dof();
        let mut names: Vec<String> = (0..m).map(|i| format!("masses[{i}]")).collect();
        for what in ["dampers", "springs"] {
            names.extend((0..m - 1).map(|i| format!("{what}[{i}]")));
        }
        names.push("bumper.force".into());
        names.join(", ")
    }

    fn scaled(car: &ChainCar, parts: &[ChainPart], factors: &[f64]) -> Option<ChainCar> {
        let m = &car.model;
        let mut values = [m.masses(), m.dampers(), m.springs()].map(<[f64]>::to_vec);
        let mut bumper = 1.0;
        for (part, &f) in parts.iter().zip(factors) {
            let (kind, i) = match *part {
                ChainPart::Mass(i) => (0, i),
                ChainPart::Damper(i) => (1, i),
                ChainPart::Spring(i) => (2, i),
                ChainPart::BumperForce => {
                    bumper *= f;
                    continue;
                }
            };
            *values[kind].get_mut(i)? *= f;
        }
        let [masses, dampers, springs] = values;
        Some(ChainCar {
            model: MsdModel::new(masses, dampers, springs).ok()?,
            bumper: car.bumper.scaled(bumper).ok()?,
        })
    }

    fn identified(doc: &serde_json::Value, source: &str) -> Result<Identified, UncertaintyError> {
        chain_identified(doc, source)
    }
}

/// The chain identification's result in a document: itself, or the
/// recommended one of a DOF table.
fn chosen(doc: &serde_json::Value) -> Option<&serde_json::Value> {
    let Some(results) = doc.get("results").and_then(|r| r.as_array()) else {
        return Some(doc);
    };
    let dof = doc.get("recommended_dof")?.as_u64()?;
    results
        .iter()
        .find(|r| r.get("dof").and_then(|d| d.as_u64()) == Some(dof))
}

/// The spreads of a 1-D chain identification's JSON (`bumpsim identify
/// --json` on a chain study; of a DOF table, its recommended model).
fn chain_identified(doc: &serde_json::Value, source: &str) -> Result<Identified, UncertaintyError> {
    let wrong = || {
        unreadable(
            source,
            "expected a 1-D chain identification's JSON (bumpsim identify --json on a chain study) with uncertainty.names, standard_errors and correlation",
        )
    };
    let result = chosen(doc).ok_or_else(wrong)?;
    let u = result.get("uncertainty").ok_or_else(wrong)?;
    let names = u
        .get("names")
        .and_then(|n| n.as_array())
        .ok_or_else(wrong)?;
    let values: Vec<f64> = KINDS
        .iter()
        .filter_map(|k| result.get(*k)?.as_array())
        .flatten()
        .map(|v| v.as_f64().unwrap_or(f64::NAN))
        .collect();
    let se = u.get("standard_errors").and_then(|s| s.as_array());
    let mut found = Identified::default();
    let mut kept = Vec::new();
    for (i, name) in names.iter().enumerate() {
        let name = name.as_str().unwrap_or("?");
        let se = se.and_then(|s| s.get(i)?.as_f64());
        match (car_name(name), values.get(i), se) {
            (None, ..) => found.left_out.push(format!("{name}: not a car parameter")),
            (Some(n), Some(&v), Some(se)) if v > 0.0 && se > 0.0 => {
                kept.push(i);
                found.names.push(n);
                found.log_sd.push(se / v);
            }
            _ => found.left_out.push(format!(
                "{name}: no standard error (fixed, at a bound or not determined)"
            )),
        }
    }
    let matrix = u.get("correlation").and_then(|c| c.as_array());
    let matrix = matrix.ok_or_else(wrong)?;
    found.correlation = kept_correlation(matrix, &kept, "uncertainty.correlation", source)?;
    Ok(found)
}

/// The car-file name of an identification's `m1`, `c2`, `k1`.
fn car_name(name: &str) -> Option<String> {
    let kind = ["m", "c", "k"].iter().position(|k| name.starts_with(k))?;
    let index: usize = name.get(1..)?.parse().ok()?;
    Some(format!("{}[{}]", KINDS[kind], index.checked_sub(1)?))
}
