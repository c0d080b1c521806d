//! bumpsim-planar: the planar car of spec §9 (thesis ch. 5, paper A's future work).
//!
//! Angled, offset, corner and pole impacts turn the car, so the 1-D chain of
//! spec §2 cannot describe them. This crate models the car in the ground plane
//! (x forward towards the struck bumper, y left, yaw ψ counter-clockwise seen
//! from above):
//!
//! - [`car`]: the planar car — rigid body, left/right MSD chains, a segmented
//!   bumper beam, tyres — validated at construction;
//! - [`file`](mod@file): the planar car TOML file;
//! - [`forward`]: the forward prediction of a whole test (car, bumper, striker) against its measurement;
//! - [`cell_force`]: a wall's load cells one by one in a forward run;
//! - [`bands`]: the 90 % predictive bands of the held-out replays and forward predictions;
//! - [`document`]: the JSON every front end writes (impact, identification, prediction);
//! - [`drive`](mod@drive): the car driven by given forces (test replay, FE reference);
//! - [`identify`](mod@identify): the planar car identified from several load cases;
//! - [`link_verdict`]: which side-member links the data want, linear or nonlinear
//!   (held-out forward runs and replays, the BIC);
//! - [`cases`]: load cases from test channels (conditioning, integration, window);
//! - [`striker`]: rigid planes at an angle with an overlap, poles, and pendulums
//!   carrying either face;
//! - [`simulate`](mod@simulate): the central-difference integrator and [`simulate()`];
//! - [`result`]: histories, energy and momentum balances;
//! - [`picture`]: the top view of car and striker at one instant;
//! - [`presets`]: RCAR and IIHS asymmetric load cases with their sources;
//! - [`barrier`]: the RCAR bumper barrier's curved face and energy absorber;
//! - [`export`]: the car as an LS-DYNA include and a CalculiX deck;
//! - [`sensitivity`]: the replay over dual numbers (the identification's exact Jacobian);
//! - [`synth`]: synthetic asymmetric test series (load-cell wall, sills);
//! - [`series`]: the planar series file of `bumpsim synth` and the study it writes;
//! - [`study`]: the planar study file of `bumpsim identify`;
//! - [`text`]: the summary with units and the CSV histories;
//! - [`tyre`]: the tyre laws' forces (rolling with relaxation, sliding).
//!
//! ```
//! use bumpsim_core::model::MsdModel;
//! use bumpsim_impact::bumper::Bumper;
//! use bumpsim_planar::car::{Layout, PlanarCar};
//! use bumpsim_planar::striker::{Face, Side, Striker};
//! use bumpsim_planar::simulate::{Settings, simulate};
//! let chain = MsdModel::new(vec![10.0, 1200.0], vec![2e3], vec![2e6]).unwrap();
//! let bumper = Bumper::three_part(1.5e6, 60e3, 6e6).unwrap();
//! let car = PlanarCar::symmetric(&chain, &bumper, &Layout::default()).unwrap();
//! let rcar = Face::Plane { angle: 10f64.to_radians(), overlap: 0.4, side: Side::Left };
//! let r = simulate(&car, &Striker::barrier(rcar, 15.0 / 3.6), &Settings::default()).unwrap();
//! assert!(r.peak_yaw_rate > 0.0);                  // the left corner is struck: yaw to the left
//! assert!(r.energy.relative_error < 1e-3);
//! ```

pub mod bands;
pub mod barrier;
pub mod bumper_fit;
pub mod car;
pub mod cases;
pub mod cell_force;
pub mod document;
pub mod drive;
mod dynamics;
mod echo;
pub mod export;
pub mod file;
pub mod forward;
pub mod identify;
pub mod link_verdict;
pub mod picture;
pub mod presets;
pub mod result;
pub mod sensing;
pub mod sensitivity;
pub mod series;
pub mod simulate;
pub mod striker;
pub mod study;
pub mod study_priors;
pub mod synth;
pub mod text;
pub mod tyre;
pub mod uncertainty;

pub use car::{PlanarCar, PlanarError};
pub use result::PlanarResult;
pub use simulate::{Settings, simulate};
pub use striker::{Face, Motion, Side, Striker};

/// The types most planar studies need (the facade globs it; the
/// integration settings are `PlanarSettings`, the identification's setup
/// `PlanarSetup`).
pub mod prelude {
    pub use crate::car::{Layout, PlanarCar, PlanarError};
    pub use crate::identify::{PlanarIdentification, Setup as PlanarSetup};
    pub use crate::result::PlanarResult;
    pub use crate::simulate::Settings as PlanarSettings;
    pub use crate::striker::{Face, Motion, Side, Striker};
    pub use crate::study::PlanarStudy;
}
