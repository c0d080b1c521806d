//! bumpsim-impact: concept studies without an FE code (papers A, B; spec §5–6).
//!
//! - [`bumper`]: three-part and tabulated bumper characteristics with elastic unloading;
//! - [`impact`]: impactor or barrier impacts on MSD cars by central differences;
//! - [`document`]: the JSON every front end writes of an impact;
//! - [`presets`]: named load cases with their sources;
//! - [`uncertainty`], [`prediction`], [`propagation`]: a car's uncertainty carried
//!   through its run (spreads, bands, Sobol' indices);
//! - [`reduction`]: the reduced point mass of paper A and its sweeps;
//! - [`synth`]: synthetic pendulum test series with a measurement chain;
//! - [`barrier_series`]: synthetic rigid-barrier test series of a car with nonlinear links;
//! - [`text`]: summaries and CSV of results.
//!
//! A 1000 kg pendulum at 4 km/h into a 2-DOF car behind paper A's
//! three-part bumper (ramp 1 kN/mm up to a 40 kN plateau, elastic unloading
//! at 5 kN/mm):
//!
//! ```
//! use bumpsim_core::MsdModel;
//! use bumpsim_impact::{Bumper, Scenario};
//! use bumpsim_impact::impact::{Options, simulate};
//! let car = MsdModel::new(vec![100.0, 1200.0], vec![2e4], vec![5e5]).unwrap();
//! let bumper = Bumper::three_part(1e6, 4e4, 5e6).unwrap();
//! let pendulum = Scenario::Impactor { mass: 1000.0, speed: 4.0 / 3.6 };
//! let r = simulate(&car, &bumper, pendulum, &Options::default()).unwrap();
//! assert!(r.peak_force > 0.0 && r.peak_force <= 4e4 * (1.0 + 1e-9)); // N
//! assert!(r.energy.relative_error.abs() < 1e-2);
//! ```

pub mod barrier_series;
pub mod bumper;
pub mod document;
pub mod impact;
pub mod prediction;
pub mod presets;
pub mod propagation;
pub mod reduction;
pub mod synth;
pub mod text;
pub mod uncertainty;

pub use bumper::{Bumper, BumperError};
pub use impact::{ImpactError, ImpactResult, Scenario};
pub use presets::Preset;
pub use reduction::{Criterion, Reduction, ReductionError};

/// The types most impact studies need (the facade globs it; the mass
/// reduction's result is `MassReduction`, the impact's options
/// `ImpactOptions`).
pub mod prelude {
    pub use crate::bumper::{Bumper, BumperError};
    pub use crate::document::ImpactSummary;
    pub use crate::impact::{ImpactError, ImpactResult, Options as ImpactOptions, Scenario};
    pub use crate::presets::Preset;
    pub use crate::reduction::{Criterion, Reduction as MassReduction, ReductionError};
}
