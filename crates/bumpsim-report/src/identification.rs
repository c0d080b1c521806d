//! The identification report: what was found first (the model, its fit
//! per case with the fitted window, the warnings), then measured vs fitted
//! displacement per case (solid vs dashed, as in the thesis figures, the
//! fitted window shaded), residuals, the DOF table and the ±3 %
//! sensitivity of the objective and, when sampled, the posterior
//! ([`crate::posterior`]); the inputs (settings, channel notes, the study
//! file's text) last, gathered in one HTML page.

use crate::file_name;
use crate::html::Html;
use crate::plot::{LinePlot, PlotError, Series, Span, Style};
use bumpsim_core::units::{Dimension, format_number};
use bumpsim_ident::estimate::Identification;
use bumpsim_ident::explore::{Prediction, Sweep};
use bumpsim_ident::posterior::Posterior;
use bumpsim_ident::text::{case_lines, dof_table, parameter_table};

/// One DOF's outcome: identified (with its predictions) or failed.
#[derive(Debug, Clone)]
pub enum DofOutcome {
    /// Identified.
    Done {
        /// The result.
        result: Box<Identification>,
        /// The cases simulated with the identified model.
        predictions: Vec<Prediction>,
    },
    /// Could not be identified.
    Failed {
        /// Number of masses.
        dof: usize,
        /// Why.
        reason: String,
    },
}

/// An SVG file of the report: name and content.
pub type Figure = (String, String);

/// Measured (solid) vs fitted (dashed) displacement of one case over the
/// whole record, the fitted window shaded ([`Span::window`]).
pub fn fit_plot(prediction: &Prediction, dof: usize) -> Result<String, PlotError> {
    let title = format!(
        "{}: measured vs {dof}-DOF model (fit {} %)",
        prediction.fit.name,
        format_number(prediction.fit.fit_percent, 4)
    );
    let mut plot = LinePlot::new(&title, Dimension::Time, Dimension::Length)
        .quantities(None, Some("displacement"));
    plot.add(Series::new(
        "measured",
        prediction.time.clone(),
        prediction.measured.clone(),
        Style::Solid,
    ));
    plot.add(Series::new(
        "model",
        prediction.time.clone(),
        prediction.simulated.clone(),
        Style::Dashed,
    ));
    plot.span(Span::window("fitted", prediction.window));
    plot.svg()
}

/// Residuals (model − measured) of every case in its window.
pub fn residual_plot(predictions: &[Prediction], dof: usize) -> Result<String, PlotError> {
    let mut plot = LinePlot::new(
        &format!("Residuals of the {dof}-DOF model"),
        Dimension::Time,
        Dimension::Length,
    )
    .quantities(None, Some("residual (model − measured)"));
    for p in predictions {
        let inside: Vec<usize> = (0..p.time.len())
            .filter(|&k| p.time[k] >= p.window[0] && p.time[k] <= p.window[1])
            .collect();
        let t = inside.iter().map(|&k| p.time[k]).collect();
        let r = inside
            .iter()
            .map(|&k| p.simulated[k] - p.measured[k])
            .collect();
        plot.add(Series::new(&p.fit.name, t, r, Style::Solid));
    }
    plot.svg()
}

/// The objective along each parameter (paper B figure 6).
pub fn sensitivity_plot(sweeps: &[Sweep]) -> Result<String, PlotError> {
    let plot = LinePlot::new(
        "Objective when one parameter changes",
        Dimension::Dimensionless,
        Dimension::Dimensionless,
    );
    let mut plot = plot.with_labels(
        Some("relative change of the parameter [%]"),
        Some("objective F [m²]"),
    );
    for s in sweeps {
        let x = s.relative_change.iter().map(|d| 100.0 * d).collect();
        plot.add(Series::new(&s.name, x, s.objective.clone(), Style::Solid));
    }
    plot.svg()
}

/// Objective against the number of DOF.
pub fn dof_plot(results: &[&Identification]) -> Result<String, PlotError> {
    let plot = LinePlot::new(
        "Objective against model size",
        Dimension::Dimensionless,
        Dimension::Dimensionless,
    );
    let mut plot = plot.with_labels(Some("number of masses [-]"), Some("objective F [m²]"));
    let x = results.iter().map(|r| r.dof as f64).collect();
    plot.add(Series::new(
        "objective",
        x,
        results.iter().map(|r| r.objective).collect(),
        Style::Solid,
    ));
    plot.svg()
}

/// Builds the SVG figures and the HTML page of an identification.
/// `inputs` is the study file text; `settings` a one-line description;
/// `notes` what the channel selections left out or used despite a mark.
pub fn report(
    title: &str,
    inputs: &str,
    settings: &str,
    notes: &[String],
    outcomes: &[DofOutcome],
    sweeps: Option<&[Sweep]>,
) -> Result<(String, Vec<Figure>), PlotError> {
    let texts = (title, inputs, settings);
    report_with_posterior(texts, notes, outcomes, sweeps, None)
}

/// [`report`] with the posterior of one identified order (its lines and
/// corner plot, [`crate::posterior::section`]) after the models;
/// `texts` the title, the study file text and the settings line.
pub fn report_with_posterior(
    (title, inputs, settings): (&str, &str, &str),
    notes: &[String],
    outcomes: &[DofOutcome],
    sweeps: Option<&[Sweep]>,
    posterior: Option<(&Posterior, &Identification)>,
) -> Result<(String, Vec<Figure>), PlotError> {
    let mut page = Html::new(title);
    let mut figures = Vec::new();
    let done: Vec<&Identification> = outcomes
        .iter()
        .filter_map(|o| match o {
            DofOutcome::Done { result, .. } => Some(result.as_ref()),
            DofOutcome::Failed { .. } => None,
        })
        .collect();
    let answer = answer(&mut page, outcomes, &done);
    if done.len() > 1 {
        page.heading("Model size (thesis table 1)");
        let owned: Vec<Identification> = done.iter().map(|r| (*r).clone()).collect();
        page.preformatted(&dof_table(&owned));
        add(
            &mut page,
            &mut figures,
            "dof.svg",
            dof_plot(&done)?,
            "objective against the number of masses",
        );
    }
    for outcome in outcomes {
        if let DofOutcome::Done {
            result,
            predictions,
        } = outcome
        {
            let tables = Some(result.dof) != answer;
            section(&mut page, &mut figures, result, predictions, tables)?;
        }
    }
    if let Some((post, result)) = posterior {
        let (name, svg) = crate::posterior::section(&mut page, post, result)?;
        let name = crate::unique_name(&name, |n| figures.iter().any(|(f, _)| f == n));
        figures.push((name, svg));
    }
    if let Some(sweeps) = sweeps {
        page.heading("Sensitivity of the objective");
        add(
            &mut page,
            &mut figures,
            "sensitivity.svg",
            sensitivity_plot(sweeps)?,
            "each parameter alone changed by up to ±3 %",
        );
    }
    page.heading("Inputs");
    page.paragraph(settings);
    notes_section(&mut page, notes);
    page.preformatted(inputs);
    Ok((page.finish(), figures))
}

/// The first section, what was found: the model (the recommended order
/// when several were identified), its fit per case with the fitted window,
/// the failed orders and every warning. Returns the order shown.
fn answer(page: &mut Html, outcomes: &[DofOutcome], done: &[&Identification]) -> Option<usize> {
    page.heading("Result");
    let owned: Vec<Identification> = done.iter().map(|r| (*r).clone()).collect();
    let chosen = bumpsim_ident::text::recommended_dof(&owned)
        .and_then(|dof| done.iter().find(|r| r.dof == dof))
        .or(done.first());
    let failures: Vec<(usize, &str)> = outcomes
        .iter()
        .filter_map(|o| match o {
            DofOutcome::Failed { dof, reason } => Some((*dof, reason.as_str())),
            DofOutcome::Done { .. } => None,
        })
        .collect();
    for (dof, reason) in &failures {
        page.failure(&format!("{dof}-DOF model: {reason}"));
    }
    let Some(r) = chosen else {
        page.paragraph("No model was identified.");
        return None;
    };
    let which = match done.len() {
        1 => String::new(),
        n => format!(" (recommended among the {n} identified orders, see Model size)"),
    };
    page.paragraph(&format!(
        "The {}-DOF model{which}: objective {} m², overall fit {} %.",
        r.dof,
        format_number(r.objective, 5),
        format_number(r.fit_percent, 4)
    ));
    page.preformatted(&parameter_table(r));
    page.table(&FIT_HEADERS, &fit_rows(r));
    let warnings: Vec<String> = done
        .iter()
        .flat_map(|d| d.warnings.iter().map(move |w| (d.dof, w)))
        .map(|(dof, w)| match done.len() {
            1 => w.clone(),
            _ => format!("{dof}-DOF model: {w}"),
        })
        .collect();
    match warnings.is_empty() {
        true => page.paragraph("No warnings."),
        false => page.warnings(&warnings),
    }
    Some(r.dof)
}

/// The columns of the table of fits.
pub const FIT_HEADERS: [&str; 5] = [
    "case",
    "fitted window [ms]",
    "fit [%]",
    "SSE [m²]",
    "ISO/TS 18571 rating",
];

/// One row per case: name, window, fit, SSE and rating (with its grade).
fn fit_rows(r: &Identification) -> Vec<Vec<String>> {
    let ms = |t: f64| format!("{:.2}", t * 1e3);
    r.cases
        .iter()
        .map(|c| {
            vec![
                c.name.clone(),
                format!("{}–{}", ms(c.window[0]), ms(c.window[1])),
                format_number(c.fit_percent, 4),
                format_number(c.sse, 4),
                c.rating.as_ref().map_or("none".into(), |g| {
                    format!("{:.3} ({})", g.overall, g.grade())
                }),
            ]
        })
        .collect()
}

/// The notes of the channel selections and time bases, when there are any.
fn notes_section(page: &mut Html, notes: &[String]) {
    if notes.is_empty() {
        return;
    }
    page.heading("Channel selection and time base");
    page.paragraph(
        "Channels the study's selectors left out or used although marked invalid, and channels put on one time base:",
    );
    page.notes(notes);
}

fn add(page: &mut Html, figures: &mut Vec<Figure>, name: &str, svg: String, caption: &str) {
    page.figure(&svg, caption);
    let name = crate::unique_name(name, |n| figures.iter().any(|(f, _)| f == n));
    figures.push((name, svg));
}

/// One order's section: its objective and starts, its tables unless the
/// first section shows them (`tables`), its fit plots and residuals.
fn section(
    page: &mut Html,
    figures: &mut Vec<Figure>,
    result: &Identification,
    predictions: &[Prediction],
    tables: bool,
) -> Result<(), PlotError> {
    let dof = result.dof;
    page.heading(&format!("{dof}-DOF model"));
    let unit = result.objective_unit();
    let phrase = result.objective_phrase();
    let objective = match phrase.is_empty() {
        true => format!("{} {unit}", format_number(result.objective, 5)),
        false => format!("{} {unit} ({phrase})", format_number(result.objective, 5)),
    };
    page.paragraph(&format!(
        "Objective {objective}, overall fit {} %; {}.",
        format_number(result.fit_percent, 4),
        bumpsim_ident::text::starts_line(result)
    ));
    if let Some(line) = bumpsim_ident::text::residuals_line(result) {
        page.paragraph(&line);
    }
    let priors = bumpsim_ident::text::prior_lines(result);
    if !priors.is_empty() {
        page.preformatted(&priors);
    }
    if tables {
        page.preformatted(&parameter_table(result));
        page.preformatted(&case_lines(result));
        page.warnings(&result.warnings);
    }
    for p in predictions {
        let name = format!("fit-{dof}dof-{}.svg", file_name(&p.fit.name));
        add(
            page,
            figures,
            &name,
            fit_plot(p, dof)?,
            &format!(
                "{}: measured (solid) and simulated (dashed) displacement; the shaded span is the fitted window ({:.2}–{:.2} ms), outside it the model is not fitted",
                p.fit.name,
                p.window[0] * 1e3,
                p.window[1] * 1e3
            ),
        );
    }
    let name = format!("residuals-{dof}dof.svg");
    add(
        page,
        figures,
        &name,
        residual_plot(predictions, dof)?,
        "model minus measurement in the fit windows",
    );
    Ok(())
}
