//! The engine (issue 46 item 1, "models that plug in"): each command as one
//! library request that reads its inputs, picks the car model once from the
//! file's declared kind ([`bumpsim_io::kind::ModelKind`]) and runs it. A
//! request answers with an [`Outcome`] — the text to print, the warnings,
//! the JSON document, the CSV histories and the report pages — so that a
//! front end (the command line, the Python module) only converts its
//! arguments, prints and writes.
//!
//! A model plugs in by implementing [`model::CarModel`] in its own module
//! (today the chain with nonlinear links, [`links`], and the planar car,
//! [`planar`]) and by one line in
//! the registry [`registry::registered`]; the front ends name no model for it.
//! docs/architecture.md walks through adding one.
//!
//! The engine sits on floor 8 (above the models, the verdicts and the
//! report, below the front ends) and holds no physics of its own: the
//! mechanisms and their energy balances are the models' crates'.

#![deny(missing_docs)]

pub mod chain;
pub mod deck;
pub mod error;
pub mod held;
pub mod identify;
pub mod links;
pub mod model;
pub mod outcome;
pub mod planar;
pub mod registry;
pub mod sizes;
pub mod synth;
pub mod uncertain;
pub mod verdict;

pub use error::EngineError;
pub use held::HeldCar;
pub use model::{
    CarModel, Deck, End, ExportRequest, Face, ForceLoad, IdentifyRequest, ImpactRequest,
    PosteriorOptions, PredictRequest, Progress, Setup, Side, Solver, UncertaintyOptions,
    VerdictRequest, VerdictUncertainty,
};
pub use outcome::{Outcome, Report};
pub use registry::{export, identify, impact, predict, registered};
