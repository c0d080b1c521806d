//! Load cases: the one table of tests ([`bumpsim_io::protocols`]) as a
//! 1-D impact runs them (spec §5).
//!
//! A table entry becomes a 1-D scenario along the car's centre line: a
//! moving striker of mass `m` (a pendulum of the vehicle's own mass for
//! 49 CFR 581 and UN R42) hits the car at rest at the test's speed, or the
//! car runs into a rigid wall. What a line cannot carry — the face's angle,
//! the overlap, a head's width, a pole, the RCAR barrier's curvature and
//! absorber — is dropped, and [`Preset::dropped_in_1d`] says what; the
//! planar model (`bumpsim planar`) runs the whole test.

use crate::impact::{ImpactError, Scenario};
use bumpsim_io::protocols::Motion;

/// A named load case: an entry of the one table of tests.
pub type Preset = bumpsim_io::protocols::Test;

/// All load cases: the table's tests.
pub const PRESETS: &[Preset] = bumpsim_io::protocols::TESTS;

/// The preset of this name (an old name is refused naming the new one).
pub fn find(name: &str) -> Result<&'static Preset, bumpsim_io::protocols::ProtocolError> {
    bumpsim_io::protocols::find(name)
}

/// The 1-D scenario of a table entry for a car of total mass `car_mass` kg,
/// at `speed` m/s (default: the test's speed), along the centre line.
///
/// ```
/// let t = bumpsim_impact::presets::find("part581-pendulum-front").unwrap();
/// let s = bumpsim_impact::presets::scenario_of(t, 1300.0, None);
/// assert!(matches!(s, bumpsim_impact::Scenario::Impactor { mass, .. } if mass == 1300.0));
/// ```
pub fn scenario_of(preset: &Preset, car_mass: f64, speed: Option<f64>) -> Scenario {
    let speed = speed.unwrap_or(preset.speed);
    match preset.motion {
        Motion::Moving { mass } => Scenario::Impactor { mass, speed },
        Motion::VehicleMass => Scenario::Impactor {
            mass: car_mass,
            speed,
        },
        Motion::Fixed => Scenario::Barrier { speed },
    }
}

/// An impact as a command line or a script names it: a preset, or a
/// pendulum (kg) or a rigid barrier, at a speed (m/s; default the preset's).
/// Every front end builds its scenario here.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ScenarioSpec {
    /// A preset name ([`PRESETS`]).
    pub case: Option<String>,
    /// A pendulum of this mass, kg, hits the car at rest.
    pub pendulum: Option<f64>,
    /// The car hits a rigid barrier.
    pub barrier: bool,
    /// Speed, m/s.
    pub speed: Option<f64>,
}

impl ScenarioSpec {
    /// The scenario for a car of total mass `car_mass` kg, and the preset it came from.
    ///
    /// ```
    /// use bumpsim_impact::presets::ScenarioSpec;
    /// let spec = ScenarioSpec { pendulum: Some(1450.0), speed: Some(1.67), ..Default::default() };
    /// assert!(spec.scenario(1300.0).is_ok());
    /// assert!(ScenarioSpec { speed: Some(1.0), ..Default::default() }.scenario(1300.0).is_err());
    /// ```
    pub fn scenario(
        &self,
        car_mass: f64,
    ) -> Result<(Scenario, Option<&'static Preset>), ImpactError> {
        if let Some(name) = &self.case {
            let preset =
                find(name).map_err(|e| ImpactError::LoadCase(format!("case '{name}': {e}")))?;
            let scenario = scenario_of(preset, car_mass, self.speed);
            scenario.check()?;
            return Ok((scenario, Some(preset)));
        }
        let speed = self.speed.ok_or_else(|| {
            ImpactError::LoadCase("the speed is needed without a preset case".into())
        })?;
        let scenario = match (self.pendulum, self.barrier) {
            (Some(mass), false) => Scenario::Impactor { mass, speed },
            (None, true) => Scenario::Barrier { speed },
            _ => {
                return Err(ImpactError::LoadCase(
                    "say what hits: a preset case, a pendulum mass (kg) or the barrier".into(),
                ));
            }
        };
        scenario.check()?;
        Ok((scenario, None))
    }
}
