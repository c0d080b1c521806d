//! The low-speed protocols as the verdict judges them: each test of the
//! one table ([`bumpsim_io::protocols`]: speed, striker, face, source and
//! what could not be checked) with its impact heights resolved for the
//! vehicle's target market (`--market`: the RCAR barrier's lower edge, 455
//! or 405 mm) and its tyre condition. The protocols group the table's
//! tests; the table's module overview gives each regulation's figures with
//! their clauses. A corner pendulum of 49 CFR 581 and UN R42 runs as its
//! guided equivalent ([`bumpsim_planar::presets::striker_of`]).

use crate::error::VerdictError;
use crate::limits::End;
use bumpsim_io::protocols::{self as table, Market};
use bumpsim_planar::car::TyreLaw;
use bumpsim_planar::presets;
use bumpsim_planar::{Face, Motion, Striker};
use serde::Serialize;
use std::sync::LazyLock;

pub use bumpsim_io::protocols::{INCH, PROTOCOLS, Protocol};

/// Where the striker meets the car vertically (heights above the ground, m).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum Height {
    /// A pendulum's impact ridge at any height from `low` to `high`: the
    /// beam must cover the whole range.
    Ridge {
        /// Lowest ridge height, m.
        low: f64,
        /// Highest ridge height, m.
        high: f64,
    },
    /// A barrier face from `bottom` to `top`: the beam must overlap half of it.
    Face {
        /// The face's lower edge, m.
        bottom: f64,
        /// The face's upper edge, m.
        top: f64,
    },
    /// A wall or pole taller than any bumper: it meets any beam.
    Full,
    /// The protocol's figure was not available here: not checked.
    Unknown,
}

impl Height {
    fn of(height: table::Height, market: Market) -> Height {
        match height {
            table::Height::Ridge { low, high } => Height::Ridge { low, high },
            table::Height::RcarBarrier => {
                let (bottom, top) = market.rcar_face();
                Height::Face { bottom, top }
            }
            table::Height::Full => Height::Full,
            table::Height::Unknown => Height::Unknown,
        }
    }
}

/// One test of a protocol: a table entry for a market.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Test {
    /// Name (`part581-corner-front-left`).
    pub name: &'static str,
    /// The end of the car it strikes.
    pub end: End,
    /// What it is.
    pub description: &'static str,
    /// The table entry (face, motion, speed).
    pub entry: &'static table::Test,
    /// Where it meets the car vertically (for the market).
    pub height: Height,
    /// The market the heights are for.
    pub market: Market,
    /// Whether the crash-box stroke is a pass/fail criterion (insurance
    /// tests: a crash box that bottoms out lets the rails deform); the
    /// regulations allow damage to the bumper and its attachments.
    pub crash_box: bool,
    /// The tyres' condition.
    pub tyres: TyreLaw,
    /// Why: the protocol's words on brakes and gear.
    pub tyres_why: &'static str,
    /// The document the figures come from.
    pub source: &'static str,
    /// What could not be checked.
    pub uncertain: &'static str,
}

impl Test {
    fn of(entry: &'static table::Test, market: Market) -> Test {
        Test {
            name: entry.name,
            end: match entry.end {
                table::End::Front => End::Front,
                table::End::Rear => End::Rear,
            },
            description: entry.description,
            entry,
            height: Height::of(entry.height, market),
            market,
            crash_box: entry.crash_box,
            tyres: presets::tyres(entry),
            tyres_why: entry.tyres_why,
            source: entry.source,
            uncertain: entry.uncertain,
        }
    }
}

static NORTH_AMERICA: LazyLock<Vec<Test>> = LazyLock::new(|| tests_for(Market::NorthAmerica));
static EUROPE: LazyLock<Vec<Test>> = LazyLock::new(|| tests_for(Market::Europe));

fn tests_for(market: Market) -> Vec<Test> {
    table::TESTS.iter().map(|t| Test::of(t, market)).collect()
}

/// Every test for the market.
pub fn tests(market: Market) -> &'static [Test] {
    match market {
        Market::NorthAmerica => &NORTH_AMERICA,
        Market::Europe => &EUROPE,
    }
}

/// The test of this name (the default market's heights).
pub fn test(name: &str) -> Option<&'static Test> {
    test_in(name, Market::default())
}

/// The test of this name for the market.
pub fn test_in(name: &str, market: Market) -> Option<&'static Test> {
    tests(market).iter().find(|t| t.name == name)
}

/// The tests that protocol and test names select, in order and each once:
/// a protocol name (`part581`), a test name (`rcar-bumper-front`) or `all`.
///
/// ```
/// let tests = bumpsim_verdict::protocol::select(&["part581", "rcar-bumper-front"]).unwrap();
/// assert_eq!(tests.len(), 9);
/// let err = bumpsim_verdict::protocol::select(&["fmvss-999"]).unwrap_err();
/// assert!(err.to_string().contains("fmvss-999"));
/// ```
pub fn select(names: &[&str]) -> Result<Vec<&'static Test>, VerdictError> {
    select_in(names, Market::default())
}

/// [`select`] with the heights of the vehicle's target market.
///
/// ```
/// use bumpsim_io::protocols::Market;
/// use bumpsim_verdict::protocol::{Height, select_in};
/// let t = &select_in(&["rcar-bumper-rear"], Market::Europe).unwrap()[0];
/// assert_eq!(t.height, Height::Face { bottom: 0.405, top: 0.505 });
/// ```
pub fn select_in(names: &[&str], market: Market) -> Result<Vec<&'static Test>, VerdictError> {
    let all = tests(market);
    let mut picked_all: Vec<&'static Test> = Vec::new();
    for name in names {
        let name = name.trim();
        let picked: Vec<&'static Test> = match (name, PROTOCOLS.iter().find(|p| p.name == name)) {
            ("all", _) => all.iter().collect(),
            (_, Some(p)) => p.tests.iter().filter_map(|t| test_in(t, market)).collect(),
            (_, None) => vec![test_in(name, market).ok_or_else(|| unknown(name))?],
        };
        for t in picked {
            if !picked_all.iter().any(|o| o.name == t.name) {
                picked_all.push(t);
            }
        }
    }
    Ok(picked_all)
}

fn unknown(name: &str) -> VerdictError {
    if let Err(e @ table::ProtocolError::Renamed { .. }) = table::find(name) {
        return VerdictError::Protocol {
            name: name.into(),
            known: e.to_string(),
        };
    }
    let known: Vec<&str> = PROTOCOLS.iter().map(|p| p.name).collect();
    VerdictError::Protocol {
        name: name.into(),
        known: format!(
            "{} (or all, or a test name: `bumpsim verdict --list`)",
            known.join(", ")
        ),
    }
}

impl Test {
    /// The planar striker for a car of total mass `car_mass` kg (a
    /// corner pendulum as its guided equivalent, see the module overview).
    pub fn striker(&self, car_mass: f64) -> Result<Striker, VerdictError> {
        Ok(presets::striker_of(self.entry, car_mass))
    }

    /// The nominal striker: face, motion and speed as the protocol states
    /// them (a pendulum of the vehicle's mass `car_mass`).
    pub fn nominal(&self, car_mass: f64) -> Result<Striker, VerdictError> {
        Ok(presets::nominal_of(self.entry, car_mass))
    }

    /// The impact speed, m/s (car or striker).
    pub fn speed(&self) -> f64 {
        self.entry.speed
    }

    /// The striker's mass, kg (None: the car runs into a fixed face).
    pub fn mass(&self, car_mass: f64) -> Option<f64> {
        match presets::nominal_of(self.entry, car_mass).motion {
            Motion::Fixed { .. } => None,
            Motion::Pendulum { mass, .. } => Some(mass),
        }
    }

    /// The face.
    pub fn face(&self) -> Option<Face> {
        Some(presets::face_of(self.entry))
    }

    /// The face's angle, rad (0 for a pole).
    pub fn angle(&self) -> f64 {
        presets::angle_of(self.entry)
    }

    /// The overlap, fraction of the bumper width (1 for a pole).
    pub fn overlap(&self) -> f64 {
        match self.face() {
            Some(Face::Plane { overlap, .. }) => overlap,
            Some(Face::Barrier(b)) => b.overlap,
            _ => 1.0,
        }
    }
}
