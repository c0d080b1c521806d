//! What a car model answers the engine (issue 46 item 1): the requests
//! ([`ImpactRequest`]) and the trait a model implements in its own module
//! ([`CarModel`]); the registry of the models is [`crate::registry`]. No
//! equations.

use crate::{EngineError, Outcome};
use bumpsim_io::kind::ModelKind;
use std::path::Path;

/// `impact` as a front end names it, its arguments converted (SI).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ImpactRequest<'a> {
    /// The car file.
    pub car: Option<&'a Path>,
    /// A bumper file (`--bumper`; only the linear chain takes one).
    pub bumper: Option<&'a Path>,
    /// A load-case preset of the table of tests.
    pub case: Option<&'a str>,
    /// A pendulum of this mass, kg, hits the car at rest.
    pub pendulum: Option<f64>,
    /// The car hits a rigid barrier.
    pub barrier: bool,
    /// Impact speed, m/s (default: the preset's).
    pub speed: Option<f64>,
    /// The options of the planar faces (`--angle`, `--overlap`, `--side`,
    /// `--pole`, `--width`) that were given, as the user typed them.
    pub faces: &'a [&'a str],
    /// The car's uncertainty file (`--uncertainty`).
    pub uncertainty: Option<&'a Path>,
    /// Draw the report's pages too.
    pub report: bool,
}

impl<'a> ImpactRequest<'a> {
    /// The car file, needed by every model.
    pub fn car_path(&self) -> Result<&'a Path, EngineError> {
        self.car.ok_or_else(|| EngineError::Unsupported {
            option: "--car".into(),
            reason: "a car file is needed".into(),
        })
    }

    /// Refuses the options a model of `what` has no use for (a bumper file,
    /// the planar faces, the car's uncertainty), each by name.
    pub fn refuse_extras(&self, what: &str) -> Result<(), EngineError> {
        let refuse = |option: String, reason: &str| {
            Err(EngineError::Unsupported {
                option,
                reason: format!("{what} {reason}"),
            })
        };
        if self.bumper.is_some() {
            return refuse(
                "--bumper".into(),
                "carries its crush zone in its own file (a [front] link); leave --bumper out",
            );
        }
        if let Some(option) = self.faces.first() {
            return refuse(
                (*option).into(),
                "runs into a flat rigid barrier along its axis; faces other than flat need a planar car",
            );
        }
        if self.uncertainty.is_some() {
            return refuse(
                "--uncertainty".into(),
                "has no uncertainty propagation yet; leave --uncertainty out",
            );
        }
        Ok(())
    }
}

/// A car model as the engine runs it: what each command asks of it.
pub trait CarModel: Sync {
    /// Its kind in the registry ([`ModelKind`]), the one its files declare.
    fn kind(&self) -> ModelKind;

    /// `impact`: the car of `request.car` in the request's scenario.
    fn impact(&self, request: &ImpactRequest<'_>) -> Result<Outcome, EngineError>;
}
