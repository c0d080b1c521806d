//! Impact predictions as distributions (issue 39, items 3 and 4): a car's
//! uncertain parameters ([`crate::uncertainty`]) propagated through its
//! impact, and the Sobol' indices of each scalar output over them.
//!
//! - **Spreads and bands**: `N` seeded draws of the car
//!   ([`Uncertainty::factors`]), each run in parallel
//!   (`bumpsim_estimate::propagate::through`); each scalar output's median
//!   and equal-tailed interval (`propagate::spread`) and each history's
//!   pointwise band (`propagate::band`) on the nominal run's instants
//!   (at most [`BAND_POINTS`], each draw's history interpolated linearly
//!   onto them and held at its last value past its end: the step of a
//!   draw depends on its stiffness). A draw whose car is not valid or
//!   whose run fails is counted, not used.
//! - **Sobol' indices** (`bumpsim_estimate::sobol`, Saltelli sampling):
//!   the inputs are the parameters' **independent** log factors
//!   `ln θᵢ − ln θ̂ᵢ` of their laws ([`Uncertainty::inputs`]: `N(0, σᵢ²)`
//!   of a log-normal parameter, the logarithm of a factor uniform on its
//!   range of a ranged one); Sobol'
//!   indices assume independent inputs, so a correlation of the source is
//!   not used (and said: [`Sensitivity::correlation_ignored`]). Each
//!   impact runs once for all outputs.

use crate::uncertainty::{Marginal, Model, Uncertainty, UncertaintyError, kinds};
use bumpsim_core::units::{Dimension, format_quantity};
use bumpsim_estimate::propagate::{Band, Run, Spread, band, spread, through};
/// The Sobol' indices' settings (base samples N, resamples, seed).
pub use bumpsim_estimate::sobol::Settings as SobolSettings;
use bumpsim_estimate::sobol::{CLIPPED, Indices, Settings, SobolError, indices, outside, share};
use serde::Serialize;
use std::collections::HashMap;
use std::sync::Mutex;

/// Fewest and most draws of a propagation.
pub const SAMPLES: [usize; 2] = [10, 100_000];
/// Most instants of a band.
pub const BAND_POINTS: usize = 400;

/// A scalar output of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct Scalar {
    /// Its name (`peak force`).
    pub name: &'static str,
    /// Its dimension.
    pub dimension: Dimension,
    /// Its value, SI.
    pub value: f64,
}

/// A history of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct History {
    /// Its name (`force`).
    pub name: &'static str,
    /// Its dimension.
    pub dimension: Dimension,
    /// The instants, s.
    pub time: Vec<f64>,
    /// The values, SI.
    pub values: Vec<f64>,
}

/// What a run gives to a prediction: its scalar outputs and histories.
pub trait Outputs {
    /// The scalar outputs (as the summary prints them).
    fn scalars(&self) -> Vec<Scalar>;
    /// The histories a band is drawn of.
    fn histories(&self) -> Vec<History>;
}

/// How many draws, which seed, which interval.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Sampling {
    /// Draws, within [`SAMPLES`].
    pub samples: usize,
    /// The seed of the draws' streams.
    pub seed: u64,
    /// The intervals' level, in (0, 1) (0.9: 5 % to 95 %).
    pub level: f64,
}

impl Sampling {
    /// Checks the draws and the level.
    pub fn check(&self) -> Result<(), UncertaintyError> {
        let bad = |key: &str, value, unit, expected: &str| UncertaintyError::Value {
            key: key.into(),
            value,
            unit,
            expected: expected.into(),
        };
        let n = self.samples;
        if !(SAMPLES[0]..=SAMPLES[1]).contains(&n) {
            let expected = format!("between {} and {}", SAMPLES[0], SAMPLES[1]);
            return Err(bad("samples", n as f64, "draws", &expected));
        }
        if !(self.level > 0.0 && self.level < 1.0) {
            return Err(bad("level", self.level, "1", "a probability in (0, 1)"));
        }
        Ok(())
    }
}

/// A scalar output's distribution.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OutputSpread {
    /// The output.
    pub name: String,
    /// Its SI unit.
    pub unit: &'static str,
    /// Its dimension (for printing).
    #[serde(skip)]
    pub dimension: Dimension,
    /// The nominal car's value.
    pub nominal: f64,
    /// Over the draws (`None`: no draw ran).
    pub spread: Option<Spread>,
}

/// A history's pointwise band.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HistoryBand {
    /// The history.
    pub name: String,
    /// Its SI unit.
    pub unit: &'static str,
    /// Its dimension (for plotting).
    #[serde(skip)]
    pub dimension: Dimension,
    /// The instants, s.
    pub time: Vec<f64>,
    /// The nominal car's values there.
    pub nominal: Vec<f64>,
    /// The band over the draws.
    pub band: Band,
}

/// An impact predicted over the car's uncertainty.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(bound = "")]
pub struct Prediction<M> {
    /// What was propagated.
    pub uncertainty: Uncertainty<M>,
    /// Draws, seed and level.
    pub sampling: Sampling,
    /// Draws whose car or run failed.
    pub failed: usize,
    /// Each scalar output's spread.
    pub outputs: Vec<OutputSpread>,
    /// Each history's band.
    pub bands: Vec<HistoryBand>,
}

/// One draw's outputs: scalars and histories on the band's instants.
type Drawn = (Vec<f64>, Vec<Vec<f64>>);

/// Predicts the impact `run` of `car` over `uncertainty` (see the module);
/// `nominal` is `run`'s result for `car`.
///
/// ```
/// use bumpsim_impact::impact::{Options, Scenario, simulate};
/// use bumpsim_impact::prediction::{Sampling, predict};
/// use bumpsim_impact::uncertainty::{ChainCar, ChainUncertainty};
/// let car = ChainCar {
///     model: bumpsim_core::model::MsdModel::new(vec![1000.0], vec![], vec![])?,
///     bumper: bumpsim_impact::Bumper::three_part(1e6, 1e9, 1e6)?,
/// };
/// let scenario = Scenario::Barrier { speed: 2.0 };
/// let run = |c: &ChainCar| simulate(&c.model, &c.bumper, scenario, &Options::default()).ok();
/// let u = ChainUncertainty::independent("spreads", vec![("bumper.force".into(), 0.1)])?;
/// let nominal = run(&car).unwrap();
/// let p = predict(&car, &nominal, &u, &Sampling { samples: 50, seed: 1, level: 0.9 }, &run)?;
/// let peak = p.outputs[0].spread.unwrap();
/// assert!(peak.low < nominal.peak_force && nominal.peak_force < peak.high);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn predict<M: Model, R: Outputs>(
    car: &M::Car,
    nominal: &R,
    uncertainty: &Uncertainty<M>,
    sampling: &Sampling,
    run: &(dyn Fn(&M::Car) -> Option<R> + Sync),
) -> Result<Prediction<M>, UncertaintyError> {
    sampling.check()?;
    uncertainty.check(car)?;
    let histories = nominal.histories();
    let at = instants(histories.first().map_or(&[][..], |h| &h.time));
    let drawn = drawn(car, uncertainty, sampling, &at, run)?;
    let level = sampling.level;
    Ok(Prediction {
        uncertainty: uncertainty.clone(),
        sampling: *sampling,
        failed: drawn.failed,
        outputs: spreads(&nominal.scalars(), &drawn.outputs, level),
        bands: bands(&histories, &drawn.outputs, &at, level),
    })
}

/// Each draw's outputs (histories on `at`), in parallel.
fn drawn<M: Model, R: Outputs>(
    car: &M::Car,
    uncertainty: &Uncertainty<M>,
    sampling: &Sampling,
    at: &[f64],
    run: &(dyn Fn(&M::Car) -> Option<R> + Sync),
) -> Result<Run<Drawn>, UncertaintyError> {
    let parts = uncertainty.parts();
    let lower = uncertainty.cholesky()?;
    let factors: Vec<Vec<f64>> = (0..sampling.samples as u64)
        .map(|i| uncertainty.factors(&lower, sampling.seed, i))
        .collect();
    Ok(through(&factors, &|f: &[f64]| {
        let r = run(&M::scaled(car, &parts, f)?)?;
        Some(outcome(&r, at))
    }))
}

/// Each scalar output's spread over the draws.
fn spreads(scalars: &[Scalar], drawn: &[Drawn], level: f64) -> Vec<OutputSpread> {
    let values = |k: usize| drawn.iter().map(|(s, _)| s[k]).collect::<Vec<_>>();
    let output = |(k, s): (usize, &Scalar)| OutputSpread {
        name: s.name.into(),
        unit: s.dimension.si_symbol(),
        dimension: s.dimension,
        nominal: s.value,
        spread: spread(&values(k), level),
    };
    scalars.iter().enumerate().map(output).collect()
}

/// Each history's band over the draws, on `at`.
fn bands(histories: &[History], drawn: &[Drawn], at: &[f64], level: f64) -> Vec<HistoryBand> {
    let history = |(k, h): (usize, &History)| {
        let drawn: Vec<Vec<f64>> = drawn.iter().map(|(_, hs)| hs[k].clone()).collect();
        Some(HistoryBand {
            name: h.name.into(),
            unit: h.dimension.si_symbol(),
            dimension: h.dimension,
            nominal: resample(&h.time, &h.values, at),
            time: at.to_vec(),
            band: band(&drawn, level)?,
        })
    };
    histories.iter().enumerate().filter_map(history).collect()
}

/// A draw's scalars and its histories on `at`.
fn outcome<R: Outputs>(r: &R, at: &[f64]) -> Drawn {
    let scalars = r.scalars().iter().map(|s| s.value).collect();
    let histories = r.histories();
    let on = |h: &History| resample(&h.time, &h.values, at);
    (scalars, histories.iter().map(on).collect())
}

/// At most [`BAND_POINTS`] of `time`, evenly picked.
fn instants(time: &[f64]) -> Vec<f64> {
    let stride = time.len().div_ceil(BAND_POINTS).max(1);
    time.iter().step_by(stride).copied().collect()
}

/// `values` at `time` interpolated linearly at `at`; before the first
/// instant its first value, after the last its last.
pub fn resample(time: &[f64], values: &[f64], at: &[f64]) -> Vec<f64> {
    let value = |t: f64| {
        let k = time.partition_point(|&s| s <= t);
        match (k, values.get(k)) {
            (0, _) => values.first().copied().unwrap_or(f64::NAN),
            (_, None) => values.last().copied().unwrap_or(f64::NAN),
            (k, Some(&b)) => {
                let (t0, t1, a) = (time[k - 1], time[k], values[k - 1]);
                a + (b - a) * (t - t0) / (t1 - t0)
            }
        }
    };
    at.iter().map(|&t| value(t)).collect()
}

/// The Sobol' indices of each scalar output over the car's uncertain
/// parameters (independent marginals; see the module).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Sensitivity {
    /// The inputs: the parameters' names.
    pub inputs: Vec<String>,
    /// The standard deviations of their logarithms.
    pub log_sd: Vec<f64>,
    /// Their laws.
    pub laws: Vec<Marginal>,
    /// Whether the source's correlation was not used (it had one).
    pub correlation_ignored: bool,
    /// Base samples N, resamples and seed.
    pub settings: Settings,
    /// Per scalar output: its name, unit and indices.
    pub outputs: Vec<OutputIndices>,
    /// The outputs that take one value over every Sobol' point (an elastic
    /// bumper's remaining compression): they have no indices.
    pub constant: Vec<ConstantOutput>,
}

/// A scalar output that does not vary over the parameters.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ConstantOutput {
    /// The output.
    pub name: String,
    /// Its SI unit.
    pub unit: &'static str,
    /// Its value, in that unit.
    pub value: f64,
}

/// One scalar output's indices.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OutputIndices {
    /// The output.
    pub name: String,
    /// Its SI unit.
    pub unit: &'static str,
    /// First-order and total indices with their 95 % bootstrap half-widths.
    pub indices: Indices,
}

/// Why indices cannot be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SensitivityError {
    /// The uncertainty does not fit the car.
    #[error(transparent)]
    Uncertainty(#[from] UncertaintyError),
    /// The estimator refused (a failed impact gives a NaN output).
    #[error("{output}: {source}")]
    Sobol {
        /// The output.
        output: String,
        /// Why.
        source: SobolError,
    },
}

/// The Sobol' indices of every scalar output of `run` over the car's
/// uncertain parameters (see the module); `nominal` is `run`'s result for
/// `car`.
pub fn sensitivity<M: Model, R: Outputs>(
    car: &M::Car,
    nominal: &R,
    uncertainty: &Uncertainty<M>,
    settings: &Settings,
    run: &(dyn Fn(&M::Car) -> Option<R> + Sync),
) -> Result<Sensitivity, SensitivityError> {
    uncertainty.check(car)?;
    let inputs = uncertainty.inputs();
    let scalars = nominal.scalars();
    let impacts: Impacts<M, R> = Impacts {
        car,
        parts: uncertainty.parts(),
        run,
        count: scalars.len(),
        cache: Mutex::new(HashMap::new()),
    };
    let (mut outputs, mut constant) = (Vec::new(), Vec::new());
    for (k, s) in scalars.iter().enumerate() {
        let output = |x: &[f64]| impacts.values(x).get(k).copied().unwrap_or(f64::NAN);
        let (name, unit) = (s.name.to_string(), s.dimension.si_symbol());
        match indices(&inputs, &output, settings) {
            Ok(indices) => outputs.push(OutputIndices {
                name,
                unit,
                indices,
            }),
            Err(SobolError::Constant { value }) => {
                constant.push(ConstantOutput { name, unit, value })
            }
            Err(source) => {
                return Err(SensitivityError::Sobol {
                    output: name,
                    source,
                });
            }
        }
    }
    Ok(Sensitivity {
        inputs: uncertainty.names.clone(),
        log_sd: uncertainty.log_sd.clone(),
        laws: uncertainty.laws.clone(),
        correlation_ignored: uncertainty.correlated(),
        settings: *settings,
        outputs,
        constant,
    })
}

/// The impacts of the Sobol' points, each run once for all outputs (the
/// points repeat from one output's indices to the next).
struct Impacts<'a, M: Model, R> {
    car: &'a M::Car,
    parts: Vec<M::Part>,
    run: &'a (dyn Fn(&M::Car) -> Option<R> + Sync),
    count: usize,
    cache: Mutex<HashMap<Vec<u64>, Vec<f64>>>,
}

impl<M: Model, R: Outputs> Impacts<'_, M, R> {
    /// The scalar outputs at the log factors `x` (NaN where the car or its
    /// run fails).
    fn values(&self, x: &[f64]) -> Vec<f64> {
        let key: Vec<u64> = x.iter().map(|v| v.to_bits()).collect();
        if let Some(v) = self.cache.lock().ok().and_then(|c| c.get(&key).cloned()) {
            return v;
        }
        let factors: Vec<f64> = x.iter().map(|v| v.exp()).collect();
        let r = M::scaled(self.car, &self.parts, &factors).and_then(|c| (self.run)(&c));
        let scalars = |r: R| r.scalars().iter().map(|s| s.value).collect();
        let values: Vec<f64> = r.map_or(vec![f64::NAN; self.count], scalars);
        if let Ok(mut c) = self.cache.lock() {
            c.insert(key, values.clone());
        }
        values
    }
}

impl Outputs for crate::impact::ImpactResult {
    fn scalars(&self) -> Vec<Scalar> {
        let scalar = |name, dimension, value| Scalar {
            name,
            dimension,
            value,
        };
        vec![
            scalar("peak force", Dimension::Force, self.peak_force),
            scalar(
                "maximum compression",
                Dimension::Length,
                self.max_compression,
            ),
            scalar(
                "remaining compression",
                Dimension::Length,
                self.remaining_compression,
            ),
            scalar("contact time", Dimension::Time, self.contact_time),
            scalar("absorbed energy", Dimension::Energy, self.absorbed_energy),
        ]
    }

    fn histories(&self) -> Vec<History> {
        let history = |name, dimension, values: &Vec<f64>| History {
            name,
            dimension,
            time: self.time.clone(),
            values: values.clone(),
        };
        vec![
            history("force", Dimension::Force, &self.force),
            history("compression", Dimension::Length, &self.compression),
        ]
    }
}

/// Fewest and most base samples of the Sobol' indices.
pub const SOBOL_BASE: [usize; 2] = [16, 65_536];

/// Checks the Sobol' indices' base samples N and the number of
/// uncertain parameters (at most half the Sobol sequence's dimensions).
pub fn check_base(base: usize, parameters: usize) -> Result<(), UncertaintyError> {
    let most = bumpsim_estimate::sobol::DIMENSIONS / 2;
    let bad = |key: &str, value: usize, unit, expected: String| UncertaintyError::Value {
        key: key.into(),
        value: value as f64,
        unit,
        expected,
    };
    if !(SOBOL_BASE[0]..=SOBOL_BASE[1]).contains(&base) {
        let expected = format!("between {} and {}", SOBOL_BASE[0], SOBOL_BASE[1]);
        return Err(bad("base", base, "samples", expected));
    }
    if let Some((below, above)) = bumpsim_estimate::sobol::unbalanced(base) {
        let expected = format!(
            "a power of two ({below} or {above}): the Sobol sequence is balanced only over 2^m points"
        );
        return Err(bad("base", base, "samples", expected));
    }
    match parameters <= most {
        true => Ok(()),
        false => Err(bad(
            "parameters",
            parameters,
            "parameters",
            format!("Sobol indices of at most {most} parameters"),
        )),
    }
}

/// A level as a percentage: `90 %`, `97.5 %`.
pub fn percent(level: f64) -> String {
    format!("{} %", (1e6 * 100.0 * level).round() / 1e6)
}

/// The lines a prediction prints: what was propagated, then each scalar
/// output's nominal value, median and interval with units.
pub fn lines<M: Model>(p: &Prediction<M>) -> String {
    let u = &p.uncertainty;
    let correlated = if u.correlated() { ", correlated" } else { "" };
    let level = percent(p.sampling.level);
    let mut out = format!(
        "over {} ({} draws, seed {}, {} failed; {}{correlated}): median and {level} interval\n",
        u.source,
        p.sampling.samples,
        p.sampling.seed,
        p.failed,
        u.described()
    );
    for o in &p.outputs {
        let q = |v| format_quantity(v, o.dimension);
        let spread = o.spread.map_or("no draw ran".into(), |s| {
            format!(
                "median {}, {level} {} .. {}",
                q(s.median),
                q(s.low),
                q(s.high)
            )
        });
        out += &format!("  {:<30} {:>12}   {spread}\n", o.name, q(o.nominal));
    }
    u.left_out
        .iter()
        .for_each(|l| out += &format!("  not propagated: {l}\n"));
    out
}

/// The Sobol' indices as a table: per output and parameter the
/// first-order and total index with their 95 % bootstrap half-widths.
pub fn sensitivity_lines(s: &Sensitivity) -> String {
    let evaluations = s.outputs.first().map_or(0, |o| o.indices.evaluations);
    let mut out = format!(
        "Sobol indices over independent {} parameters (N = {}, {evaluations} impacts, {} bootstrap resamples, seed {}): first order S, total S_T, ± 95 %\n",
        kinds(&s.laws),
        s.settings.base,
        s.settings.resamples,
        s.settings.seed
    );
    if s.correlation_ignored {
        out += "  the source's correlation is not used: Sobol indices assume independent inputs\n";
    }
    out += &format!(
        "  {:<30} {:<24} {:>16} {:>16}\n",
        "output", "parameter", "S", "S_T"
    );
    for o in &s.outputs {
        let i = &o.indices;
        for (k, name) in i.names.iter().enumerate() {
            out += &format!(
                "  {:<30} {:<24} {:>16} {:>16}\n",
                o.name,
                name,
                share(i.first[k], i.first_conf[k]),
                share(i.total[k], i.total_conf[k])
            );
        }
    }
    let all = s
        .outputs
        .iter()
        .flat_map(|o| o.indices.first.iter().chain(&o.indices.total));
    if all.copied().any(outside) {
        out += &format!("  {CLIPPED}\n");
    }
    for c in &s.constant {
        let value = bumpsim_core::units::short(c.value);
        out += &format!(
            "  {:<30} the same at every point: {value} {} (no index)\n",
            c.name, c.unit
        );
    }
    out
}

#[cfg(test)]
mod tests;
