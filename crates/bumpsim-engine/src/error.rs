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
    /// The JSON document could not be made.
    #[error("JSON document: {0}")]
    Json(#[from] serde_json::Error),
}
