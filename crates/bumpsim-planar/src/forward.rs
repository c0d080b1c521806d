//! The forward prediction of a whole test (issue 32): the car, its bumper
//! and the test's striker simulated with no measured force
//! ([`crate::simulate()`]), against what the lab measured.
//!
//! Compared channels, each over the test's contact window:
//!
//! - **force**: the magnitude of the striker's force on the car (of its
//!   filtered x and y components, below), simulated, against `|Σ_k F_k
//!   d_k|` of the measured load cells (their directions);
//! - **x-acceleration**: the mean of the two sills' body-x accelerations,
//!   `A_x − ψ̇² ξ` (the yaw accelerations cancel), simulated from the CG's
//!   velocity history, measured as the second difference of the sills'
//!   integrated readings;
//! - **yaw rate**: simulated, against the case's yaw-rate sensor where it
//!   has one, else the
//!   first difference of the yaw the sills' readings give,
//!   `ψ = asin((x_R − x_L)/(η_L − η_R))`.
//!
//! Timing: the simulation starts at first touch, the case's record a little
//! before its force onset ([`crate::cases::TimeZero`]); both force
//! histories' onsets (the first sample above [`ONSET`] of the peak) are
//! aligned, and the shift is reported.
//!
//! Conditioning: a case with a `cfc` had its measured channels filtered at
//! that CFC class (SAE J211-1, zero phase) over their pre-trigger when it
//! was read, so each simulated channel is filtered alike (`as_measured`)
//! before onsets are found and channels compared: [`LEAD`] of its state at
//! first touch put before it, into which the filter spreads its onset as it
//! spread the measured one into the pre-trigger. Unfiltered, a fast
//! transient the filter smoothed in the measurement (a pendulum's first
//! foam spike) counts as a model error, and it enters the residuals of a
//! bumper fitted to such a test. A case without `cfc` is compared
//! unfiltered.
//!
//! Each channel is scored by the fit % of the estimation layer
//! ([`bumpsim_estimate::fit`]) and by the ISO/TS 18571 rating
//! ([`bumpsim_signal::rating`]).

use crate::car::{PlanarCar, PlanarError};
use crate::drive::Sensor;
use crate::identify::PlanarCase;
use crate::simulate::{Settings, simulate};
use serde::Serialize;

/// A force history's onset: its first sample above this fraction of its peak.
pub const ONSET: f64 = 0.02;

/// How long a simulated channel is held at its first value before first
/// touch when it is filtered as the measurement was, s (`as_measured`):
/// longer than a CFC 60 filter's spread of an onset (a few ms).
pub const LEAD: f64 = 0.02;

/// The samples of [`LEAD`] at sample interval `step` s.
pub(crate) fn lead(step: f64) -> usize {
    (LEAD / step).ceil() as usize
}

/// A simulated `history` (from first touch, every `step` s) as the case's
/// channels were conditioned: `lead` samples of its first value put before
/// it, then the case's CFC filter, zero phase; unfiltered when the case has
/// none. Index `k + lead` of the result is the history's sample `k`.
pub(crate) fn as_measured(
    case: &PlanarCase,
    history: &[f64],
    step: f64,
    lead: usize,
) -> Result<Vec<f64>, PlanarError> {
    let first = history.first().copied().unwrap_or(0.0);
    let held: Vec<f64> = std::iter::repeat_n(first, lead)
        .chain(history.iter().copied())
        .collect();
    let Some(class) = case.cfc else {
        return Ok(held);
    };
    let filter =
        bumpsim_signal::filter::Cfc::new(class, bumpsim_signal::filter::CfcStandard::SaeJ211);
    filter
        .and_then(|f| f.filter(&held, step))
        .map_err(|e| PlanarError::Case {
            case: case.name.clone(),
            message: format!("the forward run filtered at CFC {class} as the measurement: {e}"),
        })
}

/// One compared channel.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Channel {
    /// `force`, `x-acceleration` or `yaw rate`.
    pub name: &'static str,
    /// Its SI unit.
    pub unit: &'static str,
    /// Fit % of the simulation against the measurement over the window.
    pub fit_percent: f64,
    /// ISO/TS 18571 rating of the simulation against the measurement.
    pub rating: Option<bumpsim_signal::rating::Rating>,
    /// Time of the test's samples, s.
    #[serde(skip)]
    pub time: Vec<f64>,
    /// Simulated, at the test's samples (aligned).
    #[serde(skip)]
    pub simulated: Vec<f64>,
    /// Measured.
    #[serde(skip)]
    pub measured: Vec<f64>,
    /// The simulation's 90 % predictive band, when one was propagated
    /// ([`crate::bands::attach`]; its level and noise in the JSON).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub band: Option<bumpsim_estimate::band::PredictiveBand>,
}

/// The forward prediction of one test.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Forward {
    /// The case.
    pub case: String,
    /// The simulation's time zero in the test's time, s (onsets aligned).
    pub shift: f64,
    /// The compared channels.
    pub channels: Vec<Channel>,
    /// The window compared, first and last sample.
    pub window: (usize, usize),
    /// The simulation's own warnings.
    pub warnings: Vec<String>,
}

impl Forward {
    /// The fit % of its channel `name` (`"force"`, `"x-acceleration"`,
    /// `"yaw rate"`, ...), if it compared one.
    pub fn fit_of(&self, name: &str) -> Option<f64> {
        self.channels
            .iter()
            .find(|c| c.name == name)
            .map(|c| c.fit_percent)
    }
}

/// Simulates `case`'s striker against `car` and compares it with the case's
/// measurement (see the module); an error when the case has no striker,
/// no left and right sills, or a CFC class its sample interval cannot
/// filter at.
pub fn forward(car: &PlanarCar, case: &PlanarCase) -> Result<Forward, PlanarError> {
    run(car, case).map(|(ahead, _)| ahead)
}

/// [`forward()`] and the simulation it compared (its time zero `shift`
/// after the case's).
pub(crate) fn run(
    car: &PlanarCar,
    case: &PlanarCase,
) -> Result<(Forward, crate::PlanarResult), PlanarError> {
    let missing = |expected: &str| PlanarError::Case {
        case: case.name.clone(),
        message: expected.into(),
    };
    let striker = case.striker.ok_or_else(|| {
        missing("no striker: a forward prediction needs the test's `striker = { ... }` (docs/planar.md)")
    })?;
    let ([xi, eta_left], [_, eta_right]) = match case.drive.sensors.as_slice() {
        [Sensor::Body(l), Sensor::Body(r), ..] => (*l, *r),
        _ => {
            return Err(missing(
                "the first two sensors must be the left and right sills",
            ));
        }
    };
    let step = case.drive.step;
    let samples = case.measured[0].len();
    let settings = Settings {
        output_step: step,
        duration: step * samples as f64,
        stop_after_contact: false,
        ..Settings::default()
    };
    let r = simulate(car, &striker, &settings)?;
    let measured = measured(case, eta_left - eta_right);
    let lead = lead(step);
    let simulated = conditioned(case, &r, xi, lead)?;
    let at = |f: &[f64], otherwise: usize| onset(f).unwrap_or(otherwise) as f64;
    let shift = (at(&measured[0], 0) - (at(&simulated[0], lead) - lead as f64)) * step;
    let time: Vec<f64> = (0..samples).map(|k| k as f64 * step).collect();
    let (a, b) = case.window;
    let channels = [
        ("force", "N"),
        ("x-acceleration", "m/s²"),
        ("yaw rate", "rad/s"),
    ]
    .into_iter()
    .zip(measured)
    .zip(simulated)
    .map(|(((name, unit), measured), simulated)| {
        let simulated: Vec<f64> = time
            .iter()
            .map(|&t| sample(&simulated, (t - shift) / step + lead as f64))
            .collect();
        Channel {
            name,
            unit,
            fit_percent: bumpsim_estimate::fit::percent(&simulated[a..=b], &measured[a..=b]),
            rating: bumpsim_signal::rating::rate(&measured[a..=b], &simulated[a..=b], step).ok(),
            time: time.clone(),
            simulated,
            measured,
            band: None,
        }
    })
    .collect();
    let ahead = Forward {
        case: case.name.clone(),
        shift,
        channels,
        window: (a, b),
        // the run lasts as long as the test's record: a contact that
        // outlasts it is the record's length, not a duration to raise
        warnings: (r.warnings.iter())
            .filter(|w| !w.contains("raise the duration"))
            .cloned()
            .collect(),
    };
    Ok((ahead, r))
}

/// A force history's onset: its first sample above [`ONSET`] of its peak
/// (none when it never rises).
fn onset(f: &[f64]) -> Option<usize> {
    let peak = f.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    f.iter().position(|v| v.abs() > ONSET * peak)
}

/// The run's force, x-acceleration and yaw rate conditioned as the case's
/// channels were ([`as_measured`], `lead` samples before first touch); the
/// force the magnitude of its filtered components, as the cells' sum is.
fn conditioned(
    case: &PlanarCase,
    r: &crate::PlanarResult,
    xi: f64,
    lead: usize,
) -> Result<[Vec<f64>; 3], PlanarError> {
    let step = case.drive.step;
    let [along, rate] = simulated(r, xi);
    let fx = as_measured(case, &r.force_x, step, lead)?;
    let fy = as_measured(case, &r.force_y, step, lead)?;
    Ok([
        fx.iter().zip(&fy).map(|(x, y)| x.hypot(*y)).collect(),
        as_measured(case, &along, step, lead)?,
        as_measured(case, &rate, step, lead)?,
    ])
}

/// The measured force magnitude, sills' mean x-acceleration and yaw rate.
fn measured(case: &PlanarCase, spacing: f64) -> [Vec<f64>; 3] {
    let n = case.measured[0].len();
    let step = case.drive.step;
    let force: Vec<f64> = (0..n)
        .map(|k| {
            let (mut fx, mut fy) = (0.0, 0.0);
            for load in &case.drive.loads {
                let norm = load.direction[0].hypot(load.direction[1]);
                fx += load.force[k] * load.direction[0] / norm;
                fy += load.force[k] * load.direction[1] / norm;
            }
            fx.hypot(fy)
        })
        .collect();
    let (left, right) = (&case.measured[0], &case.measured[1]);
    let mean: Vec<f64> = left.iter().zip(right).map(|(l, r)| 0.5 * (l + r)).collect();
    let yaw: Vec<f64> = left
        .iter()
        .zip(right)
        .map(|(l, r)| ((r - l) / spacing).clamp(-1.0, 1.0).asin())
        .collect();
    let rate = match case.yaw_rate() {
        Some(k) => case.measured[k].clone(),
        None => difference(&yaw, step),
    };
    // the sills' mean reading is A_x − ψ̇² ξ integrated twice
    [force, difference(&difference(&mean, step), step), rate]
}

/// The simulated x-acceleration and yaw rate at the result's samples.
fn simulated(r: &crate::PlanarResult, xi: f64) -> [Vec<f64>; 2] {
    let step = r.time.get(1).map_or(1.0, |t| t - r.time[0]);
    let (ax, ay) = (
        difference(&r.velocity_x, step),
        difference(&r.velocity_y, step),
    );
    let along: Vec<f64> = (0..r.time.len())
        .map(|k| {
            let (sn, cs) = r.yaw[k].sin_cos();
            ax[k] * cs + ay[k] * sn - r.yaw_rate[k] * r.yaw_rate[k] * xi
        })
        .collect();
    [along, r.yaw_rate.clone()]
}

/// Central differences (one-sided at the ends).
fn difference(v: &[f64], step: f64) -> Vec<f64> {
    let n = v.len();
    (0..n)
        .map(|k| match (k, n) {
            (_, 0 | 1) => 0.0,
            (0, _) => (v[1] - v[0]) / step,
            (k, n) if k + 1 == n => (v[k] - v[k - 1]) / step,
            (k, _) => (v[k + 1] - v[k - 1]) / (2.0 * step),
        })
        .collect()
}

/// `v` at fractional sample `k` (linear; 0 before the first, the last after).
pub(crate) fn sample(v: &[f64], k: f64) -> f64 {
    if k <= 0.0 || v.is_empty() {
        return if k < 0.0 {
            0.0
        } else {
            v.first().copied().unwrap_or(0.0)
        };
    }
    let i = k.floor() as usize;
    match v.get(i + 1) {
        Some(next) => v[i] + (k - i as f64) * (next - v[i]),
        None => v.last().copied().unwrap_or(0.0),
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::car::Layout;
    use crate::drive::{Drive, Load};
    use crate::striker::{Face, Striker};
    use bumpsim_core::model::MsdModel;
    use bumpsim_impact::bumper::Bumper;

    /// The samples a test's record starts before first touch.
    const BEFORE: usize = 30;

    /// A pendulum test whose load cell read `car`'s force filtered at CFC
    /// `class` over a pre-contact record, as a lab's conditioning does, its
    /// time zero [`BEFORE`] samples before first touch; the case says it
    /// was filtered when `said`.
    fn filtered_test(car: &PlanarCar, class: f64, said: bool) -> PlanarCase {
        let striker = Striker::pendulum(Face::flat(), 1000.0, 3.0);
        let step = 1e-4;
        let settings = Settings {
            output_step: step,
            duration: 0.1,
            stop_after_contact: false,
            ..Settings::default()
        };
        let r = simulate(car, &striker, &settings).unwrap();
        let lead = lead(step);
        let held = [vec![0.0; lead], r.force.clone()].concat();
        let cfc = bumpsim_signal::filter::Cfc::new(class, Default::default()).unwrap();
        let force = cfc.filter(&held, step).unwrap()[lead - BEFORE..].to_vec();
        pendulum_case("pendulum", striker, force, step, said.then_some(class))
    }

    /// A pendulum case: `force` (N, every `step` s) as its one load cell
    /// along −x, two sills with no readings, the whole record its window.
    pub(crate) fn pendulum_case(
        name: &str,
        striker: Striker,
        force: Vec<f64>,
        step: f64,
        cfc: Option<f64>,
    ) -> PlanarCase {
        let n = force.len();
        let drive = Drive {
            step,
            loads: vec![Load {
                lateral: 0.0,
                anchor: None,
                cell: None,
                direction: [-1.0, 0.0],
                force,
            }],
            speed: 0.0,
            arm: 1.0,
            sensors: vec![Sensor::Body([0.6, 0.7]), Sensor::Body([0.6, -0.7])],
        };
        PlanarCase {
            striker: Some(striker),
            cfc,
            ..PlanarCase::replayed(name, drive, vec![vec![0.0; n]; 2])
        }
    }

    #[test]
    fn the_simulated_force_is_filtered_as_the_measured_one_was() {
        // a light front mass on a stiff bumper: a first spike of a few ms
        // that CFC 60 smooths away
        let chain = MsdModel::new(vec![5.0, 1200.0], vec![1e3], vec![1.5e6]).unwrap();
        let bumper = Bumper::three_part(8e6, 60e3, 2e7).unwrap();
        let car = PlanarCar::symmetric(&chain, &bumper, &Layout::default()).unwrap();
        let force = |said| {
            let ahead = forward(&car, &filtered_test(&car, 60.0, said)).unwrap();
            (ahead.fit_of("force").unwrap(), ahead.shift)
        };
        let (filtered, shift) = force(true);
        let (raw, _) = force(false);
        eprintln!("force fit {filtered:.3} % filtered alike, {raw:.3} % raw");
        assert!(filtered > 99.99, "{filtered} %");
        // the simulation's first touch lies BEFORE samples into the record
        let at = BEFORE as f64 * 1e-4;
        assert!((shift - at).abs() < 1.5e-4, "the onsets agree: {shift} s");
        assert!(raw < filtered - 1.0, "raw {raw} %, filtered {filtered} %");
    }
}
