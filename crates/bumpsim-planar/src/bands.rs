//! The 90 % predictive bands of a planar identification's predictions
//! (issue 44, item 5): the held-out replays' x and yaw ([`crate::identify::predict`])
//! and the forward predictions' force, x-acceleration and yaw rate
//! ([`crate::forward`]), propagated from the identification's covariance
//! by the estimation layer ([`bumpsim_estimate::band`]: linearised,
//! `ŷ ± z √(s_kᵀ Σ s_k + σ_e²)`).
//!
//! - **Σ** is `Cov(ln θ)` of the car's parameters as the identification
//!   gives it (`SE(θ)/θ` and the correlations of
//!   [`crate::identify::PlanarIdentification::uncertainty`], whatever error
//!   model or priors made it); a parameter without a standard error (at a
//!   bound, not determined) cannot be propagated and is named
//!   ([`Bands::left_out`]); the lines of action belong to the training
//!   cases and do not enter a prediction.
//! - **s_k** by central differences of step [`STEP`] in `ln θ`: the car with
//!   the parameter scaled by `e^{±h}`, made as the identification makes it
//!   ([`crate::identify::Unknowns::car`] of the identified car: a linked
//!   chain's spring with its link, the links' yield force and hardening,
//!   the tyres' C_α and relaxation length; the bumper's contact rate and
//!   damage kept), replayed or simulated again (2 q runs per case). When
//!   the result's names are not its own unknowns', the named parts are
//!   scaled ([`crate::uncertainty::scaled`]).
//! - **σ_e**, what the model does not reproduce: the root-mean-square
//!   residual of the same channel over the training cases' windows (the
//!   replays' x and yaw; the forward channels of the training cases that
//!   give their striker, 0 when none does): measurement noise and model
//!   error as the training data show them. A held-out replay adds the
//!   model error in proportion to its own swing,
//!   `σ_e² = σ_train² + (ε s_ŷ)²`, ε the training replays' residual over
//!   their swing (`√(Σ r²/Σ (y − ȳ)²)`, [`Discrepancy::relative`]) and
//!   s_ŷ the prediction's RMS about its mean over the window: a test that
//!   turns the car ten times as far as the training tests carries ten
//!   times their model error in yaw. Measured on the independent yaw-rate
//!   series (tests/planar/bands.rs): `ε s_ŷ` is 2.4e-4 rad for the 40 %
//!   offset test against its held-out residual's RMS of 1.9e-4 rad, so
//!   the term is the right size; it is constant over the window, while a
//!   replay's error grows with the yaw (the band is wider than needed at
//!   the onset and the parameters' part carries it at the end). Spreading
//!   it over the samples in proportion to the prediction's excursion
//!   (same RMS) changed nothing there (100 % inside either way) and lowered
//!   a missed band (the default study's off-centre face, whose error comes
//!   early, 40 % → 31 %), so it stays constant. σ_train counts the
//!   training wall's model error a second time: on the safe side.
//! - **The measured x's own error**: the bias left on the sills' mean,
//!   `σ_b = x_noise/√T` over the time T it was read
//!   (`identify::free_bias::x_bias_spread`), reads as `σ_b t²/2` in x and
//!   widens the x band in quadrature ([`PredictiveBand::widened`]).
//!
//! Each band is judged over its case's window: the share of measured
//! samples inside it, and its relative width (the parameters' mean
//! half-width over the prediction's range). Above
//! [`bumpsim_estimate::band::TOO_WIDE`] the band is too wide to trust and
//! the statement says so: for a yaw or yaw rate, "the training tests do not
//! determine OFFSET40's yaw: add an offset test". A band the measurement
//! lies inside at fewer than `level − MISSED` of the samples is *missed*,
//! and said: the model misses the test by more than the parameters'
//! uncertainty, a model error the training tests do not show or intervals
//! that are too narrow.

use crate::car::{PlanarCar, PlanarError};
use crate::forward::{Forward, forward};
use crate::identify::{PlanarCase, PlanarIdentification, Prediction, Unknowns, predict};
use crate::uncertainty::{Part, part, scaled};
pub use bumpsim_estimate::band::PredictiveBand;
use bumpsim_estimate::band::{LEVEL, TOO_WIDE, covariance, linearised, sensitivities};
use nalgebra::DMatrix;
use serde::Serialize;

/// A band the measurement lies inside at less than its level minus this
/// share of the samples is missed (samples are correlated: a margin, not a
/// binomial bound).
pub const MISSED: f64 = 0.2;

/// Step of the central differences, in `ln θ`.
pub const STEP: f64 = 0.01;

/// The identification's parameter covariance as the bands propagate it.
#[derive(Debug, Clone, PartialEq)]
pub struct Spread {
    /// The parameters propagated.
    pub names: Vec<String>,
    map: Map,
    covariance: DMatrix<f64>,
    /// Car parameters estimated without a standard error: not propagated.
    pub left_out: Vec<String>,
}

/// How a perturbation of the propagated `ln θ` makes a car.
#[derive(Debug, Clone, PartialEq)]
enum Map {
    /// Through the identification's own unknowns (every car parameter:
    /// links' yield and hardening, the tyres' relaxation length), their
    /// values `theta` at the optimum and the propagated ones' indices.
    Unknowns {
        unknowns: Box<Unknowns>,
        theta: Vec<f64>,
        index: Vec<usize>,
    },
    /// The named parts scaled ([`scaled`]), when the unknowns cannot be
    /// rebuilt from the result.
    Parts(Vec<Part>),
}

/// The unknowns of `result`'s car, rebuilt from its parameter names (the
/// car is its own template); `None` when they do not name the same
/// parameters in the same order.
fn unknowns_of(result: &PlanarIdentification) -> Option<(Unknowns, Vec<f64>)> {
    let has = |n: &str| result.parameters.iter().any(|e| e.name == n);
    let unknowns = Unknowns::new(
        &result.car,
        has("tyres.mu_lateral"),
        has("tyres.cornering_stiffness"),
        &[],
    )
    .with_relaxation(has("tyres.relaxation_length"))
    .with_width(has(crate::identify::EFFECTIVE_WIDTH));
    let names = unknowns.names();
    let same = names.len() <= result.parameters.len()
        && names
            .iter()
            .zip(&result.parameters)
            .all(|((n, _), e)| *n == e.name);
    let theta = unknowns.start();
    (same && theta.len() == names.len()).then_some((unknowns, theta))
}

impl Spread {
    /// The covariance of `result`'s car parameters in `ln θ`.
    pub fn of(result: &PlanarIdentification) -> Spread {
        let u = &result.uncertainty;
        let rebuilt = unknowns_of(result);
        let cars = rebuilt.as_ref().map(|(_, theta)| theta.len());
        let (mut kept, mut left_out) = (Vec::new(), Vec::new());
        for (i, e) in result.parameters.iter().enumerate() {
            let car_parameter = match cars {
                Some(n) => i < n,
                None => part(&e.name).is_some(),
            };
            if !car_parameter {
                continue;
            }
            let fixed = u.fixed.get(i).copied().unwrap_or(false);
            match e
                .standard_error
                .filter(|se| se.is_finite() && e.value > 0.0)
            {
                Some(se) => kept.push((i, se / e.value)),
                None if !fixed => left_out.push(e.name.clone()),
                None => {}
            }
        }
        let correlation: Vec<Vec<Option<f64>>> = kept
            .iter()
            .map(|(a, _)| {
                kept.iter()
                    .map(|(b, _)| {
                        u.correlation
                            .get(*a)
                            .and_then(|r| r.get(*b))
                            .copied()
                            .flatten()
                    })
                    .collect()
            })
            .collect();
        let sd: Vec<f64> = kept.iter().map(|(_, sd)| *sd).collect();
        let map = match rebuilt {
            Some((unknowns, theta)) => Map::Unknowns {
                unknowns: Box::new(unknowns),
                theta,
                index: kept.iter().map(|(i, _)| *i).collect(),
            },
            None => Map::Parts(
                kept.iter()
                    .filter_map(|(i, _)| part(&result.parameters[*i].name))
                    .collect(),
            ),
        };
        Spread {
            names: kept
                .iter()
                .map(|(i, _)| result.parameters[*i].name.clone())
                .collect(),
            map,
            covariance: covariance(&sd, &correlation),
            left_out,
        }
    }

    /// `car` with its propagated parameters scaled by `e^{p_j}` (its
    /// bumper's contact rate and damage kept).
    fn car(&self, car: &PlanarCar, p: &[f64]) -> Option<PlanarCar> {
        let factors: Vec<f64> = p.iter().map(|v| v.exp()).collect();
        let scaled = match &self.map {
            Map::Parts(parts) => scaled(car, parts, &factors)?,
            Map::Unknowns {
                unknowns,
                theta,
                index,
            } => {
                let mut theta = theta.clone();
                for (&i, f) in index.iter().zip(&factors) {
                    theta[i] *= f;
                }
                unknowns.car(&theta).ok()?
            }
        };
        scaled
            .with_contact_rate(car.contact_rate())
            .and_then(|c| c.with_damage(car.damage().to_vec()))
            .ok()
    }

    /// The band around `center` of the histories `model` gives at perturbed
    /// `ln θ` (concatenated channels, split by `lengths`).
    fn bands(
        &self,
        model: &(dyn Fn(&[f64]) -> Option<Vec<f64>> + Sync),
        lengths: &[usize],
        noise: &[f64],
    ) -> Option<Vec<PredictiveBand>> {
        let zero = vec![0.0; self.names.len()];
        let center = model(&zero)?;
        let s = sensitivities(model, &zero, STEP)?;
        let mut start = 0;
        let mut out = Vec::new();
        for (n, sigma) in lengths.iter().zip(noise) {
            let piece: Vec<Vec<f64>> = s.iter().map(|v| v[start..start + n].to_vec()).collect();
            out.push(linearised(
                &center[start..start + n],
                &piece,
                &self.covariance,
                *sigma,
                LEVEL,
            ));
            start += n;
        }
        Some(out)
    }
}

/// What the model does not reproduce, from the training cases: the RMS
/// residual of each channel over their windows (replay x in m, replay yaw
/// in rad; forward force N, x-acceleration m/s², yaw rate rad/s), and the
/// replays' residuals relative to the measured swing.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Discrepancy {
    /// Replay x (mean of the sills), m.
    pub x: f64,
    /// Replay yaw, rad.
    pub yaw: f64,
    /// Forward force, x-acceleration, yaw rate (0 without a training striker).
    pub forward: [f64; 3],
    /// The replays' model error relative to the output's swing, x then
    /// yaw: `√(Σ r² / Σ (y − ȳ)²)` over the training windows (ȳ each
    /// case's mean; `1 − fit/100` pooled), 0 without swing.
    pub relative: [f64; 2],
}

/// `√(Σ (model − measured)² / Σ (measured − its mean)²)` over the pairs'
/// windows (0 without swing).
fn relative<'a>(pairs: impl Iterator<Item = (&'a [f64], &'a [f64], (usize, usize))>) -> f64 {
    let (mut residual, mut swing) = (0.0, 0.0);
    for (model, measured, (a, b)) in pairs {
        let last = b.min(model.len().min(measured.len()).saturating_sub(1));
        if last < a {
            continue;
        }
        let mean = measured[a..=last].iter().sum::<f64>() / (last + 1 - a) as f64;
        for k in a..=last {
            residual += (model[k] - measured[k]).powi(2);
            swing += (measured[k] - mean).powi(2);
        }
    }
    match swing > 0.0 {
        true => (residual / swing).sqrt(),
        false => 0.0,
    }
}

/// The root-mean-square of `values[a..=b]` about their mean.
fn swing(values: &[f64], (a, b): (usize, usize)) -> f64 {
    let last = b.min(values.len().saturating_sub(1));
    if values.is_empty() || last < a {
        return 0.0;
    }
    let piece = &values[a..=last];
    let mean = piece.iter().sum::<f64>() / piece.len() as f64;
    (piece.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / piece.len() as f64).sqrt()
}

/// Root-mean-square of `model − measured` over the pairs' windows.
fn rms<'a>(pairs: impl Iterator<Item = (&'a [f64], &'a [f64], (usize, usize))>) -> f64 {
    let (mut sum, mut n) = (0.0, 0usize);
    for (model, measured, (a, b)) in pairs {
        for k in a..=b.min(model.len().min(measured.len()).saturating_sub(1)) {
            sum += (model[k] - measured[k]).powi(2);
            n += 1;
        }
    }
    if n == 0 { 0.0 } else { (sum / n as f64).sqrt() }
}

impl Discrepancy {
    /// The training residuals of `car` on `training`.
    pub fn of(car: &PlanarCar, training: &[PlanarCase]) -> Result<Discrepancy, PlanarError> {
        let replays: Vec<(Prediction, (usize, usize))> = training
            .iter()
            .map(|c| predict(car, c).map(|p| (p, c.window)))
            .collect::<Result<_, _>>()?;
        let forwards: Vec<Forward> = training
            .iter()
            .filter(|c| c.striker.is_some())
            .map(|c| forward(car, c))
            .collect::<Result<_, _>>()?;
        let channel = |j: usize| {
            rms(forwards.iter().filter_map(|f| {
                f.channels
                    .get(j)
                    .map(|c| (c.simulated.as_slice(), c.measured.as_slice(), f.window))
            }))
        };
        Ok(Discrepancy {
            x: rms(replays
                .iter()
                .map(|(p, w)| (p.x[0].as_slice(), p.x[1].as_slice(), *w))),
            yaw: rms(replays
                .iter()
                .map(|(p, w)| (p.yaw[0].as_slice(), p.yaw[1].as_slice(), *w))),
            forward: [channel(0), channel(1), channel(2)],
            relative: [
                relative(
                    replays
                        .iter()
                        .map(|(p, w)| (p.x[0].as_slice(), p.x[1].as_slice(), *w)),
                ),
                relative(
                    replays
                        .iter()
                        .map(|(p, w)| (p.yaw[0].as_slice(), p.yaw[1].as_slice(), *w)),
                ),
            ],
        })
    }
}

/// The mean of the band's half-width `(high − low)/2` over samples
/// `a..=b` over the range of `center` there (NaN for an empty window).
fn total_width(band: &PredictiveBand, center: &[f64], (a, b): (usize, usize)) -> f64 {
    let end = b.min(center.len().min(band.low.len()).saturating_sub(1));
    if a > end {
        return f64::NAN;
    }
    let window = &center[a..=end];
    let range = window.iter().fold(f64::NEG_INFINITY, |m, v| m.max(*v))
        - window.iter().fold(f64::INFINITY, |m, v| m.min(*v));
    let half: f64 = (a..=end)
        .map(|k| 0.5 * (band.high[k] - band.low[k]))
        .sum::<f64>()
        / window.len() as f64;
    half / range
}

/// One band judged against its measurement.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Judged {
    /// The case.
    pub case: String,
    /// `replay` (measured forces) or `forward` (car, bumper and striker).
    pub prediction: &'static str,
    /// `x`, `yaw`, `force`, `x-acceleration`, `yaw rate`.
    pub channel: &'static str,
    /// The channel's SI unit.
    pub unit: &'static str,
    /// The band's level (0.9).
    pub level: f64,
    /// Measured samples inside the band over the case's window, %.
    pub inside_percent: f64,
    /// The parameters' mean half-width over the prediction's range, %.
    pub relative_width_percent: f64,
    /// The whole band's mean half-width (parameters and the unreproduced
    /// part) over the prediction's range, %: how wide the band is against
    /// the signal's swing.
    pub total_width_percent: f64,
    /// The unreproduced part's standard deviation added, in `unit`.
    pub noise: f64,
    /// Whether the band is narrow enough to trust (relative width within
    /// [`TOO_WIDE`]).
    pub trusted: bool,
}

impl Judged {
    fn of(
        (case, prediction, channel, unit): (&str, &'static str, &'static str, &'static str),
        band: &PredictiveBand,
        (center, measured): (&[f64], &[f64]),
        window: (usize, usize),
    ) -> Judged {
        let width = band.relative_width(center, window);
        Judged {
            case: case.to_string(),
            prediction,
            channel,
            unit,
            level: band.level,
            inside_percent: 100.0 * band.inside(measured, window),
            relative_width_percent: 100.0 * width,
            total_width_percent: 100.0 * total_width(band, center, window),
            noise: band.noise,
            trusted: width <= TOO_WIDE,
        }
    }

    /// Whether the measurement leaves the band at so many samples
    /// (inside less than the level minus [`MISSED`]) that the model misses
    /// this test by more than its parameters' uncertainty.
    pub fn missed(&self) -> bool {
        self.inside_percent < 100.0 * (self.level - MISSED)
    }

    /// The statement of a band too wide to trust, or of one the measurement
    /// leaves ([`Judged::missed`]); `None` for one that is neither.
    pub fn statement(&self) -> Option<String> {
        if self.trusted && self.missed() {
            return Some(format!(
                "{}'s measured {} lies inside its {:.0} % band ({} prediction) at only {:.0} % of the samples: the model misses this test by more than its parameters' uncertainty (a model error the training tests do not show, or intervals too narrow)",
                self.case,
                self.channel,
                100.0 * self.level,
                self.prediction,
                self.inside_percent
            ));
        }
        if self.trusted {
            return None;
        }
        let advice = match self.channel {
            "yaw" | "yaw rate" => "add an offset test",
            _ => "add a test like it to the training",
        };
        Some(format!(
            "the training tests do not determine {}'s {} ({} prediction: its {:.0} % band's half-width from the parameters is {:.0} % of the prediction's range, above {:.0} %): {advice}",
            self.case,
            self.channel,
            self.prediction,
            100.0 * self.level,
            self.relative_width_percent,
            100.0 * TOO_WIDE
        ))
    }
}

/// The bands of an identification's predictions, judged.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Bands {
    /// The level (0.9).
    pub level: f64,
    /// The parameters propagated.
    pub parameters: Vec<String>,
    /// Car parameters without a standard error, not propagated (the bands
    /// are narrower than their uncertainty would make them).
    pub left_out: Vec<String>,
    /// What the model does not reproduce on the training cases.
    pub discrepancy: Discrepancy,
    /// Every band, judged.
    pub judged: Vec<Judged>,
}

impl Bands {
    /// The statements: the left-out parameters and every band too wide to trust.
    pub fn statements(&self) -> Vec<String> {
        let mut out = Vec::new();
        if !self.left_out.is_empty() {
            out.push(format!(
                "the predictive bands leave out {} (no standard error): they are narrower than the car's uncertainty",
                self.left_out.join(", ")
            ));
        }
        out.extend(self.judged.iter().filter_map(Judged::statement));
        out
    }
}

/// Gives each held-out replay (`replays[i]` of `held_out[i]`) its x and yaw
/// bands and each forward prediction (of a case in `training` or
/// `held_out`, by name) its channels' bands, from `result` and the
/// training cases' residuals; returns them judged.
pub fn attach(
    result: &PlanarIdentification,
    training: &[PlanarCase],
    (held_out, replays): (&[PlanarCase], &mut [Prediction]),
    forwards: &mut [Forward],
) -> Result<Bands, PlanarError> {
    let spread = Spread::of(result);
    let discrepancy = Discrepancy::of(&result.car, training)?;
    let car = &result.car;
    let mut judged = Vec::new();
    for (case, replay) in held_out.iter().zip(replays.iter_mut()) {
        let n = replay.time.len();
        let model = |p: &[f64]| {
            let run = predict(&spread.car(car, p)?, case).ok()?;
            Some([run.x[0].clone(), run.yaw[0].clone()].concat())
        };
        // the training residuals' level plus the model error they show in
        // proportion to this prediction's swing
        let noise = [
            discrepancy
                .x
                .hypot(discrepancy.relative[0] * swing(&replay.x[0], case.window)),
            discrepancy
                .yaw
                .hypot(discrepancy.relative[1] * swing(&replay.yaw[0], case.window)),
        ];
        let Some(mut b) = spread.bands(&model, &[n, n], &noise) else {
            continue;
        };
        let (yaw, mut x) = (b.pop(), b.pop());
        // the measured x's own error: the bias its sills' means leave,
        // integrated twice from time zero
        let bias = crate::identify::free_bias::x_bias_spread(case);
        let h = case.drive.step;
        if let Some(band) = x.as_mut() {
            band.widened(|k| bias * 0.5 * (k as f64 * h).powi(2));
        }
        for (channel, unit, band, [center, measured]) in
            [("x", "m", &x, &replay.x), ("yaw", "rad", &yaw, &replay.yaw)]
        {
            if let Some(band) = band {
                let what = (case.name.as_str(), "replay", channel, unit);
                judged.push(Judged::of(what, band, (center, measured), case.window));
            }
        }
        (replay.x_band, replay.yaw_band) = (x, yaw);
    }
    for f in forwards.iter_mut() {
        let Some(case) = training.iter().chain(held_out).find(|c| c.name == f.case) else {
            continue;
        };
        let lengths: Vec<usize> = f.channels.iter().map(|c| c.simulated.len()).collect();
        let model = |p: &[f64]| {
            let run = forward(&spread.car(car, p)?, case).ok()?;
            Some(run.channels.into_iter().flat_map(|c| c.simulated).collect())
        };
        let Some(bands) = spread.bands(&model, &lengths, &discrepancy.forward) else {
            continue;
        };
        for (c, band) in f.channels.iter_mut().zip(bands) {
            let what = (f.case.as_str(), "forward", c.name, c.unit);
            judged.push(Judged::of(
                what,
                &band,
                (&c.simulated, &c.measured),
                f.window,
            ));
            c.band = Some(band);
        }
    }
    Ok(Bands {
        level: LEVEL,
        parameters: spread.names,
        left_out: spread.left_out,
        discrepancy,
        judged,
    })
}

impl Bands {
    /// The summary's lines: each band's share of measured samples inside
    /// and its relative width, then the statements.
    pub fn lines(&self) -> String {
        if self.judged.is_empty() {
            return String::new();
        }
        let mut s = format!(
            "  {:.0} % predictive bands (linearised from the parameters' covariance, plus the training residuals' RMS: x {} mm, yaw {} deg)\n",
            100.0 * self.level,
            bumpsim_core::units::format_number(1e3 * self.discrepancy.x, 3),
            bumpsim_core::units::format_number(self.discrepancy.yaw.to_degrees(), 3),
        );
        for j in &self.judged {
            s += &format!(
                "    {:<16} {:<7} {:<15} {:5.1} % of measured samples inside; half-width {:5.1} % of its range{}\n",
                j.case,
                j.prediction,
                j.channel,
                j.inside_percent,
                j.relative_width_percent,
                if j.trusted {
                    ""
                } else {
                    " (too wide to trust)"
                }
            );
        }
        for w in self.statements() {
            s += &format!("    warning: {w}\n");
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn judged(channel: &'static str, inside: f64, width: f64) -> Judged {
        Judged {
            case: "OFFSET40".into(),
            prediction: "replay",
            channel,
            unit: "rad",
            level: 0.9,
            inside_percent: inside,
            relative_width_percent: width,
            total_width_percent: width,
            noise: 0.0,
            trusted: width <= 100.0 * TOO_WIDE,
        }
    }

    /// A band too wide to trust names the test that would determine it, a
    /// missed band says the model misses the test, a good one says nothing.
    #[test]
    fn each_band_is_judged_in_words() {
        let wide = judged("yaw", 95.0, 40.0).statement().unwrap();
        assert!(
            wide.starts_with("the training tests do not determine OFFSET40's yaw")
                && wide.ends_with("above 25 %): add an offset test"),
            "{wide}"
        );
        let force = judged("force", 95.0, 40.0).statement().unwrap();
        assert!(
            force.ends_with("add a test like it to the training"),
            "{force}"
        );
        let missed = judged("yaw", 17.0, 0.4).statement().unwrap();
        assert!(
            missed.starts_with(
                "OFFSET40's measured yaw lies inside its 90 % band (replay prediction) at only 17 %"
            ),
            "{missed}"
        );
        assert!(judged("yaw", 75.0, 0.4).statement().is_none());
        let bands = Bands {
            level: 0.9,
            parameters: vec!["body.mass".into()],
            left_out: vec!["body.yaw_inertia".into()],
            discrepancy: Discrepancy {
                x: 1e-4,
                yaw: 1e-3,
                forward: [0.0; 3],
                relative: [0.0; 2],
            },
            judged: vec![judged("yaw", 95.0, 40.0)],
        };
        let lines = bands.lines();
        assert!(lines.contains("(too wide to trust)"), "{lines}");
        assert!(
            lines.contains("warning: the predictive bands leave out body.yaw_inertia"),
            "{lines}"
        );
    }
}
