//! The one table of low-speed tests (issue 45 item 3): every test that
//! `bumpsim impact`, `bumpsim planar`, `bumpsim verdict`, the Python module
//! and the docs name, each with its regulation, clause, striker and face,
//! speed, heights, angle and overlap, and what could not be checked.
//!
//! A test is a face (a plane at an angle θ covering a share of the bumper
//! from one side, a head of finite width, a pole, or the RCAR bumper
//! barrier) meeting the car at a speed `v`, either because the car runs
//! into it (`Motion::Fixed`) or because it is carried by a striker of mass
//! `m` against the car at rest (`Motion::Moving`, `Motion::VehicleMass`
//! with `m` the vehicle's own mass). The front ends read it so:
//!
//! - the 1-D impact (`bumpsim impact`) runs the test along the car's centre
//!   line: a moving striker of mass `m` at `v`, or the car into a rigid wall
//!   at `v`; it drops what a line cannot carry (angle, overlap, head width,
//!   pole, the barrier's curvature and absorber), and [`Test::dropped_in_1d`]
//!   says what;
//! - the planar impact (`bumpsim planar`) runs all of it;
//! - the verdict (`bumpsim verdict`) groups the tests into [`PROTOCOLS`] and
//!   judges each against the heights and criteria of its regulation.
//!
//! Speeds are exact conversions of the regulation's own unit
//! (1 mph = 1.609344 km/h). Where a figure is read from a public text the
//! test's `source` names the clause; `uncertain` says what was not checked.
//! The checks made for issue 45: 49 CFR 581.7(a) (impact line 16–20 in, two
//! impacts per end, 2 in apart) in the GPO text of 1 October 2002; the RCAR
//! bumper barrier specification, Issue 1 (September 2007) §2.1–2.2 (steel
//! face R 3400 mm, 1500 mm wide, 100 mm tall; rigid backstop 200 mm tall,
//! 25 mm behind the face) and the RCAR barrier model manual v1.0 (2008:
//! lower edge 405 or 455 mm by the vehicle's target market).

use serde::Serialize;

/// One mile per hour in km/h (exact: 1 mi = 1609.344 m).
pub const MPH: f64 = 1.609344;
/// One inch, m.
pub const INCH: f64 = 0.0254;
const KMH: f64 = 1.0 / 3.6;

/// The end of the car a test strikes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum End {
    /// The front.
    Front,
    /// The rear (the model's x axis then points rearwards).
    Rear,
}

/// The side an overlap is measured from (seen from the struck end).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Side {
    /// Left.
    Left,
    /// Right.
    Right,
}

/// The face that meets the car.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Face {
    /// A flat rigid plane at `angle` (degrees, counter-clockwise seen from
    /// above) covering `overlap` (fraction) of the bumper from `side`.
    Plane {
        /// Angle, degrees.
        angle: f64,
        /// Overlap, fraction of the bumper width.
        overlap: f64,
        /// Side the overlap is measured from.
        side: Side,
    },
    /// A flat rigid head `width` (m) wide, centred on the car.
    Head {
        /// Width, m.
        width: f64,
    },
    /// A rigid vertical pole.
    Pole {
        /// Diameter, m.
        diameter: f64,
        /// Lateral position of its axis, m (left positive).
        lateral: f64,
    },
    /// The RCAR bumper barrier (steel face R 3400 mm, 1500 mm wide, its
    /// energy absorber) at `angle` covering `overlap` from `side`.
    RcarBarrier {
        /// Angle, degrees.
        angle: f64,
        /// Overlap, fraction of the bumper width.
        overlap: f64,
        /// Side the overlap is measured from.
        side: Side,
    },
}

/// What carries the face.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Motion {
    /// The car runs into the fixed face.
    Fixed,
    /// A striker of this mass (kg) hits the car at rest.
    Moving {
        /// Mass, kg.
        mass: f64,
    },
    /// A pendulum of the vehicle's own mass hits the car at rest, along its
    /// face's normal (49 CFR 581, UN R42).
    VehicleMass,
}

/// Where the striker meets the car vertically (heights above the ground, m).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Height {
    /// A pendulum's impact line at any height from `low` to `high`.
    Ridge {
        /// Lowest, m.
        low: f64,
        /// Highest, m.
        high: f64,
    },
    /// The RCAR bumper barrier's 100 mm face, its lower edge by the
    /// vehicle's target market ([`Market`]).
    RcarBarrier,
    /// A wall or pole taller than any bumper.
    Full,
    /// Not given by the source read here.
    Unknown,
}

/// The vehicle's target market: it sets the RCAR barrier's lower edge.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Market {
    /// North America: lower edge 455 mm.
    #[default]
    NorthAmerica,
    /// Europe and the other RCAR markets: lower edge 405 mm.
    Europe,
}

/// The RCAR barrier face's height, m (specification Issue 1, 2007, §2.1: 100 ± 2 mm).
pub const RCAR_FACE: f64 = 0.100;
/// The RCAR barrier's backstop: height (m) and set-back behind the face (m)
/// (specification Issue 1, 2007, §2.2: 200 ± 2 mm tall, 25 ± 1 mm behind).
pub const RCAR_BACKSTOP: (f64, f64) = (0.200, 0.025);

/// What is not checked of the market heights.
pub const MARKET_UNCERTAIN: &str = "the RCAR barrier model manual (v1.0, 2008) gives the lower edge as 405 or 455 mm by the vehicle's target market; which market takes which height (455 mm North America, 405 mm Europe here) was not found in a text read here";

impl Market {
    /// The market of this name (`north-america`, `europe`).
    pub fn parse(name: &str) -> Option<Market> {
        match name.trim().to_ascii_lowercase().as_str() {
            "north-america" | "na" | "us" => Some(Market::NorthAmerica),
            "europe" | "eu" => Some(Market::Europe),
            _ => None,
        }
    }

    /// `north-america` or `europe`.
    pub fn name(self) -> &'static str {
        match self {
            Market::NorthAmerica => "north-america",
            Market::Europe => "europe",
        }
    }

    /// The RCAR barrier face's lower and upper edge above the ground, m.
    pub fn rcar_face(self) -> (f64, f64) {
        let bottom = match self {
            Market::NorthAmerica => 0.455,
            Market::Europe => 0.405,
        };
        (bottom, bottom + RCAR_FACE)
    }
}

/// One test of the table.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Test {
    /// Name (`part581-corner-front-left`).
    pub name: &'static str,
    /// The protocol it belongs to ([`PROTOCOLS`]).
    pub protocol: &'static str,
    /// The end it strikes.
    pub end: End,
    /// What it is.
    pub description: &'static str,
    /// The face.
    pub face: Face,
    /// What carries the face.
    pub motion: Motion,
    /// The impact speed, m/s.
    pub speed: f64,
    /// Where it meets the car vertically.
    pub height: Height,
    /// Whether the crash-box stroke is judged (insurance tests).
    pub crash_box: bool,
    /// The tyres: every test of the table runs free rolling; the protocol's words.
    pub tyres_why: &'static str,
    /// The document and clause the figures come from.
    pub source: &'static str,
    /// What could not be checked.
    pub uncertain: &'static str,
    /// Mass added to the car for the test, kg: UN R42's laden runs carry
    /// their passengers ([`PASSENGERS`] of [`PASSENGER_MASS`]);
    /// 0 for every other test (the car file's mass as given).
    pub load: f64,
}

impl Test {
    /// The speed, km/h.
    pub fn speed_kmh(&self) -> f64 {
        self.speed * 3.6
    }

    /// What a 1-D impact along the centre line leaves out of this test
    /// (None: nothing).
    ///
    /// ```
    /// let t = bumpsim_io::protocols::find("rcar-structural-front").unwrap();
    /// assert!(t.dropped_in_1d().unwrap().contains("40 % overlap"));
    /// assert!(bumpsim_io::protocols::find("paper-a-utv").unwrap().dropped_in_1d().is_none());
    /// ```
    pub fn dropped_in_1d(&self) -> Option<String> {
        let mut out = Vec::new();
        let (angle, overlap) = match self.face {
            Face::Plane { angle, overlap, .. } => (angle, overlap),
            Face::Head { width } => {
                out.push(format!("the head's {:.0} mm width", 1e3 * width));
                (0.0, 1.0)
            }
            Face::Pole { diameter, .. } => {
                out.push(format!("the {:.0} mm pole (a flat face)", 1e3 * diameter));
                (0.0, 1.0)
            }
            Face::RcarBarrier { angle, overlap, .. } => {
                out.push(
                    "the barrier's 3.4 m curvature, 1.5 m width and absorber (a flat rigid face)"
                        .into(),
                );
                (angle, overlap)
            }
        };
        if angle != 0.0 {
            out.push(format!("the {}° angle", angle.abs()));
        }
        if overlap < 1.0 {
            out.push(format!("the {:.0} % overlap", 100.0 * overlap));
        }
        if self.load > 0.0 {
            out.push(format!("the laden car's {:.0} kg of passengers", self.load));
        }
        (!out.is_empty()).then(|| {
            format!(
                "run head-on along the centre line, without {}",
                out.join(", ")
            )
        })
    }
}

/// A protocol: a named group of tests of one regulation or test programme.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Protocol {
    /// Name (`part581`).
    pub name: &'static str,
    /// What it is.
    pub description: &'static str,
    /// Its tests, in the order it runs them.
    pub tests: &'static [&'static str],
}

/// A name the table no longer carries.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Renamed {
    /// The old name.
    pub old: &'static str,
    /// The test to use instead.
    pub new: &'static str,
    /// Why.
    pub why: &'static str,
}

/// Why a name is not a test.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ProtocolError {
    /// An old name.
    #[error("'{old}' is no longer a test name: use '{new}' ({why})")]
    Renamed {
        /// The old name.
        old: String,
        /// The new one.
        new: &'static str,
        /// Why.
        why: &'static str,
    },
    /// No test of this name.
    #[error("no test '{name}'; the tests: {known}")]
    Unknown {
        /// The name given.
        name: String,
        /// The known names.
        known: String,
    },
}

/// The old names, each with the test that replaces it.
pub const RENAMED: &[Renamed] = &[
    Renamed {
        old: "fmvss-581",
        new: "part581-pendulum-front",
        why: "the US bumper standard is 49 CFR Part 581, not a FMVSS of Part 571",
    },
    Renamed {
        old: "ece-r42",
        new: "r42-longitudinal-front",
        why: "UN R42's tests are named r42-...",
    },
    Renamed {
        old: "cmvss-215",
        new: "part581-pendulum-front",
        why: "since September 2009 CMVSS 215 asks for the bumpers of 49 CFR 581 or UN R42 (protocol cmvss215), not the older 8 km/h barrier",
    },
    Renamed {
        old: "iihs-flat",
        new: "iihs-flat-front",
        why: "the IIHS flat-barrier tests are 5 mph front and rear",
    },
    Renamed {
        old: "rcar-16",
        new: "rcar-structural-front",
        why: "the RCAR structural test runs at 15 km/h (Issue 2.2); 16 km/h was the older Allianz AZT test",
    },
    Renamed {
        old: "iihs-corner-front",
        new: "iihs-bumper-corner-front",
        why: "the IIHS corner tests run into the RCAR bumper barrier at 3 mph",
    },
    Renamed {
        old: "iihs-corner-rear",
        new: "iihs-bumper-corner-rear",
        why: "the IIHS corner tests run into the RCAR bumper barrier at 3 mph",
    },
];

/// The test of this name (exact, case-insensitive); an old name is refused
/// with the new one named.
///
/// ```
/// use bumpsim_io::protocols::find;
/// assert_eq!(find("rcar-structural-front").unwrap().speed_kmh().round(), 15.0);
/// assert!(find("rcar-16").unwrap_err().to_string().contains("rcar-structural-front"));
/// ```
pub fn find(name: &str) -> Result<&'static Test, ProtocolError> {
    let name = name.trim();
    if let Some(t) = TESTS.iter().find(|t| t.name.eq_ignore_ascii_case(name)) {
        return Ok(t);
    }
    if let Some(r) = RENAMED.iter().find(|r| r.old.eq_ignore_ascii_case(name)) {
        return Err(ProtocolError::Renamed {
            old: name.into(),
            new: r.new,
            why: r.why,
        });
    }
    Err(ProtocolError::Unknown {
        name: name.into(),
        known: TESTS.iter().map(|t| t.name).collect::<Vec<_>>().join(", "),
    })
}

/// The protocol of this name.
pub fn protocol(name: &str) -> Option<&'static Protocol> {
    PROTOCOLS.iter().find(|p| p.name == name)
}

/// The table as `--case list` prints it, protocol by protocol: a test a
/// line with its speed and description, then its source, what is unchecked
/// and its tyres; with `one_d`, what a 1-D impact drops of it.
///
/// ```
/// let text = bumpsim_io::protocols::listing(true);
/// assert!(text.contains("rcar-structural-front") && text.contains("1-D:"));
/// ```
pub fn listing(one_d: bool) -> String {
    let mut out = String::new();
    for p in PROTOCOLS.iter().filter(|p| p.name != "cmvss215") {
        out += &format!("# {}: {}\n", p.name, p.description);
        for t in p.tests.iter().filter_map(|n| find(n).ok()) {
            out += &format!(
                "{:<26} {:>6.2} km/h  {}\n{:<26} source: {}\n{:<26} uncertain: {}\n{:<26} tyres: {}\n",
                t.name,
                t.speed_kmh(),
                t.description,
                "",
                t.source,
                "",
                t.uncertain,
                "",
                t.tyres_why
            );
            if let (true, Some(dropped)) = (one_d, t.dropped_in_1d()) {
                out += &format!("{:<26} 1-D: {dropped}\n", "");
            }
        }
    }
    out
}

mod table;
pub use table::{PASSENGER_MASS, PASSENGERS, PROTOCOLS, TESTS};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_test_is_in_one_protocol_and_every_protocol_names_tests() {
        for t in TESTS {
            let holders: Vec<&str> = PROTOCOLS
                .iter()
                .filter(|p| p.tests.contains(&t.name))
                .map(|p| p.name)
                .collect();
            assert!(holders.contains(&t.protocol), "{}: {holders:?}", t.name);
            assert!(t.speed > 0.0 && t.speed < 5.0, "{}", t.name);
            assert!(
                !t.source.is_empty() && !t.uncertain.is_empty(),
                "{}",
                t.name
            );
            for word in ["from memory", "as recalled"] {
                assert!(!t.uncertain.contains(word), "{}: {word}", t.name);
            }
        }
        for p in PROTOCOLS {
            for name in p.tests {
                assert!(find(name).is_ok(), "{}: {name}", p.name);
            }
        }
        let mut names: Vec<&str> = TESTS.iter().map(|t| t.name).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), TESTS.len());
    }

    #[test]
    fn every_old_name_is_refused_naming_its_new_one() {
        for r in RENAMED {
            let err = find(r.old).unwrap_err().to_string();
            assert!(err.contains(r.new) && err.contains(r.old), "{err}");
            assert!(find(r.new).is_ok(), "{}", r.new);
        }
        assert!(matches!(find("nope"), Err(ProtocolError::Unknown { .. })));
    }

    #[test]
    fn speeds_are_the_regulations_units_converted_exactly() {
        let kmh = |n: &str| find(n).unwrap().speed_kmh();
        assert!((kmh("part581-pendulum-front") - 2.5 * MPH).abs() < 1e-12);
        assert!((kmh("iihs-bumper-front") - 6.0 * MPH).abs() < 1e-12);
        assert!((kmh("r42-corner-front-left") - 2.5).abs() < 1e-12);
        // R42's laden runs carry their passengers; every other test none
        for t in TESTS {
            let laden = t.name.starts_with("r42-laden-");
            assert_eq!(t.load, if laden { 375.0 } else { 0.0 }, "{}", t.name);
        }
        let laden = find("r42-laden-longitudinal-rear").unwrap();
        assert!(
            laden
                .dropped_in_1d()
                .unwrap()
                .contains("375 kg of passengers")
        );
        assert!((kmh("rcar-structural-front") - 15.0).abs() < 1e-12);
        assert_eq!(Market::Europe.rcar_face(), (0.405, 0.505));
        assert_eq!(Market::parse("North-America"), Some(Market::NorthAmerica));
    }
}
