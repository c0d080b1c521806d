//! The documents of a chain identification that every front end writes
//! (`bumpsim identify --json`, `bumpsim predict --json`, Python's
//! `to_json`): serialisable types, so each JSON is assembled once, here.
//!
//! One DOF writes its [`Identification`] with the notes beside its fields;
//! a DOF table writes every result, the orders that failed, the
//! recommended order and the model choice that decided it
//! ([`crate::choice`]). With a posterior, [`WithPosterior`] adds it.

use crate::explore::Prediction;
use crate::result::{CaseFit, Identification};
use bumpsim_estimate::document::Predictions;
use serde::{Serialize, Serializer};

/// An order of the DOF table that failed, and why.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Failed {
    /// The number of masses.
    pub dof: usize,
    /// The error.
    pub reason: String,
}

/// `bumpsim identify --json` of a chain study.
#[derive(Debug, Clone, Copy)]
pub enum IdentifyDocument<'a> {
    /// One order identified: the result's fields and `notes`.
    One {
        /// The result.
        result: &'a Identification,
        /// Notes on the channels.
        notes: &'a [String],
    },
    /// A DOF table.
    Table {
        /// The orders identified.
        results: &'a [Identification],
        /// The orders that failed.
        failed: &'a [Failed],
        /// Notes on the channels.
        notes: &'a [String],
    },
}

impl<'a> IdentifyDocument<'a> {
    /// One result when exactly one order was asked and it was identified,
    /// else the table.
    pub fn new(
        results: &'a [Identification],
        failed: &'a [Failed],
        notes: &'a [String],
    ) -> IdentifyDocument<'a> {
        match results {
            [one] if failed.is_empty() => IdentifyDocument::One { result: one, notes },
            _ => IdentifyDocument::Table {
                results,
                failed,
                notes,
            },
        }
    }
}

impl Serialize for IdentifyDocument<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        #[derive(Serialize)]
        struct One<'a> {
            #[serde(flatten)]
            result: &'a Identification,
            notes: &'a [String],
        }
        #[derive(Serialize)]
        struct Table<'a> {
            results: &'a [Identification],
            failed: &'a [Failed],
            recommended_dof: Option<usize>,
            model_choice: Option<crate::choice::Choice>,
            notes: &'a [String],
        }
        match *self {
            IdentifyDocument::One { result, notes } => One { result, notes }.serialize(serializer),
            IdentifyDocument::Table {
                results,
                failed,
                notes,
            } => {
                let model_choice = crate::choice::choose(results);
                Table {
                    results,
                    failed,
                    recommended_dof: model_choice.as_ref().map(|c| c.dof),
                    model_choice,
                    notes,
                }
                .serialize(serializer)
            }
        }
    }
}

/// `bumpsim identify --posterior --json`: the identification's document
/// with the posterior of one of its orders (the one identified, or the
/// DOF table's recommendation) as `posterior`
/// ([`crate::posterior::Summary`]); without one, the document alone.
#[derive(Debug, Clone, Serialize)]
pub struct WithPosterior<'a> {
    /// The identification's document.
    #[serde(flatten)]
    pub document: IdentifyDocument<'a>,
    /// The posterior, when sampled.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub posterior: Option<crate::posterior::Summary<'a>>,
}

/// `bumpsim predict --json` with a chain model: the layer's document of
/// each case's fit, the warnings of negative fits, and the notes.
pub type PredictionDocument<'a> = Predictions<'a, CaseFit>;

/// The prediction document of `predictions` of `model`.
pub fn predictions<'a>(
    model: &'a str,
    predictions: &'a [Prediction],
    notes: &'a [String],
) -> PredictionDocument<'a> {
    let warnings = predictions.iter().filter_map(Prediction::warning).collect();
    Predictions::new(model, predictions.iter().map(|p| &p.fit), warnings, notes)
}
