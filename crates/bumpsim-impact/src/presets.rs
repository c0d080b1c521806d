//! Load-case presets with their sources (spec §5).
//!
//! The thesis's pendulum tests and paper C's impactor give masses and
//! speeds measured in the work itself. The regulation and consumer tests
//! are listed by the thesis (ch. 2.1) as the tests below 16 km/h; their
//! speeds here are those of the standards' longitudinal tests (FMVSS 581 and
//! ECE R42: 4 km/h, a pendulum of the vehicle's own mass; CMVSS 215: 8 km/h
//! barrier, the 5 mph requirement of the thesis's time) and of the thesis
//! (IIHS 8 km/h flat barrier; Allianz/RCAR 16 km/h). A full-width rigid
//! barrier stands in for the angled, pole and 40 % offset barriers, which a
//! 1-D model cannot represent: read those presets as speed and energy only.

use crate::impact::{ImpactError, Scenario};

/// What the preset hits the car with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Striker {
    /// A pendulum or impactor of this mass, kg.
    Pendulum(f64),
    /// A pendulum of the vehicle's own mass (FMVSS 581, ECE R42).
    PendulumOfVehicleMass,
    /// The car hits a rigid barrier.
    Barrier,
}

/// A named load case.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Preset {
    /// Name for `--case`.
    pub name: &'static str,
    /// What it is.
    pub description: &'static str,
    /// Striker.
    pub striker: Striker,
    /// Speed, km/h.
    pub speed_kmh: f64,
    /// Where the figures come from.
    pub source: &'static str,
}

/// All presets.
pub const PRESETS: &[Preset] = &[
    Preset {
        name: "thesis-flat",
        description: "1450 kg pendulum, flat head overlapping the front",
        striker: Striker::Pendulum(1450.0),
        speed_kmh: 6.0,
        source: "thesis ch. 3.1, paper B (measured)",
    },
    Preset {
        name: "thesis-600",
        description: "1450 kg pendulum, 610 mm wide head",
        striker: Striker::Pendulum(1450.0),
        speed_kmh: 6.0,
        source: "thesis ch. 3.1, paper B (measured)",
    },
    Preset {
        name: "thesis-pole",
        description: "1450 kg pendulum, 305 mm pole",
        striker: Striker::Pendulum(1450.0),
        speed_kmh: 5.0,
        source: "thesis ch. 3.1, paper B (measured)",
    },
    Preset {
        name: "paper-c-impactor",
        description: "1475 kg impactor at 1.67 m/s",
        striker: Striker::Pendulum(1475.0),
        speed_kmh: 1.67 * 3.6,
        source: "paper C",
    },
    Preset {
        name: "paper-a-utv",
        description: "car or rigid UTV into a rigid flat barrier",
        striker: Striker::Barrier,
        speed_kmh: 8.0,
        source: "paper A",
    },
    Preset {
        name: "fmvss-581",
        description: "longitudinal pendulum of the vehicle's mass",
        striker: Striker::PendulumOfVehicleMass,
        speed_kmh: 4.0,
        source: "49 CFR 581 (2.5 mph); listed by thesis ch. 2.1",
    },
    Preset {
        name: "ece-r42",
        description: "longitudinal pendulum of the vehicle's mass",
        striker: Striker::PendulumOfVehicleMass,
        speed_kmh: 4.0,
        source: "ECE R42; listed by thesis ch. 2.1",
    },
    Preset {
        name: "cmvss-215",
        description: "rigid flat barrier",
        striker: Striker::Barrier,
        speed_kmh: 8.0,
        source: "CMVSS 215 (5 mph barrier); listed by thesis ch. 2.1",
    },
    Preset {
        name: "iihs-flat",
        description: "flat barrier front or rear",
        striker: Striker::Barrier,
        speed_kmh: 8.0,
        source: "thesis ch. 2.1 / spec §5 (IIHS)",
    },
    Preset {
        name: "rcar-16",
        description: "40 % offset barrier, as a full-width rigid barrier (energy only)",
        striker: Striker::Barrier,
        speed_kmh: 16.0,
        source: "thesis ch. 2.1 / spec §5 (Allianz/RCAR)",
    },
];

/// The preset of this name.
pub fn find(name: &str) -> Option<&'static Preset> {
    PRESETS.iter().find(|p| p.name.eq_ignore_ascii_case(name))
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
            let preset = find(name).ok_or_else(|| {
                let names: Vec<&str> = PRESETS.iter().map(|p| p.name).collect();
                ImpactError::LoadCase(format!(
                    "case '{name}': known presets: {}",
                    names.join(", ")
                ))
            })?;
            let scenario = preset.scenario(car_mass, self.speed);
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

impl Preset {
    /// The scenario for a car of total mass `car_mass` kg, at `speed` m/s
    /// (default: the preset's speed).
    pub fn scenario(&self, car_mass: f64, speed: Option<f64>) -> Scenario {
        let speed = speed.unwrap_or(self.speed_kmh / 3.6);
        match self.striker {
            Striker::Pendulum(mass) => Scenario::Impactor { mass, speed },
            Striker::PendulumOfVehicleMass => Scenario::Impactor {
                mass: car_mass,
                speed,
            },
            Striker::Barrier => Scenario::Barrier { speed },
        }
    }
}
