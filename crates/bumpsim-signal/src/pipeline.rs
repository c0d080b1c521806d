//! Repeatable processing of test data: read channels, combine, process, check.
//!
//! A pipeline ([`Pipeline`], TOML) names output signals. Each is made from
//! channels of a test file (selected by number, code or name, see
//! `bumpsim_io::test_data`), combined by mean or sum when several match
//! (both through the [`loader`](crate::loader), whose notes on left-out
//! channels become [`PipelineResult::warnings`]), or from an earlier output
//! (`from`), then put through [`Step`]s. Paths are relative to the pipeline
//! file.
//!
//! ```toml
//! [[signal]]
//! name = "barrier force"
//! path = "v10146.EV5"
//! channels = ["0-LC-*-XG"]
//! combine = "sum"
//! steps = [{ pretrigger_bias = true }, { cfc = 60 }]
//!
//! [[signal]]
//! name = "velocity"
//! path = "v10146.EV5"
//! channels = ["93", "94"]
//! combine = "mean"
//! steps = [{ pretrigger_bias = true }, { cfc = 60 }, { integrate = 15.858 }]
//!
//! [balance]          # optional momentum check
//! force = "barrier force"
//! velocity = "velocity"
//! ```
//!
//! The momentum balance compares the impulse of the force, `J = ∫ F dt`, with
//! the momentum change of the rigid test mass, `Δp = m (v(t1) − v(t0))`, over
//! the force's contact window (or a given window; the trapezoidal rule of
//! `UniformSeries::integral`, with partial intervals at off-sample ends). A barrier load cell
//! measures the force the car exerts on the wall; the force on the car is its
//! negative, so the magnitudes are compared: `(|J| − |Δp|) / |Δp|`.

pub use crate::loader::select_all;
use crate::loader::{ChannelSource, LoadError, Loader, Note, unambiguous};
use crate::process::{
    Combine, ProcessError, Step, combine, interpolate, notes as process_notes, run,
};
use crate::window::ContactThreshold;
use bumpsim_core::channel::Channel;
use bumpsim_core::units::Dimension;
use bumpsim_io::signal_error::SignalFileError;
use bumpsim_io::test_data::TestData;
use serde::Deserialize;
use std::path::{Path, PathBuf};

/// Why a pipeline cannot run.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PipelineError {
    /// The pipeline file is unreadable or malformed.
    #[error("{path}: {message}")]
    File {
        /// The pipeline file.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// The pipeline file is not a regular file or too large.
    #[error(transparent)]
    Read(bumpsim_core::files::ReadError),
    /// A test file or channel problem.
    #[error(transparent)]
    Data(#[from] SignalFileError),
    /// A processing step failed.
    #[error("signal '{signal}': {source}")]
    Process {
        /// The output signal.
        signal: String,
        /// The cause.
        source: ProcessError,
    },
    /// A signal definition is inconsistent.
    #[error("signal '{signal}': {message}")]
    Definition {
        /// The output signal.
        signal: String,
        /// What is wrong.
        message: String,
    },
}

/// One output signal of a pipeline.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SignalSpec {
    /// Output name (CSV column, plot legend).
    pub name: String,
    /// Test file (ISO-MME folder/.mme/.zip, .EV5, .csv), relative to the pipeline.
    pub path: Option<PathBuf>,
    /// Channel selectors.
    #[serde(default)]
    pub channels: Vec<String>,
    /// An earlier output to continue from, instead of `path` and `channels`.
    pub from: Option<String>,
    /// How to combine several channels.
    pub combine: Option<Combine>,
    /// Processing steps, in order.
    #[serde(default)]
    pub steps: Vec<Step>,
}

/// The optional momentum check.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BalanceSpec {
    /// The force signal (N).
    pub force: String,
    /// The velocity signal of the rigid mass (m/s).
    pub velocity: String,
    /// Mass, kg (default: the test mass stated by the force's test file).
    pub mass: Option<f64>,
    /// Window `[t0, t1]`, s (default: the contact window of the force).
    pub window: Option<[f64; 2]>,
}

/// A pipeline file.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Pipeline {
    /// Default CSV output, relative to the pipeline file.
    pub output: Option<PathBuf>,
    /// The output signals, in order.
    pub signal: Vec<SignalSpec>,
    /// The momentum check.
    pub balance: Option<BalanceSpec>,
    /// Folder of the pipeline file (for relative paths).
    #[serde(skip)]
    pub base: PathBuf,
}

/// What a pipeline produced.
#[derive(Debug, Clone)]
pub struct PipelineResult {
    /// The output signals, processed.
    pub signals: Vec<Channel>,
    /// The same signals before their steps (combined raw channels).
    pub raw: Vec<Channel>,
    /// Notes for the user (channels left out, invalid channels used).
    pub warnings: Vec<String>,
    /// The momentum check, if asked for.
    pub balance: Option<Balance>,
}

/// The result of the momentum check.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Balance {
    /// Window start and end, s.
    pub window: [f64; 2],
    /// Mass used, kg.
    pub mass: f64,
    /// Impulse of the force, N·s.
    pub impulse: f64,
    /// Momentum change of the mass, N·s.
    pub momentum_change: f64,
    /// `(|J| − |Δp|) / |Δp|`.
    pub relative_difference: f64,
}

impl Pipeline {
    /// Reads a pipeline file.
    pub fn read(path: &Path) -> Result<Pipeline, PipelineError> {
        let error = |message: String| PipelineError::File {
            path: path.to_path_buf(),
            message,
        };
        let text = bumpsim_core::files::read_text(path).map_err(PipelineError::Read)?;
        let mut pipeline: Pipeline =
            toml::from_str(&text).map_err(|e| error(bumpsim_io::toml_message(&text, &e)))?;
        // names head CSV columns, plot files and `from`: one each, printable
        let names = pipeline.signal.iter().map(|s| s.name.as_str());
        bumpsim_core::names::check_names("[[signal]]", names).map_err(|e| error(e.to_string()))?;
        pipeline.base = path.parent().map(Path::to_path_buf).unwrap_or_default();
        Ok(pipeline)
    }

    /// Runs every signal, then the balance.
    pub fn run(&self) -> Result<PipelineResult, PipelineError> {
        let mut loader = Loader::new();
        let mut result = PipelineResult {
            signals: Vec::new(),
            raw: Vec::new(),
            warnings: Vec::new(),
            balance: None,
        };
        for spec in &self.signal {
            let (raw, notes) = self.source(spec, &mut loader, &result)?;
            let named = notes
                .into_iter()
                .map(|note| format!("signal '{}': {note}", spec.name));
            result.warnings.extend(named);
            let refiltered = process_notes(&spec.steps, &raw).into_iter();
            result
                .warnings
                .extend(refiltered.map(|note| format!("signal '{}': {note}", spec.name)));
            let mut processed =
                run(&spec.steps, &raw).map_err(|source| PipelineError::Process {
                    signal: spec.name.clone(),
                    source,
                })?;
            processed.code = spec.name.clone();
            result.raw.push(raw);
            result.signals.push(processed);
        }
        if let Some(spec) = &self.balance {
            let mass = spec.mass.or_else(|| self.test_mass(&spec.force, &loader));
            result.balance = Some(balance(&result.signals, spec, mass)?);
        }
        Ok(result)
    }

    fn test_mass(&self, force: &str, loader: &Loader) -> Option<f64> {
        let spec = self.signal.iter().find(|s| s.name == force)?;
        loader.opened(&self.base.join(spec.path.as_ref()?))?.mass
    }

    fn source(
        &self,
        spec: &SignalSpec,
        loader: &mut Loader,
        done: &PipelineResult,
    ) -> Result<(Channel, Vec<Note>), PipelineError> {
        let definition = |message: String| PipelineError::Definition {
            signal: spec.name.clone(),
            message,
        };
        if let Some(from) = &spec.from {
            let earlier = done.signals.iter().find(|c| &c.code == from);
            let earlier = earlier
                .ok_or_else(|| definition(format!("'from = {from}' names no earlier signal")))?;
            return Ok((earlier.clone(), Vec::new()));
        }
        let path = spec
            .path
            .as_ref()
            .ok_or_else(|| definition("needs 'path' and 'channels', or 'from'".into()))?;
        let path = self.base.join(path);
        let sources: Vec<ChannelSource> = spec
            .channels
            .iter()
            .map(|selector| ChannelSource::new(&path, selector, 1.0))
            .collect();
        let loaded = loader
            .signal(&sources, spec.combine, &spec.name)
            .map_err(|e| load_error(&spec.name, e))?;
        Ok((loaded.data, loaded.notes))
    }
}

/// The pipeline's words for a loading failure of signal `signal`.
fn load_error(signal: &str, error: LoadError) -> PipelineError {
    match error {
        LoadError::Data(e) => PipelineError::Data(e),
        LoadError::Process(source) => PipelineError::Process {
            signal: signal.to_string(),
            source,
        },
        other => PipelineError::Definition {
            signal: signal.to_string(),
            message: other.to_string(),
        },
    }
}

fn find<'a>(
    signals: &'a [Channel],
    name: &str,
    dimension: Dimension,
) -> Result<&'a Channel, PipelineError> {
    let definition = |message: String| PipelineError::Definition {
        signal: name.to_string(),
        message,
    };
    let channel = signals
        .iter()
        .find(|c| c.code == name)
        .ok_or_else(|| definition("the balance names no such signal".into()))?;
    if channel.dimension != dimension {
        return Err(definition(format!(
            "the balance needs {dimension}, the signal is {}",
            channel.dimension
        )));
    }
    Ok(channel)
}

/// The momentum check of [`BalanceSpec`].
fn balance(
    signals: &[Channel],
    spec: &BalanceSpec,
    mass: Option<f64>,
) -> Result<Balance, PipelineError> {
    let force = find(signals, &spec.force, Dimension::Force)?;
    let velocity = find(signals, &spec.velocity, Dimension::Velocity)?;
    let mass =
        mass.filter(|m| m.is_finite() && *m > 0.0)
            .ok_or_else(|| PipelineError::Definition {
                signal: spec.force.clone(),
                message: "the balance needs 'mass' (kg): the test file states none".into(),
            })?;
    let s = &force.series;
    let window = match spec.window {
        Some(w) if !(w[0].is_finite() && w[1].is_finite() && w[0] < w[1]) => {
            return Err(PipelineError::Definition {
                signal: spec.force.clone(),
                message: format!(
                    "[balance] window = [{}, {}]: expected two finite times in s, the start before the end",
                    w[0], w[1]
                ),
            });
        }
        Some(w) => w,
        None => {
            let w = ContactThreshold::default()
                .detect(s.values())
                .map_err(|e| PipelineError::Definition {
                    signal: spec.force.clone(),
                    message: e.to_string(),
                })?;
            [s.time(w.first), s.time(w.last)]
        }
    };
    let impulse = s.integral(window[0], window[1]);
    let momentum_change = mass
        * (interpolate(&velocity.series, window[1]) - interpolate(&velocity.series, window[0]));
    let relative_difference = (impulse.abs() - momentum_change.abs()) / momentum_change.abs();
    Ok(Balance {
        window,
        mass,
        impulse,
        momentum_change,
        relative_difference,
    })
}

/// A short description of a signal: peak magnitude with its time, minimum, maximum.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Extremes {
    /// Value of largest magnitude, SI.
    pub peak: f64,
    /// Its time, s.
    pub peak_time: f64,
    /// Smallest value, SI.
    pub min: f64,
    /// Largest value, SI.
    pub max: f64,
}

/// The extremes of a channel.
pub fn extremes(channel: &Channel) -> Extremes {
    let s = &channel.series;
    let (index, _) = bumpsim_core::series::peak_of(s.values());
    let min = s.values().iter().copied().fold(f64::INFINITY, f64::min);
    let max = s.values().iter().copied().fold(f64::NEG_INFINITY, f64::max);
    Extremes {
        peak: s.values()[index],
        peak_time: s.time(index),
        min,
        max,
    }
}

/// Processes channels of one test: each selector's channels (combined when
/// `combine` is given, one output per selector) through `steps`. The
/// signals keep their channel codes (a combination is named after its selector).
pub fn export(
    test: &TestData,
    selectors: &[String],
    steps: &[Step],
    how: Option<Combine>,
) -> Result<PipelineResult, PipelineError> {
    let mut result = PipelineResult {
        signals: Vec::new(),
        raw: Vec::new(),
        warnings: Vec::new(),
        balance: None,
    };
    let mut numbers = Vec::new();
    let mut picked: Vec<(usize, &str)> = Vec::new();
    for selector in selectors {
        let (channels, notes) = select_all(test, std::slice::from_ref(selector))?;
        result
            .warnings
            .extend(notes.iter().map(ToString::to_string));
        let raws = match how {
            Some(how) if channels.len() > 1 => {
                let indices = test.select(selector)?.indices;
                unambiguous(test, selector, &indices).map_err(|e| load_error(selector, e))?;
                numbers.push(None);
                vec![combine(&channels, how, selector).map_err(|source| {
                    PipelineError::Process {
                        signal: selector.clone(),
                        source,
                    }
                })?]
            }
            _ => {
                let indices = test.select(selector)?.indices;
                once(test, &indices, selector, &mut picked)?;
                numbers.extend(indices.iter().map(|&i| Some(test.entries[i].number)));
                channels
            }
        };
        for raw in raws {
            result.warnings.extend(process_notes(steps, &raw));
            let processed = run(steps, &raw).map_err(|source| PipelineError::Process {
                signal: raw.code.clone(),
                source,
            })?;
            result.raw.push(raw);
            result.signals.push(processed);
        }
    }
    distinct_codes(&mut result.signals, &numbers);
    Ok(result)
}

/// Refuses a channel exported as it is a second time (`-c 1 -c 1`): two
/// columns of one channel, which a table cannot tell apart.
fn once<'a>(
    test: &TestData,
    indices: &[usize],
    selector: &'a str,
    picked: &mut Vec<(usize, &'a str)>,
) -> Result<(), PipelineError> {
    for &i in indices {
        if let Some((_, first)) = picked.iter().find(|(j, _)| *j == i) {
            return Err(PipelineError::Definition {
                signal: selector.to_string(),
                message: format!(
                    "channel {} ({}) is picked by '{first}' and again by '{selector}': name each channel once",
                    test.entries[i].number, test.entries[i].code
                ),
            });
        }
        picked.push((i, selector));
    }
    Ok(())
}

/// Gives channels that share a code (NHTSA's top and bottom engine
/// accelerometers are both `1-AC-ENGN-XG`) distinct ones: the code and
/// `#` and the channel's number in the test (the selector that picks it),
/// so that no two CSV columns have one name.
fn distinct_codes(signals: &mut [Channel], numbers: &[Option<usize>]) {
    let codes: Vec<String> = signals.iter().map(|s| s.code.clone()).collect();
    for (k, signal) in signals.iter_mut().enumerate() {
        if codes.iter().filter(|c| **c == codes[k]).count() > 1 {
            let number = numbers.get(k).copied().flatten().unwrap_or(k + 1);
            signal.code = format!("{}#{number}", codes[k]);
        }
    }
}
