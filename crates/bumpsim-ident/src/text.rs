//! Human-readable text for identification results: parameters with units,
//! the DOF table, per-case fits. The CLI prints these strings; reports reuse them.

use crate::estimate::Identification;
use bumpsim_core::units::{Dimension, format_number, format_quantity};

/// The parameter table: name, value, standard error, 95 % interval, and a
/// note: fixed, at bound, or not determined by the data (the estimation
/// layer's table, [`bumpsim_estimate::text::parameter_table`]).
pub fn parameter_table(result: &Identification) -> String {
    let parameters = crate::stats::parameters(result.dof);
    let theta = result.model.parameters();
    bumpsim_estimate::text::parameter_table(&parameters, &theta, &result.uncertainty)
}

/// Per-case fit lines, each followed by its ISO/TS 18571 rating.
pub fn case_lines(result: &Identification) -> String {
    result
        .cases
        .iter()
        .map(|c| {
            format!(
                "  {:<16} fit {:>7}  SSE {} m²  ({} samples)\n    {}\n",
                c.name,
                format!("{} %", format_number(c.fit_percent, 4)),
                format_number(c.sse, 4),
                c.samples,
                rating_line(c.rating.as_ref())
            )
        })
        .collect()
}

/// How correlated the residuals are and what the intervals count, for an
/// objective other than the thesis's (its output stays as it was):
/// `residuals: lag-1 correlation 0.62, 410 effective of 3357 samples
/// (intervals widened by ×2.9)`.
pub fn residuals_line(result: &Identification) -> Option<String> {
    result.compared?;
    let u = &result.uncertainty;
    let e = &result.effective_samples;
    let widened = match u.error_model {
        bumpsim_estimate::uncertainty::Correlation::RandomWalk => format!(
            "intervals from the integrated noise's random walk, widened by up to ×{}",
            format_number(u.inflation.sqrt(), 3)
        ),
        _ => format!(
            "intervals widened by ×{}",
            format_number(u.inflation.sqrt(), 3)
        ),
    };
    Some(format!(
        "residuals: lag-1 correlation {}, {} effective of {} samples ({widened})",
        format_number(u.residual_correlation, 3),
        format_number(e.effective, 3),
        e.samples,
    ))
}

/// The stated priors, a line each (indented), with how far the data
/// moved them ([`bumpsim_estimate::prior::text`]): `prior total_mass: 1450
/// kg ± 0.010 (ln) (the test sheet) -> 1449 kg (moved -0.07 sd)`; empty
/// without any.
pub fn prior_lines(result: &Identification) -> String {
    let parameters = crate::stats::parameters(result.dof);
    bumpsim_estimate::prior::indented_text(&result.priors, &parameters)
}

/// `ISO/TS 18571 rating 0.962 (excellent; corridor …, phase …, magnitude
/// …, slope …)`, or why there is none.
pub fn rating_line(rating: Option<&bumpsim_signal::rating::Rating>) -> String {
    match rating {
        Some(r) => format!("ISO/TS 18571 rating {r}"),
        None => "ISO/TS 18571 rating: none (the window is under 1 ms or over 2 s, or the measurement is zero)".into(),
    }
}

/// The start statistics (the estimation layer's line,
/// [`bumpsim_estimate::text::starts_line`]).
pub fn starts_line(result: &Identification) -> String {
    bumpsim_estimate::text::starts_line(&result.starts, result.iterations, result.run_time)
}

/// The recommended model order among `results`: the fit gained by a
/// further mass must pay for its parameters, counted with the effective
/// sample size of correlated residuals ([`crate::choice`], which also says
/// which rule decided).
pub fn recommended_dof(results: &[Identification]) -> Option<usize> {
    crate::choice::choose(results).map(|c| c.dof)
}

/// The thesis's table 1: DOF, objective, fit %, AIC, BIC (every sample
/// counted), time; then the criteria with the effective sample size and
/// the recommendation with the rule that decided ([`crate::choice::lines`]).
pub fn dof_table(results: &[Identification]) -> String {
    // the objective's unit, what it sums (every size compares the same
    // cases alike): the header said m² over dimensionless figures
    let unit = results
        .first()
        .map_or_else(|| "m²".into(), Identification::objective_unit);
    let objective = format!("objective {unit}");
    let width = objective.chars().count().max(14);
    let mut out = format!(
        "{:>4} {:>width$} {:>9} {:>12} {:>12} {:>10}\n",
        "DOF", objective, "fit %", "AIC", "BIC", "time"
    );
    for r in results {
        out += &format!(
            "{:>4} {:>width$} {:>9} {:>12} {:>12} {:>10}\n",
            r.dof,
            format_number(r.objective, 5),
            format_number(r.fit_percent, 4),
            format_number(r.aic, 6),
            format_number(r.bic, 6),
            format_quantity(r.run_time, Dimension::Time)
        );
    }
    if let Some(choice) = crate::choice::choose(results) {
        out += &crate::choice::lines(&choice);
    }
    out
}
