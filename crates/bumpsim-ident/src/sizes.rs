//! The identification of a study over its model sizes (issue 46): the one
//! loop that `bumpsim identify` and the Python `dof_table` run. The cases
//! are loaded once for the largest size, then each size n (masses) is
//! identified in the study's order with the study's settings and the
//! caller's starts and seed, continued from the last size identified
//! ([`Sweep`]; cross-validated when there are several sizes, thesis
//! table 1); a size that fails is kept with its reason and the others go on.
//! The front ends only convert arguments, watch ([`Watch`]) and print.

use crate::case::LoadCase;
use crate::dofs::Sweep;
use crate::error::IdentError;
use crate::estimate::Identification;
use crate::settings::Settings;
use crate::study::{Study, StudyError};
pub use bumpsim_estimate::observer::Observer;

/// The caller's starts and seed, over the study's.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Overrides {
    /// Number of starts (default: the study's).
    pub starts: Option<usize>,
    /// Seed of the random starts (default: the study's).
    pub seed: Option<u64>,
}

impl Overrides {
    /// The study's settings for `dof` masses with these starts and seed.
    pub fn settings(&self, study: &Study, dof: usize) -> Result<Settings, StudyError> {
        let mut settings = study.settings(dof)?;
        settings.starts = self.starts.unwrap_or(settings.starts);
        settings.seed = self.seed.unwrap_or(settings.seed);
        Ok(settings)
    }
}

/// One model size: its load cases, settings and result or failure.
#[derive(Debug, Clone)]
pub struct Order {
    /// Number of masses.
    pub dof: usize,
    /// The cases, retargeted to this size.
    pub cases: Vec<LoadCase>,
    /// The settings it was identified with.
    pub settings: Settings,
    /// The identification, or why it failed.
    pub result: Result<Identification, IdentError>,
}

/// What a study's identification over its sizes gives.
#[derive(Debug, Clone)]
pub struct Sizes {
    /// What the channel selections left out or used despite a mark.
    pub notes: Vec<String>,
    /// The sizes, in the study's order.
    pub orders: Vec<Order>,
}

impl Sizes {
    /// The identified sizes' results.
    pub fn results(&self) -> Vec<Identification> {
        self.orders
            .iter()
            .filter_map(|o| o.result.as_ref().ok().cloned())
            .collect()
    }
}

/// What a caller sees while the sizes are identified (every method does
/// nothing unless overridden).
pub trait Watch {
    /// The cases are loaded: their notes and warnings.
    fn loaded(&self, _notes: &[String], _warnings: &[String]) {}
    /// Size `dof` starts with `starts` starts: the observer of its search.
    fn starting(&self, _dof: usize, _starts: usize) -> Box<dyn Observer + '_> {
        Box::new(bumpsim_estimate::observer::Silent)
    }
    /// Size `dof` is done (identified or failed).
    fn done(&self, _order: &Order) {}
}

/// A watch that watches nothing.
#[derive(Debug, Clone, Copy, Default)]
pub struct Unwatched;

impl Watch for Unwatched {}

/// Identifies `study` over its sizes ([`Study::dofs`]) with `overrides`;
/// fails only when the study's cases or settings cannot be had.
pub fn identify(
    study: &Study,
    overrides: &Overrides,
    watch: &dyn Watch,
) -> Result<Sizes, StudyError> {
    let dofs = study.dofs();
    let loaded = study.load(dofs.iter().copied().max().unwrap_or(1))?;
    let notes: Vec<String> = loaded.notes.iter().map(ToString::to_string).collect();
    watch.loaded(&notes, &loaded.warnings);
    let mut sweep = Sweep::new().cross_validated(dofs.len() > 1);
    let mut orders = Vec::new();
    for &dof in &dofs {
        let settings = overrides.settings(study, dof)?;
        let cases = study.retarget(&loaded.cases, dof);
        let observer = watch.starting(dof, settings.starts);
        let result = sweep.identify(&cases, settings.clone(), observer.as_ref());
        drop(observer);
        let order = Order {
            dof,
            cases,
            settings,
            result,
        };
        watch.done(&order);
        orders.push(order);
    }
    Ok(Sizes { notes, orders })
}
