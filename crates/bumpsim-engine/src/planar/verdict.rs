//! `verdict` of the planar car: one car file per end with its
//! `[damageability]` (or a limits file), the protocols' tests, the
//! verdicts with their margins, and on request the bumper target region,
//! the probability of passing and the Sobol indices over the car's
//! uncertainty ([`bumpsim_verdict`], issues 36 and 39); the engine makes
//! the outcome ([`crate::verdict::verdict`]). No equations here.

use crate::EngineError;
use crate::model::{End, Judged, VerdictRequest};
use bumpsim_planar::PlanarCar;
use bumpsim_verdict::prelude::*;
use bumpsim_verdict::{probability, protocol, sensitivity, target};
use std::path::Path;

/// A refusal of the verdicts named by `context`.
fn named(context: &str) -> impl Fn(VerdictError) -> EngineError + '_ {
    move |source| EngineError::VerdictIn {
        context: context.into(),
        source: Box::new(source),
    }
}

/// `verdict`: the ends judged in the tests, and what else was asked.
pub(super) fn verdict(request: &VerdictRequest<'_>) -> Result<Judged, EngineError> {
    let names: Vec<&str> = request.protocols.iter().map(String::as_str).collect();
    let tests = protocol::select_in(&names, request.market).map_err(named("--protocol"))?;
    let mut ends = request
        .ends
        .iter()
        .map(|end| match end {
            End::File(path, limits) => Ok(CarEnd::read(path, *limits)?),
            End::Held { path, text, .. } => self::end(path, text),
        })
        .collect::<Result<Vec<_>, EngineError>>()?;
    if let Some(bumper) = request.bumper {
        ends = ends
            .iter()
            .map(|end| end.with_bumper(bumper))
            .collect::<Result<_, _>>()?;
    }
    let mut setup = Setup::new(ends, tests, request.margin)?;
    setup.sequence = request.sequence;
    setup.asi_method = request.asi_method;
    let mut v = bumpsim_verdict::verdict(&setup)?;
    let mut indices = None;
    if let Some(u) = &request.uncertainty {
        let uncertainty = Uncertainty::read(u.path)?;
        let settings = u
            .sobol_base
            .map(|base| sensitivity::Settings::new(base, u.seed));
        if let Some(settings) = &settings {
            sensitivity::check(&setup, &uncertainty, settings)?;
        }
        let sampling = Sampling {
            samples: u.samples,
            seed: u.seed,
        };
        probability::propagate(&setup, &mut v, &uncertainty, sampling)?;
        if let Some(settings) = &settings {
            let progress = request.progress;
            progress.begin(sensitivity::evaluations(&uncertainty, settings.base) as u64);
            let s = sensitivity::sensitivity(&setup, &v, &uncertainty, settings, &|| {
                progress.start_finished()
            });
            progress.end();
            indices = Some(s.map_err(named("--sobol"))?);
        }
    }
    let region = match request.target {
        true => Some(target::search(&setup, &TargetOptions::default())?),
        false => None,
    };
    Ok(Judged {
        verdict: v,
        region,
        indices,
    })
}

/// One end of a held planar car (its file's `text`, at `path`): the car
/// with the limits of its file's `[damageability]`.
pub(super) fn end(path: &Path, text: &str) -> Result<CarEnd, EngineError> {
    let planar = PlanarCar::parse(text, path)?;
    let limits = Damageability::read(path)?;
    CarEnd::new(planar, limits).map_err(named(&path.display().to_string()))
}
