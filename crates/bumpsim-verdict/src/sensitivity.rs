//! Which of the car's uncertain parameters drive each criterion (issue 39,
//! item 3): Sobol' first-order and total indices, with bootstrap
//! intervals, of every judged criterion's value over the car's
//! uncertainty ([`crate::uncertainty`]).
//!
//! - **Output**: each judged criterion's value (SI: a travel or crush in m,
//!   a force in N, a deceleration in m/s², a share in 1). Its limit is the
//!   requirement, not varied, so its margin (`limit − value` or
//!   `value − limit`) and margin ratio are affine in it and have the same
//!   indices.
//! - **Inputs**: the uncertainty's parameters as **independent** log
//!   factors, `θᵢ = θ̂ᵢ exp(xᵢ)` with `xᵢ ~ N(0, σᵢ²)` for a log-normal
//!   parameter and `exp(xᵢ)` uniform on its range for a ranged one
//!   ([`Uncertainty::inputs`]). Sobol' indices
//!   decompose the variance of an output of independent inputs (Sobol'
//!   2001): a correlation of the source (an identification's) is **not
//!   used**, and its largest |r| is stated with the indices.
//! - **Sampling and estimators**: [`bumpsim_estimate::sobol`]: Saltelli's
//!   design on a Sobol' sequence, N base samples give `N (d + 2)` cars, each
//!   run through every selected test by [`crate::verdict::verdict`] (the
//!   nominal verdict's code), in parallel; first order as Saltelli et al.
//!   (2010), total as Jansen (1999), 95 % bootstrap half-widths from
//!   resampling the N rows (seeded). The sequence is not random and each
//!   car's run is deterministic, so any thread count gives the same indices.
//!
//! A criterion whose value is the same in every car (a beam engagement, a
//! test no parameter reaches) has no indices, and says so. A car that
//! cannot be run ends the analysis with its factors named: Saltelli's
//! estimators need every row.
//!
//! ```no_run
//! use bumpsim_verdict::prelude::*;
//! use bumpsim_verdict::sensitivity::{Settings, sensitivity, table};
//! let path = std::path::Path::new("examples/verdict/car.toml");
//! let end = CarEnd::new(bumpsim_planar::PlanarCar::read(path)?, Damageability::read(path)?)?;
//! let setup = Setup::new(vec![end], bumpsim_verdict::protocol::select(&["part581-barrier-front"])?, 0.0)?;
//! let v = verdict(&setup)?;
//! let u = Uncertainty::independent("spreads", vec![("bumper.force".into(), 0.1), ("body.mass".into(), 0.02)])?;
//! let s = sensitivity(&setup, &v, &u, &Settings::new(64, 1), &|| {})?;
//! print!("{}", table(&s));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use crate::criteria::{Outcome, Quantity};
use crate::error::{VerdictError, require};
use crate::uncertainty::Uncertainty;
use crate::uncertainty::{Marginal, described};
use crate::verdict::{Setup, Verdict, verdict};
pub use bumpsim_estimate::sobol::{CLIPPED, Indices, Settings};
use bumpsim_estimate::sobol::{DIMENSIONS, SobolError, indices, outside, share};
use serde::Serialize;
use std::collections::HashMap;
use std::sync::Mutex;

/// Fewest and most base samples N (the verdict runs `N (d + 2)` times).
pub const BASE: [usize; 2] = [16, 8192];

/// The base samples when none is asked for.
pub const DEFAULT_BASE: usize = 64;

/// The indices of one criterion of one test.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CriterionIndices {
    /// The test.
    pub test: &'static str,
    /// The criterion (`rail force`, `clearance: radiator`, ...).
    pub criterion: String,
    /// What its value measures (its display unit).
    pub quantity: Quantity,
    /// The value's indices, its mean and variance (SI) over the cars;
    /// None when it does not vary.
    pub indices: Option<Indices>,
    /// The value, SI, when it is the same in every car (no variance to
    /// apportion, no indices).
    pub constant: Option<f64>,
}

/// The Sobol' indices of every judged criterion.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Sensitivity {
    /// Where the parameters' spreads come from.
    pub source: String,
    /// The parameters, by their car-file names.
    pub names: Vec<String>,
    /// The standard deviation of each one's logarithm, 1.
    pub log_sd: Vec<f64>,
    /// Each one's law.
    pub laws: Vec<Marginal>,
    /// The largest |r| of the source's correlation, not used (0: none).
    pub unused_correlation: f64,
    /// Base samples, resamples and the bootstrap's seed.
    pub settings: Settings,
    /// The design's cars, `N (d + 2)` (0 without a judged criterion); a
    /// car equal to another (a row of `A_B` that is its row of A) runs
    /// once.
    pub evaluations: usize,
    /// Each judged criterion of each assessed test, in the verdict's order.
    pub criteria: Vec<CriterionIndices>,
}

/// The verdicts a sensitivity of `uncertainty` with `base` samples runs.
pub fn evaluations(uncertainty: &Uncertainty, base: usize) -> usize {
    base.saturating_mul(uncertainty.names.len() + 2)
}

/// The Sobol' indices of every judged criterion of the nominal verdict
/// `nominal` over `uncertainty` (see the module); `progress` is called
/// after each of the [`evaluations`] verdicts.
pub fn sensitivity(
    setup: &Setup,
    nominal: &Verdict,
    uncertainty: &Uncertainty,
    settings: &Settings,
    progress: &(dyn Fn() + Sync),
) -> Result<Sensitivity, VerdictError> {
    check(setup, uncertainty, settings)?;
    let judged = judged(nominal);
    let inputs = uncertainty.inputs();
    let runs = Runs {
        setup,
        uncertainty,
        parts: uncertainty.parts(),
        judged: &judged,
        cache: Mutex::new(HashMap::new()),
        failure: Mutex::new(None),
        progress,
    };
    let mut criteria = Vec::with_capacity(judged.len());
    for (k, (test, name, quantity)) in judged.iter().enumerate() {
        let output = |u: &[f64]| runs.value(u, k);
        let (indices, constant) = match indices(&inputs, &output, settings) {
            Ok(i) => (Some(i), None),
            Err(SobolError::Constant { value }) => (None, Some(value)),
            Err(e) => return Err(runs.error(e)),
        };
        criteria.push(CriterionIndices {
            test,
            criterion: name.clone(),
            quantity: *quantity,
            indices,
            constant,
        });
    }
    Ok(Sensitivity {
        source: uncertainty.source.clone(),
        names: uncertainty.names.clone(),
        log_sd: uncertainty.log_sd.clone(),
        laws: uncertainty.laws.clone(),
        unused_correlation: largest_correlation(uncertainty),
        settings: *settings,
        evaluations: match judged.is_empty() {
            true => 0,
            false => evaluations(uncertainty, settings.base),
        },
        criteria,
    })
}

/// Checks the base samples, the number of parameters and that each is
/// the car's, before anything runs ([`sensitivity`] does too).
pub fn check(
    setup: &Setup,
    uncertainty: &Uncertainty,
    settings: &Settings,
) -> Result<(), VerdictError> {
    let base = settings.base;
    let expected = format!(
        "a power of two between {} and {} base samples (the verdict runs N (d + 2) times; a power of two keeps the Sobol sequence balanced)",
        BASE[0], BASE[1]
    );
    let within = (BASE[0]..=BASE[1]).contains(&base);
    require("sobol-base", base as f64, "samples", &expected, within)?;
    if let Some((below, above)) = bumpsim_estimate::sobol::unbalanced(base) {
        let expected = format!(
            "a power of two ({below} or {above}): the Sobol sequence is balanced only over 2^m points"
        );
        require("sobol-base", base as f64, "samples", &expected, false)?;
    }
    let d = uncertainty.names.len();
    if 2 * d > DIMENSIONS {
        return Err(VerdictError::File {
            path: uncertainty.source.clone(),
            message: format!(
                "{d} parameters: Sobol indices take at most {} (the sequence's dimensions)",
                DIMENSIONS / 2
            ),
        });
    }
    for end in [&setup.front, &setup.rear].into_iter().flatten() {
        uncertainty.check(&end.car)?;
    }
    Ok(())
}

/// A judged criterion: its test, name and quantity.
type Judged = (&'static str, String, Quantity);

/// The judged criteria of the assessed tests, in order.
fn judged(v: &Verdict) -> Vec<Judged> {
    let assessed = v.tests.iter().filter(|t| t.skipped.is_none());
    assessed
        .flat_map(|t| {
            let judged = t.criteria.iter().filter(|c| c.outcome != Outcome::Info);
            judged.map(move |c| (t.test.name, c.name.clone(), c.quantity))
        })
        .collect()
}

/// The verdicts of the drawn cars, each run once and kept for every
/// criterion.
struct Runs<'a> {
    setup: &'a Setup,
    uncertainty: &'a Uncertainty,
    /// The uncertainty's parts, found once.
    parts: Vec<crate::uncertainty::Part>,
    judged: &'a [Judged],
    /// The judged values of each point's car, by the point's bits.
    cache: Mutex<HashMap<Vec<u64>, Vec<f64>>>,
    /// The first car that could not be run.
    failure: Mutex<Option<CarFailure>>,
    progress: &'a (dyn Fn() + Sync),
}

impl Runs<'_> {
    /// Criterion `k`'s value at the point `u` (NaN when its car fails).
    fn value(&self, u: &[f64], k: usize) -> f64 {
        let key: Vec<u64> = u.iter().map(|x| x.to_bits()).collect();
        if let Some(values) = self.lock_cache().get(&key) {
            return values[k];
        }
        let values = self.run(u).unwrap_or_else(|why| {
            let mut failure = self.failure.lock().unwrap_or_else(|e| e.into_inner());
            failure.get_or_insert(why);
            vec![f64::NAN; self.judged.len()]
        });
        (self.progress)();
        let value = values[k];
        self.lock_cache().insert(key, values);
        value
    }

    fn lock_cache(&self) -> std::sync::MutexGuard<'_, HashMap<Vec<u64>, Vec<f64>>> {
        self.cache.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// The judged values of the car at `u`, or why it cannot be judged.
    fn run(&self, u: &[f64]) -> Result<Vec<f64>, CarFailure> {
        let factors = factors(u);
        let car = || self.named(&factors);
        let drawn = crate::probability::drawn(self.setup, &self.parts, &factors)
            .ok_or_else(|| CarFailure::Invalid { car: car() })?;
        let v = verdict(&drawn).map_err(|e| CarFailure::Verdict {
            car: car(),
            source: Box::new(e),
        })?;
        let values = judged_values(&v, self.judged);
        match values.iter().all(|x| x.is_finite()) && values.len() == self.judged.len() {
            true => Ok(values),
            false => Err(CarFailure::NotFinite { car: car() }),
        }
    }

    fn named(&self, factors: &[f64]) -> String {
        let names = self.uncertainty.names.iter().zip(factors);
        let named: Vec<String> = names.map(|(n, f)| format!("{n} ×{f:.4}")).collect();
        named.join(", ")
    }

    /// The error of a failed analysis: the first car that failed, else
    /// the estimator's.
    fn error(&self, e: SobolError) -> VerdictError {
        let failure = self.failure.lock().unwrap_or_else(|e| e.into_inner());
        VerdictError::File {
            path: self.uncertainty.source.clone(),
            message: match failure.as_ref() {
                Some(why) => format!("Sobol indices: {why}"),
                None => e.to_string(),
            },
        }
    }
}

/// Why a car of the design cannot be judged; `car` names its factors
/// (`bumper.force ×1.0312, body.mass ×0.9876`).
#[derive(Debug, thiserror::Error)]
enum CarFailure {
    /// The scaled parameters make no valid car.
    #[error("the car with {car}: not a valid car")]
    Invalid { car: String },
    /// The verdict refused the car.
    #[error("the car with {car}: {source}")]
    Verdict {
        car: String,
        source: Box<VerdictError>,
    },
    /// A judged criterion has no finite value or is missing.
    #[error("the car with {car}: a criterion has no finite value")]
    NotFinite { car: String },
}

/// The values of the judged criteria in `v`, in the order of `judged`
/// (shorter when a criterion is missing).
fn judged_values(v: &Verdict, judged: &[Judged]) -> Vec<f64> {
    judged
        .iter()
        .filter_map(|(test, name, _)| {
            let t = v.tests.iter().find(|t| t.test.name == *test)?;
            t.criteria.iter().find(|c| c.name == *name).map(|c| c.value)
        })
        .collect()
}

/// The factors `exp(xᵢ)` of a point of log factors `xᵢ`.
fn factors(x: &[f64]) -> Vec<f64> {
    x.iter().map(|v| v.exp()).collect()
}

/// The largest off-diagonal |r| of the uncertainty's correlation.
fn largest_correlation(uncertainty: &Uncertainty) -> f64 {
    let rows = uncertainty.correlation.iter().enumerate();
    let off = rows.flat_map(|(i, row)| {
        let cells = row.iter().enumerate().filter(move |(j, _)| *j != i);
        cells.map(|(_, r)| r.abs())
    });
    off.fold(0.0, f64::max)
}

/// The rows of the indices table: test, criterion, the value's mean ± sd
/// (its unit), parameter, S1 ± its 95 % half-width, ST ± its half-width;
/// a criterion whose value is the same in every car is one row saying so.
pub fn rows(s: &Sensitivity) -> Vec<[String; 6]> {
    let mut rows = Vec::new();
    for c in &s.criteria {
        let q = c.quantity;
        let Some(i) = &c.indices else {
            let value = c.constant.map_or("-".into(), |v| q.format(v));
            let none = "no variance to apportion".to_string();
            let same = format!("{value} in every car");
            rows.push([
                c.test.into(),
                c.criterion.clone(),
                same,
                none,
                "-".into(),
                "-".into(),
            ]);
            continue;
        };
        let value = format!("{} ± {}", q.format(i.mean), q.format(i.variance.sqrt()));
        for (p, name) in i.names.iter().enumerate() {
            let first = |text: &str| {
                if p == 0 {
                    text.to_string()
                } else {
                    String::new()
                }
            };
            rows.push([
                first(c.test),
                first(&c.criterion),
                first(&value),
                name.clone(),
                share(i.first[p], i.first_conf[p]),
                share(i.total[p], i.total_conf[p]),
            ]);
        }
    }
    rows
}

/// The column headers of [`rows`].
pub const HEADERS: [&str; 6] = [
    "test",
    "criterion",
    "value (mean ± sd)",
    "parameter",
    "S1 (1)",
    "ST (1)",
];

/// What the indices are, over what, with which samples.
pub fn caption(s: &Sensitivity) -> String {
    let correlation = match s.unused_correlation > 0.0 {
        true => format!(
            "; the source's correlation (largest |r| {:.2}) is not used: Sobol indices assume independent inputs",
            s.unused_correlation
        ),
        false => String::new(),
    };
    format!(
        "Sobol indices of each judged criterion's value over {} (independent {}{correlation}): N = {} base samples, {} verdicts, bootstrap of {} resamples with seed {}; S1 first order, ST total, dimensionless shares of the value's variance, ± their 95 % half-widths; a value's indices are its margin's too (the limit is fixed)",
        s.source,
        described(&s.names, &s.laws),
        s.settings.base,
        s.evaluations,
        s.settings.resamples,
        s.settings.seed
    )
}

/// The indices as a text table under their caption.
pub fn table(s: &Sensitivity) -> String {
    let rows = rows(s);
    let widths: Vec<usize> = (0..HEADERS.len() - 1)
        .map(|i| {
            let cells = rows.iter().map(|r| r[i].chars().count());
            cells.chain([HEADERS[i].chars().count()]).max().unwrap_or(0)
        })
        .collect();
    let line = |cells: [&str; 6]| {
        let padded = widths.iter().zip(cells).map(|(w, c)| format!("{c:<w$}  "));
        (padded.collect::<String>() + cells[5])
            .trim_end()
            .to_string()
            + "\n"
    };
    let mut out = caption(s) + "\n" + &line(HEADERS);
    for r in &rows {
        out += &line([&r[0], &r[1], &r[2], &r[3], &r[4], &r[5]].map(|c| c.as_str()));
    }
    if clipped(s) {
        out += &format!("{CLIPPED}\n");
    }
    out
}

/// Whether an index of `s` prints clipped at 0 or 1
/// ([`bumpsim_estimate::sobol::share`]).
pub fn clipped(s: &Sensitivity) -> bool {
    let indices = s.criteria.iter().filter_map(|c| c.indices.as_ref());
    indices
        .flat_map(|i| i.first.iter().chain(&i.total))
        .any(|v| outside(*v))
}
