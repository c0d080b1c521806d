//! The planar study file: the 1-D study of `bumpsim identify` (one
//! `[model]`, several `[[case]]`s of channels in test files) extended to the
//! planar car. `[model] planar = "start.toml"` makes a study planar.
//!
//! ```toml
//! [model]
//! planar = "start.toml"     # planar car file: the start (chain sizes and values), geometry, tyres
//! starts = 8                # optional (8): the start, then random points within `spread`
//! seed = 1                  # optional (1)
//! spread = 10.0             # optional (10): random starts within this factor of the start
//! friction = false          # optional: estimate the lateral tyre friction μ_y of both axles
//! cornering = true          # optional: estimate the tyres' cornering stiffness C_α
//! relaxation = true         # optional: estimate the rolling tyres' relaxation length σ
//!                           # (searched from 0.01 m, the instantaneous law, to 2 m);
//!                           # both default to true when a training case carries a yaw-rate
//!                           # sensor and the start's tyres roll with a relaxation length,
//!                           # else false (`tyres_law_estimated`)
//! mass = "1265 kg"          # optional: the test sheet's mass, checked against the identified car
//!                           # and a prior on its total mass
//! links = "linear"          # optional: the side members' law to identify: "linear", "progressive",
//!                           # "yielding" (every link), a list link by link, or { left = ..., right = ... }
//!                           # (default: the start car's links)
//! bumper = "start"          # optional: "fit" fits the bumper's curve, unloading and contact rate
//!                           # to the training tests' forward runs (their strikers) after the car
//! joint = 2.0               # optional, with bumper = "fit": polish the car and the bumper's law
//!                           # together on the replays and the forward runs, these weighing β
//!                           # (> 0, at most 100) against the replays (identify module `joint`)
//! effective_width = true   # optional: estimate the bumper's effective width, a property of
//!                           # the car (its segments' contact points' span) with a stated
//!                           # prior, written into the identified car (identify module
//!                           # `unknowns`); default: true when a training case has a wall's
//!                           # load cells (`width_estimated`), else false
//! cells = true              # optional, with bumper = "fit": compare the forward runs of a wall
//!                           # with load cells cell by cell (module `cell_force`), not by their
//!                           # total force; default: true with bumper = "fit" and a training
//!                           # case with a wall's load cells (`width_estimated`), else false
//! confirm = false           # optional (false): true runs the full search again from its
//!                           # polished best, the priors weighed at the noise there, until
//!                           # the starts ran within a factor 2 of the final noise, so that
//!                           # they search the final objective itself (two or three times the
//!                           # search's time; identify module `staged`)
//!
//! [identification]          # optional
//! objective = "displacement" # where the accelerometers are compared: "displacement" (default,
//!                           # the thesis's, [`DOMAIN`]), "velocity" or "acceleration" (as
//!                           # measured: better on issue 44's series); a yaw-rate sensor
//!                           # and displacement channels as measured (`identify` module `objective`)
//! bias = "pretrigger"       # the accelerometers' biases: removed as the pre-trigger's mean
//!                           # (default) or "nuisance": also estimated per case, with the
//!                           # pre-trigger mean's uncertainty as their prior
//! arm = false               # optional (false): true estimates each case's wall cells' arm,
//!                           # a nuisance with a stated prior (`case 'NAME' cells.arm` in
//!                           # [priors]; identify module `unknowns`); false: the segments' rule
//!
//! [priors]                  # optional: override ({ value, spread }), remove ("none") or add priors
//! body.yaw_inertia = { value = 2300.0, spread = 0.2 }   # kg·m² (SI); spread: sd of ln θ (0.2 ≈ ±20 %)
//! tyres.mu_lateral = "none"
//!
//! [[case]]
//! name = "angled"
//! speed = "8 km/h"          # the car at time zero: m/s or text with a unit (0: a pendulum test)
//! cfc = 180                 # optional CFC class of every channel
//! validate = false          # optional: predicted and reported, not fitted
//! time_zero = "onset"       # optional: where the replay starts ("onset", or s of the files' time)
//! striker = { angle = 10.0, speed = "8 km/h" }  # optional: the test's striker, for the forward prediction
//! forces = [                # force channels, N after the file's units
//!   # lateral: m on the bumper line (left +), or "estimate" (one total force whose line of
//!   # action is a parameter); direction: of the force on the car, world; anchor: a world
//!   # point on its line of action, body frame at the files' t = 0, m (a force with an
//!   # anchor needs no lateral); cell (with an anchor): a wall load cell this wide (m)
//!   # centred on the anchor
//!   { path = "ANGLED/ANGLED.mme", channel = "B0LOMA010100FOXP", lateral = -0.72, direction = [-0.985, -0.174] },
//! ]
//! sensors = [               # the first two: x accelerometers on the body, left then right
//!   { path = "ANGLED/ANGLED.mme", channel = "10SILBLE0000ACXP", body = [0.6, 0.7] },
//!   { path = "ANGLED/ANGLED.mme", channel = "10SILBRI0000ACXP", body = [0.6, -0.7] },
//!   { path = "ANGLED/ANGLED.mme", channel = "10SIMELE0000ACXP", chain = 0 },  # chain mass 0 (left front)
//!   { path = "ANGLED/ANGLED.mme", channel = "10VEHC0000CGAVZP" },             # yaw rate: no place
//! ]
//! ```
//!
//! A sensor's kind comes from its channel: the ISO/TS 13499 code's
//! physical dimension and direction (`AC` `X` at `body` or `chain`: an x
//! accelerometer; `AC` `Y` at `body`: a lateral one; `AV` `Z`: the yaw
//! rate; `DS` `X` at `body`: film, at `chain`: a string pot's crush), or,
//! for a channel without an ISO code (a CSV column), its unit's dimension
//! and `axis = "x" | "y" | "z"` (default x, z for an angular velocity). An
//! optional `noise` (its rms noise, text with a unit such as "0.2 deg/s")
//! replaces the one estimated from the pre-trigger ([`crate::cases`]).
//!
//! Channels are read and conditioned as in the 1-D study (pre-trigger bias,
//! CFC), shifted to the case's time zero and decimated ([`crate::cases`]).

use crate::car::{PlanarCar, PlanarError};
use crate::cases::{Placed, TestChannels, TimeZero};
use crate::identify::{Bias, LinkLaws, PlanarCase, Setup};
use crate::presets::StrikerFields;
use bumpsim_core::channel::Channel;
use bumpsim_core::names::check_names;
use bumpsim_core::units::{Dimension, parse_quantity};
use bumpsim_estimate::domain::{Domain, UnknownDomain};
use bumpsim_io::mass::{EXPECTED, quoted, sheet_mass};
use bumpsim_io::speed::{SpeedError, speed_value};
use bumpsim_signal::loader::{ChannelSource, LoadError, Loader};
use bumpsim_signal::process::Resampling;
use serde::Deserialize;
use std::path::{Path, PathBuf};

/// Where a study that does not say compares its accelerometers: in
/// displacement, the thesis's objective and the figures of every planar
/// test. As measured (`objective = "acceleration"`) is the better choice on
/// issue 44's yaw-rate series and three varied cars (docs/planar.md, "The
/// objective's domain": every threshold holds on all four, the forward
/// offset force 94.2 / 94.0 / 96.8 / 90.3 % against 92.0 / 69.7 / 94.9 /
/// 79.2 %), but as the default it fails
/// `independent::an_independent_asymmetric_series_predicts_its_held_out_tests`
/// (not yet re-measured), and those figures were taken with the yaw-rate
/// sensor nearly unweighted in acceleration; weighted (fixed since), the
/// forward force is 89.5 / 83.7 / 91.4 / 87.0 %: no domain holds on all
/// four yet.
pub const DOMAIN: Domain = Domain::Displacement;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct StudyFile {
    /// `kind = "planar"` (issue 46), read by `bumpsim_io::kind`.
    #[serde(default, rename = "kind")]
    _kind: Option<String>,
    model: ModelFile,
    case: Vec<CaseFile>,
    priors: Option<toml::Table>,
    identification: Option<IdentificationFile>,
}

/// The `[identification]` table, as the 1-D study's.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct IdentificationFile {
    /// Where the accelerometers are compared: `"displacement"` (the
    /// thesis's), `"velocity"` or `"acceleration"`.
    objective: Option<String>,
    /// The accelerometers' biases: `"pretrigger"` (removed as its mean)
    /// or `"nuisance"` (also estimated, with the pre-trigger's prior).
    bias: Option<String>,
    /// Estimate each case's wall cells' arm (default false).
    arm: Option<bool>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ModelFile {
    planar: PathBuf,
    starts: Option<usize>,
    seed: Option<u64>,
    spread: Option<f64>,
    #[serde(default)]
    friction: bool,
    cornering: Option<bool>,
    relaxation: Option<bool>,
    mass: Option<toml::Value>,
    links: Option<toml::Value>,
    bumper: Option<String>,
    joint: Option<f64>,
    effective_width: Option<bool>,
    cells: Option<bool>,
    #[serde(default)]
    confirm: bool,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct CaseFile {
    name: String,
    speed: Option<toml::Value>,
    cfc: Option<f64>,
    #[serde(default)]
    validate: bool,
    striker: Option<StrikerFields>,
    time_zero: Option<toml::Value>,
    forces: Vec<ForceRef>,
    sensors: Vec<SensorRef>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ForceRef {
    path: PathBuf,
    channel: String,
    lateral: Option<Lateral>,
    direction: Vec<f64>,
    #[serde(default, deserialize_with = "bumpsim_io::numbers::optional")]
    anchor: Option<[f64; 2]>,
    cell: Option<f64>,
}

/// A force's lateral position: m, or `"estimate"` (a parameter of the
/// identification: a single total force whose line of action no cell measured).
#[derive(Debug, Deserialize)]
#[serde(untagged)]
enum Lateral {
    At(f64),
    Word(String),
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SensorRef {
    path: PathBuf,
    channel: String,
    #[serde(default, deserialize_with = "bumpsim_io::numbers::optional")]
    body: Option<[f64; 2]>,
    chain: Option<usize>,
    axis: Option<String>,
    noise: Option<toml::Value>,
}

/// A force's direction as a study gives it: exactly two finite components,
/// not both zero (normalised where the force is applied).
fn direction(components: &[f64]) -> Option<[f64; 2]> {
    let &[dx, dy] = components else { return None };
    let norm = dx.hypot(dy);
    (norm.is_finite() && norm > 0.0).then_some([dx, dy])
}

/// A read planar study: the setup, the fitted cases and the validation cases.
#[derive(Debug, Clone)]
pub struct PlanarStudy {
    /// The study file.
    pub path: PathBuf,
    /// Start and search settings.
    pub setup: Setup,
    /// Cases fitted.
    pub cases: Vec<PlanarCase>,
    /// Cases predicted, not fitted (`validate = true`).
    pub validation: Vec<PlanarCase>,
    /// What the user should know of the loading, a line each (`case
    /// 'POLE': ... put on one time base ...`).
    pub notes: Vec<String>,
}

impl PlanarStudy {
    /// Reads the study, its start car and every case's channels.
    pub fn read(path: &Path) -> Result<PlanarStudy, PlanarError> {
        let error = |message: String| PlanarError::File {
            path: path.display().to_string(),
            message,
        };
        let text = std::fs::read_to_string(path).map_err(|e| error(format!("cannot read: {e}")))?;
        let file: StudyFile = toml::from_str(&text).map_err(|e| error(e.to_string()))?;
        if file.case.is_empty() {
            return Err(error(
                "no [[case]]: a study needs at least one load case".into(),
            ));
        }
        check_names("[[case]]", file.case.iter().map(|c| c.name.as_str()))
            .map_err(|e| error(e.to_string()))?;
        let base = path.parent().unwrap_or(Path::new("."));
        let mut template = PlanarCar::read(&base.join(&file.model.planar))?;
        if let Some(laws) = &file.model.links {
            template = LinkLaws::read(laws, &template)
                .and_then(|l| l.apply(&template))
                .map_err(|e| error(e.to_string()))?;
        }
        let defaults = Setup::new(template);
        let mass = file
            .model
            .mass
            .as_ref()
            .map(|m| {
                sheet_mass(m)
                    .ok_or_else(|| error(format!("[model] mass = {}: {EXPECTED}", quoted(m))))
            })
            .transpose()?;
        let identification = file.identification.as_ref();
        let mut setup = Setup {
            starts: file.model.starts.unwrap_or(defaults.starts),
            seed: file.model.seed.unwrap_or(defaults.seed),
            spread: file.model.spread.unwrap_or(defaults.spread),
            friction: file.model.friction,
            cornering: file.model.cornering.unwrap_or(false),
            relaxation: file.model.relaxation.unwrap_or(false),
            bumper: match file.model.bumper.as_deref() {
                None | Some("start") => false,
                Some("fit") => true,
                Some(other) => {
                    return Err(error(format!(
                        "[model] bumper = \"{other}\": expected \"start\" or \"fit\""
                    )));
                }
            },
            mass,
            priors: match &file.priors {
                Some(table) => {
                    crate::study_priors::settings(table).map_err(|e| error(e.to_string()))?
                }
                None => Vec::new(),
            },
            domain: match identification.and_then(|i| i.objective.as_deref()) {
                Some(name) => name
                    .parse()
                    .map_err(|e: UnknownDomain| error(format!("[identification] {e}")))?,
                None => DOMAIN,
            },
            bias: match identification.and_then(|i| i.bias.as_deref()) {
                None => defaults.bias,
                Some("pretrigger") => Bias::Pretrigger,
                Some("nuisance") => Bias::Nuisance,
                Some(other) => {
                    return Err(error(format!(
                        "[identification] bias = \"{other}\": expected \"pretrigger\" or \"nuisance\""
                    )));
                }
            },
            arms: identification.and_then(|i| i.arm).unwrap_or(defaults.arms),
            ..defaults
        };
        setup.joint = joint(file.model.joint, setup.bumper).map_err(|m| error(m.0))?;
        let mut loader = Loader::new();
        let (mut cases, mut validation, mut notes) = (Vec::new(), Vec::new(), Vec::new());
        for spec in &file.case {
            let (case, resampled) = load_case(spec, base, &mut loader)?;
            check_striker(&setup.template, &case)?;
            check_loads(&setup.template, &case)?;
            notes.extend(resampled.map(|r| format!("case '{}': {r}", spec.name)));
            match spec.validate {
                true => validation.push(case),
                false => cases.push(case),
            }
        }
        if cases.is_empty() {
            return Err(error(
                "every case is `validate = true`: at least one must be fitted".into(),
            ));
        }
        // a replay estimates the biases the objective profiles out
        for case in cases.iter_mut().chain(&mut validation) {
            case.nuisance = setup.bias == Bias::Nuisance;
        }
        let law = tyres_law_estimated(&setup.template, &cases);
        setup.cornering = file.model.cornering.unwrap_or(law);
        setup.relaxation = file.model.relaxation.unwrap_or(law);
        let walled = width_estimated(&cases);
        setup.width = (file.model.effective_width).unwrap_or(walled);
        setup.cells = cells(file.model.cells, setup.bumper, walled).map_err(|m| error(m.0))?;
        setup.confirm = file.model.confirm;
        Ok(PlanarStudy {
            path: path.to_path_buf(),
            setup,
            cases,
            validation,
            notes,
        })
    }
}

impl PlanarStudy {
    /// Every case, fitted then validation, or those named in `names`; an
    /// error names a case the study does not hold (`bumpsim predict --case`).
    pub fn named(&self, names: &[String]) -> Result<Vec<&PlanarCase>, PlanarError> {
        let all: Vec<&PlanarCase> = self.cases.iter().chain(&self.validation).collect();
        if let Some(name) = names.iter().find(|n| !all.iter().any(|c| &&c.name == n)) {
            let known: Vec<&str> = all.iter().map(|c| c.name.as_str()).collect();
            return Err(PlanarError::File {
                path: self.path.display().to_string(),
                message: format!("no case '{name}'; cases: {}", known.join(", ")),
            });
        }
        Ok(all
            .into_iter()
            .filter(|c| names.is_empty() || names.contains(&c.name))
            .collect())
    }
}

/// Whether a study that does not say (`cornering`, `relaxation` absent)
/// estimates the tyres' law, C_α and σ: when a training case carries a
/// yaw-rate sensor and the start car's tyres roll with a relaxation length
/// on both axles (σ's condition, [`crate::identify::Unknowns::with_relaxation`]).
/// The yaw rate shows the yaw's time course, which the tyres' lag shapes,
/// and the start's tyres are a guess: on issue 44's yaw-rate series and three
/// varied cars of its generator the start's law (σ = 0.4 m, C_α fixed)
/// scored the off-centre face's held-out yaw −6 to 32 %, the estimated one
/// 82 to 92 % (docs/planar.md, "Defaults chosen by evidence").
fn tyres_law_estimated(car: &PlanarCar, cases: &[PlanarCase]) -> bool {
    let tyres = car.tyres();
    let rolling = [tyres.front, tyres.rear]
        .iter()
        .all(|a| a.law == crate::car::TyreLaw::Rolling && a.relaxation_length > 0.0);
    rolling && cases.iter().any(|c| c.yaw_rate().is_some())
}

/// Whether a study that does not say (`effective_width` absent) estimates
/// the bumper's effective width: when a training case carries a wall's load
/// cells (`cell` with `anchor`), whose lines of action the segments'
/// positions set, so that the data see the width. On issue 44's
/// independent generator (20 cars) the documented study held its
/// thresholds on 11 cars with it against 8 without (docs/planar.md, "The
/// bumper's effective width").
fn width_estimated(cases: &[PlanarCase]) -> bool {
    let cells = |c: &PlanarCase| c.drive.loads.iter().any(|l| l.cell.is_some());
    cases.iter().any(cells)
}

/// A case's striker must meet the start car (angle, overlap, pole beside
/// the bumper): refused here, by the case's name, not after the search.
fn check_striker(car: &PlanarCar, case: &PlanarCase) -> Result<(), PlanarError> {
    let Some(striker) = &case.striker else {
        return Ok(());
    };
    crate::striker::place(car, striker)
        .map(|_| ())
        .map_err(|e| PlanarError::Case {
            case: case.name.clone(),
            message: format!("striker: {e}"),
        })
}

/// The largest `[model] joint` balance β: beyond it the replays hardly count.
pub const MAX_JOINT: f64 = 100.0;

/// `[model] joint = β` (the joint final stage, identify module `joint`):
/// a number above 0 and at most [`MAX_JOINT`], with `bumper = "fit"`.
fn joint(balance: Option<f64>, bumper: bool) -> Result<Option<f64>, JointKey> {
    let refused = |m: String| Err(JointKey(m));
    match balance {
        None => Ok(None),
        Some(b) if !(b > 0.0 && b <= MAX_JOINT) => refused(format!(
            "[model] joint = {b}: expected the forward runs' weight against the replays, above 0 and at most {MAX_JOINT}"
        )),
        Some(_) if !bumper => refused(
            "[model] joint polishes the car with the bumper's law: it needs bumper = \"fit\""
                .into(),
        ),
        Some(b) => Ok(Some(b)),
    }
}

/// `[model] cells` (the forward runs compared cell by cell,
/// [`crate::cell_force`]): true needs the bumper fitted, the one place
/// forward runs are compared in an identification; absent, true when the
/// bumper is fitted and a training case has a wall's load cells (`walled`).
/// On issue 44's independent generator (20 cars) the documented study held
/// its thresholds on 15 cars with them (and the width's prior then 0.05
/// wide) against 11 by the total force (docs/planar.md, "The wall's cells
/// one by one").
fn cells(cells: Option<bool>, bumper: bool, walled: bool) -> Result<bool, JointKey> {
    match (cells, bumper) {
        (Some(true), false) => Err(JointKey(
            "[model] cells compares the forward runs of the bumper's fit: it needs bumper = \"fit\"".into(),
        )),
        (cells, _) => Ok(cells.unwrap_or(bumper && walled)),
    }
}

/// A refused `[model] joint` or `cells`: what is expected (the study file's error
/// names the file).
#[derive(Debug, Clone, PartialEq)]
struct JointKey(String);

/// A case's forces placed on the bumper line (no anchor, position not
/// estimated) lie on it: a load cell at `lateral = -1.0` on a 1.6 m bumper
/// was accepted. Refused by the case's name and the force's number.
fn check_loads(car: &PlanarCar, case: &PlanarCase) -> Result<(), PlanarError> {
    let half = 0.5 * car.beam().width;
    match off_bumper(half, &case.drive.loads, &case.estimated) {
        None => Ok(()),
        Some((k, y)) => Err(PlanarError::Case {
            case: case.name.clone(),
            message: format!(
                "force {}: lateral = {} m: must lie on the bumper line, |lateral| at most half the start car's bumper width, {half} m",
                k + 1,
                bumpsim_core::units::short(y)
            ),
        }),
    }
}

/// The first load on the bumper line beyond `half` (m): its index and place
/// (a value that is not finite is the drive's own check, `load[k].lateral`).
fn off_bumper(
    half: f64,
    loads: &[crate::drive::Load],
    estimated: &[usize],
) -> Option<(usize, f64)> {
    let fixed =
        |(k, l): &(usize, &crate::drive::Load)| l.anchor.is_none() && !estimated.contains(k);
    let mut placed = loads.iter().enumerate().filter(fixed);
    placed
        .find(|(_, l)| l.lateral.abs() > half)
        .map(|(k, l)| (k, l.lateral))
}

/// A case's `time_zero`: `"onset"` (the default), or a time of the file's
/// time base: s, or text with a unit (`"-2 ms"`).
fn time_zero(value: Option<&toml::Value>) -> Option<TimeZero> {
    let at = match value {
        None => return Some(TimeZero::Onset),
        Some(toml::Value::String(s)) if s == "onset" => return Some(TimeZero::Onset),
        Some(toml::Value::Float(v)) => *v,
        Some(toml::Value::Integer(v)) => *v as f64,
        Some(toml::Value::String(s)) => parse_quantity(s, Dimension::Time).ok()?,
        _ => return None,
    };
    at.is_finite().then_some(TimeZero::At(at))
}

/// Each force and sensor channel of a case read once: a channel named
/// twice was summed twice (a force) or weighed twice (a sensor) without a
/// word, where the 1-D study refuses it ([`LoadError::Twice`]; a hostile
/// pass, issue 44). Other failures of the selection are left to the
/// loading of each channel, which names them.
fn read_once(spec: &CaseFile, base: &Path, loader: &mut Loader) -> Result<(), LoadError> {
    let forces = spec.forces.iter().map(|f| (&f.path, &f.channel));
    let sensors = spec.sensors.iter().map(|s| (&s.path, &s.channel));
    let sources: Vec<ChannelSource> = forces
        .chain(sensors)
        .map(|(path, code)| ChannelSource::new(base.join(path), code, 1.0))
        .collect();
    match loader.channels(&sources) {
        Err(twice @ LoadError::Twice { .. }) => Err(twice),
        _ => Ok(()),
    }
}

fn load_case(
    spec: &CaseFile,
    base: &Path,
    loader: &mut Loader,
) -> Result<(PlanarCase, Option<Resampling>), PlanarError> {
    let error = |message: String| PlanarError::Case {
        case: spec.name.clone(),
        message,
    };
    let speed = match &spec.speed {
        None => 0.0,
        Some(value) => speed_value(value).map_err(|e| match e {
            SpeedError::Quantity(q) => error(format!("speed: {q}")),
            other => error(other.to_string()),
        })?,
    };
    read_once(spec, base, loader).map_err(|e| error(e.to_string()))?;
    let mut channel =
        |path: &Path, code: &str, dimension: Option<Dimension>| -> Result<Channel, PlanarError> {
            let source = ChannelSource::new(base.join(path), code, 1.0);
            let loaded = loader
                .signal(&[source], None, code)
                .map_err(|e| error(format!("{}: {code}: {e}", path.display())))?;
            match dimension.is_none_or(|d| loaded.data.dimension == d) {
                true => Ok(loaded.data),
                false => Err(error(format!(
                    "{}: {code} is a {:?} channel, expected {:?}",
                    path.display(),
                    loaded.data.dimension,
                    dimension.unwrap_or(Dimension::Force)
                ))),
            }
        };
    let mut forces = Vec::new();
    for f in &spec.forces {
        let (lateral, estimated) = match (&f.lateral, f.anchor) {
            (Some(Lateral::At(y)), _) => (*y, false),
            (Some(Lateral::Word(w)), _) if w == "estimate" => (0.0, true),
            (Some(Lateral::Word(w)), _) => {
                return Err(error(format!(
                    "force {}: lateral = {w:?}: expected a position in m or \"estimate\"",
                    f.channel
                )));
            }
            // the line of action passes through the anchor: its η stands for the place
            (None, Some([_, eta])) => (eta, false),
            (None, None) => {
                return Err(error(format!(
                    "force {}: give `lateral` (m on the bumper line, or \"estimate\") or `anchor` (a world point on its line of action; a wall cell: its centre, with `cell`)",
                    f.channel
                )));
            }
        };
        let [dx, dy] = direction(&f.direction).ok_or_else(|| {
            error(format!(
                "force {}: direction = {:?}: expected two components [x, y] (world frame), finite and not both zero (a planar force has no z component; the vector is normalised, so any length will do)",
                f.channel, f.direction
            ))
        })?;
        forces.push(Placed {
            channel: channel(&f.path, &f.channel, Some(Dimension::Force))?,
            lateral,
            direction: [dx, dy],
            anchor: f.anchor,
            estimated,
            cell: f.cell,
        });
    }
    let (mut sensors, mut positions, mut noise) = (Vec::new(), Vec::new(), Vec::new());
    for s in &spec.sensors {
        let loaded = channel(&s.path, &s.channel, None)?;
        let place = crate::sensing::kind(&loaded, s.axis.as_deref(), s.body, s.chain)
            .map_err(|e| error(format!("sensor {}: {e}", s.channel)))?;
        let given = s
            .noise
            .as_ref()
            .map(|v| crate::sensing::noise(v, loaded.dimension))
            .transpose()
            .map_err(|e| error(format!("sensor {}: noise: {e}", s.channel)))?;
        sensors.push(loaded);
        positions.push(place);
        noise.push(given);
    }
    let striker = spec
        .striker
        .as_ref()
        .map(|f| {
            let (striker, _) = f
                .spec()
                .map_err(|e| error(format!("striker: {e}")))?
                .striker()
                .map_err(|e| error(format!("striker: {e}")))?;
            Ok::<_, PlanarError>(striker)
        })
        .transpose()?;
    let time_zero = time_zero(spec.time_zero.as_ref()).ok_or_else(|| {
        error(format!(
            "time_zero = {}: expected \"onset\" or a finite time of the files' time base, s or text such as \"-2 ms\"",
            spec.time_zero.as_ref().map_or(String::new(), |v| v.to_string())
        ))
    })?;
    let (mut case, resampled) = TestChannels {
        name: spec.name.clone(),
        forces,
        sensors,
        positions,
        noise,
        speed,
        cfc: spec.cfc,
        time_zero,
    }
    .case()?;
    case.striker = striker;
    Ok((case, resampled))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::drive::Load;

    #[test]
    fn a_force_off_the_bumper_line_is_found_unless_anchored_or_estimated() {
        let load = |lateral, anchor| Load {
            lateral,
            anchor,
            cell: None,
            direction: [-1.0, 0.0],
            force: vec![0.0, 1.0],
        };
        let loads = [
            load(0.8, None),
            load(-1.0, None),
            load(3.0, Some([0.0, 3.0])),
        ];
        assert_eq!(off_bumper(0.8, &loads, &[]), Some((1, -1.0)));
        assert_eq!(
            off_bumper(0.8, &loads, &[1]),
            None,
            "an estimated place is a start"
        );
        assert_eq!(
            off_bumper(0.8, &loads[..1], &[]),
            None,
            "the end of the bumper"
        );
        assert_eq!(off_bumper(0.8, &[load(1e300, None)], &[]), Some((0, 1e300)));
    }

    /// `[model] joint` is a positive balance at most 100, with the bumper
    /// fitted; anything else is refused by key, with what is expected.
    #[test]
    fn the_joint_balance_is_checked() {
        assert_eq!(joint(None, false), Ok(None));
        assert_eq!(joint(Some(2.0), true), Ok(Some(2.0)));
        assert_eq!(joint(Some(MAX_JOINT), true), Ok(Some(MAX_JOINT)));
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY, 101.0] {
            let e = joint(Some(bad), true).unwrap_err().0;
            assert!(
                e.starts_with("[model] joint = ") && e.contains("above 0"),
                "{e}"
            );
        }
        let e = joint(Some(2.0), false).unwrap_err().0;
        assert!(e.contains("bumper = \"fit\""), "{e}");
    }

    /// `[model] cells` needs the bumper fitted; absent, it is true when
    /// the bumper is fitted to a training wall's load cells.
    #[test]
    fn the_cells_need_the_bumper_fitted() {
        assert_eq!(cells(None, false, true), Ok(false));
        assert_eq!(cells(None, true, false), Ok(false));
        assert_eq!(cells(None, true, true), Ok(true));
        assert_eq!(cells(Some(false), true, true), Ok(false));
        assert_eq!(cells(Some(true), true, false), Ok(true));
        assert_eq!(cells(Some(false), false, true), Ok(false));
        let e = cells(Some(true), false, true).unwrap_err().0;
        assert!(
            e.starts_with("[model] cells") && e.contains("bumper = \"fit\""),
            "{e}"
        );
    }
}
