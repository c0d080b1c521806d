//! `synth` as one request: the series file's declared kind
//! ([`ModelKind::of`] with [`Role::Series`]) picks the registered model
//! that makes its tests ([`crate::model::CarModel::synth`]: the chain's
//! pendulum series, [`bumpsim_impact::synth`], the links chain's barrier
//! series, [`bumpsim_impact::barrier_series`], or the planar car's,
//! `bumpsim_planar::series`) — and the answer is the same for every
//! model: the tests (name, ISO-MME header, channels), the provenance
//! and the further files of the folder. No equations here; the front end
//! writes the folder.

use crate::EngineError;
use bumpsim_io::kind::{KindError, ModelKind, Role};
use std::path::Path;

pub use crate::model::Made;

/// Makes the series of the file at `path`, by its model.
pub fn make(path: &Path) -> Result<Made, EngineError> {
    let kind = ModelKind::of(path, Role::Series).map_err(|source| match source {
        // names the file itself
        KindError::NotAFile(_) => EngineError::Kind(source),
        _ => EngineError::Series {
            path: path.into(),
            source,
        },
    })?;
    crate::registry::model(kind, "synth")?.synth(path)
}
