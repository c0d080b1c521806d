//! The verdict of a car and its bumper in a set of tests: each test run on
//! the planar car of the end it strikes (`bumpsim_planar::simulate`, the
//! protocol's tyre condition), its criteria judged with their margins
//! ([`crate::criteria`]), its pulse metrics and energies. A test of an end
//! without a car file is listed as not assessed, with the reason. The tests
//! run in parallel.

use crate::criteria::{Criterion, Energies, Evidence, Outcome, criteria, energies};
use crate::error::{VerdictError, require};
use crate::limits::{Damageability, End};
use crate::protocol::Test;
use crate::pulse::{AsiMethod, Metrics, Pulse};
use crate::requirements::Requirements;
use crate::sequence::{Inherited, changes};
use crate::uncertainty::Propagation;
use bumpsim_estimate::propagate::Probability;
use bumpsim_impact::bumper::Bumper;
use bumpsim_impact::bumper::BumperState;
use bumpsim_planar::car::Block;
use bumpsim_planar::result::{Bottomed, BoxBottomed};
use bumpsim_planar::{PlanarCar, PlanarResult, Settings, Striker, simulate};
use rayon::prelude::*;
use serde::Serialize;
use std::path::Path;

/// One end of a car: its planar car and its damageability data.
#[derive(Debug, Clone, PartialEq)]
pub struct CarEnd {
    /// The planar car of that end.
    pub car: PlanarCar,
    /// Its clearances and limits.
    pub limits: Damageability,
}

impl CarEnd {
    /// Checks the limits against the car. A car without a `bumper.depth`
    /// takes `damageability.bumper_stroke` (the same crushable depth) as
    /// its segments' depth, with the default block stiffness
    /// ([`bumpsim_planar::car::DEFAULT_BLOCK_STIFFNESS`]); one with both
    /// must give the same depth. Likewise its crash boxes block at
    /// `damageability.crash_box_stroke` unless `[crash_boxes] depth` says
    /// the same ([`bumpsim_planar::car::DEFAULT_CRASH_BOX_BLOCK_STIFFNESS`]).
    pub fn new(car: PlanarCar, limits: Damageability) -> Result<CarEnd, VerdictError> {
        limits.check_car(&car)?;
        let car = match (car.beam().block, limits.bumper_stroke) {
            (None, Some(depth)) => {
                let n = car.beam().segments.len() as f64;
                let stiffness = bumpsim_planar::car::DEFAULT_BLOCK_STIFFNESS / n;
                let block = Block { depth, stiffness };
                car.with_block(Some(block))
                    .map_err(|e| planar("bumper", e))?
            }
            (Some(block), Some(stroke)) => {
                same_depth(
                    "bumper.depth",
                    block.depth,
                    "damageability.bumper_stroke",
                    stroke,
                )?;
                car
            }
            _ => car,
        };
        let stroke = limits.crash_box_stroke;
        let car = match car.crash_boxes() {
            None => {
                let stiffness = bumpsim_planar::car::DEFAULT_CRASH_BOX_BLOCK_STIFFNESS;
                let block = Block {
                    depth: stroke,
                    stiffness,
                };
                car.with_crash_boxes(Some(block))
                    .map_err(|e| planar("crash boxes", e))?
            }
            Some(block) => {
                same_depth(
                    "crash_boxes.depth",
                    block.depth,
                    "damageability.crash_box_stroke",
                    stroke,
                )?;
                car
            }
        };
        Ok(CarEnd { car, limits })
    }

    /// Reads one end of a car: a planar car file and its clearances and
    /// limits, from the car file's `[damageability]` table or, for a car
    /// file without one (an identified car, `identify --car`), from a
    /// damageability file merged in: a `[damageability]` table alone, with
    /// its own `length_unit` (`examples/verdict/damageability.toml`). A car
    /// file with its own table and a damageability file is refused: an end
    /// has one set of limits.
    ///
    /// ```
    /// use bumpsim_verdict::prelude::*;
    /// let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    /// let saloon = root.join("planar/saloon.toml"); // no [damageability]
    /// let limits = root.join("verdict/damageability.toml");
    /// let end = CarEnd::read(&saloon, Some(&limits)).unwrap();
    /// assert_eq!(end.limits.clearances[0].name, "radiator");
    /// let e = CarEnd::read(&saloon, None).unwrap_err().to_string();
    /// assert!(e.contains("damageability"), "{e}");
    /// ```
    pub fn read(car: &Path, damageability: Option<&Path>) -> Result<CarEnd, VerdictError> {
        // every refusal names the car file
        let named = |e: VerdictError| match e.to_string().contains(&car.display().to_string()) {
            true => e,
            false => VerdictError::File {
                path: car.display().to_string(),
                message: e.to_string(),
            },
        };
        CarEnd::read_named(car, damageability).map_err(named)
    }

    fn read_named(car: &Path, damageability: Option<&Path>) -> Result<CarEnd, VerdictError> {
        let planar_car = PlanarCar::read(car).map_err(VerdictError::Car)?;
        let limits = match damageability {
            None => Damageability::read(car)?,
            Some(file) if Damageability::given(car)? => {
                return Err(VerdictError::Contradiction {
                    first: format!("{} [damageability]", car.display()),
                    second: file.display().to_string(),
                    reason: "both give the car's clearances and limits: an end has one set; drop the table from the car file or the damageability file".into(),
                });
            }
            Some(file) => Damageability::read(file)?,
        };
        CarEnd::new(planar_car, limits)
    }

    /// The same end with every bumper segment replaced by an equal share
    /// of the whole-bumper characteristic `bumper`.
    pub fn with_bumper(&self, bumper: &Bumper) -> Result<CarEnd, VerdictError> {
        let n = self.car.beam().segments.len();
        let segment = bumper.scaled(1.0 / n as f64).map_err(|source| {
            let name = "bumper".into();
            planar(
                "bumper",
                bumpsim_planar::PlanarError::Bumper { name, source },
            )
        })?;
        self.with_segments(vec![segment; n])
    }

    /// The same end with these segment characteristics (as many as the
    /// car's); everything else of the car (its crash boxes, contact rate,
    /// effective width, name) kept.
    pub fn with_segments(&self, segments: Vec<Bumper>) -> Result<CarEnd, VerdictError> {
        let car = self
            .car
            .clone()
            .with_segments(segments)
            .map_err(|e| planar("bumper", e))?;
        Ok(CarEnd {
            car,
            limits: self.limits.clone(),
        })
    }
}

/// The car's depth and the limits' stroke are the same crushable depth:
/// both given, they must agree.
fn same_depth(first: &str, depth: f64, second: &str, stroke: f64) -> Result<(), VerdictError> {
    if (depth - stroke).abs() <= 1e-9 {
        return Ok(());
    }
    Err(VerdictError::Contradiction {
        first: first.into(),
        second: second.into(),
        reason: format!(
            "the car blocks at {} mm but the stroke is {} mm: both are the same crushable depth; give one, or the same",
            depth * 1e3,
            stroke * 1e3
        ),
    })
}

fn planar(test: &str, source: bumpsim_planar::PlanarError) -> VerdictError {
    VerdictError::Planar {
        test: test.into(),
        source,
    }
}

/// What a verdict runs: the car's ends, the tests and the margin asked for.
#[derive(Debug, Clone)]
pub struct Setup {
    /// The front end (front tests).
    pub front: Option<CarEnd>,
    /// The rear end (rear tests).
    pub rear: Option<CarEnd>,
    /// The tests.
    pub tests: Vec<&'static Test>,
    /// Least margin ratio a criterion must keep to pass (0: at the limit).
    pub margin: f64,
    /// Integration settings.
    pub settings: Settings,
    /// How the ASI averages the accelerations (EN 1317-1:2010 unless set).
    pub asi_method: AsiMethod,
    /// Run the tests in order on one car per end, each from the damage the
    /// earlier ones left ([`crate::sequence`]); off: each on a new car.
    pub sequence: bool,
}

impl Setup {
    /// A set-up from the car files' ends (each end once), the tests and
    /// the margin ratio (0 ≤ margin < 1).
    pub fn new(
        ends: Vec<CarEnd>,
        tests: Vec<&'static Test>,
        margin: f64,
    ) -> Result<Setup, VerdictError> {
        let expected = "a margin is a share of each limit, 0 ≤ margin < 1 (0.1: keep 10 % inside every limit); a negative margin would pass what fails";
        require(
            "margin",
            margin,
            "(a share of each limit)",
            expected,
            (0.0..1.0).contains(&margin),
        )?;
        let (mut front, mut rear) = (None, None);
        for end in ends {
            let slot = match end.limits.end {
                End::Front => &mut front,
                End::Rear => &mut rear,
            };
            if slot.is_some() {
                return Err(VerdictError::two_cars_for(end.limits.end.name()));
            }
            *slot = Some(end);
        }
        Ok(Setup {
            front,
            rear,
            tests,
            margin,
            settings: Settings::default(),
            asi_method: AsiMethod::default(),
            sequence: false,
        })
    }

    /// The end a test strikes, if given.
    pub fn end(&self, end: End) -> Option<&CarEnd> {
        match end {
            End::Front => self.front.as_ref(),
            End::Rear => self.rear.as_ref(),
        }
    }

    /// The car's name (the front's, else the rear's).
    pub fn name(&self) -> String {
        [&self.front, &self.rear]
            .into_iter()
            .flatten()
            .find_map(|e| e.car.name().map(str::to_string))
            .unwrap_or_else(|| "car".into())
    }
}

/// The verdict of one test.
#[derive(Debug, Clone, Serialize)]
pub struct TestVerdict {
    /// The test.
    pub test: &'static Test,
    /// Why it was not assessed (None: it was).
    pub skipped: Option<String>,
    /// The striker as run, in the protocol's words.
    pub striker: String,
    /// Its criteria.
    pub criteria: Vec<Criterion>,
    /// Its pulse metrics.
    pub metrics: Option<Metrics>,
    /// Its energies.
    pub energies: Option<Energies>,
    /// When and where the bumper bottomed (a segment crushed past its
    /// depth): criteria reached afterwards are on the blocked load path.
    pub bottomed: Option<Bottomed>,
    /// When and where a crash box bottomed (compressed past its stroke):
    /// criteria reached afterwards are on the blocked load path.
    pub box_bottomed: Option<BoxBottomed>,
    /// In a sequence, what it inherited from the earlier tests on the same
    /// car and what that changed (None: run on an undamaged car).
    pub inherited: Option<Inherited>,
    /// What the verdict assumes.
    pub assumptions: Vec<String>,
    /// Metrics that could not be computed, and why.
    pub notes: Vec<String>,
    /// The simulation's warnings.
    pub warnings: Vec<String>,
    /// The probability that every criterion passes over the car's
    /// uncertainty (None: not propagated; the probability module).
    pub probability: Option<Probability>,
    /// The impact (histories), for plots; the JSON's `history` holds its
    /// time, striker force, CG x, y and yaw and the segment centres under
    /// `PlanarResult`'s own names (SI), so a viewer can draw the test.
    #[serde(
        rename = "history",
        serialize_with = "history",
        skip_serializing_if = "Option::is_none"
    )]
    pub result: Option<PlanarResult>,
    /// The car and striker as run, for the top view; the JSON's `body`
    /// holds the car's body (its geometry places the outline).
    #[serde(
        rename = "body",
        serialize_with = "body",
        skip_serializing_if = "Option::is_none"
    )]
    pub run: Option<(PlanarCar, Striker)>,
}

/// The histories a test's curves and top view need, under
/// `PlanarResult`'s names.
#[derive(Serialize)]
struct History<'a> {
    time: &'a [f64],
    force: &'a [f64],
    x: &'a [f64],
    y: &'a [f64],
    yaw: &'a [f64],
    segment_centres: &'a [f64],
}

fn history<S: serde::Serializer>(
    result: &Option<PlanarResult>,
    serializer: S,
) -> Result<S::Ok, S::Error> {
    result
        .as_ref()
        .map(|r| History {
            time: &r.time,
            force: &r.force,
            x: &r.x,
            y: &r.y,
            yaw: &r.yaw,
            segment_centres: &r.segment_centres,
        })
        .serialize(serializer)
}

fn body<S: serde::Serializer>(
    run: &Option<(PlanarCar, Striker)>,
    serializer: S,
) -> Result<S::Ok, S::Error> {
    run.as_ref()
        .map(|(car, _)| car.body())
        .serialize(serializer)
}

impl TestVerdict {
    /// The verdict of `test` before anything is judged: assessed, no
    /// criteria, no run.
    pub(crate) fn empty(test: &'static Test) -> TestVerdict {
        TestVerdict {
            test,
            skipped: None,
            striker: String::new(),
            criteria: vec![],
            metrics: None,
            energies: None,
            bottomed: None,
            box_bottomed: None,
            inherited: None,
            assumptions: vec![],
            notes: vec![],
            warnings: vec![],
            probability: None,
            result: None,
            run: None,
        }
    }

    /// Whether every judged criterion passes (None: not assessed).
    pub fn passed(&self) -> Option<bool> {
        self.skipped
            .is_none()
            .then(|| self.criteria.iter().all(|c| c.outcome != Outcome::Fail))
    }

    /// The judged criterion with the smallest margin ratio.
    pub fn binding(&self) -> Option<&Criterion> {
        self.criteria
            .iter()
            .filter(|c| c.outcome != Outcome::Info)
            .min_by(|a, b| a.ratio.total_cmp(&b.ratio))
    }
}

/// The verdict of a car in a set of tests.
#[derive(Debug, Clone, Serialize)]
pub struct Verdict {
    /// The car.
    pub car: String,
    /// The margin ratio asked for.
    pub margin: f64,
    /// Every test, in the order asked.
    pub tests: Vec<TestVerdict>,
    /// The propagation over the car's uncertainty, when asked
    /// (the probability module).
    pub propagation: Option<Propagation>,
    /// What the protocols run require and how each requirement is judged
    /// (JSON: protocol → list; [`crate::requirements`]).
    #[serde(serialize_with = "crate::requirements::as_map")]
    pub requirements: Vec<&'static Requirements>,
}

impl Verdict {
    /// Whether every assessed test passes.
    pub fn passed(&self) -> bool {
        self.tests.iter().all(|t| t.passed() != Some(false))
    }

    /// The failing criteria: (test, criterion).
    pub fn failures(&self) -> Vec<(&'static str, &Criterion)> {
        self.tests
            .iter()
            .flat_map(|t| {
                t.criteria
                    .iter()
                    .filter(|c| c.outcome == Outcome::Fail)
                    .map(move |c| (t.test.name, c))
            })
            .collect()
    }
}

/// Runs every test of the set-up and judges it.
///
/// ```no_run
/// use bumpsim_verdict::prelude::*;
/// let path = std::path::Path::new("examples/verdict/car.toml");
/// let end = CarEnd::new(bumpsim_planar::PlanarCar::read(path)?, Damageability::read(path)?)?;
/// let tests = bumpsim_verdict::protocol::select(&["part581"])?;
/// let verdict = verdict(&Setup::new(vec![end], tests, 0.0)?)?;
/// println!("{}", bumpsim_verdict::text::table(&verdict));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn verdict(setup: &Setup) -> Result<Verdict, VerdictError> {
    let tests = run_all(setup, true, true)?;
    Ok(Verdict {
        car: setup.name(),
        margin: setup.margin,
        tests,
        propagation: None,
        requirements: crate::requirements::run(&setup.tests),
    })
}

/// The impact of one test on its end of the car: the car as run (with the
/// protocol's tyres), the striker and the result.
pub fn run(
    end: &CarEnd,
    test: &Test,
    settings: &Settings,
) -> Result<(PlanarCar, Striker, PlanarResult), VerdictError> {
    let unladen = end.car.total_mass();
    let car = end
        .car
        .clone()
        .with_tyre_law(test.tyres)
        .with_load(test.entry.load)
        .map_err(|e| planar(test.name, e))?;
    // R42's impactor keeps the vehicle's unladen mass (annex 3 §2.3.3)
    let striker = test.striker(unladen)?;
    let result = simulate(&car, &striker, settings).map_err(|e| planar(test.name, e))?;
    Ok((car, striker, result))
}

/// Judges one test (not assessed without a car of its end).
pub fn judge(setup: &Setup, test: &'static Test) -> Result<TestVerdict, VerdictError> {
    assess(setup, test, true)
}

/// [`judge`]; without `pulse`, the OLC and ASI are computed only when a
/// limit needs them (the target search's candidates).
pub(crate) fn assess(
    setup: &Setup,
    test: &'static Test,
    pulse: bool,
) -> Result<TestVerdict, VerdictError> {
    assess_on(setup, setup.end(test.end), test, pulse)
}

/// [`assess`] on the end `end` (None: not assessed).
pub(crate) fn assess_on(
    setup: &Setup,
    end: Option<&CarEnd>,
    test: &'static Test,
    pulse: bool,
) -> Result<TestVerdict, VerdictError> {
    let mut verdict = TestVerdict::empty(test);
    let Some(end) = end else {
        verdict.skipped = Some(format!(
            "no car file of the {} end was given",
            test.end.name()
        ));
        return Ok(verdict);
    };
    let (car, striker, result) = run(end, test, &setup.settings)?;
    let limits = &end.limits;
    let full = pulse || limits.olc.is_some() || limits.asi.is_some();
    let (metrics, notes) = Pulse::of(&result).metrics(full, setup.asi_method);
    let energies = energies(&car, &result);
    let evidence = Evidence {
        car: &car,
        limits,
        test,
        result: &result,
        metrics: &metrics,
        energies: &energies,
    };
    let (criteria, assumptions) = criteria(&evidence, setup.margin);
    let nominal = test.nominal(end.car.total_mass())?;
    verdict.striker = bumpsim_planar::text::striker(&nominal);
    verdict.criteria = criteria;
    verdict.metrics = Some(metrics);
    verdict.energies = Some(energies);
    verdict.bottomed = result.bottomed;
    verdict.box_bottomed = result.box_bottomed;
    verdict.assumptions = assumptions;
    verdict.notes = notes;
    verdict.warnings = result.warnings.clone();
    verdict.result = Some(result);
    verdict.run = Some((car, striker));
    Ok(verdict)
}

/// The damage left on one end: the segments' histories and who left it.
#[derive(Default)]
struct Damage {
    states: Vec<BumperState>,
    from: Vec<&'static str>,
}

/// Every test of `setup`: alone and in parallel, or in sequence when
/// `setup.sequence` ([`crate::sequence`]). `pulse`: [`crate::verdict::judge`]'s
/// full pulse metrics; `explain`: also run each inherited test alone and
/// list what changed.
pub(crate) fn run_all(
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
    test: &'static Test,
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
        true => changes(
            &v.criteria,
            &assess_on(setup, Some(end), test, pulse)?.criteria,
        ),
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
