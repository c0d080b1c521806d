//! The planar car (spec §9): a rigid body, a left and a right MSD chain, a
//! segmented bumper beam and tyres.
//!
//! Frame: body x forward (towards the struck bumper), y left, origin at the
//! centre of gravity (CG) of the rigid body. SI units: kg, m, N, s, rad.
//!
//! - **Body**: mass `M` and yaw inertia `I_z` about its own CG, which lies
//!   `cg_behind_bumper` behind the bumper line (the beam's undeformed front,
//!   body x = `x_f`).
//! - **Side chains**: at `y = ±b` (`b` = half the side-member spacing), each a
//!   1-D chain of spec §2 whose masses `m_1..m_k` move along the body x axis
//!   (all lumped on the bumper line) and whose last link (`k_k`, `c_k`) joins
//!   `m_k` to the body. Mass 1 carries the bumper beam. A side with no masses
//!   attaches the beam to the body directly.
//! - **Bumper beam**: `S` segments of equal width across `width`, each with a
//!   characteristic of spec §5 (three-part or tabulated, elastic unloading;
//!   force per segment) between the striker and the beam line. The beam line is
//!   a lever through the two side-member tips, so a segment force at lateral
//!   position `η` loads the left tip with the share `α = (η + b)/(2b)` and the
//!   right tip with `1 − α` (overhang: α outside 0..1). Bending couples the
//!   segments through the discrete energy `½ k_b Σ (d_{j−1} − 2 d_j + d_{j+1})²`
//!   of the crush curvature; it vanishes for a uniform crush and for a crush
//!   growing linearly across the beam (an angled wall), and stiffens a local
//!   dent (pole, overlap edge). A loaded segment that leaves the face keeps
//!   its deflection in this energy, so it never jumps (see `docs/planar.md`).
//! - **Crash boxes**: each side's first link (mass 1 to mass 2, or to the
//!   body) is its crash box. With a crash-box [`Block`] (`[crash_boxes]`),
//!   a link compressed `e = −(u_1 − u_2)` past the depth `D` adds the block
//!   force `k_block (e − D)` (elastic), the folded box passing the load on
//!   into the rail behind it (issue 45).
//! - **Tyres**: four wheels at the axles (`±track/2`), static normal loads from
//!   the total mass and the CG position, regularised Coulomb friction
//!   `F = −μ N v / √(|v|² + v_s²)` per direction with `μ_x`, `μ_y` per axle
//!   (μ = 0: no friction).
//!
//! [`PlanarCar::symmetric`] makes a planar car from a 1-D chain: the chain's
//! last mass becomes the body, the others are halved onto the two sides with
//! halved springs and dampers, and the bumper is split equally over the
//! segments, so that a full-width flat impact reduces exactly to the 1-D model.

use bumpsim_core::model::MsdModel;
use bumpsim_core::units::{Dimension, format_quantity};
use bumpsim_impact::bumper::{Bumper, BumperError, BumperState};
use serde::Serialize;

/// Standard gravity, m/s².
pub const GRAVITY: f64 = 9.80665;

/// Why a planar car, striker or simulation is not valid.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PlanarError {
    /// A parameter is out of range.
    #[error("{name} = {} {unit}: {expected}", crate::echo::Echo(*value))]
    Parameter {
        /// The parameter, as named in the car file.
        name: String,
        /// The value given.
        value: f64,
        /// Its unit.
        unit: &'static str,
        /// What is allowed.
        expected: String,
    },
    /// A needed part of the car file is missing.
    #[error("{name}: {expected}")]
    Missing {
        /// The part, as named in the car file.
        name: String,
        /// What is needed.
        expected: String,
    },
    /// A bumper characteristic is not valid.
    #[error("{name}: {source}")]
    Bumper {
        /// Which characteristic (e.g. `bumper.segment[3]`).
        name: String,
        /// Why.
        source: BumperError,
    },
    /// The file cannot be read or parsed.
    #[error("{path}: {message}")]
    File {
        /// The file.
        path: String,
        /// What is wrong (with line and column where the parser gives them).
        message: String,
    },
    /// The integration diverged: the state grew without bound (non-finite,
    /// beyond 1 km or 1000 rad, or twice the energy the run started with),
    /// which a car of plausible parts does not do at the step from its
    /// stiffest element.
    #[error(
        "the integration diverged at t = {} with a step of {}: check the car for implausible geometry or stiffness (an element far stiffer or lighter than a car's, side members far apart)",
        format_quantity(*time, Dimension::Time),
        format_quantity(*step, Dimension::Time)
    )]
    Diverged {
        /// Time of the first diverged sample, s.
        time: f64,
        /// The integration step the run took, s.
        step: f64,
    },
    /// A load case cannot be built from its channels.
    #[error("case '{case}': {message}")]
    Case {
        /// The case.
        case: String,
        /// What is wrong (names the channel).
        message: String,
    },
    /// The striker cannot touch the car.
    #[error("the striker never touches the car: {reason}")]
    NoContact {
        /// Why.
        reason: String,
    },
}

/// Most segments a bumper beam may have (docs/limits.md).
pub const MAX_SEGMENTS: usize = 1000;

/// Bumper widths a planar car file (and `impact --width`) may give, m:
/// 0.1 m (a narrower beam is no car's; `width = 1e-308` was accepted) to
/// 10 m (beyond any road vehicle's 2.6 m). docs/limits.md.
pub const WIDTH_RANGE: std::ops::RangeInclusive<f64> = 0.1..=10.0;

pub(crate) fn parameter(name: &str, value: f64, unit: &'static str, expected: &str) -> PlanarError {
    PlanarError::Parameter {
        name: name.into(),
        value,
        unit,
        expected: expected.into(),
    }
}

/// `Ok` when `value` is finite and `ok` holds, else a parameter error.
pub(crate) fn require(
    name: &str,
    value: f64,
    unit: &'static str,
    expected: &str,
    ok: bool,
) -> Result<(), PlanarError> {
    match value.is_finite() && ok {
        true => Ok(()),
        false => Err(parameter(name, value, unit, expected)),
    }
}

fn positive(name: &str, value: f64, unit: &'static str) -> Result<(), PlanarError> {
    require(
        name,
        value,
        unit,
        "must be a positive finite number",
        value > 0.0,
    )
}

/// The rigid body.
// Deserialize: Python's pickled impact keeps its car's body (a PlanarCar
// is still validated whole when built from one)
#[derive(Debug, Clone, Copy, PartialEq, Serialize, serde::Deserialize)]
pub struct Body {
    /// Mass M, kg.
    pub mass: f64,
    /// Yaw inertia I_z about the body's CG, kg·m².
    pub yaw_inertia: f64,
    /// Distance from the bumper line back to the CG, m (> 0).
    pub cg_behind_bumper: f64,
    /// Wheelbase, m.
    pub wheelbase: f64,
    /// Distance from the front axle back to the CG, m (0 < a < wheelbase).
    pub cg_behind_front_axle: f64,
    /// Track (wheel centre to wheel centre), m.
    pub track: f64,
}

/// One side's chain: masses 1..k along the body x axis, link j joins mass j
/// to mass j+1 and the last link joins mass k to the body.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct SideChain {
    /// Masses, kg (mass 1 carries the bumper beam).
    pub masses: Vec<f64>,
    /// Dampers, N·s/m (one per mass).
    pub dampers: Vec<f64>,
    /// Springs, N/m (one per mass); with `links`, each link's initial slope.
    pub springs: Vec<f64>,
    /// Nonlinear links ([`bumpsim_core::link`], issue 46), one per mass
    /// (link j behind mass j), or empty: every link linear with `springs`.
    /// [`SideChain::linked`] builds a chain from its links.
    #[serde(
        skip_serializing_if = "Vec::is_empty",
        serialize_with = "links::described"
    )]
    pub links: Vec<bumpsim_core::link::Link>,
}

/// The segmented bumper beam.
#[derive(Debug, Clone, PartialEq)]
pub struct Beam {
    /// Width of the bumper face, m (centred on the car's axis).
    pub width: f64,
    /// Lateral distance between the side members, 2b, m.
    pub side_member_spacing: f64,
    /// One characteristic per segment, from right (−y) to left (+y); force per segment.
    pub segments: Vec<Bumper>,
    /// Bending coupling k_b of the crush curvature, N/m (≥ 0).
    pub bending: f64,
    /// The end of the segments' stroke (None: a segment crushes without end).
    pub block: Option<Block>,
}

/// Default whole-bumper block stiffness, N/m (50 kN/mm): an assumption
/// chosen here, the low end of a crash box's elastic axial stiffness before
/// it folds (E·A/L of a steel box of 1.5 mm walls, 60 mm square and 200 mm
/// long is about 380 kN/mm; an aluminium one of 2 mm walls, 80 mm square
/// and 150 mm long about 300 kN/mm), kept soft enough that the explicit
/// step stays of the order of the bumper's own (docs/planar.md).
pub const DEFAULT_BLOCK_STIFFNESS: f64 = 5e7;

/// Default block stiffness of a crash box, N/m per box (100 kN/mm): an
/// assumption chosen here, the order of the elastic axial stiffness E·A/L
/// of the side member behind it, into which a crash box folded to its end
/// passes the force (a steel rail, E = 210 GPa, of 2 mm walls, 100 × 60 mm
/// and 1.2 m long: 2.1e11 · 6.4e-4 / 1.2 ≈ 112 kN/mm; the folded box's
/// own solid stack is stiffer and in series). docs/planar.md.
pub const DEFAULT_CRASH_BOX_BLOCK_STIFFNESS: f64 = 1e8;

/// The end of a bumper segment's stroke (issue 45): beyond its `depth` the
/// crushed beam blocks on the crash boxes and rails, and the segment's force
/// grows by `stiffness · (crush − depth)` on top of its characteristic.
/// Elastic: the energy it stores is returned on unloading.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Block {
    /// The segment's crushable depth, m (> 0).
    pub depth: f64,
    /// The block's stiffness per segment, N/m (> 0).
    pub stiffness: f64,
}

impl Block {
    /// The block's force at a segment crush `crush` (m), N.
    pub fn force(&self, crush: f64) -> f64 {
        self.stiffness * (crush - self.depth).max(0.0)
    }
}

/// A validated planar car.
#[derive(Debug, Clone, PartialEq)]
pub struct PlanarCar {
    name: Option<String>,
    body: Body,
    left: SideChain,
    right: SideChain,
    beam: Beam,
    tyres: Tyres,
    crash_boxes: Option<Block>,
    damage: Vec<BumperState>,
    contact_rate: f64,
    /// The width the segments' contact points span, m (`car_contact.rs`).
    effective_width: f64,
}

/// Geometry and tyres that turn a 1-D chain into a symmetric planar car.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Layout {
    /// Yaw inertia of the body, kg·m².
    pub yaw_inertia: f64,
    /// CG behind the bumper line, m.
    pub cg_behind_bumper: f64,
    /// Wheelbase, m.
    pub wheelbase: f64,
    /// Front axle to CG, m.
    pub cg_behind_front_axle: f64,
    /// Track, m.
    pub track: f64,
    /// Bumper width, m.
    pub bumper_width: f64,
    /// Side-member spacing 2b, m.
    pub side_member_spacing: f64,
    /// Number of bumper segments.
    pub segments: usize,
    /// Bending coupling, N/m.
    pub bending: f64,
    /// Tyres.
    pub tyres: Tyres,
}

impl Default for Layout {
    /// A mid-size saloon of the thesis's time (order of a Volvo S40: 4.5 m
    /// long, 1.5 m track, 2.6 m wheelbase); I_z = 2000 kg·m², ten segments,
    /// frictionless tyres.
    fn default() -> Self {
        Layout {
            yaw_inertia: 2000.0,
            cg_behind_bumper: 2.0,
            wheelbase: 2.6,
            cg_behind_front_axle: 1.1,
            track: 1.5,
            bumper_width: 1.6,
            side_member_spacing: 1.0,
            segments: 10,
            bending: 0.0,
            tyres: Tyres::default(),
        }
    }
}

/// The bumper with its forces scaled by `factor` (> 0): [`Bumper::scaled`].
pub fn scaled(bumper: &Bumper, factor: f64) -> Result<Bumper, BumperError> {
    bumper.scaled(factor)
}

impl PlanarCar {
    /// Validates and builds a planar car; errors name the parameter.
    pub fn new(
        body: Body,
        left: SideChain,
        right: SideChain,
        beam: Beam,
        tyres: Tyres,
    ) -> Result<PlanarCar, PlanarError> {
        check_body(&body)?;
        check_chain("left", &left)?;
        check_chain("right", &right)?;
        check_beam(&beam)?;
        check_tyres(&tyres)?;
        Ok(PlanarCar {
            name: None,
            body,
            left,
            right,
            effective_width: beam.width,
            beam,
            tyres,
            crash_boxes: None,
            damage: Vec::new(),
            contact_rate: 0.0,
        })
    }

    /// The symmetric planar car of a 1-D chain: the last mass is the body,
    /// the others, the springs and the dampers are halved onto each side, and
    /// the bumper's force is split equally over `layout.segments` segments.
    pub fn symmetric(
        chain: &MsdModel,
        bumper: &Bumper,
        layout: &Layout,
    ) -> Result<PlanarCar, PlanarError> {
        let n = chain.dof();
        let half = |v: &[f64]| v.iter().map(|x| 0.5 * x).collect::<Vec<_>>();
        let side = SideChain {
            masses: half(&chain.masses()[..n - 1]),
            dampers: half(chain.dampers()),
            springs: half(chain.springs()),
            links: Vec::new(),
        };
        if layout.segments == 0 {
            return Err(parameter(
                "bumper.segments",
                0.0,
                "1",
                "at least one segment",
            ));
        }
        let segment = bumper
            .scaled(1.0 / layout.segments as f64)
            .map_err(|source| PlanarError::Bumper {
                name: "bumper".into(),
                source,
            })?;
        let body = Body {
            mass: chain.masses()[n - 1],
            yaw_inertia: layout.yaw_inertia,
            cg_behind_bumper: layout.cg_behind_bumper,
            wheelbase: layout.wheelbase,
            cg_behind_front_axle: layout.cg_behind_front_axle,
            track: layout.track,
        };
        let beam = Beam {
            width: layout.bumper_width,
            side_member_spacing: layout.side_member_spacing,
            segments: vec![segment; layout.segments],
            bending: layout.bending,
            block: None,
        };
        PlanarCar::new(body, side.clone(), side, beam, layout.tyres)
    }

    /// [`PlanarCar::symmetric`] of a layout a user gave (`impact --width`):
    /// its beam, as a car file's, from 0.1 to 10 m wide
    /// ([`WIDTH_RANGE`]) and at least as wide as its side-member
    /// spacing (`--width 1e-308` ran an angled impact on a beam narrower than
    /// its rails). `symmetric` itself also builds test cars outside them.
    ///
    /// ```
    /// use bumpsim_planar::car::{Layout, PlanarCar};
    /// let chain = bumpsim_core::model::MsdModel::new(vec![16.0, 1300.0], vec![4e3], vec![6e6]).unwrap();
    /// let bumper = bumpsim_impact::bumper::Bumper::three_part(3e6, 200e3, 2e7).unwrap();
    /// let narrow = Layout { bumper_width: 0.5, ..Layout::default() };
    /// assert!(PlanarCar::symmetric_fitted(&chain, &bumper, &narrow).is_err());
    /// ```
    pub fn symmetric_fitted(
        chain: &MsdModel,
        bumper: &Bumper,
        layout: &Layout,
    ) -> Result<PlanarCar, PlanarError> {
        let (w, spacing) = (layout.bumper_width, layout.side_member_spacing);
        let (low, high) = WIDTH_RANGE.into_inner();
        let expected = format!(
            "from {low} to {high} m (WIDTH_RANGE) and at least the side-member spacing, {spacing} m"
        );
        let fits = WIDTH_RANGE.contains(&w) && spacing <= w;
        require("bumper width", w, "m", &expected, fits)?;
        PlanarCar::symmetric(chain, bumper, layout)
    }

    /// The same car with its segments blocking at `block` (checked).
    pub fn with_block(mut self, block: Option<Block>) -> Result<PlanarCar, PlanarError> {
        self.beam.block = block;
        check_beam(&self.beam)?;
        Ok(self)
    }

    /// The same car with its crash boxes (each side's first chain link)
    /// blocking at `block` (checked: a positive depth and stiffness).
    pub fn with_crash_boxes(mut self, block: Option<Block>) -> Result<PlanarCar, PlanarError> {
        if let Some(b) = block {
            positive("crash_boxes.depth", b.depth, "m")?;
            positive("crash_boxes.block_stiffness", b.stiffness, "N/m per box")?;
        }
        self.crash_boxes = block;
        Ok(self)
    }

    /// The end of the crash boxes' stroke (None: they compress without end).
    pub fn crash_boxes(&self) -> Option<Block> {
        self.crash_boxes
    }

    /// The same car with a name.
    pub fn with_name(mut self, name: Option<String>) -> PlanarCar {
        self.name = name;
        self
    }

    /// The same car with both axles' tyres under `law` (a protocol's
    /// condition: brakes released and in neutral, or locked).
    pub fn with_tyre_law(mut self, law: TyreLaw) -> PlanarCar {
        self.tyres.front.law = law;
        self.tyres.rear.law = law;
        self
    }

    /// The same car on `tyres`, checked as [`PlanarCar::new`] checks them.
    pub fn with_tyres(mut self, tyres: Tyres) -> Result<PlanarCar, PlanarError> {
        check_tyres(&tyres)?;
        self.tyres = tyres;
        Ok(self)
    }

    /// The name, if any.
    pub fn name(&self) -> Option<&str> {
        self.name.as_deref()
    }

    /// The rigid body.
    pub fn body(&self) -> &Body {
        &self.body
    }

    /// The left chain (y = +b).
    pub fn left(&self) -> &SideChain {
        &self.left
    }

    /// The right chain (y = −b).
    pub fn right(&self) -> &SideChain {
        &self.right
    }

    /// The bumper beam.
    pub fn beam(&self) -> &Beam {
        &self.beam
    }

    /// The tyres.
    pub fn tyres(&self) -> &Tyres {
        &self.tyres
    }

    /// Total mass (body and both chains), kg.
    pub fn total_mass(&self) -> f64 {
        self.body.mass
            + self.left.masses.iter().sum::<f64>()
            + self.right.masses.iter().sum::<f64>()
    }

    /// Lateral centre of segment `j` (0 = rightmost) across the
    /// [`PlanarCar::effective_width`], m.
    pub fn segment_centre(&self, j: usize) -> f64 {
        let s = self.beam.segments.len() as f64;
        let w = self.effective_width;
        -0.5 * w + (j as f64 + 0.5) * w / s
    }

    /// Width of one segment's contact strip, m (the effective width's share).
    pub fn segment_width(&self) -> f64 {
        self.effective_width / self.beam.segments.len() as f64
    }

    /// The car mirrored about its x axis: left and right chains swap and the
    /// segments reverse.
    pub fn mirrored(&self) -> PlanarCar {
        let mut car = self.clone();
        std::mem::swap(&mut car.left, &mut car.right);
        car.beam.segments.reverse();
        car.damage.reverse();
        car
    }
}

fn check_body(body: &Body) -> Result<(), PlanarError> {
    positive("body.mass", body.mass, "kg")?;
    positive("body.yaw_inertia", body.yaw_inertia, "kg·m²")?;
    positive("body.cg_behind_bumper", body.cg_behind_bumper, "m")?;
    positive("body.wheelbase", body.wheelbase, "m")?;
    positive("body.track", body.track, "m")?;
    require(
        "body.cg_behind_front_axle",
        body.cg_behind_front_axle,
        "m",
        &format!(
            "the CG must lie between the axles: 0 < a < wheelbase = {} m",
            body.wheelbase
        ),
        body.cg_behind_front_axle > 0.0 && body.cg_behind_front_axle < body.wheelbase,
    )
}

fn check_chain(side: &str, chain: &SideChain) -> Result<(), PlanarError> {
    let n = chain.masses.len();
    // the limit of every car model (docs/limits.md): 100 000 masses a side
    // passed and ran for minutes (each step is linear in the masses)
    let most = bumpsim_core::model::MAX_DOF;
    require(
        &format!("{side}.masses"),
        n as f64,
        "masses",
        &format!("at most {most} masses a side (MAX_DOF, docs/limits.md)"),
        n <= most,
    )?;
    for (kind, len) in [
        ("dampers", chain.dampers.len()),
        ("springs", chain.springs.len()),
    ] {
        require(
            &format!("{side}.{kind}"),
            len as f64,
            "values",
            &format!("one per mass ({n}): the last joins mass {n} to the body"),
            len == n,
        )?;
    }
    for (i, &m) in chain.masses.iter().enumerate() {
        positive(&format!("{side}.masses[{}]", i + 1), m, "kg")?;
    }
    for (i, &k) in chain.springs.iter().enumerate() {
        positive(&format!("{side}.springs[{}]", i + 1), k, "N/m")?;
    }
    links::check(side, chain)?;
    for (i, &c) in chain.dampers.iter().enumerate() {
        let name = format!("{side}.dampers[{}]", i + 1);
        require(
            &name,
            c,
            "N·s/m",
            "must be finite and not negative",
            c >= 0.0,
        )?;
    }
    Ok(())
}

fn check_beam(beam: &Beam) -> Result<(), PlanarError> {
    positive("bumper.width", beam.width, "m")?;
    positive("bumper.side_member_spacing", beam.side_member_spacing, "m")?;
    require(
        "bumper.bending",
        beam.bending,
        "N/m",
        "must be finite and not negative",
        beam.bending >= 0.0,
    )?;
    if let Some(block) = beam.block {
        positive("bumper.depth", block.depth, "m")?;
        positive("bumper.block_stiffness", block.stiffness, "N/m per segment")?;
    }
    require(
        "bumper.segments",
        beam.segments.len() as f64,
        "1",
        &format!("between 1 and {MAX_SEGMENTS} segments"),
        (1..=MAX_SEGMENTS).contains(&beam.segments.len()),
    )
}

#[path = "car_tyres.rs"]
mod tyres;
use tyres::check_tyres;
pub use tyres::{Axle, CORNERING_STIFFNESS, RELAXATION_LENGTH, TyreLaw, Tyres};

#[path = "car_history.rs"]
mod history;

#[path = "car_contact.rs"]
mod contact;
pub use contact::{ARM_RANGE, EFFECTIVE_WIDTH_RANGE, MAX_CONTACT_RATE};
pub(crate) use contact::{check_arm, rated};

#[path = "car_links.rs"]
mod links;
pub(crate) use links::scaled as scaled_link;

#[cfg(test)]
#[path = "car_tests.rs"]
mod tests;
