//! Per-point identification (paper C stage 2 at scale): an `[identify]`
//! section names a study template (`bumpsim identify`'s study file, with
//! `{{name}}` placeholders like the deck), rendered into each point folder
//! as `study.toml`; its load cases read the histories the point's run
//! wrote (paths relative to the point folder). `campaign collect`
//! identifies one `dof`-mass model per done point with
//! [`bumpsim_ident::identify`] and appends its parameters to the table as
//! `m1 [kg]`, ..., `c1 [Ns/m]`, ..., `k1 [N/m]` (the columns of `doe
//! collect`), which `[regress]` may then name; then `k1.se [N/m]`, ...: the
//! identification's standard error of each parameter that has one at every
//! collected point (`bumpsim doe fit --se k1` reads them).

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

/// A point's identified parameters and their standard errors (`None`
/// where the identification has none: fixed, at a bound, undetermined),
/// both in the order of [`IdentifySpec::columns`].
pub type Identified = (Vec<f64>, Vec<Option<f64>>);

/// Identifies the model of the point in `folder`, or says why not.
pub fn identify_point(
    folder: &Path,
    spec: &IdentifySpec,
) -> Result<Identified, PointIdentifyError> {
    let study = Study::read(&folder.join(STUDY_FILE))?;
    let loaded = study.load(spec.dof)?;
    let mut settings = study.settings(spec.dof)?;
    settings.starts = spec.starts.unwrap_or(settings.starts);
    let cases = study.retarget(&loaded.cases, spec.dof);
    let result = bumpsim_ident::identify(&cases, &settings, &|| {})?;
    let parameters = result.model.parameters();
    let u = &result.uncertainty;
    let errors = spec
        .columns()
        .iter()
        .map(|(name, _)| {
            let i = u.names.iter().position(|n| n == name)?;
            u.standard_errors[i].filter(|s| s.is_finite() && *s >= 0.0)
        })
        .collect();
    match parameters.iter().all(|v| v.is_finite()) {
        true => Ok((parameters, errors)),
        false => Err(PointIdentifyError::NotFinite),
    }
}
