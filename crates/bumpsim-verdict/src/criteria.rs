//! The criteria of a test and their margins, from a planar impact and the
//! car's damageability data ([`crate::limits`]).
//!
//! - **Clearance** (per part): the largest travel, over time and over the
//!   part's lateral range, of what closes on it: the beam's rearward travel
//!   relative to the body, `−(α u_L + (1 − α) u_R)` with the side-member
//!   tips' displacements `u` and the lever share `α = (y + b)/2b` of the
//!   planar car; or the front surface's, the segment's own crush plus that
//!   travel. Margin: gap − travel.
//! - **Rail force**: the largest compressive side-member force, either
//!   side, against the force at which the rails yield.
//! - **Crash-box stroke**: the largest compression of each chain's first
//!   link (tip to next mass, or to the body), against the usable stroke;
//!   pass/fail in the insurance tests, reported in the regulations (which
//!   allow damage to the bumper and its attachments).
//! - **Bumper stroke** (optional): the largest crush of a segment.
//! - **Beam engagement** (with the beam's heights): a pendulum's ridge must
//!   meet the beam at every height it may be set to; a barrier face must
//!   overlap the beam by half its own height (a choice made here: RCAR's
//!   qualifying-height rule was not available). Without the heights it is
//!   an assumption stated with the verdict.
//! - **Pulse** (optional limits): 3 ms clip, OLC, ASI ([`crate::pulse`]).
//! - **Bumper energy share** (optional): the energy the bumper dissipates
//!   against the bumper's and the structure's together.
//!
//! Every criterion has a margin in its own unit and a margin ratio: the
//! margin over its reference, the quantity that is 100 % (the limit; for a
//! pendulum's beam engagement, whose limit is 0 mm, the ridge's height
//! range: [`Criterion::reference`]); a criterion passes when its ratio is
//! at least the margin asked for.

use crate::limits::{Closer, Damageability};
use crate::protocol::{Height, Test};
use crate::pulse::Metrics;
use bumpsim_estimate::propagate::Probability;
use bumpsim_planar::{PlanarCar, PlanarResult};
use serde::Serialize;

/// What a criterion measures (for its display unit).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Quantity {
    /// m, shown in mm.
    Length,
    /// N, shown in kN.
    Force,
    /// m/s², shown in g.
    Acceleration,
    /// A pure number.
    Ratio,
}

impl Quantity {
    /// The display unit.
    pub fn unit(self) -> &'static str {
        match self {
            Quantity::Length => "mm",
            Quantity::Force => "kN",
            Quantity::Acceleration => "g",
            Quantity::Ratio => "1",
        }
    }

    /// An SI value in the display unit.
    pub fn display(self, si: f64) -> f64 {
        match self {
            Quantity::Length => si * 1e3,
            Quantity::Force => si * 1e-3,
            Quantity::Acceleration => si / bumpsim_planar::car::GRAVITY,
            Quantity::Ratio => si,
        }
    }

    /// An SI value with its display unit, four significant digits.
    pub fn format(self, si: f64) -> String {
        let unit = match self {
            Quantity::Ratio => String::new(),
            q => format!(" {}", q.unit()),
        };
        format!(
            "{}{unit}",
            bumpsim_core::units::format_number(self.display(si), 4)
        )
    }
}

/// A criterion's outcome.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Outcome {
    /// Within its limit by at least the margin asked for.
    Pass,
    /// Outside its limit, or within it by less than the margin.
    Fail,
    /// Reported, not judged.
    Info,
}

/// One criterion of one test.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Criterion {
    /// What it is (`clearance: radiator`, `rail force`, ...).
    pub name: String,
    /// Where or how it was reached.
    pub detail: String,
    /// What it measures.
    pub quantity: Quantity,
    /// The value reached, SI.
    pub value: f64,
    /// The limit, SI.
    pub limit: f64,
    /// Whether the value must stay at or below the limit (else at or above).
    pub upper: bool,
    /// The margin, SI (positive: inside the limit).
    pub margin: f64,
    /// The margin over its reference ([`Criterion::reference`]), 1.
    pub ratio: f64,
    /// What the margin ratio is a share of (100 %), SI: the limit's size,
    /// or another scale where the limit is 0 ([`Criterion::reference_name`]).
    pub reference: f64,
    /// What [`Criterion::reference`] is: `the limit`, or e.g. `the
    /// ridge's height range (406-508 mm)`.
    pub reference_name: String,
    /// The outcome.
    pub outcome: Outcome,
    /// Its probability of passing over the car's uncertainty (None: not
    /// propagated, or reported only; the probability module).
    pub probability: Option<Probability>,
}

impl Criterion {
    pub(crate) fn new(
        name: String,
        detail: String,
        quantity: Quantity,
        value: f64,
        limit: f64,
        upper: bool,
    ) -> Criterion {
        let margin = if upper { limit - value } else { value - limit };
        Criterion {
            name,
            detail,
            quantity,
            value,
            limit,
            upper,
            margin,
            ratio: margin / limit.abs(),
            reference: limit.abs(),
            reference_name: "the limit".into(),
            outcome: Outcome::Info,
            probability: None,
        }
    }

    /// The margin ratio taken over `reference` (SI), named `name`, where
    /// the limit cannot be the scale (a limit of 0).
    fn relative_to(mut self, reference: f64, name: String) -> Criterion {
        self.ratio = self.margin / reference;
        self.reference = reference;
        self.reference_name = name;
        self
    }

    /// Whether the margin ratio is a share of the limit (else of
    /// [`Criterion::reference_name`]).
    pub fn of_limit(&self) -> bool {
        self.reference_name == "the limit"
    }

    /// Judged against the margin ratio asked for.
    pub(crate) fn judged(mut self, margin: f64) -> Criterion {
        self.outcome = match self.ratio >= margin {
            true => Outcome::Pass,
            false => Outcome::Fail,
        };
        self
    }
}

/// The side-member tips' displacements `(u_L, u_R)` at sample `k`, m.
fn tips(car: &PlanarCar, r: &PlanarResult, k: usize) -> (f64, f64) {
    let left = car.left().masses.len();
    let u = |i: usize| {
        r.chain_displacement
            .get(i)
            .and_then(|h| h.get(k))
            .copied()
            .unwrap_or(0.0)
    };
    let right = if car.right().masses.is_empty() {
        0.0
    } else {
        u(left)
    };
    (if left == 0 { 0.0 } else { u(0) }, right)
}

/// The beam's rearward travel relative to the body at `y`, sample `k`, m.
fn beam_travel(car: &PlanarCar, r: &PlanarResult, k: usize, y: f64) -> f64 {
    let b = 0.5 * car.beam().side_member_spacing;
    let alpha = (y + b) / (2.0 * b);
    let (left, right) = tips(car, r, k);
    -(alpha * left + (1.0 - alpha) * right)
}

fn clearance(car: &PlanarCar, r: &PlanarResult, c: &crate::limits::Clearance) -> Criterion {
    let half = 0.5 * car.beam().width;
    let [low, high] = c.lateral.unwrap_or([-half, half]);
    let h = 0.5 * car.segment_width();
    let segments: Vec<usize> = (0..r.segment_centres.len())
        .filter(|&j| r.segment_centres[j] + h > low && r.segment_centres[j] - h < high)
        .collect();
    let (mut worst, mut at) = (f64::NEG_INFINITY, (0.0, 0.0));
    // the points that may close the gap, as (y, travel at sample k):
    // the span's ends for the beam, each segment in it for the front
    let travel = |k: usize, y: f64, j: Option<usize>| {
        j.map_or(0.0, |j| r.crush[j][k]) + beam_travel(car, r, k, y)
    };
    for k in 0..r.time.len() {
        let mut consider = |y: f64, j: Option<usize>| {
            let t = travel(k, y, j);
            if t > worst {
                (worst, at) = (t, (y, r.time[k]));
            }
        };
        match c.from {
            Closer::Beam => [low, high].into_iter().for_each(|y| consider(y, None)),
            Closer::Front => segments
                .iter()
                .for_each(|&j| consider(r.segment_centres[j], Some(j))),
        }
    }
    let what = match c.from {
        Closer::Beam => "beam travel",
        Closer::Front => "front travel",
    };
    let detail = format!(
        "{what} at y = {:.0} mm, t = {:.1} ms{}",
        at.0 * 1e3,
        at.1 * 1e3,
        blocked(r, at.1)
    );
    Criterion::new(
        format!("clearance: {}", c.name),
        detail,
        Quantity::Length,
        worst.max(0.0),
        c.gap,
        true,
    )
}

/// The label of a criterion reached at `t` (s) once the bumper or a crash
/// box had bottomed: from then on the load goes through the block
/// (issue 45).
fn blocked(r: &PlanarResult, t: f64) -> String {
    let bumper = r
        .bottomed
        .filter(|b| t >= b.time)
        .map(|_| "the bumper".to_string());
    let boxed = r
        .box_bottomed
        .filter(|b| t >= b.time)
        .map(|b| format!("the {} crash box", b.side.name()));
    match (bumper, boxed) {
        (None, None) => String::new(),
        (Some(a), Some(b)) => format!(", after {a} and {b} bottomed: on the blocked load path"),
        (Some(a), None) | (None, Some(a)) => {
            format!(", after {a} bottomed: on the blocked load path")
        }
    }
}

/// The largest value of a history and its time, s (0 and the first
/// sample's time when it never exceeds 0).
fn peak(r: &PlanarResult, value: impl Fn(usize) -> f64) -> (f64, f64) {
    let mut best = (0.0, r.time.first().copied().unwrap_or(0.0));
    for k in 0..r.time.len() {
        if value(k) > best.0 {
            best = (value(k), r.time[k]);
        }
    }
    best
}

/// The largest compression of each side's first chain link, m, and its
/// time, s (None: a side without a chain).
fn crash_boxes(car: &PlanarCar, r: &PlanarResult) -> [Option<(f64, f64)>; 2] {
    let left = car.left().masses.len();
    let sides = [(0, left), (left, car.right().masses.len())];
    sides.map(|(first, count)| {
        (count > 0).then(|| {
            let u = |i: usize, k: usize| r.chain_displacement[first + i][k];
            peak(r, |k| -(u(0, k) - if count > 1 { u(1, k) } else { 0.0 }))
        })
    })
}

/// The energies of an impact, J.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Energies {
    /// The impact's kinetic energy.
    pub initial: f64,
    /// Dissipated by the car's bumper segments.
    pub bumper: f64,
    /// Dissipated by the barrier's absorber (RCAR barrier).
    pub absorber: f64,
    /// Taken by the structure behind the bumper (chain dampers, and the
    /// chain springs' energy at the end).
    pub structure: f64,
    /// Kinetic energy at the end (rebound).
    pub kinetic: f64,
    /// Dissipated by the tyres.
    pub tyres: f64,
    /// The bumper's share of bumper and structure, 1.
    pub bumper_share: f64,
}

/// The energies of an impact from its balance and the segments' states.
pub fn energies(car: &PlanarCar, r: &PlanarResult) -> Energies {
    let bumper: f64 = car
        .beam()
        .segments
        .iter()
        .zip(&r.max_crush)
        .map(|(s, &d)| {
            let peak = s.loading_force(d);
            s.loading_energy(d) - 0.5 * peak * peak / s.unloading_slope()
        })
        .sum();
    let e = &r.energy;
    let structure = e.dampers + e.springs;
    Energies {
        initial: e.initial,
        bumper,
        absorber: (e.crush - bumper).max(0.0),
        structure,
        kinetic: e.kinetic,
        tyres: e.friction,
        bumper_share: bumper / (bumper + structure).max(f64::MIN_POSITIVE),
    }
}

/// What a test's criteria are judged from.
pub struct Evidence<'a> {
    /// The car as run.
    pub car: &'a PlanarCar,
    /// Its clearances and limits.
    pub limits: &'a Damageability,
    /// The test.
    pub test: &'a Test,
    /// The impact.
    pub result: &'a PlanarResult,
    /// Its pulse metrics.
    pub metrics: &'a Metrics,
    /// Its energies.
    pub energies: &'a Energies,
}

/// Every criterion of a test, judged with the margin ratio `margin`, and
/// the assumptions the verdict rests on.
pub fn criteria(e: &Evidence, margin: f64) -> (Vec<Criterion>, Vec<String>) {
    let (d, r) = (e.limits, e.result);
    let mut out: Vec<Criterion> = d
        .clearances
        .iter()
        .map(|c| clearance(e.car, r, c).judged(margin))
        .collect();
    let rails = [(&r.side_force_left, "left"), (&r.side_force_right, "right")]
        .map(|(h, side)| (peak(r, |k| h[k]), side));
    let ((force, at), side) = if rails[0].0.0 >= rails[1].0.0 {
        rails[0]
    } else {
        rails[1]
    };
    out.push(
        Criterion::new(
            "rail force".into(),
            format!("{side} side member{}", blocked(r, at)),
            Quantity::Force,
            force,
            d.rail_yield,
            true,
        )
        .judged(margin),
    );
    out.extend(crash_box(e, margin));
    if let Some(stroke) = d.bumper_stroke {
        let crush = r.max_crush.iter().copied().fold(0.0, f64::max);
        let detail = match r.bottomed {
            Some(b) => format!(
                "largest segment crush; bottomed at segment {} (y = {:.0} mm), t = {:.1} ms",
                b.segment + 1,
                b.centre * 1e3,
                b.time * 1e3
            ),
            None => "largest segment crush".into(),
        };
        out.push(bumper_stroke(e.test, detail, crush, stroke, margin));
    }
    let mut assumptions = vec![e.test.uncertain.to_string()];
    match engagement(d, e.test) {
        Engagement::Judged(c) => out.push(c.judged(margin)),
        Engagement::Whole => {}
        Engagement::Assumed(assumption) => assumptions.push(assumption),
    }
    out.extend(pulse(d, e.metrics, margin));
    if let Some(least) = d.bumper_energy_share {
        let share = e.energies.bumper_share;
        let detail = "bumper ÷ (bumper + structure)".to_string();
        out.push(
            Criterion::new(
                "bumper energy share".into(),
                detail,
                Quantity::Ratio,
                share,
                least,
                false,
            )
            .judged(margin),
        );
    }
    (out, assumptions)
}

/// Why the bumper's stroke is reported, not judged, in RCAR's structural
/// test (issue 45 item 8).
pub const STRUCTURAL: &str = "reported, not judged: the structural test crushes the bumper into its crash boxes by design; it judges the crash-box stroke and the rails";

/// Whether a test judges the bumper's stroke: every test but RCAR's
/// structural one, which is run to crush the bumper beam into its crash
/// boxes (RCAR structural protocol: the damage kept to the crash boxes and
/// the rails undeformed; its requirements, [`crate::requirements`], list
/// no bumper stroke). Judging it there made every bumper fail it
/// (`--target` found nothing at any stiffness).
pub fn bumper_stroke_judged(test: &Test) -> bool {
    !test.name.starts_with("rcar-structural")
}

/// The bumper stroke's criterion in `test`: the largest crush `crush`
/// against `stroke` (m), judged with `margin` where the test judges it
/// ([`bumper_stroke_judged`]), else reported with why.
pub(crate) fn bumper_stroke(
    test: &Test,
    detail: String,
    crush: f64,
    stroke: f64,
    margin: f64,
) -> Criterion {
    let judged = bumper_stroke_judged(test);
    let detail = match judged {
        true => detail,
        false => format!("{detail}; {STRUCTURAL}"),
    };
    let c = Criterion::new(
        "bumper stroke".into(),
        detail,
        Quantity::Length,
        crush,
        stroke,
        true,
    );
    match judged {
        true => c.judged(margin),
        false => c,
    }
}

fn crash_box(e: &Evidence, margin: f64) -> Option<Criterion> {
    let boxes = crash_boxes(e.car, e.result);
    let ((used, at), side) = match boxes {
        [Some(l), Some(r)] if l.0 >= r.0 => (l, "left"),
        [_, Some(r)] => (r, "right"),
        [Some(l), None] => (l, "left"),
        [None, None] => return None,
    };
    let stroke = e.limits.crash_box_stroke;
    let bottomed = match e.result.box_bottomed {
        Some(b) => format!(
            "; the {} crash box bottomed at t = {:.1} ms",
            b.side.name(),
            b.time * 1e3
        ),
        None => String::new(),
    };
    let detail = format!(
        "{side}: {:.0} % of the stroke{bottomed}{}",
        100.0 * used / stroke,
        blocked(e.result, at)
    );
    let c = Criterion::new(
        "crash-box stroke".into(),
        detail,
        Quantity::Length,
        used,
        stroke,
        true,
    );
    Some(match e.test.crash_box {
        true => c.judged(margin),
        false => c,
    })
}

/// What can be said of the beam's engagement with the striker.
pub(crate) enum Engagement {
    /// A criterion, judged from the beam's and the striker's heights.
    Judged(Criterion),
    /// Nothing to judge: the striker covers the whole front or its
    /// height is not known with the beam's heights given.
    Whole,
    /// The assumption made without the beam's heights.
    Assumed(String),
}

/// The least height range a pendulum's ridge is taken to span for the
/// beam engagement's margin ratio, m: a ridge set at one height (a corner
/// impact at 20 in) has no range of its own.
const SPAN: f64 = 0.05;

/// The beam's engagement with the striker.
pub(crate) fn engagement(d: &Damageability, test: &Test) -> Engagement {
    let mm = |v: f64| format!("{:.0} mm", v * 1e3);
    let Some([bottom, top]) = d.beam_height else {
        return match test.height {
            Height::Full => Engagement::Whole,
            Height::Unknown => Engagement::Assumed(
                "the striker's height is not known here: the beam is assumed to engage it".into(),
            ),
            Height::Ridge { low, high } => Engagement::Assumed(format!(
                "the beam is assumed to engage the impact ridge at {}-{} (no damageability.beam_height: override and underride not assessed)",
                mm(low),
                mm(high)
            )),
            Height::Face { bottom, top } => Engagement::Assumed(format!(
                "the beam is assumed to engage the barrier face at {}-{} (no damageability.beam_height: override and underride not assessed)",
                mm(bottom),
                mm(top)
            )),
        };
    };
    match test.height {
        Height::Full | Height::Unknown => Engagement::Whole,
        Height::Ridge { low, high } => {
            let cover = (low - bottom).min(top - high);
            // the limit is 0 mm (the ridge just within the beam): the share
            // is of the heights the ridge may be set to, at least 50 mm
            let (span, reference) = match high - low >= SPAN {
                true => (high - low, "the ridge's height range".to_string()),
                false => (
                    SPAN,
                    "the least ridge height range taken (the ridge is set at one height)".into(),
                ),
            };
            let detail = format!(
                "ridge at {}-{}, beam at {}-{}; the margin's share is of {reference}",
                mm(low),
                mm(high),
                mm(bottom),
                mm(top)
            );
            let c = Criterion::new(
                "beam engagement".into(),
                detail,
                Quantity::Length,
                cover,
                0.0,
                false,
            );
            Engagement::Judged(c.relative_to(span, reference))
        }
        Height::Face {
            bottom: low,
            top: high,
        } => {
            let overlap = top.min(high) - bottom.max(low);
            let need = 0.5 * (high - low);
            let detail = format!(
                "face at {}-{}, beam at {}-{}: override or underride below {}",
                mm(low),
                mm(high),
                mm(bottom),
                mm(top),
                mm(need)
            );
            Engagement::Judged(Criterion::new(
                "beam engagement".into(),
                detail,
                Quantity::Length,
                overlap,
                need,
                false,
            ))
        }
    }
}

pub(crate) fn pulse(d: &Damageability, m: &Metrics, margin: f64) -> Vec<Criterion> {
    let mut out = Vec::new();
    let limited = [
        (
            "deceleration (3 ms clip)",
            Some(m.clip),
            d.deceleration,
            Quantity::Acceleration,
        ),
        ("OLC", m.olc, d.olc, Quantity::Acceleration),
        ("ASI", m.asi, d.asi, Quantity::Ratio),
    ];
    for (name, value, limit, quantity) in limited {
        if let (Some(v), Some(l)) = (value, limit) {
            out.push(
                Criterion::new(name.into(), "body CG".into(), quantity, v, l, true).judged(margin),
            );
        }
    }
    out
}
