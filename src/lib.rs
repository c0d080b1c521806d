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
//! | [`estimate`] | bumpsim-estimate | the estimation layer under both cars: bounded LM, staged multi-start, uncertainty, fit %, reduced-model advice |
//! | [`ident`] | bumpsim-ident | identification of an MSD model from load cases |
//! | [`impact`] | bumpsim-impact | bumpers, impacts, presets, synthetic tests, mass reduction |
//! | [`doe`] | bumpsim-doe | designs, regression, prediction, stiffness, reachable regions |
//! | [`export`] | bumpsim-export | LS-DYNA and CalculiX decks |
//! | [`planar`] | bumpsim-planar | the planar car with yaw: angled, offset, corner and pole impacts |
//! | [`fe`] | bumpsim-fe | a parametric bumper coupled to the MSD car, run in CalculiX or written for LS-DYNA |
//! | [`verdict`] | bumpsim-verdict | low-speed protocols (49 CFR 581, CMVSS 215, UN R42, RCAR, IIHS), damageability verdicts with margins, pulse metrics, bumper targets |
//! | `report` | bumpsim-report | SVG plots and self-contained HTML reports (feature `report`) |
//! | `campaign` | bumpsim-campaign | campaigns of FE runs: templates, local and Slurm executors, collection (feature `campaign`) |
//! | `view` | bumpsim-view | tests and results in the browser: a local read-only server or one self-contained page (feature `view`) |
//!
//! and [`prelude`] brings the main types of all of them into scope. Units
//! are SI throughout (kg, m, s, N). `examples/identify.rs` runs the main job
//! end to end: `cargo run --example identify`.
//!
//! **Features** (all on by default except `png`): `report` (plots and HTML
//! reports: plotters and its fonts), `campaign` (FE campaigns; builds the
//! report crate too), `view` (the browser viewer: a small HTTP server),
//! `zip` (ISO-MME tests packed as `.zip`) and `png`
//! (`LinePlot::png`: plotters' bitmap backend and PNG encoder).
//! `default-features = false` keeps the models, solvers and decks only.
//!
//! ```
//! use bumpsim::prelude::*;
//! // a 2-DOF car: masses (kg), dampers (N s/m), springs (N/m)
//! let car = MsdModel::new(vec![300.0, 900.0], vec![4e3], vec![8e5]).unwrap();
//! assert_eq!(car.dof(), 2);
//! ```
//!
//! The prelude reaches across the crates: the thesis's 3-DOF car as an
//! LS-DYNA include in mm-s-t units, and the parametric FE bumper's settings.
//!
//! ```
//! use bumpsim::prelude::*;
//! let car = MsdModel::new(vec![1.8, 74.8, 1670.0], vec![6.46e6, 1.97e5], vec![4.75e5, 5.0e5])?;
//! let options = LsDynaOptions { id_offset: 900_000, ..Default::default() };
//! let deck = lsdyna_include(&car, &options)?;
//! assert!(deck.contains("*ELEMENT_DISCRETE"));
//! let run = LsDynaRun { units: UnitSystem::MmSTonne, duration: 0.08, output_interval: 1e-4 };
//! assert_eq!(run.units.symbols()[1], "mm");
//! # #[cfg(feature = "report")] // `Series` is the plot's, not ambiguous
//! # let _: Series = Series::new("F", vec![0.0, 1e-3], vec![0.0, 1e3], Style::Solid);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

#![forbid(unsafe_code)]

#[cfg(feature = "campaign")]
pub use bumpsim_campaign as campaign;
pub use bumpsim_core as core;
pub use bumpsim_doe as doe;
#[cfg(feature = "report")]
pub use bumpsim_engine as engine;
pub use bumpsim_estimate as estimate;
pub use bumpsim_export as export;
pub use bumpsim_fe as fe;
pub use bumpsim_ident as ident;
pub use bumpsim_impact as impact;
pub use bumpsim_io as io;
pub use bumpsim_planar as planar;
#[cfg(feature = "report")]
pub use bumpsim_report as report;
pub use bumpsim_signal as signal;
pub use bumpsim_verdict as verdict;
#[cfg(feature = "view")]
pub use bumpsim_view as view;

/// The main types of every bumpsim crate: each crate's own prelude, globbed
/// (polars' layout). Names two crates would share are aliased in their
/// preludes (`PlanarSettings`, `ImpactOptions`, `MassReduction`,
/// `ResidualSeries`, `DoeModelError`, `CampaignSpec`).
pub mod prelude {
    #[cfg(feature = "campaign")]
    pub use bumpsim_campaign::prelude::*;
    pub use bumpsim_core::prelude::*;
    pub use bumpsim_doe::prelude::*;
    pub use bumpsim_estimate::prelude::*;
    pub use bumpsim_export::prelude::*;
    pub use bumpsim_fe::prelude::*;
    pub use bumpsim_ident::prelude::*;
    pub use bumpsim_impact::prelude::*;
    pub use bumpsim_io::prelude::*;
    pub use bumpsim_planar::prelude::*;
    #[cfg(feature = "report")]
    pub use bumpsim_report::prelude::*;
    pub use bumpsim_signal::prelude::*;
}
