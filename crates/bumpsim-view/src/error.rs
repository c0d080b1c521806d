//! The viewer's errors: an input that cannot be opened, a request whose
//! parameter is refused (named, with the reason), processing the library
//! refused, and the server's own failures.

use std::path::PathBuf;

/// What went wrong in the viewer.
#[derive(Debug, thiserror::Error)]
pub enum ViewError {
    /// An input named on the command line cannot be read.
    #[error("{path}: {reason}")]
    Input {
        /// The input.
        path: PathBuf,
        /// Why.
        reason: String,
    },
    /// A test file the library's readers refused.
    #[error(transparent)]
    Test(#[from] bumpsim_io::SignalFileError),
    /// A request parameter refused.
    #[error("parameter '{parameter}': {reason}")]
    Parameter {
        /// The parameter as the request names it.
        parameter: String,
        /// Why it is refused.
        reason: String,
    },
    /// Processing refused by bumpsim-signal.
    #[error(transparent)]
    Pipeline(#[from] bumpsim_signal::PipelineError),
    /// A processing step refused by bumpsim-signal.
    #[error(transparent)]
    Process(#[from] bumpsim_signal::ProcessError),
    /// A table that cannot be written as CSV.
    #[error(transparent)]
    Table(#[from] bumpsim_io::TableError),
    /// An output the guard or the writer refused.
    #[error(transparent)]
    Output(#[from] bumpsim_io::output::OutputError),
    /// The server could not start or answer.
    #[error("viewer server: {reason}")]
    Server {
        /// Why.
        reason: String,
    },
}

impl ViewError {
    /// A refused request parameter.
    pub fn parameter(parameter: &str, reason: impl Into<String>) -> ViewError {
        ViewError::Parameter {
            parameter: parameter.to_string(),
            reason: reason.into(),
        }
    }
}
