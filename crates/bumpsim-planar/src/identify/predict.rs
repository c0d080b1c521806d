//! A planar case replayed with a car and compared with its measurement:
//! x (the mean of the two sensors) and the yaw: the model's ψ against the
//! yaw-rate sensor's integral (trapezoids from zero at time zero) where
//! the case has one, else
//! `ψ = asin((x_R − x_L)/(η_L − η_R))` of the model and the measured
//! sills, each scored by the fit % of the estimation layer
//! ([`bumpsim_estimate::fit`]: `100 (1 − √(SSE/SST))`) and by the ISO/TS
//! 18571 rating ([`bumpsim_signal::rating`]) over the case's window.
//!
//! With nuisance biases ([`PlanarCase::nuisance`], the study's `bias =
//! "nuisance"`) each accelerometer's remaining bias is read after the
//! contact, where the car rolls free, and their mean removed from the
//! measured x before it is scored (`identify::free_bias`).

use super::check::{check_case, spacing};
use super::{PlanarCase, free_bias};
use crate::car::{PlanarCar, PlanarError};
use crate::drive::drive;
use bumpsim_estimate::band::PredictiveBand;
use bumpsim_estimate::fit::{negative_fit, percent};
use bumpsim_signal::rating::{Rating, rate};
use serde::Serialize;

/// How well the model replays one case.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CaseFit {
    /// The case.
    pub name: String,
    /// Fit of x (mean of the two sensors), %.
    pub fit_x: f64,
    /// Fit of the yaw angle, %.
    pub fit_yaw: f64,
    /// Peak measured yaw, rad.
    pub peak_yaw: f64,
    /// ISO/TS 18571 rating of the model's x against the measured one.
    pub rating_x: Option<Rating>,
    /// ISO/TS 18571 rating of the model's yaw against the measured one.
    pub rating_yaw: Option<Rating>,
    /// Where the replay started, s of the test files' time
    /// ([`PlanarCase::time_zero`]).
    pub time_zero: f64,
    /// Times of the window's first and last sample, s from the replay's
    /// first sample (the plots' time): the span of the fits and ratings.
    pub window: [f64; 2],
    /// The bias removed from the measured x before the comparison, m/s²
    /// (read after the contact, `identify::free_bias`; `None`: the
    /// pre-trigger's mean only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bias_x: Option<f64>,
    /// Whether the yaw compared is the case's yaw-rate sensor integrated
    /// (`true`) or the sills' difference (`false`, not written to JSON).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub yaw_rate_sensor: bool,
}

impl CaseFit {
    /// The warnings of a negative fit of x or yaw (the model follows it
    /// worse than its mean does).
    pub fn warnings(&self) -> Vec<String> {
        [("x displacement", self.fit_x), ("yaw", self.fit_yaw)]
            .into_iter()
            .filter_map(|(signal, fit)| negative_fit(&self.name, signal, fit))
            .collect()
    }
}

/// A case replayed with a car: x and yaw, model and measured, and the fit.
#[derive(Debug, Clone, PartialEq)]
pub struct Prediction {
    /// Time from the first sample, s.
    pub time: Vec<f64>,
    /// Model and measured x (mean of the sensors; the measured less the
    /// bias [`CaseFit::bias_x`] when the case reads one), m.
    pub x: [Vec<f64>; 2],
    /// Model and measured yaw, rad.
    pub yaw: [Vec<f64>; 2],
    /// The fit over the case's window.
    pub fit: CaseFit,
    /// The 90 % predictive band of the model's x, when one was propagated
    /// ([`crate::bands::attach`]).
    pub x_band: Option<PredictiveBand>,
    /// The 90 % predictive band of the model's yaw, likewise.
    pub yaw_band: Option<PredictiveBand>,
}

/// Replays `case` with `car` and compares it with the measurement.
pub fn predict(car: &PlanarCar, case: &PlanarCase) -> Result<Prediction, PlanarError> {
    check_case(case)?;
    let replay = drive(car, &case.drive, 0.05)?;
    let spacing = spacing(case);
    let mean = |s: &[Vec<f64>]| {
        s[0].iter()
            .zip(&s[1])
            .map(|(l, r)| 0.5 * (l + r))
            .collect::<Vec<_>>()
    };
    let yaw = |s: &[Vec<f64>]| {
        s[0].iter()
            .zip(&s[1])
            .map(|(l, r)| ((r - l) / spacing).clamp(-1.0, 1.0).asin())
            .collect::<Vec<_>>()
    };
    let bias_x = free_bias::x_bias(case, &replay.sensor_reading);
    let mut x = [mean(&replay.sensor_reading), mean(&case.measured)];
    free_bias::removed(&mut x[1], bias_x.unwrap_or(0.0), case.drive.step);
    let yaw = match case.yaw_rate() {
        Some(k) => [
            replay.yaw.clone(),
            integral(&case.measured[k], case.drive.step),
        ],
        None => [yaw(&replay.sensor_reading), yaw(&case.measured)],
    };
    let (a, b) = case.window;
    let step = case.drive.step;
    let fit = CaseFit {
        name: case.name.clone(),
        fit_x: percent(&x[0][a..=b], &x[1][a..=b]),
        fit_yaw: percent(&yaw[0][a..=b], &yaw[1][a..=b]),
        peak_yaw: yaw[1][a..=b].iter().fold(0.0, |m: f64, v| m.max(v.abs())),
        rating_x: rate(&x[1][a..=b], &x[0][a..=b], step).ok(),
        rating_yaw: rate(&yaw[1][a..=b], &yaw[0][a..=b], step).ok(),
        time_zero: case.time_zero,
        window: [a, b].map(|k| k as f64 * step),
        bias_x,
        yaw_rate_sensor: case.yaw_rate().is_some(),
    };
    Ok(Prediction {
        time: replay.time,
        x,
        yaw,
        fit,
        x_band: None,
        yaw_band: None,
    })
}

/// The running integral of `rate` sampled every `step`, from 0 (trapezoids).
fn integral(rate: &[f64], step: f64) -> Vec<f64> {
    let mut sum = 0.0;
    let mut out = Vec::with_capacity(rate.len());
    for (k, v) in rate.iter().enumerate() {
        if k > 0 {
            sum += 0.5 * step * (rate[k - 1] + v);
        }
        out.push(sum);
    }
    out
}
