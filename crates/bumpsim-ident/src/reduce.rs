//! The simpler model the data cannot tell apart (issue 19).
//!
//! A spring k_j that the data do not determine — at a bound, without an
//! interval, or with a 95 % interval wider than a factor [`SPREAD`] — may
//! join two masses that move as one. The reduced model merges them
//! (`m_j + m_{j+1}` on one node; link j removed, the other links kept; an
//! output on either mass is the merged mass's) and is refitted by one LM
//! run from the merged start. When it fits within [`TOLERANCE`] of the full
//! model's objective, the result says so, naming the spring: the simpler
//! model describes the data as well.
//! Springs are tried widest interval first; the first that passes is reported.

use crate::case::LoadCase;
use crate::estimate::{Bounds, IdentError, Identification, Settings};
use bumpsim_core::model::{MsdModel, format_parameter, parameter_name};
use bumpsim_core::units::{Dimension, format_number, format_quantity};
use serde::Serialize;

/// A spring whose 95 % interval spans more than this factor is undetermined.
pub const SPREAD: f64 = 1e3;

/// The reduced model must fit within this fraction of the full objective.
pub const TOLERANCE: f64 = 0.01;

/// A reduced model that fits as well.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Reduction {
    /// The undetermined spring (`k2`).
    pub parameter: String,
    /// What the user should know, with units.
    pub statement: String,
    /// The refitted reduced model; serialised as `masses`, `dampers`, `springs` (SI).
    pub model: MsdModel,
    /// Its objective, m².
    pub objective: f64,
    /// `F_reduced / F_full − 1`.
    pub relative_objective: f64,
}

/// How undetermined spring `j` (0-based) of `result` is: the interval's
/// ratio (infinite without one), or `None` when it is determined.
fn spread(result: &Identification, j: usize) -> Option<f64> {
    let i = 2 * result.dof - 1 + j;
    let u = &result.uncertainty;
    if u.fixed[i] {
        return None;
    }
    let ratio = match (u.at_bound[i], u.ci95[i]) {
        (true, _) | (_, None) => f64::INFINITY,
        (false, Some([low, high])) => high / low,
    };
    (ratio > SPREAD).then_some(ratio)
}

/// `model` with masses j and j+1 (0-based) merged and link j removed.
pub fn merged(model: &MsdModel, j: usize) -> Vec<f64> {
    let mut masses = model.masses().to_vec();
    let second = masses.remove(j + 1);
    masses[j] += second;
    let mut dampers = model.dampers().to_vec();
    dampers.remove(j);
    let mut springs = model.springs().to_vec();
    springs.remove(j);
    [masses, dampers, springs].concat()
}

/// The cases measured on the model with masses j and j+1 merged.
fn retargeted(cases: &[LoadCase], j: usize) -> Vec<LoadCase> {
    let mut cases = cases.to_vec();
    for c in &mut cases {
        if c.output_dof > j + 1 {
            c.output_dof -= 1;
        }
    }
    cases
}

/// An identification without the search for a reduced model.
pub(crate) type Refit<'a> =
    dyn Fn(&[LoadCase], &Settings) -> Result<Identification, IdentError> + 'a;

/// The first reduced model that fits within [`TOLERANCE`], if any.
pub(crate) fn suggest(
    cases: &[LoadCase],
    result: &Identification,
    settings: &Settings,
    refit: &Refit<'_>,
) -> Option<Reduction> {
    if result.dof < 2 || settings.bounds.fixed.iter().any(Option::is_some) {
        return None;
    }
    let mut candidates: Vec<(usize, f64)> = (0..result.dof - 1)
        .filter_map(|j| spread(result, j).map(|s| (j, s)))
        .collect();
    candidates.sort_by(|a, b| b.1.total_cmp(&a.1));
    let lower = settings
        .bounds
        .lower
        .iter()
        .copied()
        .fold(f64::INFINITY, f64::min);
    candidates.into_iter().find_map(|(j, _)| {
        let mut reduced = Settings::new(result.dof - 1, 1);
        reduced.bounds = Bounds::uniform(result.dof - 1, lower);
        reduced.start = Some(merged(&result.model, j));
        reduced.solver = settings.solver;
        let fit = refit(&retargeted(cases, j), &reduced).ok()?;
        let relative = fit.objective / result.objective - 1.0;
        (relative <= TOLERANCE).then(|| reduction(result, j, fit, relative))
    })
}

fn reduction(result: &Identification, j: usize, fit: Identification, relative: f64) -> Reduction {
    let dof = result.dof;
    let i = 2 * dof - 1 + j;
    let name = parameter_name(dof, i);
    let u = &result.uncertainty;
    let how = match (u.at_bound[i], u.ci95[i]) {
        (true, _) => format!(
            "it is at its bound, {}",
            format_parameter(dof, i, result.model.springs()[j])
        ),
        (false, Some([a, b])) => format!(
            "its 95 % interval is {} .. {}",
            format_parameter(dof, i, a),
            format_parameter(dof, i, b)
        ),
        (false, None) => "it has no interval: the Jacobian does not determine it".into(),
    };
    let statement = format!(
        "{name} is not determined by the data ({how}): m{} and m{} move as one. The {}-DOF model with m{} + m{} = {} fits within {} % of the objective ({} m² against {} m²): prefer the simpler model.",
        j + 1,
        j + 2,
        dof - 1,
        j + 1,
        j + 2,
        format_quantity(fit.model.masses()[j], Dimension::Mass),
        format_number(100.0 * relative.max(0.0), 3),
        format_number(fit.objective, 5),
        format_number(result.objective, 5),
    );
    Reduction {
        parameter: name,
        statement,
        model: fit.model,
        objective: fit.objective,
        relative_objective: relative,
    }
}
