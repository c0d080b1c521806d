//! Synthetic asymmetric test series of the planar car (spec §9): what a lab
//! would record in flat, offset, angled and pole tests, for examples and for
//! testing the planar identification against a known car.
//!
//! Each test is simulated by [`crate::simulate()`] with its own step (safety
//! factor [`Chain::safety`], coarser than identification's replay) and
//! histories every `T/10` (T the sample interval). The measurement chain,
//! as the 1-D pendulum series of `bumpsim_impact::synth`:
//! - a fixed plane (rigid barrier) carries one load cell per bumper segment
//!   (`B0LOMA01jj00FOXP`, j = 1 at the right): a load-cell wall whose cells
//!   are as wide as the segments and face them at first contact (the car's
//!   lateral drift, millimetres, is neglected); it measures the force normal
//!   to the wall;
//! - a pole (fixed or on a pendulum) has a two-axis load cell
//!   (`B0POLE000000FOXP`/`FOYP`, or `P0IMPA…`): −F_x and F_y, whose line of
//!   action passes through the pole's axis (normal forces on a circle do);
//! - a flat pendulum's load cell (`P0IMPA000000FOXP`) measures the whole
//!   contact force, placed at the centre of the overlap;
//! - accelerometers on the sills at (ξ, ±η) (`10SILBLE0000ACXP`,
//!   `10SILBRI0000ACXP`) and, when the car has chains, on the side members'
//!   front ends (`10SIMELE0000ACXP`, `10SIMERI0000ACXP`, as in the 1-D
//!   series) measure the acceleration along the body x axis (second
//!   differences of the sensor's world position, projected on the body
//!   axis), plus a bias (left, right);
//! - optionally ([`Chain::yaw_rate`]) a yaw-rate sensor (`10VEHC0000CGAVZP`,
//!   rad/s, the simulation's ψ̇) with its own noise;
//! - every channel passes a causal 4th-order Butterworth anti-alias filter
//!   at a quarter of the sampling rate, is sampled every T, gets Gaussian
//!   noise (ChaCha8, seeded per test: reproducible bit for bit) and a
//!   pre-trigger of zeros.
//!
//! With each test comes the description identification needs ([`LoadSpec`]):
//! every force channel's lateral position and direction.

use crate::car::{PlanarCar, PlanarError, parameter};
use crate::drive::Sensor;
use crate::simulate::{Settings, simulate};
use crate::striker::Placed;
use crate::striker::{Face, Motion, Side, Striker, place};
use bumpsim_core::channel::Channel;
use bumpsim_core::series::UniformSeries;
use bumpsim_core::units::{Dimension, STANDARD_GRAVITY};
use bumpsim_impact::synth::gaussian;
use bumpsim_signal::filter::Butterworth;
use rand_chacha::ChaCha8Rng;
use rand_core::SeedableRng;

/// The measurement chain of a planar series: the 1-D series' chain
/// (`bumpsim_impact::synth::Chain`: step, pre-trigger, duration, noise,
/// biases, seed) plus where the sills are and the generator's step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Chain {
    /// Sampling, duration, noise, biases (left, right) and seed.
    pub measurement: bumpsim_impact::synth::Chain,
    /// Sill accelerometers: ξ ahead of the CG and the half-spacing η, m.
    pub sensor: [f64; 2],
    /// Safety factor of the simulation's step (the generator's own).
    pub safety: f64,
    /// A yaw-rate sensor with this rms noise, rad/s, or none.
    pub yaw_rate: Option<f64>,
}

impl Default for Chain {
    /// 10 kHz, 50 ms pre-trigger, 150 ms after contact, 20 N per cell,
    /// 0.05 g noise and (0.03, −0.02) g biases, sills 0.6 m ahead of the CG
    /// at ±0.7 m, simulated at a quarter of the critical step, seed 1.
    fn default() -> Self {
        Chain {
            measurement: bumpsim_impact::synth::Chain {
                step: 1e-4,
                pretrigger: 0.05,
                duration: 0.15,
                force_noise: 20.0,
                acceleration_noise: 0.05 * STANDARD_GRAVITY,
                biases: [0.03 * STANDARD_GRAVITY, -0.02 * STANDARD_GRAVITY],
                seed: 1,
            },
            sensor: [0.6, 0.7],
            safety: 0.25,
            yaw_rate: None,
        }
    }
}

/// A force channel's place on the car: what identification needs to replay it.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadSpec {
    /// Channel code.
    pub channel: String,
    /// Lateral position on the bumper line, m (left positive).
    pub lateral: f64,
    /// Direction of the force on the car, world frame (unit vector).
    pub direction: [f64; 2],
    /// A world-fixed point on its line of action, body frame at t = 0, m
    /// (a pole's axis: every normal force on a circle passes through it).
    pub anchor: Option<[f64; 2]>,
}

/// One synthetic test.
#[derive(Debug, Clone, PartialEq)]
pub struct Recorded {
    /// Test name.
    pub name: String,
    /// The channels (SI values; source units kN and g).
    pub channels: Vec<Channel>,
    /// The force channels' places.
    pub loads: Vec<LoadSpec>,
    /// The accelerometers, in the order of their channels: the sills (left,
    /// right), then the side members' front ends (left, right) when the
    /// car has chains.
    pub sensors: Vec<Sensor>,
    /// The car's speed before contact, m/s (0 for a pendulum test).
    pub car_speed: f64,
    /// The striker's speed, m/s, and mass, kg (pendulum tests).
    pub striker: (f64, Option<f64>),
    /// The car's mass, kg.
    pub car_mass: f64,
}

impl Recorded {
    /// The ISO-MME test header: the title, the car as test object 1 (its
    /// speed before contact, m/s, and mass, kg, as the `1…` codes number
    /// it) and a pendulum as test object 2 (its speed and mass).
    pub fn test_header(&self) -> Vec<(String, String)> {
        use bumpsim_io::test_data::iso_header::{TestObject, test_objects_header};
        let title = format!("{}: synthetic planar test (bumpsim synth)", self.name);
        let mut objects = vec![TestObject {
            name: "car".into(),
            speed: Some(self.car_speed),
            mass: Some(self.car_mass),
        }];
        if let (speed, Some(mass)) = self.striker {
            objects.push(TestObject {
                name: "pendulum".into(),
                speed: Some(speed),
                mass: Some(mass),
            });
        }
        test_objects_header(&title, &objects)
    }
}

/// The code and name of the yaw-rate sensor.
pub const YAW_RATE_CODE: (&str, &str) = ("10VEHC0000CGAVZP", "Vehicle yaw rate Z");

/// Codes and names of the accelerometers: sills left and right, side
/// members left and right.
pub const SENSOR_CODES: [(&str, &str); 4] = [
    ("10SILBLE0000ACXP", "Sill left X"),
    ("10SILBRI0000ACXP", "Sill right X"),
    ("10SIMELE0000ACXP", "Side member left X"),
    ("10SIMERI0000ACXP", "Side member right X"),
];

/// The accelerometers of `car` with sills at (ξ, ±η).
fn sensors(car: &PlanarCar, [xi, eta]: [f64; 2]) -> Vec<Sensor> {
    let mut out = vec![Sensor::Body([xi, eta]), Sensor::Body([xi, -eta])];
    let left = car.left().masses.len();
    if left > 0 && !car.right().masses.is_empty() {
        out.extend([Sensor::Chain(0), Sensor::Chain(left)]);
    }
    out
}

fn check(chain: &Chain) -> Result<(), PlanarError> {
    let times = [
        ("chain.step", chain.measurement.step),
        ("chain.duration", chain.measurement.duration),
    ];
    for (name, value) in times {
        if !(value.is_finite() && value > 0.0) {
            return Err(parameter(name, value, "s", "a finite positive time"));
        }
    }
    if !(chain.measurement.pretrigger.is_finite() && chain.measurement.pretrigger >= 0.0) {
        return Err(parameter(
            "chain.pretrigger",
            chain.measurement.pretrigger,
            "s",
            "a finite time ≥ 0",
        ));
    }
    let samples =
        10.0 * (chain.measurement.pretrigger + chain.measurement.duration) / chain.measurement.step;
    if samples > crate::drive::MAX_SAMPLES as f64 {
        return Err(parameter(
            "chain.duration",
            chain.measurement.duration,
            "s",
            &format!(
                "at most {} simulated samples (10 per sample interval)",
                crate::drive::MAX_SAMPLES
            ),
        ));
    }
    use bumpsim_impact::synth::{SeriesError, check_noise};
    if let Err(SeriesError::Noise {
        name,
        value,
        unit,
        expected,
    }) = check_noise(&chain.measurement)
    {
        return Err(parameter(&format!("chain.{name}"), value, unit, expected));
    }
    if !(chain.sensor.iter().all(|v| v.is_finite()) && chain.sensor[1] > 0.0) {
        return Err(parameter(
            "chain.sensor",
            chain.sensor[1],
            "m",
            "a finite position with a positive half-spacing",
        ));
    }
    if let Some(sigma) = chain.yaw_rate.filter(|s| !(s.is_finite() && *s >= 0.0)) {
        return Err(parameter(
            "chain.yaw_rate",
            sigma,
            "rad/s",
            "the yaw-rate sensor's rms noise: finite, ≥ 0",
        ));
    }
    if !(chain.safety > 0.0 && chain.safety <= 1.0) {
        return Err(parameter(
            "chain.safety",
            chain.safety,
            "1",
            "must lie in (0, 1]",
        ));
    }
    Ok(())
}

/// The force channels of a test: (code, name, values at the fine step, place).
type Forces = Vec<(String, String, Vec<f64>, LoadSpec)>;

fn forces(
    car: &PlanarCar,
    striker: &Striker,
    r: &crate::PlanarResult,
) -> Result<Forces, PlanarError> {
    let normal = match place(car, striker)? {
        Placed::Plane { normal, .. } => normal,
        Placed::Pole { .. } | Placed::Barrier { .. } => [-1.0, 0.0],
    };
    let spec = |channel: &str, lateral, direction, anchor| LoadSpec {
        channel: channel.into(),
        lateral,
        direction,
        anchor,
    };
    let x_f = car.body().cg_behind_bumper;
    let (fx, fy): (Vec<f64>, Vec<f64>) =
        (r.force_x.iter().map(|f| -f).collect(), r.force_y.clone());
    // a pole's two-axis load cell: −F_x and F_y through the axis
    let pole = |object: char, radius: f64, lateral: f64| -> Forces {
        let anchor = Some([x_f + radius, lateral]);
        [
            ("X", fx.clone(), [-1.0, 0.0]),
            ("Y", fy.clone(), [0.0, 1.0]),
        ]
        .into_iter()
        .map(|(axis, values, direction)| {
            let code = match object {
                'B' => format!("B0POLE000000FO{axis}P"),
                _ => format!("P0IMPA000000FO{axis}P"),
            };
            let name = format!("Pole load cell {axis}");
            (
                code.clone(),
                name,
                values,
                spec(&code, lateral, direction, anchor),
            )
        })
        .collect()
    };
    Ok(match (striker.motion, striker.face) {
        (_, Face::Barrier(_)) => {
            return Err(PlanarError::Missing {
                name: "striker".into(),
                expected: "a plane or a pole: synthetic tests of the bumper barrier are not made (it carries no load cells)".into(),
            });
        }
        (Motion::Fixed { .. }, Face::Plane { .. }) => r
            .segment_force
            .iter()
            .zip(&r.segment_centres)
            .enumerate()
            .map(|(j, (force, &lateral))| {
                let code = format!("B0LOMA01{:02}00FOXP", j + 1);
                let name = format!("Load-cell wall row 1 column {} X", j + 1);
                (
                    code.clone(),
                    name,
                    force.clone(),
                    spec(&code, lateral, normal, None),
                )
            })
            .collect(),
        (Motion::Fixed { .. }, Face::Pole { radius, lateral }) => pole('B', radius, lateral),
        (Motion::Pendulum { .. }, Face::Pole { radius, lateral }) => pole('P', radius, lateral),
        (Motion::Pendulum { .. }, Face::Plane { overlap, side, .. }) => {
            let centre = car.beam().width
                * 0.5
                * (1.0 - overlap)
                * if side == Side::Left { 1.0 } else { -1.0 };
            let code = "P0IMPA000000FOXP";
            vec![(
                code.to_string(),
                "Pendulum load cell X".to_string(),
                r.force.clone(),
                spec(code, centre, normal, None),
            )]
        }
    })
}

/// Body-x acceleration of a sensor from the CG, yaw and chain histories at
/// interval `fine`: second differences of its world position, projected on
/// the body axis.
fn sensor_acceleration(
    car: &PlanarCar,
    r: &crate::PlanarResult,
    sensor: Sensor,
    fine: f64,
) -> Vec<f64> {
    let n = r.x.len();
    let b = 0.5 * car.beam().side_member_spacing;
    let left = car.left().masses.len();
    let point = |k: usize| match sensor {
        Sensor::Chain(i) | Sensor::Crush(i) => {
            let eta = if i < left { b } else { -b };
            [
                car.body().cg_behind_bumper + r.chain_displacement[i][k],
                eta,
            ]
        }
        Sensor::Body(p) | Sensor::Lateral(p) | Sensor::Film(p) => p,
        Sensor::YawRate => [0.0; 2],
    };
    let position = |k: usize| {
        let (sn, cs) = r.yaw[k].sin_cos();
        let [xi, eta] = point(k);
        [r.x[k] + xi * cs - eta * sn, r.y[k] + xi * sn + eta * cs]
    };
    (0..n)
        .map(|k| {
            if k == 0 || k + 1 >= n {
                return 0.0;
            }
            let (a, b, c) = (position(k - 1), position(k), position(k + 1));
            let (sn, cs) = r.yaw[k].sin_cos();
            let acc = [
                (a[0] - 2.0 * b[0] + c[0]) / (fine * fine),
                (a[1] - 2.0 * b[1] + c[1]) / (fine * fine),
            ];
            acc[0] * cs + acc[1] * sn
        })
        .collect()
}

/// Simulates `striker` on `car` and records the test `name` through `chain`;
/// `index` selects the noise stream (the test's position in the series).
pub fn record(
    car: &PlanarCar,
    name: &str,
    striker: &Striker,
    chain: &Chain,
    index: u64,
) -> Result<Recorded, PlanarError> {
    check(chain)?;
    let fine = chain.measurement.step / 10.0;
    let settings = Settings {
        safety: chain.safety,
        output_step: fine,
        duration: chain.measurement.duration,
        step: None,
        stop_after_contact: false,
        gap: 0.0,
        refine: 0,
    };
    let r = simulate(car, striker, &settings)?;
    let sensors = sensors(car, chain.sensor);
    let pre = (chain.measurement.pretrigger / fine).round() as usize;
    let length = pre + r.time.len();
    let padded = |h: &[f64]| -> Vec<f64> {
        std::iter::repeat_n(0.0, pre)
            .chain(h.iter().copied())
            .take(length)
            .collect()
    };
    let anti_alias = Butterworth::new(4, 0.25 / chain.measurement.step, fine)
        .map_err(|e| parameter("chain.step", chain.measurement.step, "s", &e.to_string()))?;
    let mut rng = ChaCha8Rng::seed_from_u64(
        chain
            .measurement
            .seed
            .wrapping_mul(1000)
            .wrapping_add(index),
    );
    let mut sample = |signal: Vec<f64>, sigma: f64, bias: f64| -> Vec<f64> {
        anti_alias
            .causal(&signal)
            .into_iter()
            .step_by(10)
            .map(|v| v + bias + sigma * gaussian(&mut rng))
            .collect()
    };
    let step = chain.measurement.step;
    // each channel says how faithful it is: its ISO/TS 18571 rating against
    // the noise-free signal at its samples
    let channel =
        |code: &str, name: &str, dimension, (truth, values): (Vec<f64>, Vec<f64>), unit: &str| {
            let comment = bumpsim_impact::synth::truth_comment(&truth, &values, step);
            UniformSeries::new(-(pre as f64) * fine, step, values)
                .map(|series| {
                    let mut c = Channel::new(code, name, dimension, series);
                    c.source_unit = unit.into();
                    c.set_meta("Comments", &comment);
                    c
                })
                .map_err(|e| parameter("chain.step", chain.measurement.step, "s", &e.to_string()))
        };
    let mut channels = Vec::new();
    let mut loads = Vec::new();
    for (code, title, force, spec) in forces(car, striker, &r)? {
        let truth = padded(&force).into_iter().step_by(10).collect();
        let values = sample(padded(&force), chain.measurement.force_noise, 0.0);
        let mut load = channel(&code, &title, Dimension::Force, (truth, values), "kN")?;
        if code.starts_with('P') {
            load.set_meta("Test object number", "2"); // the pendulum (see `test_header`)
        }
        channels.push(load);
        loads.push(spec);
    }
    for (k, (sensor, (code, title))) in sensors.iter().zip(SENSOR_CODES).enumerate() {
        let acceleration = padded(&sensor_acceleration(car, &r, *sensor, fine));
        let truth = acceleration.iter().step_by(10).copied().collect();
        let values = sample(
            acceleration,
            chain.measurement.acceleration_noise,
            chain.measurement.biases[k % 2],
        );
        channels.push(channel(
            code,
            title,
            Dimension::Acceleration,
            (truth, values),
            "g",
        )?);
    }
    let mut sensors = sensors;
    if let Some(sigma) = chain.yaw_rate {
        let rate = padded(&r.yaw_rate);
        let truth = rate.iter().step_by(10).copied().collect();
        let values = sample(rate, sigma, 0.0);
        let (code, title) = YAW_RATE_CODE;
        let data = (truth, values);
        channels.push(channel(
            code,
            title,
            Dimension::AngularVelocity,
            data,
            "deg/s",
        )?);
        sensors.push(Sensor::YawRate);
    }
    let (car_speed, striker_motion) = match striker.motion {
        Motion::Fixed { speed } => (speed, (speed, None)),
        Motion::Pendulum { mass, speed } => (0.0, (speed, Some(mass))),
    };
    Ok(Recorded {
        name: name.into(),
        channels,
        loads,
        sensors,
        car_speed,
        striker: striker_motion,
        car_mass: car.total_mass(),
    })
}
