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

use crate::case::LoadCase;
use crate::estimate::{Bounds, Settings};
use bumpsim_core::channel::Channel;
use bumpsim_core::model::{parameter_count, parameter_name};
use bumpsim_core::units::Dimension;
use bumpsim_io::signal_error::SignalFileError;
use bumpsim_io::test_data::TestData;
use bumpsim_signal::process::{Combine, ProcessError, Step, align, combine, run};
use bumpsim_signal::window::ContactThreshold;
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Why a study cannot be read.
#[derive(Debug, thiserror::Error)]
pub enum StudyError {
    /// The study file itself.
    #[error("{path}: {message}")]
    File {
        /// The study file.
        path: PathBuf,
        /// What is wrong.
        message: String,
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
    #[error("case '{case}': {message}")]
    Case {
        /// The case.
        case: String,
        /// What is wrong.
        message: String,
    },
}

/// `dof = 3` or `dof = [1, 2, 3]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(untagged)]
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
    /// Per-parameter bounds by name: `bounds = { m1 = [1, 50] }`.
    #[serde(default)]
    pub bounds: BTreeMap<String, [f64; 2]>,
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
#[serde(untagged)]
pub enum OutputDof {
    /// A mass number, 1-based.
    Number(usize),
    /// `"last"`: the last mass of each model.
    Named(String),
}

/// `window = "contact"` or `window = [t0, t1]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(untagged)]
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
        let mut study: Study = toml::from_str(&text).map_err(|e| error(e.to_string()))?;
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
        Ok(study)
    }

    /// The DOF values to identify.
    pub fn dofs(&self) -> Vec<usize> {
        match &self.model.dof {
            DofSpec::One(n) => vec![*n],
            DofSpec::Many(list) => list.clone(),
        }
    }

    /// Settings for `dof` masses.
    pub fn settings(&self, dof: usize) -> Result<Settings, StudyError> {
        let error = |message: String| StudyError::File {
            path: self.path.clone(),
            message,
        };
        let p = parameter_count(dof);
        let mut bounds = Bounds::uniform(dof, self.model.lower_bound);
        if let Some(upper) = self.model.upper_bound {
            bounds.upper = vec![upper; p];
        }
        let names: Vec<String> = (0..p).map(|i| parameter_name(dof, i)).collect();
        let index = |name: &str| names.iter().position(|n| n == name);
        for (name, [lo, hi]) in &self.model.bounds {
            if let Some(i) = index(name) {
                (bounds.lower[i], bounds.upper[i]) = (*lo, *hi);
            } else if dof == self.dofs().into_iter().max().unwrap_or(dof) {
                return Err(error(format!(
                    "bounds: no parameter '{name}' in a {dof}-DOF model ({})",
                    names.join(", ")
                )));
            }
        }
        for (name, value) in &self.model.fixed {
            if let Some(i) = index(name) {
                bounds.fixed[i] = Some(*value);
            }
        }
        let start = match &self.model.start {
            Some(s) if s.masses.len() == dof => {
                Some([&s.masses[..], &s.dampers, &s.springs].concat())
            }
            _ => None,
        };
        Ok(Settings {
            dof,
            bounds,
            starts: self.model.starts,
            seed: self.model.seed,
            start,
            ..Settings::new(dof, 1)
        })
    }

    /// Reads and processes every case for a `dof`-mass model.
    pub fn cases(&self, dof: usize) -> Result<Vec<LoadCase>, StudyError> {
        let mut tests = BTreeMap::new();
        self.case
            .iter()
            .map(|spec| self.load_case(spec, dof, &mut tests))
            .collect()
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
        let mut tests = BTreeMap::new();
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
        self.case
            .iter()
            .filter(|c| names.is_empty() || names.contains(&c.name))
            .map(|spec| self.load_case(spec, dof, &mut tests))
            .collect()
    }

    fn load_case(
        &self,
        spec: &CaseSpec,
        dof: usize,
        tests: &mut BTreeMap<PathBuf, TestData>,
    ) -> Result<LoadCase, StudyError> {
        let ctx = CaseContext { study: self, spec };
        let force = ctx.force(tests)?;
        let output = match (&spec.displacement, spec.acceleration.is_empty()) {
            (Some(d), true) => ctx.channels(std::slice::from_ref(d), tests, Combine::Mean)?,
            (None, false) => ctx.displacement_from_acceleration(tests)?,
            _ => {
                return Err(
                    ctx.case("give either 'displacement' or 'acceleration' (a list of channels)")
                );
            }
        };
        if output.dimension != Dimension::Length {
            return Err(ctx.case(&format!(
                "the displacement channel is {}, expected a length",
                output.dimension
            )));
        }
        ctx.build(force, output, dof)
    }
}

struct CaseContext<'a> {
    study: &'a Study,
    spec: &'a CaseSpec,
}

impl CaseContext<'_> {
    fn case(&self, message: &str) -> StudyError {
        StudyError::Case {
            case: self.spec.name.clone(),
            message: message.to_string(),
        }
    }

    fn process(&self, result: Result<Channel, ProcessError>) -> Result<Channel, StudyError> {
        result.map_err(|source| StudyError::Process {
            case: self.spec.name.clone(),
            source,
        })
    }

    fn data(&self, result: Result<TestData, SignalFileError>) -> Result<TestData, StudyError> {
        result.map_err(|source| StudyError::Data {
            case: self.spec.name.clone(),
            source,
        })
    }

    /// Loads, scales and combines channel references.
    fn channels(
        &self,
        refs: &[ChannelRef],
        tests: &mut BTreeMap<PathBuf, TestData>,
        how: Combine,
    ) -> Result<Channel, StudyError> {
        let mut loaded = Vec::new();
        for r in refs {
            let path = self.study.base.join(&r.path);
            if !tests.contains_key(&path) {
                let test = self.data(TestData::open(&path))?;
                tests.insert(path.clone(), test);
            }
            let test = &tests[&path];
            let wrap = |source| StudyError::Data {
                case: self.spec.name.clone(),
                source,
            };
            let selection = test.select(&r.channel).map_err(wrap)?;
            for channel in test.load_all(&selection).map_err(wrap)? {
                loaded.push(self.process(Step::Scale(r.scale).apply(&channel))?);
            }
        }
        match loaded.len() {
            1 => Ok(loaded.remove(0)),
            _ => self.process(combine(&loaded, how, &self.spec.name)),
        }
    }

    /// Bias removal and the CFC filter.
    fn conditioning(&self, channel: &Channel) -> Vec<Step> {
        let mut steps = Vec::new();
        match self.spec.bias {
            Some(window) => steps.push(Step::Bias(window)),
            None if channel.series.start() < 0.0 => steps.push(Step::PretriggerBias(true)),
            None => {}
        }
        if let Some(class) = self.spec.cfc {
            steps.push(Step::Cfc(class));
        }
        steps
    }

    fn force(&self, tests: &mut BTreeMap<PathBuf, TestData>) -> Result<Channel, StudyError> {
        let raw = self.channels(std::slice::from_ref(&self.spec.force), tests, Combine::Sum)?;
        if raw.dimension != Dimension::Force {
            return Err(self.case(&format!(
                "the force channel is {}, expected a force",
                raw.dimension
            )));
        }
        self.process(run(&self.conditioning(&raw), &raw))
    }

    fn displacement_from_acceleration(
        &self,
        tests: &mut BTreeMap<PathBuf, TestData>,
    ) -> Result<Channel, StudyError> {
        let raw = self.channels(&self.spec.acceleration, tests, Combine::Mean)?;
        if raw.dimension != Dimension::Acceleration {
            return Err(self.case(&format!(
                "the acceleration channels are {}, expected accelerations",
                raw.dimension
            )));
        }
        let mut steps = self.conditioning(&raw);
        steps.extend([
            Step::Integrate(self.spec.initial_velocity),
            Step::Integrate(0.0),
        ]);
        self.process(run(&steps, &raw))
    }

    /// Aligns force and displacement, starts at t = 0 and sets the window.
    fn build(&self, force: Channel, output: Channel, dof: usize) -> Result<LoadCase, StudyError> {
        let (time, columns) = align(&[force, output]).map_err(|source| StudyError::Process {
            case: self.spec.name.clone(),
            source,
        })?;
        let first = time
            .iter()
            .position(|&t| t >= -1e-9)
            .ok_or_else(|| self.case("no samples at or after t = 0"))?;
        let (force, measured) = (columns[0][first..].to_vec(), columns[1][first..].to_vec());
        let step = if time.len() > 1 {
            time[1] - time[0]
        } else {
            0.0
        };
        let start = time[first];
        let window = self.window(&force, start, step)?;
        let output_dof = match &self.spec.output_dof {
            None => 1,
            Some(OutputDof::Number(n)) => *n,
            Some(OutputDof::Named(s)) if s.eq_ignore_ascii_case("last") => dof,
            Some(OutputDof::Named(s)) => {
                return Err(self.case(&format!("output_dof '{s}': expected a number or \"last\"")));
            }
        };
        let case = LoadCase {
            name: self.spec.name.clone(),
            start,
            step,
            force,
            measured,
            output_dof,
            initial_velocity: self.spec.initial_velocity,
            window,
        };
        case.validate().map_err(|e| self.case(&e.to_string()))?;
        Ok(case)
    }

    fn window(&self, force: &[f64], start: f64, step: f64) -> Result<(usize, usize), StudyError> {
        match &self.spec.window {
            None => self.contact(force),
            Some(WindowSpec::Named(s)) if s.eq_ignore_ascii_case("contact") => self.contact(force),
            Some(WindowSpec::Named(s)) => Err(self.case(&format!(
                "window '{s}': expected \"contact\" or [t0, t1] in s"
            ))),
            Some(WindowSpec::Times([t0, t1])) => {
                let index = |t: f64| ((t - start) / step).round().max(0.0) as usize;
                let (a, b) = (index(*t0), index(*t1).min(force.len() - 1));
                if a >= b {
                    return Err(self.case(&format!(
                        "window [{t0}, {t1}] s holds no samples of the data"
                    )));
                }
                Ok((a, b))
            }
        }
    }

    fn contact(&self, force: &[f64]) -> Result<(usize, usize), StudyError> {
        let w = ContactThreshold::default()
            .detect(force)
            .map_err(|e| self.case(&e.to_string()))?;
        Ok((w.first, w.last))
    }
}
