//! The planar car ([`bumpsim_planar`], `kind = "planar"`) as the engine
//! runs it: `impact` (and `planar`) simulates the car hit by a striker —
//! a preset of the table of tests, or a plane (angle, overlap, side) or a
//! pole, carried by a pendulum or fixed (spec §9) — and, with the car's
//! uncertainty, the results as distributions; `identify` and `predict`
//! (`identify`), and `export` writes its decks (`export`) identify the car from a planar study and replay its
//! cases. A 1-D car and its bumper become a symmetric planar car of a
//! given bumper width ([`widened_impact`], `impact --width`).
//!
//! No equations here: the mechanism, the striker, the tyres and the
//! identification are `bumpsim_planar`'s; this module picks the options,
//! names the option behind a refused value and assembles the outcome.

mod export;
mod identify;
mod verdict;

use crate::model::{
    CarModel, CarText, Deck, ExportRequest, IdentifyRequest, ImpactRequest, Judged, Made,
    PredictRequest, Setup, VerdictRequest,
};
use crate::uncertain::{self, Uncertain};
use crate::{EngineError, Outcome, Report};
use bumpsim_core::names::printable;
use bumpsim_core::units::{Dimension, parse_quantity, short};
use bumpsim_impact::bumper::Bumper;
use bumpsim_io::car::Car;
use bumpsim_io::kind::ModelKind;
use bumpsim_planar::car::{Layout, PlanarError, TyreLaw};
use bumpsim_planar::document::ImpactDocument;
use bumpsim_planar::presets::{PlanarPreset, StrikerSpec};
use bumpsim_planar::uncertainty::Planar as Uncertainty;
use bumpsim_planar::{PlanarCar, Settings, Striker, simulate};
use std::path::Path;

/// The planar car, registered in [`crate::registry::registered`].
#[derive(Debug, Clone, Copy)]
pub struct Planar;

impl CarModel for Planar {
    fn kind(&self) -> ModelKind {
        ModelKind::Planar
    }

    fn impact(&self, request: &ImpactRequest<'_>) -> Result<Outcome, EngineError> {
        let path = request.car_path()?;
        if request.bumper.is_some() {
            return Err(EngineError::Unsupported {
                option: "--bumper".into(),
                reason: "a planar car carries its bumper segments ([bumper] of its file); leave --bumper out".into(),
            });
        }
        if request.width.is_some() {
            return Err(EngineError::Unsupported {
                option: "--width".into(),
                reason: "a planar car has its bumper width ([bumper] width of its file)".into(),
            });
        }
        run(read(path, request.car_text)?, path, request)
    }

    fn car(&self, path: &Path, text: Option<&str>) -> Result<CarText, EngineError> {
        let car = read(path, text)?;
        Ok(CarText {
            name: car.name().map(str::to_string),
            toml: car.to_toml(),
        })
    }

    fn judges(&self) -> bool {
        true
    }

    fn judges_unmarked(&self) -> bool {
        true
    }

    fn verdict(&self, request: &VerdictRequest<'_>) -> Result<Judged, EngineError> {
        verdict::verdict(request)
    }

    fn end(
        &self,
        path: &Path,
        text: &str,
    ) -> Result<bumpsim_verdict::prelude::CarEnd, EngineError> {
        verdict::end(path, text)
    }

    fn synth(&self, path: &Path) -> Result<Made, EngineError> {
        let series = bumpsim_planar::series::make_series(path)?;
        let tests = series
            .tests
            .into_iter()
            .map(|t| (t.name.clone(), t.test_header(), t.channels))
            .collect();
        let files = vec![("study.toml", series.study), ("start.toml", series.start)];
        Ok(Made {
            tests,
            provenance: series.provenance,
            files,
        })
    }

    fn identify(&self, request: &IdentifyRequest<'_>) -> Result<Outcome, EngineError> {
        identify::identify(request)
    }

    fn predict(&self, request: &PredictRequest<'_>) -> Result<Outcome, EngineError> {
        identify::predict(request)
    }

    fn export(&self, request: &ExportRequest<'_>) -> Result<Deck, EngineError> {
        export::export(request)
    }
}

/// The planar car of a file's `text` (held by the front end), else of the
/// file at `path`.
fn read(path: &Path, text: Option<&str>) -> Result<PlanarCar, PlanarError> {
    match text {
        Some(text) => PlanarCar::parse(text, path),
        None => PlanarCar::read(path),
    }
}

/// `impact --width`: the 1-D `car` and its `bumper` as a symmetric planar
/// car of that bumper width (`PlanarCar::symmetric_fitted` with the
/// default layout), in the planar impact of `request`.
pub fn widened_impact(
    request: &ImpactRequest<'_>,
    car: &Car,
    bumper: &Bumper,
) -> Result<Outcome, EngineError> {
    let path = request.car_path()?;
    let width = request.width.ok_or_else(|| EngineError::Unsupported {
        option: "--width".into(),
        reason: "the bumper width of the symmetric planar car is needed".into(),
    })?;
    let layout = Layout {
        bumper_width: quantity("width", width, Dimension::Length)?,
        ..Layout::default()
    };
    let planar = PlanarCar::symmetric_fitted(&car.model, bumper, &layout)
        .map_err(|source| EngineError::PlanarIn {
            context: "--width: the symmetric planar car".into(),
            source,
        })?
        .with_name(car.name.clone());
    run(planar, path, request)
}

/// A quantity option read with its unit; a refusal names it as typed.
fn quantity(option: &'static str, text: &str, dimension: Dimension) -> Result<f64, EngineError> {
    parse_quantity(text, dimension).map_err(|source| EngineError::Quantity {
        option,
        text: text.into(),
        source,
    })
}

/// The simulation settings of the set-up (gap, duration); a run whose
/// energy balance misses 0.1 % is repeated at half the step up to
/// [`IMPACT_REFINEMENTS`] times.
fn settings(setup: &Setup<'_>) -> Result<Settings, EngineError> {
    let mut settings = Settings {
        refine: IMPACT_REFINEMENTS,
        ..Settings::default()
    };
    if let Some(gap) = setup.gap {
        settings.gap = quantity("gap", gap, Dimension::Length)?;
    }
    if let Some(duration) = setup.duration {
        settings.duration = quantity("duration", duration, Dimension::Time)?;
    }
    Ok(settings)
}

/// How often `impact` halves the safety factor of a run whose energy
/// balance stays open (0.05 → 0.00625 at most).
pub const IMPACT_REFINEMENTS: u32 = 3;

/// The tyre law the run uses: `--tyres`, else the preset's, else none (the car's).
fn tyre_law(tyres: Option<&str>, preset: Option<&PlanarPreset>) -> Option<(TyreLaw, String)> {
    match (tyres, preset) {
        (Some("sliding"), _) => Some((TyreLaw::Sliding, "sliding (locked wheels, --tyres)".into())),
        (Some(_), _) => Some((TyreLaw::Rolling, "free rolling (--tyres)".into())),
        (None, Some(p)) => Some((bumpsim_planar::presets::tyres(p), p.tyres_why.to_string())),
        (None, None) => None,
    }
}

/// The striker of the request, its label and its preset.
fn striker(
    request: &ImpactRequest<'_>,
    car: &PlanarCar,
) -> Result<(Striker, String, Option<&'static PlanarPreset>), EngineError> {
    let face = request.face;
    let length = |option, text: Option<&str>| {
        text.map(|t| quantity(option, t, Dimension::Length))
            .transpose()
    };
    let spec = StrikerSpec {
        case: request.case.map(str::to_string),
        angle: face.angle,
        overlap: face.overlap,
        side: face.side,
        pole: length("pole", face.pole)?,
        pole_offset: length("pole-offset", face.pole_offset)?,
        pendulum: request.pendulum,
        speed: request.speed()?,
        car_mass: Some(car.total_mass()),
    };
    let (striker, preset) = spec.striker().map_err(|source| EngineError::PlanarIn {
        context: "--case or --speed".into(),
        source,
    })?;
    let label = match (preset, request.pendulum) {
        (Some(p), _) => format!("{} [{}]", p.name, p.source),
        (None, Some(_)) => "pendulum".into(),
        (None, None) => "barrier".into(),
    };
    Ok((striker, label, preset))
}

/// Names the option behind a refused face or set-up value, with the value
/// as given (the library names the parameter in its own unit: the overlap
/// as a fraction, the angle in radians, the pole by its radius).
fn name_option(error: PlanarError, request: &ImpactRequest<'_>) -> EngineError {
    let PlanarError::Parameter { name, .. } = &error else {
        return error.into();
    };
    let (face, setup) = (request.face, request.setup);
    let option = match name.as_str() {
        "overlap" => face.overlap.map(|v| {
            format!(
                "--overlap {}: the overlap, in percent of the bumper width, must lie in 0 < overlap ≤ 100",
                short(v)
            )
        }),
        "barrier angle" => face.angle.map(|v| {
            format!(
                "--angle {}: the face angle, in degrees, must lie within ±80",
                short(v)
            )
        }),
        "pole radius" => face
            .pole
            .map(|v| format!("--pole '{v}' (the pole's diameter; its radius is half of it)")),
        "pole lateral position" => face.pole_offset.map(|v| format!("--pole-offset '{v}'")),
        "gap" => setup.gap.map(|v| format!("--gap '{v}'")),
        "duration" | "duration / output step" => setup.duration.map(|v| format!("--duration '{v}'")),
        _ => None,
    };
    match option {
        Some(context) => EngineError::PlanarIn {
            context,
            source: error,
        },
        None => error.into(),
    }
}

/// Simulates the planar impact of `request` with `car` (read from `path`).
fn run(car: PlanarCar, path: &Path, request: &ImpactRequest<'_>) -> Result<Outcome, EngineError> {
    let (striker, label, preset) = striker(request, &car)?;
    let law = tyre_law(request.setup.tyres, preset);
    let car = &match (&law, request.setup.tyres.is_some()) {
        (Some((law, _)), true) => car.clone().with_tyre_law(*law),
        _ => bumpsim_planar::presets::prepared(&car, preset),
    };
    let settings = settings(&request.setup)?;
    let uncertain = Uncertain::<Uncertainty>::read(request.uncertainty, car)?;
    let result = simulate(car, &striker, &settings).map_err(|e| name_option(e, request))?;
    let name = car
        .name()
        .map_or_else(|| path.display().to_string(), str::to_string);
    let run = |c: &PlanarCar| simulate(c, &striker, &settings).ok();
    let predicted = uncertain.map(|u| u.run(car, &result, &run)).transpose()?;
    let summary = bumpsim_planar::text::summary(&result)
        + &predicted.as_ref().map_or(String::new(), |p| p.text.clone());
    let heading = format!(
        "{name}: {} ({label})",
        bumpsim_planar::text::striker(&striker)
    );
    let mut text = format!("{}\n", printable(&heading));
    if let Some((_, why)) = &law {
        text += &format!("  tyres: {why}\n");
    }
    text += &summary;
    let document = ImpactDocument {
        car: &name,
        striker: &striker,
        result: &result,
        body: Some(car.body()),
    };
    let document = uncertain::with(serde_json::to_value(document)?, &predicted)?;
    let report = match request.report {
        true => {
            let peak = bumpsim_planar::picture::peak_sample(&result);
            let view = bumpsim_planar::picture::top_view(car, &striker, &result, peak)?;
            let (html, mut figures) = bumpsim_report::planar::planar_report(
                &heading,
                &uncertain::summary(&summary, &predicted),
                &result,
                Some(&view),
            )?;
            uncertain::pages(&predicted, &heading, &mut figures)?;
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
        warnings: result.warnings.clone(),
        json: serde_json::to_string_pretty(&document)?,
        csv: bumpsim_planar::text::histories(&result),
        report,
        ..Outcome::default()
    })
}
