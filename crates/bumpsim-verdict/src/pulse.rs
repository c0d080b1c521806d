//! Pulse metrics an engineer reads off a low-speed test: the peak and the
//! 3 ms clip of the deceleration, the velocity change, the occupant load
//! criterion and the acceleration severity index.
//!
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
//! - **ASI** (acceleration severity index, EN 1317-1:2010 §6.1):
//!   `ASI(t) = √((ā_x/12g)² + (ā_y/9g)² + (ā_z/10g)²)` with `ā` the averages
//!   of the vehicle's accelerations over a moving 50 ms window and
//!   g = 9.81 m/s² (the standard's value); ASI is its largest value. The
//!   averages are the trapezoidal integral over the window (linear between
//!   samples). EN 1317-1 filters measured accelerations first (its 13 Hz
//!   low-pass); a simulated pulse carries no noise and is used as it is.
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
/// The ASI's averaging window, s.
pub const ASI_WINDOW: f64 = 0.05;
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
    /// Velocity change of the body's CG from the first to the last sample, m/s.
    pub delta_v: f64,
}

/// The metrics of a pulse.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Metrics {
    /// Largest deceleration, m/s².
    pub peak: f64,
    /// 3 ms clip of the deceleration, m/s².
    pub clip: f64,
    /// Velocity change, m/s.
    pub delta_v: f64,
    /// Occupant load criterion, m/s² (None: not computable, see `notes`).
    pub olc: Option<f64>,
    /// Acceleration severity index, 1.
    pub asi: Option<f64>,
}

impl Pulse {
    /// The body's pulse in a planar result: the CG velocity turned into
    /// the body's axes, its accelerations by central differences.
    pub fn of(r: &PlanarResult) -> Pulse {
        let n = r.time.len();
        let body = |k: usize| {
            let (sn, cs) = r.yaw[k].sin_cos();
            let (vx, vy) = (r.velocity_x[k], r.velocity_y[k]);
            (vx * cs + vy * sn, -vx * sn + vy * cs)
        };
        let velocity: Vec<f64> = (0..n).map(|k| body(k).0).collect();
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
                (r.velocity_x[n - 1] - r.velocity_x[0]).hypot(r.velocity_y[n - 1] - r.velocity_y[0])
            }
        };
        Pulse {
            time: r.time.clone(),
            velocity,
            deceleration,
            lateral,
            delta_v,
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

    /// Peak, 3 ms clip, velocity change and, with `full`, OLC and ASI
    /// (the record continued as far as they need, up to 8 s); the reasons
    /// a metric could not be computed are returned with them.
    pub fn metrics(&self, full: bool) -> (Metrics, Vec<String>) {
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
            let long = self.extended(end + ASI_WINDOW);
            let zeros = vec![0.0; long.time.len()];
            asi_value = asi(&long.time, [&long.deceleration, &long.lateral, &zeros])
                .map_err(|e| notes.push(e.to_string()))
                .ok();
        }
        let (olc, asi) = (olc_value, asi_value);
        let metrics = Metrics {
            peak: self.deceleration.iter().copied().fold(0.0, f64::max),
            clip: clip(&self.time, &self.deceleration, CLIP),
            delta_v: self.delta_v,
            olc,
            asi,
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

/// The acceleration severity index of the accelerations `[a_x, a_y, a_z]`
/// (m/s², any sign) sampled at `time` (s): the largest value over the
/// 50 ms windows that fit in the record.
///
/// ```
/// // a constant 12 g longitudinal for 60 ms: ASI 1
/// let time: Vec<f64> = (0..=600).map(|k| k as f64 * 1e-4).collect();
/// let ax = vec![12.0 * 9.81; time.len()];
/// let zeros = vec![0.0; time.len()];
/// let asi = bumpsim_verdict::pulse::asi(&time, [&ax, &zeros, &zeros]).unwrap();
/// assert!((asi - 1.0).abs() < 1e-12);
/// ```
pub fn asi(time: &[f64], a: [&[f64]; 3]) -> Result<f64, VerdictError> {
    check_series("ASI", time, &a)?;
    let end = time[time.len() - 1];
    if end - time[0] < ASI_WINDOW {
        return Err(VerdictError::Pulse {
            metric: "ASI",
            reason: format!(
                "the record ({} s) is shorter than the 50 ms window",
                end - time[0]
            ),
        });
    }
    let sums = a.map(|values| integral(time, values));
    let limits = [12.0, 9.0, 10.0].map(|g| g * G_EN1317);
    let mut largest = 0.0f64;
    for (k, &t) in time
        .iter()
        .enumerate()
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
