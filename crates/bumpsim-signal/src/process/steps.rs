//! The processing steps of one channel ([`Step`]) and their pipeline
//! ([`run`]): filters, bias, scale, integration and derivation, trimming,
//! shift, resampling, F = m a and the contact window.

use super::error::ProcessError;
use super::time_base::interpolate;
use crate::filter::{Butterworth, Cfc, CfcStandard, FilterError, moving_average};
use crate::integrate::{cumulative_trapezoid, derivative};
use crate::window::ContactThreshold;
use bumpsim_core::channel::{Channel, ChannelCode};
use bumpsim_core::series::{SeriesError, UniformSeries, WINDOW_TOLERANCE};
use bumpsim_core::units::{Dimension, format_quantity, short};
use serde::Deserialize;

/// A Butterworth low-pass step.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ButterworthStep {
    /// Filter order.
    pub order: usize,
    /// Cut-off, Hz.
    pub cutoff: f64,
    /// Forward and backward (default) or forward only.
    #[serde(default = "yes")]
    pub zero_phase: bool,
}

fn yes() -> bool {
    true
}

/// One processing step. TOML spelling in parentheses.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum Step {
    /// CFC filter of this class, SAE J211-1 constant (`cfc = 60`).
    Cfc(f64),
    /// CFC filter with the ISO 6487 constant (`cfc_iso = 60`).
    CfcIso(f64),
    /// Butterworth low-pass (`butterworth = { order = 4, cutoff = 300 }`).
    Butterworth(ButterworthStep),
    /// Centred N-point moving average (`moving_average = 10`).
    MovingAverage(usize),
    /// Subtract the mean over `[t0, t1]` s (`bias = [-0.05, 0.0]`).
    Bias(#[serde(deserialize_with = "bumpsim_io::numbers::exact")] [f64; 2]),
    /// Subtract the mean of every sample before t = 0 (`pretrigger_bias = true`).
    PretriggerBias(bool),
    /// Multiply by a factor, e.g. −1 to change sign (`scale = -1`).
    Scale(f64),
    /// Integrate; the result equals this value (SI) at t = 0, or at the
    /// first sample when the signal starts after t = 0 (`integrate = 15.86`).
    Integrate(f64),
    /// Differentiate (`derivative = true`).
    Derivative(bool),
    /// Keep `[t0, t1]` s (`trim = [0.0, 0.12]`).
    Trim(#[serde(deserialize_with = "bumpsim_io::numbers::exact")] [f64; 2]),
    /// Add this many seconds to the time base (`shift = -0.002`).
    Shift(f64),
    /// Linear resampling to this interval, s (`resample = 1e-4`).
    Resample(f64),
    /// Force of a rigid body of this mass, kg, from its acceleration (`mass = 1719`).
    Mass(f64),
    /// Trim to the channel's own contact window (`contact = { rise = 0.05, fall = 0.02 }`).
    Contact(ContactThreshold),
}

impl Step {
    /// The step's name as written in TOML.
    pub fn name(&self) -> &'static str {
        match self {
            Step::Cfc(_) => "cfc",
            Step::CfcIso(_) => "cfc_iso",
            Step::Butterworth(_) => "butterworth",
            Step::MovingAverage(_) => "moving_average",
            Step::Bias(_) => "bias",
            Step::PretriggerBias(_) => "pretrigger_bias",
            Step::Scale(_) => "scale",
            Step::Integrate(_) => "integrate",
            Step::Derivative(_) => "derivative",
            Step::Trim(_) => "trim",
            Step::Shift(_) => "shift",
            Step::Resample(_) => "resample",
            Step::Mass(_) => "mass",
            Step::Contact(_) => "contact",
        }
    }

    /// Applies the step to a channel.
    pub fn apply(&self, channel: &Channel) -> Result<Channel, ProcessError> {
        let c = Context {
            channel,
            step: self.name(),
        };
        match self {
            Step::Cfc(class) => c.cfc_labelled(*class, CfcStandard::SaeJ211),
            Step::CfcIso(class) => c.cfc_labelled(*class, CfcStandard::Iso6487),
            Step::Butterworth(b) => c.butterworth(b),
            Step::MovingAverage(n) => c.moving_average(*n),
            Step::PretriggerBias(false) | Step::Derivative(false) => Ok(channel.clone()),
            Step::Bias([t0, t1]) => c.bias([*t0, *t1]),
            Step::PretriggerBias(true) => c.bias([channel.series.start(), 0.0]),
            Step::Scale(factor) => Ok(c.map(|v| v * factor)?.scaled(*factor)),
            Step::Integrate(initial) => c.integrate(*initial),
            Step::Derivative(true) => c.derivative(),
            Step::Trim(window) => c.trim(window[0], window[1]),
            Step::Shift(dt) => c.rebase(
                channel.series.start() + dt,
                channel.series.values().to_vec(),
            ),
            Step::Resample(step) => c.resample(*step),
            Step::Mass(mass) => c.mass(*mass),
            Step::Contact(threshold) => c.contact(threshold),
        }
    }
}

/// Applies steps in order.
pub fn run(steps: &[Step], channel: &Channel) -> Result<Channel, ProcessError> {
    steps
        .iter()
        .try_fold(channel.clone(), |c, step| step.apply(&c))
}

/// The channel frequency class a channel's content is limited to: its
/// `Channel frequency class` field, else its ISO code's filter letter.
pub fn frequency_class(channel: &Channel) -> Option<f64> {
    let field = channel
        .meta("Channel frequency class")
        .and_then(|v| v.trim().parse().ok());
    field.or_else(|| ChannelCode::parse(&channel.code).and_then(|c| c.cfc()))
}

/// What the steps cannot do to `channel` as asked: a CFC filter above the
/// class the channel already has leaves its content limited to that class,
/// so it keeps that class's label (code letter and `Channel frequency class`).
pub fn notes(steps: &[Step], channel: &Channel) -> Vec<String> {
    let mut class = frequency_class(channel);
    let mut notes = Vec::new();
    for step in steps {
        let asked = match step {
            Step::Cfc(asked) | Step::CfcIso(asked) => *asked,
            _ => continue,
        };
        match class {
            Some(held) if held < asked => notes.push(format!(
                "channel {}: CFC {asked} after CFC {held} leaves it limited to CFC {held}; it stays labelled CFC {held}",
                channel.code
            )),
            _ => class = Some(asked),
        }
    }
    notes
}

struct Context<'a> {
    channel: &'a Channel,
    step: &'static str,
}

impl Context<'_> {
    fn range(&self, reason: String) -> ProcessError {
        ProcessError::Range {
            channel: self.channel.code.clone(),
            step: self.step,
            reason,
        }
    }

    fn rebase(&self, start: f64, values: Vec<f64>) -> Result<Channel, ProcessError> {
        let step = self.channel.series.step();
        self.series(UniformSeries::new(start, step, values))
    }

    fn series(&self, series: Result<UniformSeries, SeriesError>) -> Result<Channel, ProcessError> {
        let series = series.map_err(|source| ProcessError::Series {
            channel: self.channel.code.clone(),
            step: self.step,
            source,
        })?;
        Ok(self.channel.with_series(series))
    }

    /// The centred average of `points` samples, at most the record's own
    /// length (a window of 1e9 samples was accepted and averaged nothing
    /// but the whole record).
    fn moving_average(&self, points: usize) -> Result<Channel, ProcessError> {
        let samples = self.channel.series.len();
        if points > samples {
            return Err(self.range(format!(
                "{points} points: at most the record's {samples} samples"
            )));
        }
        self.filtered(moving_average(self.channel.series.values(), points))
    }

    fn filtered(&self, values: Result<Vec<f64>, FilterError>) -> Result<Channel, ProcessError> {
        let values = values.map_err(|source| ProcessError::Filter {
            channel: self.channel.code.clone(),
            source,
        })?;
        self.rebase(self.channel.series.start(), values)
    }

    fn map(&self, f: impl Fn(f64) -> f64) -> Result<Channel, ProcessError> {
        let values = self.channel.series.values().iter().map(|&v| f(v)).collect();
        self.rebase(self.channel.series.start(), values)
    }

    /// A CFC filter, labelled with its class unless the channel already has
    /// a lower one (see [`notes`]).
    fn cfc_labelled(&self, class: f64, standard: CfcStandard) -> Result<Channel, ProcessError> {
        let filtered = self.cfc(class, standard)?;
        match frequency_class(self.channel) {
            Some(held) if held < class => Ok(filtered),
            _ => Ok(filtered.filtered(class)),
        }
    }

    fn cfc(&self, class: f64, standard: CfcStandard) -> Result<Channel, ProcessError> {
        let s = &self.channel.series;
        self.filtered(Cfc::new(class, standard).and_then(|f| f.filter(s.values(), s.step())))
    }

    fn butterworth(&self, b: &ButterworthStep) -> Result<Channel, ProcessError> {
        let s = &self.channel.series;
        let values =
            Butterworth::new(b.order, b.cutoff, s.step()).and_then(|f| match b.zero_phase {
                true => f.zero_phase(s.values(), f.default_padding()),
                false => Ok(f.causal(s.values())),
            });
        self.filtered(values)
    }

    /// Subtracts the mean over `[t0, t1]` s (`t1` excluded when it is 0, the
    /// pre-trigger) and records the interval as ISO/TS 13499's `Start offset
    /// interval` and `End offset interval`.
    fn bias(&self, [t0, t1]: [f64; 2]) -> Result<Channel, ProcessError> {
        let s = &self.channel.series;
        let pretrigger = matches!(self.step, "pretrigger_bias");
        // a window reaching past the record took the mean of the test
        // itself as the bias (issue 44's hostile pass: exit 0, a wrong fit)
        let (first, last) = (s.start() - 0.5 * s.step(), s.end() + 0.5 * s.step());
        if !pretrigger && (t0 < first || t1 > last) {
            return Err(self.range(format!(
                "the bias window [{}, {}] s reaches beyond the record, {} s to {} s",
                short(t0),
                short(t1),
                s.start(),
                s.end()
            )));
        }
        let inside = |t: f64| t >= t0 && (t < t1 || (!pretrigger && t <= t1));
        let picked: Vec<f64> = (0..s.len())
            .filter(|&i| inside(s.time(i)))
            .map(|i| s.values()[i])
            .collect();
        if picked.is_empty() {
            return Err(self.range(match pretrigger {
                true => "no samples before t = 0 (no pre-trigger)".into(),
                false => format!(
                    "no samples in the bias window [{}, {}] s",
                    short(t0),
                    short(t1)
                ),
            }));
        }
        let mean = picked.iter().sum::<f64>() / picked.len() as f64;
        let mut out = self.map(|v| v - mean)?;
        out.set_meta("Start offset interval", &format!("{t0:e}"));
        out.set_meta("End offset interval", &format!("{t1:e}"));
        Ok(out)
    }

    fn with_dimension(
        &self,
        found: Result<Dimension, &'static str>,
    ) -> Result<Dimension, ProcessError> {
        found.map_err(|expected| ProcessError::Dimension {
            channel: self.channel.code.clone(),
            step: self.step,
            expected,
            found: self.channel.dimension,
        })
    }

    fn integrate(&self, initial: f64) -> Result<Channel, ProcessError> {
        let dimension = self.with_dimension(match self.channel.dimension {
            Dimension::Acceleration => Ok(Dimension::Velocity),
            Dimension::Velocity => Ok(Dimension::Length),
            Dimension::AngularAcceleration => Ok(Dimension::AngularVelocity),
            Dimension::AngularVelocity => Ok(Dimension::Angle),
            _ => Err("an acceleration or a velocity (linear or angular)"),
        })?;
        let s = &self.channel.series;
        let mut integral = cumulative_trapezoid(s.values(), s.step(), 0.0);
        let at_zero = if s.start() < 0.0 && s.end() >= 0.0 {
            let series = UniformSeries::new(s.start(), s.step(), integral.clone());
            series.map(|i| interpolate(&i, 0.0)).unwrap_or(0.0)
        } else {
            0.0
        };
        integral.iter_mut().for_each(|v| *v += initial - at_zero);
        Ok(self.filtered(Ok(integral))?.with_dimension(dimension))
    }

    fn derivative(&self) -> Result<Channel, ProcessError> {
        let dimension = self.with_dimension(match self.channel.dimension {
            Dimension::Length => Ok(Dimension::Velocity),
            Dimension::Velocity => Ok(Dimension::Acceleration),
            Dimension::Angle => Ok(Dimension::AngularVelocity),
            Dimension::AngularVelocity => Ok(Dimension::AngularAcceleration),
            _ => Err("a displacement or a velocity (linear or angular)"),
        })?;
        let s = &self.channel.series;
        Ok(self
            .filtered(Ok(derivative(s.values(), s.step())))?
            .with_dimension(dimension))
    }

    fn mass(&self, mass: f64) -> Result<Channel, ProcessError> {
        if !(mass.is_finite() && mass > 0.0) {
            return Err(self.range(format!("mass {mass:?} kg must be positive")));
        }
        self.with_dimension(match self.channel.dimension {
            Dimension::Acceleration => Ok(Dimension::Force),
            _ => Err("an acceleration"),
        })?;
        Ok(self.map(|a| mass * a)?.with_dimension(Dimension::Force))
    }

    fn trim(&self, t0: f64, t1: f64) -> Result<Channel, ProcessError> {
        let s = &self.channel.series;
        match s.window(t0, t1).map(|w| w.into_inner()) {
            Some((a, b)) if b > a => self.rebase(s.time(a), s.values()[a..=b].to_vec()),
            // one sample has no interval: nothing downstream can use it
            Some(_) => Err(self.range(format!(
                "[{t0}, {t1}] s keeps one sample; a channel needs at least two (the interval is {} s)",
                s.step()
            ))),
            None => Err(self.range(format!(
                "no samples in [{t0}, {t1}] s; the channel spans [{}, {}] s",
                s.start(),
                s.end()
            ))),
        }
    }

    fn contact(&self, threshold: &ContactThreshold) -> Result<Channel, ProcessError> {
        let s = &self.channel.series;
        let w = threshold
            .detect(s.values())
            .map_err(|source| ProcessError::Window {
                channel: self.channel.code.clone(),
                source,
            })?;
        self.rebase(s.time(w.first), s.values()[w.first..=w.last].to_vec())
    }

    fn resample(&self, step: f64) -> Result<Channel, ProcessError> {
        if !(step.is_finite() && step > 0.0) {
            return Err(self.range(format!("interval {step:?} s must be positive")));
        }
        let s = &self.channel.series;
        let count = ((s.end() - s.start()) / step + WINDOW_TOLERANCE).floor() + 1.0;
        // what the readers take back (a resampled export is read again)
        let max = bumpsim_core::files::MAX_INPUT_SAMPLES;
        if !count.is_finite() || count > max as f64 {
            return Err(self.range(format!(
                "interval {step:?} s gives {count:.3e} samples, at most {max} per channel (limit MAX_INPUT_SAMPLES)"
            )));
        }
        let duration = s.end() - s.start();
        if count < 2.0 {
            return Err(self.range(format!(
                "interval {step:?} s leaves {count} sample of the record's {}: at most {}, two samples (a table needs a sample interval)",
                format_quantity(duration, Dimension::Time),
                format_quantity(duration, Dimension::Time)
            )));
        }
        let count = count as usize;
        let values = (0..count)
            .map(|k| interpolate(s, s.start() + k as f64 * step))
            .collect();
        self.series(UniformSeries::new(s.start(), step, values))
    }
}
