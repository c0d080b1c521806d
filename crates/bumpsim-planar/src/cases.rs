//! Planar load cases from test channels: the conditioning of the 1-D
//! identification (bumpsim_ident's study, thesis ch. 3.2) applied to each
//! force channel and to each of the two sensors.
//!
//! - Every channel: bias removal over the pre-trigger (when it starts
//!   before t = 0) and, when given, the CFC filter (SAE J211-1).
//! - Forces: in N, each with its lateral position, direction and anchor ([`Placed`]).
//! - Sensors, each to the domain its model reading has
//!   ([`Sensor::integrations`]): body-x accelerations integrated twice, from
//!   the car's speed at t = 0 and zero displacement, to the world-x
//!   displacements the replay predicts; lateral accelerations twice from
//!   rest; the yaw rate as measured; displacements (film, string pots) as
//!   measured, less their value at t = 0 and without the pre-trigger bias
//!   (a film target moves before contact).
//! - Each sensor's weight (`weights`): its noise in the compared domain,
//!   from the white noise level σ of its pre-trigger (the residual about a
//!   straight line, unfiltered) or as the study gives it, over the fit
//!   window's duration T: σ as measured, `σ √h T^{3/2}/√12` integrated
//!   twice (the rms over the window of integrated white noise sampled
//!   every h). The x accelerometers keep weight 1 (their
//!   residuals in m, as before); every other sensor is weighted by the x
//!   accelerometers' pooled noise over its own, so the objective stays in
//!   m² and a study of x accelerometers alone is the same least-squares
//!   problem as it was.
//! - Time zero, where the replay starts: by default just before the force
//!   onset (ISO 6487 and SAE J211 put time zero at the first contact). The
//!   onset is the last sample before the summed force's 5 % rise at which
//!   it is within its noise ([`onset`], on the conditioned forces); a soft
//!   toe (a pole's curve, an angled wall's corner) stays in the noise for a
//!   while after the true first touch, so time zero lies the longer of
//!   [`ONSET_LEAD`] and the onset's rise time (onset to 5 %) before it: a
//!   replay that starts before contact is exact (free travel at the
//!   speed), one that starts late has lost crush. Or a time the study gives
//!   (`time_zero`, s of the file's time base: 0 keeps the file's). Every
//!   channel is shifted so that this instant is t = 0 before the sensors
//!   are integrated from the car's speed there. Anchors (a pole's axis, a
//!   wall cell's centre) are given in the body frame at the files' t = 0,
//!   as the lab measured the set-up; they move into the body frame at time
//!   zero by the car's travel between the two instants (the mean of the two
//!   body sensors' displacement there; the car does not turn before contact).
//! - Samples from t = 0 on; the fit window is the contact window of the
//!   summed force (rise 5 %, fall 2 % of its peak, as the 1-D study).

use crate::car::PlanarError;
use crate::drive::{Drive, Load, Sensor};
use crate::identify::PlanarCase;
use crate::synth::Recorded;
use bumpsim_core::channel::Channel;
use bumpsim_core::units::{Dimension, format_quantity};
use bumpsim_signal::process::{Resampling, Step, align, resampling, run};
use bumpsim_signal::window::ContactThreshold;

/// A force channel and its place on the bumper line.
#[derive(Debug, Clone, PartialEq)]
pub struct Placed {
    /// The channel (force).
    pub channel: Channel,
    /// Lateral position, m (left positive).
    pub lateral: f64,
    /// Direction of the force on the car, world frame.
    pub direction: [f64; 2],
    /// A world-fixed point on its line of action (a pole's axis), body
    /// frame at t = 0, m ([`Load::anchor`]).
    pub anchor: Option<[f64; 2]>,
    /// Whether its lateral position is estimated (`lateral` is the start):
    /// a single total force whose line of action no cell measured.
    pub estimated: bool,
    /// A wall's load cell of this width, m ([`Load::cell`]).
    pub cell: Option<f64>,
}

/// The decimation of samples every `step` (s) filtered at CFC `cfc`: the
/// largest whole factor that keeps the rate at least [`RATE_PER_CFC`] times
/// the filter's −3 dB frequency (`5 cfc / 3` Hz), at least 1.
///
/// ```
/// use bumpsim_planar::cases::decimation;
/// assert_eq!(decimation(1e-4, 180.0), 3);   // 10 kHz to 3.3 kHz: ≥ 3 kHz
/// assert_eq!(decimation(1e-4, 1000.0), 1);
/// ```
pub fn decimation(step: f64, cfc: f64) -> usize {
    let rate = RATE_PER_CFC * 5.0 * cfc / 3.0;
    let factor = (1.0 / (step * rate)).floor();
    match factor.is_finite() && factor >= 1.0 {
        true => factor as usize,
        false => 1,
    }
}

/// A CFC-filtered case is sampled at least this many times its filter's
/// −3 dB frequency (SAE J211-1 asks for at least 8 to 10 times).
pub const RATE_PER_CFC: f64 = 10.0;

/// The summed force's onset is the last sample before its rise at which it
/// is within [`ONSET_NOISE`] times its noise (the median absolute deviation
/// of the samples before the rise, as a standard deviation), and at most
/// this fraction of its peak.
pub const ONSET_FLOOR: f64 = 1e-3;

/// How many standard deviations of noise a force may show before contact.
pub const ONSET_NOISE: f64 = 4.0;

/// The shortest lead of time zero before the detected onset, s.
pub const ONSET_LEAD: f64 = 2e-3;

/// Where a case's time zero lies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TimeZero {
    /// At the summed force's onset (the first contact).
    Onset,
    /// At this time of the file's time base, s (0: the file's own).
    At(f64),
}

/// The index of the onset of `force` (any sign) whose contact starts at
/// sample `first`: walking back from `first`, the last sample within the
/// noise before it (at most [`ONSET_NOISE`] standard deviations, estimated
/// by the median absolute deviation of the samples before `first`, or
/// [`ONSET_FLOOR`] of the peak when that is larger); 0 when none is.
///
/// ```
/// use bumpsim_planar::cases::onset;
/// let f = [0.0, 0.0, 0.0, 0.0, 0.0004, 0.02, 0.2, 1.0, 0.3, 0.0];
/// assert_eq!(onset(&f, 6), 4);
/// ```
pub fn onset(force: &[f64], first: usize) -> usize {
    let first = first.min(force.len().saturating_sub(1));
    let peak = force.iter().fold(0.0f64, |m, f| m.max(f.abs()));
    let floor = (ONSET_NOISE * noise(&force[..first])).max(ONSET_FLOOR * peak);
    force[..=first]
        .iter()
        .rposition(|f| f.abs() <= floor)
        .unwrap_or(0)
}

/// The standard deviation of a signal's noise from its median absolute
/// deviation (1.4826 MAD for Gaussian noise; robust to the few samples of a
/// contact's toe among many of the pre-trigger).
fn noise(values: &[f64]) -> f64 {
    let median = |v: &mut Vec<f64>| -> f64 {
        v.sort_by(f64::total_cmp);
        v.get(v.len() / 2).copied().unwrap_or(0.0)
    };
    let centre = median(&mut values.to_vec());
    1.4826 * median(&mut values.iter().map(|v| (v - centre).abs()).collect())
}

/// The car's travel along x from time zero to `at` (s, time zero's time
/// base): the mean of the two body sensors' displacements `sensors` there,
/// linearly interpolated (0 without two sensors or at time zero itself).
fn travel(time: &[f64], sensors: &[Vec<f64>], at: f64) -> f64 {
    if sensors.len() < 2 || at == 0.0 || time.len() < 2 {
        return 0.0;
    }
    let step = time[1] - time[0];
    let k = ((at - time[0]) / step).clamp(0.0, (time.len() - 2) as f64);
    let (i, w) = (k.floor() as usize, k.fract());
    let mean = |j: usize| 0.5 * (sensors[0][j] + sensors[1][j]);
    mean(i) + w * (mean(i + 1) - mean(i))
}

/// A channel's conditioning with extra steps after the common ones.
type Conditioning<'a> = dyn Fn(&Channel, &[Step]) -> Result<Channel, PlanarError> + 'a;

/// The channels of one test and what is known of it.
#[derive(Debug, Clone, PartialEq)]
pub struct TestChannels {
    /// Case name.
    pub name: String,
    /// The force channels.
    pub forces: Vec<Placed>,
    /// The accelerometers (body x): the first two on the body, left then
    /// right, then any others.
    pub sensors: Vec<Channel>,
    /// Where each sits and what it measures.
    pub positions: Vec<Sensor>,
    /// Each sensor's noise as the study gives it (SI of its channel), or
    /// `None`: from its pre-trigger.
    pub noise: Vec<Option<f64>>,
    /// The car's speed at t = 0, m/s.
    pub speed: f64,
    /// CFC class of the filter, if any.
    pub cfc: Option<f64>,
    /// Where time zero lies.
    pub time_zero: TimeZero,
}

impl TestChannels {
    /// The channels of a synthetic test, CFC 180 as the 1-D example study.
    pub fn of(recorded: &Recorded) -> TestChannels {
        let n = recorded.loads.len();
        let forces = recorded.channels[..n]
            .iter()
            .zip(&recorded.loads)
            .map(|(channel, spec)| Placed {
                channel: channel.clone(),
                lateral: spec.lateral,
                direction: spec.direction,
                anchor: spec.anchor,
                estimated: false,
                cell: None,
            })
            .collect();
        TestChannels {
            name: recorded.name.clone(),
            forces,
            sensors: recorded.channels[n..].to_vec(),
            positions: recorded.sensors.clone(),
            noise: vec![None; recorded.sensors.len()],
            speed: recorded.car_speed,
            cfc: Some(180.0),
            time_zero: TimeZero::Onset,
        }
    }

    /// Conditions the channels into a load case, with what putting them on
    /// one time base did to them when it did anything
    /// ([`bumpsim_signal::process::resampling`]).
    pub fn case(&self) -> Result<(PlanarCase, Option<Resampling>), PlanarError> {
        let error = |message: String| PlanarError::Case {
            case: self.name.clone(),
            message,
        };
        if self.forces.is_empty() {
            return Err(error("no force channel".into()));
        }
        let mut steps = vec![Step::PretriggerBias(true)];
        steps.extend(self.cfc.map(Step::Cfc));
        let condition = |c: &Channel, extra: &[Step]| {
            let mut all = match c.series.start() < 0.0 {
                true => steps.clone(),
                false => steps[1..].to_vec(),
            };
            all.extend_from_slice(extra);
            run(&all, c).map_err(|e| error(e.to_string()))
        };
        let span = self.forces[0].channel.series.start()..=self.forces[0].channel.series.end();
        let zero = match self.time_zero {
            TimeZero::At(t) if span.contains(&t) => t,
            TimeZero::At(t) if t.is_finite() => {
                return Err(error(format!(
                    "time_zero = {t:?} s lies outside the record ({} to {})",
                    format_quantity(*span.start(), Dimension::Time),
                    format_quantity(*span.end(), Dimension::Time)
                )));
            }
            TimeZero::At(t) => {
                return Err(error(format!(
                    "time_zero = {t} s: expected a finite time of the file's time base"
                )));
            }
            TimeZero::Onset => self.onset(&condition)?,
        };
        let shift = [Step::Shift(-zero)];
        let mut channels = Vec::new();
        for f in &self.forces {
            channels.push(condition(&f.channel, &shift)?);
        }
        for (s, place) in self.sensors.iter().zip(&self.positions) {
            let start = if place.along_x() { self.speed } else { 0.0 };
            let integrals = (0..place.integrations()).map(|k| match k {
                0 => Step::Integrate(start),
                _ => Step::Integrate(0.0),
            });
            let extra: Vec<Step> = shift.iter().cloned().chain(integrals).collect();
            channels.push(match place.displacement() {
                // a displacement keeps its pre-trigger: a film target moves before contact
                true => run(
                    &[self.cfc.map(Step::Cfc).into_iter().collect(), extra].concat(),
                    s,
                )
                .map_err(|e| error(e.to_string()))?,
                false => condition(s, &extra)?,
            });
        }
        let (time, columns) = align(&channels).map_err(|e| error(e.to_string()))?;
        // the note speaks of the files' times
        let resampled = resampling(&channels).map(|mut r| {
            r.span = r.span.map(|t| t + zero);
            r
        });
        let first = time
            .iter()
            .position(|&t| t >= -1e-9 * time.get(1).map_or(1.0, |t1| (t1 - time[0]).abs()))
            .ok_or_else(|| error("no sample at or after t = 0".into()))?;
        let step = match time.len() > 1 {
            true => time[1] - time[0],
            false => 0.0,
        };
        // channels filtered at CFC c carry nothing above its −3 dB
        // frequency 5c/3 Hz: keep every d-th sample, as long as the rate
        // stays at least 10 times that frequency (SAE J211-1's sampling)
        let every = self.cfc.map_or(1, |c| decimation(step, c));
        let kept = |values: &[f64]| -> Vec<f64> {
            values[first..].iter().step_by(every).copied().collect()
        };
        let n = self.forces.len();
        let mut columns = columns;
        for (column, place) in columns[n..].iter_mut().zip(&self.positions) {
            if place.displacement() {
                let at_zero = column[first];
                column.iter_mut().for_each(|v| *v -= at_zero);
            }
        }
        let travel = travel(&time, &columns[n..], -zero);
        let loads: Vec<Load> = self
            .forces
            .iter()
            .zip(&columns)
            .map(|(f, values)| Load {
                lateral: f.lateral,
                anchor: f.anchor.map(|[xi, eta]| [xi + travel, eta]),
                cell: f.cell,
                direction: f.direction,
                force: kept(values),
            })
            .collect();
        let total: Vec<f64> = (first..time.len())
            .step_by(every)
            .map(|k| columns[..n].iter().map(|c| c[k]).sum::<f64>().abs())
            .collect();
        let window = ContactThreshold::default()
            .detect(&total)
            .map_err(|e| error(format!("force: {e}")))?;
        let step = step * every as f64;
        // the forward runs filter their simulated channels at this class and
        // the kept samples' interval (crate::forward): checked here, once
        if let Some(class) = self.cfc {
            bumpsim_signal::filter::Cfc::new(class, Default::default())
                .and_then(|f| f.design(step))
                .map_err(|e| {
                    error(format!(
                        "cfc = {class} at the kept samples' interval {step} s: {e}"
                    ))
                })?;
        }
        let duration = step * (window.last - window.first) as f64;
        let weights = weights(self, duration)?;
        let case = PlanarCase {
            name: self.name.clone(),
            drive: Drive {
                step,
                loads,
                speed: self.speed,
                arm: 1.0,
                sensors: self.positions.clone(),
            },
            measured: columns[n..].iter().map(|c| kept(c)).collect(),
            window: (window.first, window.last),
            estimated: (0..n).filter(|&k| self.forces[k].estimated).collect(),
            striker: None,
            time_zero: zero,
            weights,
            pretrigger: self.pretrigger(),
            cfc: self.cfc,
            nuisance: false,
            x_noise: self.x_noise(),
        };
        Ok((case, resampled))
    }

    /// The noise density of the first two sensors' mean (the sills),
    /// (m/s²)·√s: `√((σ_L² h_L + σ_R² h_R)/4)`, each σ as the study gives
    /// it or from its pre-trigger ([`pretrigger_noise`]) at its step h; 0
    /// when either is unknown.
    fn x_noise(&self) -> f64 {
        let density = |k: usize| {
            let c = self.sensors.get(k)?;
            let sigma = self
                .noise
                .get(k)
                .copied()
                .flatten()
                .or_else(|| pretrigger_noise(c))?;
            Some(sigma * sigma * c.series.step())
        };
        match (density(0), density(1)) {
            (Some(l), Some(r)) if (l + r).is_finite() => (0.25 * (l + r)).sqrt(),
            _ => 0.0,
        }
    }

    /// The shortest pre-trigger (record before the file's t = 0) of the
    /// accelerometers, over which their biases are removed, s (0: one has
    /// none).
    fn pretrigger(&self) -> f64 {
        self.sensors
            .iter()
            .zip(&self.positions)
            .filter(|(_, place)| !place.displacement() && place.integrations() == 2)
            .map(|(c, _)| (-c.series.start()).max(0.0))
            .reduce(f64::min)
            .filter(|t| t.is_finite())
            .unwrap_or(0.0)
    }

    /// Time zero before the summed conditioned forces' onset ([`onset`],
    /// [`ONSET_LEAD`]), s of the file's time base.
    fn onset(&self, condition: &Conditioning) -> Result<f64, PlanarError> {
        let forces = self
            .forces
            .iter()
            .map(|f| condition(&f.channel, &[]))
            .collect::<Result<Vec<_>, _>>()?;
        let (time, columns) = align(&forces).map_err(|e| PlanarError::Case {
            case: self.name.clone(),
            message: e.to_string(),
        })?;
        let total: Vec<f64> = (0..time.len())
            .map(|k| columns.iter().map(|c| c[k]).sum::<f64>())
            .collect();
        let window = ContactThreshold::default()
            .detect(&total)
            .map_err(|e| PlanarError::Case {
                case: self.name.clone(),
                message: format!("force: {e}"),
            })?;
        let at = onset(&total, window.first);
        let lead = ONSET_LEAD.max(time[window.first] - time[at]);
        Ok((time[at] - lead).max(time[0]))
    }
}

/// The white noise level of a channel's pre-trigger (samples before t = 0):
/// the standard deviation of its residual about a least-squares line, in
/// its SI unit; `None` with fewer than [`PRETRIGGER_SAMPLES`] samples.
pub fn pretrigger_noise(channel: &Channel) -> Option<f64> {
    let series = &channel.series;
    let values: Vec<f64> = (0..series.len())
        .filter(|&k| series.time(k) < 0.0)
        .map(|k| series.values()[k])
        .collect();
    let n = values.len();
    if n < PRETRIGGER_SAMPLES {
        return None;
    }
    let mean_k = 0.5 * (n - 1) as f64;
    let mean_v = values.iter().sum::<f64>() / n as f64;
    let (mut sxy, mut sxx) = (0.0, 0.0);
    for (k, v) in values.iter().enumerate() {
        sxy += (k as f64 - mean_k) * (v - mean_v);
        sxx += (k as f64 - mean_k).powi(2);
    }
    let slope = sxy / sxx;
    let sse: f64 = values
        .iter()
        .enumerate()
        .map(|(k, v)| (v - mean_v - slope * (k as f64 - mean_k)).powi(2))
        .sum();
    let sigma = (sse / (n - 2) as f64).sqrt();
    sigma.is_finite().then_some(sigma)
}

/// The fewest pre-trigger samples a noise level is estimated from.
pub const PRETRIGGER_SAMPLES: usize = 20;

/// White noise of level `sigma` sampled every `step` in the domain of
/// `integrations` integrals: its rms over `duration` (see the module).
pub fn domain_noise(sigma: f64, step: f64, duration: f64, integrations: usize) -> f64 {
    bumpsim_estimate::domain::integrated_noise(sigma, step, duration, integrations)
}

/// Each sensor's residual weight (see the module): 1 for the x
/// accelerometers, their pooled noise over its own for every other; an
/// error names a sensor whose noise is neither given nor estimable.
fn weights(channels: &TestChannels, duration: f64) -> Result<Vec<f64>, PlanarError> {
    let noise: Vec<Option<f64>> = channels
        .sensors
        .iter()
        .zip(&channels.positions)
        .zip(&channels.noise)
        .map(|((c, place), given)| {
            let sigma = given.or_else(|| pretrigger_noise(c))?;
            let step = c.series.step();
            let domain = domain_noise(sigma, step, duration, place.integrations());
            (domain.is_finite() && domain > 0.0).then_some(domain)
        })
        .collect();
    if channels.positions.iter().all(Sensor::along_x) {
        return Ok(vec![1.0; channels.positions.len()]);
    }
    let x: Vec<f64> = noise
        .iter()
        .zip(&channels.positions)
        .filter(|(_, p)| p.along_x())
        .map(|(n, _)| n.unwrap_or(f64::NAN))
        .collect();
    if x.is_empty() {
        // it blamed the first sensor's pre-trigger (a yaw-rate sensor's,
        // with 500 samples of it): issue 44's hostile pass
        return Err(PlanarError::Case {
            case: channels.name.clone(),
            message: "sensors: no x accelerometer, which the other sensors are weighed against: the first two sensors are x accelerometers on the body (body = [ξ, η] m), left then right".into(),
        });
    }
    let pooled = (x.iter().map(|v| v * v).sum::<f64>() / x.len() as f64).sqrt();
    let unknown = |k: usize| PlanarError::Case {
        case: channels.name.clone(),
        message: format!(
            "sensor {}: no noise to weigh it by: its record has no pre-trigger of {PRETRIGGER_SAMPLES} samples (or it is exactly flat); give `noise` (its rms noise, with a unit) in the study",
            channels.sensors[k].code
        ),
    };
    if !(pooled.is_finite() && pooled > 0.0) {
        let k = (0..noise.len())
            .find(|&k| channels.positions[k].along_x() && noise[k].is_none())
            .unwrap_or(0);
        return Err(unknown(k));
    }
    (0..noise.len())
        .map(|k| match (channels.positions[k].along_x(), noise[k]) {
            (true, _) => Ok(1.0),
            (false, Some(own)) => Ok(pooled / own),
            (false, None) => Err(unknown(k)),
        })
        .collect()
}
