//! The planar car file (TOML). Unknown keys are errors; the car is validated
//! by [`PlanarCar::new`], whose errors name the parameter (`body.yaw_inertia`,
//! `left.springs[2]`, `bumper.segment[3]`, …).
//!
//! ```toml
//! name = "mid-size saloon, planar"        # optional
//! length_unit = "mm"                      # optional: "m" (default) or "mm"; applies to
//!                                         # the keys marked (length) only
//! [body]
//! mass = 1300.0                           # kg, the rigid body (without the chains)
//! yaw_inertia = 2000.0                    # kg·m², about the body's CG
//! cg_behind_bumper = 2000.0               # (length) bumper line to CG
//! wheelbase = 2600.0                      # (length)
//! cg_behind_front_axle = 1100.0           # (length) front axle to CG
//! track = 1500.0                          # (length)
//!
//! [left]                                  # chain at y = +b; mass 1 carries the beam
//! masses = [5.0]                          # kg
//! dampers = [1000.0]                      # N·s/m, the last joins the last mass to the body
//! springs = [2e6]                         # N/m
//! [right]                                 # chain at y = −b (absent: beam on the body)
//! masses = [5.0]
//! dampers = [1000.0]
//! springs = [2e6]
//!
//! [bumper]
//! width = 1600.0                          # (length), centred on the car's axis
//! effective_width = 1650.0                # optional (length; default `width`): the width the
//!                                         # segments' contact points span (car_contact.rs)
//! side_member_spacing = 1000.0            # (length) 2b
//! segments = 10                           # the whole-bumper curve is split equally
//! bending = 1e5                           # N/m between neighbouring segments
//! ramp = 1.5e6                            # N/m  } the whole bumper's characteristic
//! plateau = 60e3                          # N    } (spec §5), or `curve = [[d, F], ...]`
//! unloading = 6e6                         # N/m  } with d in m and F in N
//! # or, instead of the whole-bumper keys, one table per segment (right to left,
//! # force per segment):  segment = [{ ramp = 1.5e5, plateau = 6e3, unloading = 6e5 }, ...]
//! depth = 80.0                            # optional (length): each segment's crushable depth;
//!                                         # beyond it the beam blocks (docs/planar.md)
//! block_stiffness = 5e7                   # N/m, whole bumper, split equally (default 5e7,
//!                                         # car::DEFAULT_BLOCK_STIFFNESS; needs `depth`)
//! rate = 0.0                              # optional (0), s/m: the contact's rate term, each
//!                                         # segment's force times max(0, 1 + rate·ḋ) (car_contact.rs)
//!
//! [crash_boxes]                           # optional: each side's first link (mass 1 to
//! depth = 40.0                            # the next) is its crash box; (length) its stroke,
//!                                         # beyond which it blocks (docs/planar.md)
//! block_stiffness = 1e8                   # N/m per box (default 1e8,
//!                                         # car::DEFAULT_CRASH_BOX_BLOCK_STIFFNESS)
//!
//! [tyres]                                 # optional; absent = frictionless
//! slip_speed = 0.05                       # m/s, regularisation of the laws at standstill
//! # law = "rolling" (default: free-rolling wheels, car in neutral) or "sliding"
//! # (locked or braked); rolling: rolling_resistance along the wheel (default 0),
//! # cornering_stiffness (N/rad per tyre, default 60000) and relaxation_length
//! # (m, default 0.4; 0: instantaneous slip-angle law); mu_lateral the grip across;
//! # mu_longitudinal the locked wheel's sliding grip along (default: mu_lateral);
//! # shape (rolling only): the Magic Formula's shape factor C in [1, 2) (about
//! # 1.3; default: none, the linear law clamped at mu_lateral N, or its tanh
//! # with relaxation_length = 0)
//! front = { rolling_resistance = 0.015, mu_lateral = 0.8 }
//! rear = { mu_longitudinal = 0.75, mu_lateral = 0.8, law = "sliding" }   # e.g. parking brake on
//!
//! [damageability]                         # optional: clearances and limits of the
//!                                         # damageability verdicts (docs/verdict.md)
//! ```
//!
//! Slopes are always N/m and curve compressions always m: `length_unit` is
//! only a convenience for the layout dimensions, which drawings give in mm.

use crate::car::{
    Axle, Beam, Block, Body, DEFAULT_BLOCK_STIFFNESS, DEFAULT_CRASH_BOX_BLOCK_STIFFNESS,
    MAX_SEGMENTS, PlanarCar, PlanarError, TyreLaw, Tyres,
};
use bumpsim_impact::bumper::{Bumper, Loading};
use serde::Deserialize;
use std::path::Path;

pub use crate::car::WIDTH_RANGE;

/// The beam of a car file lies across the car and carries the side members
/// (at ±spacing/2, under the beam): refused naming the key otherwise.
fn check_beam_fits(beam: &Beam, error: &dyn Fn(String) -> PlanarError) -> Result<(), PlanarError> {
    let (low, high) = WIDTH_RANGE.into_inner();
    if !WIDTH_RANGE.contains(&beam.width) {
        let width = bumpsim_core::units::short(beam.width);
        return Err(error(format!(
            "bumper.width = {width} m: expected {low} to {high} m (WIDTH_RANGE)"
        )));
    }
    if beam.side_member_spacing > beam.width {
        return Err(error(format!(
            "bumper.side_member_spacing = {} m is wider than bumper.width = {} m: the side members must lie under the bumper beam",
            bumpsim_core::units::short(beam.side_member_spacing),
            bumpsim_core::units::short(beam.width)
        )));
    }
    Ok(())
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct PlanarFile {
    /// `kind = "planar"` (issue 46), read by `bumpsim_io::kind`.
    #[serde(default, rename = "kind")]
    _kind: Option<String>,
    name: Option<String>,
    length_unit: Option<String>,
    body: BodyFile,
    #[serde(default)]
    left: ChainFile,
    #[serde(default)]
    right: ChainFile,
    bumper: BumperFile,
    #[serde(default)]
    crash_boxes: Option<CrashBoxesFile>,
    #[serde(default)]
    tyres: Option<TyresFile>,
    /// Clearances and limits for damageability verdicts: read and checked
    /// by bumpsim-verdict (docs/verdict.md); the planar car ignores it.
    #[serde(default)]
    #[allow(dead_code)]
    damageability: Option<toml::Table>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct BodyFile {
    mass: f64,
    yaw_inertia: f64,
    cg_behind_bumper: f64,
    wheelbase: f64,
    cg_behind_front_axle: f64,
    track: f64,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct ChainFile {
    #[serde(default)]
    masses: Vec<f64>,
    #[serde(default)]
    dampers: Vec<f64>,
    #[serde(default)]
    springs: Vec<f64>,
    /// Nonlinear links, as the 1-D links car's `[[links]]` ([`links`]).
    #[serde(default)]
    links: Vec<toml::Value>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Characteristic {
    ramp: Option<f64>,
    plateau: Option<f64>,
    unloading: Option<f64>,
    #[serde(default, deserialize_with = "bumpsim_io::numbers::optional_list")]
    curve: Option<Vec<[f64; 2]>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct BumperFile {
    width: f64,
    side_member_spacing: f64,
    segments: Option<usize>,
    #[serde(default)]
    bending: f64,
    ramp: Option<f64>,
    plateau: Option<f64>,
    unloading: Option<f64>,
    #[serde(default, deserialize_with = "bumpsim_io::numbers::optional_list")]
    curve: Option<Vec<[f64; 2]>>,
    #[serde(default)]
    segment: Vec<Characteristic>,
    depth: Option<f64>,
    block_stiffness: Option<f64>,
    #[serde(default)]
    rate: f64,
    effective_width: Option<f64>,
}

/// The block of a `[bumper]` table: its depth (scaled by `unit`) and its
/// whole-bumper stiffness split over `n` segments.
fn block(file: &BumperFile, unit: f64, n: usize) -> Result<Option<Block>, PlanarError> {
    match (file.depth, file.block_stiffness) {
        (None, None) => Ok(None),
        (None, Some(k)) => Err(PlanarError::Missing {
            name: format!("bumper.block_stiffness = {k:?}"),
            expected: "needs `bumper.depth`, the depth at which the segments block".into(),
        }),
        (Some(depth), k) => Ok(Some(Block {
            depth: depth * unit,
            stiffness: k.unwrap_or(DEFAULT_BLOCK_STIFFNESS) / n.max(1) as f64,
        })),
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct CrashBoxesFile {
    depth: Option<f64>,
    block_stiffness: Option<f64>,
}

/// The crash boxes' block of a `[crash_boxes]` table: its depth (scaled
/// by `unit`) and its stiffness per box.
fn crash_boxes(file: &Option<CrashBoxesFile>, unit: f64) -> Result<Option<Block>, PlanarError> {
    let Some(file) = file else { return Ok(None) };
    match (file.depth, file.block_stiffness) {
        (None, k) => Err(PlanarError::Missing {
            name: format!("crash_boxes.block_stiffness = {k:?}"),
            expected: "needs `crash_boxes.depth`, the stroke at which the crash boxes block".into(),
        }),
        (Some(depth), k) => Ok(Some(Block {
            depth: depth * unit,
            stiffness: k.unwrap_or(DEFAULT_CRASH_BOX_BLOCK_STIFFNESS),
        })),
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct TyresFile {
    slip_speed: Option<f64>,
    #[serde(default)]
    front: AxleFile,
    #[serde(default)]
    rear: AxleFile,
}

/// An axle as the car file gives it: the sliding grip along the wheel
/// defaults to the lateral grip; a rolling axle's `mu_longitudinal`
/// without `rolling_resistance` is a file from before issue 45 (where it
/// was the rolling resistance) and is refused, naming the fix.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct AxleFile {
    mu_longitudinal: Option<f64>,
    rolling_resistance: Option<f64>,
    #[serde(default)]
    mu_lateral: f64,
    #[serde(default)]
    law: TyreLaw,
    cornering_stiffness: Option<f64>,
    relaxation_length: Option<f64>,
    shape: Option<f64>,
}

impl AxleFile {
    /// The axle (`name`: `front` or `rear`; `error` names the file).
    fn axle(&self, name: &str, error: &dyn Fn(String) -> PlanarError) -> Result<Axle, PlanarError> {
        if let (TyreLaw::Rolling, Some(mu), None) =
            (self.law, self.mu_longitudinal, self.rolling_resistance)
        {
            return Err(error(format!(
                "tyres.{name}.mu_longitudinal = {mu:?} on a rolling axle without rolling_resistance: mu_longitudinal is the locked wheel's sliding grip along the wheel (about 0.7-0.8 on dry asphalt) and the rolling resistance is rolling_resistance (about 0.01-0.015); a car file written before issue 45 meant the rolling resistance: write rolling_resistance = {mu:?} (and mu_longitudinal only where the sliding grip along the wheel differs from mu_lateral; docs/planar.md)"
            )));
        }
        let d = Axle::default();
        Ok(Axle {
            mu_longitudinal: self.mu_longitudinal.unwrap_or(self.mu_lateral),
            rolling_resistance: self.rolling_resistance.unwrap_or(0.0),
            mu_lateral: self.mu_lateral,
            law: self.law,
            cornering_stiffness: self.cornering_stiffness.unwrap_or(d.cornering_stiffness),
            relaxation_length: self.relaxation_length.unwrap_or(d.relaxation_length),
            shape: self.shape,
        })
    }
}

fn characteristic(c: &Characteristic, name: &str) -> Result<Option<Bumper>, PlanarError> {
    let bumper = |r| PlanarError::Bumper {
        name: name.into(),
        source: r,
    };
    let missing = |what: &str| PlanarError::Missing {
        name: name.into(),
        expected: what.into(),
    };
    match (c.ramp, c.plateau, &c.curve, c.unloading) {
        (None, None, None, None) => Ok(None),
        (Some(ramp), Some(plateau), None, Some(u)) => Bumper::three_part(ramp, plateau, u)
            .map(Some)
            .map_err(bumper),
        (None, None, Some(curve), Some(u)) => {
            let (d, f) = curve.iter().map(|p| (p[0], p[1])).unzip();
            Bumper::table(d, f, u).map(Some).map_err(bumper)
        }
        _ => Err(missing(
            "give `unloading` with either `ramp` and `plateau`, or `curve`",
        )),
    }
}

fn segments(file: &BumperFile) -> Result<Vec<Bumper>, PlanarError> {
    let whole = Characteristic {
        ramp: file.ramp,
        plateau: file.plateau,
        unloading: file.unloading,
        curve: file.curve.clone(),
    };
    let whole = characteristic(&whole, "bumper")?;
    match (whole, file.segment.is_empty(), file.segments) {
        (Some(b), true, Some(n)) if (1..=MAX_SEGMENTS).contains(&n) => {
            let one = b
                .scaled(1.0 / n as f64)
                .map_err(|source| PlanarError::Bumper {
                    name: "bumper".into(),
                    source,
                })?;
            Ok(vec![one; n])
        }
        (None, false, count) if count.is_none_or(|n| n == file.segment.len()) => file
            .segment
            .iter()
            .enumerate()
            .map(|(j, c)| {
                let name = format!("bumper.segment[{}]", j + 1);
                characteristic(c, &name)?.ok_or_else(|| PlanarError::Missing {
                    name,
                    expected: "a characteristic: `unloading` with `ramp` and `plateau` or `curve`"
                        .into(),
                })
            })
            .collect(),
        _ => Err(PlanarError::Parameter {
            name: "bumper".into(),
            value: file.segments.unwrap_or(0) as f64,
            unit: "segments",
            expected: format!(
                "either a whole-bumper characteristic with `segments` from 1 to {MAX_SEGMENTS}, or a `segment` list (whose length `segments` must match if given)"
            ),
        }),
    }
}

impl PlanarCar {
    /// Parses a planar car file; `path` is used in messages.
    ///
    /// ```
    /// use bumpsim_planar::PlanarCar;
    /// let text = r#"
    ///     [body]
    ///     mass = 1200.0
    ///     yaw_inertia = 1800.0
    ///     cg_behind_bumper = 2.0
    ///     wheelbase = 2.6
    ///     cg_behind_front_axle = 1.1
    ///     track = 1.5
    ///     [bumper]
    ///     width = 1.6
    ///     side_member_spacing = 1.0
    ///     segments = 8
    ///     ramp = 1.5e6
    ///     plateau = 60e3
    ///     unloading = 6e6
    /// "#;
    /// let car = PlanarCar::parse(text, "car.toml".as_ref()).unwrap();
    /// assert_eq!(car.beam().segments.len(), 8);
    /// let bad = text.replace("yaw_inertia = 1800.0", "yaw_inertia = -1800.0");
    /// let err = PlanarCar::parse(&bad, "car.toml".as_ref()).unwrap_err();
    /// assert!(err.to_string().contains("body.yaw_inertia"));
    /// ```
    pub fn parse(text: &str, path: &Path) -> Result<PlanarCar, PlanarError> {
        let error = |message: String| PlanarError::File {
            path: path.display().to_string(),
            message,
        };
        let file: PlanarFile = toml::from_str(text).map_err(|e| error(e.to_string()))?;
        let unit = match file.length_unit.as_deref() {
            None | Some("m") => 1.0,
            Some("mm") => 1e-3,
            Some(other) => {
                return Err(error(format!(
                    "length_unit = {other:?}: expected \"m\" or \"mm\""
                )));
            }
        };
        let b = &file.body;
        let body = Body {
            mass: b.mass,
            yaw_inertia: b.yaw_inertia,
            cg_behind_bumper: b.cg_behind_bumper * unit,
            wheelbase: b.wheelbase * unit,
            cg_behind_front_axle: b.cg_behind_front_axle * unit,
            track: b.track * unit,
        };
        let chain = |side: &str, c: ChainFile| links::side_chain(side, c, &error);
        let segments = segments(&file.bumper).map_err(|e| error(e.to_string()))?;
        let beam = Beam {
            width: file.bumper.width * unit,
            side_member_spacing: file.bumper.side_member_spacing * unit,
            block: block(&file.bumper, unit, segments.len()).map_err(|e| error(e.to_string()))?,
            segments,
            bending: file.bumper.bending,
        };
        if beam.width.is_finite() && beam.side_member_spacing.is_finite() {
            check_beam_fits(&beam, &error)?;
        }
        let tyres = match file.tyres {
            None => Tyres::default(),
            Some(t) => Tyres {
                front: t.front.axle("front", &error)?,
                rear: t.rear.axle("rear", &error)?,
                slip_speed: t.slip_speed.unwrap_or(Tyres::default().slip_speed),
            },
        };
        // a value out of range is named with the file it came from
        let boxes = crash_boxes(&file.crash_boxes, unit).map_err(|e| error(e.to_string()))?;
        let (left, right) = (chain("left", file.left)?, chain("right", file.right)?);
        let rate = file.bumper.rate;
        let effective = file.bumper.effective_width.map(|w| w * unit);
        let car = PlanarCar::new(body, left, right, beam, tyres)
            .and_then(|car| car.with_crash_boxes(boxes))
            .and_then(|car| car.with_contact_rate(rate))
            .and_then(|car| match effective {
                Some(w) => car.with_effective_width(w),
                None => Ok(car),
            })
            .map_err(|e| error(e.to_string()))?;
        Ok(car.with_name(file.name))
    }

    /// Reads a planar car file.
    pub fn read(path: &Path) -> Result<PlanarCar, PlanarError> {
        let text = std::fs::read_to_string(path).map_err(|e| PlanarError::File {
            path: path.display().to_string(),
            message: format!("cannot read: {e}"),
        })?;
        Self::parse(&text, path)
    }
}

impl PlanarCar {
    /// The car as a planar car file (SI lengths; one characteristic per
    /// segment), which [`PlanarCar::parse`] reads back to the same car.
    ///
    /// ```
    /// use bumpsim_core::model::MsdModel;
    /// use bumpsim_impact::bumper::Bumper;
    /// use bumpsim_planar::car::{Layout, PlanarCar};
    /// let chain = MsdModel::new(vec![10.0, 1200.0], vec![2e3], vec![2e6]).unwrap();
    /// let bumper = Bumper::three_part(1.5e6, 60e3, 6e6).unwrap();
    /// let car = PlanarCar::symmetric(&chain, &bumper, &Layout::default()).unwrap();
    /// let again = PlanarCar::parse(&car.to_toml(), "car.toml".as_ref()).unwrap();
    /// assert_eq!(again, car);
    /// ```
    pub fn to_toml(&self) -> String {
        let mut s = String::new();
        if let Some(name) = self.name() {
            // TOML's own escapes (Rust's `{:?}` writes `\u{7f}`, which TOML refuses)
            s += &format!("name = {}\n", toml::Value::String(name.into()));
        }
        let b = self.body();
        s += &format!(
            "[body]\nmass = {:?}    # kg\nyaw_inertia = {:?}    # kg·m²\ncg_behind_bumper = {:?}    # m\nwheelbase = {:?}    # m\ncg_behind_front_axle = {:?}    # m\ntrack = {:?}    # m\n",
            b.mass, b.yaw_inertia, b.cg_behind_bumper, b.wheelbase, b.cg_behind_front_axle, b.track
        );
        for (side, chain) in [("left", self.left()), ("right", self.right())] {
            s += &links::side_toml(side, chain);
        }
        let beam = self.beam();
        s += &format!(
            "\n[bumper]\nwidth = {:?}    # m\nside_member_spacing = {:?}    # m\nbending = {:?}    # N/m\n",
            beam.width, beam.side_member_spacing, beam.bending
        );
        if self.contact_rate() > 0.0 {
            s += &format!(
                "rate = {:?}    # s/m, the contact's rate term\n",
                self.contact_rate()
            );
        }
        if self.effective_width() != beam.width {
            s += &format!(
                "effective_width = {:?}    # m, where the segments' contact points reach\n",
                self.effective_width()
            );
        }
        if let Some(block) = beam.block {
            let whole = block.stiffness * beam.segments.len() as f64;
            s += &format!(
                "depth = {:?}    # m\nblock_stiffness = {whole:?}    # N/m, whole bumper\n",
                block.depth
            );
        }
        s += "segment = [    # right to left, force per segment\n";
        let boxes = self.crash_boxes().map(|b| {
            format!(
                "\n[crash_boxes]\ndepth = {:?}    # m\nblock_stiffness = {:?}    # N/m per box\n",
                b.depth, b.stiffness
            )
        });
        for segment in &beam.segments {
            let unloading = segment.unloading_slope();
            s += &match segment.loading() {
                Loading::ThreePart { ramp, plateau } => {
                    format!(
                        "  {{ ramp = {ramp:?}, plateau = {plateau:?}, unloading = {unloading:?} }},\n"
                    )
                }
                Loading::Table { compression, force } => {
                    let points: Vec<String> = compression
                        .iter()
                        .zip(force)
                        .map(|(d, f)| format!("[{d:?}, {f:?}]"))
                        .collect();
                    format!(
                        "  {{ curve = [{}], unloading = {unloading:?} }},\n",
                        points.join(", ")
                    )
                }
            };
        }
        let t = self.tyres();
        let axle = |a: &Axle| {
            let law = match a.law {
                TyreLaw::Rolling => "rolling",
                TyreLaw::Sliding => "sliding",
            };
            let shape = a
                .shape
                .map_or(String::new(), |c| format!(", shape = {c:?}"));
            format!(
                "{{ rolling_resistance = {:?}, mu_longitudinal = {:?}, mu_lateral = {:?}, law = \"{law}\", cornering_stiffness = {:?}, relaxation_length = {:?}{shape} }}",
                a.rolling_resistance,
                a.mu_longitudinal,
                a.mu_lateral,
                a.cornering_stiffness,
                a.relaxation_length
            )
        };
        s += &format!(
            "]\n\n[tyres]\nslip_speed = {:?}    # m/s\nfront = {}\nrear = {}\n",
            t.slip_speed,
            axle(&t.front),
            axle(&t.rear)
        );
        s + &boxes.unwrap_or_default()
    }
}

#[path = "file_links.rs"]
mod links;

#[cfg(test)]
mod tests {
    use super::*;

    /// The example of the module documentation.
    fn example() -> String {
        let doc = include_str!("file.rs");
        doc.lines()
            .filter_map(|l| l.strip_prefix("//! "))
            .skip_while(|l| !l.starts_with("```toml"))
            .skip(1)
            .take_while(|l| !l.starts_with("```"))
            .map(|l| l.split('#').next().unwrap_or("").to_string() + "\n")
            .collect()
    }

    #[test]
    fn the_documented_example_reads() {
        let car = PlanarCar::parse(&example(), "doc.toml".as_ref()).unwrap();
        assert_eq!(car.name(), Some("mid-size saloon, planar"));
        assert!((car.body().cg_behind_bumper - 2.0).abs() < 1e-12);
        assert!((car.beam().width - 1.6).abs() < 1e-12);
        assert_eq!(car.beam().segments.len(), 10);
        assert!((car.beam().segments[3].loading_force(1.0) - 6e3).abs() < 1e-9);
        assert!((car.tyres().rear.mu_longitudinal - 0.75).abs() < 1e-12);
        let front = car.tyres().front;
        assert_eq!(
            (front.rolling_resistance, front.mu_longitudinal),
            (0.015, 0.8)
        );
    }

    #[test]
    fn a_beam_that_does_not_fit_the_car_is_refused_naming_the_key() {
        let saloon = include_str!("../../../examples/planar/saloon.toml");
        let car = |from: &str, to: &str| {
            PlanarCar::parse(&saloon.replacen(from, to, 1), "c.toml".as_ref())
        };
        assert!(car("", "").is_ok());
        for (from, to, needle) in [
            (
                "width = 1500.0",
                "width = 500.0",
                "c.toml: bumper.side_member_spacing = 1 m is wider than bumper.width = 0.5 m",
            ),
            (
                "width = 1500.0",
                "width = 1e-308",
                "bumper.width = 1e-311 m: expected 0.1 to 10 m",
            ),
            (
                "width = 1500.0",
                "width = 2e4",
                "bumper.width = 20 m: expected 0.1 to 10 m",
            ),
        ] {
            let e = car(from, to).unwrap_err().to_string();
            assert!(e.contains(needle), "{e}");
        }
    }

    #[test]
    fn per_segment_characteristics_read_in_order() {
        let text = "[body]\nmass = 1000.0\nyaw_inertia = 1500.0\ncg_behind_bumper = 2.0\n\
            wheelbase = 2.5\ncg_behind_front_axle = 1.0\ntrack = 1.4\n\
            [bumper]\nwidth = 1.2\nside_member_spacing = 0.9\nsegment = [\n\
            { ramp = 1e5, plateau = 5e3, unloading = 4e5 },\n\
            { curve = [[0.0, 0.0], [0.05, 8e3]], unloading = 4e5 },\n]\n";
        let car = PlanarCar::parse(text, "seg.toml".as_ref()).unwrap();
        assert_eq!(car.beam().segments.len(), 2);
        assert!((car.beam().segments[1].loading_force(0.025) - 4e3).abs() < 1e-9);
        assert!(
            car.left().masses.is_empty(),
            "no chain: the beam sits on the body"
        );
        let bad = text.replace(
            "{ ramp = 1e5, plateau = 5e3, unloading = 4e5 }",
            "{ ramp = 1e5 }",
        );
        let err = PlanarCar::parse(&bad, "seg.toml".as_ref())
            .unwrap_err()
            .to_string();
        assert!(err.contains("bumper.segment[1]"), "{err}");
        let both = text.replace("[bumper]\n", "[bumper]\nsegments = 3\n");
        assert!(PlanarCar::parse(&both, "seg.toml".as_ref()).is_err());
    }

    use crate::car::Layout;
    use bumpsim_core::model::MsdModel;
    use proptest::prelude::*;

    /// A drawn bumper: three-part or a table of 2 to 5 points.
    fn bumper() -> impl Strategy<Value = Bumper> {
        let three = (1e5..1e7f64, 1e3..1e6f64, 1.0..10.0f64)
            .prop_map(|(ramp, plateau, u)| Bumper::three_part(ramp, plateau, ramp * u).unwrap());
        let table = prop::collection::vec((1e-3..0.05f64, 1e2..1e5f64), 1..5).prop_map(|steps| {
            let (mut d, mut f) = (vec![0.0], vec![0.0]);
            for (dd, df) in steps {
                d.push(d[d.len() - 1] + dd);
                f.push(f[f.len() - 1] + df);
            }
            Bumper::table(d, f, 1e9).unwrap()
        });
        prop_oneof![three, table]
    }

    /// A drawn symmetric car with a name TOML must escape (quotes,
    /// backslashes, controls, non-ASCII) or none, its front tyres rolling
    /// with a Magic-Formula shape or without one.
    fn car() -> impl Strategy<Value = PlanarCar> {
        let name = proptest::option::of("[a-zA-Z0-9 \"\\\\\t\u{1}\u{7f}\u{e9}\u{3a9}#=]{0,20}");
        let chain = (1..4usize).prop_flat_map(|dof| {
            (
                prop::collection::vec(1.0..2000.0f64, dof),
                prop::collection::vec(0.0..1e4f64, dof - 1),
                prop::collection::vec(1e4..1e8f64, dof - 1),
            )
        });
        let layout =
            (1e2..5e3f64, 1..20usize, 0.0..1e5f64).prop_map(|(iz, segments, bending)| Layout {
                yaw_inertia: iz,
                segments,
                bending,
                ..Layout::default()
            });
        let shape = proptest::option::of(1.0..2.0f64);
        (chain, bumper(), layout, name, shape).prop_map(
            |((m, c, k), bumper, layout, name, shape)| {
                let chain = MsdModel::new(m, c, k).unwrap();
                let car = PlanarCar::symmetric(&chain, &bumper, &layout).unwrap();
                let mut tyres = *car.tyres();
                tyres.front = Axle {
                    shape,
                    ..Axle::rolling(0.015, 0.8)
                };
                car.with_tyres(tyres).unwrap().with_name(name)
            },
        )
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]

        /// Issue 34: a planar car bumpsim writes reads back equal.
        #[test]
        fn whatever_planar_car_is_written_reads_back_equal(car in car()) {
            let text = car.to_toml();
            let read = PlanarCar::parse(&text, "car.toml".as_ref());
            prop_assert_eq!(read.map_err(|e| format!("{e}\n{text}")), Ok(car));
        }
    }

    #[test]
    fn errors_name_the_file_and_the_parameter() {
        let text = example().replace("yaw_inertia = 2000.0", "yaw_inertia = -1.0");
        let err = PlanarCar::parse(&text, "car.toml".as_ref())
            .unwrap_err()
            .to_string();
        assert!(err.contains("body.yaw_inertia = -1"), "{err}");
        let text = example().replace("track =", "trak =");
        let err = PlanarCar::parse(&text, "car.toml".as_ref())
            .unwrap_err()
            .to_string();
        assert!(err.contains("car.toml") && err.contains("trak"), "{err}");
        let text = example().replace("length_unit = \"mm\"", "length_unit = \"in\"");
        let err = PlanarCar::parse(&text, "car.toml".as_ref())
            .unwrap_err()
            .to_string();
        assert!(err.contains("length_unit"), "{err}");
        let text = example().replace("unloading = 6e6", "unloading = 1e3");
        let err = PlanarCar::parse(&text, "car.toml".as_ref())
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("bumper") && err.contains("ramp slope"),
            "{err}"
        );
    }
}
