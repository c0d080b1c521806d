//! Sequences on one car (issue 45 item 2): a protocol's impacts run in
//! their order on the same car, each starting from the damage the earlier
//! ones left on that end. 49 CFR 581.5(a) runs the pendulum impacts and
//! then the barrier impacts on one vehicle; RCAR's bumper and structural
//! tests, asked together, run one after the other.
//!
//! The damage a test leaves is each bumper segment's history, its largest
//! crush `d_max` and force `F_max` (`bumpsim_planar::PlanarCar::with_damage`):
//! the next test's segment carries `max(0, F_max − k_u (d_max − d))` up to
//! `d_max` (its unloading line from the permanent set
//! `d_max − F_max/k_u`) and its loading curve beyond. The crash boxes and
//! chains are elastic here and carry no set; the car starts each test at
//! rest, as a test house sets it up again.
//!
//! The runner is `crate::verdict`'s, the lines `crate::text::sequence`.
//! With `Setup::sequence` off (the default) every test runs on an
//! undamaged car, in parallel. With it on, each test after the first on an
//! end is also run alone, and its row states what it inherited and which
//! criteria the inherited damage changed, against the run alone.

use crate::criteria::{Criterion, Quantity};
use serde::Serialize;

/// What a test run in a sequence inherited from the earlier ones.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Inherited {
    /// The earlier tests on the same end, in order.
    pub from: Vec<&'static str>,
    /// The largest permanent set they left on a segment, m.
    pub set: f64,
    /// That segment (0 = rightmost).
    pub segment: usize,
    /// The criteria whose value the inherited damage changed, against the
    /// test run alone on the undamaged car (empty: it reproduces it).
    pub changes: Vec<Change>,
}

/// A criterion's value in the sequence and alone.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Change {
    /// The criterion.
    pub criterion: String,
    /// What it measures.
    pub quantity: Quantity,
    /// Its value run alone, SI.
    pub alone: f64,
    /// Its value in the sequence, SI.
    pub sequence: f64,
}

/// Relative change below which a value counts as reproduced.
pub const REPRODUCED: f64 = 1e-6;

/// The criteria of `sequence` whose value differs from `alone`'s by more
/// than [`REPRODUCED`] relative.
pub fn changes(sequence: &[Criterion], alone: &[Criterion]) -> Vec<Change> {
    let mut out = vec![];
    for c in sequence {
        let Some(a) = alone.iter().find(|a| a.name == c.name) else {
            continue;
        };
        if (c.value - a.value).abs() > REPRODUCED * a.value.abs().max(1e-9) {
            out.push(Change {
                criterion: c.name.clone(),
                quantity: c.quantity,
                alone: a.value,
                sequence: c.value,
            });
        }
    }
    out
}
