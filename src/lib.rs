//! bumpsim: a toolkit for car-bumper engineers — crash-test signal
//! processing, identification of a lumped mass-spring-damper (MSD) car model
//! from several load cases, impact simulation with a bumper characteristic,
//! mass reduction, Design of Experiments and export to FE decks.
//!
//! This crate gathers the workspace's library crates under one name:
//!
//! | module | crate | what |
//! |---|---|---|
//! | [`core`] | bumpsim-core | units, sampled series, the MSD model, discretisation, simulation |
//! | [`io`] | bumpsim-io | CSV with unit headers, car TOML, ISO-MME, NHTSA EV5 |
//! | [`signal`] | bumpsim-signal | CFC and Butterworth filters, integration, windows, pipelines |
//! | [`ident`] | bumpsim-ident | identification of an MSD model from load cases |
//! | [`impact`] | bumpsim-impact | bumpers, impacts, presets, synthetic tests, mass reduction |
//! | [`doe`] | bumpsim-doe | designs, regression, prediction, stiffness, reachable regions |
//! | [`export`] | bumpsim-export | LS-DYNA and CalculiX decks |
//! | [`planar`] | bumpsim-planar | the planar car with yaw: angled, offset, corner and pole impacts |
//! | [`report`] | bumpsim-report | SVG plots and self-contained HTML reports |
//! | [`campaign`] | bumpsim-campaign | campaigns of FE runs: templates, local and Slurm executors, collection |
//!
//! and [`prelude`] brings the main types of all of them into scope. Units
//! are SI throughout (kg, m, s, N). `examples/identify.rs` runs the main job
//! end to end: `cargo run --example identify`.
//!
//! ```
//! use bumpsim::prelude::*;
//! // a 2-DOF car: masses (kg), dampers (N s/m), springs (N/m)
//! let car = MsdModel::new(vec![300.0, 900.0], vec![4e3], vec![8e5]).unwrap();
//! assert_eq!(car.dof(), 2);
//! ```

#![forbid(unsafe_code)]

pub use bumpsim_campaign as campaign;
pub use bumpsim_core as core;
pub use bumpsim_doe as doe;
pub use bumpsim_export as export;
pub use bumpsim_ident as ident;
pub use bumpsim_impact as impact;
pub use bumpsim_io as io;
pub use bumpsim_planar as planar;
pub use bumpsim_report as report;
pub use bumpsim_signal as signal;

/// The main types of every bumpsim crate.
pub mod prelude {
    pub use bumpsim_campaign::spec::Spec as CampaignSpec;
    pub use bumpsim_core::prelude::*;
    pub use bumpsim_doe::{Design, DesignKind, DesignOptions, Factor, Fit, ModelFile};
    pub use bumpsim_export::{CalculixOptions, LsDynaOptions, UnitSystem};
    pub use bumpsim_ident::{Identification, LoadCase, Settings, Study, identify};
    pub use bumpsim_impact::{Bumper, ImpactResult, Preset, Scenario};
    pub use bumpsim_io::{Car, TestData};
    pub use bumpsim_planar::{PlanarCar, PlanarResult, Striker};
    pub use bumpsim_report::{Html, LinePlot};
    pub use bumpsim_signal::{Cfc, Pipeline};
}
