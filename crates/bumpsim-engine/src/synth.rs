//! `synth` as one request: the series file's declared kind
//! ([`ModelKind::of`] with [`Role::Series`]) picks the model that makes its
//! tests — the chain's pendulum series ([`bumpsim_impact::synth`]) or the
//! planar car's ([`bumpsim_planar::series`]) — and the answer is the same
//! for both: the tests (name, ISO-MME header, channels), the provenance
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
    match kind {
        ModelKind::Planar => {
            let series = bumpsim_planar::series::make_series(path)?;
            let tests = series
                .tests
                .into_iter()
                .map(|t| (t.name.clone(), t.test_header(), t.channels))
                .collect();
            let files = vec![("study.toml", series.study), ("start.toml", series.start)];
            Ok(Made {
                tests,
                provenance: series.provenance,
                files,
            })
        }
        ModelKind::Chain => {
            let (tests, provenance) = bumpsim_impact::synth::make_series(path)?;
            Ok(Made {
                tests,
                provenance,
                files: Vec::new(),
            })
        }
        other => Err(EngineError::NotRegistered {
            command: "synth",
            kind: other.name(),
        }),
    }
}
