//! Planar load cases from test channels: the conditioning of the 1-D
//! identification (bumpsim_ident's study, thesis ch. 3.2) applied to each
//! force channel and to each of the two sensors.
//!
//! - Every channel: bias removal over the pre-trigger (when it starts
//!   before t = 0) and, when given, the CFC filter (SAE J211-1).
//! - Forces: in N, each with its lateral position, direction and anchor ([`Placed`]).
//! - Sensors: the body-x accelerations integrated twice, from the car's
//!   speed at t = 0 and zero displacement, to the world-x displacements
//!   the replay predicts.
//! - Samples from t = 0 on; the fit window is the contact window of the
//!   summed force (rise 5 %, fall 2 % of its peak, as the 1-D study).

use crate::car::PlanarError;
use crate::drive::{Drive, Load, Sensor};
use crate::identify::PlanarCase;
use crate::synth::Recorded;
use bumpsim_core::channel::Channel;
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
    /// Where each sits.
    pub positions: Vec<Sensor>,
    /// The car's speed at t = 0, m/s.
    pub speed: f64,
    /// CFC class of the filter, if any.
    pub cfc: Option<f64>,
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
            speed: recorded.car_speed,
            cfc: Some(180.0),
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
        let integrate = [Step::Integrate(self.speed), Step::Integrate(0.0)];
        let mut channels = Vec::new();
        for f in &self.forces {
            channels.push(condition(&f.channel, &[])?);
        }
        for s in &self.sensors {
            channels.push(condition(s, &integrate)?);
        }
        let (time, columns) = align(&channels).map_err(|e| error(e.to_string()))?;
        let resampled = resampling(&channels);
        let first = time
            .iter()
            .position(|&t| t >= -1e-9 * time.get(1).map_or(1.0, |t1| (t1 - time[0]).abs()))
            .ok_or_else(|| error("no sample at or after t = 0".into()))?;
        let step = match time.len() > 1 {
            true => time[1] - time[0],
            false => 0.0,
        };
        let n = self.forces.len();
        let loads: Vec<Load> = self
            .forces
            .iter()
            .zip(&columns)
            .map(|(f, values)| Load {
                lateral: f.lateral,
                anchor: f.anchor,
                cell: f.cell,
                direction: f.direction,
                force: values[first..].to_vec(),
            })
            .collect();
        let total: Vec<f64> = (first..time.len())
            .map(|k| columns[..n].iter().map(|c| c[k]).sum::<f64>().abs())
            .collect();
        let window = ContactThreshold::default()
            .detect(&total)
            .map_err(|e| error(format!("force: {e}")))?;
        let case = PlanarCase {
            name: self.name.clone(),
            drive: Drive {
                step,
                loads,
                speed: self.speed,
                sensors: self.positions.clone(),
            },
            measured: columns[n..].iter().map(|c| c[first..].to_vec()).collect(),
            window: (window.first, window.last),
            estimated: (0..n).filter(|&k| self.forces[k].estimated).collect(),
            striker: None,
        };
        Ok((case, resampled))
    }
}
