//! Synthetic pendulum test series: what a lab would record if a pendulum
//! hit this car through this bumper (spec §5), for examples and tests.
//!
//! For each head, the impact is simulated ([`impact`](crate::impact)) with
//! histories every `T/10` (T the sample interval). The measurement chain:
//! - the load cell measures the bumper force, plus Gaussian noise;
//! - left and right side-member accelerometers on m1 measure its
//!   acceleration (central differences of its velocity) in g, plus a bias
//!   each and Gaussian noise;
//! - every channel passes a causal 4th-order Butterworth anti-alias filter
//!   at a quarter of the sampling rate, then is sampled every T;
//! - a pre-trigger of zeros (plus noise and bias) precedes the impact.
//!
//! Noise comes from a ChaCha8 stream seeded per series (Box–Muller), so a
//! series is reproducible bit for bit.

use crate::bumper::Bumper;
use crate::impact::{ImpactError, Options, Scenario, simulate};
use bumpsim_core::channel::Channel;
use bumpsim_core::model::MsdModel;
use bumpsim_core::series::UniformSeries;
use bumpsim_core::units::{Dimension, STANDARD_GRAVITY};
use bumpsim_signal::filter::Butterworth;
use rand_chacha::ChaCha8Rng;
use rand_core::{Rng, SeedableRng};

/// One impactor head: its name, the bumper characteristic it meets, the
/// pendulum mass (kg) and speed (m/s).
#[derive(Debug, Clone, PartialEq)]
pub struct Head {
    /// Test name (also the ISO-MME folder name).
    pub name: String,
    /// The bumper as this head loads it.
    pub bumper: Bumper,
    /// Pendulum mass, kg.
    pub mass: f64,
    /// Impact speed, m/s.
    pub speed: f64,
}

/// The measurement chain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Chain {
    /// Sample interval, s.
    pub step: f64,
    /// Pre-trigger, s.
    pub pretrigger: f64,
    /// Recorded time after contact, s.
    pub duration: f64,
    /// Load-cell noise, N rms.
    pub force_noise: f64,
    /// Accelerometer noise, m/s² rms.
    pub acceleration_noise: f64,
    /// Accelerometer biases (left, right), m/s².
    pub biases: [f64; 2],
    /// Seed of the noise.
    pub seed: u64,
}

impl Default for Chain {
    fn default() -> Self {
        Chain {
            step: 1e-4,
            pretrigger: 0.01,
            duration: 0.16,
            force_noise: 150.0,
            acceleration_noise: 0.4 * STANDARD_GRAVITY,
            biases: [0.15 * STANDARD_GRAVITY, -0.10 * STANDARD_GRAVITY],
            seed: 1,
        }
    }
}

/// Gaussian noise by Box–Muller.
pub fn gaussian(rng: &mut ChaCha8Rng) -> f64 {
    let u = |rng: &mut ChaCha8Rng| ((rng.next_u64() >> 11) as f64 + 0.5) / (1u64 << 53) as f64;
    let (a, b) = (u(rng), u(rng));
    (-2.0 * a.ln()).sqrt() * (2.0 * std::f64::consts::PI * b).cos()
}

/// The three channels (load cell, left and right accelerometer) of one head.
/// `index` selects the noise stream (the head's position in the series).
pub fn record(
    car: &MsdModel,
    head: &Head,
    chain: &Chain,
    index: u64,
) -> Result<Vec<Channel>, ImpactError> {
    let fine = chain.step / 10.0;
    let options = Options {
        output_step: fine,
        duration: chain.duration.max(1.0),
        ..Options::default()
    };
    let impact = simulate(
        car,
        &head.bumper,
        Scenario::Impactor {
            mass: head.mass,
            speed: head.speed,
        },
        &options,
    )?;
    let length = ((chain.pretrigger + chain.duration) / fine).round() as usize;
    let pre = (chain.pretrigger / fine).round() as usize;
    let at = |h: &[f64], k: usize| {
        if k < pre {
            0.0
        } else {
            h.get(k - pre).or(h.last()).copied().unwrap_or(0.0)
        }
    };
    let force: Vec<f64> = (0..length).map(|k| at(&impact.force, k)).collect();
    let v1 = &impact.velocities[1];
    let accel: Vec<f64> = (0..length)
        .map(|k| {
            (at(v1, k + 1) - at(v1, k.saturating_sub(1))) / (fine * if k == 0 { 1.0 } else { 2.0 })
        })
        .collect();
    let signals = [
        ("P0IMPA000000FOXP", "Pendulum load cell X", force, 0.0),
        (
            "10SIMELE0000ACXP",
            "Side member left X",
            accel.clone(),
            chain.biases[0],
        ),
        (
            "10SIMERI0000ACXP",
            "Side member right X",
            accel,
            chain.biases[1],
        ),
    ];
    let mut channels = measure(signals.map(Signal::from), chain, index)?;
    // the pendulum is test object 2 (see `test_header`)
    channels[0].set_meta("Test object number", "2");
    Ok(channels)
}

/// A true signal before the measurement chain: its ISO code, name, the
/// values on the fine grid (interval `T/10`) and the sensor's bias (SI);
/// its noise is the chain's for its dimension (force or acceleration).
#[derive(Debug, Clone, PartialEq)]
pub struct Signal {
    /// ISO code.
    pub code: &'static str,
    /// Channel name.
    pub name: &'static str,
    /// Physical dimension (force or acceleration).
    pub dimension: Dimension,
    /// The true values on the fine grid, SI.
    pub values: Vec<f64>,
    /// The sensor's constant bias, SI.
    pub bias: f64,
}

impl From<(&'static str, &'static str, Vec<f64>, f64)> for Signal {
    /// A force channel when the code's dimension letters are `FO`, else an
    /// acceleration.
    fn from((code, name, values, bias): (&'static str, &'static str, Vec<f64>, f64)) -> Self {
        let dimension = match code.get(12..14) {
            Some("FO") => Dimension::Force,
            _ => Dimension::Acceleration,
        };
        Signal {
            code,
            name,
            dimension,
            values,
            bias,
        }
    }
}

/// The measurement chain on true signals (one test, noise stream `index`):
/// each passes the causal anti-alias filter, is sampled every `T`, gets
/// its bias and Gaussian noise (drawn signal by signal, in order) and
/// becomes a channel starting at `−pretrigger` whose `Comments` rate it
/// against its noise-free samples ([`truth_comment`]); forces are written
/// in kN, accelerations in g.
pub fn measure(
    signals: impl IntoIterator<Item = Signal>,
    chain: &Chain,
    index: u64,
) -> Result<Vec<Channel>, ImpactError> {
    let fine = chain.step / 10.0;
    let mut rng = ChaCha8Rng::seed_from_u64(chain.seed.wrapping_mul(1000).wrapping_add(index));
    let anti_alias =
        Butterworth::new(4, 0.25 / chain.step, fine).map_err(|_| ImpactError::Parameter {
            name: "sample interval (s)",
            value: chain.step,
            expected: "positive and finite",
        })?;
    let signals: Vec<Signal> = signals.into_iter().collect();
    let mut noisy = Vec::with_capacity(signals.len());
    for s in &signals {
        let sigma = match s.dimension {
            Dimension::Force => chain.force_noise,
            _ => chain.acceleration_noise,
        };
        let sampled = anti_alias.causal(&s.values).into_iter().step_by(10);
        let values: Vec<f64> = sampled
            .map(|v| v + s.bias + sigma * gaussian(&mut rng))
            .collect();
        noisy.push(values);
    }
    let mut channels = Vec::with_capacity(signals.len());
    for (s, values) in signals.iter().zip(noisy) {
        let truth: Vec<f64> = s.values.iter().step_by(10).copied().collect();
        let comment = truth_comment(&truth, &values, chain.step);
        let series = UniformSeries::new(-chain.pretrigger, chain.step, values).map_err(|_| {
            ImpactError::NoSeparation {
                duration: chain.duration,
            }
        })?;
        let mut c = Channel::new(s.code, s.name, s.dimension, series);
        c.set_meta("Comments", &comment);
        c.source_unit = match s.dimension {
            Dimension::Force => "kN".into(),
            _ => "g".into(),
        };
        channels.push(c);
    }
    Ok(channels)
}

/// The `Comments` of a synthetic channel: its ISO/TS 18571 rating against
/// the noise-free signal it records (`truth`, at the same samples), i.e. how
/// much the measurement chain (anti-alias filter, noise, bias) costs.
pub fn truth_comment(truth: &[f64], recorded: &[f64], step: f64) -> String {
    match bumpsim_signal::rating::rate(truth, recorded, step) {
        Ok(r) => format!(
            "synthetic (bumpsim synth): ISO/TS 18571 rating against the noise-free signal {:.3} (corridor {:.3}, phase {:.3}, magnitude {:.3}, slope {:.3})",
            r.overall, r.corridor, r.phase, r.magnitude, r.slope
        ),
        Err(e) => format!(
            "synthetic (bumpsim synth): no ISO/TS 18571 rating against the noise-free signal ({e})"
        ),
    }
}

/// A series file (TOML): the car, the noise seed, optional chain settings
/// and the heads. Paths relative to the file.
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SeriesFile {
    /// The declared model kind (`kind = "chain"`; issue 46), read by
    /// `bumpsim_io::kind`, which chose this reader.
    #[serde(default)]
    pub kind: Option<String>,
    /// Car file (TOML or model JSON).
    pub car: std::path::PathBuf,
    /// Noise seed.
    #[serde(default = "one")]
    pub seed: u64,
    /// Chain settings (SI, accelerometer figures in g).
    #[serde(default)]
    pub chain: ChainFile,
    /// The heads.
    pub head: Vec<HeadFile>,
}

fn one() -> u64 {
    1
}

/// `[chain]` of a series file.
#[derive(Debug, Clone, Default, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ChainFile {
    /// Sample interval, s.
    pub step: Option<f64>,
    /// Pre-trigger, s.
    pub pretrigger: Option<f64>,
    /// Recorded time after contact, s.
    pub duration: Option<f64>,
    /// Load-cell noise, N rms.
    pub force_noise: Option<f64>,
    /// Accelerometer noise, g rms.
    pub acceleration_noise: Option<f64>,
    /// Accelerometer biases (left, right), g: exactly two numbers.
    #[serde(default, deserialize_with = "bumpsim_io::numbers::optional")]
    pub biases: Option<[f64; 2]>,
}

impl ChainFile {
    /// The chain these settings give over `defaults`, with the noise `seed`
    /// (accelerometer figures from g to m/s²).
    pub fn resolve(&self, defaults: &Chain, seed: u64) -> Chain {
        let (g, d) = (STANDARD_GRAVITY, defaults);
        Chain {
            step: self.step.unwrap_or(d.step),
            pretrigger: self.pretrigger.unwrap_or(d.pretrigger),
            duration: self.duration.unwrap_or(d.duration),
            force_noise: self.force_noise.unwrap_or(d.force_noise),
            acceleration_noise: self
                .acceleration_noise
                .map_or(d.acceleration_noise, |a| a * g),
            biases: self.biases.map_or(d.biases, |[l, r]| [l * g, r * g]),
            seed,
        }
    }
}

/// A speed in a series file: m/s, or text with a unit ("6 km/h"); the one
/// rule of speeds in input files, [`bumpsim_io::speed::speed_value`].
pub use bumpsim_io::speed::{SpeedError, speed_value};

/// `[[head]]` of a series file.
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HeadFile {
    /// Test name.
    pub name: String,
    /// Bumper file as this head loads it.
    pub bumper: std::path::PathBuf,
    /// Pendulum mass, kg.
    pub mass: f64,
    /// Speed: m/s, or text with a unit ("6 km/h").
    pub speed: toml::Value,
}

/// Why a series cannot be made.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SynthError {
    /// A file or value.
    #[error("{path}: {message}")]
    File {
        /// The file.
        path: String,
        /// What is wrong.
        message: String,
    },
    /// A value of the series file.
    #[error("{path}: {source}")]
    Series {
        /// The series file.
        path: String,
        /// What is wrong.
        source: SeriesError,
    },
    /// The car file (its message names the file).
    #[error(transparent)]
    Car(#[from] bumpsim_io::car::CarError),
    /// A links car's run into the barrier (a `kind = "links"` series,
    /// [`crate::barrier_series`]).
    #[error("test '{test}': {source}")]
    Barrier {
        /// The test.
        test: String,
        /// The cause.
        source: bumpsim_core::chain::ChainError,
    },
    /// The impact.
    #[error("head '{head}': {source}")]
    Impact {
        /// The head.
        head: String,
        /// The cause.
        source: ImpactError,
    },
}

/// What is wrong with a value of a series file (the error adds the file).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SeriesError {
    /// A `[chain]` time that is not finite and positive (the pre-trigger
    /// may be zero; the duration is at least one step).
    #[error(
        "[chain] {name} = {value:?} s: expected a finite positive time (a duration of at least one step)"
    )]
    Time {
        /// `step`, `pretrigger` or `duration`.
        name: &'static str,
        /// The time given, s.
        value: f64,
    },
    /// More samples per channel than [`bumpsim_io::output::MAX_SAMPLES`]
    /// allows for the fine grid.
    #[error(
        "[chain] {samples:.3e} samples per channel (pretrigger + duration over step): at most {max} (limit MAX_SAMPLES); shorten duration or lengthen step"
    )]
    Samples {
        /// Samples per channel.
        samples: f64,
        /// The most allowed.
        max: usize,
    },
    /// A noise level that is negative or not finite, or a noise or bias
    /// beyond [`MAX_NOISE`].
    #[error("[chain] {name} = {value:?} {unit}: expected {expected}")]
    Noise {
        /// `force_noise`, `acceleration_noise` or `biases`.
        name: &'static str,
        /// The value given, in the file's unit.
        value: f64,
        /// The file's unit.
        unit: &'static str,
        /// What is allowed.
        expected: &'static str,
    },
    /// The head names as a list (empty, repeated, invisible characters).
    #[error(transparent)]
    Names(#[from] bumpsim_core::names::NameError),
    /// More tests than [`bumpsim_io::output::MAX_TESTS`].
    #[error(transparent)]
    Tests(#[from] bumpsim_io::output::TooManyTests),
    /// A head name that cannot name a folder.
    #[error("head name {0}")]
    HeadName(bumpsim_core::names::FolderNameError),
    /// A test name (of a links series) that cannot name a folder.
    #[error("test name {0}")]
    TestName(bumpsim_core::names::FolderNameError),
    /// A links series test's speed that is no speed.
    #[error("test '{test}': {source}")]
    TestSpeed {
        /// The test.
        test: String,
        /// What is wrong with it.
        source: bumpsim_io::speed::SpeedError,
    },
    /// A links series test's speed outside
    /// [`crate::impact::SPEED_RANGE`] (the car moves into the barrier).
    #[error(
        "test '{test}': speed {speed:?} m/s: the car must move into the barrier at a positive speed of 0.001 to 1000 m/s (SPEED_RANGE)"
    )]
    BarrierSpeed {
        /// The test.
        test: String,
        /// The speed given, m/s.
        speed: f64,
    },
    /// A links series' `accelerometers` list.
    #[error("accelerometers: {reason}")]
    Accelerometers {
        /// What is wrong.
        reason: String,
    },
    /// A links series whose fine histories of one test would hold more
    /// than [`crate::barrier_series::MAX_HISTORY_VALUES`] values.
    #[error(
        "[chain] {values:.3e} history values per test (duration over step/10, times 3 per mass + 6): at most {max:.0e} (limit MAX_HISTORY_VALUES); shorten duration, lengthen step or use fewer masses"
    )]
    History {
        /// Values per test.
        values: f64,
        /// The most allowed.
        max: f64,
    },
    /// A head's speed.
    #[error("head '{head}': {source}")]
    Speed {
        /// The head.
        head: String,
        /// What is wrong with it.
        source: bumpsim_io::speed::SpeedError,
    },
}

/// The largest noise level or bias of a chain, in SI (N or m/s²): larger
/// ones are no measurement and their samples overflow.
pub const MAX_NOISE: f64 = 1e12;

/// The chain's noise levels are finite, non-negative and at most
/// [`MAX_NOISE`]; its biases finite and at most [`MAX_NOISE`] in size.
pub fn check_noise(chain: &Chain) -> Result<(), SeriesError> {
    let g = STANDARD_GRAVITY;
    let levels = [
        ("force_noise", chain.force_noise, 1.0, "N"),
        ("acceleration_noise", chain.acceleration_noise, g, "g"),
    ];
    for (name, value, scale, unit) in levels {
        if !(value.is_finite() && (0.0..=MAX_NOISE).contains(&value)) {
            let expected = "a noise level (rms) from 0 to 1e12 in SI (limit MAX_NOISE)";
            let value = value / scale;
            return Err(SeriesError::Noise {
                name,
                value,
                unit,
                expected,
            });
        }
    }
    match chain
        .biases
        .iter()
        .find(|b| !b.is_finite() || b.abs() > MAX_NOISE)
    {
        Some(&bias) => Err(SeriesError::Noise {
            name: "biases",
            value: bias / g,
            unit: "g",
            expected: "two finite biases (left, right) of at most 1e12 m/s² in size (limit MAX_NOISE)",
        }),
        None => Ok(()),
    }
}

/// The chain's times are finite and positive, and the fine simulation grid
/// (10 points per sample) stays within [`bumpsim_io::output::MAX_SAMPLES`].
pub fn check_chain(chain: &Chain) -> Result<(), SeriesError> {
    check_noise(chain)?;
    for (name, value) in [
        ("step", chain.step),
        ("pretrigger", chain.pretrigger),
        ("duration", chain.duration),
    ] {
        if !(value.is_finite() && value >= 0.0) || (name != "pretrigger" && value == 0.0) {
            return Err(SeriesError::Time { name, value });
        }
    }
    // a duration shorter than a sample (1e-308 s) made a test of one sample
    if chain.duration < chain.step {
        return Err(SeriesError::Time {
            name: "duration",
            value: chain.duration,
        });
    }
    let max = bumpsim_io::output::MAX_SAMPLES / 10;
    let samples = (chain.pretrigger + chain.duration.max(1.0)) / chain.step;
    match samples > max as f64 {
        true => Err(SeriesError::Samples { samples, max }),
        false => Ok(()),
    }
}

/// Head names become folder and file names: printable, distinct names
/// ([`bumpsim_core::names::check_names`]), plain (no path separator, not
/// `.` or `..`) and without surrounding spaces.
fn check_names(heads: &[HeadFile]) -> Result<(), SeriesError> {
    check_test_names("[[head]]", heads.iter().map(|h| h.name.as_str()))
}

/// Test names (of the `table`, `[[head]]` or `[[test]]`) become folder and
/// file names: printable, distinct names ([`bumpsim_core::names::check_names`]),
/// plain (no path separator, not `.` or `..`) and without surrounding spaces;
/// at most [`bumpsim_io::output::MAX_TESTS`] of them.
pub fn check_test_names<'a>(
    table: &'static str,
    names: impl Iterator<Item = &'a str> + Clone,
) -> Result<(), SeriesError> {
    bumpsim_io::output::series_size(table, names.clone().count())?;
    bumpsim_core::names::check_names(table, names.clone())?;
    let error = match table {
        "[[head]]" => SeriesError::HeadName,
        _ => SeriesError::TestName,
    };
    for name in names {
        bumpsim_core::names::check_folder_name(name).map_err(error)?;
    }
    Ok(())
}

/// The ISO-MME test header of a head: the title and two test objects, as
/// the channel codes number them: the car at rest (test object 1, the `1…`
/// side-member accelerometers; its total mass, kg) and the pendulum (test
/// object 2, the `P…` load cell; its speed, m/s, and mass, kg).
pub fn test_header(head: &Head, car_mass: f64) -> Vec<(String, String)> {
    use bumpsim_io::test_data::iso_header::{TestObject, test_objects_header};
    let title = format!("{}: synthetic pendulum test (bumpsim synth)", head.name);
    let objects = [
        TestObject {
            name: "car".into(),
            speed: Some(0.0),
            mass: Some(car_mass),
        },
        TestObject {
            name: "pendulum".into(),
            speed: Some(head.speed),
            mass: Some(head.mass),
        },
    ];
    test_objects_header(&title, &objects)
}

/// One synthetic test: name, ISO-MME test header ([`test_header`]), channels.
pub type SynthTest = (String, Vec<(String, String)>, Vec<Channel>);

/// Reads a series file and makes every head's channels; returns the heads'
/// tests, and the text of every input (for provenance).
pub fn make_series(path: &std::path::Path) -> Result<(Vec<SynthTest>, String), SynthError> {
    let error = |p: &std::path::Path, message: String| SynthError::File {
        path: p.display().to_string(),
        message,
    };
    let text =
        std::fs::read_to_string(path).map_err(|e| error(path, format!("cannot read: {e}")))?;
    let file: SeriesFile =
        toml::from_str(&text).map_err(|e| error(path, bumpsim_io::toml_message(&text, &e)))?;
    let base = path.parent().unwrap_or(std::path::Path::new("."));
    let car_path = base.join(&file.car);
    let car = bumpsim_io::car::Car::read_model_file(&car_path)?;
    let series = |source: SeriesError| SynthError::Series {
        path: path.display().to_string(),
        source,
    };
    let chain = file.chain.resolve(&Chain::default(), file.seed);
    check_chain(&chain).map_err(series)?;
    check_names(&file.head).map_err(series)?;
    let mut provenance = format!("# series file {}\n{text}\n", path.display());
    provenance += &format!(
        "# car file {}\n{}\n",
        car_path.display(),
        std::fs::read_to_string(&car_path).unwrap_or_default()
    );
    let mut out = Vec::new();
    for (index, h) in file.head.iter().enumerate() {
        let bumper_path = base.join(&h.bumper);
        let bumper = Bumper::read(&bumper_path).map_err(|e| error(&bumper_path, e.to_string()))?;
        provenance += &format!(
            "# bumper file {}\n{}\n",
            bumper_path.display(),
            std::fs::read_to_string(&bumper_path).unwrap_or_default()
        );
        let speed = speed_value(&h.speed).map_err(|source| {
            series(SeriesError::Speed {
                head: h.name.clone(),
                source,
            })
        })?;
        let head = Head {
            name: h.name.clone(),
            bumper,
            mass: h.mass,
            speed,
        };
        let channels = record(&car.model, &head, &chain, index as u64).map_err(|source| {
            SynthError::Impact {
                head: h.name.clone(),
                source,
            }
        })?;
        out.push((
            h.name.clone(),
            test_header(&head, car.model.total_mass()),
            channels,
        ));
    }
    Ok((out, provenance))
}
