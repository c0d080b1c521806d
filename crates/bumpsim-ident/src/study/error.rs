//! Why a study cannot be read: the file, its values, a case's definition
//! or data.

use crate::case::{CaseError, MAX_INITIAL_VELOCITY, VALID_RANGE};
use bumpsim_core::names::NameError;
use bumpsim_core::units::{Dimension, format_number};
use bumpsim_io::signal_error::SignalFileError;
use bumpsim_signal::loader::LoadError;
use bumpsim_signal::process::ProcessError;
use bumpsim_signal::window::WindowError;
use std::path::PathBuf;

/// Why a study cannot be read.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum StudyError {
    /// The study file itself.
    #[error("{path}: {message}")]
    File {
        /// The study file.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// A `bounds` or `fixed` entry names no parameter of the models.
    #[error("{path}: {table}: no parameter '{name}' in a {dof}-DOF model ({})", valid.join(", "))]
    Parameter {
        /// The study file.
        path: PathBuf,
        /// `bounds` or `fixed`.
        table: &'static str,
        /// The name given.
        name: String,
        /// Masses of the largest model identified.
        dof: usize,
        /// The parameter names of that model.
        valid: Vec<String>,
    },
    /// The `start` does not fit the models identified.
    #[error("{path}: start: {masses} masses, {dampers} dampers, {springs} springs; {expected}")]
    Start {
        /// The study file.
        path: PathBuf,
        /// Masses given.
        masses: usize,
        /// Dampers given.
        dampers: usize,
        /// Springs given.
        springs: usize,
        /// What fits.
        expected: String,
    },
    /// A test file or channel.
    #[error("case '{case}': {source}")]
    Data {
        /// The case.
        case: String,
        /// The cause.
        source: SignalFileError,
    },
    /// Processing a signal.
    #[error("case '{case}': {source}")]
    Process {
        /// The case.
        case: String,
        /// The cause.
        source: ProcessError,
    },
    /// A case definition.
    #[error("case '{case}': {source}")]
    Case {
        /// The case.
        case: String,
        /// What is wrong.
        source: DefinitionError,
    },
    /// A value of the study file refused on reading.
    #[error("{path}: {source}")]
    Value {
        /// The study file.
        path: PathBuf,
        /// The value and what is wrong with it.
        source: StudyValueError,
    },
}

/// A value of a study file refused on reading, named by its key (the
/// study's error adds the file).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum StudyValueError {
    /// `lower_bound` outside the search's range.
    #[error(
        "[model] lower_bound = {}: expected a number from {:e} to below {:e} (SI: kg, N·s/m and N/m alike, the range the search works in; the thesis uses 1)",
        format_number(*.value, 4),
        VALID_RANGE.start(),
        VALID_RANGE.end()
    )]
    LowerBound {
        /// The bound given.
        value: f64,
    },
    /// `upper_bound` not above `lower_bound`.
    #[error(
        "[model] upper_bound = {}: expected a number above lower_bound = {} (SI)",
        format_number(*.upper, 4),
        format_number(*.lower, 4)
    )]
    UpperBound {
        /// The upper bound given.
        upper: f64,
        /// The lower bound.
        lower: f64,
    },
    /// A parameter's `bounds` entry outside the search's range or empty.
    #[error(
        "bounds: {name} = [{}, {}]: expected {:e} <= lower < upper with lower below {:e} (SI)",
        format_number(*.lower, 4),
        format_number(*.upper, 4),
        VALID_RANGE.start(),
        VALID_RANGE.end()
    )]
    Bounds {
        /// The parameter.
        name: String,
        /// Its lower bound.
        lower: f64,
        /// Its upper bound.
        upper: f64,
    },
    /// A `fixed` value that is not finite and positive.
    #[error(
        "fixed: {name} = {}: expected a finite positive value (SI)",
        format_number(*.value, 4)
    )]
    Fixed {
        /// The parameter.
        name: String,
        /// The value given.
        value: f64,
    },
    /// The case names as a list (empty, repeated, invisible characters).
    #[error(transparent)]
    CaseNames(#[from] NameError),
    /// A case's initial velocity beyond [`MAX_INITIAL_VELOCITY`].
    #[error(
        "[[case]] '{case}': initial_velocity = {} m/s: expected a finite speed of at most {max} m/s (a crash test's is a few m/s)",
        format_number(*.value, 4),
        max = MAX_INITIAL_VELOCITY
    )]
    InitialVelocity {
        /// The case.
        case: String,
        /// The velocity given, m/s.
        value: f64,
    },
    /// A case's `window`, `bias` or `cfc` that no channel can have
    /// (not finite, not ordered, not positive, or a CFC class outside what
    /// the channel's sample rate allows).
    #[error("[[case]] '{case}': {key} = {value}: expected {expected}")]
    CaseValue {
        /// The case.
        case: String,
        /// The key (`window`, `bias`, `cfc`).
        key: &'static str,
        /// The value as written.
        value: String,
        /// What is allowed.
        expected: String,
    },
    /// `dof = []`.
    #[error("[model] dof = []: expected at least one DOF (dof = 3 or dof = [1, 2, 3])")]
    NoDof,
    /// A DOF given twice.
    #[error("[model] dof: {dof} is given twice; each model order once")]
    RepeatedDof {
        /// The DOF.
        dof: usize,
    },
    /// A DOF of no model.
    #[error(
        "[model] dof = {dof}: expected 1 to {max} masses ({reason})",
        reason = crate::settings::MAX_DOF_REASON
    )]
    DofRange {
        /// The DOF given.
        dof: usize,
        /// The most masses.
        max: usize,
    },
    /// A `bounds` entry that is not two values.
    #[error("bounds: {name} = {values:?}: expected [lower, upper], two values")]
    BoundsShape {
        /// The parameter.
        name: String,
        /// The values given.
        values: Vec<f64>,
    },
    /// A parameter both fixed and bounded.
    #[error("{name} is both fixed and bounded: give it in one of fixed and bounds")]
    FixedAndBounded {
        /// The parameter.
        name: String,
    },
}

/// What is wrong with a `[[case]]` definition or its data.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum DefinitionError {
    /// Neither or both of `displacement` and `acceleration`.
    #[error("give either 'displacement' or 'acceleration' (a list of channels)")]
    Output,
    /// A signal of the wrong physical dimension.
    #[error("the {signal} is {found}, expected {expected}")]
    Dimension {
        /// Which signal (`force channel`, ...).
        signal: &'static str,
        /// Its dimension.
        found: Dimension,
        /// What it must be.
        expected: &'static str,
    },
    /// A channel whose ISO code measures across the impact (a lateral
    /// accelerometer, a yaw rate) in a chain study, which compares motion
    /// along the impact only (issue 44's hostile pass: one was averaged in).
    #[error(
        "the {signal} {channel} measures along {direction}: a chain study compares motion along the impact (ISO direction X); a lateral or yaw sensor belongs in a planar study (docs/planar.md)"
    )]
    Across {
        /// Which signal (`acceleration channel`, ...).
        signal: &'static str,
        /// The channel's code.
        channel: String,
        /// The direction letter of its code.
        direction: char,
    },
    /// The channels could not be made into one signal.
    #[error(transparent)]
    Load(LoadError),
    /// The data end before t = 0.
    #[error("no samples at or after t = 0")]
    NoSamples,
    /// `output_dof` is neither a number nor `"last"`.
    #[error("output_dof '{0}': expected a number or \"last\"")]
    OutputDof(String),
    /// `output_dof` names no mass of the model.
    #[error("output_dof = {output_dof}: the model has masses 1 to {dof}")]
    OutputDofRange {
        /// The mass given (1-based).
        output_dof: usize,
        /// The model's number of masses.
        dof: usize,
    },
    /// `window` is neither `"contact"` nor two times.
    #[error("window '{0}': expected \"contact\" or [t0, t1] in s")]
    WindowName(String),
    /// The window `[t0, t1]` s holds fewer than two samples.
    #[error(
        "window [{t0}, {t1}] s holds fewer than two samples of the data (a window needs t0 < t1 and at least two samples)"
    )]
    EmptyWindow {
        /// Start, s.
        t0: f64,
        /// End, s.
        t1: f64,
    },
    /// No contact in the force.
    #[error(transparent)]
    Contact(#[from] WindowError),
    /// A case failed after its force and displacement were put on one
    /// time base: the failure, and how they were.
    #[error("{error} (after {note})")]
    Resampled {
        /// What [`bumpsim_signal::process::Resampling`] says.
        note: String,
        /// The failure.
        error: Box<DefinitionError>,
    },
    /// The processed case is not usable (shown without the case's name,
    /// which [`StudyError::Case`] gives already).
    #[error("{}", .0.reason())]
    Invalid(CaseError),
}

impl From<CaseError> for DefinitionError {
    fn from(error: CaseError) -> DefinitionError {
        DefinitionError::Invalid(error)
    }
}
