//! The errors of a campaign: each names the file, key, point or program it
//! is about, so the engineer can fix the campaign file or the cluster setup.

use crate::response::ResponseError;
use std::path::PathBuf;

/// Why a campaign cannot be set up, run, or collected.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum CampaignError {
    /// A file cannot be read.
    #[error("{path}: cannot read: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// The campaign file is not valid TOML or has unknown keys.
    #[error("{path}: {message}")]
    Toml {
        /// The file.
        path: PathBuf,
        /// The parser's message (with line and column).
        message: String,
    },
    /// A key of the campaign file has an unusable value.
    #[error("{path}: {key}: {message}")]
    Invalid {
        /// The campaign file.
        path: PathBuf,
        /// The key (`design.factors`, `derived.k2`, ...).
        key: String,
        /// What is wrong.
        message: String,
    },
    /// A template placeholder names no factor or derived quantity.
    #[error(
        "{path}:{line}: placeholder {{{{{name}}}}} has no factor or derived quantity (known: {known})"
    )]
    Placeholder {
        /// The template file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// The placeholder's name.
        name: String,
        /// The names that are defined.
        known: String,
    },
    /// A program the campaign needs is not on PATH.
    #[error("{what} '{program}' not found on PATH ({hint})")]
    Program {
        /// `solver` or `sbatch`, ...
        what: String,
        /// The program.
        program: String,
        /// What to do.
        hint: String,
    },
    /// Another controller holds the campaign's lock.
    #[error(
        "{path}: the campaign is run by another controller ({holder}); remove the lock file only if that controller is gone"
    )]
    Locked {
        /// The lock file.
        path: PathBuf,
        /// Who holds it (pid, host, since).
        holder: String,
    },
    /// The state file does not parse or does not match the campaign.
    #[error("{path}: {message}")]
    State {
        /// The state file.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// The state journal is damaged, truncated, or of an earlier bumpsim.
    #[error(
        "{path}: the campaign's state is damaged: {problem}; `bumpsim campaign repair {dir}` rebuilds it from the point folders (nothing done runs again)",
        dir = dir.display()
    )]
    Damaged {
        /// The state journal.
        path: PathBuf,
        /// The campaign folder.
        dir: PathBuf,
        /// What is wrong (line, checksum, missing points).
        problem: String,
    },
    /// A file of the campaign folder cannot be written.
    #[error("{path}: cannot write: {source}")]
    WriteFile {
        /// The file or folder.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// A point folder has lost or cannot give the inputs its state records.
    #[error(
        "{journal}:{line}: run {run}: its point folder {folder} is damaged ({problem}); `bumpsim campaign init CAMPAIGN.toml -o {dir}` renders its inputs again (points done with unchanged inputs are kept)",
        folder = folder.display(),
        dir = dir.display()
    )]
    PointFolder {
        /// The state journal.
        journal: PathBuf,
        /// The line of the point's record in it.
        line: usize,
        /// The point's run.
        run: usize,
        /// The point folder.
        folder: PathBuf,
        /// The campaign folder.
        dir: PathBuf,
        /// What is wrong with it.
        problem: String,
    },
    /// The state journal cannot be appended to.
    #[error("{path}: cannot append to the state journal: {source}")]
    Journal {
        /// The state journal.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// A scheduler command failed.
    #[error("{command}: {message}")]
    Scheduler {
        /// The command line.
        command: String,
        /// Its error output or status.
        message: String,
    },
    /// A `[[response]]` of the campaign file is not usable.
    #[error("{path}: {key}: {source}")]
    Response {
        /// The campaign file.
        path: PathBuf,
        /// The response (`response[2] 'peak'`).
        key: String,
        /// What is wrong.
        source: ResponseError,
    },
    /// A point's output cannot be read (missing, corrupt, not finite).
    #[error("point {run}: response '{response}': {source}")]
    Output {
        /// The point's run number.
        run: usize,
        /// The response.
        response: String,
        /// What is wrong (boxed: it is large beside the other variants).
        source: Box<ReadError>,
    },
    /// A point's model cannot be identified from its outputs.
    #[error("point {run}: response 'identification': {source}")]
    Identification {
        /// The point's run number.
        run: usize,
        /// Why not (boxed: it is large beside the other variants).
        source: Box<PointIdentifyError>,
    },
    /// Nothing to collect or fit.
    #[error("{0}")]
    Collect(String),
    /// An output cannot be written.
    #[error(transparent)]
    Write(#[from] bumpsim_io::output::OutputError),
    /// The design cannot be made.
    #[error(transparent)]
    Design(#[from] bumpsim_doe::DesignError),
    /// The regression of the collected table failed.
    #[error(transparent)]
    Fit(#[from] bumpsim_doe::table_fit::TableFitError),
    /// A plot of the report failed.
    #[error("report: {0}")]
    Report(String),
    /// A process could not be started.
    #[error("{program}: cannot start: {source}")]
    Spawn {
        /// The program.
        program: String,
        /// The cause.
        source: std::io::Error,
    },
}

/// Why a point's response cannot be read: the output file is missing,
/// unreadable, of a layout the reader does not know, or holds no finite
/// values of the quantity. Never read as a zero.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ReadError {
    /// The file cannot be read.
    #[error("{path}: cannot read: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// A word where a number should be.
    #[error("{path}:{line}: '{word}' is not a finite number")]
    NotANumber {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// The word.
        word: String,
    },
    /// The file holds no value of the quantity.
    #[error("{path}: no values of '{quantity}'")]
    NoValues {
        /// The file.
        path: PathBuf,
        /// The quantity asked for.
        quantity: String,
    },
    /// A quantity not of the reader's form.
    #[error("quantity '{quantity}': expected {expected}")]
    Quantity {
        /// The quantity given.
        quantity: String,
        /// The reader's form of it, with an example.
        expected: &'static str,
    },
    /// A row ends before the named column's value.
    #[error("{path}:{line}: the row has no '{column}' value (truncated?)")]
    NamedColumn {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// The column's name.
        column: String,
    },
    /// A row ends before the numbered column.
    #[error("{path}:{line}: the row has no column {column} (truncated?)")]
    Column {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// The 1-based column after the id.
        column: usize,
    },
    /// A dataset without the component asked for.
    #[error("{path}:{line}: dataset {dataset} has no component {component} ({components})")]
    Component {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// The dataset.
        dataset: String,
        /// The component asked for.
        component: String,
        /// The dataset's components, comma-separated.
        components: String,
    },
    /// A row ends before the component's value.
    #[error("{path}:{line}: the row has no {component} value")]
    ComponentValue {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// The component.
        component: String,
    },
    /// A line without the label asked for.
    #[error("{path}:{line}: no '{label}' on the line")]
    Label {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// The label.
        label: String,
    },
    /// A label at the end of its line.
    #[error("{path}:{line}: no value after '{label}'")]
    LabelValue {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// The label.
        label: String,
    },
    /// A mass the deck does not have.
    #[error("{deck}: mass {mass}: the deck has {masses} masses")]
    Mass {
        /// The deck.
        deck: PathBuf,
        /// The 1-based mass asked for.
        mass: usize,
        /// The deck's masses.
        masses: usize,
    },
    /// An empty history.
    #[error("no values")]
    Empty,
    /// A non-finite value in the history.
    #[error("a value of {value}")]
    NonFinite {
        /// The value.
        value: f64,
    },
    /// The CalculiX results (the `.dat` file or the deck).
    #[error(transparent)]
    Calculix(#[from] bumpsim_export::ExportError),
    /// The CSV table or its column.
    #[error(transparent)]
    Table(#[from] bumpsim_io::table::TableError),
}

/// Why a point's model cannot be identified.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PointIdentifyError {
    /// The point's study file or its cases (boxed: a study error names its
    /// file, case, key and value, and would make every result large).
    #[error(transparent)]
    Study(Box<bumpsim_ident::StudyError>),
    /// The identification.
    #[error(transparent)]
    Identify(#[from] bumpsim_ident::IdentError),
    /// The identified parameters are not finite.
    #[error("the identified parameters are not finite")]
    NotFinite,
}

impl From<bumpsim_ident::StudyError> for PointIdentifyError {
    fn from(error: bumpsim_ident::StudyError) -> Self {
        PointIdentifyError::Study(Box::new(error))
    }
}

/// Shorthand for results of this crate.
pub type Result<T> = std::result::Result<T, CampaignError>;

/// A read error of `path`.
pub(crate) fn read_error(path: &std::path::Path, source: std::io::Error) -> CampaignError {
    CampaignError::Read {
        path: path.into(),
        source,
    }
}
