//! bumpsim-doe: Design of Experiments relating MSD parameters to car
//! stiffness and mass (thesis ch. 3.5, paper C, spec §7).
//!
//! - [`design`]: full and fractional factorials (with resolution), central
//!   composite, Latin hypercube and random designs;
//! - [`data`]: design and response tables (CSV);
//! - [`regression`]: least squares with standard errors, intervals, R², Q², ANOVA;
//! - [`model`]: model files and prediction with intervals;
//! - [`stiffness`]: the slope of a force–displacement curve;
//! - [`reachable`]: the reachable region of two linear responses;
//! - [`table_fit`]: the regression of a whole table (`doe fit`, campaigns);
//! - [`text`]: human-readable summaries of fits;
//! - [`weighted`]: regression on identified parameters with their standard
//!   errors (τ² by REML, weighted least squares).
//!
//! A 2² factorial, its runs in physical units, a fitted main-effect model
//! and a prediction at the centre:
//!
//! ```
//! use bumpsim_doe::{DesignKind, DesignOptions, Factor, design};
//! use bumpsim_doe::regression::{fit, terms};
//! let factors: Vec<Factor> = ["k:1e5:3e5", "m:1000:1400"]
//!     .iter()
//!     .map(|s| s.parse().unwrap())
//!     .collect();
//! let names = ["k", "m"];
//! let (d, _) = design::make(DesignKind::Full, &names, &DesignOptions::default()).unwrap();
//! assert_eq!(d.runs.len(), 4);
//! // a response exactly linear in the coded factors: y = 10 + 2 zk − 3 zm
//! let y: Vec<f64> = d.runs.iter().map(|z| 10.0 + 2.0 * z[0] - 3.0 * z[1]).collect();
//! let names: Vec<String> = names.iter().map(|s| s.to_string()).collect();
//! let f = fit(&d.runs, &y, &terms(2, false, false), &names).unwrap();
//! assert!((f.coefficients[1] - 2.0).abs() < 1e-12 && (f.coefficients[2] + 3.0).abs() < 1e-12);
//! assert!(d.to_csv(&factors, &d.order(false, 1)).starts_with("run,standard order,k,m"));
//! ```

pub mod data;
pub mod design;
pub mod model;
pub mod reachable;
pub mod regression;
pub mod stiffness;
pub mod table_fit;
pub mod text;
pub mod weighted;

pub use data::{Data, DataError};
pub use design::{Design, DesignError, DesignKind, DesignOptions};
pub use model::{Factor, ModelError, ModelFile};
pub use reachable::LinearMap;
pub use regression::{Fit, RegressionError};
pub use stiffness::{Curve, Stiffness};

/// The types most DOE studies need (the facade globs it; the model file's
/// error is `DoeModelError`).
pub mod prelude {
    pub use crate::data::{Data, DataError};
    pub use crate::design::{Design, DesignError, DesignKind, DesignOptions};
    pub use crate::model::{Factor, ModelError as DoeModelError, ModelFile};
    pub use crate::regression::{Fit, RegressionError};
    pub use crate::stiffness::{Curve, Stiffness};
}
