//! `synth` of a `kind = "links"` series: the car with nonlinear links run
//! into the rigid barrier at each test's speed, recorded through the
//! pendulum series' measurement chain
//! ([`bumpsim_impact::barrier_series`]: the barrier force
//! `B0LOMASU0000FOXP`, negative while the wall pushes, and left and right
//! X accelerometers on the output masses, in the vehicle frame), and the
//! study that identifies the car from them (`study.toml`): a chain study
//! with `kind = "links"`, one `[[case]]` per test naming its barrier force
//! and the first output mass's accelerometers, `initial_velocity` the
//! test's speed (x forward: the signs of docs/simulate.md), CFC 60 and the
//! window from the contact to the end of the record. The links
//! identification's own `[links]` table is not written
//! ([`bumpsim_impact::barrier_series::study_text`]). No equations.

use crate::EngineError;
use crate::model::Made;
use bumpsim_impact::barrier_series::{make_barrier_series, study_text};
use std::path::Path;

/// The made tests, the provenance and `study.toml`.
pub(super) fn make(path: &Path) -> Result<Made, EngineError> {
    let series = make_barrier_series(path)?;
    let study = study_text(&series, path);
    Ok(Made {
        tests: series.tests,
        provenance: series.provenance,
        files: vec![("study.toml", study)],
    })
}

#[cfg(test)]
#[path = "synth_tests.rs"]
mod tests;
