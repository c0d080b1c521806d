//! The errors of a campaign: each names the file, key, point or program it
//! is about, so the engineer can fix the campaign file or the cluster setup.

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
    /// A scheduler command failed.
    #[error("{command}: {message}")]
    Scheduler {
        /// The command line.
        command: String,
        /// Its error output or status.
        message: String,
    },
    /// A point's output cannot be read (missing, corrupt, not finite).
    #[error("point {run}: response '{response}': {message}")]
    Output {
        /// The point's run number.
        run: usize,
        /// The response.
        response: String,
        /// What is wrong.
        message: String,
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

/// Shorthand for results of this crate.
pub type Result<T> = std::result::Result<T, CampaignError>;

/// A read error of `path`.
pub(crate) fn read_error(path: &std::path::Path, source: std::io::Error) -> CampaignError {
    CampaignError::Read {
        path: path.into(),
        source,
    }
}
