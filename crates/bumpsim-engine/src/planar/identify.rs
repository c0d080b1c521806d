//! `identify` and `predict` of the planar car: the study identified
//! ([`bumpsim_planar::identify::identify`]), its fitted and held-out cases
//! replayed, the forward predictions of the cases that give their striker
//! ([`bumpsim_planar::forward`]) and their bands ([`bumpsim_planar::bands`]);
//! `predict` replays a study's cases with a given car. No equations here.

use crate::model::{IdentifyRequest, PredictRequest};
use crate::{EngineError, Outcome, Report};
use bumpsim_core::units::{Dimension, format_number, format_quantity};
use bumpsim_planar::PlanarCar;
use bumpsim_planar::document::{IdentificationDocument, forward_warnings};
use bumpsim_planar::forward::Forward;
use bumpsim_planar::identify::{PlanarCase, Prediction, predict as replay};
use bumpsim_planar::study::PlanarStudy;
use bumpsim_report::planar::CasePage;

/// `identify` on a planar study: identifies, summarises, predicts the
/// validation cases, and gives the document, the car file and the report.
pub(super) fn identify(request: &IdentifyRequest<'_>) -> Result<Outcome, EngineError> {
    if request.posterior.is_some() {
        return Err(EngineError::Unsupported {
            option: "--posterior".into(),
            reason: "the planar car's posterior is not in the command line yet (docs/uncertainty.md); a chain study samples it".into(),
        });
    }
    if request.sizes.is_some() || request.sensitivity {
        return Err(EngineError::Unsupported {
            option: "--dof and --sensitivity".into(),
            reason: "a planar study takes its chain sizes from its start car (docs/planar.md)"
                .into(),
        });
    }
    let mut study = PlanarStudy::read(request.study)?;
    let mut text: String = study.notes.iter().map(|n| format!("note: {n}\n")).collect();
    study.setup.starts = request.starts.unwrap_or(study.setup.starts);
    study.setup.seed = request.seed.unwrap_or(study.setup.seed);
    let progress = request.progress;
    // the starts of every search the identification runs (the bar may
    // finish early: `confirm` searches again only while it must)
    progress.begin(study.setup.start_count() as u64);
    // the identification, then the bumper from the training tests' forward
    // runs when the study asks (`[model] bumper = "fit"`)
    let result = study.identified(&|| progress.start_finished());
    progress.end();
    // the study file named: a `[priors]` entry the identification refuses
    // (its names depend on what the study estimates) named no file
    let result = result.map_err(|source| EngineError::PlanarIn {
        context: format!("planar identification of {}", request.study.display()),
        source,
    })?;
    let fitted: Vec<Prediction> = study
        .cases
        .iter()
        .map(|c| replay(&result.car, c))
        .collect::<Result<_, _>>()?;
    let mut validation: Vec<Prediction> = study
        .validation
        .iter()
        .map(|c| replay(&result.car, c))
        .collect::<Result<_, _>>()?;
    let validation_fits: Vec<_> = validation.iter().map(|p| p.fit.clone()).collect();
    let mut forward = forwards(&result.car, study.cases.iter().chain(&study.validation))?;
    let bands = bumpsim_planar::bands::attach(
        &result,
        &study.cases,
        (&study.validation, &mut validation),
        &mut forward,
    )?;
    let summary = bumpsim_planar::text::identification_summary(&result, &validation_fits)
        + &bumpsim_planar::text::forward_lines(&forward)
        + &bands.lines();
    text += &summary;
    // the bands' statements and the identification's warnings are printed
    // in the summary, as the 1-D identification prints its own
    let printed_warnings = bands.statements().len()
        + bumpsim_planar::text::identification_warnings(&result, &validation_fits).len();
    let warnings: Vec<String> = forward.iter().flat_map(forward_warnings).collect();
    let document = IdentificationDocument {
        result: &result,
        validation: &validation_fits,
        forward: &forward,
        notes: &study.notes,
        bands: Some(&bands),
    };
    let report = match request.report {
        true => {
            let inputs = std::fs::read_to_string(request.study).unwrap_or_default();
            let pages: Vec<CasePage> = fitted
                .iter()
                .map(|p| (p, false))
                .chain(validation.iter().map(|p| (p, true)))
                .map(|(prediction, validation)| CasePage {
                    prediction,
                    validation,
                    forward: forward.iter().find(|f| f.case == prediction.fit.name),
                })
                .collect();
            let (html, figures) = bumpsim_report::planar::identification_report(
                (&summary, &warnings),
                &inputs,
                &study.notes,
                &pages,
            )?;
            Some(Report {
                html,
                figures,
                inputs: vec![request.study.to_path_buf()],
            })
        }
        false => None,
    };
    Ok(Outcome {
        text,
        warnings,
        json: serde_json::to_string_pretty(&document)?,
        report,
        printed_warnings,
        car: Some(result.car.to_toml()),
        ..Outcome::default()
    })
}

/// `predict` with a planar car: replays the study's cases (fitted and
/// validation alike) with the car's measured forces and gives each fit of
/// x and yaw, as the chain's `predict` gives its fits.
pub(super) fn predict(request: &PredictRequest<'_>) -> Result<Outcome, EngineError> {
    let car = PlanarCar::read(request.car)?;
    let study = PlanarStudy::read(request.study)?;
    let mut text: String = study.notes.iter().map(|n| format!("note: {n}\n")).collect();
    let predictions: Vec<Prediction> = study
        .named(request.cases)?
        .into_iter()
        .map(|c| replay(&car, c))
        .collect::<Result<_, _>>()?;
    if let Some(f) = predictions
        .iter()
        .map(|p| &p.fit)
        .find(|f| !(f.fit_x.is_finite() && f.fit_yaw.is_finite()))
    {
        return Err(EngineError::NotFinite {
            case: f.name.clone(),
            car: request.car.into(),
            fit_x: f.fit_x,
            fit_yaw: f.fit_yaw,
        });
    }
    for p in &predictions {
        let f = &p.fit;
        text += &format!(
            "{}: fit x {} %  yaw {} %  (peak yaw {} deg){}\n",
            f.name,
            format_number(f.fit_x, 4),
            format_number(f.fit_yaw, 4),
            format_number(f.peak_yaw.to_degrees(), 4),
            f.bias_x.map_or_else(String::new, |b| format!(
                "  (x less its bias read after the contact, {})",
                format_quantity(b, Dimension::Acceleration)
            ))
        );
    }
    let name = car
        .name()
        .map_or_else(|| request.car.display().to_string(), str::to_string);
    let fits: Vec<_> = predictions.iter().map(|p| p.fit.clone()).collect();
    let forward = forwards(&car, study.named(request.cases)?.into_iter())?;
    text += &bumpsim_planar::text::forward_lines(&forward);
    let document = bumpsim_planar::document::predictions(&name, &fits, &forward, &study.notes);
    let mut plots = Vec::new();
    if request.plot {
        for p in &predictions {
            for (name, svg, _) in bumpsim_report::planar::case_figures(p, false)? {
                plots.push((format!("predict-{name}"), svg));
            }
        }
    }
    Ok(Outcome {
        text,
        warnings: document.predictions.warnings.clone(),
        json: serde_json::to_string_pretty(&document)?,
        plots,
        ..Outcome::default()
    })
}

/// The forward predictions of the cases that give their striker.
fn forwards<'a>(
    car: &PlanarCar,
    cases: impl Iterator<Item = &'a PlanarCase>,
) -> Result<Vec<Forward>, EngineError> {
    cases
        .filter(|c| c.striker.is_some())
        .map(|c| Ok(bumpsim_planar::forward::forward(car, c)?))
        .collect()
}
