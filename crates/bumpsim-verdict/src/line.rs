//! The verdict of a car along a line (issue 46): a 1-D car whose model
//! runs each test along the car's centre line (the chain with nonlinear
//! links, `kind = "links"`, in `bumpsim-engine`) hands its histories here
//! ([`LineRun`]), and they are judged on the planar car's criteria
//! ([`crate::criteria`]) with the same limits (`[damageability]`, read by
//! [`crate::limits`]), margins, pulse metrics ([`Pulse::along`]) and
//! tables.
//!
//! The planar car's parts on the line, as the model maps them:
//!
//! - the **bumper** is the crush zone between the striker and m1 (the
//!   front link): the bumper stroke is its largest crush, the bumper's
//!   energy its plastic work;
//! - the **beam** is m1 and the **body** the last mass: the beam's travel
//!   relative to the body is the sum of the links' compressions; a
//!   clearance closed by the beam is judged on it, one closed by the
//!   front surface on the front link's crush plus it;
//! - the **crash box** is the first link behind the beam (m1 to m2; a car
//!   of one mass has none);
//! - the **rails** carry the force of the last link into the body
//!   (spring and damper), shared equally by two side members: the rail
//!   force is half of it;
//! - the **pulse** is the body's velocity along the impact.
//!
//! A line has no width, no height and no tyres: every clearance is judged
//! on the centre line (a clearance's `lateral` range is not used and the
//! verdict says so), the test's face angle and overlap are dropped (the
//! protocols' table says what, [`bumpsim_io::protocols::Test::dropped_in_1d`]),
//! the beam's engagement is judged from the heights as for the planar
//! car, and the car is free along the line (no rolling resistance).

use crate::criteria::{
    Criterion, Energies, Engagement, Quantity, bumper_stroke, engagement, pulse,
};
use crate::error::VerdictError;
use crate::limits::{Closer, Damageability};
use crate::protocol::Test;
use crate::pulse::{AsiMethod, Pulse};
use crate::verdict::{TestVerdict, Verdict};

/// What a 1-D run of one test gives the verdict, at its samples (SI; the
/// car's frame: compressions positive).
#[derive(Debug, Clone, PartialEq)]
pub struct LineRun {
    /// Sample times, s (first contact at 0).
    pub time: Vec<f64>,
    /// The striker's (or barrier's) force on the car, N, pushing positive.
    pub force: Vec<f64>,
    /// The bumper's crush (the front link), m (None: no bumper, the
    /// striker meets m1).
    pub bumper: Option<Vec<f64>>,
    /// The beam's travel relative to the body, m.
    pub beam_travel: Vec<f64>,
    /// The crash box's compression, m (None: a car of one mass).
    pub crash_box: Option<Vec<f64>>,
    /// The force into the body through the rails, both sides, N.
    pub body_force: Vec<f64>,
    /// The body's velocity along x towards the struck end, m/s.
    pub body_velocity: Vec<f64>,
    /// The run's energies.
    pub energies: Energies,
    /// The simulation's warnings.
    pub warnings: Vec<String>,
}

/// How one test of a line car is judged: the test, the end's limits, the
/// striker as the protocol words it, the margin ratio and the ASI's method.
#[derive(Debug, Clone, Copy)]
pub struct Judging<'a> {
    /// The test.
    pub test: &'static Test,
    /// The struck end's clearances and limits.
    pub limits: &'a Damageability,
    /// The striker in the protocol's words.
    pub striker: &'a str,
    /// Least margin ratio a criterion must keep.
    pub margin: f64,
    /// How the ASI averages the accelerations.
    pub asi_method: AsiMethod,
}

/// Refuses limits that contradict each other on a line: every clearance
/// closed by the beam lies between the rails, so its gap must exceed the
/// crash-box stroke (as [`Damageability::check_car`] for a planar car).
pub fn check(limits: &Damageability) -> Result<(), VerdictError> {
    for (i, c) in limits.clearances.iter().enumerate() {
        if c.from == Closer::Beam && c.gap <= limits.crash_box_stroke {
            return Err(VerdictError::Contradiction {
                first: format!("damageability.clearance[{}].gap", i + 1),
                second: "damageability.crash_box_stroke".into(),
                reason: format!(
                    "'{}' sits {} mm behind the beam, but the crash box may travel {} mm: the beam would reach it before the crash box's stroke is used; a stroke must stay within the clearances it moves the beam towards",
                    c.name,
                    c.gap * 1e3,
                    limits.crash_box_stroke * 1e3
                ),
            });
        }
    }
    Ok(())
}

/// A test with nothing judged yet (`skipped`: why it is not assessed).
fn empty(test: &'static Test, skipped: Option<String>) -> TestVerdict {
    TestVerdict {
        skipped,
        ..TestVerdict::empty(test)
    }
}

/// A test of an end no car file describes.
pub fn not_assessed(test: &'static Test) -> TestVerdict {
    let why = format!("no car file of the {} end was given", test.end.name());
    empty(test, Some(why))
}

/// The largest value of `values` and its time, s (0 at the first sample
/// when it never exceeds 0).
fn peak(time: &[f64], values: impl Iterator<Item = f64>) -> (f64, f64) {
    let first = time.first().copied().unwrap_or(0.0);
    time.iter().zip(values).fold(
        (0.0, first),
        |best, (t, v)| if v > best.0 { (v, *t) } else { best },
    )
}

fn ms(t: f64) -> String {
    format!("t = {:.1} ms", t * 1e3)
}

/// The clearances, the rail force, the crash-box and bumper strokes.
fn structure(j: &Judging<'_>, run: &LineRun) -> Vec<Criterion> {
    let (d, time) = (j.limits, &run.time);
    let bumper = |k: usize| run.bumper.as_ref().map_or(0.0, |b| b[k]);
    let mut out: Vec<Criterion> = d
        .clearances
        .iter()
        .map(|c| {
            let (what, (travel, at)) = match c.from {
                Closer::Beam => ("beam travel", peak(time, run.beam_travel.iter().copied())),
                Closer::Front => {
                    let front = (0..time.len()).map(|k| bumper(k) + run.beam_travel[k]);
                    ("front travel", peak(time, front))
                }
            };
            let detail = format!("{what} on the centre line, {}", ms(at));
            Criterion::new(
                format!("clearance: {}", c.name),
                detail,
                Quantity::Length,
                travel,
                c.gap,
                true,
            )
            .judged(j.margin)
        })
        .collect();
    let (rails, at) = peak(time, run.body_force.iter().map(|f| 0.5 * f));
    let detail = format!(
        "half the force into the body (two side members), {}",
        ms(at)
    );
    out.push(
        Criterion::new(
            "rail force".into(),
            detail,
            Quantity::Force,
            rails,
            d.rail_yield,
            true,
        )
        .judged(j.margin),
    );
    if let Some(boxes) = &run.crash_box {
        let (used, at) = peak(time, boxes.iter().copied());
        let stroke = d.crash_box_stroke;
        let detail = format!(
            "link 1 (m1 to m2): {:.0} % of the stroke, {}",
            100.0 * used / stroke,
            ms(at)
        );
        let c = Criterion::new(
            "crash-box stroke".into(),
            detail,
            Quantity::Length,
            used,
            stroke,
            true,
        );
        out.push(match j.test.crash_box {
            true => c.judged(j.margin),
            false => c,
        });
    }
    if let Some(stroke) = d.bumper_stroke {
        let (crush, at) = peak(time, (0..time.len()).map(bumper));
        let detail = match run.bumper {
            Some(_) => format!("the front link's largest crush, {}", ms(at)),
            None => "no front link: the striker meets m1".into(),
        };
        out.push(bumper_stroke(j.test, detail, crush, stroke, j.margin));
    }
    out
}

/// What a verdict along the line assumes besides the test's own.
fn assumptions(j: &Judging<'_>) -> Vec<String> {
    let mut out = vec![j.test.uncertain.to_string()];
    let line = match j.test.entry.dropped_in_1d() {
        Some(dropped) => format!("run along the car's centre line (1-D): {dropped}"),
        None => "run along the car's centre line (1-D)".into(),
    };
    out.push(line);
    out.push(
        "the car is free along the line: no tyres, no rolling resistance; the force into the body is shared equally by two side members".into(),
    );
    let lateral: Vec<&str> = j
        .limits
        .clearances
        .iter()
        .filter(|c| c.lateral.is_some())
        .map(|c| c.name.as_str())
        .collect();
    if !lateral.is_empty() {
        out.push(format!(
            "a line has no width: the lateral ranges of {} are not used, each is judged on the centre line",
            lateral.join(", ")
        ));
    }
    out
}

/// One test of a line car judged from its run.
pub fn judge(j: &Judging<'_>, run: &LineRun) -> TestVerdict {
    let d = j.limits;
    // every pulse metric, as the planar verdict computes them
    let pulse_of = Pulse::along(&run.time, &run.force, &run.body_velocity);
    let (metrics, notes) = pulse_of.metrics(true, j.asi_method);
    let mut criteria = structure(j, run);
    let mut assumed = assumptions(j);
    match engagement(d, j.test) {
        Engagement::Judged(c) => criteria.push(c.judged(j.margin)),
        Engagement::Whole => {}
        Engagement::Assumed(assumption) => assumed.push(assumption),
    }
    criteria.extend(pulse(d, &metrics, j.margin));
    if let Some(least) = d.bumper_energy_share {
        criteria.push(
            Criterion::new(
                "bumper energy share".into(),
                "bumper ÷ (bumper + structure)".into(),
                Quantity::Ratio,
                run.energies.bumper_share,
                least,
                false,
            )
            .judged(j.margin),
        );
    }
    let mut verdict = empty(j.test, None);
    verdict.striker = j.striker.to_string();
    verdict.criteria = criteria;
    verdict.metrics = Some(metrics);
    verdict.energies = Some(run.energies);
    verdict.assumptions = assumed;
    verdict.notes = notes;
    verdict.warnings = run.warnings.clone();
    verdict
}

/// The verdict of the car `car` in `tests` (the tests asked, in order)
/// from each test's [`TestVerdict`].
pub fn verdict(
    car: String,
    margin: f64,
    tests: &[&'static Test],
    judged: Vec<TestVerdict>,
) -> Verdict {
    Verdict {
        car,
        margin,
        tests: judged,
        propagation: None,
        requirements: crate::requirements::run(tests),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::criteria::Outcome;

    fn limits() -> Damageability {
        let text = "length_unit = \"mm\"\n[damageability]\nrail_yield = 100e3\ncrash_box_stroke = 40.0\nbumper_stroke = 60.0\n[[damageability.clearance]]\nname = \"radiator\"\ngap = 50.0\nfrom = \"beam\"\n[[damageability.clearance]]\nname = \"lamp\"\ngap = 90.0\nfrom = \"front\"\nlateral = [500.0, 700.0]\n";
        Damageability::parse(text, "car.toml".as_ref()).unwrap()
    }

    /// A made-up run: triangles of known peaks at known times.
    fn run() -> LineRun {
        let time: Vec<f64> = (0..=400).map(|k| k as f64 * 1e-4).collect();
        let tri = |top: f64, at: f64| {
            time.iter()
                .map(|t| (top * (1.0 - (t - at).abs() / at)).max(0.0))
                .collect::<Vec<_>>()
        };
        LineRun {
            force: tri(80e3, 0.02),
            bumper: Some(tri(0.03, 0.02)),
            beam_travel: tri(0.045, 0.015),
            crash_box: Some(tri(0.02, 0.01)),
            body_force: tri(150e3, 0.02),
            body_velocity: time.iter().map(|t| 2.0 - 50.0 * t.min(0.02)).collect(),
            energies: Energies {
                initial: 1.0,
                bumper: 0.3,
                absorber: 0.0,
                structure: 0.5,
                kinetic: 0.2,
                tyres: 0.0,
                bumper_share: 0.3 / 0.8,
            },
            warnings: vec![],
            time,
        }
    }

    #[test]
    fn the_line_criteria_read_the_peaks_of_their_histories() {
        let limits = limits();
        let test = crate::protocol::test("part581-pendulum-front").unwrap();
        let j = Judging {
            test,
            limits: &limits,
            striker: "pendulum",
            margin: 0.0,
            asi_method: AsiMethod::default(),
        };
        let v = judge(&j, &run());
        let find = |name: &str| v.criteria.iter().find(|c| c.name == name).unwrap();
        let radiator = find("clearance: radiator");
        assert!((radiator.value - 0.045).abs() < 1e-12 && radiator.outcome == Outcome::Pass);
        assert!(
            radiator.detail.contains("t = 15.0 ms"),
            "{}",
            radiator.detail
        );
        // front: bumper crush + beam travel, largest at 15 ms (the beam's
        // peak falls faster than the crush rises): 0.03·(1 − 5/20) + 0.045
        let lamp = find("clearance: lamp");
        assert!((lamp.value - 0.0675).abs() < 1e-9, "{}", lamp.value);
        // the rails: half of 150 kN against 100 kN
        let rails = find("rail force");
        assert!((rails.value - 75e3).abs() < 1e-6 && rails.outcome == Outcome::Pass);
        assert_eq!(find("crash-box stroke").value, 0.02);
        assert_eq!(find("bumper stroke").value, 0.03);
        // ΔV: 2 m/s to 1 m/s by the contact's end
        let m = v.metrics.unwrap();
        assert!((m.delta_v - 1.0).abs() < 1e-2, "{}", m.delta_v);
        assert!((m.peak - 50.0).abs() < 1e-6, "{}", m.peak);
        assert!(
            v.assumptions
                .iter()
                .any(|a| a.contains("lamp are not used")),
            "{:?}",
            v.assumptions
        );
        assert!(v.passed() == Some(true));
    }

    #[test]
    fn a_beam_clearance_within_the_crash_box_stroke_is_refused() {
        let mut limits = limits();
        limits.crash_box_stroke = 0.05;
        let e = check(&limits).unwrap_err().to_string();
        assert!(
            e.contains("radiator") && e.contains("crash_box_stroke"),
            "{e}"
        );
    }
}
