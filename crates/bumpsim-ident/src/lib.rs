//! bumpsim-ident: one MSD car model from several load cases at once
//! (thesis ch. 3.4, paper B, spec §3).
//!
//! - [`case`]: load cases and the objective `F = Σ (x − x̂)²` (the model's
//!   residuals and exact Jacobian, handed to the estimation layer);
//! - [`settings`]: bounds, starts and solver, and their checks;
//! - [`estimate`]: the data-derived start and the identification;
//! - [`sizes`]: a study identified over its model sizes (the one loop of the front ends);
//! - [`crossval`], [`choice`]: leave-one-load-case-out cross-validation and
//!   the DOF table's recommendation with correlated residuals;
//! - [`priors`]: the stated priors (the test sheet's mass, each element
//!   near the start) and the study's `[priors]`; [`prior_fit`]: the fit with them;
//! - [`posterior`], [`whitened`]: the parameters' posterior (ensemble
//!   sampler) and its whitened likelihood;
//! - [`result`]: what an identification finds;
//! - [`error`]: why it cannot run;
//! - [`search`]: the starts: continuation across the DOF table;
//! - [`explore`]: predictions and the ±3 % sensitivity of the objective;
//! - [`links`]: the chain with yielding links (issue 46): its parameters,
//!   objective, identification and plastic sets;
//! - [`reduce`]: the simpler chain when a spring is undetermined;
//! - [`stats`]: standard errors, intervals, correlations, identifiability;
//! - [`document`]: the JSON every front end writes (identification, prediction);
//! - [`text`]: text tables of results (as `doe::text` and `impact::text`);
//! - [`study`]: study files (TOML) and the processing of their load cases.
//!
//! The search (bounded LM, the staged multi-start, polishing), the
//! uncertainty, fit % and reduced-model advice are the estimation layer's,
//! [`bumpsim_estimate`], shared with the planar car.
//!
//! Simulation, prediction and the identification Jacobian all run core's one
//! zoh discretisation ([`bumpsim_core::discrete::DiscreteModel`], with the
//! exact sensitivities of [`bumpsim_core::sensitivity`]), so `bumpsim
//! simulate`, `predict` and `identify` agree to the last bit.
//!
//! ```
//! use bumpsim_core::prelude::*;
//! use bumpsim_ident::case::LoadCase;
//! use bumpsim_ident::estimate::{Settings, identify};
//! let truth = MsdModel::new(vec![300.0, 900.0], vec![4e3], vec![8e5]).unwrap();
//! let force: Vec<f64> = (0..400).map(|k| 3e4 * (k as f64 * 0.0005 * 40.0).sin().max(0.0)).collect();
//! let mut case = LoadCase {
//!     name: "flat".into(), start: 0.0, step: 5e-4, force, measured: vec![], output_dof: 1,
//!     initial_velocity: 0.0, window: (0, 399), compare: Default::default(),
//! };
//! case.measured = case.simulate(&truth).unwrap();
//! let result = identify(&[case], &Settings::new(2, 4), &|| {}).unwrap();
//! assert!(result.cases[0].fit_percent > 99.9);
//! ```

pub mod case;
pub mod choice;
pub mod crossval;
pub mod document;
pub mod dofs;
pub mod error;
pub mod estimate;
pub mod explore;
pub mod links;
pub mod posterior;
pub mod prior_fit;
pub mod priors;
pub mod reduce;
pub mod result;
pub mod search;
pub mod settings;
pub mod sizes;
pub mod stats;
pub mod study;
pub mod text;
pub mod whitened;

pub use case::LoadCase;
pub use dofs::DofList;
pub use estimate::{IdentError, Identification, Settings, identify};
pub use study::{Study, StudyError};

/// The types most chain identifications need (the facade globs it).
pub mod prelude {
    pub use crate::case::LoadCase;
    pub use crate::document::IdentifyDocument;
    pub use crate::dofs::DofList;
    pub use crate::estimate::{IdentError, Identification, Settings, identify};
    pub use crate::study::{Study, StudyError};
}
