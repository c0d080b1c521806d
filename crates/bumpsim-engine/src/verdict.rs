//! `verdict` as one request: the car files' declared kinds
//! ([`ModelKind::of_path`] with [`Role::Car`]) pick the model that judges
//! them ([`crate::model::CarModel::verdict`]: the planar car's and the
//! links car's), whose verdict becomes the outcome here, once for
//! every front end (the command line prints and writes it, Python holds the
//! [`Judged`]); a held car becomes one end of the verdicts through its
//! model ([`end`]). No equations here: the tests, criteria and margins are
//! `bumpsim_verdict`'s.

use crate::held::HeldCar;
use crate::model::{End, Judged, VerdictRequest};
use crate::registry::model;
use crate::{EngineError, Outcome, Report};
use bumpsim_io::kind::{ModelKind, Role};
use bumpsim_verdict::{sensitivity, text};

/// `verdict` of the request's cars: what the model judged
/// ([`judged`]), as the text, the JSON document and the report.
pub fn verdict(request: &VerdictRequest<'_>) -> Result<Outcome, EngineError> {
    let Judged {
        verdict: v,
        region,
        indices,
    } = judged(request)?;
    let mut document = serde_json::json!({ "verdict": v, "target": region });
    // only with --sobol: the document of a plain verdict stays as Python's
    if let (Some(s), Some(fields)) = (&indices, document.as_object_mut()) {
        fields.insert("sensitivity".into(), serde_json::to_value(s)?);
    }
    let report = match request.report {
        true => {
            let (html, figures) =
                bumpsim_report::verdict::verdict_report(&v, region.as_ref(), indices.as_ref())?;
            Some(Report {
                html,
                figures,
                inputs: Vec::new(),
            })
        }
        false => None,
    };
    let mut printed = text::table(&v);
    if let Some(r) = &region {
        printed += &text::region(r);
    }
    if let Some(s) = &indices {
        printed += &sensitivity::table(s);
    }
    Ok(Outcome {
        text: printed,
        json: serde_json::to_string_pretty(&document)?,
        report,
        ..Outcome::default()
    })
}

/// The request's cars judged (the front ends that hold the verdict:
/// Python's `verdict`): every end's car is of one kind, whose model
/// judges them.
pub fn judged(request: &VerdictRequest<'_>) -> Result<Judged, EngineError> {
    let mut kinds = Vec::new();
    for end in request.ends {
        kinds.push(match end {
            End::File(car, _) => (ModelKind::of_path(car, Role::Car)?, *car),
            End::Held { kind, path, .. } => (*kind, *path),
        });
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
    model(car.kind(), "verdict")?.end(car.path(), car.text())
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
        .find(|m| m.judges() && m.judges_unmarked())
        .map(|m| m.kind());
    match (kind, fallback) {
        (ModelKind::Chain, Some(judge)) if !judges(kind) => judge,
        _ => kind,
    }
}

#[cfg(test)]
mod tests {
    use super::verdict;
    use crate::held::HeldCar;
    use crate::model::{End, Unwatched, VerdictRequest};
    use bumpsim_io::kind::ModelKind;
    use std::path::{Path, PathBuf};

    fn examples() -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
    }

    #[test]
    fn a_held_planar_car_reads_back_to_the_same_car_through_its_model() {
        let saloon = examples().join("planar/saloon.toml");
        let held = HeldCar::read(&saloon, ModelKind::Planar).unwrap();
        assert_eq!(held.kind(), ModelKind::Planar);
        // the file is in mm; its canonical form in SI reads back the same
        let again = HeldCar::parse(held.to_toml(), &saloon, ModelKind::Planar).unwrap();
        assert_ne!(again.text(), held.text());
        assert_eq!(again, held);
        // a 1-D car file held as a planar car: the planar reader refuses it
        let chain = examples().join("simulate/car-3dof.toml");
        let refused = HeldCar::read(&chain, ModelKind::Planar).unwrap_err();
        assert!(refused.to_string().contains("car-3dof.toml"), "{refused}");
    }

    #[test]
    fn a_links_car_and_the_planar_car_are_judged_by_their_models() {
        let dir = std::env::temp_dir().join(format!("bumpsim-engine-held-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let links = dir.join("links.toml");
        let text = "kind = \"links\"\nmasses = [2.0, 900.0]\ndampers = [0.0]\n[[links]]\ncurve = \"linear\"\nstiffness = \"1000 N/mm\"\n";
        std::fs::write(&links, text).unwrap();
        let ends = [End::File(links.as_path(), None)];
        let protocols = vec!["part581".to_string()];
        let request = VerdictRequest {
            ends: &ends,
            protocols: &protocols,
            market: Default::default(),
            margin: 0.0,
            target: false,
            sequence: false,
            asi_method: bumpsim_verdict::pulse::AsiMethod::of_year(2010).unwrap(),
            uncertainty: None,
            report: false,
            progress: &Unwatched,
            bumper: None,
        };
        // judged by its own model: without its limits it is refused
        // naming the table, with them it is judged
        let refused = verdict(&request).unwrap_err();
        let why = std::error::Error::source(&refused).map(ToString::to_string);
        let refused = format!("{refused}: {}", why.unwrap_or_default());
        assert!(
            refused.contains("links.toml") && refused.contains("damageability"),
            "{refused}"
        );
        let limits = examples().join("verdict/damageability.toml");
        let ends = [End::File(links.as_path(), Some(limits.as_path()))];
        let judged = verdict(&VerdictRequest {
            ends: &ends,
            ..request
        })
        .unwrap();
        assert!(
            judged.text.contains("part581-pendulum-front"),
            "{}",
            judged.text
        );
        // the planar car with its limits is judged
        let saloon = examples().join("planar/saloon.toml");
        let limits = examples().join("verdict/damageability.toml");
        let ends = [End::File(saloon.as_path(), Some(limits.as_path()))];
        let judged = verdict(&VerdictRequest {
            ends: &ends,
            ..request
        })
        .unwrap();
        assert!(judged.json.contains("\"verdict\""), "{}", judged.json);
        std::fs::remove_dir_all(&dir).ok();
    }
}
