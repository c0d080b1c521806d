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
//! With `Setup::sequence` off (the default) every test runs on an
//! undamaged car, in parallel. With it on, each test after the first on an
//! end is also run alone, and its row states what it inherited and which
//! criteria the inherited damage changed, against the run alone.

use crate::criteria::Quantity;
use crate::error::VerdictError;
use crate::limits::End;
use crate::verdict::{CarEnd, Setup, TestVerdict, assess_on};
use bumpsim_impact::bumper::BumperState;
use rayon::prelude::*;
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

/// The damage left on one end: the segments' histories and who left it.
#[derive(Default)]
struct Damage {
    states: Vec<BumperState>,
    from: Vec<&'static str>,
}

/// Every test of `setup`: alone and in parallel, or in sequence when
/// `setup.sequence` (see the module). `pulse`: [`crate::verdict::judge`]'s
/// full pulse metrics; `explain`: also run each inherited test alone and
/// list what changed.
pub(crate) fn run(
    setup: &Setup,
    pulse: bool,
    explain: bool,
) -> Result<Vec<TestVerdict>, VerdictError> {
    if !setup.sequence {
        return setup
            .tests
            .par_iter()
            .map(|t| assess_on(setup, setup.end(t.end), t, pulse))
            .collect();
    }
    let mut damage = [Damage::default(), Damage::default()];
    let mut out = Vec::with_capacity(setup.tests.len());
    for test in &setup.tests {
        let Some(end) = setup.end(test.end) else {
            out.push(assess_on(setup, None, test, pulse)?);
            continue;
        };
        let left = &mut damage[matches!(test.end, End::Rear) as usize];
        let mut v = match left.from.is_empty() {
            true => assess_on(setup, Some(end), test, pulse)?,
            false => inherit(setup, end, test, left, pulse, explain)?,
        };
        if let Some(r) = &v.result {
            left.states = r.damage.clone();
            left.from.push(test.name);
        }
        v.assumptions
            .retain(|a| !a.starts_with("run on the undamaged car"));
        out.push(v);
    }
    Ok(out)
}

/// `test` on `end` carrying the damage `left`.
fn inherit(
    setup: &Setup,
    end: &CarEnd,
    test: &'static crate::protocol::Test,
    left: &Damage,
    pulse: bool,
    explain: bool,
) -> Result<TestVerdict, VerdictError> {
    let car = end
        .car
        .clone()
        .with_damage(left.states.clone())
        .map_err(|source| VerdictError::Planar {
            test: test.name.into(),
            source,
        })?;
    let damaged = CarEnd {
        car,
        limits: end.limits.clone(),
    };
    let mut v = assess_on(setup, Some(&damaged), test, pulse)?;
    let segments = &end.car.beam().segments;
    let sets = segments
        .iter()
        .zip(&left.states)
        .map(|(b, s)| b.remaining(s));
    let (segment, set) = sets.enumerate().fold(
        (0, 0.0),
        |best, (j, s)| if s > best.1 { (j, s) } else { best },
    );
    let changes = match explain {
        true => changes(&v, &assess_on(setup, Some(end), test, pulse)?),
        false => vec![],
    };
    v.assumptions.insert(
        0,
        format!(
            "run in sequence on the same car after {}: a permanent set of up to {:.2} mm (segment {}) inherited",
            left.from.join(", "),
            set * 1e3,
            segment + 1
        ),
    );
    v.inherited = Some(Inherited {
        from: left.from.clone(),
        set,
        segment,
        changes,
    });
    Ok(v)
}

/// The criteria of `sequence` whose value differs from `alone`'s by more
/// than [`REPRODUCED`] relative.
fn changes(sequence: &TestVerdict, alone: &TestVerdict) -> Vec<Change> {
    let mut out = vec![];
    for c in &sequence.criteria {
        let Some(a) = alone.criteria.iter().find(|a| a.name == c.name) else {
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

/// The lines that say what each test of a sequence inherited and what it
/// changed (empty without a sequence).
pub fn text(tests: &[TestVerdict]) -> String {
    let mut out = String::new();
    for t in tests {
        let Some(i) = &t.inherited else { continue };
        out += &format!(
            "  {} in sequence after {}: inherits a permanent set of up to {:.2} mm (segment {})",
            t.test.name,
            i.from.join(", "),
            i.set * 1e3,
            i.segment + 1
        );
        out += &match i.changes.is_empty() {
            true => "; every criterion as run alone (the set is not reached or nil)\n".into(),
            false => {
                let each: Vec<String> = i
                    .changes
                    .iter()
                    .map(|c| {
                        format!(
                            "{} {} (alone {})",
                            c.criterion,
                            c.quantity.format(c.sequence),
                            c.quantity.format(c.alone)
                        )
                    })
                    .collect();
                format!(
                    "; against the test run alone, the inherited damage changes: {}\n",
                    each.join(", ")
                )
            }
        };
    }
    out
}
