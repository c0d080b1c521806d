//! The registry of the car models the engine runs and the requests they
//! answer (issue 46 item 1). A model implements [`CarModel`] in its own
//! module and adds one line to [`registered`]; a front end asks
//! [`bumpsim_io::kind::ModelKind::of`] for a file's kind once and hands
//! the request to [`impact`], which finds the model here. No equations.

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

/// The models the engine runs: one registration line each.
pub fn registered() -> &'static [&'static dyn CarModel] {
    &[&crate::links::Links]
}

/// The registered model of `kind`.
pub fn model(kind: ModelKind) -> Result<&'static dyn CarModel, EngineError> {
    registered()
        .iter()
        .copied()
        .find(|m| m.kind() == kind)
        .ok_or(EngineError::NotRegistered {
            command: "impact",
            kind: kind.name(),
        })
}

/// `impact` of a car of `kind` (the front end asked the file's kind).
pub fn impact(kind: ModelKind, request: &ImpactRequest<'_>) -> Result<Outcome, EngineError> {
    model(kind)?.impact(request)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_registered_model_has_its_own_kind_and_the_others_are_refused() {
        let kinds: Vec<ModelKind> = registered().iter().map(|m| m.kind()).collect();
        assert_eq!(kinds, vec![ModelKind::Links]);
        let refused = impact(ModelKind::Planar, &ImpactRequest::default()).unwrap_err();
        assert!(
            refused.to_string().starts_with("impact: a planar car"),
            "{refused}"
        );
    }
}
