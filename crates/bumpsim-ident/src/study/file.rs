//! The study file's layout (TOML, read by serde with unknown keys
//! refused): `[model]` (the models, bounds, fixed values, starts, the
//! user's start) and the `[[case]]`s (force, displacement or
//! accelerations, bias, filter, initial velocity, output DOF, window).

use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::PathBuf;

/// The domain a study compares its cases in when it does not say
/// (docs/identify.md shows the comparison that chose it).
pub const DEFAULT_OBJECTIVE: crate::case::Domain = crate::case::Domain::Velocity;

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
    /// The test sheet's mass of the car (kg, or text such as `"1719 kg"`):
    /// the identified masses' sum is checked against it
    /// ([`crate::Settings::sheet_mass`]).
    pub mass: Option<toml::Value>,
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
    /// Seconds (exactly two: a third value is refused, not dropped).
    Times(bumpsim_io::numbers::Numbers<2>),
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
    #[serde(default, deserialize_with = "bumpsim_io::numbers::optional")]
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
    /// The measurement's noise in the objective's domain (standard
    /// deviation, SI: m, m/s or m/s²); default: from the pre-trigger
    /// (velocity and acceleration), none (displacement).
    pub noise: Option<f64>,
}

/// The `[identification]` table.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IdentificationSpec {
    /// The domain each case is compared in: `"displacement"` (the
    /// thesis's), `"velocity"` or `"acceleration"` (issue 44).
    pub objective: Option<String>,
}

impl CaseSpec {
    /// The case's channel references with the signal each is (`force`,
    /// `acceleration`, `displacement`).
    pub fn channels(&self) -> impl Iterator<Item = (&'static str, &ChannelRef)> {
        std::iter::once(("force", &self.force))
            .chain(self.acceleration.iter().map(|r| ("acceleration", r)))
            .chain(self.displacement.iter().map(|r| ("displacement", r)))
    }

    /// The selectors of the case's channels given a negative scale (turned
    /// in sign by the study), for the fix a sign warning names.
    pub fn turned_channels(&self) -> Vec<String> {
        std::iter::once(&self.force)
            .chain(&self.acceleration)
            .chain(&self.displacement)
            .filter(|r| r.scale < 0.0)
            .map(|r| r.channel.clone())
            .collect()
    }
}

/// A study file.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Study {
    /// The declared model kind (`kind = "chain"`; issue 46), read by
    /// `bumpsim_io::kind`, which chose this reader.
    #[serde(default)]
    pub kind: Option<String>,
    /// Model settings.
    pub model: ModelSpec,
    /// How the cases are compared.
    #[serde(default)]
    pub identification: IdentificationSpec,
    /// The stated priors: `[priors]` overrides, removes (`"none"`) or adds
    /// to the defaults ([`crate::priors`]).
    #[serde(default)]
    pub priors: Option<toml::Table>,
    /// The barrier identification's settings of a links study (`kind =
    /// "links"`), read by [`crate::links::study::LinksStudy::of`].
    #[serde(default)]
    pub links: Option<toml::Table>,
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
    /// The domain the cases are compared in (`[identification]
    /// objective`; default [`DEFAULT_OBJECTIVE`]).
    pub fn objective(&self) -> Result<crate::case::Domain, crate::case::UnknownDomain> {
        match &self.identification.objective {
            Some(name) => name.parse(),
            None => Ok(DEFAULT_OBJECTIVE),
        }
    }

    /// The DOF values to identify.
    pub fn dofs(&self) -> Vec<usize> {
        match &self.model.dof {
            DofSpec::One(n) => vec![*n],
            DofSpec::Many(list) => list.clone(),
        }
    }
}
