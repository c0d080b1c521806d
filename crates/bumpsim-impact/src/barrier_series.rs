//! Synthetic rigid-barrier test series of a car with nonlinear links
//! (issue 46 item 2: `synth` of a `kind = "links"` series): what a lab
//! would record if the car ran into a load-cell barrier at each given
//! speed, for examples and for testing the links identification against a
//! known car.
//!
//! Each test runs the car ([`bumpsim_core::chain`], [`Drive::Barrier`]:
//! every mass at the speed V, m1 at the wall, x forward) with histories
//! every `T/10` (T the sample interval) for the chain's duration. The
//! signals, in the car's frame (ISO vehicle frame, X forward; the signs of
//! docs/simulate.md and of the NHTSA barrier tests):
//! - the barrier's force on the car, `B0LOMASU0000FOXP` (the code of a
//!   load-cell wall's summed cells): negative while the wall pushes, as a
//!   load-cell barrier's summed Fx is recorded;
//! - on each output mass j a left and a right accelerometer along X,
//!   `a_j = dv_j/dt` (central differences of its velocity; negative while
//!   the car decelerates), with the chain's left and right biases: m1
//!   `10SIMELE/RI0000ACXP` (side members, as in the pendulum series), the
//!   last mass `10SECMLE/RI0000ACXP` (rear-seat crossmembers, as NHTSA's),
//!   a middle mass `10ENGN000001/2ACXP` (engine top and bottom);
//! - then the measurement chain of the pendulum series
//!   ([`crate::synth::measure`]: causal anti-alias filter, sampling,
//!   Gaussian noise seeded per test, bit for bit reproducible) after a
//!   pre-trigger in which the car moves at V (force and accelerations 0).
//!
//! Momentum: the chain conserves it exactly but for the wall, so the
//! force's impulse over a run equals the car's momentum change,
//! `∫ F dt = Σ m_i (v_i(t_end) − V)`.

use crate::impact::ImpactError;
use crate::synth::{
    Chain, ChainFile, SeriesError, Signal, SynthError, SynthTest, check_chain, check_test_names,
    measure, speed_value,
};
use bumpsim_core::chain::{Chain as LinkChain, Drive};
use bumpsim_core::units::format_number;
use bumpsim_io::link_car::LinkCar;
use std::path::{Path, PathBuf};

/// The barrier force channel's code and name.
pub const FORCE_CODE: (&str, &str) = ("B0LOMASU0000FOXP", "Load-cell barrier sum X");

/// Most values the fine histories of one test may hold (masses' x and v,
/// links' forces, energies; 8 bytes each): 5·10⁷, 400 MB.
pub const MAX_HISTORY_VALUES: f64 = 5e7;

/// A `kind = "links"` series file (TOML; paths relative to it).
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BarrierSeriesFile {
    /// The declared model kind, `"links"` (read by `bumpsim_io::kind`,
    /// which chose this reader).
    #[serde(default)]
    pub kind: Option<String>,
    /// The car file with nonlinear links.
    pub car: PathBuf,
    /// Noise seed.
    #[serde(default = "one")]
    pub seed: u64,
    /// Chain settings (SI, accelerometer figures in g), as the pendulum
    /// series' `[chain]`.
    #[serde(default)]
    pub chain: ChainFile,
    /// The masses (1-based) carrying the accelerometers: default the last.
    #[serde(default)]
    pub accelerometers: Option<Vec<i64>>,
    /// The tests.
    pub test: Vec<BarrierTestFile>,
}

fn one() -> u64 {
    1
}

/// `[[test]]` of a links series file.
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BarrierTestFile {
    /// Test name (also the ISO-MME folder name).
    pub name: String,
    /// Speed into the barrier: m/s, or text with a unit ("56 km/h").
    pub speed: toml::Value,
}

/// One accelerometer position: its mass (0-based) and its two channels
/// (code, name), left then right.
pub type Accelerometers = (usize, [(&'static str, &'static str); 2]);

/// A made links series: the tests and what a study of them needs.
#[derive(Debug, Clone)]
pub struct BarrierSeries {
    /// The tests, in the file's order: name, ISO-MME header, channels.
    pub tests: Vec<SynthTest>,
    /// Each test's speed, m/s.
    pub speeds: Vec<f64>,
    /// The car.
    pub car: LinkCar,
    /// The car file as the series names it (relative to the series file).
    pub car_file: PathBuf,
    /// The measurement chain.
    pub chain: Chain,
    /// The accelerometers, in the file's order.
    pub accelerometers: Vec<Accelerometers>,
    /// Every input's text, for provenance.
    pub provenance: String,
}

/// The accelerometers of mass `j` (0-based) of a car of `n` masses.
fn positions(j: usize, n: usize) -> [(&'static str, &'static str); 2] {
    match j {
        0 => [
            ("10SIMELE0000ACXP", "Side member left X"),
            ("10SIMERI0000ACXP", "Side member right X"),
        ],
        j if j + 1 == n => [
            ("10SECMLE0000ACXP", "Rear seat crossmember left X"),
            ("10SECMRI0000ACXP", "Rear seat crossmember right X"),
        ],
        _ => [
            ("10ENGN000001ACXP", "Engine top X"),
            ("10ENGN000002ACXP", "Engine bottom X"),
        ],
    }
}

/// The accelerometers the file asks for on a car of `n` masses: mass
/// numbers from 1 to n, none twice, at most one between the first and the
/// last (the engine's codes).
pub fn accelerometers(given: Option<&[i64]>, n: usize) -> Result<Vec<Accelerometers>, SeriesError> {
    let masses: Vec<i64> = given.map_or(vec![n as i64], <[i64]>::to_vec);
    let refuse = |reason: String| Err(SeriesError::Accelerometers { reason });
    if masses.is_empty() {
        return refuse("an empty list: give at least one mass number".into());
    }
    let mut out: Vec<Accelerometers> = Vec::new();
    for (i, &m) in masses.iter().enumerate() {
        if m < 1 || m > n as i64 {
            return refuse(format!("mass {m}: the car's masses are 1 to {n}"));
        }
        let j = (m - 1) as usize;
        if masses[..i].contains(&m) {
            return refuse(format!("mass {m} is given twice"));
        }
        let codes = positions(j, n);
        if out.iter().any(|(_, c)| c == &codes) {
            return refuse(format!(
                "mass {m}: only one mass between the first and the last carries accelerometers (the engine's codes 10ENGN000001/2ACXP)"
            ));
        }
        out.push((j, codes));
    }
    Ok(out)
}

/// The ISO-MME test header of a test: the title and the car (test object
/// 1, its speed V, m/s, and total mass, kg).
pub fn test_header(name: &str, speed: f64, car_mass: f64) -> Vec<(String, String)> {
    use bumpsim_io::test_data::iso_header::{TestObject, test_objects_header};
    let title = format!("{name}: synthetic rigid-barrier test (bumpsim synth)");
    let car = TestObject {
        name: "car".into(),
        speed: Some(speed),
        mass: Some(car_mass),
    };
    test_objects_header(&title, &[car])
}

/// The channels of one test: the barrier force and the accelerometers,
/// through the measurement chain (noise stream `index`).
pub fn record(
    car: &LinkChain,
    (name, speed): (&str, f64),
    accelerometers: &[Accelerometers],
    chain: &Chain,
    index: u64,
) -> Result<Vec<bumpsim_core::channel::Channel>, SynthError> {
    let fine = chain.step / 10.0;
    let length = ((chain.pretrigger + chain.duration) / fine).round() as usize;
    let pre = ((chain.pretrigger / fine).round() as usize).min(length);
    let drive = Drive::Barrier {
        speed,
        step: fine,
        samples: length - pre + 1,
    };
    let r = car.run(&drive).map_err(|source| SynthError::Barrier {
        test: name.into(),
        source,
    })?;
    let padded = |h: Vec<f64>| -> Vec<f64> {
        let mut out = vec![0.0; pre];
        out.extend(h.into_iter().take(length - pre));
        out
    };
    let mut signals = vec![Signal::from((
        FORCE_CODE.0,
        FORCE_CODE.1,
        padded(r.force.clone()),
        0.0,
    ))];
    for (j, codes) in accelerometers {
        let a = padded(derivative(&r.velocity[*j], fine));
        for ((code, name), bias) in codes.iter().zip(chain.biases) {
            signals.push(Signal::from((*code, *name, a.clone(), bias)));
        }
    }
    measure(signals, chain, index).map_err(|source: ImpactError| SynthError::Impact {
        head: name.into(),
        source,
    })
}

/// The fine histories of one test (samples after the pre-trigger times
/// the values per sample of a car of `n` masses) stay within
/// [`MAX_HISTORY_VALUES`].
fn check_history(chain: &Chain, n: usize) -> Result<(), SeriesError> {
    let samples = chain.duration / (chain.step / 10.0) + 2.0;
    let values = samples * (3 * n + 6) as f64;
    match values > MAX_HISTORY_VALUES {
        true => Err(SeriesError::History {
            values,
            max: MAX_HISTORY_VALUES,
        }),
        false => Ok(()),
    }
}

/// `dv/dt` of samples at interval `step`: central differences, one-sided
/// at the ends.
fn derivative(v: &[f64], step: f64) -> Vec<f64> {
    let n = v.len();
    (0..n)
        .map(|k| {
            let (a, b) = (k.saturating_sub(1), (k + 1).min(n - 1));
            match b > a {
                true => (v[b] - v[a]) / ((b - a) as f64 * step),
                false => 0.0,
            }
        })
        .collect()
}

/// Reads a `kind = "links"` series file and makes every test.
pub fn make_barrier_series(path: &Path) -> Result<BarrierSeries, SynthError> {
    let error = |p: &Path, message: String| SynthError::File {
        path: p.display().to_string(),
        message,
    };
    let text =
        std::fs::read_to_string(path).map_err(|e| error(path, format!("cannot read: {e}")))?;
    let file: BarrierSeriesFile =
        toml::from_str(&text).map_err(|e| error(path, bumpsim_io::toml_message(&text, &e)))?;
    let series = |source: SeriesError| SynthError::Series {
        path: path.display().to_string(),
        source,
    };
    let chain = file.chain.resolve(&Chain::default(), file.seed);
    check_chain(&chain).map_err(series)?;
    check_test_names("[[test]]", file.test.iter().map(|t| t.name.as_str())).map_err(series)?;
    let base = path.parent().unwrap_or(Path::new("."));
    let car_path = base.join(&file.car);
    let car_text = bumpsim_core::files::read_car_text(&car_path)
        .map_err(|e| SynthError::Car(bumpsim_io::car::CarError::from(e)))?;
    let car = LinkCar::parse(&car_text, &car_path)?;
    let n = car.chain.dof();
    let accelerometers = accelerometers(file.accelerometers.as_deref(), n).map_err(series)?;
    check_history(&chain, n).map_err(series)?;
    let speeds = file
        .test
        .iter()
        .map(|t| test_speed(t).map_err(series))
        .collect::<Result<Vec<f64>, _>>()?;
    let total: f64 = car.chain.masses().iter().sum();
    let mut tests = Vec::with_capacity(speeds.len());
    for (index, (t, &speed)) in file.test.iter().zip(&speeds).enumerate() {
        let test = (t.name.as_str(), speed);
        let channels = record(&car.chain, test, &accelerometers, &chain, index as u64)?;
        tests.push((t.name.clone(), test_header(&t.name, speed, total), channels));
    }
    let provenance = format!(
        "# series file {}\n{text}\n# car file {}\n{car_text}\n",
        path.display(),
        car_path.display()
    );
    Ok(BarrierSeries {
        tests,
        speeds,
        car,
        car_file: file.car,
        chain,
        accelerometers,
        provenance,
    })
}

/// A test's speed: finite and within [`crate::impact::SPEED_RANGE`] (the
/// car moves into the barrier).
fn test_speed(test: &BarrierTestFile) -> Result<f64, SeriesError> {
    let speed = speed_value(&test.speed).map_err(|source| SeriesError::TestSpeed {
        test: test.name.clone(),
        source,
    })?;
    match crate::impact::SPEED_RANGE.contains(&speed) {
        true => Ok(speed),
        false => Err(SeriesError::BarrierSpeed {
            test: test.name.clone(),
            speed,
        }),
    }
}

/// A TOML string (quoted and escaped).
fn quoted(text: &str) -> String {
    toml::Value::String(text.into()).to_string()
}

/// The study of a made series (paths relative to the output folder): a
/// chain study with `kind = "links"`, one `[[case]]` per test (the barrier
/// force, the first output mass's two accelerometers, the test's speed as
/// `initial_velocity`, x forward, CFC 60, the window from the contact to
/// the record's end). The links identification's `[links]` table is not
/// written: a comment says to add it.
pub fn study_text(series: &BarrierSeries, path: &Path) -> String {
    let n = series.car.chain.dof();
    let total: f64 = series.car.chain.masses().iter().sum();
    let (output, codes) = series
        .accelerometers
        .first()
        .copied()
        .unwrap_or((n - 1, [("10SECMLE0000ACXP", ""), ("10SECMRI0000ACXP", "")]));
    let mut text = format!(
        "# Written by `bumpsim synth {}`: one case per rigid-barrier test of the\n\
         # car {} (kind = \"links\"). The force is the barrier's on the car as\n\
         # recorded (negative: it decelerates the car), the output m{} read by its\n\
         # left and right X accelerometers (vehicle frame, negative while it\n\
         # decelerates), the initial velocity the test's speed: x forward.\n\
         # `bumpsim identify` runs it as it is, with the [links] table's\n\
         # defaults (docs/identify.md, \"Nonlinear links\"): add a [links]\n\
         # table to choose the front knots, a second path or a rebound link.\n\
         kind = \"links\"\n\n[model]\ndof = {n}\nmass = {}   # the car's total mass (the tests' \"Mass test object 1\")\nstarts = 16\nseed = 1\n",
        path.display().to_string().escape_debug(),
        series.car_file.display().to_string().escape_debug(),
        output + 1,
        quoted(&format!("{total} kg")),
    );
    for ((name, _, channels), &speed) in series.tests.iter().zip(&series.speeds) {
        // the record's last sample (one step before the duration's end: a
        // window reaching past the record is refused, docs/identify.md)
        let end = channels
            .first()
            .map_or(series.chain.duration, |c| c.series.end());
        let end = format_number(end, 6);
        let file = quoted(&format!("{name}/{name}.mme"));
        text += &format!(
            "\n[[case]]\nname = {}\nforce = {{ path = {file}, channel = {} }}\nacceleration = [\n  {{ path = {file}, channel = {} }},\n  {{ path = {file}, channel = {} }},\n]\ncfc = 60\ninitial_velocity = {speed:?}   # m/s, {} km/h\noutput_dof = {}\nwindow = [0.0, {end}]\n",
            quoted(name),
            quoted(FORCE_CODE.0),
            quoted(codes[0].0),
            quoted(codes[1].0),
            bumpsim_core::units::format_number(speed * 3.6, 4),
            output + 1,
        );
    }
    text
}

#[cfg(test)]
#[path = "barrier_series_tests.rs"]
mod tests;
