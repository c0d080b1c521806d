//! `verdict` as one request: the car files' declared kinds
//! ([`ModelKind::of_path`] with [`Role::Car`]) pick the model that judges
//! them ([`crate::model::CarModel::verdict`]; today the planar car's,
//! [`crate::planar`]), and a held car becomes one end of the verdicts
//! through its model ([`end`]). No equations here: the tests, criteria and
//! margins are `bumpsim_verdict`'s.

use crate::held::HeldCar;
use crate::model::VerdictRequest;
use crate::registry::model;
use crate::{EngineError, Outcome};
use bumpsim_io::kind::{ModelKind, Role};

/// `verdict` of the request's cars: every end's car file is of one kind,
/// whose model judges them.
pub fn verdict(request: &VerdictRequest<'_>) -> Result<Outcome, EngineError> {
    let mut kinds = Vec::new();
    for (car, _) in request.ends {
        kinds.push((ModelKind::of_path(car, Role::Car)?, *car));
    }
    let Some(&(kind, _)) = kinds.first() else {
        return Err(EngineError::Needed {
            what: "--car FILE is needed: a car file with a [damageability] table, one per end",
        });
    };
    if let Some((other, path)) = kinds.iter().find(|(k, _)| *k != kind) {
        return Err(EngineError::Refused {
            path: path.to_path_buf(),
            reason: format!(
                "a {} car among {} cars: the ends of one car are of one model",
                other.name(),
                kind.name()
            ),
        });
    }
    model(judge(kind), "verdict")?.verdict(request)
}

/// One end of a car for the verdicts: the held car with its limits, by
/// its model.
pub fn end(car: &HeldCar) -> Result<bumpsim_verdict::prelude::CarEnd, EngineError> {
    model(car.kind(), "verdict")?.end(car)
}

/// The model that judges a car file of `kind`: a file the registry reads
/// as the 1-D chain's (its fallback, also for a planar car file with a
/// mistake) is judged by the model with verdicts, whose reader then says
/// what is wrong with it; any other kind by its own model.
fn judge(kind: ModelKind) -> ModelKind {
    let judges = |k: ModelKind| {
        crate::registry::registered()
            .iter()
            .any(|m| m.kind() == k && m.judges())
    };
    let fallback = crate::registry::registered()
        .iter()
        .map(|m| m.kind())
        .find(|&k| judges(k));
    match (kind, fallback) {
        (ModelKind::Chain, Some(judge)) if !judges(kind) => judge,
        _ => kind,
    }
}
