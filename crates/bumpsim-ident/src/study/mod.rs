//! Study files (TOML): the load cases and settings of an identification.
//!
//! Paths are relative to the study file. Each case names its force
//! (channels summed when a selector matches several, e.g. the cells of a
//! load-cell wall) and either a displacement channel or accelerometer
//! channels (averaged, bias removed, filtered, integrated twice from the
//! initial velocity at t = 0). Force and acceleration get the same bias
//! removal (default: the mean before t = 0, when there are such samples) and
//! the optional CFC filter. The case starts at t = 0, where the initial
//! state applies; the fit window is the contact window of the force
//! (5 % rise, 2 % fall) or `[t0, t1]` s. See docs/identify.md.

use crate::case::{CaseError, LoadCase, VALID_RANGE};
use crate::estimate::{Bounds, Settings};
use crate::estimate::{usable_bounds, usable_fixed};
use bumpsim_core::model::{parameter_count, parameter_name};
use bumpsim_core::names::check_names;
use bumpsim_core::units::{Dimension, format_number};
use bumpsim_io::signal_error::SignalFileError;
use bumpsim_signal::loader::{LoadError, Loader, Note};
use bumpsim_signal::process::ProcessError;
use bumpsim_signal::window::WindowError;
use serde::Deserialize;
use std::collections::BTreeMap;
use std::fmt;
use std::path::{Path, PathBuf};

mod context;
use context::CaseContext;

pub use crate::case::MAX_INITIAL_VELOCITY;

/// Why a study cannot be read.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum StudyError {
    /// The study file itself.
    #[error("{path}: {message}")]
    File {
        /// The study file.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// A `bounds` or `fixed` entry names no parameter of the models.
    #[error("{path}: {table}: no parameter '{name}' in a {dof}-DOF model ({})", valid.join(", "))]
    Parameter {
        /// The study file.
        path: PathBuf,
        /// `bounds` or `fixed`.
        table: &'static str,
        /// The name given.
        name: String,
        /// Masses of the largest model identified.
        dof: usize,
        /// The parameter names of that model.
        valid: Vec<String>,
    },
    /// The `start` does not fit the models identified.
    #[error("{path}: start: {masses} masses, {dampers} dampers, {springs} springs; {expected}")]
    Start {
        /// The study file.
        path: PathBuf,
        /// Masses given.
        masses: usize,
        /// Dampers given.
        dampers: usize,
        /// Springs given.
        springs: usize,
        /// What fits.
        expected: String,
    },
    /// A test file or channel.
    #[error("case '{case}': {source}")]
    Data {
        /// The case.
        case: String,
        /// The cause.
        source: SignalFileError,
    },
    /// Processing a signal.
    #[error("case '{case}': {source}")]
    Process {
        /// The case.
        case: String,
        /// The cause.
        source: ProcessError,
    },
    /// A case definition.
    #[error("case '{case}': {source}")]
    Case {
        /// The case.
        case: String,
        /// What is wrong.
        source: DefinitionError,
    },
}

/// What is wrong with a `[[case]]` definition or its data.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum DefinitionError {
    /// Neither or both of `displacement` and `acceleration`.
    #[error("give either 'displacement' or 'acceleration' (a list of channels)")]
    Output,
    /// A signal of the wrong physical dimension.
    #[error("the {signal} is {found}, expected {expected}")]
    Dimension {
        /// Which signal (`force channel`, ...).
        signal: &'static str,
        /// Its dimension.
        found: Dimension,
        /// What it must be.
        expected: &'static str,
    },
    /// The channels could not be made into one signal.
    #[error(transparent)]
    Load(LoadError),
    /// The data end before t = 0.
    #[error("no samples at or after t = 0")]
    NoSamples,
    /// `output_dof` is neither a number nor `"last"`.
    #[error("output_dof '{0}': expected a number or \"last\"")]
    OutputDof(String),
    /// `output_dof` names no mass of the model.
    #[error("output_dof = {output_dof}: the model has masses 1 to {dof}")]
    OutputDofRange {
        /// The mass given (1-based).
        output_dof: usize,
        /// The model's number of masses.
        dof: usize,
    },
    /// `window` is neither `"contact"` nor two times.
    #[error("window '{0}': expected \"contact\" or [t0, t1] in s")]
    WindowName(String),
    /// The window `[t0, t1]` s holds fewer than two samples.
    #[error(
        "window [{t0}, {t1}] s holds fewer than two samples of the data (a window needs t0 < t1 and at least two samples)"
    )]
    EmptyWindow {
        /// Start, s.
        t0: f64,
        /// End, s.
        t1: f64,
    },
    /// No contact in the force.
    #[error(transparent)]
    Contact(#[from] WindowError),
    /// A case failed after its force and displacement were put on one
    /// time base: the failure, and how they were.
    #[error("{error} (after {note})")]
    Resampled {
        /// What [`bumpsim_signal::process::Resampling`] says.
        note: String,
        /// The failure.
        error: Box<DefinitionError>,
    },
    /// The processed case is not usable (shown without the case's name,
    /// which [`StudyError::Case`] gives already).
    #[error("{}", .0.reason())]
    Invalid(CaseError),
}

impl From<CaseError> for DefinitionError {
    fn from(error: CaseError) -> DefinitionError {
        DefinitionError::Invalid(error)
    }
}

/// A note on the channels of one case (left out, or used despite a mark).
#[derive(Debug, Clone, PartialEq)]
pub struct CaseNote {
    /// The case.
    pub case: String,
    /// The note of its channel selection.
    pub note: Note,
}

impl fmt::Display for CaseNote {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "case '{}': {}", self.case, self.note)
    }
}

/// The load cases of a study and the notes of their channel selections.
#[derive(Debug, Clone)]
pub struct LoadedCases {
    /// The cases, processed.
    pub cases: Vec<LoadCase>,
    /// What the channel selections left out or used despite a mark.
    pub notes: Vec<CaseNote>,
}

/// `dof = 3` or `dof = [1, 2, 3]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(
    untagged,
    expecting = "dof: expected a number of masses (dof = 3) or a list of them (dof = [1, 2, 3])"
)]
pub enum DofSpec {
    /// One model size.
    One(usize),
    /// A sweep.
    Many(Vec<usize>),
}

/// A start or fixed set by kind.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ParameterSet {
    /// Masses, kg.
    pub masses: Vec<f64>,
    /// Dampers, N·s/m.
    pub dampers: Vec<f64>,
    /// Springs, N/m.
    pub springs: Vec<f64>,
}

/// The `[model]` table.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelSpec {
    /// Number of masses, or a list to sweep.
    pub dof: DofSpec,
    /// Lower bound of every parameter, SI (thesis: 1).
    #[serde(default = "one")]
    pub lower_bound: f64,
    /// Upper bound of every parameter, SI (default: none).
    pub upper_bound: Option<f64>,
    /// Per-parameter bounds by name: `bounds = { m1 = [1, 50] }` (exactly
    /// two values, checked with the names: a fixed-size array let a third
    /// value pass unseen).
    #[serde(default)]
    pub bounds: BTreeMap<String, Vec<f64>>,
    /// Per-parameter fixed values by name: `fixed = { m1 = 2.0 }`.
    #[serde(default)]
    pub fixed: BTreeMap<String, f64>,
    /// Number of starts.
    #[serde(default = "default_starts")]
    pub starts: usize,
    /// Seed of the random starts.
    #[serde(default = "default_seed")]
    pub seed: u64,
    /// Discretisation: only `zoh` (exact, with exact sensitivities).
    #[serde(default = "zoh")]
    pub method: String,
    /// The user's start.
    pub start: Option<ParameterSet>,
}

fn one() -> f64 {
    1.0
}
fn default_starts() -> usize {
    32
}
fn default_seed() -> u64 {
    1
}
fn zoh() -> String {
    "zoh".into()
}

/// A channel reference: file, selector, scale factor.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ChannelRef {
    /// Test file (relative to the study).
    pub path: PathBuf,
    /// Channel selector (number, code with wildcards, name).
    pub channel: String,
    /// Factor applied after reading (e.g. −1 to change sign).
    #[serde(default = "unit_scale")]
    pub scale: f64,
}

fn unit_scale() -> f64 {
    1.0
}

/// `output_dof = 1` or `output_dof = "last"`.
#[derive(Debug, Clone, Deserialize)]
#[serde(
    untagged,
    expecting = "output_dof: expected a mass number (output_dof = 1) or \"last\""
)]
pub enum OutputDof {
    /// A mass number, 1-based.
    Number(usize),
    /// `"last"`: the last mass of each model.
    Named(String),
}

/// `window = "contact"` or `window = [t0, t1]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(
    untagged,
    expecting = "window: expected \"contact\" or a start and end time in seconds (window = [0.0, 0.06])"
)]
pub enum WindowSpec {
    /// `"contact"`.
    Named(String),
    /// Seconds.
    Times([f64; 2]),
}

/// One `[[case]]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CaseSpec {
    /// Case name.
    pub name: String,
    /// Force on m1 (several matches are summed).
    pub force: ChannelRef,
    /// Accelerometers of the output DOF (averaged, integrated twice).
    #[serde(default)]
    pub acceleration: Vec<ChannelRef>,
    /// Or the displacement directly.
    pub displacement: Option<ChannelRef>,
    /// Bias window, s.
    pub bias: Option<[f64; 2]>,
    /// CFC class for force and acceleration.
    pub cfc: Option<f64>,
    /// Initial velocity of the car, m/s.
    #[serde(default)]
    pub initial_velocity: f64,
    /// Output DOF.
    pub output_dof: Option<OutputDof>,
    /// Fit window.
    pub window: Option<WindowSpec>,
}

/// A study file.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Study {
    /// Model settings.
    pub model: ModelSpec,
    /// Load cases.
    pub case: Vec<CaseSpec>,
    /// Folder of the study file.
    #[serde(skip)]
    pub base: PathBuf,
    /// The study file.
    #[serde(skip)]
    pub path: PathBuf,
}

impl Study {
    /// Reads a study file.
    pub fn read(path: &Path) -> Result<Study, StudyError> {
        let error = |message: String| StudyError::File {
            path: path.to_path_buf(),
            message,
        };
        let text = std::fs::read_to_string(path).map_err(|e| error(format!("cannot read: {e}")))?;
        let mut study: Study =
            toml::from_str(&text).map_err(|e| error(bumpsim_io::toml_message(&text, &e)))?;
        study.base = path.parent().map(Path::to_path_buf).unwrap_or_default();
        study.path = path.to_path_buf();
        if !study.model.method.eq_ignore_ascii_case("zoh") {
            return Err(error(format!(
                "method '{}': identification uses the exact zoh discretisation (its sensitivities are exact); use method = \"zoh\"",
                study.model.method
            )));
        }
        if study.case.is_empty() {
            return Err(error(
                "no [[case]]: a study needs at least one load case".into(),
            ));
        }
        study.check_case_names().map_err(error)?;
        study.check_global_bounds().map_err(error)?;
        study.check_tables().map_err(error)?;
        study.check_dofs().map_err(error)?;
        Ok(study)
    }

    /// `lower_bound` and `upper_bound` apply to every parameter, `bounds`
    /// and `fixed` to one: checked here, where their keys can be named
    /// (the identification's own check names a parameter, m1 first, and
    /// not the file).
    fn check_global_bounds(&self) -> Result<(), String> {
        let lower = self.model.lower_bound;
        let upper = self.model.upper_bound.unwrap_or(f64::INFINITY);
        let (floor, ceiling) = (*VALID_RANGE.start(), *VALID_RANGE.end());
        if !usable_bounds(lower, f64::INFINITY) {
            return Err(format!(
                "[model] lower_bound = {}: expected a number from {floor:e} to below {ceiling:e} (SI: kg, N·s/m and N/m alike, the range the search works in; the thesis uses 1)",
                format_number(lower, 4)
            ));
        }
        if !usable_bounds(lower, upper) {
            return Err(format!(
                "[model] upper_bound = {}: expected a number above lower_bound = {} (SI)",
                format_number(upper, 4),
                format_number(lower, 4)
            ));
        }
        for (name, pair) in &self.model.bounds {
            if let [lo, hi] = pair[..]
                && !usable_bounds(lo, hi)
            {
                return Err(format!(
                    "bounds: {name} = [{}, {}]: expected {floor:e} <= lower < upper with lower below {ceiling:e} (SI)",
                    format_number(lo, 4),
                    format_number(hi, 4)
                ));
            }
        }
        match self.model.fixed.iter().find(|(_, v)| !usable_fixed(**v)) {
            Some((name, v)) => Err(format!(
                "fixed: {name} = {}: expected a finite positive value (SI)",
                format_number(*v, 4)
            )),
            None => Ok(()),
        }
    }

    /// Case names follow [`bumpsim_core::names::check_names`]; each
    /// case's initial velocity is finite and at most
    /// [`MAX_INITIAL_VELOCITY`].
    fn check_case_names(&self) -> Result<(), String> {
        let names = self.case.iter().map(|c| c.name.as_str());
        check_names("[[case]]", names).map_err(|e| e.to_string())?;
        for case in &self.case {
            let v = case.initial_velocity;
            if !(v.is_finite() && v.abs() <= MAX_INITIAL_VELOCITY) {
                return Err(format!(
                    "[[case]] '{}': initial_velocity = {} m/s: expected a finite speed of at most {MAX_INITIAL_VELOCITY} m/s (a crash test's is a few m/s)",
                    case.name,
                    format_number(v, 4)
                ));
            }
        }
        Ok(())
    }

    /// The DOF values to identify.
    pub fn dofs(&self) -> Vec<usize> {
        match &self.model.dof {
            DofSpec::One(n) => vec![*n],
            DofSpec::Many(list) => list.clone(),
        }
    }

    /// Settings for `dof` masses. `bounds` and `fixed` entries must name
    /// parameters of the largest model (of the study's DOF and `dof`); they
    /// apply to each model that has them. A `start` must fit one of those
    /// models (it is used for that one).
    pub fn settings(&self, dof: usize) -> Result<Settings, StudyError> {
        let largest = self.dofs().into_iter().chain([dof]).max().unwrap_or(dof);
        self.check_names(largest)?;
        let p = parameter_count(dof);
        let mut bounds = Bounds::uniform(dof, self.model.lower_bound);
        if let Some(upper) = self.model.upper_bound {
            bounds.upper = vec![upper; p];
        }
        let names: Vec<String> = (0..p).map(|i| parameter_name(dof, i)).collect();
        let index = |name: &str| names.iter().position(|n| n == name);
        for (name, pair) in &self.model.bounds {
            if let (Some(i), [lo, hi]) = (index(name), pair.as_slice()) {
                (bounds.lower[i], bounds.upper[i]) = (*lo, *hi);
            }
        }
        for (name, value) in &self.model.fixed {
            if let Some(i) = index(name) {
                bounds.fixed[i] = Some(*value);
            }
        }
        Ok(Settings {
            dof,
            bounds,
            starts: self.model.starts,
            seed: self.model.seed,
            start: self.start(dof)?,
            ..Settings::new(dof, 1)
        })
    }

    /// Refuses `bounds` and `fixed` entries that name no parameter of a
    /// `largest`-mass model (names of smaller models are a subset).
    fn check_names(&self, largest: usize) -> Result<(), StudyError> {
        let valid: Vec<String> = (0..parameter_count(largest))
            .map(|i| parameter_name(largest, i))
            .collect();
        let tables = [
            ("bounds", self.model.bounds.keys().collect::<Vec<_>>()),
            ("fixed", self.model.fixed.keys().collect()),
        ];
        for (table, names) in tables {
            if let Some(name) = names.into_iter().find(|n| !valid.contains(n)) {
                return Err(StudyError::Parameter {
                    path: self.path.clone(),
                    table,
                    name: name.clone(),
                    dof: largest,
                    valid,
                });
            }
        }
        Ok(())
    }

    /// At least one DOF, each once, each from 1 to `MAX_DOF`.
    fn check_dofs(&self) -> Result<(), String> {
        let dofs = self.dofs();
        let max = crate::estimate::MAX_DOF;
        if dofs.is_empty() {
            return Err(
                "[model] dof = []: expected at least one DOF (dof = 3 or dof = [1, 2, 3])".into(),
            );
        }
        if let Some(twice) = crate::dofs::repeated(&dofs) {
            return Err(format!(
                "[model] dof: {twice} is given twice; each model order once"
            ));
        }
        match dofs.into_iter().find(|&n| n == 0 || n > max) {
            Some(bad) => Err(format!(
                "[model] dof = {bad}: expected 1 to {max} masses (limit MAX_DOF)"
            )),
            None => Ok(()),
        }
    }

    /// A `bounds` entry is two values; a parameter is fixed or bounded, not
    /// both (the fixed value silently won).
    fn check_tables(&self) -> Result<(), String> {
        if let Some((name, pair)) = self.model.bounds.iter().find(|(_, b)| b.len() != 2) {
            return Err(format!(
                "bounds: {name} = {pair:?}: expected [lower, upper], two values"
            ));
        }
        match self
            .model
            .fixed
            .keys()
            .find(|n| self.model.bounds.contains_key(*n))
        {
            Some(name) => Err(format!(
                "{name} is both fixed and bounded: give it in one of fixed and bounds"
            )),
            None => Ok(()),
        }
    }

    /// The user's start for a `dof`-mass model: used when it has `dof`
    /// masses, an error when it fits none of the models identified.
    fn start(&self, dof: usize) -> Result<Option<Vec<f64>>, StudyError> {
        let Some(s) = &self.model.start else {
            return Ok(None);
        };
        let n = s.masses.len();
        let consistent = n >= 1 && s.dampers.len() == n - 1 && s.springs.len() == n - 1;
        let mut dofs = self.dofs();
        dofs.push(dof);
        if consistent && dofs.contains(&n) {
            return Ok((n == dof).then(|| [&s.masses[..], &s.dampers, &s.springs].concat()));
        }
        dofs.sort_unstable();
        dofs.dedup();
        let sizes: Vec<String> = dofs
            .iter()
            .map(|d| format!("{d}, {}, {}", d - 1, d - 1))
            .collect();
        Err(StudyError::Start {
            path: self.path.clone(),
            masses: n,
            dampers: s.dampers.len(),
            springs: s.springs.len(),
            expected: format!(
                "the {} model needs {} (masses, dampers, springs)",
                dofs.iter()
                    .map(|d| format!("{d}-DOF"))
                    .collect::<Vec<_>>()
                    .join(" or "),
                sizes.join(" or ")
            ),
        })
    }

    /// Reads and processes every case for a `dof`-mass model.
    pub fn cases(&self, dof: usize) -> Result<Vec<LoadCase>, StudyError> {
        Ok(self.load(dof)?.cases)
    }

    /// Reads and processes every case for a `dof`-mass model, with the
    /// notes of the channel selections.
    pub fn load(&self, dof: usize) -> Result<LoadedCases, StudyError> {
        self.load_named(dof, &[])
    }

    /// The cases loaded once (for any DOF) adapted to `dof` masses: cases
    /// whose output is `"last"` measure mass `dof`. Saves reading and
    /// processing the test files again for every model size of a sweep.
    pub fn retarget(&self, cases: &[LoadCase], dof: usize) -> Vec<LoadCase> {
        let last = |spec: &CaseSpec| matches!(&spec.output_dof, Some(OutputDof::Named(s)) if s.eq_ignore_ascii_case("last"));
        cases
            .iter()
            .zip(&self.case)
            .map(|(case, spec)| LoadCase {
                output_dof: if last(spec) { dof } else { case.output_dof },
                ..case.clone()
            })
            .collect()
    }

    /// Reads and processes the named cases (all when `names` is empty).
    pub fn cases_named(&self, dof: usize, names: &[String]) -> Result<Vec<LoadCase>, StudyError> {
        Ok(self.load_named(dof, names)?.cases)
    }

    /// Reads and processes the named cases (all when `names` is empty),
    /// with the notes of the channel selections.
    pub fn load_named(&self, dof: usize, names: &[String]) -> Result<LoadedCases, StudyError> {
        if let Some(name) = names
            .iter()
            .find(|n| !self.case.iter().any(|c| &&c.name == n))
        {
            let known: Vec<&str> = self.case.iter().map(|c| c.name.as_str()).collect();
            return Err(StudyError::File {
                path: self.path.clone(),
                message: format!("no case '{name}'; cases: {}", known.join(", ")),
            });
        }
        let mut loader = Loader::new();
        let mut loaded = LoadedCases {
            cases: Vec::new(),
            notes: Vec::new(),
        };
        for spec in self
            .case
            .iter()
            .filter(|c| names.is_empty() || names.contains(&c.name))
        {
            let mut ctx = CaseContext {
                study: self,
                spec,
                loader: &mut loader,
                notes: Vec::new(),
            };
            loaded.cases.push(ctx.load_case(dof)?);
            loaded.notes.append(&mut ctx.notes);
        }
        Ok(loaded)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use bumpsim_signal::loader::Note;
    use std::fmt::Write;

    fn study(model: &str, case: &str, base: &Path) -> Study {
        let text = format!("[model]\n{model}\n[[case]]\nname = \"a\"\n{case}\n");
        let mut study: Study = toml::from_str(&text).unwrap();
        study.base = base.to_path_buf();
        study.path = base.join("study.toml");
        study
    }

    const CASE: &str = "force = { path = \"t.EV5\", channel = \"0-LC-*-XG\" }\ndisplacement = { path = \"t.EV5\", channel = \"3\", scale = 2.0 }";

    /// An EV5 test: a force pulse (curve 1), an invalid load cell (2), a
    /// displacement (3), 0.02 s from t = −0.005 s at 10 kHz.
    fn ev5(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("bumpsim-study-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let row = |vehicle: u8,
                   curve: usize,
                   kind: &str,
                   location: &str,
                   unit: &str,
                   comment: &str| {
            format!(
                "{vehicle}|{curve}|{kind}|00|{location}|XG|SEC|{unit}|0|S|01/JAN/2020|1|1|0|-50|149|100|AM|P|{comment}\n"
            )
        };
        let mut text = String::from("----- INSTRUMENTATION -----\n");
        text += &row(0, 1, "LC", "WALL", "NWT", "WALL FX");
        text += &row(0, 2, "LC", "WALX", "NWT", "No valid data");
        text += &row(1, 3, "DS", "CG", "MM", "CG DX");
        std::fs::write(dir.join("t.EV5"), text).unwrap();
        let pulse = |t: f64| {
            if (0.0..0.01).contains(&t) {
                1e4 * (t * 100.0 * std::f64::consts::PI).sin()
            } else {
                0.0
            }
        };
        let curves: [&dyn Fn(f64) -> f64; 3] = [&pulse, &|t| 5.0 * pulse(t), &|t| 1e-2 * pulse(t)];
        for (curve, value) in curves.iter().enumerate() {
            let mut samples = String::new();
            for k in -50..150 {
                let t = k as f64 * 1e-4;
                writeln!(samples, "{t}\t{}", value(t)).unwrap();
            }
            std::fs::write(dir.join(format!("t.{:03}", curve + 1)), samples).unwrap();
        }
        dir
    }

    /// A displacement sampled at half the force's rate, over a shorter
    /// span, was resampled and cut without a word.
    #[test]
    fn force_and_displacement_on_different_time_bases_get_a_note() {
        let dir = ev5("resampled");
        // 5 kHz from 0 to 0.009 s (the force: 10 kHz from -0.005 s to 0.0149 s)
        let mut csv = String::from("time [s],x [m]\n");
        for k in 0..46 {
            let t = k as f64 * 2e-4;
            writeln!(csv, "{t},{}", 1e-3 * t).unwrap();
        }
        std::fs::write(dir.join("x.csv"), csv).unwrap();
        let case = "force = { path = \"t.EV5\", channel = \"1\" }\ndisplacement = { path = \"x.csv\", channel = \"x\" }\nwindow = [0.0, 0.009]";
        let loaded = study("dof = 1", case, &dir).load(1).unwrap();
        let notes: Vec<&CaseNote> = loaded
            .notes
            .iter()
            .filter(|n| matches!(n.note, Note::Resampled(_)))
            .collect();
        assert_eq!(notes.len(), 1, "{:?}", loaded.notes);
        let Note::Resampled(r) = &notes[0].note else {
            unreachable!()
        };
        approx::assert_relative_eq!(r.step, 1e-4, max_relative = 1e-12);
        approx::assert_relative_eq!(r.span[1], 0.009, max_relative = 1e-9);
        assert_eq!(r.interpolated.len(), 1);
        assert_eq!(r.codes[r.interpolated[0].0], "x");
        approx::assert_relative_eq!(r.interpolated[0].1, 2e-4, max_relative = 1e-9);
        // the force's 50 samples before t = 0 and 59 after 0.009 s
        assert_eq!(r.trimmed, [(0, 50 + 59)]);
        let text = notes[0].to_string();
        assert_eq!(
            text,
            "case 'a': force '1' and displacement 'x' put on one time base, every 0.1000 ms from 0 ms to 9.000 ms; displacement (every 0.2000 ms) interpolated linearly; force: 109 samples outside that span left out"
        );
        // the displacement between its samples is the straight line
        let case = &loaded.cases[0];
        approx::assert_relative_eq!(case.measured[3], 1e-3 * 3e-4, max_relative = 1e-9);
    }

    /// Force and displacement that overlap in one sample were refused as
    /// "the force is zero everywhere", although the force file has a pulse.
    #[test]
    fn a_case_failing_on_its_overlap_says_how_the_channels_were_aligned() {
        let dir = ev5("overlap");
        let mut csv = String::from("time [s],x [m]\n");
        for k in 0..20 {
            writeln!(csv, "{},0", 0.0148 + k as f64 * 1e-4).unwrap();
        }
        std::fs::write(dir.join("x.csv"), csv).unwrap();
        let case = "force = { path = \"t.EV5\", channel = \"1\" }\ndisplacement = { path = \"x.csv\", channel = \"x\" }";
        let err = study("dof = 1", case, &dir).load(1).unwrap_err();
        assert!(
            matches!(
                &err,
                StudyError::Case {
                    source: DefinitionError::Resampled { .. },
                    ..
                }
            ),
            "{err:?}"
        );
        let text = err.to_string();
        assert!(
            text.contains("(after force '1' and displacement 'x' put on one time base")
                && text.contains("displacement: 18 samples outside that span left out)"),
            "{text}"
        );
    }

    #[test]
    fn unknown_bounds_and_fixed_names_are_errors_naming_them() {
        let base = Path::new("/study");
        let bad = study("dof = 3\nfixed = { M1 = 2.0 }", CASE, base);
        let err = bad.settings(3).unwrap_err();
        assert!(
            matches!(&err, StudyError::Parameter { table: "fixed", name, dof: 3, .. } if name == "M1")
        );
        let text = err.to_string();
        assert!(
            text.contains("'M1'") && text.contains("m1, m2, m3, c1, c2, k1, k2"),
            "{text}"
        );
        let bad = study("dof = 3\nbounds = { m9 = [1.0, 2.0] }", CASE, base);
        assert!(
            bad.settings(3)
                .unwrap_err()
                .to_string()
                .contains("bounds: no parameter 'm9'")
        );
        // a name of the largest model of a sweep applies where it exists
        let sweep = study(
            "dof = [1, 2, 3]\nfixed = { m3 = 7.0 }\nbounds = { k2 = [5.0, 9.0] }",
            CASE,
            base,
        );
        assert!(
            sweep
                .settings(2)
                .unwrap()
                .bounds
                .fixed
                .iter()
                .all(Option::is_none)
        );
        let three = sweep.settings(3).unwrap();
        assert_eq!(three.bounds.fixed[2], Some(7.0));
        assert_eq!((three.bounds.lower[6], three.bounds.upper[6]), (5.0, 9.0));
    }

    #[test]
    fn a_start_that_fits_no_model_is_an_error() {
        let base = Path::new("/study");
        let start = "[model.start]\nmasses = [1.0, 2.0]\ndampers = [3.0]\nsprings = [4.0]";
        let fits = study(&format!("dof = [2, 3]\n{start}"), CASE, base);
        assert_eq!(
            fits.settings(2).unwrap().start,
            Some(vec![1.0, 2.0, 3.0, 4.0])
        );
        assert_eq!(fits.settings(3).unwrap().start, None);
        let wrong = study(&format!("dof = 3\n{start}"), CASE, base);
        let err = wrong.settings(3).unwrap_err().to_string();
        assert!(
            err.contains("start: 2 masses") && err.contains("3-DOF model needs 3, 2, 2"),
            "{err}"
        );
        let ragged = "[model.start]\nmasses = [1.0, 2.0]\ndampers = [3.0, 1.0]\nsprings = [4.0]";
        assert!(matches!(
            study(&format!("dof = 2\n{ragged}"), CASE, base).settings(2),
            Err(StudyError::Start { dampers: 2, .. })
        ));
    }

    /// A temporary folder of its own, and a reader of a study file written
    /// there with the given text (its error as text).
    fn reader(name: &str) -> (PathBuf, impl Fn(&str) -> Result<Study, String>) {
        let dir = std::env::temp_dir().join(format!("bumpsim-study-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("study.toml");
        let read = move |text: &str| {
            std::fs::write(&path, text).unwrap();
            Study::read(&path).map_err(|e| e.to_string())
        };
        (dir, read)
    }

    /// `lower_bound = -1` was blamed on m1, a name the study does not hold.
    #[test]
    fn global_bounds_are_refused_by_their_own_keys() {
        let (dir, file) = reader("bounds");
        let read = |model: &str| {
            let text = format!("[model]\ndof = 2\n{model}\n[[case]]\nname = \"a\"\n{CASE}\n");
            file(&text).map(|_| ())
        };
        let range = "expected a number from 1e-12 to below 1e15";
        for (model, expected) in [
            (
                "lower_bound = -1.0",
                format!("[model] lower_bound = -1.000: {range}"),
            ),
            (
                "lower_bound = nan",
                format!("[model] lower_bound = NaN: {range}"),
            ),
            (
                "lower_bound = 1e300",
                format!("[model] lower_bound = 1.000e300: {range}"),
            ),
            (
                "lower_bound = 1e-13",
                format!("[model] lower_bound = 1.000e-13: {range}"),
            ),
            (
                "upper_bound = 0.5",
                "[model] upper_bound = 0.5000: expected a number above lower_bound = 1.000".into(),
            ),
            ("upper_bound = nan", "[model] upper_bound = NaN".into()),
            (
                "lower_bound = 1e-12\nupper_bound = 1e-12",
                "[model] upper_bound = 1.000e-12: expected a number above lower_bound = 1.000e-12"
                    .into(),
            ),
            (
                "bounds = { k1 = [-1.0, 5.0] }",
                "bounds: k1 = [-1.000, 5.000]: expected 1e-12 <= lower < upper".into(),
            ),
            (
                "bounds = { c1 = [5.0, 5.0] }",
                "bounds: c1 = [5.000, 5.000]: expected".into(),
            ),
            (
                "fixed = { k1 = nan }",
                "fixed: k1 = NaN: expected a finite positive value".into(),
            ),
            ("fixed = { c1 = 0.0 }", "fixed: c1 = 0: expected".into()),
        ] {
            let err = read(model).unwrap_err();
            assert!(
                err.contains(&expected) && !err.contains("m1") && err.contains("study.toml"),
                "{model}: {err}"
            );
        }
        assert_eq!(read("lower_bound = 1e-3\nupper_bound = inf"), Ok(()));
        assert_eq!(
            read("upper_bound = 1e20\nbounds = { m2 = [0.5, 2.0] }"),
            Ok(())
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// `dof = []` ran nothing with exit 0; two cases named `flat` gave two
    /// `flat` rows; `dof = -2` said "untagged enum DofSpec".
    #[test]
    fn empty_dof_lists_repeated_case_names_and_wrong_shapes_are_errors() {
        let (dir, file) = reader("names");
        let read = |text: &str| file(text).unwrap_err();
        let case = |name: &str| format!("[[case]]\nname = \"{name}\"\n{CASE}\n");
        let err = read(&format!("[model]\ndof = [2, 3, 2]\n{}", case("a")));
        assert!(err.contains("dof: 2 is given twice"), "{err}");
        let err = read(&format!("[model]\ndof = []\n{}", case("a")));
        assert!(err.contains("dof = []: expected at least one DOF"), "{err}");
        let err = read(&format!(
            "[model]\ndof = 2\n{}{}",
            case("flat"),
            case(" Flat")
        ));
        assert!(
            err.contains("[[case]] number 2: name ' Flat' is already used by 'flat'"),
            "{err}"
        );
        let err = read(&format!("[model]\ndof = 2\n{}", case(" ")));
        assert!(err.contains("an empty name"), "{err}");
        let fast = format!("{}initial_velocity = 1e300\n", case("fast"));
        let err = read(&format!("[model]\ndof = 2\n{fast}"));
        assert!(
            err.contains("[[case]] 'fast': initial_velocity = 1.000e300 m/s: expected a finite speed of at most 1000 m/s"),
            "{err}"
        );
        let err = read(&format!(
            "[model]\ndof = 2\n{}initial_velocity = nan\n",
            case("n")
        ));
        assert!(err.contains("initial_velocity = NaN m/s"), "{err}");
        let err = read(&format!("[model]\ndof = 2\n{}", case("red\\u001b[31m")));
        assert!(
            err.contains(r#"the name "red\u001B[31m" holds control or invisible characters"#),
            "{err}"
        );
        let err = read(&format!(
            "[model]\ndof = 2\n{}",
            case("O'Brien \\\"q\\\" bidi\\u202Eevil")
        ));
        assert!(
            err.contains(r#"the name "O'Brien \"q\" bidi\u202Eevil""#),
            "{err}"
        );
        let err = read(&format!("[model]\ndof = 2\n{}", case("zw\\u200Bsp")));
        assert!(err.contains("zw\\u200Bsp"), "{err}");
        let err = read(&format!(
            "[model]\ndof = 2\nbounds = {{ m1 = [1.0, 2.0, 3.0] }}\n{}",
            case("a")
        ));
        assert!(
            err.contains("bounds: m1 = [1.0, 2.0, 3.0]: expected [lower, upper]"),
            "{err}"
        );
        let err = read(&format!(
            "[model]\ndof = 2\nbounds = {{ m1 = [1.0, 20.0] }}\nfixed = {{ m1 = 30.0 }}\n{}",
            case("a")
        ));
        assert!(err.contains("m1 is both fixed and bounded"), "{err}");
        let err = read(&format!("[model]\ndof = -2\n{}", case("a")));
        assert!(
            err.contains("dof: expected a number of masses") && !err.contains("enum"),
            "{err}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_case_keeps_the_notes_of_its_channel_selection() {
        let dir = ev5("notes");
        let loaded = study("dof = 1", CASE, &dir).load(1).unwrap();
        let notes: Vec<String> = loaded.notes.iter().map(ToString::to_string).collect();
        assert_eq!(
            notes,
            ["case 'a': '0-LC-*-XG': left out channel 2 (0-LC-WALX-XG): marked invalid"]
        );
        let case = &loaded.cases[0];
        assert!(case.start.abs() < 1e-12, "{}", case.start);
        assert_eq!(case.force.len(), 150);
        // the invalid cell (5× the force) is not in the sum; the scale applies
        let peak = case.force.iter().fold(0.0_f64, |m, f| m.max(*f));
        approx::assert_relative_eq!(peak, 1e4, max_relative = 1e-3);
        approx::assert_relative_eq!(
            case.measured[25],
            2.0 * 1e-5 * case.force[25],
            max_relative = 1e-9
        );
        assert_eq!(study("dof = 1", CASE, &dir).cases(1).unwrap(), loaded.cases);
    }

    #[test]
    fn a_window_in_seconds_takes_the_samples_inside() {
        let dir = ev5("window");
        let windowed = |w: &str| study("dof = 1", &format!("{CASE}\nwindow = {w}"), &dir).load(1);
        assert_eq!(
            windowed("[0.001, 0.005]").unwrap().cases[0].window,
            (10, 50)
        );
        assert_eq!(
            windowed("[-1.0, 0.00505]").unwrap().cases[0].window,
            (0, 50)
        );
        for empty in ["[-1.0, -0.002]", "[0.00101, 0.00109]", "[0.5, 0.6]"] {
            let err = windowed(empty).unwrap_err();
            assert!(
                matches!(
                    err,
                    StudyError::Case {
                        source: DefinitionError::EmptyWindow { .. },
                        ..
                    }
                ),
                "{empty}: {err}"
            );
        }
        let err = windowed("\"somewhere\"").unwrap_err().to_string();
        assert!(err.contains("case 'a': window 'somewhere'"), "{err}");
    }
}
