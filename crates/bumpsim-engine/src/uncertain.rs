//! The car's uncertainty carried through an impact (issue 39), for every
//! model's `impact` request: the options read and checked before anything
//! runs ([`Uncertain::read`]), the prediction and Sobol indices called
//! ([`bumpsim_impact::propagation`]), their text, JSON and report page.
//! No equations here: the draws, quantiles and indices are the propagation's.

use crate::EngineError;
use crate::model::UncertaintyOptions;
use bumpsim_impact::prediction::{self, HistoryBand, Outputs, Sampling};
use bumpsim_impact::propagation::{Propagated, Propagation, PropagationError};
use bumpsim_impact::uncertainty::{Model, UncertaintyError};
use bumpsim_report::plot::{Band, LinePlot, PlotError, Series, Style};
use serde_json::Value;

/// The checked options and the uncertainty they read.
pub struct Uncertain<M: Model> {
    propagation: Propagation<M>,
}

/// What a prediction gave: its lines and the library's results.
pub struct Predicted<M> {
    /// The lines printed after the summary.
    pub text: String,
    out: Propagated<M>,
}

/// The option a refusal of the propagation names.
fn flag(error: &PropagationError) -> String {
    match error {
        PropagationError::Sampling(UncertaintyError::Value { key, .. }) => format!("--{key}"),
        PropagationError::Sampling(_) => "--samples".into(),
        PropagationError::Sobol(_) => "--sobol, --sobol-base".into(),
        _ => "--uncertainty".into(),
    }
}

impl<M: Model> Uncertain<M> {
    /// The options checked against `car` (`None`: no uncertainty asked).
    pub fn read(
        options: Option<UncertaintyOptions<'_>>,
        car: &M::Car,
    ) -> Result<Option<Self>, EngineError> {
        let Some(options) = options else {
            return Ok(None);
        };
        let sampling = Sampling {
            samples: options.samples,
            seed: options.seed,
            level: options.level,
        };
        let propagation = Propagation::read(options.path, sampling, options.sobol_base, car)
            .map_err(|source| EngineError::Uncertainty {
                option: flag(&source),
                source,
            })?;
        Ok(Some(Uncertain { propagation }))
    }

    /// The prediction of `run` over the uncertainty (and the Sobol
    /// indices when asked); `nominal` is `run`'s result for `car`.
    pub fn run<R: Outputs>(
        &self,
        car: &M::Car,
        nominal: &R,
        run: &(dyn Fn(&M::Car) -> Option<R> + Sync),
    ) -> Result<Predicted<M>, EngineError> {
        let out = self
            .propagation
            .run(car, nominal, run)
            .map_err(EngineError::Propagation)?;
        let text = out.lines();
        Ok(Predicted { text, out })
    }
}

/// `document` with the prediction and the Sobol indices beside its results.
pub fn with<M: Model>(
    mut document: Value,
    predicted: &Option<Predicted<M>>,
) -> Result<Value, EngineError> {
    if let Some(p) = predicted {
        p.out.insert_into(&mut document)?;
    }
    Ok(document)
}

/// The report's summary: the results, then their distributions and where
/// the bands are (the uncertainty page was not reachable from the
/// report's index).
pub fn summary<M>(summary: &str, predicted: &Option<Predicted<M>>) -> String {
    match predicted {
        Some(p) => format!(
            "{summary}\n{}\nBands of the histories over the draws: uncertainty.html in this folder.\n",
            p.text
        ),
        None => summary.to_string(),
    }
}

/// Adds the report's uncertainty page (`uncertainty.html`: the lines and
/// each history's band around the nominal curve) and its figures.
pub fn pages<M>(
    predicted: &Option<Predicted<M>>,
    title: &str,
    figures: &mut Vec<(String, String)>,
) -> Result<(), PlotError> {
    let Some(p) = predicted else {
        return Ok(());
    };
    let mut page = bumpsim_report::html::Html::new(&format!("{title}: over the car's uncertainty"));
    page.heading("Results as distributions");
    page.preformatted(&p.text);
    for b in &p.out.prediction.bands {
        let svg = band_plot(b).svg()?;
        let caption = format!(
            "{}: nominal (solid) and the {} band over the draws (shaded, pointwise)",
            b.name,
            prediction::percent(b.band.level)
        );
        page.figure(&svg, &caption);
        figures.push((format!("{}-band.svg", b.name.replace(' ', "-")), svg));
    }
    figures.push(("uncertainty.html".into(), page.finish()));
    Ok(())
}

/// A history's nominal curve over its shaded band.
fn band_plot(b: &HistoryBand) -> LinePlot {
    let time = bumpsim_core::units::Dimension::Time;
    let mut plot = LinePlot::new(&format!("{} band", b.name), time, b.dimension);
    let tail = prediction::percent((1.0 - b.band.level) / 2.0);
    let head = prediction::percent((1.0 + b.band.level) / 2.0);
    let nominal = Series::new("nominal", b.time.clone(), b.nominal.clone(), Style::Solid);
    plot.add(nominal).band(Band {
        name: format!("{tail} to {head}"),
        x: b.time.clone(),
        low: b.band.low.clone(),
        high: b.band.high.clone(),
    });
    plot
}
