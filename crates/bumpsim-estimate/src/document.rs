//! The document of a prediction that every model's front end writes
//! (`bumpsim predict --json`, chain or planar): the model, each case's fit
//! (the model's own fit type), the warnings of negative fits and the notes
//! on the channels, assembled once here.
//!
//! ```
//! use bumpsim_estimate::document::Predictions;
//! #[derive(serde::Serialize)]
//! struct Fit { name: String, fit_percent: f64 }
//! let fits = [Fit { name: "flat".into(), fit_percent: 99.5 }];
//! let doc = Predictions::new("car", &fits, Vec::new(), &[]);
//! assert_eq!(doc.cases.len(), 1);
//! ```

use serde::Serialize;

/// `bumpsim predict --json`: the model's name (or its file), the fits per
/// case, the warnings and the notes.
#[derive(Debug, Clone, Serialize)]
pub struct Predictions<'a, F: Serialize> {
    /// The model's name, or its file.
    pub model: &'a str,
    /// Fits per case.
    pub cases: Vec<&'a F>,
    /// Negative fits (the model follows a signal worse than its mean).
    pub warnings: Vec<String>,
    /// Notes on the channels' time base.
    pub notes: &'a [String],
}

impl<'a, F: Serialize> Predictions<'a, F> {
    /// The document of `fits` of `model`, with their `warnings`.
    pub fn new(
        model: &'a str,
        fits: impl IntoIterator<Item = &'a F>,
        warnings: Vec<String>,
        notes: &'a [String],
    ) -> Predictions<'a, F> {
        Predictions {
            model,
            cases: fits.into_iter().collect(),
            warnings,
            notes,
        }
    }
}
