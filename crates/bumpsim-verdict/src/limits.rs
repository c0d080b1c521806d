//! A car's damageability data: the clearances of the parts behind its
//! bumper and the limits of its structure, from the `[damageability]`
//! table of its planar car file (docs/verdict.md). Lengths follow the
//! file's `length_unit` (m or mm) like the car's layout; forces are N,
//! accelerations m/s².
//!
//! ```toml
//! [damageability]
//! end = "front"                  # the end this car file describes: front (default) or rear
//! rail_yield = 150e3             # N, compressive force at which a side member (rail) yields
//! crash_box_stroke = 45.0        # (length) usable stroke of the crash box: the first chain link
//! bumper_stroke = 90.0           # (length) optional: the bumper's crushable depth
//! beam_height = [400.0, 520.0]   # (length) optional: the beam's bottom and top above the ground
//! bumper_energy_share = 0.3      # optional: least share of the structure's energy the bumper takes
//! deceleration = 150.0           # optional, m/s²: largest 3 ms clip of the body's deceleration
//! olc = 120.0                    # optional, m/s²: largest occupant load criterion
//! asi = 1.0                      # optional: largest acceleration severity index
//! [[damageability.clearance]]
//! name = "radiator"
//! gap = 60.0                     # (length) how far the part sits behind what closes on it
//! from = "beam"                  # beam: closed by the beam's travel relative to the body;
//!                                # front: by the car's front surface (bumper crush + beam travel)
//! lateral = [-400.0, 400.0]      # (length) optional: where across the car, left positive
//! ```
//!
//! A clearance closed by the beam between the side members can never be
//! smaller than the crash-box stroke: the crash box would push the beam
//! into the part before its stroke is used. Such limits contradict each
//! other and are refused with both keys named.

use crate::error::{VerdictError, require};
use bumpsim_planar::PlanarCar;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// Which end of the car a car file describes (the planar car's x axis
/// points to the struck end).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum End {
    /// The front end (front tests).
    Front,
    /// The rear end (rear tests).
    Rear,
}

impl End {
    /// `front` or `rear`.
    pub fn name(self) -> &'static str {
        match self {
            End::Front => "front",
            End::Rear => "rear",
        }
    }
}

/// What closes a clearance.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Closer {
    /// The beam's rearward travel relative to the body (radiator,
    /// condenser, front-end carrier behind the beam).
    Beam,
    /// The car's front surface: the bumper's crush plus the beam's travel
    /// (lamps, bonnet and its latch, wings behind the fascia).
    Front,
}

/// A part behind the bumper and the gap it has.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Clearance {
    /// The part (`radiator`, `left headlamp`).
    pub name: String,
    /// The gap, m.
    pub gap: f64,
    /// What closes it.
    pub from: Closer,
    /// Where across the car, body y from right to left, m.
    pub lateral: Option<[f64; 2]>,
}

/// A car's clearances and limits (SI).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Damageability {
    /// The end of the car the file describes.
    pub end: End,
    /// Compressive side-member force at which a rail yields, N.
    pub rail_yield: f64,
    /// Usable crash-box stroke, m.
    pub crash_box_stroke: f64,
    /// The bumper's crushable depth, m.
    pub bumper_stroke: Option<f64>,
    /// The beam's bottom and top above the ground, m.
    pub beam_height: Option<[f64; 2]>,
    /// Least share of the structure's energy the bumper must take, 1.
    pub bumper_energy_share: Option<f64>,
    /// Largest 3 ms clip of the body's deceleration, m/s².
    pub deceleration: Option<f64>,
    /// Largest OLC, m/s².
    pub olc: Option<f64>,
    /// Largest ASI, 1.
    pub asi: Option<f64>,
    /// The clearances.
    pub clearances: Vec<Clearance>,
}

#[derive(Debug, Deserialize)]
struct CarFile {
    length_unit: Option<String>,
    damageability: Option<toml::Value>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Table {
    end: Option<End>,
    rail_yield: Option<f64>,
    crash_box_stroke: Option<f64>,
    bumper_stroke: Option<f64>,
    #[serde(default, deserialize_with = "bumpsim_io::numbers::optional")]
    beam_height: Option<[f64; 2]>,
    bumper_energy_share: Option<f64>,
    deceleration: Option<f64>,
    olc: Option<f64>,
    asi: Option<f64>,
    #[serde(default)]
    clearance: Vec<ClearanceFile>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ClearanceFile {
    name: Option<String>,
    gap: Option<f64>,
    from: Option<Closer>,
    #[serde(default, deserialize_with = "bumpsim_io::numbers::optional")]
    lateral: Option<[f64; 2]>,
}

const KEY: &str = "damageability";

/// The plausible range of each limit, SI: `(key, low, high, unit, what)`.
/// A limit outside it is a slip (a unit or an exponent), and one near zero
/// would make a margin ratio (margin / limit) infinite. A side member
/// yields at tens to hundreds of kN: 1 kN to 10 MN holds any car's rail.
/// Strokes and gaps behind a bumper are millimetres to decimetres: 1 mm to
/// 1 m. A body's 3 ms deceleration and OLC limits are a few g to a few
/// hundred g: 1 to 10,000 m/s² (0.1 g to 1,000 g). ASI limits are about
/// 1 to 1.4: 0.01 to 100. The bumper's least energy share: 0.1 % to 100 %
/// (exclusive).
pub const RANGES: [(&str, f64, f64, &str, &str); 8] = [
    (
        "rail_yield",
        1e3,
        1e7,
        "N",
        "a yield force from 1 kN to 10 MN",
    ),
    (
        "crash_box_stroke",
        1e-3,
        1.0,
        "m",
        "a stroke from 1 mm to 1 m",
    ),
    ("bumper_stroke", 1e-3, 1.0, "m", "a stroke from 1 mm to 1 m"),
    ("gap", 1e-3, 1.0, "m", "a gap from 1 mm to 1 m"),
    (
        "deceleration",
        1.0,
        1e4,
        "m/s²",
        "a deceleration from 1 to 10000 m/s² (0.1 g to 1000 g)",
    ),
    (
        "olc",
        1.0,
        1e4,
        "m/s²",
        "an OLC from 1 to 10000 m/s² (0.1 g to 1000 g)",
    ),
    ("asi", 0.01, 100.0, "1", "an ASI from 0.01 to 100"),
    (
        "bumper_energy_share",
        1e-3,
        1.0 - f64::EPSILON,
        "1",
        "a share from 0.001 to below 1",
    ),
];

/// Refuses `value` (SI) of limit `name` outside its range in [`RANGES`].
fn plausible(key: &str, name: &str, value: f64) -> Result<(), VerdictError> {
    let Some(&(_, low, high, unit, what)) = RANGES.iter().find(|r| r.0 == name) else {
        return Ok(());
    };
    require(
        key,
        value,
        unit,
        &format!("expected {what}"),
        (low..=high).contains(&value),
    )
}

impl Damageability {
    /// Reads the `[damageability]` table of a planar car file's text;
    /// `path` names the file in messages.
    ///
    /// ```
    /// use bumpsim_verdict::limits::Damageability;
    /// let text = "length_unit = \"mm\"\n[damageability]\nrail_yield = 150e3\ncrash_box_stroke = 40.0\n\
    ///             [[damageability.clearance]]\nname = \"radiator\"\ngap = 60.0\nfrom = \"beam\"\n";
    /// let d = Damageability::parse(text, "car.toml".as_ref()).unwrap();
    /// assert!((d.clearances[0].gap - 0.06).abs() < 1e-12);
    /// let err = Damageability::parse("[damageability]\nrail_yield = 1e5\n", "car.toml".as_ref()).unwrap_err();
    /// assert!(err.to_string().contains("damageability.crash_box_stroke"));
    /// ```
    pub fn parse(text: &str, path: &Path) -> Result<Damageability, VerdictError> {
        let file_error = |message: String| VerdictError::File {
            path: path.display().to_string(),
            message,
        };
        let file: CarFile = toml::from_str(text).map_err(|e| file_error(e.message().into()))?;
        let unit = match file.length_unit.as_deref() {
            None | Some("m") => 1.0,
            Some("mm") => 1e-3,
            Some(other) => {
                return Err(file_error(format!(
                    "length_unit = {other:?}: expected \"m\" or \"mm\""
                )));
            }
        };
        let missing = |key: &str, expected: &str| VerdictError::Missing {
            path: path.display().to_string(),
            key: key.into(),
            expected: expected.into(),
        };
        let value = file.damageability.ok_or_else(|| {
            missing(KEY, "the verdict needs the car's clearances and limits: add a [damageability] table (docs/verdict.md), or give them in a file of their own merged with the car (bumpsim verdict --damageability FILE, as examples/verdict/damageability.toml)")
        })?;
        let table: Table = value.try_into().map_err(|e: toml::de::Error| {
            file_error(format!("[{KEY}]: {}", e.message().trim_end()))
        })?;
        let rail_yield = table.rail_yield.ok_or_else(|| {
            missing(
                "damageability.rail_yield",
                "the compressive force (N) at which a side member yields",
            )
        })?;
        let stroke = table.crash_box_stroke.ok_or_else(|| {
            missing(
                "damageability.crash_box_stroke",
                "the usable crash-box stroke (length_unit): the first chain link's compression",
            )
        })?;
        if table.clearance.is_empty() {
            return Err(missing(
                "damageability.clearance",
                "at least one [[damageability.clearance]] (name, gap, from = \"beam\" or \"front\"): the parts the bumper must keep clear of",
            ));
        }
        let clearances = table
            .clearance
            .iter()
            .enumerate()
            .map(|(i, c)| clearance(c, i, unit, &missing))
            .collect::<Result<Vec<_>, _>>()?;
        let d = Damageability {
            end: table.end.unwrap_or(End::Front),
            rail_yield,
            crash_box_stroke: stroke * unit,
            bumper_stroke: table.bumper_stroke.map(|s| s * unit),
            beam_height: table.beam_height.map(|h| h.map(|v| v * unit)),
            bumper_energy_share: table.bumper_energy_share,
            deceleration: table.deceleration,
            olc: table.olc,
            asi: table.asi,
            clearances,
        };
        d.check()?;
        Ok(d)
    }

    /// Reads a planar car file's `[damageability]` table.
    pub fn read(path: &Path) -> Result<Damageability, VerdictError> {
        let text = std::fs::read_to_string(path).map_err(|e| VerdictError::File {
            path: path.display().to_string(),
            message: format!("cannot read: {e}"),
        })?;
        Damageability::parse(&text, path)
    }

    /// Whether a car file carries a `[damageability]` table.
    pub fn given(path: &Path) -> Result<bool, VerdictError> {
        let file = |message: String| VerdictError::File {
            path: path.display().to_string(),
            message,
        };
        let text = std::fs::read_to_string(path).map_err(|e| file(format!("cannot read: {e}")))?;
        let table: toml::Table = toml::from_str(&text).map_err(|e| file(e.message().into()))?;
        Ok(table.contains_key(KEY))
    }

    /// Checks every limit on its own: within its plausible range (see
    /// [`RANGES`]), ordered, names unique.
    fn check(&self) -> Result<(), VerdictError> {
        let limits = [
            ("rail_yield", Some(self.rail_yield)),
            ("crash_box_stroke", Some(self.crash_box_stroke)),
            ("bumper_stroke", self.bumper_stroke),
            ("bumper_energy_share", self.bumper_energy_share),
            ("deceleration", self.deceleration),
            ("olc", self.olc),
            ("asi", self.asi),
        ];
        for (name, value) in limits {
            if let Some(v) = value {
                plausible(&format!("{KEY}.{name}"), name, v)?;
            }
        }
        if let Some([bottom, top]) = self.beam_height {
            let expected = format!(
                "the beam's bottom and top above the ground, bottom ≥ 0 below top = {top} m"
            );
            require(
                "damageability.beam_height",
                bottom,
                "m",
                &expected,
                bottom >= 0.0 && top.is_finite() && bottom < top,
            )?;
        }
        for (i, c) in self.clearances.iter().enumerate() {
            if let Some(j) = self.clearances[..i].iter().position(|o| o.name == c.name) {
                return Err(VerdictError::Contradiction {
                    first: format!("damageability.clearance[{}]", j + 1),
                    second: format!("damageability.clearance[{}]", i + 1),
                    reason: format!("both are named '{}': give each part its own name", c.name),
                });
            }
        }
        Ok(())
    }

    /// Checks the limits against the car they belong to: each clearance's
    /// lateral range lies on the bumper, and no clearance closed by the
    /// beam between the side members is within the crash-box stroke.
    pub fn check_car(&self, car: &PlanarCar) -> Result<(), VerdictError> {
        let half = 0.5 * car.beam().width;
        let rails = 0.5 * car.beam().side_member_spacing;
        for (i, c) in self.clearances.iter().enumerate() {
            let key = format!("damageability.clearance[{}]", i + 1);
            let [low, high] = c.lateral.unwrap_or([-half, half]);
            if low < -half - 1e-12 || high > half + 1e-12 {
                return Err(VerdictError::Value {
                    key: format!("{key}.lateral"),
                    value: if low < -half { low } else { high },
                    unit: "m",
                    expected: format!(
                        "'{}' must lie across the {} m bumper, within ±{half} m",
                        c.name,
                        2.0 * half
                    ),
                });
            }
            let between_rails = low < rails && high > -rails;
            if c.from == Closer::Beam && between_rails && c.gap <= self.crash_box_stroke {
                return Err(VerdictError::Contradiction {
                    first: format!("{key}.gap"),
                    second: "damageability.crash_box_stroke".into(),
                    reason: format!(
                        "'{}' sits {} mm behind the beam between the side members, but the crash box may travel {} mm: the beam would reach it before the crash box's stroke is used; a stroke must stay within the clearances it moves the beam towards",
                        c.name,
                        c.gap * 1e3,
                        self.crash_box_stroke * 1e3
                    ),
                });
            }
        }
        Ok(())
    }
}

fn clearance(
    c: &ClearanceFile,
    i: usize,
    unit: f64,
    missing: &dyn Fn(&str, &str) -> VerdictError,
) -> Result<Clearance, VerdictError> {
    let key = format!("damageability.clearance[{}]", i + 1);
    let name = c.name.clone().filter(|n| !n.trim().is_empty());
    let name = name.ok_or_else(|| {
        missing(
            &format!("{key}.name"),
            "the part's name (radiator, left headlamp, ...)",
        )
    })?;
    let gap = c.gap.ok_or_else(|| {
        missing(
            &format!("{key}.gap"),
            "how far the part sits behind what closes on it (length_unit)",
        )
    })?;
    let from = c.from.ok_or_else(|| {
        missing(&format!("{key}.from"), "\"beam\" (closed by the beam's travel) or \"front\" (by the front surface: bumper crush + beam travel)")
    })?;
    plausible(&format!("{key}.gap"), "gap", gap * unit)?;
    if let Some([low, high]) = c.lateral {
        let expected = format!("from right to left: the first must be below the second ({high})");
        require(
            &format!("{key}.lateral"),
            low,
            "length_unit",
            &expected,
            high.is_finite() && low < high,
        )?;
    }
    Ok(Clearance {
        name,
        gap: gap * unit,
        from,
        lateral: c.lateral.map(|l| l.map(|v| v * unit)),
    })
}
