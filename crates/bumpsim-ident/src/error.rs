//! Why a chain identification cannot run.

use crate::case::CaseError;
use bumpsim_estimate::multistart;

/// Why identification cannot run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum IdentError {
    /// A load case is unusable.
    #[error(transparent)]
    Case(#[from] CaseError),
    /// A setting is out of range.
    #[error("identification setting {name}: {reason}")]
    Setting {
        /// The setting.
        name: &'static str,
        /// What is wrong.
        reason: String,
    },
    /// The best start's parameters do not make a model (cannot happen within
    /// the bounds; checked so that no invalid model is returned).
    #[error("the best parameters {theta:?} (SI) do not make a valid model")]
    Parameters {
        /// The parameters, SI, thesis order.
        theta: Vec<f64>,
    },
    /// Every start failed.
    #[error(transparent)]
    AllFailed(#[from] multistart::AllFailed),
}
