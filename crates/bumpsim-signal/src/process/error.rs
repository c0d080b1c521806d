//! Why a processing step, a combination or an alignment failed: each
//! error names the channel and the step.

use crate::filter::FilterError;
use crate::window::WindowError;
use bumpsim_core::series::SeriesError;
use bumpsim_core::units::Dimension;

/// Why a processing step failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ProcessError {
    /// A filter could not be designed or run.
    #[error("channel {channel}: {source}")]
    Filter {
        /// Channel code.
        channel: String,
        /// The filter error.
        source: FilterError,
    },
    /// The step does not apply to the channel's dimension.
    #[error("channel {channel}: step '{step}' needs {expected}, the channel is {found}")]
    Dimension {
        /// Channel code.
        channel: String,
        /// Step name.
        step: &'static str,
        /// What the step needs.
        expected: &'static str,
        /// The channel's dimension.
        found: Dimension,
    },
    /// The result is not a valid series (empty, non-finite).
    #[error("channel {channel}: step '{step}': {source}")]
    Series {
        /// Channel code.
        channel: String,
        /// Step name.
        step: &'static str,
        /// The series error.
        source: SeriesError,
    },
    /// A parameter or time interval is out of range.
    #[error("channel {channel}: step '{step}': {reason}")]
    Range {
        /// Channel code.
        channel: String,
        /// Step name.
        step: &'static str,
        /// What is wrong.
        reason: String,
    },
    /// Contact detection failed.
    #[error("channel {channel}: {source}")]
    Window {
        /// Channel code.
        channel: String,
        /// The window error.
        source: WindowError,
    },
}
