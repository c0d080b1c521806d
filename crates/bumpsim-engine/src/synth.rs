//! `synth` as one request: the series file's declared kind
//! ([`ModelKind::of`] with [`Role::Series`]) picks the registered model
//! that makes its tests ([`crate::model::CarModel::synth`]: the chain's
//! pendulum series, [`bumpsim_impact::synth`], or the planar car's,
//! `bumpsim_planar::series`) — and the answer is the same for every
//! model: the tests (name, ISO-MME header, channels), the provenance
//! and the further files of the folder. No equations here; the front end
//! writes the folder.

use crate::EngineError;
use bumpsim_impact::synth::SynthTest;
use bumpsim_io::kind::{ModelKind, Role};
use std::path::Path;

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

/// Makes the series of the file at `path`, by its model.
pub fn make(path: &Path) -> Result<Made, EngineError> {
    let kind = ModelKind::of(path, Role::Series).map_err(|source| EngineError::Series {
        path: path.into(),
        source,
    })?;
    crate::registry::model(kind, "synth")?.synth(path)
}
