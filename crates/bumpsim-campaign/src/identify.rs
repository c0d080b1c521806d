//! Per-point identification (paper C stage 2 at scale): an `[identify]`
//! section names a study template (`bumpsim identify`'s study file, with
//! `{{name}}` placeholders like the deck), rendered into each point folder
//! as `study.toml`; its load cases read the histories the point's run
//! wrote (paths relative to the point folder). `campaign collect`
//! identifies one `dof`-mass model per done point with
//! [`bumpsim_ident::identify`] and appends its parameters to the table as
//! `m1 [kg]`, ..., `c1 [Ns/m]`, ..., `k1 [N/m]` (the columns of `doe
//! collect`), which `[regress]` may then name.

use crate::error::PointIdentifyError;
use bumpsim_ident::study::Study;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// The study file's name in a point folder.
pub const STUDY_FILE: &str = "study.toml";

/// The `[identify]` section.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IdentifySpec {
    /// The study template (relative to the campaign file).
    pub study: PathBuf,
    /// Masses of the identified model.
    pub dof: usize,
    /// Starts of the multi-start search (default: the study's).
    #[serde(default)]
    pub starts: Option<usize>,
}

impl IdentifySpec {
    /// The parameter columns: names and SI units (`m1 [kg]`, `c1 [Ns/m]`, `k1 [N/m]`).
    pub fn columns(&self) -> Vec<(String, &'static str)> {
        let n = self.dof;
        let mut columns: Vec<(String, &'static str)> =
            (1..=n).map(|j| (format!("m{j}"), "kg")).collect();
        columns.extend((1..n).map(|j| (format!("c{j}"), "Ns/m")));
        columns.extend((1..n).map(|j| (format!("k{j}"), "N/m")));
        columns
    }
}

/// Identifies the model of the point in `folder`: its parameters in the
/// order of [`IdentifySpec::columns`], or why not.
pub fn identify_point(folder: &Path, spec: &IdentifySpec) -> Result<Vec<f64>, PointIdentifyError> {
    let study = Study::read(&folder.join(STUDY_FILE))?;
    let loaded = study.load(spec.dof)?;
    let mut settings = study.settings(spec.dof)?;
    settings.starts = spec.starts.unwrap_or(settings.starts);
    let cases = study.retarget(&loaded.cases, spec.dof);
    let result = bumpsim_ident::identify(&cases, &settings, &|| {})?;
    let parameters = result.model.parameters();
    match parameters.iter().all(|v| v.is_finite()) {
        true => Ok(parameters),
        false => Err(PointIdentifyError::NotFinite),
    }
}
