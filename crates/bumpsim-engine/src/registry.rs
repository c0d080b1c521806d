//! The registry of the car models the engine runs (issue 46 item 1): a
//! model implements [`CarModel`] in its own module and adds one line to
//! [`registered`]; a front end asks [`bumpsim_io::kind::ModelKind::of`] for
//! a file's kind once and hands the request to [`impact`], [`identify`] or
//! [`predict`], which find the model here. No equations.

use crate::model::{CarModel, Deck, ExportRequest, IdentifyRequest, ImpactRequest, PredictRequest};
use crate::{EngineError, Outcome};
use bumpsim_io::kind::{ModelKind, Role};

/// The models the engine runs: one registration line each.
pub fn registered() -> &'static [&'static dyn CarModel] {
    &[
        &crate::chain::Chain,
        &crate::links::Links,
        &crate::planar::Planar,
    ]
}

/// The registered model of `kind`, for `command`.
pub fn model(kind: ModelKind, command: &'static str) -> Result<&'static dyn CarModel, EngineError> {
    registered()
        .iter()
        .copied()
        .find(|m| m.kind() == kind)
        .ok_or(EngineError::NotRegistered {
            command,
            kind: kind.name(),
        })
}

/// `impact` of a car of `kind` (the front end asked the file's kind).
pub fn impact(kind: ModelKind, request: &ImpactRequest<'_>) -> Result<Outcome, EngineError> {
    model(kind, "impact")?.impact(request)
}

/// `identify` of a study of `kind` (the front end asked the study's kind).
pub fn identify(kind: ModelKind, request: &IdentifyRequest<'_>) -> Result<Outcome, EngineError> {
    model(kind, "identify")?.identify(request)
}

/// `export` of a car of `kind` as a solver's deck.
pub fn export(kind: ModelKind, request: &ExportRequest<'_>) -> Result<Deck, EngineError> {
    model(kind, "export")?.export(request)
}

/// `predict`: the car file's and the study's kinds must agree; the study's
/// model replays it.
pub fn predict(request: &PredictRequest<'_>) -> Result<Outcome, EngineError> {
    let (car, study) = (request.car, request.study);
    let refused = |path: &std::path::Path, reason: String| EngineError::Refused {
        path: path.into(),
        reason,
    };
    match (
        ModelKind::of_path(car, Role::Car)?,
        ModelKind::of_path(study, Role::Study)?,
    ) {
        (ModelKind::Planar, ModelKind::Chain) => Err(refused(
            car,
            format!(
                "a planar car predicts a planar study (`[model] planar = ...`, docs/planar.md); {} is a chain study",
                study.display()
            ),
        )),
        (ModelKind::Chain, ModelKind::Planar)
            if ModelKind::of_path(car, Role::Result)? == ModelKind::Planar =>
        {
            Err(refused(
                car,
                format!(
                    "a planar identification's JSON (`identify --json`) holds the identified body, side chains and tyres but not the bumper beam (the start car's), so it is not a whole car: predict with the planar car file `bumpsim identify {} --car CAR.toml` writes",
                    study.display()
                ),
            ))
        }
        (ModelKind::Chain, ModelKind::Planar) => {
            // a planar car file with a mistake is not recognised as one:
            // its own error says more than "not a planar car"
            let needed = format!(
                "{}: a planar study needs a planar car (a car file with [body], docs/planar.md)",
                study.display()
            );
            bumpsim_planar::PlanarCar::read(car).map_err(|source| EngineError::PlanarIn {
                context: needed,
                source,
            })?;
            Err(refused(
                study,
                format!(
                    "a planar study needs a planar car (a car file with [body], docs/planar.md); {} is not one",
                    car.display()
                ),
            ))
        }
        (c, s) if c == s => model(s, "predict")?.predict(request),
        (c, s) => Err(refused(
            car,
            format!(
                "predict runs a chain, links or planar car on a study of its kind; a {} car (on the {} study {}) is not predicted yet",
                c.name(),
                s.name(),
                study.display()
            ),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_registered_model_has_its_own_kind_and_the_others_are_refused() {
        let kinds: Vec<ModelKind> = registered().iter().map(|m| m.kind()).collect();
        assert_eq!(
            kinds,
            vec![ModelKind::Chain, ModelKind::Links, ModelKind::Planar]
        );
        let request = IdentifyRequest {
            study: std::path::Path::new("study.toml"),
            starts: None,
            seed: None,
            report: false,
            posterior: None,
            sizes: None,
            sensitivity: false,
            car: false,
            progress: &crate::model::Unwatched,
        };
        // a links study reaches its model, which reads the (absent) study
        let refused = identify(ModelKind::Links, &request).unwrap_err();
        assert!(
            refused.to_string().starts_with("study.toml: cannot read"),
            "{refused}"
        );
    }
}
