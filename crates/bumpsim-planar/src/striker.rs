//! Strikers: a rigid plane at an angle with an overlap, or a pole; fixed (the
//! car moves into it) or carried by a pendulum that moves in a straight line
//! (spec §9).
//!
//! World frame = the car's body frame at t = 0 (x forward towards the struck
//! bumper, y left, origin at the body's CG). Both faces are frictionless: a
//! plane pushes along its normal, a pole along the radius through its axis.
//!
//! - **Plane**: its face is turned counter-clockwise by `angle` θ from
//!   perpendicular to the car's x axis; its normal towards the car is
//!   `n = (−cos θ, −sin θ)`. It covers `overlap` (a fraction of the bumper
//!   width, 0 < overlap ≤ 1) from the `side` given, measured in world y:
//!   left covers `y ≥ w/2 − overlap·w`, right `y ≤ −w/2 + overlap·w`; a full
//!   overlap covers everything. RCAR's structural test on the left corner is
//!   θ = +10°, left, 0.4: the left corner is struck first. The mirror case is
//!   (−θ, other side).
//! - **Pole**: radius `r`, axis at world `y = lateral`.
//!
//! The striker is placed so that it just touches the segments' nearest contact
//! point at t = 0 (a pole's: see `pole_contact_span`). A pendulum starts
//! there at `speed` towards the car (along −x) with the car at rest; a fixed
//! striker is hit by the car at `speed` along +x.
//! The pendulum is guided: it neither turns nor moves sideways; its guide's
//! reactions are reported in the momentum balance.

use crate::barrier::{Absorber, Arc, Shape};
use crate::car::{PlanarCar, PlanarError, require};
use bumpsim_impact::impact::{MASS_RANGE, SPEED_RANGE};
use serde::Serialize;

/// Largest lateral-to-longitudinal ratio of a pole's push on a segment strip
/// grazing the pole (about 72°); keeps the wedge term bounded at the tangent.
const GRAZING: f64 = 3.0;

/// How far a strip's contact point with a pole of radius `r` may move from
/// the strip's centre towards the pole's axis, m, for strips of half-width
/// `h` (width `w = 2h`): `h · clamp(2 w/r − 1, 0, 1)`.
///
/// A strip's characteristic is its force at a crush uniform across its
/// width. Under a pole its crush varies across the width:
///
/// - a strip narrow against the pole (`w ≤ r/2`) sees the pole's profile
///   nearly as a parabola, and the crush at its centre is its mean crush to
///   about `h²/(6r)` near the axis (the midpoint rule), where the crush at its point
///   nearest the axis overstates a flank strip's by about `(2 s h − ⅔ h²)/(2r)`,
///   `s` the centre's distance from the axis. On a 40-strip 1.6 m bumper
///   under a 254 mm pole that was 8.6 mm for a strip centred 60 mm off the
///   axis, and a bumper fitted to a pole
///   test came out 16 % soft (docs/planar.md, "The pole's contact point");
/// - a strip as wide as the pole's radius or wider (`w ≥ r`) is covered
///   only in part, its centre may lie beside the pole, and its deepest
///   point (the point nearest the axis) is the better single crush: it
///   keeps the load under the pole, and a pole narrower than a strip still
///   meets the strip it lies over;
/// - between the two the point moves linearly from one rule to the other.
///
/// A crush integrated across each strip would serve both; until then this
/// rule takes the better of the two single points (w21).
pub(crate) fn pole_contact_span(r: f64, half_width: f64) -> f64 {
    let ratio = 2.0 * half_width / r;
    half_width * (2.0 * ratio - 1.0).clamp(0.0, 1.0)
}

/// A pole's reach ahead of its axis at lateral distance `dy` from it, m, and
/// the push's lateral-to-longitudinal ratio `−d reach / d dy`: the circle of
/// radius `r` until its slope reaches [`GRAZING`], then its tangent line, so
/// the push stays bounded and is still the gradient of the penetration
/// (the contact stays conservative). Reach ≤ 0: the strip misses the pole.
pub(crate) fn pole_profile(r: f64, dy: f64) -> (f64, f64) {
    let s0 = r / (1.0 + GRAZING * GRAZING).sqrt();
    let d0 = GRAZING * s0;
    match dy.abs() <= d0 {
        true => {
            let s = (r * r - dy * dy).sqrt();
            (s, dy / s)
        }
        false => (s0 - (dy.abs() - d0) * GRAZING, GRAZING * dy.signum()),
    }
}

/// Largest pole radius as a multiple of the bumper width.
pub const MAX_POLE_TO_WIDTH: f64 = 1000.0;

/// Which side an overlap is measured from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Side {
    /// From the car's left (+y).
    Left,
    /// From the car's right (−y).
    Right,
}

impl Side {
    /// The other side.
    pub fn other(self) -> Side {
        match self {
            Side::Left => Side::Right,
            Side::Right => Side::Left,
        }
    }
}

/// A side's name that names neither side.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("'{text}': expected left or right")]
pub struct SideError {
    /// The name as given.
    pub text: String,
}

impl std::str::FromStr for Side {
    type Err = SideError;

    /// `left` or `right` (any case).
    fn from_str(text: &str) -> Result<Side, SideError> {
        match text.trim().to_ascii_lowercase().as_str() {
            "left" => Ok(Side::Left),
            "right" => Ok(Side::Right),
            _ => Err(SideError { text: text.into() }),
        }
    }
}

/// The striker's rigid face.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum Face {
    /// A plane at `angle` (rad) covering `overlap` (fraction) of the bumper from `side`.
    Plane {
        /// Angle θ of the face, rad (counter-clockwise, |θ| < 80°).
        angle: f64,
        /// Overlap, fraction of the bumper width (0 < overlap ≤ 1).
        overlap: f64,
        /// Side the overlap is measured from.
        side: Side,
    },
    /// A vertical pole.
    Pole {
        /// Radius, m.
        radius: f64,
        /// Lateral position of its axis, world y, m.
        lateral: f64,
    },
    /// A barrier of finite width whose face is curved in plan, with an
    /// energy absorber on it (the RCAR bumper barrier, [`crate::barrier`]).
    Barrier(Barrier),
}

/// A barrier face curved in plan (convex towards the car) with an optional
/// energy absorber: the RCAR bumper barrier ([`crate::barrier`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Barrier {
    /// Angle θ of the barrier's chord, rad (counter-clockwise, as a plane's).
    pub angle: f64,
    /// Overlap, fraction of the car's bumper width (1: the barrier centred on the car).
    pub overlap: f64,
    /// Side the overlap is measured from.
    pub side: Side,
    /// Radius of the face in plan, m.
    pub radius: f64,
    /// Width of the face (its chord), m.
    pub width: f64,
    /// The energy absorber on the face (None: the bare steel face).
    pub absorber: Option<Absorber>,
}

impl Barrier {
    /// The RCAR bumper barrier (radius 3.4 m, 1.5 m wide, its absorber) at
    /// `angle` (rad) covering `overlap` of the bumper from `side`.
    pub const fn rcar(angle: f64, overlap: f64, side: Side) -> Barrier {
        Barrier {
            angle,
            overlap,
            side,
            radius: 3.4,
            width: 1.5,
            absorber: Some(Absorber::RCAR),
        }
    }
}

impl Face {
    /// A full-width flat barrier.
    pub fn flat() -> Face {
        Face::Plane {
            angle: 0.0,
            overlap: 1.0,
            side: Side::Left,
        }
    }

    /// A plane in a test protocol's terms: `angle` in degrees
    /// (counter-clockwise), `overlap` in percent of the bumper width, from
    /// `side`. Ranges are checked when the striker is placed against a car.
    pub fn plane_in_degrees(angle: f64, overlap: f64, side: Side) -> Face {
        Face::Plane {
            angle: angle.to_radians(),
            overlap: overlap / 100.0,
            side,
        }
    }

    /// A pole of `diameter` (m) with its axis at world `lateral` (m).
    pub fn pole_of_diameter(diameter: f64, lateral: f64) -> Face {
        Face::Pole {
            radius: 0.5 * diameter,
            lateral,
        }
    }

    /// The mirror image about the car's x axis.
    pub fn mirrored(self) -> Face {
        match self {
            Face::Plane {
                angle,
                overlap,
                side,
            } => Face::Plane {
                angle: -angle,
                overlap,
                side: side.other(),
            },
            Face::Pole { radius, lateral } => Face::Pole {
                radius,
                lateral: -lateral,
            },
            Face::Barrier(b) => Face::Barrier(Barrier {
                angle: -b.angle,
                side: b.side.other(),
                ..b
            }),
        }
    }
}

/// How the striker and the car move.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum Motion {
    /// The car moves at `speed` (m/s, along +x) into the fixed face.
    Fixed {
        /// Car speed, m/s.
        speed: f64,
    },
    /// A pendulum of `mass` (kg) carries the face at `speed` (m/s, along −x)
    /// into the car at rest.
    Pendulum {
        /// Pendulum mass, kg.
        mass: f64,
        /// Pendulum speed, m/s.
        speed: f64,
    },
}

impl Motion {
    /// The closing speed, m/s (the car's or the pendulum's).
    pub fn speed(&self) -> f64 {
        match *self {
            Motion::Fixed { speed } | Motion::Pendulum { speed, .. } => speed,
        }
    }
}

/// A face and its motion.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Striker {
    /// The face.
    pub face: Face,
    /// The motion.
    pub motion: Motion,
}

impl Striker {
    /// The car at `speed` m/s into a fixed `face`.
    pub fn barrier(face: Face, speed: f64) -> Striker {
        Striker {
            face,
            motion: Motion::Fixed { speed },
        }
    }

    /// A pendulum of `mass` kg carrying `face` at `speed` m/s into the car at rest.
    pub fn pendulum(face: Face, mass: f64, speed: f64) -> Striker {
        Striker {
            face,
            motion: Motion::Pendulum { mass, speed },
        }
    }

    /// The same striker at another `speed`, m/s (car or pendulum).
    pub fn with_speed(self, speed: f64) -> Striker {
        let motion = match self.motion {
            Motion::Fixed { .. } => Motion::Fixed { speed },
            Motion::Pendulum { mass, .. } => Motion::Pendulum { mass, speed },
        };
        Striker { motion, ..self }
    }

    /// The mirror image about the car's x axis.
    pub fn mirrored(self) -> Striker {
        Striker {
            face: self.face.mirrored(),
            ..self
        }
    }
}

/// A face placed against a car, in the world frame at pendulum travel 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Placed {
    /// Points p with `normal·p < offset` are inside; covered when
    /// `sign·(p_y − edge) ≥ 0` (`sign` 0: everywhere).
    Plane {
        normal: [f64; 2],
        offset: f64,
        edge: f64,
        sign: f64,
    },
    /// Axis at `centre`.
    Pole { centre: [f64; 2], radius: f64 },
    /// A curved face and its absorber.
    Barrier {
        arc: Arc,
        absorber: Option<Absorber>,
    },
}

impl Placed {
    /// The face after the pendulum travelled `s` along −x.
    pub(crate) fn moved(&self, s: f64) -> Placed {
        match *self {
            Placed::Plane {
                normal,
                offset,
                edge,
                sign,
            } => Placed::Plane {
                normal,
                offset: offset - s * normal[0],
                edge,
                sign,
            },
            Placed::Pole { centre, radius } => Placed::Pole {
                centre: [centre[0] - s, centre[1]],
                radius,
            },
            Placed::Barrier { mut arc, absorber } => {
                arc.centre[0] -= s;
                Placed::Barrier { arc, absorber }
            }
        }
    }

    /// A reference point of the face (for the pendulum's angular momentum), world, m.
    pub(crate) fn reference(&self) -> [f64; 2] {
        match *self {
            Placed::Plane { normal, offset, .. } => [offset * normal[0], offset * normal[1]],
            Placed::Pole { centre, .. } => centre,
            Placed::Barrier { arc, .. } => arc.apex(),
        }
    }
}

/// Checks the striker and places it against the car at rest in its initial pose.
pub(crate) fn place(car: &PlanarCar, striker: &Striker) -> Result<Placed, PlanarError> {
    // the 1-D impact's ranges (1e5 m/s gave a 1e8 mm crush, exit 0)
    let (mass, speed) = match striker.motion {
        Motion::Fixed { speed } => (1.0, speed),
        Motion::Pendulum { mass, speed } => (mass, speed),
    };
    require(
        "striker mass",
        mass,
        "kg",
        "must be from 0.001 to 1e7 kg (limit bumpsim_impact::impact::MASS_RANGE: 1 g to 10 000 t; beyond it the striker kinetic energy overflows or underflows)",
        MASS_RANGE.contains(&mass),
    )?;
    require(
        "speed",
        speed,
        "m/s",
        "must be from 0.001 to 1000 m/s (limit bumpsim_impact::impact::SPEED_RANGE: 1 mm/s to 3600 km/h; an impact needs a closing speed, and below it the striker kinetic energy is too small to resolve)",
        SPEED_RANGE.contains(&speed),
    )?;
    let x_f = car.body().cg_behind_bumper;
    let half = 0.5 * car.beam().width;
    match striker.face {
        Face::Plane {
            angle,
            overlap,
            side,
        } => place_plane(car, angle, overlap, side, x_f),
        Face::Pole { radius, lateral } => {
            // a pole far wider than the bumper is a flat face to it, and its
            // reach (≈ radius) swamps the millimetre crush in the contact
            // geometry: 1e6 m already broke a centred hit's symmetry, 1e308 m
            // overflowed to a pole that never touched (exit 0, "diameter inf mm")
            let largest = MAX_POLE_TO_WIDTH * car.beam().width;
            require(
                "pole radius",
                radius,
                "m",
                &format!(
                    "must be positive and at most {MAX_POLE_TO_WIDTH} times the bumper width ({largest} m): a larger pole is a flat face to the bumper, use a plane"
                ),
                radius > 0.0 && radius <= largest,
            )?;
            require(
                "pole lateral position",
                lateral,
                "m",
                &format!(
                    "the pole cannot hit: |y| must be below half the bumper width plus the radius, {} m",
                    half + radius
                ),
                lateral.abs() < half + radius,
            )?;
            place_pole(car, radius, lateral, x_f)
        }
        Face::Barrier(b) => place_barrier(car, &b, x_f),
    }
}

fn place_barrier(car: &PlanarCar, b: &Barrier, x_f: f64) -> Result<Placed, PlanarError> {
    if let Some(absorber) = &b.absorber {
        absorber.check()?;
    }
    let shape = Shape {
        angle: b.angle,
        overlap: b.overlap,
        side: if b.side == Side::Left { 1.0 } else { -1.0 },
        radius: b.radius,
        width: b.width,
    };
    let arc = crate::barrier::place(car, &shape, x_f)?;
    Ok(Placed::Barrier {
        arc,
        absorber: b.absorber,
    })
}

fn place_plane(
    car: &PlanarCar,
    angle: f64,
    overlap: f64,
    side: Side,
    x_f: f64,
) -> Result<Placed, PlanarError> {
    require(
        "barrier angle",
        angle,
        "rad",
        "must lie within ±80° (±1.396 rad)",
        angle.abs() <= 80f64.to_radians(),
    )?;
    require(
        "overlap",
        overlap,
        "fraction of the bumper width",
        "must lie in 0 < overlap ≤ 1 (0.4 is 40 %)",
        overlap > 0.0 && overlap <= 1.0,
    )?;
    let w = car.beam().width;
    let (edge, sign) = match (overlap >= 1.0, side) {
        (true, _) => (0.0, 0.0),
        (false, Side::Left) => (0.5 * w - overlap * w, 1.0),
        (false, Side::Right) => (-0.5 * w + overlap * w, -1.0),
    };
    let normal = [-angle.cos(), -angle.sin()];
    let offset = (0..car.beam().segments.len())
        .map(|j| car.segment_centre(j))
        .filter(|&y| sign * (y - edge) >= 0.0)
        .map(|y| normal[0] * x_f + normal[1] * y)
        .fold(f64::INFINITY, f64::min);
    if !offset.is_finite() {
        return Err(PlanarError::NoContact {
            reason: format!(
                "an overlap of {:.1} % of the {w} m bumper covers no segment centre; raise the overlap or the number of segments",
                overlap * 100.0
            ),
        });
    }
    Ok(Placed::Plane {
        normal,
        offset,
        edge,
        sign,
    })
}

fn place_pole(car: &PlanarCar, radius: f64, lateral: f64, x_f: f64) -> Result<Placed, PlanarError> {
    // the pole's axis sits where its deepest reach into the strips'
    // contact points is zero
    let h = pole_contact_span(radius, 0.5 * car.segment_width());
    let reach = (0..car.beam().segments.len())
        .map(|j| {
            let y = car.segment_centre(j);
            pole_profile(radius, lateral.clamp(y - h, y + h) - lateral).0
        })
        .fold(f64::NEG_INFINITY, f64::max);
    if reach <= 0.0 {
        return Err(PlanarError::NoContact {
            reason: format!(
                "a pole of radius {radius} m at y = {lateral} m passes beside the {} m bumper",
                car.beam().width
            ),
        });
    }
    Ok(Placed::Pole {
        centre: [x_f + reach, lateral],
        radius,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::car::Layout;
    use bumpsim_core::model::MsdModel;
    use bumpsim_impact::bumper::Bumper;

    fn car() -> PlanarCar {
        let chain = MsdModel::new(vec![1000.0], vec![], vec![]).unwrap();
        let bumper = Bumper::three_part(1e6, 5e4, 4e6).unwrap();
        PlanarCar::symmetric(&chain, &bumper, &Layout::default()).unwrap()
    }

    #[test]
    fn bad_strikers_are_refused_with_reasons() {
        let plane = |overlap| {
            Striker::barrier(
                Face::Plane {
                    angle: 0.1,
                    overlap,
                    side: Side::Left,
                },
                2.0,
            )
        };
        for overlap in [0.0, -0.2, 1.5, f64::NAN] {
            let err = place(&car(), &plane(overlap)).unwrap_err().to_string();
            assert!(err.contains("overlap"), "{err}");
        }
        let err = place(&car(), &plane(0.01)).unwrap_err().to_string();
        assert!(err.contains("never touches"), "{err}");
        let pole = Striker::barrier(
            Face::Pole {
                radius: 0.15,
                lateral: 1.2,
            },
            2.0,
        );
        let err = place(&car(), &pole).unwrap_err().to_string();
        assert!(err.contains("cannot hit"), "{err}");
        let err = place(&car(), &Striker::pendulum(Face::flat(), -1.0, 2.0)).unwrap_err();
        assert!(err.to_string().contains("striker mass"), "{err}"); // a pole of 1e308 m diameter overflowed into one that never touched
        for diameter in [1e308, 1e7] {
            let pole = Striker::barrier(Face::pole_of_diameter(diameter, 0.0), 2.0);
            let err = place(&car(), &pole).unwrap_err().to_string();
            assert!(
                err.contains("pole radius") && err.contains("1000 times the bumper width"),
                "{err}"
            );
        }
        let big = Striker::barrier(Face::pole_of_diameter(2e3 * 1.6, 0.0), 2.0);
        assert!(place(&car(), &big).is_ok(), "the limit itself is allowed");
    }

    #[test]
    fn speeds_and_masses_outside_the_impact_ranges_are_refused() {
        for speed in [1e5, 1e-308, 1e-4, -1.0] {
            let err = place(&car(), &Striker::barrier(Face::flat(), speed)).unwrap_err();
            assert!(err.to_string().contains("from 0.001 to 1000 m/s"), "{err}");
        }
        for mass in [1e12, 1e-308, 1e-4] {
            let err = place(&car(), &Striker::pendulum(Face::flat(), mass, 2.0)).unwrap_err();
            assert!(err.to_string().contains("from 0.001 to 1e7 kg"), "{err}");
        }
        for (mass, speed) in [(1e-3, 1e-3), (1e7, 1e3)] {
            assert!(place(&car(), &Striker::pendulum(Face::flat(), mass, speed)).is_ok());
        }
    }

    #[test]
    fn faces_touch_the_nearest_segment() {
        let rcar = Striker::barrier(
            Face::Plane {
                angle: 10f64.to_radians(),
                overlap: 0.4,
                side: Side::Left,
            },
            2.0,
        );
        let Placed::Plane { normal, offset, .. } = place(&car(), &rcar).unwrap() else {
            panic!("a plane")
        };
        // the left-most segment centre (y = 0.72 m) on the bumper line (x = 2 m) touches
        let touch = normal[0] * 2.0 + normal[1] * 0.72;
        assert!((touch - offset).abs() < 1e-12);
        // ten 0.16 m strips, wider than the pole's radius: their points
        // nearest the axis
        assert!((centred_pole_axis(0.15) - 2.15).abs() < 1e-12);
    }

    /// The x of a centred pole's axis of `radius` placed before [`car`].
    fn centred_pole_axis(radius: f64) -> f64 {
        let pole = Striker::barrier(
            Face::Pole {
                radius,
                lateral: 0.0,
            },
            2.0,
        );
        let Placed::Pole { centre, .. } = place(&car(), &pole).unwrap() else {
            panic!("a pole")
        };
        centre[0]
    }

    #[test]
    fn a_pole_crushes_a_narrow_strip_at_its_centre_and_a_wide_one_at_its_deepest_point() {
        // 40 mm strips under a 254 mm pole: the strip's centre (midpoint rule)
        assert_eq!(pole_contact_span(0.127, 0.02), 0.0);
        // strips as wide as the radius and wider: the point nearest the axis
        assert_eq!(pole_contact_span(0.04, 0.02), 0.02);
        assert_eq!(pole_contact_span(0.03, 0.08), 0.08);
        // between: w/r = 2/3 moves a third of the way
        assert!((pole_contact_span(0.06, 0.02) - 0.02 / 3.0).abs() < 1e-15);
        // a 60 mm pole between two 0.16 m strips' centres (0.08 m from its
        // axis, beyond its radius) still meets both, at its axis
        assert!((centred_pole_axis(0.03) - 2.03).abs() < 1e-12);
    }
}
