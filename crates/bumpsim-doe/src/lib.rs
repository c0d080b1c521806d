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
//! - [`text`]: human-readable summaries of fits.

pub mod data;
pub mod design;
pub mod model;
pub mod reachable;
pub mod regression;
pub mod stiffness;
pub mod text;
