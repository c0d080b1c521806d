//! The simpler chain the data cannot tell apart (issue 19): the layer's
//! reduced-model advice ([`bumpsim_estimate::reduce`]) on the chain's links.
//!
//! Link j joins masses j and j+1; its merge puts `m_j + m_{j+1}` on one
//! node, removes link j and keeps the other links; a case measured on
//! either mass is measured on the merged one. The merged model is refitted
//! with every parameter free within the study's lowest lower bound. See
//! the layer for which links are tried and when a merge is suggested
//! (an undetermined spring within 1 % of the objective, or an unneeded
//! link by the F-test).

use crate::case::{LoadCase, Objective};
use crate::result::Identification;
use crate::settings::{Settings, uniform_bounds};
use bumpsim_core::model::{MsdModel, parameter_count, parameter_name};
use bumpsim_estimate::reduce::{self, Full, Link, Merged, Reducible};

pub use bumpsim_estimate::reduce::{SIGNIFICANCE, SPREAD, TOLERANCE, f_test};

/// A reduced chain that fits as well; serialised with its `model` as
/// `masses`, `dampers`, `springs` (SI).
pub type Reduction = reduce::Reduction<MsdModel>;

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

/// The identified chain, its cases and settings, as the layer reduces them.
struct Chain<'a> {
    cases: &'a [LoadCase],
    result: &'a Identification,
    settings: &'a Settings,
}

impl Reducible for Chain<'_> {
    type Model = MsdModel;

    fn links(&self) -> Vec<Link> {
        let dof = self.result.dof;
        if dof < 2 || self.settings.bounds.fixed.iter().any(Option::is_some) {
            return Vec::new();
        }
        (0..dof - 1)
            .map(|j| Link {
                spring: 2 * dof - 1 + j,
                masses: [format!("m{}", j + 1), format!("m{}", j + 2)],
            })
            .collect()
    }

    fn merged_objective(&self, j: usize) -> Option<f64> {
        let r = self.result;
        let model = MsdModel::from_parameters(r.dof - 1, &merged(&r.model, j)).ok()?;
        retargeted(self.cases, j).iter().try_fold(0.0, |sum, case| {
            let simulated = case.simulate(&model).ok()?;
            Some(sum + case.fit(&simulated).0)
        })
    }

    fn refit(&self, j: usize, target: f64) -> Option<Merged<MsdModel>> {
        let dof = self.result.dof - 1;
        let cases = retargeted(self.cases, j);
        let lowest = self
            .settings
            .bounds
            .lower
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min);
        let (lower, upper) = uniform_bounds(dof, lowest).log_free();
        let start: Vec<f64> = merged(&self.result.model, j)
            .iter()
            .map(|v| v.ln())
            .collect();
        let make = || Objective::new(&cases, dof, &[]);
        let outcome = reduce::refit(
            &make,
            start,
            (&lower, &upper),
            &self.settings.solver,
            target,
        )?;
        let model = make().model(&outcome.parameters)?;
        Some(Merged {
            mass: model.masses()[j],
            model,
            objective: outcome.objective,
        })
    }

    fn reduced_name(&self) -> String {
        format!("{}-DOF model", self.result.dof - 1)
    }

    fn objective_unit(&self) -> String {
        self.result.objective_unit()
    }
}

/// The first reduced model that fits as well, if any (see the module).
pub(crate) fn suggest(
    cases: &[LoadCase],
    result: &Identification,
    settings: &Settings,
) -> Option<Reduction> {
    let parameters = crate::stats::parameters(result.dof);
    let theta = result.model.parameters();
    let full = Full {
        parameters: &parameters,
        theta: &theta,
        uncertainty: &result.uncertainty,
        objective: result.objective,
        residuals: result.residuals,
    };
    debug_assert_eq!(parameters.len(), parameter_count(result.dof));
    debug_assert!(parameter_name(result.dof, 0) == parameters[0].name);
    reduce::suggest(
        &Chain {
            cases,
            result,
            settings,
        },
        &full,
    )
}
