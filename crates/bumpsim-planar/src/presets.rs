//! Load cases: the one table of tests ([`bumpsim_io::protocols`]) as the
//! planar model runs them (spec §9, thesis ch. 2.1).
//!
//! The model's x axis points towards the struck bumper, so a rear test is
//! described with the car's rear as its "front": give the planar car of the
//! rear structure and read left/right as seen from behind the car. Each
//! table entry becomes a striker whole: a plane at its angle and overlap,
//! a head of finite width (a flat barrier of that width centred on the
//! car), a pole, or the RCAR bumper barrier with its curved face and
//! absorber ([`crate::barrier`]); carried by a guided pendulum of its mass,
//! or fixed with the car running into it.
//!
//! A pendulum of the vehicle's own mass `m` (49 CFR 581, UN R42) swings
//! along its face's normal; the planar pendulum is guided along the car's
//! axis. For a frictionless face covering the car the two are the same
//! impact when the guided one has mass `m cos²θ` and speed `v / cos θ`
//! (its push along the normal, its normal speed and its energy are then the
//! real pendulum's), which [`striker_of`] builds.
//!
//! Every test of the table runs free-rolling cars (gear in neutral, brakes
//! released): their wheels build lateral force through the slip angle
//! ([`TyreLaw::Rolling`]); a locked-wheel variant is the user's choice
//! (`bumpsim planar --tyres sliding`).

use crate::car::{PlanarError, TyreLaw};
use crate::striker::{Barrier, Face, Side, Striker};
use bumpsim_io::protocols::{self, Motion};

/// A named planar load case: an entry of the one table of tests.
pub type PlanarPreset = protocols::Test;

pub use bumpsim_io::protocols::MPH;

/// Every planar load case: the table's tests.
pub const PRESETS: &[PlanarPreset] = protocols::TESTS;

/// The tyre law every table test prescribes (free rolling).
pub fn tyres(_preset: &PlanarPreset) -> TyreLaw {
    TyreLaw::Rolling
}

/// The preset of this name (an old name is refused naming the new one).
pub fn find(name: &str) -> Result<&'static PlanarPreset, protocols::ProtocolError> {
    protocols::find(name)
}

fn side(side: protocols::Side) -> Side {
    match side {
        protocols::Side::Left => Side::Left,
        protocols::Side::Right => Side::Right,
    }
}

/// A flat face of finite width: a barrier whose plan radius is so large
/// that its sagitta over a 1 m chord is 0.1 µm (1000 km).
const FLAT_RADIUS: f64 = 1e6;

/// The face of a table entry.
pub fn face_of(preset: &PlanarPreset) -> Face {
    match preset.face {
        protocols::Face::Plane {
            angle,
            overlap,
            side: s,
        } => Face::Plane {
            angle: angle.to_radians(),
            overlap,
            side: side(s),
        },
        protocols::Face::Head { width } => Face::Barrier(Barrier {
            angle: 0.0,
            overlap: 1.0,
            side: Side::Left,
            radius: FLAT_RADIUS,
            width,
            absorber: None,
        }),
        protocols::Face::Pole { diameter, lateral } => Face::pole_of_diameter(diameter, lateral),
        protocols::Face::RcarBarrier {
            angle,
            overlap,
            side: s,
        } => Face::Barrier(Barrier::rcar(angle.to_radians(), overlap, side(s))),
    }
}

/// The face's angle, rad (0 for a pole or head).
pub fn angle_of(preset: &PlanarPreset) -> f64 {
    match preset.face {
        protocols::Face::Plane { angle, .. } | protocols::Face::RcarBarrier { angle, .. } => {
            angle.to_radians()
        }
        _ => 0.0,
    }
}

/// The planar striker of a table entry for a car of total mass `car_mass`
/// kg (a pendulum of the vehicle's mass as its guided equivalent, see the
/// module overview), at its own speed.
///
/// ```
/// let t = bumpsim_planar::presets::find("part581-corner-front-left").unwrap();
/// let s = bumpsim_planar::presets::striker_of(t, 1500.0);
/// let cos = 30f64.to_radians().cos();
/// assert!((s.motion.speed() - t.speed / cos).abs() < 1e-12);
/// ```
pub fn striker_of(preset: &PlanarPreset, car_mass: f64) -> Striker {
    let face = face_of(preset);
    match preset.motion {
        Motion::Fixed => Striker::barrier(face, preset.speed),
        Motion::Moving { mass } => Striker::pendulum(face, mass, preset.speed),
        Motion::VehicleMass => {
            let cos = angle_of(preset).cos();
            Striker::pendulum(face, car_mass * cos * cos, preset.speed / cos)
        }
    }
}

/// The nominal striker of a table entry: face, motion and speed as the
/// protocol states them (a pendulum of the vehicle's mass `car_mass`
/// swinging along its normal, not its guided equivalent).
pub fn nominal_of(preset: &PlanarPreset, car_mass: f64) -> Striker {
    match preset.motion {
        Motion::VehicleMass => Striker::pendulum(face_of(preset), car_mass, preset.speed),
        _ => striker_of(preset, car_mass),
    }
}

/// A striker's fields as an input file writes them (a series' `[[test]]`,
/// a study case's `striker = { ... }`): a preset or a face, a pendulum, a
/// speed in m/s or as text with a unit, a side as `left` or `right`.
#[derive(Debug, Clone, Default, PartialEq, serde::Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct StrikerFields {
    /// A preset name.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub case: Option<String>,
    /// Plane angle, degrees.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub angle: Option<f64>,
    /// Overlap, percent.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub overlap: Option<f64>,
    /// `left` or `right`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub side: Option<String>,
    /// Pole diameter, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pole: Option<f64>,
    /// Pole axis's lateral position, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pole_offset: Option<f64>,
    /// Pendulum mass, kg.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pendulum: Option<f64>,
    /// Speed: m/s, or text with a unit.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub speed: Option<toml::Value>,
}

impl StrikerFields {
    /// The fields as a TOML inline table (`{ angle = 10.0, speed = "8 km/h" }`).
    pub fn inline(&self) -> String {
        toml::Value::try_from(self).map_or_else(|_| "{}".into(), |v| v.to_string())
    }
}

/// Why a striker's fields are not a striker.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum StrikerFieldError {
    /// The speed.
    #[error(transparent)]
    Speed(#[from] bumpsim_io::speed::SpeedError),
    /// The side.
    #[error(transparent)]
    Side(#[from] crate::striker::SideError),
}

impl StrikerFields {
    /// The striker specification of these fields.
    ///
    /// ```
    /// use bumpsim_planar::presets::StrikerFields;
    /// let fields: StrikerFields = toml::from_str("overlap = 40.0\nside = \"left\"\nspeed = \"15 km/h\"").unwrap();
    /// let (striker, _) = fields.spec().unwrap().striker().unwrap();
    /// assert!((striker.motion.speed() - 15.0 / 3.6).abs() < 1e-12);
    /// ```
    pub fn spec(&self) -> Result<StrikerSpec, StrikerFieldError> {
        let speed = self
            .speed
            .as_ref()
            .map(bumpsim_io::speed::speed_value)
            .transpose()?;
        let side = self.side.as_deref().map(str::parse).transpose()?;
        Ok(StrikerSpec {
            case: self.case.clone(),
            angle: self.angle,
            overlap: self.overlap,
            side,
            pole: self.pole,
            pole_offset: self.pole_offset,
            pendulum: self.pendulum,
            speed,
            car_mass: None,
        })
    }
}

/// A striker as a test protocol, a command line or a script names it: a
/// preset (which needs the car's mass when its pendulum is the vehicle's), or a plane (degrees, percent, side) or a pole (diameter and
/// lateral position, m), carried by a pendulum (kg) or fixed, at a speed
/// (m/s). Every front end builds its striker here.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct StrikerSpec {
    /// A preset name ([`PRESETS`]): face, motion and speed.
    pub case: Option<String>,
    /// Plane angle, degrees, counter-clockwise seen from above (default 0).
    pub angle: Option<f64>,
    /// Overlap, percent of the bumper width (default 100).
    pub overlap: Option<f64>,
    /// Side the overlap is measured from (default left).
    pub side: Option<Side>,
    /// Pole diameter, m: a pole instead of a plane.
    pub pole: Option<f64>,
    /// Lateral position of the pole's axis, m, left positive (default 0).
    pub pole_offset: Option<f64>,
    /// Pendulum mass, kg (default: the car drives into the fixed face).
    pub pendulum: Option<f64>,
    /// Speed, m/s (default: the preset's; needed without a preset).
    pub speed: Option<f64>,
    /// The car's total mass, kg: a preset's pendulum of the vehicle's mass
    /// (49 CFR 581, UN R42) needs it.
    pub car_mass: Option<f64>,
}

/// The car a run uses: with a preset, both axles' tyres under the law the
/// test prescribes ([`tyres`]) and a laden test's load on
/// its body ([`crate::car::PlanarCar::with_load`]; the striker keeps the
/// unladen mass); otherwise the car as its file says. Every front end runs presets on this car.
///
/// ```
/// use bumpsim_core::model::MsdModel;
/// use bumpsim_impact::Bumper;
/// use bumpsim_planar::car::{Layout, PlanarCar, TyreLaw};
/// use bumpsim_planar::presets::{StrikerSpec, prepared};
/// let chain = MsdModel::new(vec![20.0, 1300.0], vec![2e3], vec![3e6]).unwrap();
/// let bumper = Bumper::three_part(1e6, 5e4, 2e6).unwrap();
/// let car = PlanarCar::symmetric(&chain, &bumper, &Layout::default()).unwrap();
/// let sliding = car.clone().with_tyre_law(TyreLaw::Sliding);
/// let rcar = StrikerSpec { case: Some("rcar-structural-front".into()), ..Default::default() };
/// let (_, preset) = rcar.striker().unwrap();
/// assert_eq!(prepared(&sliding, preset), car.clone().with_tyre_law(TyreLaw::Rolling));
/// assert_eq!(prepared(&sliding, None), sliding);
/// ```
pub fn prepared(
    car: &crate::car::PlanarCar,
    preset: Option<&PlanarPreset>,
) -> crate::car::PlanarCar {
    match preset {
        // the table's loads are constants, finite and ≥ 0 (bumpsim-io's tests)
        Some(p) => match car.clone().with_tyre_law(tyres(p)).with_load(p.load) {
            Ok(laden) => laden,
            Err(_) => car.clone().with_tyre_law(tyres(p)),
        },
        None => car.clone(),
    }
}

impl StrikerSpec {
    /// The striker, and the preset it came from.
    ///
    /// ```
    /// use bumpsim_planar::presets::StrikerSpec;
    /// let rcar = StrikerSpec { case: Some("rcar-structural-front".into()), ..Default::default() };
    /// let (striker, preset) = rcar.striker().unwrap();
    /// assert!(preset.is_some());
    /// let pole = StrikerSpec { pole: Some(0.178), speed: Some(2.2), ..Default::default() };
    /// assert!(pole.striker().unwrap().1.is_none());
    /// assert!(StrikerSpec::default().striker().is_err()); // no preset, no speed
    /// ```
    pub fn striker(&self) -> Result<(Striker, Option<&'static PlanarPreset>), PlanarError> {
        if let Some(name) = &self.case {
            let preset = find(name).map_err(|e| PlanarError::Missing {
                name: format!("case '{name}'"),
                expected: e.to_string(),
            })?;
            let car_mass = match (preset.motion, self.car_mass) {
                (Motion::VehicleMass, None) => {
                    return Err(PlanarError::Missing {
                        name: format!("case '{name}'"),
                        expected: "the car's mass: its pendulum has the vehicle's mass".into(),
                    });
                }
                (_, mass) => mass.unwrap_or(1.0),
            };
            let striker = striker_of(preset, car_mass);
            let striker = self.speed.map_or(striker, |v| striker.with_speed(v));
            return Ok((striker, Some(preset)));
        }
        let speed = self.speed.ok_or_else(|| PlanarError::Missing {
            name: "speed".into(),
            expected: "the impact speed is needed without a preset".into(),
        })?;
        let face = match self.pole {
            Some(diameter) => Face::pole_of_diameter(diameter, self.pole_offset.unwrap_or(0.0)),
            None => Face::plane_in_degrees(
                self.angle.unwrap_or(0.0),
                self.overlap.unwrap_or(100.0),
                self.side.unwrap_or(Side::Left),
            ),
        };
        let striker = match self.pendulum {
            Some(mass) => Striker::pendulum(face, mass, speed),
            None => Striker::barrier(face, speed),
        };
        Ok((striker, None))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::car::{Layout, PlanarCar};
    use crate::simulate::{Settings, simulate};
    use bumpsim_core::model::MsdModel;
    use bumpsim_impact::bumper::Bumper;

    /// Every test of the table runs on a saloon, balances its energy and
    /// takes force; the RCAR barrier's absorber shares the crush.
    #[test]
    fn every_table_test_runs_on_a_saloon_and_balances() {
        let chain = MsdModel::new(vec![10.0, 1300.0], vec![2e3], vec![1.5e6]).unwrap();
        let bumper = Bumper::three_part(1.5e6, 60e3, 6e6).unwrap();
        let car = PlanarCar::symmetric(&chain, &bumper, &Layout::default()).unwrap();
        for preset in PRESETS {
            let striker = striker_of(preset, car.total_mass());
            let r = simulate(&car, &striker, &Settings::default()).unwrap();
            let name = preset.name;
            assert!(r.energy.max_relative_error < 1e-3, "{name}: {:?}", r.energy);
            assert!(r.peak_force > 1e3, "{name}");
            if matches!(preset.face, protocols::Face::RcarBarrier { .. }) {
                let recorded = r.crush.iter().flatten().copied().fold(0.0, f64::max);
                assert!((recorded - r.max_compression).abs() < 1e-6, "{name}");
            }
            if name.ends_with("bumper-front") {
                assert!(r.yaw.iter().all(|y| y.abs() < 1e-9), "{name}");
                // the 60 kN bumper meets the 35 kN/m absorber: the absorber crushes too
                assert!(r.energy.crush > 1.05 * bumper_work(&bumper, &r), "{name}");
            }
        }
        assert!(find("iihs-pole-rear").is_ok() && find("nope").is_err());
    }

    /// The 610 mm head meets only the middle of a wider bumper: the outer
    /// segments stay uncrushed; a full-width flat face crushes them all.
    #[test]
    fn the_head_meets_only_the_middle_of_the_bumper() {
        let chain = MsdModel::new(vec![10.0, 1300.0], vec![2e3], vec![1.5e6]).unwrap();
        let bumper = Bumper::three_part(1.5e6, 60e3, 6e6).unwrap();
        let car = PlanarCar::symmetric(&chain, &bumper, &Layout::default()).unwrap();
        let crush = |name: &str| {
            let t = find(name).unwrap();
            let r = simulate(&car, &striker_of(t, car.total_mass()), &Settings::default()).unwrap();
            r.max_crush.clone()
        };
        let (head, flat) = (crush("thesis-600"), crush("thesis-flat"));
        assert!(head[0] < 1e-6 && head[head.len() - 1] < 1e-6, "{head:?}");
        assert!(flat.iter().all(|&d| d > 1e-4), "{flat:?}");
    }

    /// The work the bumper segments took at their largest crush, J.
    fn bumper_work(bumper: &Bumper, r: &crate::PlanarResult) -> f64 {
        let n = r.max_crush.len() as f64;
        r.max_crush
            .iter()
            .map(|&d| bumper.loading_energy(d) / n)
            .sum()
    }
}
