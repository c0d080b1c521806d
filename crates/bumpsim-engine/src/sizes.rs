//! The chain's identification over its model sizes as every front end
//! takes it (issue 46 item 1): the one loop ([`bumpsim_ident::sizes`])
//! gives each size's result or failure; here they are assembled once —
//! the sizes identified with their cases and settings, those that failed
//! with their reasons, each identified size's cases replayed, the JSON
//! document (with the posterior when sampled), the ±3 % sensitivity as
//! CSV and the report — for the command line's `identify` and Python's
//! `identify` and `dof_table`. No equations here.

use crate::{EngineError, Outcome, Report};
use bumpsim_ident::document::{Failed, IdentifyDocument, WithPosterior};
use bumpsim_ident::explore::Sweep;
use bumpsim_ident::posterior::{Posterior, Summary};
use bumpsim_ident::sizes::Sizes;
use bumpsim_ident::{IdentError, Identification, LoadCase, Settings};
use bumpsim_report::identification::DofOutcome;
use std::path::Path;

/// One size identified: its result, its cases and its settings.
#[derive(Debug, Clone)]
pub struct Done {
    /// The identification.
    pub result: Identification,
    /// The cases, retargeted to this size.
    pub cases: Vec<LoadCase>,
    /// The settings it was identified with.
    pub settings: Settings,
}

/// One size's outcome, in the study's order.
#[derive(Debug, Clone)]
pub enum Size {
    /// Identified.
    Done(Box<Done>),
    /// Could not be identified.
    Failed {
        /// Number of masses.
        dof: usize,
        /// Why.
        error: IdentError,
    },
}

/// A study identified over its sizes.
#[derive(Debug, Clone)]
pub struct Identified {
    /// What the channel selections left out or used despite a mark.
    pub notes: Vec<String>,
    /// The sizes, in the study's order.
    pub sizes: Vec<Size>,
}

/// What the command line's `identify` asked to be written besides the
/// document: the report's texts, when a report is asked.
#[derive(Debug, Clone, Copy)]
pub struct Asked<'a> {
    /// The study file (its text goes into the report).
    pub study: &'a Path,
    /// Starts and seed of the run, for the report's settings line.
    pub starts: usize,
    /// Seed of the random starts.
    pub seed: u64,
    /// Draw the report's pages.
    pub report: bool,
}

impl Identified {
    /// The one loop's sizes, assembled.
    pub fn of(sizes: Sizes) -> Identified {
        let sizes_out = sizes
            .orders
            .into_iter()
            .map(|order| match order.result {
                Ok(result) => Size::Done(Box::new(Done {
                    result,
                    cases: order.cases,
                    settings: order.settings,
                })),
                Err(error) => Size::Failed {
                    dof: order.dof,
                    error,
                },
            })
            .collect();
        Identified {
            notes: sizes.notes,
            sizes: sizes_out,
        }
    }

    /// The sizes identified.
    pub fn done(&self) -> Vec<&Done> {
        self.sizes
            .iter()
            .filter_map(|s| match s {
                Size::Done(done) => Some(done.as_ref()),
                Size::Failed { .. } => None,
            })
            .collect()
    }

    /// The identified sizes' results.
    pub fn results(&self) -> Vec<Identification> {
        self.done().into_iter().map(|d| d.result.clone()).collect()
    }

    /// The sizes that failed, with their reasons.
    pub fn failed(&self) -> Vec<Failed> {
        self.sizes
            .iter()
            .filter_map(|s| match s {
                Size::Failed { dof, error } => Some(Failed {
                    dof: *dof,
                    reason: error.to_string(),
                }),
                Size::Done(_) => None,
            })
            .collect()
    }

    /// Each size as the report shows it: an identified size with its
    /// cases replayed by the identified model.
    pub fn outcomes(&self) -> Result<Vec<DofOutcome>, EngineError> {
        self.sizes
            .iter()
            .map(|s| match s {
                Size::Done(d) => Ok(DofOutcome::Done {
                    result: Box::new(d.result.clone()),
                    predictions: bumpsim_ident::explore::predict(&d.cases, &d.result.model)
                        .map_err(Box::new)?,
                }),
                Size::Failed { dof, error } => Ok(DofOutcome::Failed {
                    dof: *dof,
                    reason: error.to_string(),
                }),
            })
            .collect()
    }

    /// The ±3 % sensitivity of the objective around the last size
    /// identified (91 simulations per case).
    pub fn sweeps(&self) -> Result<Option<Vec<Sweep>>, EngineError> {
        let Some(last) = self.done().last().copied() else {
            return Ok(None);
        };
        let sweeps = bumpsim_ident::explore::sensitivity(&last.cases, &last.result.model, 0.03, 13)
            .map_err(Box::new)?;
        Ok(Some(sweeps))
    }

    /// What `identify` writes: the document (with the posterior when
    /// sampled), the sensitivity as CSV (when swept) and the report (when
    /// asked); the text was printed as each size was done.
    pub fn outcome(
        &self,
        asked: &Asked<'_>,
        sweeps: Option<&[Sweep]>,
        posterior: Option<(&Posterior, &Identification)>,
    ) -> Result<Outcome, EngineError> {
        let (results, failed) = (self.results(), self.failed());
        let document = WithPosterior {
            document: IdentifyDocument::new(&results, &failed, &self.notes),
            posterior: posterior.map(|(p, r)| Summary::new(p, r)),
        };
        let report = match asked.report {
            true => Some(self.report(asked, sweeps, posterior)?),
            false => None,
        };
        Ok(Outcome {
            json: serde_json::to_string_pretty(&document)?,
            csv: sweeps.map(sensitivity_csv).unwrap_or_default(),
            report,
            ..Outcome::default()
        })
    }

    /// The identification's report.
    fn report(
        &self,
        asked: &Asked<'_>,
        sweeps: Option<&[Sweep]>,
        posterior: Option<(&Posterior, &Identification)>,
    ) -> Result<Report, EngineError> {
        let inputs = std::fs::read_to_string(asked.study).unwrap_or_default();
        let outcomes = self.outcomes()?;
        let dofs: Vec<String> = outcomes
            .iter()
            .map(|o| match o {
                DofOutcome::Done { result, .. } => result.dof.to_string(),
                DofOutcome::Failed { dof, .. } => format!("{dof} (failed)"),
            })
            .collect();
        let settings = format!(
            "Study {}; DOF {}; {} starts, seed {}; exact zoh discretisation.",
            asked.study.display(),
            dofs.join(", "),
            asked.starts,
            asked.seed
        );
        let texts = ("bumpsim identification", inputs.as_str(), settings.as_str());
        let (html, figures) = bumpsim_report::identification::report_with_posterior(
            texts,
            &self.notes,
            &outcomes,
            sweeps,
            posterior,
        )?;
        Ok(Report {
            html,
            figures,
            inputs: vec![asked.study.to_path_buf()],
        })
    }
}

/// The objective's sensitivity as CSV: the relative change, then one
/// column per case.
fn sensitivity_csv(sweeps: &[Sweep]) -> String {
    let mut csv = String::from("relative change [-]");
    sweeps
        .iter()
        .for_each(|s| csv += &format!(",objective {} [m^2]", s.name));
    csv.push('\n');
    for j in 0..sweeps.first().map_or(0, |s| s.relative_change.len()) {
        csv += &sweeps[0].relative_change[j].to_string();
        sweeps
            .iter()
            .for_each(|s| csv += &format!(",{}", s.objective[j]));
        csv.push('\n');
    }
    csv
}
