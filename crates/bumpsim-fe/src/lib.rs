//! bumpsim-fe: the thesis's FE step, open and runnable — a bumper mesh
//! coupled to the MSD car (spec §8, thesis ch. 3.3: "the mesh of the bumper
//! system is coupled to a simplified model of the car"), run in CalculiX and
//! read back into the terms of `bumpsim impact`.
//!
//! - [`bumper`]: the parametric bumper (box-section beam, two crash boxes,
//!   elastic or elastic–plastic materials) and its equivalent
//!   characteristic against a flat face;
//! - [`deck`]: the coupled deck (bumper, contact, barrier or pendulum, and
//!   the car of `bumpsim export calculix` with its `*EQUATION` coupling);
//! - [`lsdyna`]: the same coupled model as an LS-DYNA keyword deck;
//! - [`run`]: runs `ccx`, reads the `.dat` file, and gives force,
//!   compression, contact time, energies and an energy balance as an
//!   [`bumpsim_impact::impact::ImpactResult`].
//!
//! ```no_run
//! use bumpsim_core::model::MsdModel;
//! use bumpsim_fe::{bumper::BumperMesh, run::{FeRun, run}};
//! use bumpsim_impact::impact::Scenario;
//! let car = MsdModel::new(vec![30.0, 250.0, 1170.0], vec![8e3, 2.5e4], vec![1.5e6, 6e5]).unwrap();
//! let mesh = BumperMesh::read("examples/fe/bumper-elastic.toml".as_ref()).unwrap();
//! let settings = FeRun::new(mesh, car, Scenario::Barrier { speed: 2.2 }, "fe-work".into());
//! let result = run(&settings).unwrap();
//! println!("peak force {} N", result.impact.peak_force);
//! ```

pub mod bumper;
pub mod deck;
pub mod lsdyna;
pub mod run;
pub mod text;

/// The main types, for `use bumpsim_fe::prelude::*` (the facade's prelude
/// globs it).
pub mod prelude {
    pub use crate::FeError;
    pub use crate::bumper::BumperMesh;
    pub use crate::lsdyna::{LsDynaRun, lsdyna_deck};
    pub use crate::run::{FeResult, FeRun};
}

use bumpsim_core::units::short;

/// Why an FE run cannot be set up, run or read.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum FeError {
    /// A parameter out of range.
    #[error("{name} = {}: expected {expected}", short(*value))]
    Parameter {
        /// The parameter, as in the bumper file.
        name: String,
        /// The value given.
        value: f64,
        /// What is allowed.
        expected: String,
    },
    /// A file that cannot be read or parsed.
    #[error("{path}: {message}")]
    File {
        /// The file.
        path: String,
        /// What is wrong.
        message: String,
    },
    /// The car deck cannot be written.
    #[error("the car deck: {0}")]
    Export(#[from] bumpsim_export::ExportError),
    /// The solver did not run or failed.
    #[error("{solver}: {message}")]
    Solver {
        /// The solver command.
        solver: String,
        /// What happened (with the log file to read).
        message: String,
    },
    /// A speed or pendulum mass outside the ranges every impact keeps
    /// (`bumpsim_impact::impact::SPEED_RANGE`, `MASS_RANGE`).
    #[error("{0}")]
    Scenario(bumpsim_impact::impact::ImpactError),
    /// The duration estimate from the equivalent characteristic failed.
    #[error("estimating the contact time with the equivalent characteristic: {0}")]
    Estimate(String),
}
