//! Bumper targets, the inverse question: for a car and a set of tests, the
//! region of bumper characteristics that passes every criterion with the
//! margin asked for, the criterion binding at each boundary, and the
//! force–deflection corridor of the passing characteristics.
//!
//! **Family.** Every characteristic `F(d)` of the car's bumper segments is
//! scaled in force by `a` and in deflection by `b`: `F'(d) = a F(d/b)`, so a
//! three-part bumper keeps its shape with ramp `s·(a/b)` and plateau
//! `F_max·a`, a tabulated one its curve (the "tabulated corridor"); the
//! unloading slope scales like the ramp. The search's axes are the whole
//! bumper's initial stiffness `x = (a/b)·x₀` (N/m: the ramp, or the
//! table's first slope) and its force level `y = a·y₀` (N: the plateau, or
//! the table's largest force).
//!
//! **Search.** Rows of log-spaced stiffnesses; in each row, a coarse scan
//! of log-spaced force levels, then bisection of each pass/fail transition
//! of the longest passing run to a relative tolerance, naming the failing
//! criterion (and its test) just outside each boundary. Rows and their
//! scans run in parallel (rayon); every candidate runs every test of the set, and no
//! candidate runs twice (the scan's outcomes start the bisections, the
//! stroke is the passing end's). A passing
//! interval narrower than the scan's spacing can be missed; the corridor
//! is the envelope of the passing characteristics, and a curve inside it
//! is not guaranteed to pass: check it with the verdict.
//!
//! **Step.** The candidates integrate with the one step rule of
//! `bumpsim_core::leapfrog` at a safety factor of [`SEARCH_SAFETY`] of the
//! critical step (the verdict's 0.05 is set for histories accurate to
//! 1e-9) and record every [`SEARCH_OUTPUT_STEP`]: over the example's
//! search range (¼ to 4 times its stiffness and force level, every test
//! of 49 CFR 581 and the RCAR bumper test) every margin ratio is within
//! 4e-4 of the verdict's, far inside the boundaries' 1 % (test
//! `the_search_step_keeps_every_margin_ratio_within_1e_3`).

use crate::error::{VerdictError, require};
use crate::verdict::{CarEnd, Setup};
use bumpsim_impact::bumper::{Bumper, Loading};
use bumpsim_planar::Settings;
use rayon::prelude::*;
use serde::Serialize;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The candidates' fraction of the critical step (the verdict's is 0.05).
pub const SEARCH_SAFETY: f64 = 0.3;

/// The candidates' recording interval, s (the verdict's is 0.1 ms).
pub const SEARCH_OUTPUT_STEP: f64 = 2e-4;

/// The integration settings of the search's candidates: the set-up's,
/// with a safety factor of at least [`SEARCH_SAFETY`] and a recording
/// interval of at least [`SEARCH_OUTPUT_STEP`] (the step from the rule).
pub fn search_settings(settings: &Settings) -> Settings {
    Settings {
        safety: settings.safety.max(SEARCH_SAFETY),
        output_step: settings.output_step.max(SEARCH_OUTPUT_STEP),
        step: None,
        ..*settings
    }
}

/// The search's ranges and resolution.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TargetOptions {
    /// Whole-bumper initial stiffness range, N/m (None: ¼ to 4 times the car's).
    pub stiffness: Option<[f64; 2]>,
    /// Whole-bumper force-level range, N (None: ¼ to 4 times the car's).
    pub force: Option<[f64; 2]>,
    /// Number of stiffness rows.
    pub rows: usize,
    /// Number of force levels of each row's coarse scan.
    pub levels: usize,
    /// Relative tolerance of the boundaries.
    pub tolerance: f64,
}

impl Default for TargetOptions {
    fn default() -> Self {
        TargetOptions {
            stiffness: None,
            force: None,
            rows: 12,
            levels: 9,
            tolerance: 0.01,
        }
    }
}

/// A boundary of a row's passing interval.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Bound {
    /// The force level, N.
    pub force: f64,
    /// The criterion failing just outside, and its test (None: the
    /// boundary is the search range's edge).
    pub binding: Option<String>,
}

/// One stiffness row of the region.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Row {
    /// Whole-bumper initial stiffness, N/m.
    pub stiffness: f64,
    /// The passing interval's lower and upper bound (None: nothing passes).
    pub interval: Option<[Bound; 2]>,
    /// The largest bumper crush at the interval's lower bound, m: the
    /// stroke a bumper of this stiffness needs.
    pub stroke: Option<f64>,
    /// The failing criterion of the row's middle level when nothing passes.
    pub failing: Option<String>,
}

/// The force–deflection corridor of the passing characteristics (whole
/// bumper).
#[derive(Debug, Clone, PartialEq, Serialize, Default)]
pub struct Corridor {
    /// Deflections, m.
    pub deflection: Vec<f64>,
    /// The least force of a passing characteristic, N.
    pub lower: Vec<f64>,
    /// The largest force of a passing characteristic, N.
    pub upper: Vec<f64>,
}

/// The region of passing bumpers.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Region {
    /// The car's own bumper: initial stiffness (N/m) and force level (N).
    pub origin: [f64; 2],
    /// Whether the family is three-part (ramp and plateau) or tabulated.
    pub tabulated: bool,
    /// The margin ratio asked for.
    pub margin: f64,
    /// The rows, stiffness increasing.
    pub rows: Vec<Row>,
    /// The corridor of the passing characteristics.
    pub corridor: Corridor,
    /// Impacts simulated.
    pub impacts: usize,
    /// Wall time of the search, s.
    pub seconds: f64,
    /// When nothing passes at any stiffness: which criterion and test rule
    /// out every bumper, the test's energy budget and what would have to
    /// change ([`crate::diagnosis`]).
    pub diagnosis: Option<String>,
}

impl Region {
    /// The row at the car's own stiffness, if the search range holds it.
    pub fn own_row(&self) -> Option<&Row> {
        let own = self.origin[0];
        self.rows
            .iter()
            .find(|r| (r.stiffness / own - 1.0).abs() < 1e-9)
    }

    /// Impacts per second of the search.
    pub fn rate(&self) -> f64 {
        self.impacts as f64 / self.seconds.max(1e-9)
    }

    /// Whether a whole-bumper stiffness (N/m) and force level (N) lie in
    /// the region: between its neighbouring rows' intervals, interpolated
    /// in the logarithms.
    pub fn contains(&self, stiffness: f64, force: f64) -> bool {
        let i = self.rows.partition_point(|r| r.stiffness <= stiffness);
        if i == 0 || i == self.rows.len() {
            return false;
        }
        let (a, b) = (&self.rows[i - 1], &self.rows[i]);
        let (Some(ia), Some(ib)) = (&a.interval, &b.interval) else {
            return false;
        };
        let w = (stiffness / a.stiffness).ln() / (b.stiffness / a.stiffness).ln();
        let between = |k: usize| (ia[k].force.ln() * (1.0 - w) + ib[k].force.ln() * w).exp();
        force >= between(0) && force <= between(1)
    }
}

/// The family of characteristics around the car's own.
#[derive(Debug, Clone)]
struct Family {
    segments: Vec<Bumper>,
    origin: [f64; 2],
    tabulated: bool,
}

fn initial_slope(b: &Bumper) -> f64 {
    match b.loading() {
        Loading::ThreePart { ramp, .. } => *ramp,
        Loading::Table { compression, force } => force[1] / compression[1],
    }
}

fn level(b: &Bumper) -> f64 {
    match b.loading() {
        Loading::ThreePart { plateau, .. } => *plateau,
        Loading::Table { force, .. } => force.iter().copied().fold(0.0, f64::max),
    }
}

/// `F'(d) = a F(d/b)` with the unloading slope scaled like the ramp.
fn transformed(bumper: &Bumper, a: f64, b: f64) -> Result<Bumper, VerdictError> {
    let unloading = bumper.unloading_slope() * a / b;
    let made = match bumper.loading() {
        Loading::ThreePart { ramp, plateau } => {
            Bumper::three_part(ramp * a / b, plateau * a, unloading)
        }
        Loading::Table { compression, force } => Bumper::table(
            compression.iter().map(|d| d * b).collect(),
            force.iter().map(|f| f * a).collect(),
            unloading,
        ),
    };
    made.map_err(|e| VerdictError::Value {
        key: "bumper".into(),
        value: a,
        unit: "1",
        expected: format!("the scaled characteristic is not valid: {e}"),
    })
}

impl Family {
    fn of(end: &CarEnd) -> Family {
        let segments = end.car.beam().segments.clone();
        let x: f64 = segments.iter().map(initial_slope).sum();
        let y: f64 = segments.iter().map(level).sum();
        let tabulated = segments
            .iter()
            .any(|s| matches!(s.loading(), Loading::Table { .. }));
        Family {
            segments,
            origin: [x, y],
            tabulated,
        }
    }

    fn scales(&self, stiffness: f64, force: f64) -> (f64, f64) {
        let a = force / self.origin[1];
        (a, a / (stiffness / self.origin[0]))
    }

    fn segments(&self, stiffness: f64, force: f64) -> Result<Vec<Bumper>, VerdictError> {
        let (a, b) = self.scales(stiffness, force);
        self.segments.iter().map(|s| transformed(s, a, b)).collect()
    }

    /// The whole bumper's loading force at deflection `d`, N.
    fn force(&self, stiffness: f64, force: f64, d: f64) -> f64 {
        let (a, b) = self.scales(stiffness, force);
        self.segments
            .iter()
            .map(|s| a * s.loading_force(d / b))
            .sum()
    }
}

/// What one candidate gives: pass, the worst criterion ("name (test)"),
/// and the largest bumper crush (m).
struct Candidate {
    pass: bool,
    worst: String,
    crush: f64,
}

struct Search<'a> {
    /// The set-up with the search's settings ([`search_settings`]).
    setup: Setup,
    family: Family,
    impacts: &'a AtomicUsize,
}

impl Search<'_> {
    fn evaluate(&self, stiffness: f64, force: f64) -> Result<Candidate, VerdictError> {
        let segments = self.family.segments(stiffness, force)?;
        let mut setup = Setup {
            front: None,
            rear: None,
            ..self.setup.clone()
        };
        for (slot, end) in [
            (&mut setup.front, &self.setup.front),
            (&mut setup.rear, &self.setup.rear),
        ] {
            if let Some(end) = end {
                *slot = Some(end.with_segments(segments.clone())?);
            }
        }
        let (mut pass, mut worst, mut crush) = (true, (f64::INFINITY, String::new()), 0.0f64);
        for v in crate::verdict::run_all(&setup, false, false)? {
            let test = v.test;
            if v.skipped.is_some() {
                continue;
            }
            self.impacts.fetch_add(1, Ordering::Relaxed);
            pass &= v.passed() == Some(true);
            if let Some(c) = v.binding().filter(|c| c.ratio < worst.0) {
                worst = (c.ratio, format!("{} ({})", c.name, test.name));
            }
            crush = crush.max(v.result.map_or(0.0, |r| r.max_compression));
        }
        Ok(Candidate {
            pass,
            worst: worst.1,
            crush,
        })
    }

    /// Bisects between a failing and a passing level (log scale), both
    /// evaluated already: the passing end with the failing end's worst
    /// criterion, and the passing end's crush (m).
    fn boundary(
        &self,
        stiffness: f64,
        fail: (f64, &Candidate),
        pass: (f64, &Candidate),
        tolerance: f64,
    ) -> Result<(Bound, f64), VerdictError> {
        let (mut fail, mut worst) = (fail.0, fail.1.worst.clone());
        let (mut pass, mut crush) = (pass.0, pass.1.crush);
        while (pass / fail).ln().abs() > tolerance {
            let mid = (fail * pass).sqrt();
            let o = self.evaluate(stiffness, mid)?;
            match o.pass {
                true => (pass, crush) = (mid, o.crush),
                false => (fail, worst) = (mid, o.worst),
            }
        }
        let bound = Bound {
            force: pass,
            binding: Some(worst),
        };
        Ok((bound, crush))
    }

    fn row(&self, stiffness: f64, levels: &[f64], tolerance: f64) -> Result<Row, VerdictError> {
        // the scan's levels in parallel too: rows end unevenly
        let outcomes = levels
            .par_iter()
            .map(|&f| self.evaluate(stiffness, f))
            .collect::<Result<Vec<_>, _>>()?;
        let Some((first, last)) = longest_run(&outcomes) else {
            let middle = &outcomes[outcomes.len() / 2];
            return Ok(Row {
                stiffness,
                interval: None,
                stroke: None,
                failing: Some(middle.worst.clone()),
            });
        };
        let at = |i: usize| (levels[i], &outcomes[i]);
        let edge = |i: usize| {
            let bound = Bound {
                force: levels[i],
                binding: None,
            };
            (bound, outcomes[i].crush)
        };
        let low = match first {
            0 => edge(0),
            i => self.boundary(stiffness, at(i - 1), at(i), tolerance)?,
        };
        let high = match last + 1 == levels.len() {
            true => edge(last),
            false => self.boundary(stiffness, at(last + 1), at(last), tolerance)?,
        };
        Ok(Row {
            stiffness,
            interval: Some([low.0, high.0]),
            stroke: Some(low.1),
            failing: None,
        })
    }
}

/// The first and last index of the longest run of passing outcomes.
fn longest_run(outcomes: &[Candidate]) -> Option<(usize, usize)> {
    let mut best: Option<(usize, usize)> = None;
    let mut start = None;
    for (i, o) in outcomes.iter().enumerate() {
        match (o.pass, start) {
            (true, None) => start = Some(i),
            (false, Some(s)) => {
                if best.is_none_or(|(a, b)| i - s > b - a + 1) {
                    best = Some((s, i - 1));
                }
                start = None;
            }
            _ => {}
        }
    }
    if let Some(s) = start
        && best.is_none_or(|(a, b)| outcomes.len() - s > b - a + 1)
    {
        best = Some((s, outcomes.len() - 1));
    }
    best
}

fn spaced(range: [f64; 2], n: usize) -> Vec<f64> {
    let (lo, hi) = (range[0].ln(), range[1].ln());
    (0..n)
        .map(|i| (lo + (hi - lo) * i as f64 / (n - 1).max(1) as f64).exp())
        .collect()
}

/// The rows' stiffnesses: `n` log-spaced over the range and, when it lies
/// inside and is not one of them, the car's own, so that a row answers
/// for the car's stiffness (issue 45).
fn stiffnesses(range: [f64; 2], n: usize, own: f64) -> Vec<f64> {
    let mut rows = spaced(range, n);
    let listed = rows.iter().any(|x| (x / own - 1.0).abs() < 1e-9);
    if own > range[0] && own < range[1] && !listed {
        rows.insert(rows.partition_point(|&x| x < own), own);
    }
    rows
}

fn check(options: &TargetOptions, origin: [f64; 2]) -> Result<([f64; 2], [f64; 2]), VerdictError> {
    let ranges = [
        (
            "--stiffness",
            options
                .stiffness
                .unwrap_or([origin[0] / 4.0, origin[0] * 4.0]),
            "N/m",
        ),
        (
            "--force",
            options.force.unwrap_or([origin[1] / 4.0, origin[1] * 4.0]),
            "N",
        ),
    ];
    for (key, [lo, hi], unit) in ranges {
        require(
            key,
            lo,
            unit,
            &format!("a range from a positive value up to a larger one ({hi})"),
            lo > 0.0 && hi.is_finite() && hi > lo,
        )?;
    }
    let counts = [("rows", options.rows), ("levels", options.levels)];
    for (key, n) in counts {
        require(key, n as f64, "1", "from 2 to 200", (2..=200).contains(&n))?;
    }
    let t = options.tolerance;
    require(
        "tolerance",
        t,
        "1",
        "a relative tolerance in (0, 0.5]",
        t > 0.0 && t <= 0.5,
    )?;
    Ok((ranges[0].1, ranges[1].1))
}

/// Searches the region of passing bumpers for the set-up's car (the
/// front's bumper family, else the rear's) and tests.
pub fn search(setup: &Setup, options: &TargetOptions) -> Result<Region, VerdictError> {
    let start = std::time::Instant::now();
    let end = setup
        .front
        .as_ref()
        .or(setup.rear.as_ref())
        .ok_or_else(|| VerdictError::Missing {
            path: "car".into(),
            key: "car".into(),
            expected: "a car file of the end the tests strike".into(),
        })?;
    let family = Family::of(end);
    let (stiffness, force) = check(options, family.origin)?;
    let levels = spaced(force, options.levels);
    let impacts = AtomicUsize::new(0);
    let search = Search {
        setup: Setup {
            settings: search_settings(&setup.settings),
            ..setup.clone()
        },
        family: family.clone(),
        impacts: &impacts,
    };
    let rows = stiffnesses(stiffness, options.rows, family.origin[0])
        .par_iter()
        .map(|&x| search.row(x, &levels, options.tolerance))
        .collect::<Result<Vec<_>, _>>()?;
    let corridor = corridor(&family, &rows);
    let failing: Vec<Option<&str>> = rows
        .iter()
        .map(|r| match r.interval {
            Some(_) => None,
            None => Some(r.failing.as_deref().unwrap_or("")),
        })
        .collect();
    let diagnosis = crate::diagnosis::nothing_passes(setup, &failing)?;
    Ok(Region {
        diagnosis,
        origin: family.origin,
        tabulated: family.tabulated,
        margin: setup.margin,
        rows,
        corridor,
        impacts: impacts.load(Ordering::Relaxed),
        seconds: start.elapsed().as_secs_f64(),
    })
}

/// The envelope of the rows' passing characteristics over the deflections
/// up to the largest stroke a row needs (at least twice the car's knee).
fn corridor(family: &Family, rows: &[Row]) -> Corridor {
    let passing: Vec<(f64, [f64; 2])> = rows
        .iter()
        .filter_map(|r| {
            r.interval
                .as_ref()
                .map(|i| (r.stiffness, [i[0].force, i[1].force]))
        })
        .collect();
    if passing.is_empty() {
        return Corridor::default();
    }
    let knee = family.origin[1] / family.origin[0];
    let reach = rows
        .iter()
        .filter_map(|r| r.stroke)
        .fold(2.0 * knee, f64::max);
    let deflection: Vec<f64> = (0..=100).map(|i| reach * i as f64 / 100.0).collect();
    let curve = |x: f64, y: f64, d: f64| family.force(x, y, d);
    let lower = deflection
        .iter()
        .map(|&d| {
            passing
                .iter()
                .map(|&(x, [lo, _])| curve(x, lo, d))
                .fold(f64::INFINITY, f64::min)
        })
        .collect();
    let upper = deflection
        .iter()
        .map(|&d| {
            passing
                .iter()
                .map(|&(x, [_, hi])| curve(x, hi, d))
                .fold(0.0, f64::max)
        })
        .collect();
    Corridor {
        deflection,
        lower,
        upper,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::limits::Damageability;
    use crate::protocol::select;
    use crate::verdict::judge;
    use std::path::Path;

    /// The worked example's front in 49 CFR 581 and the RCAR bumper test.
    fn example() -> Setup {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/verdict/car.toml");
        let car = bumpsim_planar::PlanarCar::read(&path).unwrap();
        let end = CarEnd::new(car, Damageability::read(&path).unwrap()).unwrap();
        Setup::new(vec![end], select(&["part581", "rcar-bumper"]).unwrap(), 0.0).unwrap()
    }

    /// A target candidate's car is the user's car with other segments:
    /// its contact rate and effective width stay (they were dropped when
    /// the end was rebuilt from its parts).
    #[test]
    fn a_candidate_keeps_the_cars_contact_rate_and_effective_width() {
        let end = &example().front.unwrap();
        let car = end.car.clone().with_contact_rate(0.5).unwrap();
        let width = 1.05 * car.effective_width();
        let car = car.with_effective_width(width).unwrap();
        let end = CarEnd::new(car, end.limits.clone()).unwrap();
        let family = Family::of(&end);
        let [x0, y0] = family.origin;
        let segments = family.segments(1.5 * x0, 0.8 * y0).unwrap();
        let candidate = end.with_segments(segments).unwrap();
        assert!((candidate.car.contact_rate() - 0.5).abs() < 1e-12);
        assert!((candidate.car.effective_width() - width).abs() < 1e-12);
    }

    /// Every criterion's margin ratio at the search's step and recording
    /// against the verdict's, at the corners and the centre of the
    /// default search range: within 1e-3 (4e-4 measured), far inside the
    /// boundaries' 1 % tolerance.
    #[test]
    fn the_search_step_keeps_every_margin_ratio_within_1e_3() {
        let setup = example();
        let family = Family::of(setup.front.as_ref().unwrap());
        let [x0, y0] = family.origin;
        for (x, y) in [
            (0.25, 0.25),
            (0.25, 4.0),
            (1.0, 1.0),
            (4.0, 0.25),
            (4.0, 4.0),
        ] {
            let segments = family.segments(x * x0, y * y0).unwrap();
            let front = setup.front.as_ref().unwrap().with_segments(segments);
            let fine = Setup {
                front: Some(front.unwrap()),
                ..setup.clone()
            };
            let coarse = Setup {
                settings: search_settings(&fine.settings),
                ..fine.clone()
            };
            for test in &setup.tests {
                let (a, b) = (judge(&fine, test).unwrap(), judge(&coarse, test).unwrap());
                for (p, q) in a.criteria.iter().zip(&b.criteria) {
                    assert_eq!(p.name, q.name);
                    assert!(
                        (p.ratio - q.ratio).abs() <= 1e-3,
                        "{x} x {y}, {}: {} margin ratio {} at the verdict's step, {} at the search's",
                        test.name,
                        p.name,
                        p.ratio,
                        q.ratio
                    );
                }
            }
        }
    }
}
