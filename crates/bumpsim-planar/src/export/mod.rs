//! The planar car as FE solver input (issue 15, item 6): an LS-DYNA keyword
//! include ([`lsdyna`](mod@lsdyna)) and a CalculiX deck, a complete transient
//! analysis under force histories ([`calculix`](mod@calculix)), both written
//! with bumpsim-export's card writers, unit systems and id checks.
//!
//! **Geometry** (both decks): the car points along global +x, y is left, z
//! up; the body's CG sits at `origin` (SI, converted to the deck's units).
//! Chain mass i (0-based) of the left (right) side sits at
//! `(x_f − i·spacing, +b (−b), 0)` from the CG, x_f = `cg_behind_bumper`,
//! b = half the side-member spacing; the chain's last link ends on a body
//! node one `spacing` further back. The front mass (i = 0) is on the bumper
//! line and carries the user's attachment nodes of its side (a side
//! without masses: a body node on the bumper line does).
//!
//! **Loads** are those of [`crate::drive`]: load k acts on the bumper line at
//! lateral position η_k with a fixed world direction d_k (a load anchored
//! to a world point, a pole's line of action, is refused); the two front
//! masses take the shares α_k = (η_k + b)/(2b) and 1 − α_k of the force
//! (lever rule), its lateral part reaching the body through the chains'
//! lateral guidance. Loads are summed per node and direction into one
//! history each.
//!
//! **Not exported**: tyre friction (the decks are frictionless, μ = 0) and
//! the bumper segments' crush characteristics (the decks carry the car
//! behind the beam; `bumpsim export bumper` writes a characteristic as a
//! nonlinear spring).
//!
//! Sources: LS-DYNA Keyword User's Manual, vol. I (R13); CalculiX CrunchiX
//! User's Manual 2.20.
//!
//! ```
//! use bumpsim_core::model::MsdModel;
//! use bumpsim_impact::bumper::Bumper;
//! use bumpsim_planar::car::{Layout, PlanarCar};
//! use bumpsim_planar::export::{PlanarExport, lsdyna_include};
//! let chain = MsdModel::new(vec![8.0, 1300.0], vec![2e3], vec![3e6]).unwrap();
//! let bumper = Bumper::three_part(3e6, 2e5, 2e7).unwrap();
//! let car = PlanarCar::symmetric(&chain, &bumper, &Layout::default()).unwrap();
//! let options = PlanarExport { attach: [vec![101], vec![102]], id_offset: 9_000_000, ..Default::default() };
//! let deck = lsdyna_include(&car, &options).unwrap();
//! assert!(deck.contains("*CONSTRAINED_NODAL_RIGID_BODY_INERTIA_SPC"));
//! assert!(deck.contains("*CONSTRAINED_JOINT_TRANSLATIONAL"));
//! ```

pub mod calculix;
pub mod lsdyna;

pub use calculix::{FeHistories, calculix_deck, read_calculix};
pub use lsdyna::lsdyna_include;

use crate::car::{PlanarCar, PlanarError, SideChain, require};
use crate::drive::Load;
use bumpsim_export::{ExportError, UnitSystem};

/// Why a planar deck cannot be written or read.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum PlanarExportError {
    /// A deck-level problem (ids, attachments, units, increments, results).
    #[error(transparent)]
    Export(#[from] ExportError),
    /// A parameter of the export or of its loads.
    #[error(transparent)]
    Parameter(#[from] PlanarError),
}

/// Force histories on the bumper line, as [`crate::drive::Drive`] takes them.
#[derive(Debug, Clone, PartialEq)]
pub struct Forces {
    /// Sample interval, s; sample k is at time k · step.
    pub step: f64,
    /// The loads (each with the same number of samples, at least two).
    pub loads: Vec<Load>,
}

impl Forces {
    /// The loads' length, s: (samples − 1) · step.
    pub fn duration(&self) -> f64 {
        let samples = self.loads.first().map_or(0, |l| l.force.len());
        samples.saturating_sub(1) as f64 * self.step
    }
}

/// Options of the planar export.
#[derive(Debug, Clone, PartialEq)]
pub struct PlanarExport {
    /// Deck units.
    pub units: UnitSystem,
    /// Position of the body's CG in the deck, m (SI).
    pub origin: [f64; 3],
    /// Distance between neighbouring chain nodes along x, m (> 0; no effect
    /// on the physics of the CalculiX deck, see [`lsdyna`](mod@lsdyna) for LS-DYNA).
    pub spacing: f64,
    /// Added to every id.
    pub id_offset: u64,
    /// The user's attachment nodes coupled to the left and to the right front mass.
    pub attach: [Vec<u64>; 2],
    /// Initial forward speed (+x) of the whole car, m/s.
    pub speed: Option<f64>,
    /// Force histories (LS-DYNA: curves and nodal loads; CalculiX: the analysis).
    pub forces: Option<Forces>,
    /// LS-DYNA: history outputs every this many s.
    pub output_interval: Option<f64>,
    /// CalculiX: fixed time increment, s (default: the forces' step).
    pub increment: Option<f64>,
    /// CalculiX: results every this many increments (≥ 1).
    pub output_every: usize,
    /// CalculiX: prefix of every set and amplitude name.
    pub prefix: String,
    /// Title comment.
    pub title: String,
}

impl Default for PlanarExport {
    fn default() -> Self {
        PlanarExport {
            units: UnitSystem::Si,
            origin: [0.0; 3],
            spacing: 0.1,
            id_offset: 0,
            attach: [vec![], vec![]],
            speed: None,
            forces: None,
            output_interval: None,
            increment: None,
            output_every: 1,
            prefix: bumpsim_export::calculix::DEFAULT_PREFIX.into(),
            title: String::new(),
        }
    }
}

/// One side of the car as the decks see it.
pub(crate) struct Side<'a> {
    /// Lateral position, m (+b left, −b right).
    pub eta: f64,
    pub chain: &'a SideChain,
    /// 0 left, 1 right.
    pub index: usize,
}

/// The left and right sides.
pub(crate) fn sides(car: &PlanarCar) -> [Side<'_>; 2] {
    let b = half_spacing(car);
    [
        Side {
            eta: b,
            chain: car.left(),
            index: 0,
        },
        Side {
            eta: -b,
            chain: car.right(),
            index: 1,
        },
    ]
}

/// b, m.
pub(crate) fn half_spacing(car: &PlanarCar) -> f64 {
    0.5 * car.beam().side_member_spacing
}

/// A point of the car (body frame, from the CG, m) in deck coordinates.
pub(crate) fn place(options: &PlanarExport, p: [f64; 3]) -> [f64; 3] {
    let l = options.units.length();
    std::array::from_fn(|c| (options.origin[c] + p[c]) * l)
}

/// The world force of every load on the left (0) and right (1) front
/// masses, per sample: `[side][component][sample]`, N (SI).
pub(crate) fn front_forces(car: &PlanarCar, forces: &Forces) -> [[Vec<f64>; 2]; 2] {
    let b = half_spacing(car);
    let samples = forces.loads.first().map_or(0, |l| l.force.len());
    let mut out: [[Vec<f64>; 2]; 2] = Default::default();
    out.iter_mut()
        .flatten()
        .for_each(|h| *h = vec![0.0; samples]);
    for load in &forces.loads {
        let norm = load.direction[0].hypot(load.direction[1]);
        let d = load.direction.map(|c| c / norm);
        let alpha = (load.lateral + b) / (2.0 * b);
        for (side, share) in [(0, alpha), (1, 1.0 - alpha)] {
            for (c, &dc) in d.iter().enumerate() {
                for (h, f) in out[side][c].iter_mut().zip(&load.force) {
                    *h += share * dc * f;
                }
            }
        }
    }
    out
}

/// Checks what the decks take from the options, beyond the card writers'
/// own checks: placement, speed, forces, and every value finite in the
/// deck's units.
pub(crate) fn check(car: &PlanarCar, options: &PlanarExport) -> Result<(), PlanarExportError> {
    let positive = "must be positive and finite";
    let spacing = options.spacing;
    require("spacing", spacing, "m", positive, spacing > 0.0)?;
    for (c, &x) in options.origin.iter().enumerate() {
        require(&format!("origin[{c}]"), x, "m", "must be finite", true)?;
    }
    if let Some(v) = options.speed {
        require("initial velocity", v, "m/s", "must be finite", true)?;
    }
    if let Some(forces) = &options.forces {
        check_forces(car, forces)?;
    }
    // the decks write each link's spring as linear: a nonlinear side member
    // exported as its initial slope would be a different car, silently
    for (side, chain) in [("left", car.left()), ("right", car.right())] {
        let links = chain.links.len() as f64;
        let expected = "none: the planar decks carry linear side members only \
             (a nonlinear link would be written as its initial slope); export \
             the side member as a 1-D links chain, or a linear car";
        require(
            &format!("{side}.links"),
            links,
            "links",
            expected,
            links == 0.0,
        )?;
    }
    if let Some(dt) = options.output_interval {
        let duration = options.forces.as_ref().map(Forces::duration);
        bumpsim_export::check_interval(
            "output interval (--output-interval)",
            dt,
            duration,
            bumpsim_export::MAX_OUTPUTS,
        )?;
    }
    check_units(car, options)
}

fn check_forces(car: &PlanarCar, forces: &Forces) -> Result<(), PlanarExportError> {
    // a load is applied on the bumper line: beyond its ends the lever rule
    // gave the front masses shares above 1 and below 0 (--lateral 5 on a
    // 0.75 m half-width exited 0)
    let half = 0.5 * car.beam().width;
    let on_bumper =
        format!("must lie on the bumper line, |y| at most half the bumper width, {half} m");
    let step = forces.step;
    require("step", step, "s", "must be positive and finite", step > 0.0)?;
    let samples = forces.loads.first().map_or(0, |l| l.force.len());
    if forces.loads.is_empty() || samples < 2 {
        return Err(ExportError::ForceSamples { samples }.into());
    }
    for (k, load) in forces.loads.iter().enumerate() {
        let name = |what: &str| format!("load[{k}].{what}");
        let y = load.lateral;
        require(&name("lateral"), y, "m", &on_bumper, y.abs() <= half)?;
        if let Some(p) = load.anchor {
            let expected = "the decks apply a load at a fixed place on the bumper line: no anchor";
            require(&name("anchor"), p[0] + p[1], "m", expected, false)?;
        }
        let norm = load.direction[0].hypot(load.direction[1]);
        let expected = "must be a finite, non-zero vector";
        require(&name("direction"), norm, "1", expected, norm > 0.0)?;
        let same = format!("all loads need the same {samples} samples");
        let len = load.force.len() as f64;
        require(
            &name("force"),
            len,
            "samples",
            &same,
            load.force.len() == samples,
        )?;
        for (i, &f) in load.force.iter().enumerate() {
            require(
                &format!("load[{k}].force[{i}]"),
                f,
                "N",
                "must be finite",
                true,
            )?;
        }
    }
    Ok(())
}

/// Every value a deck writes, converted to its units, must stay finite
/// (a value finite in SI can overflow: 1e307 s is inf ms).
fn check_units(car: &PlanarCar, options: &PlanarExport) -> Result<(), PlanarExportError> {
    let u = options.units;
    let overflow = |what: &str| ExportError::Overflow {
        what: what.into(),
        units: u.to_string(),
    };
    let longest = car.left().masses.len().max(car.right().masses.len()) as f64 + 1.0;
    let reach = car.body().cg_behind_bumper.abs() + longest * options.spacing + half_spacing(car);
    let far = options.origin.iter().map(|x| x.abs()).fold(0.0, f64::max) + reach;
    let body = car.body();
    let checks = [
        ("a node position (--origin, --spacing)", far * u.length()),
        ("body.mass", body.mass * u.mass()),
        (
            "body.yaw_inertia",
            body.yaw_inertia * u.mass() * u.length().powi(2),
        ),
        (
            "the initial velocity",
            options.speed.unwrap_or(0.0) * u.velocity(),
        ),
        (
            "the output interval",
            options.output_interval.unwrap_or(0.0) * u.time(),
        ),
    ];
    for (what, value) in checks {
        if !value.is_finite() {
            return Err(overflow(what).into());
        }
    }
    for side in sides(car) {
        let c = side.chain;
        let values = c.masses.iter().map(|m| m * u.mass());
        let values = values.chain(c.springs.iter().map(|k| k * u.stiffness()));
        let values = values.chain(c.dampers.iter().map(|d| d * u.damping()));
        if values.into_iter().any(|v| !v.is_finite()) {
            return Err(overflow("a chain mass, spring or damper").into());
        }
    }
    if let Some(forces) = &options.forces {
        let samples = forces.loads[0].force.len();
        let end = (samples - 1) as f64 * forces.step * u.time();
        let total: f64 = forces
            .loads
            .iter()
            .flat_map(|l| &l.force)
            .map(|f| f.abs())
            .sum();
        if !end.is_finite() || !(total * u.force()).is_finite() {
            return Err(overflow("a force sample (time or value)").into());
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::car::Layout;
    use bumpsim_core::model::MsdModel;
    use bumpsim_impact::bumper::Bumper;

    #[test]
    fn a_load_beyond_the_bumper_ends_is_refused() {
        let chain = MsdModel::new(vec![8.0, 1300.0], vec![2e3], vec![3e6]).unwrap();
        let bumper = Bumper::three_part(3e6, 2e5, 2e7).unwrap();
        let car = PlanarCar::symmetric(&chain, &bumper, &Layout::default()).unwrap();
        let at = |lateral| {
            let load = Load {
                lateral,
                anchor: None,
                cell: None,
                direction: [-1.0, 0.0],
                force: vec![0.0, 1e3, 0.0],
            };
            let forces = Forces {
                step: 1e-3,
                loads: vec![load],
            };
            check(
                &car,
                &PlanarExport {
                    forces: Some(forces),
                    ..Default::default()
                },
            )
        };
        assert!(
            at(0.8).is_ok() && at(-0.8).is_ok(),
            "the ends of a 1.6 m bumper"
        );
        for lateral in [5.0, -0.81, f64::NAN] {
            let e = at(lateral).unwrap_err().to_string();
            assert!(
                e.contains("load[0].lateral") && e.contains("half the bumper width, 0.8 m"),
                "{e}"
            );
        }
    }
}
