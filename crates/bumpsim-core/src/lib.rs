//! bumpsim-core: units, sampled signals, the n-DOF chain mass-spring-damper
//! car model of Isaksson (2006, thesis ch. 3.3), its state-space form, three
//! discretisations and the simulation of a sampled force history.
//!
//! Everything is SI `f64`: kg, m, s, N, N/m, N·s/m, J. The modules:
//!
//! - [`units`]: unit parsing and formatting, `name [unit]` labels;
//! - [`files`]: input files read whole within bounds (regular files only);
//! - [`fixed_width`]: the words of solver text whose numbers touch;
//! - [`series`]: uniformly sampled signals;
//! - [`channel`]: a measured channel (series, code, name, unit, metadata);
//! - [`model`]: the validated chain model and its parameter vector;
//! - [`state_space`]: A, B and the elastic modes;
//! - [`discrete`]: zoh, foh and taylor1 discretisations and the update loop
//!   (Φ and Γ of the exact holds from one balanced exponential);
//! - [`dual`]: dual numbers, exact first derivatives of code written over [`dual::Real`];
//! - [`sensitivity`]: one output and its exact parameter sensitivities;
//! - [`modal`]: the same zoh output and sensitivities in modal coordinates
//!   (identification's fast form);
//! - [`energy`]: exact per-step energy integrals;
//! - [`leapfrog`]: the one explicit integrator of every impact (1-D and planar);
//! - [`simulate`]: responses with forces and energies;
//! - [`link`]: nonlinear links (progressive, yielding, plastic) and their history;
//! - [`chain`]: the chain with nonlinear links, integrated by [`leapfrog`].
//!
//! ```
//! use bumpsim_core::prelude::*;
//! let car = MsdModel::new(vec![150.0, 500.0, 800.0], vec![1e2, 2e5], vec![5e5, 5e5]).unwrap();
//! let force = UniformSeries::new(0.0, 1e-4, vec![1000.0; 500]).unwrap();
//! let response = simulate(&car, &force, Method::Zoh, &InitialState::Rest).unwrap();
//! assert!(response.energy.relative_error() < 1e-9);
//! ```

pub mod chain;
pub mod channel;
pub mod discrete;
pub mod dual;
pub mod energy;
mod exponential;
pub mod files;
pub mod fixed_width;
pub mod leapfrog;
pub mod link;
pub mod modal;
pub mod model;
pub mod names;
pub mod sensitivity;
pub mod series;
pub mod simulate;
pub mod state_space;
pub mod units;

pub use channel::Channel;
pub use discrete::{DiscreteModel, Method};
pub use model::MsdModel;
pub use series::UniformSeries;
pub use simulate::{InitialState, Response, Simulator};
pub use units::{Dimension, Unit};

/// The types most programs need.
pub mod prelude {
    pub use crate::channel::Channel;
    pub use crate::discrete::{DiscreteModel, Method, Substeps};
    pub use crate::model::MsdModel;
    pub use crate::series::UniformSeries;
    pub use crate::simulate::{InitialState, Response, Simulator, simulate};
    pub use crate::units::{Dimension, Unit};
}
