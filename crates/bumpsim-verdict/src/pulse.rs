//! Pulse metrics an engineer reads off a low-speed test: the peak and the
//! 3 ms clip of the deceleration, the velocity change, the occupant load
//! criterion and the acceleration severity index.
//!
//! - **Contact end** ([`contact_end`]): the first time after the force's
//!   peak at which the striker's force falls below
//!   [`CONTACT_END_SHARE`] (1 %) of its peak and stays below for
//!   [`CONTACT_END_QUIET`] (2 ms), the crossing interpolated between
//!   samples. The simulation's own contact end is the first sample with no
//!   force at all, so a force that hovers at a few newtons while the beam
//!   leaves the face ends the contact at 46.9 ms or 54.0 ms by rounding
//!   (a pendulum speed of 1.1176 or 1.1176000000000001 m/s), and the
//!   velocity change to the record's end moved with it (0.9009 against
//!   0.8986 m/s). 1 % of the peak: a force that small changes the car's
//!   velocity at a hundredth of the peak's rate, about what a load cell
//!   sized for the peak resolves, so the end does not hinge on whether a
//!   residual force is exactly zero; 2 ms (20 samples at 0.1 ms, a
//!   twentieth of a 40 ms contact): a beam that leaves the face for a
//!   moment and strikes again is not taken for the end. The pulse is the
//!   car's motion from first contact (t = 0) to that end; after it the car
//!   rolls on at its velocity then, with no acceleration (the tyres'
//!   braking after the impact is not part of the pulse).
//! - **Velocity change** ΔV: the body CG's velocity at the contact end
//!   minus its velocity at first contact (a vector difference, its
//!   magnitude).
//! - **3 ms clip**: the level the deceleration exceeds for a cumulative
//!   3 ms (the 3 ms criterion of FMVSS 208 and ECE R94's chest
//!   acceleration): the 3 ms ÷ T-th largest sample.
//! - **OLC** (occupant load criterion; Euro NCAP Technical Bulletin TB 027,
//!   MPDB compatibility): a virtual occupant moves on at the vehicle's
//!   initial velocity v₀ until it has moved 65 mm relative to the vehicle
//!   (t₁), then decelerates uniformly so that it comes to the vehicle's
//!   velocity after a further 235 mm (t₂); OLC is that deceleration,
//!   `(v₀ − v(t₂)) / (t₂ − t₁)`. As pyisomme computes it
//!   (`pyisomme.calculate.olc`): the relative displacement is the
//!   trapezoidal integral of `v₀ − v` from t = 0, t₁ the first sample at or
//!   beyond 65 mm and t₂ the first sample after t₁ at which
//!   `s(t₂) − OLC (t₂ − t₁)²/2 ≥ 300 mm`.
//! - **ASI** (acceleration severity index, EN 1317-1):
//!   `ASI(t) = √((ā_x/12g)² + (ā_y/9g)² + (ā_z/10g)²)`, g = 9.81 m/s² (the
//!   standard's value); ASI is its largest value. [`AsiMethod`] says how
//!   the accelerations `ā` are averaged:
//!   - EN 1317-1:2010 (the default): each acceleration through a
//!     "4-pole phaseless Butterworth" low-pass filter of 13 Hz cut-off.
//!     That is read as SAE J211-1 and ISO 6487 use the same words for the
//!     CFC filters (bumpsim_signal::filter): a **2-pole** Butterworth run
//!     forward and then backward, so the cascade has four poles and no
//!     phase (`scipy.signal.butter(2, 13, fs=1/T)` with `filtfilt`), not a
//!     4-pole design run both ways (eight poles). Codes that implement the
//!     2010 ASI name it the same way (Oasys T/HIS: "four-pole phaseless
//!     Butterworth filter with a 13 Hz cut-off", after a CFC 180 filter,
//!     the record padded with 0.5 s). The record is padded with 0.5 s of
//!     zero acceleration on each side (the car at constant speed before
//!     the contact, rolling on after it) so that the filter's start-up
//!     does not touch the pulse; the maximum is taken over every sample.
//!   - EN 1317-1:1998: averages over a moving 50 ms window (the
//!     trapezoidal integral over the window, linear between samples),
//!     windows starting at first contact (t = 0) or later, up to the last
//!     that fits in the record.
//!
//!   A simulated pulse carries no measurement noise, so no CFC filter runs
//!   first.
//!
//! Signs: the pulse is taken along the body's x axis towards the struck
//! end (the planar car's frame), so the deceleration is positive in a
//! barrier test and in a pendulum test alike, and `v₀ − v` grows in both.
//! A record that ends before the virtual occupant has travelled its 300 mm
//! is continued at its last velocity (the car rolls on after the impact):
//! [`Pulse::extended`].

use crate::error::VerdictError;
use bumpsim_planar::PlanarResult;
use serde::Serialize;

/// g as EN 1317-1 and pyisomme's OLC take it, m/s².
pub const G_EN1317: f64 = 9.81;
/// The free-flight displacement of the OLC's virtual occupant, m.
pub const OLC_FREE_FLIGHT: f64 = 0.065;
/// Its restraint displacement after the free flight, m.
pub const OLC_RESTRAINT: f64 = 0.235;
/// The 1998 ASI's averaging window, s.
pub const ASI_WINDOW: f64 = 0.05;
/// The 2010 ASI's low-pass cut-off, Hz.
pub const ASI_CUTOFF: f64 = 13.0;
/// The 2010 ASI's Butterworth order per pass (run forward and backward:
/// four poles, no phase).
pub const ASI_ORDER: usize = 2;
/// The zero acceleration the 2010 ASI's record is padded with on each
/// side, s.
pub const ASI_PADDING: f64 = 0.5;
/// The share of its peak below which the striker's force must stay for
/// the contact to end, 1 (see the module).
pub const CONTACT_END_SHARE: f64 = 0.01;
/// How long the force must stay below that share, s.
pub const CONTACT_END_QUIET: f64 = 0.002;

/// How the ASI averages the vehicle's accelerations (see the module).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub enum AsiMethod {
    /// EN 1317-1:2010: a 2-pole Butterworth low-pass of 13 Hz run forward
    /// and backward (4 poles, phaseless).
    #[default]
    #[serde(rename = "EN 1317-1:2010")]
    En2010,
    /// EN 1317-1:1998: 50 ms moving averages from first contact.
    #[serde(rename = "EN 1317-1:1998")]
    En1998,
}

impl AsiMethod {
    /// The method of an edition's year, `2010` or `1998`.
    pub fn of_year(year: u16) -> Option<AsiMethod> {
        match year {
            2010 => Some(AsiMethod::En2010),
            1998 => Some(AsiMethod::En1998),
            _ => None,
        }
    }

    /// The edition, `EN 1317-1:2010`.
    pub fn name(self) -> &'static str {
        match self {
            AsiMethod::En2010 => "EN 1317-1:2010",
            AsiMethod::En1998 => "EN 1317-1:1998",
        }
    }
}
/// The cumulative duration of the clip, s.
pub const CLIP: f64 = 0.003;

/// The body's motion along its own axes, sampled at a fixed interval.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Pulse {
    /// Sample times, s.
    pub time: Vec<f64>,
    /// Velocity along the body's x axis, m/s.
    pub velocity: Vec<f64>,
    /// Deceleration along the body's x axis (−a_x), m/s².
    pub deceleration: Vec<f64>,
    /// Lateral acceleration along the body's y axis, m/s².
    pub lateral: Vec<f64>,
    /// Velocity change of the body's CG from first contact to the contact
    /// end, m/s.
    pub delta_v: f64,
    /// The contact end, s ([`contact_end`]; the last sample's time when
    /// the force never falls away).
    pub contact_end: f64,
}

/// The metrics of a pulse.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Metrics {
    /// Largest deceleration, m/s².
    pub peak: f64,
    /// 3 ms clip of the deceleration, m/s².
    pub clip: f64,
    /// Velocity change from first contact to the contact end, m/s.
    pub delta_v: f64,
    /// The contact end, s.
    pub contact_end: f64,
    /// Occupant load criterion, m/s² (None: not computable, see `notes`).
    pub olc: Option<f64>,
    /// Acceleration severity index, 1.
    pub asi: Option<f64>,
    /// How the ASI averaged the accelerations.
    pub asi_method: AsiMethod,
}

impl Pulse {
    /// The body's pulse in a planar result: the CG velocity turned into
    /// the body's axes, its accelerations by central differences, up to
    /// the contact end ([`contact_end`]); the samples after it carry the
    /// velocity at the contact end and no acceleration, and the record
    /// stops at the first sample past it.
    pub fn of(r: &PlanarResult) -> Pulse {
        let n = r.time.len();
        let last = r.time.last().copied().unwrap_or(0.0);
        let end = contact_end(&r.time, &r.force).unwrap_or(last);
        let body = |k: usize| {
            let (sn, cs) = r.yaw[k].sin_cos();
            let (vx, vy) = (r.velocity_x[k], r.velocity_y[k]);
            (vx * cs + vy * sn, -vx * sn + vy * cs)
        };
        let mut velocity: Vec<f64> = (0..n).map(|k| body(k).0).collect();
        let (mut deceleration, mut lateral) = (vec![0.0; n], vec![0.0; n]);
        for k in 0..n {
            let (a, b) = (k.saturating_sub(1), (k + 1).min(n - 1));
            if b == a {
                continue;
            }
            let dt = r.time[b] - r.time[a];
            let ax = (r.velocity_x[b] - r.velocity_x[a]) / dt;
            let ay = (r.velocity_y[b] - r.velocity_y[a]) / dt;
            let (sn, cs) = r.yaw[k].sin_cos();
            deceleration[k] = -(ax * cs + ay * sn);
            lateral[k] = -ax * sn + ay * cs;
        }
        let delta_v = match n {
            0 => 0.0,
            _ => {
                let change = |v: &[f64]| at(&r.time, v, end) - at(&r.time, v, 0.0);
                change(&r.velocity_x).hypot(change(&r.velocity_y))
            }
        };
        let after = r.time.partition_point(|&t| t <= end);
        let keep = (after + 1).min(n);
        if after < n {
            let rolling = at(&r.time, &velocity, end);
            velocity[after..].iter_mut().for_each(|v| *v = rolling);
            deceleration[after..].iter_mut().for_each(|a| *a = 0.0);
            lateral[after..].iter_mut().for_each(|a| *a = 0.0);
        }
        for series in [&mut velocity, &mut deceleration, &mut lateral] {
            series.truncate(keep);
        }
        Pulse {
            time: r.time[..keep].to_vec(),
            velocity,
            deceleration,
            lateral,
            delta_v,
            contact_end: end,
        }
    }

    /// The pulse of a body moving along a line (a 1-D car,
    /// [`crate::line`]): its velocity `velocity` (m/s, along x towards the
    /// struck end) at the samples `time` with the striker's force `force`
    /// (N); the same as [`Pulse::of`] with no yaw and no lateral motion:
    /// the deceleration by central differences, ΔV to the contact end,
    /// the record after it rolling on.
    pub fn along(time: &[f64], force: &[f64], velocity: &[f64]) -> Pulse {
        let n = time.len().min(velocity.len());
        let last = time.last().copied().unwrap_or(0.0);
        let end = contact_end(time, force).unwrap_or(last);
        let mut velocity = velocity[..n].to_vec();
        let mut deceleration = vec![0.0; n];
        for (k, d) in deceleration.iter_mut().enumerate() {
            let (a, b) = (k.saturating_sub(1), (k + 1).min(n - 1));
            if b != a {
                *d = -(velocity[b] - velocity[a]) / (time[b] - time[a]);
            }
        }
        let delta_v = match n {
            0 => 0.0,
            _ => (at(time, &velocity, end) - at(time, &velocity, 0.0)).abs(),
        };
        let after = time[..n].partition_point(|&t| t <= end);
        let keep = (after + 1).min(n);
        if after < n {
            let rolling = at(time, &velocity, end);
            velocity[after..].iter_mut().for_each(|v| *v = rolling);
            deceleration[after..].iter_mut().for_each(|a| *a = 0.0);
        }
        velocity.truncate(keep);
        deceleration.truncate(keep);
        Pulse {
            time: time[..keep].to_vec(),
            velocity,
            deceleration,
            lateral: vec![0.0; keep],
            delta_v,
            contact_end: end,
        }
    }

    /// The pulse continued to `until` s at its last velocity and zero
    /// acceleration (the car rolling on after the record).
    pub fn extended(&self, until: f64) -> Pulse {
        let mut p = self.clone();
        let (Some(&last), Some(&v)) = (self.time.last(), self.velocity.last()) else {
            return p;
        };
        let step = match self.time.len() {
            0 | 1 => return p,
            n => (self.time[n - 1] - self.time[0]) / (n - 1) as f64,
        };
        let extra = ((until - last) / step).ceil().max(0.0) as usize;
        for k in 1..=extra {
            p.time.push(last + k as f64 * step);
            p.velocity.push(v);
            p.deceleration.push(0.0);
            p.lateral.push(0.0);
        }
        p
    }

    /// Peak, 3 ms clip, velocity change and, with `full`, OLC and the ASI
    /// by `method` (the record continued as far as they need, up to 8 s);
    /// the reasons a metric could not be computed are returned with them.
    pub fn metrics(&self, full: bool, method: AsiMethod) -> (Metrics, Vec<String>) {
        let end = self.time.last().copied().unwrap_or(0.0);
        let mut notes = Vec::new();
        let (mut olc_value, mut asi_value) = (None, None);
        if full {
            let mut found = Err(VerdictError::Pulse {
                metric: "OLC",
                reason: "no record".into(),
            });
            for more in [0.5, 2.0, 8.0] {
                let long = self.extended(end + more);
                found = olc(&long.time, &long.velocity);
                if found.is_ok() {
                    break;
                }
            }
            olc_value = found
                .map(|o| o.value)
                .map_err(|e| notes.push(e.to_string()))
                .ok();
            let long = match method {
                AsiMethod::En1998 => self.extended(end + ASI_WINDOW),
                AsiMethod::En2010 => self.clone(),
            };
            let zeros = vec![0.0; long.time.len()];
            let a = [&long.deceleration[..], &long.lateral, &zeros];
            asi_value = asi(&long.time, a, method)
                .map_err(|e| notes.push(e.to_string()))
                .ok();
        }
        let (olc, asi) = (olc_value, asi_value);
        let metrics = Metrics {
            peak: self.deceleration.iter().copied().fold(0.0, f64::max),
            clip: clip(&self.time, &self.deceleration, CLIP),
            delta_v: self.delta_v,
            contact_end: self.contact_end,
            olc,
            asi,
            asi_method: method,
        };
        (metrics, notes)
    }
}

/// The level `values` exceed for a cumulative `duration` s (samples every
/// `time` step): the 3 ms clip with `duration` 0.003.
///
/// ```
/// let time: Vec<f64> = (0..100).map(|k| k as f64 * 1e-4).collect();
/// let a: Vec<f64> = (0..100).map(|k| k as f64).collect();
/// assert_eq!(bumpsim_verdict::pulse::clip(&time, &a, 0.003), 70.0);
/// ```
pub fn clip(time: &[f64], values: &[f64], duration: f64) -> f64 {
    let n = values.len();
    if n < 2 {
        return values.first().copied().unwrap_or(0.0);
    }
    let step = (time[n - 1] - time[0]) / (n - 1) as f64;
    let count = ((duration / step).round() as usize).clamp(1, n);
    let mut sorted = values.to_vec();
    let (_, nth, _) = sorted.select_nth_unstable_by(count - 1, |a, b| b.total_cmp(a));
    *nth
}

/// The OLC of a pulse: its value (m/s²) and the times t₁ and t₂ (s).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Olc {
    /// OLC, m/s².
    pub value: f64,
    /// End of the free flight, s.
    pub t1: f64,
    /// End of the restraint, s.
    pub t2: f64,
}

/// Linear interpolation of `values` at `t` (constant beyond the ends).
fn at(time: &[f64], values: &[f64], t: f64) -> f64 {
    let i = time.partition_point(|&x| x <= t);
    match i {
        0 => values[0],
        i if i >= time.len() => values[time.len() - 1],
        i => {
            values[i - 1]
                + (values[i] - values[i - 1]) * (t - time[i - 1]) / (time[i] - time[i - 1])
        }
    }
}

/// The cumulative trapezoidal integral of `values`, from the first sample.
fn integral(time: &[f64], values: &[f64]) -> Vec<f64> {
    let mut sum = vec![0.0; values.len()];
    for k in 1..values.len() {
        sum[k] = sum[k - 1] + 0.5 * (values[k] + values[k - 1]) * (time[k] - time[k - 1]);
    }
    sum
}

fn check_series(metric: &'static str, time: &[f64], values: &[&[f64]]) -> Result<(), VerdictError> {
    let bad = |reason: String| Err(VerdictError::Pulse { metric, reason });
    if time.len() < 2 || values.iter().any(|v| v.len() != time.len()) {
        return bad(format!(
            "needs at least two samples of equal length ({} times)",
            time.len()
        ));
    }
    if time
        .windows(2)
        .any(|w| w[1].partial_cmp(&w[0]) != Some(std::cmp::Ordering::Greater))
        || time
            .iter()
            .chain(values.iter().copied().flatten())
            .any(|x| !x.is_finite())
    {
        return bad("times must increase and every value be finite".into());
    }
    Ok(())
}

/// The occupant load criterion of a velocity `velocity` (m/s, along the
/// direction the vehicle decelerates in) sampled at `time` (s, time zero =
/// first contact), as pyisomme computes it.
///
/// ```
/// // a vehicle from 15 m/s to rest at a constant 300 m/s² from t = 0
/// let time: Vec<f64> = (0..2000).map(|k| k as f64 * 1e-4).collect();
/// let v: Vec<f64> = time.iter().map(|t| (15.0 - 300.0 * t).max(0.0)).collect();
/// let olc = bumpsim_verdict::pulse::olc(&time, &v).unwrap();
/// assert!(olc.value > 300.0 && olc.t1 > 0.0);
/// ```
pub fn olc(time: &[f64], velocity: &[f64]) -> Result<Olc, VerdictError> {
    check_series("OLC", time, &[velocity])?;
    let bad = |reason: String| VerdictError::Pulse {
        metric: "OLC",
        reason,
    };
    let v0 = at(time, velocity, 0.0);
    let relative: Vec<f64> = velocity.iter().map(|v| v0 - v).collect();
    let mut s = integral(time, &relative);
    let zero = at(time, &s, 0.0);
    s.iter_mut().for_each(|x| *x -= zero);
    let i1 = s.iter().position(|&x| x >= OLC_FREE_FLIGHT).ok_or_else(|| {
        bad(format!(
            "the occupant's free flight of {} mm relative to the vehicle is not reached within the record",
            OLC_FREE_FLIGHT * 1e3
        ))
    })?;
    let t1 = time[i1];
    for i2 in i1 + 1..time.len() {
        let (t2, v2) = (time[i2], velocity[i2]);
        let value = (v0 - v2) / (t2 - t1);
        let occupant = s[i2] - value * (0.5 * t2 * t2 + 0.5 * t1 * t1 - t1 * t2);
        if occupant >= OLC_FREE_FLIGHT + OLC_RESTRAINT {
            return Ok(Olc { value, t1, t2 });
        }
    }
    Err(bad(format!(
        "the restraint displacement of {} mm is not reached within the record",
        OLC_RESTRAINT * 1e3
    )))
}

/// The contact end of a striker force `force` (N, any sign) sampled at
/// `time` (s): the first time after its peak at which its magnitude falls
/// below [`CONTACT_END_SHARE`] of the peak and stays below for
/// [`CONTACT_END_QUIET`] (or to the record's end), interpolated linearly
/// between the samples around the crossing. None without any force.
///
/// ```
/// // a half sine of 40 ms, then a residual 0.1 % of the peak
/// let time: Vec<f64> = (0..800).map(|k| k as f64 * 1e-4).collect();
/// let pi = std::f64::consts::PI;
/// let f: Vec<f64> = time.iter().map(|&t| if t < 0.04 { 1e4 * (pi * t / 0.04).sin() } else { 10.0 }).collect();
/// let end = bumpsim_verdict::pulse::contact_end(&time, &f).unwrap();
/// // sin(π t / 40 ms) = 0.01 at t = 40 ms × (1 − asin(0.01)/π)
/// assert!((end - 0.04 * (1.0 - 0.01f64.asin() / pi)).abs() < 1e-6);
/// ```
pub fn contact_end(time: &[f64], force: &[f64]) -> Option<f64> {
    let n = time.len().min(force.len());
    let magnitude: Vec<f64> = force[..n].iter().map(|f| f.abs()).collect();
    let (top, peak) = magnitude
        .iter()
        .copied()
        .enumerate()
        .fold(
            (0, 0.0),
            |best, (k, f)| if f > best.1 { (k, f) } else { best },
        );
    if peak <= 0.0 {
        return None;
    }
    let threshold = CONTACT_END_SHARE * peak;
    let mut k = top + 1;
    while k < n {
        if magnitude[k] >= threshold {
            k += 1;
            continue;
        }
        let quiet_until = time[k] + CONTACT_END_QUIET;
        let again = (k + 1..n)
            .take_while(|&j| time[j] <= quiet_until)
            .find(|&j| magnitude[j] >= threshold);
        match again {
            Some(j) => k = j + 1,
            None => {
                let (f0, f1) = (magnitude[k - 1], magnitude[k]);
                let share = (f0 - threshold) / (f0 - f1);
                return Some(time[k - 1] + share * (time[k] - time[k - 1]));
            }
        }
    }
    time.get(n.wrapping_sub(1)).copied()
}

/// The acceleration severity index of the accelerations `[a_x, a_y, a_z]`
/// (m/s², any sign) sampled at `time` (s; t = 0 at first contact) by
/// `method` (see the module).
///
/// ```
/// use bumpsim_verdict::pulse::{AsiMethod, asi};
/// // a constant 12 g longitudinal for 60 ms: 1998 ASI 1
/// let time: Vec<f64> = (0..=600).map(|k| k as f64 * 1e-4).collect();
/// let ax = vec![12.0 * 9.81; time.len()];
/// let zeros = vec![0.0; time.len()];
/// let a = asi(&time, [&ax, &zeros, &zeros], AsiMethod::En1998).unwrap();
/// assert!((a - 1.0).abs() < 1e-12);
/// // the 2010 filter rings over the 60 ms step by 2.9 % (as scipy's
/// // filtfilt of butter(2, 13 Hz) on the same padded record)
/// let filtered = asi(&time, [&ax, &zeros, &zeros], AsiMethod::En2010).unwrap();
/// assert!((filtered - 1.028926300604871).abs() < 1e-9);
/// ```
pub fn asi(time: &[f64], a: [&[f64]; 3], method: AsiMethod) -> Result<f64, VerdictError> {
    check_series("ASI", time, &a)?;
    match method {
        AsiMethod::En1998 => asi_1998(time, a),
        AsiMethod::En2010 => asi_2010(time, a),
    }
}

/// The acceleration limits 12 g, 9 g, 10 g, m/s².
fn limits() -> [f64; 3] {
    [12.0, 9.0, 10.0].map(|g| g * G_EN1317)
}

/// EN 1317-1:2010: filtered, padded, the largest value over the samples.
fn asi_2010(time: &[f64], a: [&[f64]; 3]) -> Result<f64, VerdictError> {
    let bad = |reason: String| VerdictError::Pulse {
        metric: "ASI",
        reason,
    };
    let n = time.len();
    let step = (time[n - 1] - time[0]) / (n - 1) as f64;
    let uneven = time
        .windows(2)
        .any(|w| ((w[1] - w[0]) / step - 1.0).abs() > 1e-6);
    if uneven {
        return Err(bad(
            "the EN 1317-1:2010 filter needs a constant sample interval".into(),
        ));
    }
    let filter = bumpsim_signal::filter::Butterworth::new(ASI_ORDER, ASI_CUTOFF, step)
        .map_err(|e| bad(format!("its {ASI_CUTOFF} Hz low-pass: {e}")))?;
    let pad = (ASI_PADDING / step).round() as usize;
    let limits = limits();
    let mut squares = vec![0.0; n + 2 * pad];
    for (values, limit) in a.iter().zip(limits) {
        let padded: Vec<f64> = std::iter::repeat_n(0.0, pad)
            .chain(values.iter().copied())
            .chain(std::iter::repeat_n(0.0, pad))
            .collect();
        let filtered = filter
            .zero_phase(&padded, ASI_FILTER_PADDING)
            .map_err(|e| bad(format!("its {ASI_CUTOFF} Hz low-pass: {e}")))?;
        for (s, f) in squares.iter_mut().zip(filtered) {
            *s += (f / limit).powi(2);
        }
    }
    Ok(squares.into_iter().fold(0.0, f64::max).sqrt())
}

/// The filter's own odd padding at each end, samples (scipy's `filtfilt`
/// default for a 2-pole design, `3 max(len(a), len(b))`; the record's zero
/// padding already keeps the start-up off the pulse).
const ASI_FILTER_PADDING: usize = 9;

/// EN 1317-1:1998: the largest value over the 50 ms windows from first
/// contact that fit in the record.
fn asi_1998(time: &[f64], a: [&[f64]; 3]) -> Result<f64, VerdictError> {
    let end = time[time.len() - 1];
    let first = time.partition_point(|&t| t < 0.0);
    if first >= time.len() || end - time[first] < ASI_WINDOW {
        return Err(VerdictError::Pulse {
            metric: "ASI",
            reason: format!(
                "the record from first contact ({} s) is shorter than the 50 ms window",
                end - time[first.min(time.len() - 1)].max(0.0)
            ),
        });
    }
    let sums = a.map(|values| integral(time, values));
    let limits = limits();
    let mut largest = 0.0f64;
    for (k, &t) in time
        .iter()
        .enumerate()
        .skip(first)
        .take_while(|(_, t)| **t + ASI_WINDOW <= end + 1e-12)
    {
        let squares: f64 = (0..3)
            .map(|i| {
                let mean = (at(time, &sums[i], t + ASI_WINDOW) - sums[i][k]) / ASI_WINDOW;
                (mean / limits[i]).powi(2)
            })
            .sum();
        largest = largest.max(squares.sqrt());
    }
    Ok(largest)
}
