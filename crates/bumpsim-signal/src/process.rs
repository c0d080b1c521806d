//! Processing steps on channels, composable into a pipeline (spec §4).
//!
//! Each [`Step`] maps a [`Channel`] to a new channel with the same identity:
//! filters ([`filter`](crate::filter)), bias removal (subtract the mean over a
//! pre-trigger interval, by default every sample before t = 0), scaling and
//! sign, trapezoidal integration and differentiation
//! ([`integrate`](crate::integrate), which also change the dimension:
//! acceleration ↔ velocity ↔ displacement, and the angular ones), trimming, time shift, linear
//! resampling, and force from a rigid mass times its acceleration
//! (`F = m a`, spec §4). [`combine`] forms the mean or sum of channels (left
//! and right side members; the cells of a load-cell wall) on their common
//! time base.
//!
//! Steps keep an ISO/TS 13499 code true to the data (see
//! [`Channel::filtered`]): CFC sets the filter-class letter and `Channel
//! frequency class`, integration and derivation the dimension letters
//! (`AC` → `VE` → `DS`), F = m a `FO`, and a negative scale notes the sign
//! change in `Comments`.
//!
//! In TOML a pipeline is a list of one-key tables, e.g.
//! `steps = [{ cfc = 60 }, { bias = [-0.05, 0.0] }, { integrate = 15.86 }]`.
//!
//! ```
//! use bumpsim_core::prelude::*;
//! use bumpsim_signal::process::Step;
//! let a = UniformSeries::new(0.0, 0.001, vec![-9.81; 1001]).unwrap();
//! let ch = Channel::new("ACX", "decel", Dimension::Acceleration, a);
//! let v = Step::Integrate(5.0).apply(&ch).unwrap();
//! assert_eq!(v.dimension, Dimension::Velocity);
//! assert!((v.series.values()[1000] - (5.0 - 9.81)).abs() < 1e-9);
//! ```

use crate::filter::{Butterworth, Cfc, CfcStandard, FilterError, moving_average};
use crate::integrate::{cumulative_trapezoid, derivative};
use crate::window::{ContactThreshold, WindowError};
use bumpsim_core::channel::Channel;
use bumpsim_core::names;
use bumpsim_core::series::{SeriesError, UniformSeries, WINDOW_TOLERANCE};
use bumpsim_core::units::{Dimension, format_number};
use serde::Deserialize;

/// Why a processing step failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ProcessError {
    /// A filter could not be designed or run.
    #[error("channel {channel}: {source}")]
    Filter {
        /// Channel code.
        channel: String,
        /// The filter error.
        source: FilterError,
    },
    /// The step does not apply to the channel's dimension.
    #[error("channel {channel}: step '{step}' needs {expected}, the channel is {found}")]
    Dimension {
        /// Channel code.
        channel: String,
        /// Step name.
        step: &'static str,
        /// What the step needs.
        expected: &'static str,
        /// The channel's dimension.
        found: Dimension,
    },
    /// The result is not a valid series (empty, non-finite).
    #[error("channel {channel}: step '{step}': {source}")]
    Series {
        /// Channel code.
        channel: String,
        /// Step name.
        step: &'static str,
        /// The series error.
        source: SeriesError,
    },
    /// A parameter or time interval is out of range.
    #[error("channel {channel}: step '{step}': {reason}")]
    Range {
        /// Channel code.
        channel: String,
        /// Step name.
        step: &'static str,
        /// What is wrong.
        reason: String,
    },
    /// Contact detection failed.
    #[error("channel {channel}: {source}")]
    Window {
        /// Channel code.
        channel: String,
        /// The window error.
        source: WindowError,
    },
}

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
    Bias([f64; 2]),
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
    Trim([f64; 2]),
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
            Step::Cfc(class) => Ok(c.cfc(*class, CfcStandard::SaeJ211)?.filtered(*class)),
            Step::CfcIso(class) => Ok(c.cfc(*class, CfcStandard::Iso6487)?.filtered(*class)),
            Step::Butterworth(b) => c.butterworth(b),
            Step::MovingAverage(n) => c.filtered(moving_average(channel.series.values(), *n)),
            Step::Bias([t0, t1]) => c.bias(
                |t| (*t0..=*t1).contains(&t),
                format!("in the bias window [{t0}, {t1}] s"),
            ),
            Step::PretriggerBias(false) | Step::Derivative(false) => Ok(channel.clone()),
            Step::PretriggerBias(true) => {
                c.bias(|t| t < 0.0, "before t = 0 (no pre-trigger)".into())
            }
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

    fn bias(&self, inside: impl Fn(f64) -> bool, what: String) -> Result<Channel, ProcessError> {
        let s = &self.channel.series;
        let picked: Vec<f64> = (0..s.len())
            .filter(|&i| inside(s.time(i)))
            .map(|i| s.values()[i])
            .collect();
        if picked.is_empty() {
            return Err(self.range(format!("no samples {what}")));
        }
        let mean = picked.iter().sum::<f64>() / picked.len() as f64;
        self.map(|v| v - mean)
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
            return Err(self.range(format!("mass {mass} kg must be positive")));
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
            Some((a, b)) => self.rebase(s.time(a), s.values()[a..=b].to_vec()),
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
            return Err(self.range(format!("interval {step} s must be positive")));
        }
        let s = &self.channel.series;
        let count = ((s.end() - s.start()) / step + WINDOW_TOLERANCE).floor() + 1.0;
        let max = bumpsim_io::output::MAX_SAMPLES;
        if !count.is_finite() || count > max as f64 {
            return Err(self.range(format!(
                "interval {step} s gives {count:.3e} samples, at most {max} per channel (limit MAX_SAMPLES)"
            )));
        }
        let count = count as usize;
        let values = (0..count)
            .map(|k| interpolate(s, s.start() + k as f64 * step))
            .collect();
        self.series(UniformSeries::new(s.start(), step, values))
    }
}

/// Linear interpolation of a series at time `t` (clamped to its ends).
pub fn interpolate(series: &UniformSeries, t: f64) -> f64 {
    series.at(t)
}

/// How channels are combined.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Combine {
    /// The arithmetic mean (left and right side members).
    Mean,
    /// The sum (the cells of a load-cell wall).
    Sum,
}

/// Combines channels of one dimension on their common time base (the
/// overlap of their spans, at the finest interval; linear interpolation
/// where bases differ). The result takes the first channel's identity with
/// a code listing all inputs.
pub fn combine(channels: &[Channel], how: Combine, code: &str) -> Result<Channel, ProcessError> {
    let first = channels.first().ok_or_else(|| ProcessError::Range {
        channel: code.to_string(),
        step: "combine",
        reason: "no channels to combine".into(),
    })?;
    if let Some(odd) = channels.iter().find(|c| c.dimension != first.dimension) {
        return Err(ProcessError::Range {
            channel: code.to_string(),
            step: "combine",
            reason: format!(
                "{} is {} but {} is {}",
                first.code, first.dimension, odd.code, odd.dimension
            ),
        });
    }
    let base = common_base(channels).ok_or_else(|| ProcessError::Range {
        channel: code.to_string(),
        step: "combine",
        reason: "the channels do not overlap in time".into(),
    })?;
    let scale = match how {
        Combine::Mean => 1.0 / channels.len() as f64,
        Combine::Sum => 1.0,
    };
    let values = base
        .times()
        .iter()
        .map(|&t| {
            scale
                * channels
                    .iter()
                    .map(|c| sample_at(&c.series, t))
                    .sum::<f64>()
        })
        .collect();
    let series = UniformSeries::new(base.start(), base.step(), values).map_err(|source| {
        ProcessError::Series {
            channel: code.to_string(),
            step: "combine",
            source,
        }
    })?;
    let mut out = first.with_series(series);
    out.code = code.to_string();
    Ok(out)
}

/// Samples every channel on their common time base (see [`combine`]):
/// returns the times, s, and one value column per channel.
pub fn align(channels: &[Channel]) -> Result<(Vec<f64>, Vec<Vec<f64>>), ProcessError> {
    let base = common_base(channels).ok_or_else(|| ProcessError::Range {
        channel: channels
            .iter()
            .map(|c| c.code.as_str())
            .collect::<Vec<_>>()
            .join(", "),
        step: "align",
        reason: "the channels do not overlap in time".into(),
    })?;
    let times = base.times();
    let columns = channels
        .iter()
        .map(|c| times.iter().map(|&t| sample_at(&c.series, t)).collect())
        .collect();
    Ok((times, columns))
}

/// What sampling channels on their common time base ([`align`],
/// [`combine`]) does to them: which are interpolated and which lose
/// samples outside the overlap. Nothing of it is silent: the study and the
/// loader turn it into a note.
#[derive(Debug, Clone, PartialEq)]
pub struct Resampling {
    /// The common sample interval, s (the finest of the channels').
    pub step: f64,
    /// The common span's first and last time, s (the channels' overlap).
    pub span: [f64; 2],
    /// Each channel's code, in the order given.
    pub codes: Vec<String>,
    /// Each channel's role in the note (`force`); its code unless
    /// [`Resampling::with_roles`] names them.
    pub roles: Vec<String>,
    /// Channels whose samples do not fall on the common base and are
    /// interpolated linearly: index into `codes` and own interval, s.
    pub interpolated: Vec<(usize, f64)>,
    /// Channels with samples outside the overlap, left out: index into
    /// `codes` and count.
    pub trimmed: Vec<(usize, usize)>,
}

impl std::fmt::Display for Resampling {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let own: Vec<f64> = self.interpolated.iter().map(|&(_, step)| step).collect();
        let times = distinct_times(&[&[self.step, self.span[0], self.span[1]], &own[..]].concat());
        let all = match self.codes.len() {
            n if n > 3 => format!("{n} channels"),
            n => (0..n)
                .map(|i| self.named(i))
                .collect::<Vec<_>>()
                .join(" and "),
        };
        write!(
            f,
            "{all} put on one time base, every {} from {} to {}",
            times[0], times[1], times[2]
        )?;
        // channels with the same own interval, or losing as many samples,
        // are named together
        let steps: Vec<(usize, &String)> = self
            .interpolated
            .iter()
            .map(|e| e.0)
            .zip(&times[3..])
            .collect();
        for (every, group) in grouped(&steps) {
            write!(
                f,
                "; {} (every {every}) interpolated linearly",
                self.roles_of(&group)
            )?;
        }
        for (&count, group) in grouped(&self.trimmed) {
            let each = if group.len() > 1 { " each" } else { "" };
            let samples = plural(count, "sample");
            let roles = self.roles_of(&group);
            write!(
                f,
                "; {roles}: {count} {samples}{each} outside that span left out"
            )?;
        }
        Ok(())
    }
}

/// `(index, value)` pairs grouped by equal value, in order of first
/// appearance.
fn grouped<T: PartialEq>(pairs: &[(usize, T)]) -> Vec<(&T, Vec<usize>)> {
    let mut groups: Vec<(&T, Vec<usize>)> = Vec::new();
    for (i, value) in pairs {
        match groups.iter_mut().find(|(v, _)| *v == value) {
            Some((_, members)) => members.push(*i),
            None => groups.push((value, vec![*i])),
        }
    }
    groups
}

impl Resampling {
    /// The same, with the channels named by their roles (`force`,
    /// `displacement`) in the order given; the note then shows both.
    pub fn with_roles(self, roles: &[&str]) -> Resampling {
        let roles = roles.iter().map(ToString::to_string).collect();
        Resampling { roles, ..self }
    }

    /// The roles of channels `group`, escaped, joined by commas.
    fn roles_of(&self, group: &[usize]) -> String {
        let roles: Vec<String> = group
            .iter()
            .map(|&i| names::escaped(&self.roles[i]))
            .collect();
        roles.join(", ")
    }

    /// Channel `i` as first named: its code, or its role and code.
    fn named(&self, i: usize) -> String {
        let code = names::escaped(&self.codes[i]);
        match self.roles[i] == self.codes[i] {
            true => code,
            false => format!("{} '{code}'", names::escaped(&self.roles[i])),
        }
    }
}

fn plural(count: usize, noun: &str) -> String {
    match count {
        1 => noun.to_string(),
        _ => format!("{noun}s"),
    }
}

/// `values` (s) in the display unit with the fewest significant digits,
/// from 4 to 12, that keep different values apart (a 1 ns span at 10 ms
/// must not read "from 10.00 ms to 10.00 ms").
fn distinct_times(values: &[f64]) -> Vec<String> {
    let unit = Dimension::Time.display_unit();
    let texts = |digits: usize| -> Vec<String> {
        let text = |v: &f64| {
            format!(
                "{} {}",
                format_number(unit.from_si(*v), digits),
                unit.symbol
            )
        };
        values.iter().map(text).collect()
    };
    let apart = |t: &[String]| {
        (0..values.len()).all(|i| (0..i).all(|j| values[i] == values[j] || t[i] != t[j]))
    };
    (4..=12)
        .map(texts)
        .find(|t| apart(t))
        .unwrap_or_else(|| texts(17))
}

/// What [`align`] or [`combine`] would change in `channels`; `None` when
/// every sample of every channel is used as it is.
///
/// ```
/// use bumpsim_core::prelude::*;
/// use bumpsim_signal::process::resampling;
/// let at = |step: f64, n: usize| UniformSeries::new(0.0, step, vec![1.0; n]).unwrap();
/// let force = Channel::new("F", "force", Dimension::Force, at(2e-4, 500));
/// let x = Channel::new("X", "x", Dimension::Length, at(1e-4, 1000));
/// let r = resampling(&[force, x]).unwrap();
/// assert_eq!(r.interpolated.len(), 1);
/// assert_eq!(r.interpolated[0].0, 0); // F
/// assert_eq!(r.trimmed, vec![(1, 1)]); // X: one sample after the force's last
/// let note = r.with_roles(&["force", "displacement"]).to_string();
/// assert!(note.starts_with("force 'F' and displacement 'X' put on one time base"));
/// ```
pub fn resampling(channels: &[Channel]) -> Option<Resampling> {
    let base = common_base(channels)?;
    let (start, step) = (base.start(), base.step());
    let end = start + step * (base.len() - 1) as f64;
    let on_base = |s: &UniformSeries| {
        let phase = (s.start() - start) / step;
        (s.step() / step - 1.0).abs() < 1e-9 && (phase - phase.round()).abs() < 1e-6
    };
    // samples before the span and after it, counted, not visited
    let outside = |s: &UniformSeries| {
        let slack = 1e-6 * step;
        let index = |t: f64| (t - s.start()) / s.step();
        let before = index(start - slack).ceil().clamp(0.0, s.len() as f64) as usize;
        let through = (index(end + slack).floor() + 1.0).clamp(0.0, s.len() as f64) as usize;
        s.len() - through + before
    };
    let series = || channels.iter().map(|c| &c.series).enumerate();
    let interpolated: Vec<(usize, f64)> = series()
        .filter(|(_, s)| !on_base(s))
        .map(|(i, s)| (i, s.step()))
        .collect();
    let trimmed: Vec<(usize, usize)> = series()
        .map(|(i, s)| (i, outside(s)))
        .filter(|&(_, n)| n > 0)
        .collect();
    let codes: Vec<String> = channels.iter().map(|c| c.code.clone()).collect();
    let changed = !(interpolated.is_empty() && trimmed.is_empty());
    changed.then(|| Resampling {
        step,
        span: [start, end],
        roles: codes.clone(),
        codes,
        interpolated,
        trimmed,
    })
}

/// The value at `t`, exact when `t` falls on a sample.
fn sample_at(series: &UniformSeries, t: f64) -> f64 {
    let x = (t - series.start()) / series.step();
    let k = x.round();
    if (x - k).abs() < 1e-6 && k >= 0.0 && (k as usize) < series.len() {
        return series.values()[k as usize];
    }
    interpolate(series, t)
}

/// The overlap of the channels' spans sampled at the finest interval.
fn common_base(channels: &[Channel]) -> Option<UniformSeries> {
    if channels.is_empty() {
        return None;
    }
    let start = channels
        .iter()
        .map(|c| c.series.start())
        .fold(f64::NEG_INFINITY, f64::max);
    let end = channels
        .iter()
        .map(|c| c.series.end())
        .fold(f64::INFINITY, f64::min);
    let step = channels
        .iter()
        .map(|c| c.series.step())
        .fold(f64::INFINITY, f64::min);
    if end < start {
        return None;
    }
    let count = ((end - start) / step + 1e-6).floor() as usize + 1;
    UniformSeries::new(start, step, vec![0.0; count]).ok()
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn channel(start: f64, values: Vec<f64>, dimension: Dimension) -> Channel {
        Channel::new(
            "X",
            "x",
            dimension,
            UniformSeries::new(start, 0.1, values).unwrap(),
        )
    }

    #[test]
    fn bias_trim_shift_and_mass() {
        let c = channel(-0.2, vec![1.0, 1.0, 3.0, 5.0], Dimension::Acceleration);
        let b = Step::PretriggerBias(true).apply(&c).unwrap();
        assert_relative_eq!(b.series.values()[3], 4.0);
        let t = Step::Trim([0.0, 0.1]).apply(&c).unwrap();
        assert_eq!(t.series.values(), &[3.0, 5.0]);
        let s = Step::Shift(0.2).apply(&c).unwrap();
        assert_relative_eq!(s.series.start(), 0.0);
        let f = Step::Mass(2.0).apply(&c).unwrap();
        assert_eq!(f.dimension, Dimension::Force);
        assert!(Step::Mass(2.0).apply(&f).is_err());
        assert!(Step::Bias([5.0, 6.0]).apply(&c).is_err());
        assert!(Step::Trim([5.0, 6.0]).apply(&c).is_err());
        assert!(Step::Integrate(0.0).apply(&f).is_err());
    }

    #[test]
    fn resampling_names_interpolated_and_trimmed_channels() {
        let a = channel(0.0, vec![1.0, 2.0, 3.0], Dimension::Force);
        assert_eq!(resampling(&[a.clone(), a.clone()]), None);
        // half a step later: the common base starts at 0.05 s, ends at 0.15 s
        let mut b = channel(0.05, vec![1.0, 2.0, 3.0], Dimension::Force);
        b.code = "Y\u{1b}[31m".into();
        let r = resampling(&[a.clone(), b.clone()]).unwrap();
        assert_eq!(r.interpolated.len(), 1);
        assert_eq!(r.interpolated[0].0, 0);
        approx::assert_relative_eq!(r.span[0], 0.05, max_relative = 1e-12);
        approx::assert_relative_eq!(r.span[1], 0.15, max_relative = 1e-12);
        assert_eq!(r.trimmed, [(0, 2), (1, 1)]);
        // the common base is what align and combine use
        let (times, _) = align(&[a, b]).unwrap();
        assert_eq!(times.len(), 2);
        let text = r.to_string();
        assert_eq!(
            text,
            r"X and Y\u001B[31m put on one time base, every 100.0 ms from 50.00 ms to 150.0 ms; X (every 100.0 ms) interpolated linearly; X: 2 samples outside that span left out; Y\u001B[31m: 1 sample outside that span left out"
        );
    }

    #[test]
    fn many_resampled_channels_are_named_in_groups() {
        let at = |code: &str, start: f64| {
            let mut c = channel(start, vec![1.0; 5], Dimension::Force);
            c.code = code.into();
            c
        };
        let five = [
            at("A", 0.0),
            at("B", 0.05),
            at("C", 0.05),
            at("D", 0.05),
            at("E", 0.0),
        ];
        let text = resampling(&five).unwrap().to_string();
        assert_eq!(
            text,
            "5 channels put on one time base, every 100.0 ms from 50.00 ms to 350.0 ms; A, E (every 100.0 ms) interpolated linearly; A, E: 2 samples each outside that span left out; B, C, D: 1 sample each outside that span left out"
        );
    }

    #[test]
    fn resampled_times_get_the_digits_that_tell_them_apart() {
        assert_eq!(
            distinct_times(&[1e-4, 0.01, 0.01 + 1e-9]),
            ["0.10000000 ms", "10.000000 ms", "10.000001 ms"]
        );
        assert_eq!(
            distinct_times(&[1e-4, 1.00000001e-4]),
            ["0.100000000 ms", "0.100000001 ms"]
        );
        assert_eq!(distinct_times(&[0.0, 0.0998]), ["0 ms", "99.80 ms"]);
    }

    #[test]
    fn combine_mean_and_sum_on_the_overlap() {
        let a = channel(0.0, vec![1.0, 2.0, 3.0], Dimension::Force);
        let b = channel(0.1, vec![10.0, 20.0, 30.0], Dimension::Force);
        let sum = combine(&[a.clone(), b.clone()], Combine::Sum, "A+B").unwrap();
        assert_eq!(sum.series.values(), &[12.0, 23.0]);
        let mean = combine(&[a.clone(), b], Combine::Mean, "m").unwrap();
        assert_relative_eq!(mean.series.values()[0], 6.0);
        let c = channel(0.0, vec![1.0], Dimension::Length);
        assert!(combine(&[a, c], Combine::Sum, "bad").is_err());
        assert!(combine(&[], Combine::Sum, "none").is_err());
    }

    #[test]
    fn resample_interpolates_linearly() {
        let a = channel(0.0, vec![0.0, 1.0, 2.0], Dimension::Length);
        let r = Step::Resample(0.05).apply(&a).unwrap();
        assert_eq!(r.series.len(), 5);
        assert_relative_eq!(r.series.values()[3], 1.5, max_relative = 1e-12);
    }

    #[test]
    fn steps_parse_from_toml_like_json() {
        let steps: Vec<Step> = serde_json::from_str(r#"[{"cfc": 60}, {"bias": [-0.05, 0.0]}, {"butterworth": {"order": 4, "cutoff": 300}}]"#).unwrap();
        assert_eq!(steps[0], Step::Cfc(60.0));
        assert!(matches!(
            steps[2],
            Step::Butterworth(ButterworthStep {
                zero_phase: true,
                ..
            })
        ));
    }
}
