//! What a car model answers the engine (issue 46 item 1): the requests
//! ([`ImpactRequest`]) and the trait a model implements in its own module
//! ([`CarModel`]); the registry of the models is [`crate::registry`]. No
//! equations.

use crate::{EngineError, Outcome};
use bumpsim_impact::synth::SynthTest;
use bumpsim_io::kind::ModelKind;
pub use bumpsim_planar::striker::Side;
use std::path::Path;

/// `impact` (and `planar`) as a front end names it, its arguments
/// converted (SI); quantities a model reads with their unit (the planar
/// faces' lengths, the set-up's gap and duration) stay as typed, so that a
/// refusal names the option with the value given.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ImpactRequest<'a> {
    /// The car file.
    pub car: Option<&'a Path>,
    /// The car file's text, when the front end holds the car
    /// ([`crate::held::HeldCar`]): read instead of the file `car`, which
    /// it names.
    pub car_text: Option<&'a str>,
    /// A bumper file (`--bumper`; only the linear chain takes one).
    pub bumper: Option<&'a Path>,
    /// A load-case preset of the table of tests.
    pub case: Option<&'a str>,
    /// A pendulum of this mass, kg, hits the car at rest.
    pub pendulum: Option<f64>,
    /// The car hits a rigid barrier.
    pub barrier: bool,
    /// Impact speed as typed: m/s, or with a unit (default: the preset's).
    pub speed: Option<&'a str>,
    /// The planar faces (`--angle`, `--overlap`, `--side`, `--pole`, `--pole-offset`).
    pub face: Face<'a>,
    /// A bumper width as typed (`--width`: a 1-D car made a symmetric planar car).
    pub width: Option<&'a str>,
    /// The planar set-up (`--gap`, `--duration`, `--tyres`).
    pub setup: Setup<'a>,
    /// The car's uncertainty (`--uncertainty` and its options).
    pub uncertainty: Option<UncertaintyOptions<'a>>,
    /// Draw the report's pages too.
    pub report: bool,
}

/// The striker's face options of a planar impact, as given.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Face<'a> {
    /// Face angle, degrees, counter-clockwise seen from above.
    pub angle: Option<f64>,
    /// Overlap, percent of the bumper width.
    pub overlap: Option<f64>,
    /// Side the overlap is measured from.
    pub side: Option<Side>,
    /// A pole's diameter, as typed (m, or with a unit).
    pub pole: Option<&'a str>,
    /// The pole axis's lateral position, as typed (m, or with a unit).
    pub pole_offset: Option<&'a str>,
}

impl Face<'_> {
    /// The face options given, by name.
    pub fn names(&self) -> Vec<&'static str> {
        [
            (self.angle.is_some(), "--angle"),
            (self.overlap.is_some(), "--overlap"),
            (self.side.is_some(), "--side"),
            (self.pole.is_some(), "--pole"),
            (self.pole_offset.is_some(), "--pole-offset"),
        ]
        .into_iter()
        .filter_map(|(given, name)| given.then_some(name))
        .collect()
    }

    /// Whether any face option is given.
    pub fn given(&self) -> bool {
        !self.names().is_empty()
    }
}

/// The planar test set-up as given: the gap and the longest duration as
/// typed (m or s, or with a unit), the tyres (`rolling` or `sliding`).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Setup<'a> {
    /// Initial gap between the striker and its first touch.
    pub gap: Option<&'a str>,
    /// Longest simulated time.
    pub duration: Option<&'a str>,
    /// The tyres of both axles: `rolling` or `sliding`.
    pub tyres: Option<&'a str>,
}

/// The car's uncertainty carried through a run (issue 39).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UncertaintyOptions<'a> {
    /// An identification's JSON or a TOML of relative deviations and ranges.
    pub path: &'a Path,
    /// Draws of the car's parameters.
    pub samples: usize,
    /// Seed of the draws.
    pub seed: u64,
    /// Level of the intervals and bands, in (0, 1).
    pub level: f64,
    /// Base samples of the Sobol indices, when asked.
    pub sobol_base: Option<usize>,
}

impl<'a> ImpactRequest<'a> {
    /// The impact speed, m/s, read with its unit.
    pub fn speed(&self) -> Result<Option<f64>, EngineError> {
        self.speed
            .map(|text| {
                bumpsim_core::units::parse_quantity(text, bumpsim_core::units::Dimension::Velocity)
                    .map_err(|source| EngineError::Quantity {
                        option: "speed",
                        text: text.into(),
                        source,
                    })
            })
            .transpose()
    }

    /// The car file, needed by every model.
    pub fn car_path(&self) -> Result<&'a Path, EngineError> {
        self.car.ok_or_else(|| EngineError::Unsupported {
            option: "--car".into(),
            reason: "a car file is needed".into(),
        })
    }

    /// Refuses the options a model of `what` has no use for (a bumper file,
    /// the planar faces, the car's uncertainty), each by name.
    pub fn refuse_extras(&self, what: &str) -> Result<(), EngineError> {
        let refuse = |option: String, reason: &str| {
            Err(EngineError::Unsupported {
                option,
                reason: format!("{what} {reason}"),
            })
        };
        if self.bumper.is_some() {
            return refuse(
                "--bumper".into(),
                "carries its crush zone in its own file (a [front] link); leave --bumper out",
            );
        }
        let mut faces = self.face.names();
        faces.extend(self.width.map(|_| "--width"));
        if let Some(option) = faces.first() {
            return refuse(
                (*option).into(),
                "runs into a flat rigid barrier along its axis; faces other than flat need a planar car",
            );
        }
        if self.uncertainty.is_some() {
            return refuse(
                "--uncertainty".into(),
                "has no uncertainty propagation yet; leave --uncertainty out",
            );
        }
        Ok(())
    }
}

/// A car model as the engine runs it: what each command asks of it.
pub trait CarModel: Sync {
    /// Its kind in the registry ([`ModelKind`]), the one its files declare.
    fn kind(&self) -> ModelKind;

    /// `impact`: the car of `request.car` in the request's scenario.
    fn impact(&self, request: &ImpactRequest<'_>) -> Result<Outcome, EngineError>;

    /// `identify`: the study of `request.study` (a model without an
    /// identification through the engine refuses).
    fn identify(&self, request: &IdentifyRequest<'_>) -> Result<Outcome, EngineError> {
        let _ = request;
        Err(self.not_registered("identify"))
    }

    /// `predict`: the car of `request.car` replaying the study's cases.
    fn predict(&self, request: &PredictRequest<'_>) -> Result<Outcome, EngineError> {
        let _ = request;
        Err(self.not_registered("predict"))
    }

    /// `export`: the car of `request.car` as a solver's deck.
    fn export(&self, request: &ExportRequest<'_>) -> Result<Deck, EngineError> {
        let _ = request;
        Err(self.not_registered("export"))
    }

    /// A car file of this model read (`text`, else the file at `path`):
    /// its name and the car as its file, for a front end that holds the
    /// car ([`crate::held::HeldCar`]).
    fn car(&self, path: &Path, text: Option<&str>) -> Result<CarText, EngineError> {
        let _ = (path, text);
        Err(self.not_registered("car"))
    }

    /// `verdict`: the cars of `request.ends` judged in the protocols' tests
    /// (the engine makes the outcome, [`crate::verdict::verdict`]).
    fn verdict(&self, request: &VerdictRequest<'_>) -> Result<Judged, EngineError> {
        let _ = request;
        Err(self.not_registered("verdict"))
    }

    /// Whether this model's cars are judged by `verdict`.
    fn judges(&self) -> bool {
        false
    }

    /// Whether `verdict` hands this model the car files the registry
    /// reads as the 1-D chain's (which does not judge): its reader then
    /// says what is wrong with them (the planar car's, whose files with a
    /// mistake fall back to the chain's kind).
    fn judges_unmarked(&self) -> bool {
        false
    }

    /// One end of a car for the verdicts ([`bumpsim_verdict::prelude::CarEnd`]):
    /// the held car with the limits of its file's `[damageability]`.
    fn end(
        &self,
        path: &Path,
        text: &str,
    ) -> Result<bumpsim_verdict::prelude::CarEnd, EngineError> {
        let _ = (path, text);
        Err(self.not_registered("verdict"))
    }

    /// `synth`: the test series of the file at `path`.
    fn synth(&self, path: &Path) -> Result<Made, EngineError> {
        let _ = path;
        Err(self.not_registered("synth"))
    }

    /// The refusal of a command this model does not run through the engine.
    fn not_registered(&self, command: &'static str) -> EngineError {
        EngineError::NotRegistered {
            command,
            kind: self.kind().name(),
        }
    }
}

/// `identify` as a front end names it.
#[derive(Clone, Copy)]
pub struct IdentifyRequest<'a> {
    /// The study file.
    pub study: &'a Path,
    /// Starts instead of the study's.
    pub starts: Option<usize>,
    /// Seed of the random starts instead of the study's.
    pub seed: Option<u64>,
    /// Draw the report's pages too.
    pub report: bool,
    /// The posterior, when asked for (`--posterior`).
    pub posterior: Option<PosteriorOptions>,
    /// Model sizes (numbers of masses) instead of the study's (`--dof`).
    pub sizes: Option<&'a [usize]>,
    /// The sensitivities were asked for (`--sensitivity`).
    pub sensitivity: bool,
    /// The identified car as a car file was asked for (`--car`).
    pub car: bool,
    /// Hears of the identification's progress and its text as it comes.
    pub progress: &'a dyn Progress,
}

/// The posterior run's settings as given (`None`: the default).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct PosteriorOptions {
    /// Walkers of the ensemble sampler.
    pub walkers: Option<usize>,
    /// Steps, a quarter of them burnt.
    pub steps: Option<usize>,
}

/// A long request's progress, as a front end shows it (a progress bar, a
/// callback); every method does nothing by default.
pub trait Progress: Sync {
    /// The run begins: `starts` starts to go.
    fn begin(&self, starts: u64) {
        let _ = starts;
    }
    /// A named stage of the run begins (`2-DOF`, `posterior 2-DOF`) with
    /// `count` of `unit` (`starts`, `steps`) to go; by default [`Self::begin`].
    fn stage(&self, name: &str, count: u64, unit: &str) {
        let _ = (name, unit);
        self.begin(count);
    }
    /// One start (or step) has finished (from any thread).
    fn start_finished(&self) {}
    /// The run (or stage) has ended.
    fn end(&self) {}
    /// A part of the outcome's text as soon as it is known (a terminal
    /// prints it as it comes; the outcome's text holds it too).
    fn text(&self, text: &str) {
        let _ = text;
    }
    /// A part of the run failed and the rest goes on: why.
    fn part_failed(&self, why: &str) {
        let _ = why;
    }
}

/// A progress nobody watches.
#[derive(Debug, Clone, Copy, Default)]
pub struct Unwatched;

impl Progress for Unwatched {}

/// `predict` as a front end names it.
#[derive(Debug, Clone, Copy)]
pub struct PredictRequest<'a> {
    /// The car (a car file, or an identification's JSON).
    pub car: &'a Path,
    /// The study.
    pub study: &'a Path,
    /// The cases to predict (all when empty).
    pub cases: &'a [String],
    /// Draw the plots of each case too.
    pub plot: bool,
}

/// The solvers a deck is written for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Solver {
    /// LS-DYNA keyword include.
    Lsdyna,
    /// CalculiX/Abaqus deck.
    Calculix,
}

/// `export` as a front end names it, its options converted (SI).
#[derive(Debug, Clone, PartialEq)]
pub struct ExportRequest<'a> {
    /// The car file.
    pub car: &'a Path,
    /// The solver.
    pub solver: Solver,
    /// Deck units.
    pub units: bumpsim_export::layout::UnitSystem,
    /// Position of the body's centre of gravity, m.
    pub origin: [f64; 3],
    /// Distance between neighbouring chain nodes, m.
    pub spacing: f64,
    /// Added to every id.
    pub id_offset: u64,
    /// The user's node ids coupled to the left and right front masses.
    pub attach: [Vec<u64>; 2],
    /// Initial forward speed of the whole car, m/s.
    pub speed: Option<f64>,
    /// A force history on the bumper line.
    pub force: Option<ForceLoad<'a>>,
    /// LS-DYNA history output interval, s.
    pub output_interval: Option<f64>,
    /// CalculiX fixed time increment, s.
    pub increment: Option<f64>,
    /// CalculiX: results every this many increments.
    pub output_every: usize,
    /// CalculiX: prefix of every set and amplitude name.
    pub prefix: String,
}

/// A force history on the bumper line.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ForceLoad<'a> {
    /// Sample interval, s.
    pub step: f64,
    /// The force, N, sample k at time k · step.
    pub values: &'a [f64],
    /// Lateral position on the bumper line, m, left positive.
    pub lateral: f64,
    /// Direction of the force on the car (world x, y).
    pub direction: [f64; 2],
}

/// A deck and what it holds, in words.
#[derive(Debug, Clone, PartialEq)]
pub struct Deck {
    /// The deck's text.
    pub text: String,
    /// What it holds (after "wrote FILE: ").
    pub what: String,
}

/// One end of the car judged by `verdict`.
#[derive(Debug, Clone, Copy)]
pub enum End<'a> {
    /// A car file and, for a car file without a `[damageability]` table,
    /// the file of its clearances and limits.
    File(&'a Path, Option<&'a Path>),
    /// A car the front end holds ([`crate::held::HeldCar::end`]), with the
    /// limits of its file's `[damageability]`.
    Held {
        /// The file it was read from (or that its text names).
        path: &'a Path,
        /// The file's text.
        text: &'a str,
        /// The model kind it is read as.
        kind: ModelKind,
    },
}

/// What `verdict` judged, before the engine makes its outcome: the
/// verdict, the bumper target region and the Sobol indices when asked.
#[derive(Debug, Clone)]
pub struct Judged {
    /// The verdict of every test.
    pub verdict: bumpsim_verdict::verdict::Verdict,
    /// The region of passing bumpers (`--target`).
    pub region: Option<bumpsim_verdict::target::Region>,
    /// The Sobol indices (`--sobol`).
    pub indices: Option<bumpsim_verdict::sensitivity::Sensitivity>,
}

/// `verdict` as a front end names it, its options converted.
pub struct VerdictRequest<'a> {
    /// The ends of the car, one per end.
    pub ends: &'a [End<'a>],
    /// A bumper that replaces every end's (Python's `bumper=`), shared
    /// equally by its segments.
    pub bumper: Option<&'a bumpsim_impact::bumper::Bumper>,
    /// Protocols or tests by name (`all`, a protocol, a test's name).
    pub protocols: &'a [String],
    /// The vehicle's target market (the RCAR barrier's lower edge).
    pub market: bumpsim_io::protocols::Market,
    /// Least margin each criterion keeps, a share of its limit.
    pub margin: f64,
    /// Also search the region of passing bumper characteristics.
    pub target: bool,
    /// Run the tests in order, each from the damage the earlier ones left.
    pub sequence: bool,
    /// How the ASI averages the accelerations.
    pub asi_method: bumpsim_verdict::pulse::AsiMethod,
    /// The car's uncertainty: the probability of passing (and the Sobol
    /// indices when asked).
    pub uncertainty: Option<VerdictUncertainty<'a>>,
    /// Draw the report's pages too.
    pub report: bool,
    /// Hears of the Sobol indices' verdicts, one "start" each.
    pub progress: &'a dyn Progress,
}

/// The car's uncertainty in a verdict.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VerdictUncertainty<'a> {
    /// An identification's JSON or a TOML of deviations and ranges.
    pub path: &'a Path,
    /// Draws of the car's parameters.
    pub samples: usize,
    /// Seed of the draws (and of the indices' bootstrap).
    pub seed: u64,
    /// Base samples of the Sobol indices, when asked.
    pub sobol_base: Option<usize>,
}

/// What a model reads from a car file's text: the car's name and the car
/// written again as its own file (canonical: the same car reads back).
#[derive(Debug, Clone, PartialEq)]
pub struct CarText {
    /// The name the file gives, if any.
    pub name: Option<String>,
    /// The car as its model writes its file.
    pub toml: String,
}

/// A made series.
#[derive(Debug, Clone)]
pub struct Made {
    /// The tests, in the file's order: name, ISO-MME header, channels.
    pub tests: Vec<SynthTest>,
    /// The inputs' texts (for `generated-by.toml`).
    pub provenance: String,
    /// Further files of the output folder (name, text): the planar
    /// series' `study.toml` and `start.toml`.
    pub files: Vec<(&'static str, String)>,
}
