//! bumpsim-signal: turning crash-test channels into the force and
//! displacement signals that identification needs (thesis ch. 3.1, spec §4).
//!
//! - [`filter`]: SAE J211-1 / ISO 6487 CFC filters, Butterworth, moving average;
//! - [`integrate`]: trapezoidal integration and differentiation;
//! - [`window`]: contact windows from a force signal;
//! - [`process`]: processing steps on channels, and their mean or sum;
//! - [`loader`]: channels from test files: open, select, scale, combine, with notes;
//! - [`pipeline`]: repeatable processing of test files (TOML), momentum balance;
//! - [`rating`]: ISO/TS 18571 objective rating of a model's signal against a test's.
//!
//! ```
//! use bumpsim_signal::filter::{Cfc, CfcStandard};
//! let cfc = Cfc::new(1000.0, CfcStandard::SaeJ211).unwrap();
//! assert!((cfc.standard.factor() - 2.0775).abs() < 1e-12);
//! ```

pub mod filter;
pub mod integrate;
pub mod loader;
pub mod pipeline;
pub mod process;
pub mod rating;
pub mod window;

pub use filter::{Butterworth, Cfc, FilterError};
pub use pipeline::{Pipeline, PipelineError, PipelineResult};
pub use process::{ProcessError, Step};
pub use rating::{Rating, RatingError, rate, rate_histories};
pub use window::ContactWindow;

/// The types most signal processing needs (the facade globs it).
pub mod prelude {
    pub use crate::filter::{Butterworth, Cfc, FilterError};
    pub use crate::pipeline::{Pipeline, PipelineError, PipelineResult};
    pub use crate::process::ProcessError;
    pub use crate::rating::{Rating, RatingError};
    pub use crate::window::ContactWindow;
}
