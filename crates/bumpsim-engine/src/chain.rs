//! The linear chain ([`bumpsim_core::model::MsdModel`] with a bumper
//! characteristic, `kind = "chain"`) as the engine runs it: `impact`
//! simulates the car and its bumper against a pendulum or a rigid barrier
//! ([`bumpsim_impact::impact::simulate`], spec §6) and, with the car's
//! uncertainty, the results as distributions; with a bumper width the 1-D
//! car becomes a symmetric planar car ([`crate::planar::widened_impact`]);
//! `identify` runs the study over its model sizes ([`mod@crate::identify`]);
//! `predict` simulates a study's cases with the car and gives their fits.
//! No equations here: the mechanism and its energy balance are
//! `bumpsim_impact`'s.

use crate::model::{CarModel, IdentifyRequest, ImpactRequest, PredictRequest};
use crate::uncertain::{self, Uncertain};
use crate::{EngineError, Outcome, Report};
use bumpsim_core::names::printable;
use bumpsim_core::units::format_number;
use bumpsim_impact::bumper::Bumper;
use bumpsim_impact::impact::{Options, Scenario, simulate};
use bumpsim_impact::presets::ScenarioSpec;
use bumpsim_impact::uncertainty::{Chain as Uncertainty, ChainCar};
use bumpsim_io::car::Car;
use bumpsim_io::kind::ModelKind;

/// The linear chain, registered in [`crate::registry::registered`].
#[derive(Debug, Clone, Copy)]
pub struct Chain;

impl CarModel for Chain {
    fn kind(&self) -> ModelKind {
        ModelKind::Chain
    }

    fn impact(&self, request: &ImpactRequest<'_>) -> Result<Outcome, EngineError> {
        let car_path = request.car_path()?;
        let Some(bumper_path) = request.bumper else {
            return Err(EngineError::Needed {
                what: "--bumper FILE is needed for a 1-D car (docs/impact.md)",
            });
        };
        let car = Car::read_model_file(car_path)?;
        let bumper = Bumper::read(bumper_path)?;
        if request.width.is_some() {
            return crate::planar::widened_impact(request, &car, &bumper);
        }
        if request.face.given() {
            return Err(EngineError::Unsupported {
                option: "--angle, --overlap, --side, --pole".into(),
                reason: "faces other than flat need a planar car (--car with [body], docs/planar.md), or --width to make this 1-D car a symmetric one".into(),
            });
        }
        let (scenario, label) = scenario(request, car.model.total_mass())?;
        let chain = ChainCar {
            model: car.model.clone(),
            bumper: bumper.clone(),
        };
        let uncertain = Uncertain::<Uncertainty>::read(request.uncertainty, &chain)?;
        let result =
            simulate(&car.model, &bumper, scenario, &Options::default()).map_err(|source| {
                EngineError::ChainRun {
                    car: car_path.into(),
                    bumper: bumper_path.into(),
                    source,
                }
            })?;
        let warnings = result.warnings();
        let run = |c: &ChainCar| simulate(&c.model, &c.bumper, scenario, &Options::default()).ok();
        let predicted = uncertain
            .map(|u| u.run(&chain, &result, &run))
            .transpose()?;
        let summary = bumpsim_impact::text::summary(&result)
            + &warnings
                .iter()
                .map(|w| format!("warning: {w}\n"))
                .collect::<String>()
            + &predicted.as_ref().map_or(String::new(), |p| p.text.clone());
        let name = car
            .name
            .clone()
            .unwrap_or_else(|| car_path.display().to_string());
        let text = format!(
            "{} with {}: {label}\n{summary}",
            printable(&name),
            bumper_path.display()
        );
        let json = bumpsim_impact::document::ImpactSummary::of(scenario, &result);
        let json = uncertain::with(serde_json::to_value(json)?, &predicted)?;
        let report = match request.report {
            true => {
                let title = format!("{name} — {label}");
                let shown = uncertain::summary(&summary, &predicted);
                let (html, mut figures) =
                    bumpsim_report::impact::impact_report(&title, &shown, &result)?;
                uncertain::pages(&predicted, &title, &mut figures)?;
                Some(Report {
                    html,
                    figures,
                    inputs: Vec::new(),
                })
            }
            false => None,
        };
        Ok(Outcome {
            text,
            warnings,
            json: serde_json::to_string_pretty(&json)?,
            csv: bumpsim_impact::text::histories(&result),
            report,
            ..Outcome::default()
        })
    }

    fn identify(&self, request: &IdentifyRequest<'_>) -> Result<Outcome, EngineError> {
        crate::identify::identify(request)
    }

    fn predict(&self, request: &PredictRequest<'_>) -> Result<Outcome, EngineError> {
        predict(request)
    }

    fn synth(&self, path: &std::path::Path) -> Result<crate::model::Made, EngineError> {
        let (tests, provenance) = bumpsim_impact::synth::make_series(path)?;
        Ok(crate::model::Made {
            tests,
            provenance,
            files: Vec::new(),
        })
    }
}

/// `predict` of a chain model (a car file, or an identification's JSON of
/// one DOF) on a chain study: each case simulated with the case's measured
/// force ([`bumpsim_ident::explore::predict`]) and its fit.
fn predict(request: &PredictRequest<'_>) -> Result<Outcome, EngineError> {
    let car = Car::read_model_file(request.car).map_err(|source| EngineError::CarIn {
        context: format!(
            "{}: a result of `bumpsim identify --json` for one DOF, or a car file",
            request.car.display()
        ),
        source: Box::new(source),
    })?;
    let study = bumpsim_ident::Study::read(request.study).map_err(Box::new)?;
    let loaded = study
        .load_named(car.model.dof(), request.cases)
        .map_err(Box::new)?;
    let notes: Vec<String> = loaded.notes.iter().map(ToString::to_string).collect();
    let mut text: String = notes.iter().map(|n| format!("note: {n}\n")).collect();
    let mut warnings = loaded.warnings.clone();
    let predictions =
        bumpsim_ident::explore::predict(&loaded.cases, &car.model).map_err(Box::new)?;
    if let Some(p) = predictions
        .iter()
        .find(|p| !(p.fit.fit_percent.is_finite() && p.fit.sse.is_finite()))
    {
        return Err(EngineError::Diverged {
            case: p.fit.name.clone(),
            car: request.car.into(),
            fit: p.fit.fit_percent,
        });
    }
    for p in &predictions {
        text += &format!(
            "{}: fit {} %  SSE {} m²  ({} samples)\n  {}\n",
            p.fit.name,
            format_number(p.fit.fit_percent, 4),
            format_number(p.fit.sse, 4),
            p.fit.samples,
            bumpsim_ident::text::rating_line(p.fit.rating.as_ref())
        );
    }
    let name = car
        .name
        .clone()
        .unwrap_or_else(|| request.car.display().to_string());
    let document = bumpsim_ident::document::predictions(&name, &predictions, &notes);
    warnings.extend(document.warnings.iter().cloned());
    let mut plots = Vec::new();
    if request.plot {
        for p in &predictions {
            let svg = bumpsim_report::identification::fit_plot(p, car.model.dof())?;
            let name = bumpsim_report::file_name(&p.fit.name);
            plots.push((format!("predict-{name}.svg"), svg));
        }
    }
    Ok(Outcome {
        text,
        warnings,
        json: serde_json::to_string_pretty(&document)?,
        plots,
        ..Outcome::default()
    })
}

/// The scenario of the request for a car of `car_mass` kg, and its label.
fn scenario(request: &ImpactRequest<'_>, car_mass: f64) -> Result<(Scenario, String), EngineError> {
    let spec = ScenarioSpec {
        case: request.case.map(str::to_string),
        pendulum: request.pendulum,
        barrier: request.barrier,
        speed: request.speed()?,
    };
    let (scenario, preset) =
        spec.scenario(car_mass)
            .map_err(|source| EngineError::ScenarioGiven {
                speed: request.speed.map(|s| format!(" '{s}'")).unwrap_or_default(),
                source,
            })?;
    let label = match (preset, scenario) {
        (Some(p), _) => format!(
            "{} ({}, {}; {}){}",
            p.name,
            p.description,
            format_number(p.speed_kmh(), 3) + " km/h",
            p.source,
            p.dropped_in_1d()
                .map(|d| format!("; 1-D: {d}"))
                .unwrap_or_default()
        ),
        (None, Scenario::Impactor { mass, .. }) => format!("{mass} kg pendulum"),
        (None, Scenario::Barrier { .. }) => "rigid barrier".into(),
    };
    Ok((scenario, label))
}
