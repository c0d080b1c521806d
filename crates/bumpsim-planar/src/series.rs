//! The planar series file (TOML) of `bumpsim synth`: a planar car, a
//! measurement chain and tests named as `bumpsim planar` names strikers;
//! and the planar study file that identifies the series it made.
//!
//! ```toml
//! planar_car = "car-truth.toml"    # the car that makes the series (planar car file)
//! start = "start.toml"             # optional: the study's start (default: planar_car), copied as start.toml
//! seed = 1                         # noise seed
//! [chain]                          # optional (synth::Chain's defaults)
//! step = 1e-4                      # s
//! pretrigger = 0.05                # s
//! duration = 0.15                  # s after contact
//! force_noise = 20.0               # N rms per load cell
//! acceleration_noise = 0.05        # g rms
//! biases = [0.03, -0.02]           # g, left and right accelerometers
//! sensor = [0.6, 0.7]              # m: sills at ξ ahead of the CG, ±η
//! yaw_rate = "0.2 deg/s"           # optional: a yaw-rate sensor with this rms noise
//! safety = 0.25                    # the generator's step, fraction of the critical step
//! [[test]]
//! name = "ANGLED"                  # folder and file name
//! angle = 10.0                     # degrees; or case = "rcar-structural-front", or
//! overlap = 100.0                  # percent   pole = 0.254 (m) with pole_offset = -0.3 (m)
//! side = "left"
//! speed = "8 km/h"                 # m/s or text with a unit
//! pendulum = 1100.0                # optional: a pendulum of this mass, kg
//! validate = true                  # optional: in the study, predicted but not fitted
//! ```

use crate::car::{PlanarCar, PlanarError};
use crate::drive::Sensor;
use crate::presets::{StrikerFieldError, StrikerFields, StrikerSpec};
use crate::synth::{Chain, Recorded, record};
use bumpsim_core::units::{Dimension, parse_quantity};
use serde::Deserialize;
use std::fmt::Write;
use std::path::{Path, PathBuf};

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SeriesFile {
    /// `kind = "planar"` (issue 46), read by `bumpsim_io::kind`.
    #[serde(default, rename = "kind")]
    _kind: Option<String>,
    planar_car: PathBuf,
    start: Option<PathBuf>,
    #[serde(default = "one")]
    seed: u64,
    /// `[chain]`: the 1-D series' keys plus `sensor` and `safety` (read in [`chain`]).
    #[serde(default)]
    chain: toml::Table,
    test: Vec<TestFile>,
}

fn one() -> u64 {
    1
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct TestFile {
    name: String,
    case: Option<String>,
    angle: Option<f64>,
    overlap: Option<f64>,
    side: Option<String>,
    pole: Option<f64>,
    pole_offset: Option<f64>,
    pendulum: Option<f64>,
    speed: Option<toml::Value>,
    #[serde(default)]
    validate: bool,
}

/// A made series: the tests, every input's text (provenance) and the study
/// file that identifies the series (its paths relative to the output folder).
#[derive(Debug, Clone)]
pub struct Series {
    /// The tests, in the file's order.
    pub tests: Vec<Recorded>,
    /// The inputs' texts, each after a `# <kind> file <path>` line.
    pub provenance: String,
    /// A planar study file for the tests (`study.toml` in the output
    /// folder), which starts from `start.toml` there.
    pub study: String,
    /// The text of the start's car file (`start.toml` in the output folder).
    pub start: String,
}

fn file_error(path: &Path, message: String) -> PlanarError {
    PlanarError::File {
        path: path.display().to_string(),
        message,
    }
}

/// What is wrong with a value of a planar series file (the file's error,
/// [`PlanarError::File`], adds the file).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SeriesError {
    /// A `[chain]` key of the planar series (`sensor`, `safety`).
    #[error("[chain] {key}: {source}")]
    ChainKey {
        /// The key.
        key: &'static str,
        /// The parser's message.
        source: toml::de::Error,
    },
    /// `[chain] yaw_rate`: the yaw-rate sensor's noise.
    #[error("[chain] yaw_rate: {0}")]
    YawRate(String),
    /// The `[chain]` keys the 1-D series reads.
    #[error("[chain]: {0}")]
    Chain(toml::de::Error),
    /// No `[[test]]`.
    #[error("no [[test]]: a series needs at least one test")]
    NoTest,
    /// The test names as a list (empty, repeated, invisible characters).
    #[error(transparent)]
    Names(#[from] bumpsim_core::names::NameError),
    /// More tests than [`bumpsim_io::output::MAX_TESTS`].
    #[error(transparent)]
    Tests(#[from] bumpsim_io::output::TooManyTests),
    /// A test name that cannot name a folder.
    #[error("test name {0}")]
    TestName(bumpsim_core::names::FolderNameError),
    /// A test's speed.
    #[error("test '{test}': {source}")]
    Speed {
        /// The test.
        test: String,
        /// What is wrong with it.
        source: bumpsim_io::speed::SpeedError,
    },
    /// A pole test with a plane's key (`overlap`, `angle`): the pole was
    /// made and the key silently did nothing.
    #[error(
        "test '{test}': `pole` and `{key}` together: a pole has no {key} (a plane's); give one of them (a pole's place is `pole_offset`)"
    )]
    PoleAndPlane {
        /// The test.
        test: String,
        /// The plane's key.
        key: &'static str,
    },
    /// A test's side.
    #[error("test '{test}': {source}")]
    Side {
        /// The test.
        test: String,
        /// What is wrong with it.
        source: crate::striker::SideError,
    },
}

/// Reads a planar series file and makes every test.
pub fn make_series(path: &Path) -> Result<Series, PlanarError> {
    let text =
        std::fs::read_to_string(path).map_err(|e| file_error(path, format!("cannot read: {e}")))?;
    let file: SeriesFile = toml::from_str(&text).map_err(|e| file_error(path, e.to_string()))?;
    let base = path.parent().unwrap_or(Path::new("."));
    let car_path = base.join(&file.planar_car);
    let car = PlanarCar::read(&car_path)?;
    let series_error = |e: SeriesError| file_error(path, e.to_string());
    let chain = chain(&file.chain, file.seed).map_err(series_error)?;
    names(&file.test).map_err(series_error)?;
    let mut provenance = format!("# series file {}\n{text}\n", path.display());
    let car_text = std::fs::read_to_string(&car_path).unwrap_or_default();
    let _ = write!(
        provenance,
        "# planar car file {}\n{car_text}\n",
        car_path.display()
    );
    let mut tests = Vec::new();
    for (index, test) in file.test.iter().enumerate() {
        let spec = striker_spec(test).map_err(series_error)?;
        let (striker, _) = spec.striker()?;
        let recorded = record(&car, &test.name, &striker, &chain, index as u64)
            .map_err(|e| file_error(path, format!("test '{}': {e}", test.name)))?;
        tests.push(recorded);
    }
    let start = match &file.start {
        Some(s) => {
            let start_path = base.join(s);
            PlanarCar::read(&start_path)?;
            std::fs::read_to_string(&start_path)
                .map_err(|e| file_error(&start_path, format!("cannot read: {e}")))?
        }
        None => car_text,
    };
    let setups = file
        .test
        .iter()
        .map(|t| TestSetup {
            validate: t.validate,
            striker: striker_fields(t),
        })
        .collect::<Vec<_>>();
    let friction = PlanarCar::parse(&start, Path::new("start.toml"))?
        .tyres()
        .front
        .mu_lateral
        > 0.0;
    let study = study_text(&tests, &setups, Path::new("start.toml"), friction);
    Ok(Series {
        tests,
        provenance,
        study,
        start,
    })
}

/// Removes `key` from `table` and reads it as a `T`.
fn take<T: serde::de::DeserializeOwned>(
    table: &mut toml::Table,
    key: &'static str,
) -> Result<Option<T>, SeriesError> {
    let value = table.remove(key);
    value
        .map(|v| v.try_into())
        .transpose()
        .map_err(|source| SeriesError::ChainKey { key, source })
}

/// `[chain]`: `sensor` and `safety` here, the rest as the 1-D series reads it.
fn chain(table: &toml::Table, seed: u64) -> Result<Chain, SeriesError> {
    let d = Chain::default();
    let mut rest = table.clone();
    let sensor: Option<[f64; 2]> = take(&mut rest, "sensor")?;
    let safety: Option<f64> = take(&mut rest, "safety")?;
    let yaw_rate: Option<toml::Value> = take(&mut rest, "yaw_rate")?;
    let yaw_rate = yaw_rate
        .map(|v| {
            let sigma = match &v {
                toml::Value::Float(x) => Some(*x),
                toml::Value::Integer(x) => Some(*x as f64),
                toml::Value::String(text) => parse_quantity(text, Dimension::AngularVelocity).ok(),
                _ => None,
            };
            sigma.filter(|s| s.is_finite() && *s >= 0.0).ok_or(v)
        })
        .transpose()
        .map_err(|v| SeriesError::YawRate(format!("{v}: expected the yaw-rate sensor's rms noise, ≥ 0, text with a unit (\"0.2 deg/s\") or rad/s")))?;
    let common: bumpsim_impact::synth::ChainFile = rest.try_into().map_err(SeriesError::Chain)?;
    Ok(Chain {
        measurement: common.resolve(&d.measurement, seed),
        sensor: sensor.unwrap_or(d.sensor),
        safety: safety.unwrap_or(d.safety),
        yaw_rate,
    })
}

/// Test names become folder and file names: plain names, each once.
fn names(tests: &[TestFile]) -> Result<(), SeriesError> {
    if tests.is_empty() {
        return Err(SeriesError::NoTest);
    }
    bumpsim_io::output::series_size("[[test]]", tests.len())?;
    let names = tests.iter().map(|t| t.name.as_str());
    bumpsim_core::names::check_names("[[test]]", names)?;
    for t in tests {
        bumpsim_core::names::check_folder_name(&t.name).map_err(SeriesError::TestName)?;
    }
    Ok(())
}

/// What the study says of a test besides its channels.
#[derive(Debug, Clone, PartialEq)]
pub struct TestSetup {
    /// Predicted, not fitted.
    pub validate: bool,
    /// The striker as the series gave it (for the forward prediction).
    pub striker: StrikerFields,
}

/// A `[[test]]`'s striker fields (every input file shares them, [`StrikerFields`]).
fn striker_fields(t: &TestFile) -> StrikerFields {
    StrikerFields {
        case: t.case.clone(),
        angle: t.angle,
        overlap: t.overlap,
        side: t.side.clone(),
        pole: t.pole,
        pole_offset: t.pole_offset,
        pendulum: t.pendulum,
        speed: t.speed.clone(),
    }
}

/// The striker of a `[[test]]`: its case or geometry, side and speed.
fn striker_spec(t: &TestFile) -> Result<StrikerSpec, SeriesError> {
    let test = t.name.clone();
    let plane = [("overlap", t.overlap), ("angle", t.angle)];
    if let (Some(_), Some((key, _))) = (t.pole, plane.iter().find(|(_, v)| v.is_some())) {
        return Err(SeriesError::PoleAndPlane { test, key });
    }
    striker_fields(t).spec().map_err(|e| match e {
        StrikerFieldError::Speed(source) => SeriesError::Speed { test, source },
        StrikerFieldError::Side(source) => SeriesError::Side { test, source },
    })
}

/// The planar study of the tests: one case each, every force channel with
/// its place, the accelerometers with theirs (see [`crate::study`]).
/// `friction`: estimate the lateral tyre friction (the start has some).
/// The cases carry their strikers (for the forward prediction) and the
/// model the test sheet's mass (the first test's car).
pub fn study_text(
    tests: &[Recorded],
    setups: &[TestSetup],
    start: &Path,
    friction: bool,
) -> String {
    let mut s = String::from(
        "# Identifies the planar car from the tests of this series (made by bumpsim synth).\n",
    );
    let _ = writeln!(
        s,
        "[model]\nplanar = {:?}    # the start: chain sizes, values, geometry\nstarts = 8\nseed = 1\nfriction = {friction}    # estimate the lateral tyre friction",
        start.display().to_string()
    );
    if let Some(test) = tests.first() {
        let _ = writeln!(
            s,
            "mass = {}    # kg, the test sheet's",
            number(test.car_mass)
        );
    }
    for (test, setup) in tests.iter().zip(setups) {
        let file = format!("{0}/{0}.mme", test.name);
        let _ = writeln!(
            s,
            "\n[[case]]\nname = {:?}\nspeed = {}    # m/s, the car at t = 0\ncfc = 180",
            test.name,
            number(test.car_speed)
        );
        if setup.validate {
            s += "validate = true    # predicted, not fitted\n";
        }
        let _ = writeln!(
            s,
            "striker = {}    # for the forward prediction",
            setup.striker.inline()
        );
        s += "forces = [\n";
        for load in &test.loads {
            let anchor = load.anchor.map_or(String::new(), |a| {
                format!(", anchor = [{}, {}]", number(a[0]), number(a[1]))
            });
            let (lateral, [dx, dy]) = (number(load.lateral), load.direction.map(number));
            let _ = writeln!(
                s,
                "  {{ path = {file:?}, channel = {:?}, lateral = {lateral}, direction = [{dx}, {dy}]{anchor} }},",
                load.channel
            );
        }
        s += "]\nsensors = [\n";
        let n = test.loads.len();
        for (channel, sensor) in test.channels[n..].iter().zip(&test.sensors) {
            let place = match sensor {
                Sensor::Body(p) | Sensor::Lateral(p) | Sensor::Film(p) => {
                    format!(", body = [{}, {}]", number(p[0]), number(p[1]))
                }
                Sensor::Chain(i) | Sensor::Crush(i) => format!(", chain = {i}"),
                Sensor::YawRate => String::new(),
            };
            let _ = writeln!(
                s,
                "  {{ path = {file:?}, channel = {:?}{place} }},",
                channel.code
            );
        }
        s += "]\n";
    }
    s
}

/// A TOML float rounded to 12 significant digits (0.72, not
/// 0.7200000000000001), without a negative zero.
fn number(v: f64) -> String {
    let rounded: f64 = format!("{v:.11e}").parse().unwrap_or(v);
    format!("{:?}", rounded + 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_short_and_never_negative_zero() {
        assert_eq!(number(-0.7200000000000001), "-0.72");
        assert_eq!(number(-0.0), "0.0");
        assert_eq!(number(2.177), "2.177");
        assert_eq!(number(1e-7), "1e-7");
    }

    #[test]
    fn a_pole_test_with_a_planes_key_is_refused_naming_the_test() {
        let test = |extra: &str| -> TestFile {
            toml::from_str(&format!("name = \"P\"\npole = 0.254\nspeed = 2.0\n{extra}")).unwrap()
        };
        for key in ["overlap", "angle"] {
            let e = striker_spec(&test(&format!("{key} = 40.0")))
                .unwrap_err()
                .to_string();
            assert!(
                e.starts_with(&format!("test 'P': `pole` and `{key}` together")),
                "{e}"
            );
        }
        assert!(striker_spec(&test("pole_offset = -0.3")).is_ok());
    }
}
