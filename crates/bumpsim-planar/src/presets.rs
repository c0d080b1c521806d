//! Asymmetric low-speed load cases with their sources (spec §9, thesis ch. 2.1).
//!
//! The model's x axis points towards the struck bumper, so a rear test is
//! described with the car's rear as its "front": give the planar car of the
//! rear structure (CG distance behind the rear bumper line, the rear chains)
//! and read left/right as seen from behind the car. Figures, as best
//! established from the public protocols (uncertainties stated per preset):
//!
//! - **RCAR structural test** — RCAR *Low-speed structural crash test
//!   protocol*, Issue 2.2 (July 2011): front, the car at 15 km/h (+1/−0) into a
//!   rigid barrier with a 10° face at 40 % overlap (the driver's side); rear, a
//!   1400 kg mobile barrier at 15 km/h, 40 % overlap, 10°. The thesis (and the
//!   older Allianz AZT test it descends from) gives 16 km/h; the protocol
//!   issue used here gives 15 km/h.
//! - **IIHS front-into-angle-barrier and rear-into-pole** — IIHS *Low-speed
//!   crash test protocol* of the 1990s–2006 (superseded in 2006 by the
//!   IIHS/RCAR bumper test): four 5 mph (8 km/h) tests — front and rear into a
//!   flat barrier, front into an angle barrier, rear into a pole. Angle 30° and
//!   a 7 in (178 mm) diameter pole centred on the rear are as reported in IIHS
//!   status reports of the period; the original protocol document was not
//!   available here, so read the angle and the pole diameter as uncertain.
//! - **IIHS corner tests** — IIHS/RCAR *Bumper test protocol* (IIHS Version I,
//!   2006; RCAR Bumper Test Issue 2.0, 2010): front and rear corner impacts at
//!   3 mph (4.8 km/h; RCAR: 5 km/h) into the bumper barrier at 15 % overlap,
//!   the barrier face angled 10°. The bumper barrier (RCAR *Dimensions and
//!   specifications of the RCAR bumper barrier system*, Issue 1, September
//!   2007) is a rigid steel beam 1500 mm wide whose face is curved with a
//!   3400 mm radius, used with an energy absorber in front; here it is a flat
//!   rigid plane (curvature and absorber neglected: put the absorber's
//!   characteristic in series with the bumper's if it matters). The 10° angle
//!   is from memory of the protocol figure, not checked against the document.
//!
//! Each preset states the tyres' condition (`tyres`, `tyres_why`): all of
//! these run free-rolling cars (gear in neutral, brakes released), so their
//! wheels build lateral force through the slip angle ([`TyreLaw::Rolling`]);
//! a locked-wheel variant is the user's choice (`bumpsim planar --tyres sliding`).

use crate::car::{PlanarError, TyreLaw};
use crate::striker::{Barrier, Face, Motion, Side, Striker};

/// A named planar load case.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanarPreset {
    /// Name.
    pub name: &'static str,
    /// What it is.
    pub description: &'static str,
    /// Face and motion (SI: rad, m, kg, m/s).
    pub striker: Striker,
    /// The public document the figures come from.
    pub source: &'static str,
    /// What could not be confirmed.
    pub uncertain: &'static str,
    /// The tyres' condition the test prescribes (applied to the car's axles
    /// unless the user says otherwise, [`crate::car::TyreLaw`]).
    pub tyres: TyreLaw,
    /// Why: the protocol's words on brakes and gear.
    pub tyres_why: &'static str,
}

const KMH: f64 = 1.0 / 3.6;
/// One mile per hour in km/h (exact: 1 mi = 1609.344 m).
pub const MPH: f64 = 1.609344;
const DEG10: f64 = 10.0 * std::f64::consts::PI / 180.0;
const DEG30: f64 = 30.0 * std::f64::consts::PI / 180.0;

const fn plane(angle: f64, overlap: f64, side: Side) -> Face {
    Face::Plane {
        angle,
        overlap,
        side,
    }
}

const fn fixed(face: Face, kmh: f64) -> Striker {
    Striker {
        face,
        motion: Motion::Fixed { speed: kmh * KMH },
    }
}

/// All planar presets.
pub const PRESETS: &[PlanarPreset] = &[
    PlanarPreset {
        name: "rcar-structural-front",
        description: "front, 15 km/h into a rigid 10° barrier at 40 % overlap, left (driver's) side",
        striker: fixed(plane(DEG10, 0.4, Side::Left), 15.0),
        source: "RCAR Low-speed structural crash test protocol, Issue 2.2 (2011)",
        uncertain: "speed: the thesis and the older Allianz AZT test give 16 km/h",
        tyres: TyreLaw::Rolling,
        tyres_why: "free rolling: the car runs into the barrier under its own momentum, gear in neutral and brakes released, as the protocol's set-up is read here",
    },
    PlanarPreset {
        name: "rcar-structural-rear",
        description: "rear, a 1400 kg mobile barrier at 15 km/h with a 10° face at 40 % overlap",
        striker: Striker {
            face: plane(DEG10, 0.4, Side::Left),
            motion: Motion::Pendulum {
                mass: 1400.0,
                speed: 15.0 * KMH,
            },
        },
        source: "RCAR Low-speed structural crash test protocol, Issue 2.2 (2011)",
        uncertain: "the side struck depends on the market (driver's side); the mobile barrier is guided here",
        tyres: TyreLaw::Rolling,
        tyres_why: "free rolling: the struck car stands in neutral with its brakes released, as the protocol's set-up is read here",
    },
    PlanarPreset {
        name: "iihs-angle-front",
        description: "front, 8 km/h (5 mph) into a rigid barrier angled 30°, full width",
        striker: fixed(plane(DEG30, 1.0, Side::Left), 8.0),
        source: "IIHS low-speed crash test protocol (1990s to 2006), front-into-angle-barrier test",
        uncertain: "angle (30°) and the side taken from IIHS status reports, not the protocol",
        tyres: TyreLaw::Rolling,
        tyres_why: "free rolling: the car runs into the barrier under its own momentum, gear in neutral and brakes released, as the protocol's set-up is read here",
    },
    PlanarPreset {
        name: "iihs-pole-rear",
        description: "rear, 8 km/h (5 mph) into a rigid 178 mm (7 in) pole centred on the car",
        striker: fixed(
            Face::Pole {
                radius: 0.0889,
                lateral: 0.0,
            },
            8.0,
        ),
        source: "IIHS low-speed crash test protocol (1990s to 2006), rear-into-pole test",
        uncertain: "pole diameter (7 in) from IIHS status reports, not the protocol",
        tyres: TyreLaw::Rolling,
        tyres_why: "free rolling: the car runs into the barrier under its own momentum, gear in neutral and brakes released, as the protocol's set-up is read here",
    },
    PlanarPreset {
        name: "iihs-corner-front",
        description: "front corner, 4.8 km/h (3 mph) into the bumper barrier, 15 % overlap, 10°",
        striker: fixed(plane(DEG10, 0.15, Side::Left), 4.8),
        source: "IIHS/RCAR Bumper test protocol (IIHS Version I 2006; RCAR Issue 2.0 2010)",
        uncertain: "the 10° face angle; RCAR runs the corner tests at 5 km/h; the barrier's 3.4 m face radius and energy absorber are neglected",
        tyres: TyreLaw::Rolling,
        tyres_why: "free rolling: the car runs into the barrier under its own momentum, gear in neutral and brakes released, as the protocol's set-up is read here",
    },
    PlanarPreset {
        name: "iihs-corner-rear",
        description: "rear corner, 4.8 km/h (3 mph) into the bumper barrier, 15 % overlap, 10°",
        striker: fixed(plane(-DEG10, 0.15, Side::Right), 4.8),
        source: "IIHS/RCAR Bumper test protocol (IIHS Version I 2006; RCAR Issue 2.0 2010)",
        uncertain: "the 10° face angle; RCAR runs the corner tests at 5 km/h; the barrier's 3.4 m face radius and energy absorber are neglected",
        tyres: TyreLaw::Rolling,
        tyres_why: "free rolling: the car runs into the barrier under its own momentum, gear in neutral and brakes released, as the protocol's set-up is read here",
    },
];

const FREE_ROLLING: &str = "free rolling: the car runs into the barrier under its own momentum, gear in neutral and brakes released, as the protocol's set-up is read here";

const fn bumper_barrier(angle: f64, overlap: f64, side: Side, kmh: f64) -> Striker {
    fixed(Face::Barrier(Barrier::rcar(angle, overlap, side)), kmh)
}

/// What the RCAR bumper barrier presets could not confirm.
const BARRIER_UNCERTAIN: &str = "the absorber's crush strength (0.35 MPa over the 100 mm face, solid at 40 mm) is assumed: the specification's corridor was not available here; the absorber's 0.25-0.5 friction is not modelled (frictionless face)";

/// The presets of issue 36: the RCAR bumper barrier with its curved face
/// and absorber (RCAR Bumper Test Issue 2.0, 2010; barrier specification
/// Issue 1, 2007), the IIHS bumper tests that use it, and the flat-barrier
/// tests of 49 CFR 581 and the older IIHS series. The pendulums of the
/// vehicle's own mass (49 CFR 581, UN R42) depend on the car and live in
/// bumpsim-verdict's protocol library.
pub const BARRIER_PRESETS: &[PlanarPreset] = &[
    PlanarPreset {
        name: "rcar-bumper-front",
        description: "front, 10 km/h full width into the RCAR bumper barrier (R 3400 mm, 1500 mm wide, 50 mm absorber), centred",
        striker: bumper_barrier(0.0, 1.0, Side::Left, 10.0),
        source: "RCAR Bumper Test, Issue 2.0 (September 2010) §6; RCAR bumper barrier specification, Issue 1 (September 2007) §2-3",
        uncertain: BARRIER_UNCERTAIN,
        tyres: TyreLaw::Rolling,
        tyres_why: FREE_ROLLING,
    },
    PlanarPreset {
        name: "rcar-bumper-rear",
        description: "rear, 10 km/h full width into the RCAR bumper barrier, centred",
        striker: bumper_barrier(0.0, 1.0, Side::Left, 10.0),
        source: "RCAR Bumper Test, Issue 2.0 (September 2010) §6; RCAR bumper barrier specification, Issue 1 (September 2007) §2-3",
        uncertain: BARRIER_UNCERTAIN,
        tyres: TyreLaw::Rolling,
        tyres_why: FREE_ROLLING,
    },
    PlanarPreset {
        name: "rcar-bumper-corner-front",
        description: "front corner, 5 km/h into the RCAR bumper barrier at 15 % overlap, 10°, left",
        striker: bumper_barrier(DEG10, 0.15, Side::Left, 5.0),
        source: "RCAR Bumper Test, Issue 2.0 (September 2010) §6",
        uncertain: "the 10° angle and the side struck are from memory of the protocol's figure; the absorber as for the full-width test",
        tyres: TyreLaw::Rolling,
        tyres_why: FREE_ROLLING,
    },
    PlanarPreset {
        name: "rcar-bumper-corner-rear",
        description: "rear corner, 5 km/h into the RCAR bumper barrier at 15 % overlap, 10°, right",
        striker: bumper_barrier(-DEG10, 0.15, Side::Right, 5.0),
        source: "RCAR Bumper Test, Issue 2.0 (September 2010) §6",
        uncertain: "the 10° angle and the side struck are from memory of the protocol's figure; the absorber as for the full-width test",
        tyres: TyreLaw::Rolling,
        tyres_why: FREE_ROLLING,
    },
    PlanarPreset {
        name: "iihs-bumper-front",
        description: "front, 6 mph (9.66 km/h) full width into the bumper barrier, centred",
        striker: bumper_barrier(0.0, 1.0, Side::Left, 6.0 * MPH),
        source: "IIHS Bumper test protocol, Version I (2006), full-width test (the RCAR barrier)",
        uncertain: BARRIER_UNCERTAIN,
        tyres: TyreLaw::Rolling,
        tyres_why: FREE_ROLLING,
    },
    PlanarPreset {
        name: "iihs-bumper-rear",
        description: "rear, 6 mph (9.66 km/h) full width into the bumper barrier, centred",
        striker: bumper_barrier(0.0, 1.0, Side::Left, 6.0 * MPH),
        source: "IIHS Bumper test protocol, Version I (2006), full-width test (the RCAR barrier)",
        uncertain: BARRIER_UNCERTAIN,
        tyres: TyreLaw::Rolling,
        tyres_why: FREE_ROLLING,
    },
    PlanarPreset {
        name: "iihs-bumper-corner-front",
        description: "front corner, 3 mph (4.83 km/h) into the bumper barrier at 15 % overlap, 10°, left",
        striker: bumper_barrier(DEG10, 0.15, Side::Left, 3.0 * MPH),
        source: "IIHS Bumper test protocol, Version I (2006), corner test (the RCAR barrier)",
        uncertain: "the 10° angle and the side struck are from memory of the protocol's figure; the absorber as for the full-width test",
        tyres: TyreLaw::Rolling,
        tyres_why: FREE_ROLLING,
    },
    PlanarPreset {
        name: "iihs-bumper-corner-rear",
        description: "rear corner, 3 mph (4.83 km/h) into the bumper barrier at 15 % overlap, 10°, right",
        striker: bumper_barrier(-DEG10, 0.15, Side::Right, 3.0 * MPH),
        source: "IIHS Bumper test protocol, Version I (2006), corner test (the RCAR barrier)",
        uncertain: "the 10° angle and the side struck are from memory of the protocol's figure; the absorber as for the full-width test",
        tyres: TyreLaw::Rolling,
        tyres_why: FREE_ROLLING,
    },
    PlanarPreset {
        name: "part581-barrier-front",
        description: "front, 2.5 mph (4.02 km/h) forward into a fixed flat barrier perpendicular to the line of travel",
        striker: fixed(plane(0.0, 1.0, Side::Left), 2.5 * MPH),
        source: "49 CFR 581.5(a) (barrier impacts after the pendulum impacts, 2.5 mph); 581.6(a) conditions",
        uncertain: "581.5(a) runs the barrier impacts after the pendulum impacts on the same car: the accumulated damage is not carried over here",
        tyres: TyreLaw::Rolling,
        tyres_why: "581.6(a)(4): brakes disengaged and the transmission in neutral: free rolling",
    },
    PlanarPreset {
        name: "part581-barrier-rear",
        description: "rear, 2.5 mph (4.02 km/h) rearward into a fixed flat barrier perpendicular to the line of travel",
        striker: fixed(plane(0.0, 1.0, Side::Left), 2.5 * MPH),
        source: "49 CFR 581.5(a) (barrier impacts after the pendulum impacts, 2.5 mph); 581.6(a) conditions",
        uncertain: "581.5(a) runs the barrier impacts after the pendulum impacts on the same car: the accumulated damage is not carried over here",
        tyres: TyreLaw::Rolling,
        tyres_why: "581.6(a)(4): brakes disengaged and the transmission in neutral: free rolling",
    },
    PlanarPreset {
        name: "iihs-flat-front",
        description: "front, 5 mph (8.05 km/h) full width into a flat rigid barrier",
        striker: fixed(plane(0.0, 1.0, Side::Left), 5.0 * MPH),
        source: "IIHS low-speed crash test protocol (1990s to 2006), front-into-flat-barrier test",
        uncertain: "the protocol document was not available here: speed and set-up from IIHS status reports",
        tyres: TyreLaw::Rolling,
        tyres_why: FREE_ROLLING,
    },
    PlanarPreset {
        name: "iihs-flat-rear",
        description: "rear, 5 mph (8.05 km/h) full width into a flat rigid barrier",
        striker: fixed(plane(0.0, 1.0, Side::Left), 5.0 * MPH),
        source: "IIHS low-speed crash test protocol (1990s to 2006), rear-into-flat-barrier test",
        uncertain: "the protocol document was not available here: speed and set-up from IIHS status reports",
        tyres: TyreLaw::Rolling,
        tyres_why: FREE_ROLLING,
    },
];

/// The preset of this name.
pub fn find(name: &str) -> Option<&'static PlanarPreset> {
    all().find(|p| p.name == name)
}

/// Every planar preset: [`PRESETS`], then [`BARRIER_PRESETS`].
pub fn all() -> impl Iterator<Item = &'static PlanarPreset> {
    PRESETS.iter().chain(BARRIER_PRESETS)
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
        })
    }
}

/// A striker as a test protocol, a command line or a script names it: a
/// preset, or a plane (degrees, percent, side) or a pole (diameter and
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
}

/// The car a run uses: with a preset, both axles' tyres under the law the
/// test prescribes ([`PlanarPreset::tyres`]); otherwise the car as its
/// file says. Every front end runs presets on this car.
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
        Some(p) => car.clone().with_tyre_law(p.tyres),
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
            let preset = find(name).ok_or_else(|| PlanarError::Missing {
                name: format!("case '{name}'"),
                expected: format!(
                    "known presets: {}",
                    all().map(|p| p.name).collect::<Vec<_>>().join(", ")
                ),
            })?;
            let striker = self
                .speed
                .map_or(preset.striker, |v| preset.striker.with_speed(v));
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

    #[test]
    fn every_preset_runs_on_a_saloon_and_balances() {
        let chain = MsdModel::new(vec![10.0, 1300.0], vec![2e3], vec![1.5e6]).unwrap();
        let bumper = Bumper::three_part(1.5e6, 60e3, 6e6).unwrap();
        let car = PlanarCar::symmetric(&chain, &bumper, &Layout::default()).unwrap();
        for preset in PRESETS {
            let r = simulate(&car, &preset.striker, &Settings::default()).unwrap();
            assert!(
                r.energy.max_relative_error < 1e-3,
                "{}: {:?}",
                preset.name,
                r.energy
            );
            assert!(r.peak_force > 1e3, "{}", preset.name);
            assert!(!preset.source.is_empty() && !preset.uncertain.is_empty());
        }
        assert!(find("iihs-pole-rear").is_some() && find("nope").is_none());
    }

    /// The bumper barrier's absorber takes part of the crush and of the
    /// work; the energy still balances; a centred full-width test of a
    /// symmetric car does not turn it.
    #[test]
    fn barrier_presets_run_balance_and_share_the_crush_with_the_absorber() {
        let chain = MsdModel::new(vec![10.0, 1300.0], vec![2e3], vec![1.5e6]).unwrap();
        let bumper = Bumper::three_part(1.5e6, 60e3, 6e6).unwrap();
        let car = PlanarCar::symmetric(&chain, &bumper, &Layout::default()).unwrap();
        for preset in BARRIER_PRESETS {
            let r = simulate(&car, &preset.striker, &Settings::default()).unwrap();
            let name = preset.name;
            assert!(r.energy.max_relative_error < 1e-3, "{name}: {:?}", r.energy);
            assert!(r.peak_force > 1e3 && r.contact_end.is_some(), "{name}");
            assert!(find(name).is_some(), "{name}");
            // the recorded crush is the bumper's own: its largest equals the state's
            let recorded = r.crush.iter().flatten().copied().fold(0.0, f64::max);
            assert!(
                (recorded - r.max_compression).abs() < 1e-6,
                "{name}: {recorded} {}",
                r.max_compression
            );
            if name.ends_with("bumper-front") {
                assert!(r.yaw.iter().all(|y| y.abs() < 1e-9), "{name}");
                // the 60 kN bumper meets the 35 kN/m absorber: the absorber crushes too
                assert!(r.energy.crush > 1.05 * bumper_work(&bumper, &r), "{name}");
            }
        }
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
