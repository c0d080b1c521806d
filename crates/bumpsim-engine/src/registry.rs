//! The registry of the car models the engine runs (issue 46 item 1): a
//! model implements [`CarModel`] in its own module and adds one line to
//! [`registered`]; a front end asks [`bumpsim_io::kind::ModelKind::of`] for
//! a file's kind once and hands the request to [`impact`], which finds the
//! model here. No equations.

use crate::model::{CarModel, ImpactRequest};
use crate::{EngineError, Outcome};
use bumpsim_io::kind::ModelKind;

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
