//! What the page draws and reads: min/max decimation, cursor readouts and
//! pulse metrics, all in Rust.
//!
//! - **Decimation** ([`decimate`]): a window of `n` samples drawn on `px`
//!   pixels is sent as it is when `n ≤ 2 px` (zoomed in, every raw sample
//!   shows); otherwise the samples are split into `px` runs and each run
//!   gives its minimum and maximum, in time order, at their own times, so
//!   every peak of a 2-million-sample channel stays on screen.
//! - **Cursor** ([`readout`]): the sample nearest the cursor time,
//!   `k = round((t − t₀)/Δt)` clamped to the record, its time and value in
//!   the display unit; with two cursors their differences.
//! - **Pulse metrics** ([`metrics`]): an acceleration channel taken as the
//!   vehicle's x acceleration `a` from t = 0 (first contact) to the window's
//!   end: deceleration `−a`, velocity `v₀ + ∫a dt` (trapezoidal; `v₀` the
//!   test's impact speed, else 0), no lateral acceleration, then
//!   bumpsim-verdict's [`Pulse::metrics`]: peak, 3 ms clip, ΔV, OLC, ASI
//!   (EN 1317-1:2010).

use crate::session::Signal;
use bumpsim_core::series::{UniformSeries, cumulative_trapezoid};
use bumpsim_core::units::{Dimension, Unit};
use bumpsim_verdict::pulse::{AsiMethod, Pulse};
use serde::Serialize;

/// Samples of one signal to draw.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Drawn {
    /// Times, s.
    pub time: Vec<f64>,
    /// Values in the display unit.
    pub value: Vec<f64>,
    /// Whether these are the raw samples (no decimation).
    pub raw: bool,
}

/// The index range of the samples in `[t0, t1]`, one more on each side.
fn span(series: &UniformSeries, window: Option<(f64, f64)>) -> (usize, usize) {
    let last = series.len().saturating_sub(1);
    let Some((t0, t1)) = window else {
        return (0, last);
    };
    let at = |t: f64| ((t - series.start()) / series.step()).clamp(0.0, last as f64);
    let i0 = (at(t0).floor() as usize).saturating_sub(1);
    let i1 = (at(t1).ceil() as usize + 1).min(last);
    (i0, i1.max(i0))
}

/// The samples of `series` in `window` for `px` pixels, in `unit`.
pub fn decimate(
    series: &UniformSeries,
    window: Option<(f64, f64)>,
    px: usize,
    unit: Unit,
) -> Drawn {
    let (i0, i1) = span(series, window);
    let values = series.values();
    let count = i1 + 1 - i0;
    let mut drawn = Drawn {
        time: Vec::new(),
        value: Vec::new(),
        raw: count <= 2 * px,
    };
    let mut push = |k: usize| {
        drawn.time.push(series.time(k));
        drawn.value.push(unit.from_si(values[k]));
    };
    if count <= 2 * px {
        (i0..=i1).for_each(&mut push);
        return drawn;
    }
    for b in 0..px {
        let (a, z) = (i0 + b * count / px, i0 + (b + 1) * count / px);
        let (mut lo, mut hi) = (a, a);
        for k in a..z {
            if values[k] < values[lo] {
                lo = k;
            }
            if values[k] > values[hi] {
                hi = k;
            }
        }
        push(lo.min(hi));
        if lo != hi {
            push(lo.max(hi));
        }
    }
    drawn
}

/// A signal's sample at a cursor.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Reading {
    /// The sample's time, s.
    pub time: f64,
    /// Its value in the display unit.
    pub value: f64,
    /// Its index in the record.
    pub index: usize,
}

/// The readout of a signal at cursors A and B.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Readout {
    /// Legend label.
    pub label: String,
    /// Display unit.
    pub unit: String,
    /// At cursor A.
    pub a: Option<Reading>,
    /// At cursor B.
    pub b: Option<Reading>,
    /// B − A: time (s) and value (display unit).
    pub difference: Option<(f64, f64)>,
}

fn reading(signal: &Signal, t: f64) -> Option<Reading> {
    let s = &signal.channel.series;
    let last = s.len().checked_sub(1)?;
    let index = ((t - s.start()) / s.step()).round().clamp(0.0, last as f64) as usize;
    Some(Reading {
        time: s.time(index),
        value: signal.unit.from_si(s.values()[index]),
        index,
    })
}

/// The readouts of signals at cursors `ta` and `tb`.
pub fn readout(signals: &[Signal], ta: Option<f64>, tb: Option<f64>) -> Vec<Readout> {
    signals
        .iter()
        .map(|signal| {
            let a = ta.and_then(|t| reading(signal, t));
            let b = tb.and_then(|t| reading(signal, t));
            let difference = match (&a, &b) {
                (Some(a), Some(b)) => Some((b.time - a.time, b.value - a.value)),
                _ => None,
            };
            Readout {
                label: signal.label.clone(),
                unit: signal.unit.symbol.to_string(),
                a,
                b,
                difference,
            }
        })
        .collect()
}

/// The pulse metrics of one acceleration signal.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PulseMetrics {
    /// Legend label.
    pub label: String,
    /// Peak deceleration, g.
    pub peak_g: f64,
    /// 3 ms clip, g.
    pub clip_g: f64,
    /// Velocity change, km/h.
    pub delta_v_kmh: f64,
    /// OLC, g.
    pub olc_g: Option<f64>,
    /// ASI, 1.
    pub asi: Option<f64>,
    /// Why a metric is missing; what was assumed.
    pub notes: Vec<String>,
}

const G: f64 = 9.80665;

/// The pulse metrics of the acceleration signals, from t = 0 (or the
/// window's start, if later) to the window's end; `speed` the impact speed
/// of each signal's test, m/s.
pub fn metrics(
    signals: &[Signal],
    window: Option<(f64, f64)>,
    speed: &dyn Fn(usize) -> Option<f64>,
) -> Vec<PulseMetrics> {
    signals
        .iter()
        .filter(|s| s.channel.dimension == Dimension::Acceleration)
        .filter_map(|s| pulse_metrics(s, window, speed(s.test)))
        .collect()
}

fn pulse_metrics(
    signal: &Signal,
    window: Option<(f64, f64)>,
    v0: Option<f64>,
) -> Option<PulseMetrics> {
    let s = &signal.channel.series;
    let (w0, w1) = window.unwrap_or((0.0, s.end()));
    let (i0, i1) = span(s, Some((w0.max(0.0), w1)));
    if i1 < i0 + 2 {
        return None;
    }
    let a = &s.values()[i0..=i1];
    let time: Vec<f64> = (i0..=i1).map(|k| s.time(k)).collect();
    let mut notes = vec![
        "the channel taken as the vehicle's x acceleration (deceleration = −a), no lateral acceleration".to_string(),
    ];
    let v0 = v0.unwrap_or_else(|| {
        notes.push("no impact speed in the test: v₀ = 0".into());
        0.0
    });
    let velocity = cumulative_trapezoid(a, s.step(), v0);
    let delta_v = (velocity[0] - velocity[velocity.len() - 1]).abs();
    let pulse = Pulse {
        deceleration: a.iter().map(|v| -v).collect(),
        lateral: vec![0.0; a.len()],
        contact_end: time[time.len() - 1],
        time,
        velocity,
        delta_v,
    };
    let (m, more) = pulse.metrics(true, AsiMethod::En2010);
    notes.extend(more);
    Some(PulseMetrics {
        label: signal.label.clone(),
        peak_g: m.peak / G,
        clip_g: m.clip / G,
        delta_v_kmh: m.delta_v * 3.6,
        olc_g: m.olc.map(|v| v / G),
        asi: m.asi,
        notes,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decimation_keeps_extremes_and_raw_when_zoomed() {
        let values: Vec<f64> = (0..100_000).map(|k| ((k * 7919) % 1000) as f64).collect();
        let series = UniformSeries::new(0.0, 1e-5, values).unwrap();
        let unit = Unit::si(Dimension::Force);
        let d = decimate(&series, None, 100, unit);
        assert!(!d.raw && d.value.len() <= 200);
        assert_eq!(d.value.iter().copied().fold(f64::MIN, f64::max), 999.0);
        assert_eq!(d.value.iter().copied().fold(f64::MAX, f64::min), 0.0);
        let z = decimate(&series, Some((0.0, 5e-4)), 100, unit);
        assert!(z.raw);
        assert_eq!(z.value[..51], series.values()[..51]);
    }
}
