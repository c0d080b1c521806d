//! Why a request cannot run: typed errors with the file, parameter or
//! option they concern (no equations here).

use std::path::PathBuf;

/// Why a request cannot run.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum EngineError {
    /// The car file's kind cannot be told (unreadable, unknown `kind`).
    #[error(transparent)]
    Kind(#[from] bumpsim_io::kind::KindError),
    /// The car file is not a valid car of its kind.
    #[error(transparent)]
    Car(#[from] bumpsim_io::car::CarError),
    /// The series file's kind cannot be told.
    #[error("{path}: {source}")]
    Series {
        /// The series file.
        path: PathBuf,
        /// Why.
        #[source]
        source: bumpsim_io::kind::KindError,
    },
    /// The chain's series cannot be made.
    #[error(transparent)]
    Synth(#[from] bumpsim_impact::synth::SynthError),
    /// The planar car's input is not valid or its run failed.
    #[error(transparent)]
    Planar(#[from] bumpsim_planar::car::PlanarError),
    /// The scenario (preset, pendulum, barrier, speed) is not valid.
    #[error("--case, --pendulum, --barrier, --speed: {0}")]
    Scenario(#[from] bumpsim_impact::impact::ImpactError),
    /// The model cannot run the request as asked (an option it has no use for).
    #[error("{option}: {reason}")]
    Unsupported {
        /// The option or input concerned.
        option: String,
        /// Why, and what to do instead.
        reason: String,
    },
    /// The model's run failed.
    #[error("{path}: {source}")]
    Run {
        /// The car file.
        path: PathBuf,
        /// The mechanism's error.
        source: bumpsim_core::chain::ChainError,
    },
    /// A quantity option is not a valid value of its dimension.
    #[error("--{option} '{text}'")]
    Quantity {
        /// The option, without `--`.
        option: &'static str,
        /// The value as typed.
        text: String,
        /// Why.
        #[source]
        source: bumpsim_core::units::QuantityError,
    },
    /// The planar car refused a value; `context` names the option or step
    /// (as given) behind it.
    #[error("{context}")]
    PlanarIn {
        /// The option with its value as given, or what was being done.
        context: String,
        /// The planar car's refusal.
        #[source]
        source: bumpsim_planar::car::PlanarError,
    },
    /// The car's uncertainty options or file are not valid.
    #[error("{option}")]
    Uncertainty {
        /// The option(s) concerned.
        option: String,
        /// Why.
        #[source]
        source: bumpsim_impact::propagation::PropagationError,
    },
    /// The propagation of the car's uncertainty failed.
    #[error(transparent)]
    Propagation(bumpsim_impact::propagation::PropagationError),
    /// A file is not for what the command asks of it (a car of another
    /// kind than its study, an identification that is not a whole car).
    #[error("{path}: {reason}")]
    Refused {
        /// The file.
        path: PathBuf,
        /// Why, and what to give instead.
        reason: String,
    },
    /// A replay of a study's case is not finite.
    #[error(
        "case '{case}': the replay with {car} is not finite (fit x {fit_x} %, yaw {fit_yaw} %): the car cannot be integrated at the study's sample interval"
    )]
    NotFinite {
        /// The case.
        case: String,
        /// The car file.
        car: PathBuf,
        /// Fit of x, %.
        fit_x: f64,
        /// Fit of yaw, %.
        fit_yaw: f64,
    },
    /// The planar car's deck cannot be written.
    #[error(transparent)]
    PlanarExport(bumpsim_planar::export::PlanarExportError),
    /// An output interval of zero increments.
    #[error("--output-every {every}")]
    OutputEvery {
        /// The value given.
        every: usize,
        /// The refusal.
        #[source]
        source: bumpsim_planar::export::PlanarExportError,
    },
    /// A needed input is missing.
    #[error("{what}")]
    Needed {
        /// What is needed, and where it is described.
        what: &'static str,
    },
    /// The bumper file is not a valid bumper characteristic.
    #[error(transparent)]
    Bumper(#[from] bumpsim_impact::bumper::BumperError),
    /// The scenario (preset, pendulum, barrier, speed as given) is not valid.
    #[error("--case, --pendulum, --barrier, --speed{speed}")]
    ScenarioGiven {
        /// ` 'SPEED'` as given, or nothing.
        speed: String,
        /// Why.
        #[source]
        source: bumpsim_impact::impact::ImpactError,
    },
    /// The chain's impact failed.
    #[error("--car {car} with --bumper {bumper}")]
    ChainRun {
        /// The car file.
        car: PathBuf,
        /// The bumper file.
        bumper: PathBuf,
        /// Why.
        #[source]
        source: bumpsim_impact::impact::ImpactError,
    },
    /// The car file cannot be read; `context` says what was expected.
    #[error("{context}")]
    CarIn {
        /// The file and what it should be.
        context: String,
        /// Why.
        #[source]
        source: Box<bumpsim_io::car::CarError>,
    },
    /// The chain study cannot be read or loaded.
    #[error(transparent)]
    Study(Box<bumpsim_ident::StudyError>),
    /// A chain study's case cannot be simulated.
    #[error(transparent)]
    Case(Box<bumpsim_ident::case::CaseError>),
    /// A simulation of a study's case with the chain is not finite.
    #[error(
        "case '{case}': the simulation with {car} is not finite (fit {fit} %): the model is beyond what the zoh discretisation can represent at this sample interval"
    )]
    Diverged {
        /// The case.
        case: String,
        /// The car file.
        car: PathBuf,
        /// The fit, %.
        fit: f64,
    },
    /// No model of this kind answers the command through the engine.
    #[error("{command}: a {kind} car is not run by the engine (its front end runs it)")]
    NotRegistered {
        /// The command.
        command: &'static str,
        /// The kind's name.
        kind: &'static str,
    },
    /// A figure of the report could not be drawn.
    #[error("report: {0}")]
    Plot(#[from] bumpsim_report::plot::PlotError),
    /// The verdicts refused a car, a protocol or an option.
    #[error(transparent)]
    Verdict(Box<bumpsim_verdict::VerdictError>),
    /// The verdicts refused a value; `context` names the option or file.
    #[error("{context}")]
    VerdictIn {
        /// The option or file concerned.
        context: String,
        /// The verdicts' refusal.
        #[source]
        source: Box<bumpsim_verdict::VerdictError>,
    },
    /// The car's uncertainty file cannot be read.
    #[error(transparent)]
    UncertaintyFile(#[from] bumpsim_impact::uncertainty::UncertaintyError),
    /// One model size (the only one asked) could not be identified.
    #[error("{dof}-DOF identification")]
    Size {
        /// Number of masses.
        dof: usize,
        /// Why.
        #[source]
        source: Box<bumpsim_ident::IdentError>,
    },
    /// The posterior run cannot be made as asked (`--walkers`, `--steps`).
    #[error("--{0}")]
    Ensemble(Box<bumpsim_ident::posterior::SamplingError>),
    /// The posterior run failed.
    #[error("--posterior of the {dof}-DOF model")]
    Posterior {
        /// Number of masses.
        dof: usize,
        /// Why.
        #[source]
        source: Box<bumpsim_ident::posterior::SamplingError>,
    },
    /// A links study's `[links]` table (or what the rest of the study
    /// says against it) is not valid.
    #[error("{path}: {source}")]
    LinksStudy {
        /// The study file.
        path: PathBuf,
        /// The key and why.
        #[source]
        source: bumpsim_ident::links::study::LinksStudyError,
    },
    /// The identification with nonlinear links failed.
    #[error("identification with nonlinear links: {0}")]
    LinkIdent(Box<bumpsim_ident::links::LinkIdentError>),
    /// The JSON document could not be made.
    #[error("JSON document: {0}")]
    Json(#[from] serde_json::Error),
}

impl From<Box<bumpsim_ident::StudyError>> for EngineError {
    fn from(error: Box<bumpsim_ident::StudyError>) -> Self {
        EngineError::Study(error)
    }
}

impl From<Box<bumpsim_ident::case::CaseError>> for EngineError {
    fn from(error: Box<bumpsim_ident::case::CaseError>) -> Self {
        EngineError::Case(error)
    }
}

impl From<bumpsim_verdict::VerdictError> for EngineError {
    fn from(error: bumpsim_verdict::VerdictError) -> Self {
        EngineError::Verdict(Box::new(error))
    }
}
