//! bumpsim-export: the identified MSD car model as input for FE solvers, so it
//! can sit behind a bumper mesh (thesis ch. 3.3, paper B; spec §8).
//!
//! - [`lsdyna`]: an LS-DYNA keyword include file (fixed-format cards);
//! - [`cards`]: the LS-DYNA card writers every include shares;
//! - [`inp`]: the CalculiX/Abaqus card writers every deck shares;
//! - [`chain`]: the chain with nonlinear links: which element carries
//!   which link, and its LS-DYNA include;
//! - [`chain_calculix`]: its CalculiX deck, barrier run and link forces;
//! - [`calculix`]: a CalculiX/Abaqus deck, optionally a complete transient
//!   analysis under a force history, and reading its results back;
//! - [`dat`]: the print blocks of any CalculiX `.dat` file;
//! - [`layout`]: unit systems, axis and node placement shared by both;
//! - [`spring`]: the bumper characteristic as a nonlinear discrete spring;
//! - [`car_deck`]: a car of either chain form to its deck (picks the writer);
//! - [`timestep`]: the car's explicit critical time step.
//!
//! ```
//! use bumpsim_core::model::MsdModel;
//! use bumpsim_export::lsdyna::{lsdyna_include, LsDynaOptions};
//! let car = MsdModel::new(vec![1.8, 74.8, 1670.0], vec![6.46e6, 1.97e5], vec![4.75e5, 5.0e5]).unwrap();
//! let deck = lsdyna_include(&car, &LsDynaOptions { id_offset: 900_000, ..Default::default() }).unwrap();
//! assert!(deck.contains("*ELEMENT_DISCRETE"));
//! ```

pub mod calculix;
pub mod car_deck;
pub mod cards;
pub mod chain;
pub mod chain_calculix;
pub mod dat;
pub mod inp;
pub mod layout;
pub mod lsdyna;
pub mod spring;
pub mod timestep;

pub use calculix::{CalculixOptions, calculix_deck};
pub use layout::{Axis, Layout, UnitSystem};
pub use lsdyna::{LsDynaOptions, lsdyna_include};

/// The main types and writers, for `use bumpsim_export::prelude::*` (the
/// facade's prelude globs it; `Layout` stays out, several crates have one).
pub mod prelude {
    pub use crate::ExportError;
    pub use crate::calculix::{Analysis, CalculixOptions, calculix_deck};
    pub use crate::layout::{Axis, UnitSystem};
    pub use crate::lsdyna::{LsDynaOptions, lsdyna_include};
    pub use crate::spring::{SpringCurve, SpringOptions};
}

use std::path::PathBuf;

/// What bounds the ids of a deck: LS-DYNA's 8-column fields or CalculiX's
/// 32-bit integers.
fn id_limit(limit: u64) -> &'static str {
    match limit {
        lsdyna::MAX_ID => "8-column",
        _ => "CalculiX 32-bit id",
    }
}

/// Why a deck cannot be written or its results read.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ExportError {
    /// An id offset at or above the 8-column limit (checked before any id
    /// is added to it, so that no sum wraps around).
    #[error("id offset {offset}: must be below the 8-column id limit {limit}")]
    IdOffset {
        /// The offset given.
        offset: u64,
        /// The largest id LS-DYNA's fixed format holds.
        limit: u64,
    },
    /// The id offset leaves no room for the include's ids in 8 columns.
    #[error("id offset {offset} puts ids up to {last}, beyond the {} limit {limit}", id_limit(*limit))]
    IdRange {
        /// The offset given.
        offset: u64,
        /// The largest id it would need.
        last: u64,
        /// The largest id LS-DYNA's fixed format holds.
        limit: u64,
    },
    /// An attachment node is one of the include's own nodes.
    #[error(
        "attachment node {node} clashes with the include's nodes {first}..{last}: \
         choose an --id-offset above your model's ids"
    )]
    IdClash {
        /// The node given.
        node: u64,
        /// The include's first node id.
        first: u64,
        /// The include's last node id.
        last: u64,
    },
    /// An attachment node given twice.
    #[error("attachment node {node} is given twice")]
    DuplicateNode {
        /// The node.
        node: u64,
    },
    /// An attachment node id out of range.
    #[error("attachment node {node} is not a valid node id (1..{limit})")]
    NodeId {
        /// The node given.
        node: u64,
        /// The largest valid id.
        limit: u64,
    },
    /// A time increment or output interval out of its range.
    #[error("{what} = {} s: expected {expected}", bumpsim_core::units::short(*increment))]
    Increment {
        /// Which: the option's name.
        what: &'static str,
        /// The increment, s.
        increment: f64,
        /// What it must be.
        expected: String,
    },
    /// An output interval of zero increments.
    #[error("the output interval must be at least 1 increment")]
    OutputInterval,
    /// A force history too short for a transient analysis.
    #[error("the force needs at least two samples, got {samples}")]
    ForceSamples {
        /// Samples given.
        samples: usize,
    },
    /// A set-name prefix CalculiX cannot read.
    #[error("name prefix '{prefix}': use letters, digits and '_' (not first a digit), at most 40")]
    Prefix {
        /// The prefix given.
        prefix: String,
    },
    /// A standalone deck without a force history to end at.
    #[error("a standalone deck needs a force history (its end is the termination time)")]
    Standalone,
    /// A value that is finite in SI but overflows in the deck's units (or
    /// is not finite at all): the deck would carry `inf`.
    #[error(
        "{what} does not fit the deck's units ({units}): every value must stay finite after conversion"
    )]
    Overflow {
        /// The value, as the user knows it (`node 3 position`, `force sample 2`, …).
        what: String,
        /// The deck's unit system.
        units: String,
    },
    /// An increment so small that the analysis needs more increments than
    /// CalculiX's `*STEP, INC=` (a 32-bit integer) holds.
    #[error(
        "time increment {increment:e} s needs {count:e} increments for the force's {duration:e} s, above CalculiX's limit {limit}: choose a larger --increment"
    )]
    Increments {
        /// The increment, s.
        increment: f64,
        /// Increments needed.
        count: f64,
        /// Length of the force history, s.
        duration: f64,
        /// The largest count.
        limit: u64,
    },
    /// A minimum time step to warn below that is negative or not finite.
    #[error("minimum time step {value} s: must be finite and not negative (0: never warn)")]
    MinTimeStep {
        /// The value given, s.
        value: f64,
    },
    /// A bumper curve the solvers cannot take.
    #[error("bumper curve point {point}: {reason}")]
    Curve {
        /// 1-based point (0: the curve as a whole).
        point: usize,
        /// What is wrong.
        reason: String,
    },
    /// A barrier run of a chain deck that cannot be written.
    #[error("barrier run: {reason}")]
    Barrier {
        /// What is wrong.
        reason: &'static str,
    },
    /// A results file that cannot be read.
    #[error("{}{}: {reason}", path.display(), if *line > 0 { format!(":{line}") } else { String::new() })]
    Dat {
        /// The file.
        path: PathBuf,
        /// 1-based line (0: the file as a whole).
        line: usize,
        /// What is wrong.
        reason: String,
    },
    /// A wall link whose gap is too large for its curve's points to stay
    /// apart once written.
    #[error(
        "{what}: its gap of {gap} m leaves its curve degenerate: the point at {at} m past the barrier rounds onto the one before it in the deck (13 significant digits); expected a gap small against the curve's first deformation"
    )]
    WallGap {
        /// `the second load path` or `the rebound link`.
        what: String,
        /// Its gap, m.
        gap: f64,
        /// The deformation (m, the gap included) that collapses.
        at: f64,
    },
}

/// Checks the user's attachment nodes: none of the include's own nodes
/// `ours`, none twice, each in 1..=`limit`.
pub fn check_attach(
    attach: &[u64],
    ours: std::ops::RangeInclusive<u64>,
    limit: u64,
) -> Result<(), ExportError> {
    if let Some(node) = attach.iter().find(|n| ours.contains(n)) {
        return Err(ExportError::IdClash {
            node: *node,
            first: *ours.start(),
            last: *ours.end(),
        });
    }
    let mut seen = std::collections::HashSet::new();
    if let Some(node) = attach.iter().find(|n| !seen.insert(**n)) {
        return Err(ExportError::DuplicateNode { node: *node });
    }
    match attach.iter().find(|&&n| n == 0 || n > limit) {
        Some(node) => Err(ExportError::NodeId { node: *node, limit }),
        None => Ok(()),
    }
}

/// Checks that every value a deck writes stays finite in the deck's units:
/// node positions, masses, springs, dampers, initial velocity, force samples
/// (value and shifted time) and the given extra times (increment, output
/// interval), s. A value finite in SI can overflow on conversion
/// (1e307 s → ms), and the writers would print `inf`.
pub(crate) fn check_finite(
    model: &bumpsim_core::model::MsdModel,
    layout: &layout::Layout,
    initial_velocity: Option<f64>,
    force: Option<&bumpsim_core::series::UniformSeries>,
    times: &[(&str, f64)],
) -> Result<(), ExportError> {
    let u = layout.units;
    let overflow = |what: String| ExportError::Overflow {
        what,
        units: u.to_string(),
    };
    let fine = |v: f64| v.is_finite();
    for i in 0..model.dof() {
        if !layout.node_position(i).into_iter().all(fine) {
            return Err(overflow(format!(
                "the position of mass {} (--origin, --spacing)",
                i + 1
            )));
        }
        if !fine(model.masses()[i] * u.mass()) {
            return Err(overflow(format!("mass {}", i + 1)));
        }
    }
    for j in 0..model.springs().len() {
        if !fine(model.springs()[j] * u.stiffness()) || !fine(model.dampers()[j] * u.damping()) {
            return Err(overflow(format!("link {} (spring or damper)", j + 1)));
        }
    }
    if let Some(v) = initial_velocity
        && !fine(v * u.velocity())
    {
        return Err(overflow(format!("the initial velocity {v} m/s")));
    }
    if let Some(force) = force {
        for k in 0..force.len() {
            let t = (force.time(k) - force.start()) * u.time();
            if !fine(t) || !fine(force.values()[k] * u.force()) {
                return Err(overflow(format!("force sample {} (time or value)", k + 1)));
            }
        }
    }
    for &(what, t) in times {
        if !fine(t * u.time()) {
            return Err(overflow(format!("{what} {t} s")));
        }
    }
    Ok(())
}

/// The shortest output interval or increment a deck may ask for, s: a
/// low-speed car model's explicit time step is microseconds, and 1e-308 s
/// asked for 1e307 outputs.
pub const MIN_INTERVAL: f64 = 1e-9;

/// The most outputs an LS-DYNA deck's output interval may ask for over its
/// force (as `fe lsdyna`'s runs).
pub const MAX_OUTPUTS: f64 = 1e6;

/// An increment or output interval `dt` (s) named `what`: finite, at least
/// [`MIN_INTERVAL`], and with a force of `duration` (s) at most that
/// duration and at most `most` of them over it.
pub fn check_interval(
    what: &'static str,
    dt: f64,
    duration: Option<f64>,
    most: f64,
) -> Result<(), ExportError> {
    let refuse = |expected: String| ExportError::Increment {
        what,
        increment: dt,
        expected,
    };
    if !(dt.is_finite() && dt >= MIN_INTERVAL) {
        return Err(refuse("finite and at least 1e-9 s".into()));
    }
    match duration {
        Some(d) if dt > d => Err(refuse(format!(
            "at most the force's duration, {} s",
            bumpsim_core::units::short(d)
        ))),
        Some(d) if d / dt > most => Err(refuse(format!(
            "at least the force's duration / {} = {} s",
            bumpsim_core::units::short(most),
            bumpsim_core::units::short(d / most)
        ))),
        _ => Ok(()),
    }
}
