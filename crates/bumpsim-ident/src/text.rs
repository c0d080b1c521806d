//! Human-readable text for identification results: parameters with units,
//! the DOF table, per-case fits. The CLI prints these strings; reports reuse them.

use crate::estimate::Identification;
use bumpsim_core::model::{format_parameter, parameter_count, parameter_name};
use bumpsim_core::units::{Dimension, format_number, format_quantity};

/// The parameter table: name, value, standard error, 95 % interval, and a
/// note: fixed, at bound, or not determined by the data
/// ([`crate::stats::is_determined`]).
pub fn parameter_table(result: &Identification) -> String {
    let dof = result.dof;
    let theta = result.model.parameters();
    let u = &result.uncertainty;
    let mut out = format!(
        "{:<5} {:>14} {:>14} {:>32}  note\n",
        "", "value", "std. error", "95 % interval"
    );
    for (i, &value) in theta.iter().enumerate().take(parameter_count(dof)) {
        let se = u.standard_errors[i].map_or("-".to_string(), |s| format_parameter(dof, i, s));
        let ci = u.ci95[i].map_or("-".to_string(), |[a, b]| {
            format!(
                "{} .. {}",
                format_parameter(dof, i, a),
                format_parameter(dof, i, b)
            )
        });
        let note = match (u.fixed[i], u.at_bound[i], u.determined.get(i)) {
            (true, _, _) => "fixed",
            (_, true, _) => "at bound",
            (_, _, Some(Some(false))) => "not determined",
            _ => "",
        };
        let value = format_parameter(dof, i, value);
        out += &format!(
            "{:<5} {value:>14} {se:>14} {ci:>32}  {note}\n",
            parameter_name(dof, i)
        );
    }
    out
}

/// Per-case fit lines.
pub fn case_lines(result: &Identification) -> String {
    result
        .cases
        .iter()
        .map(|c| {
            format!(
                "  {:<16} fit {:>7}  SSE {} m²  ({} samples)\n",
                c.name,
                format!("{} %", format_number(c.fit_percent, 4)),
                format_number(c.sse, 4),
                c.samples
            )
        })
        .collect()
}

/// The start statistics: run (and refined around the best), converged,
/// reached the best fit (within the noise) and the best objective (to
/// 1e-6), and by how many runs of their own; abandoned, not polished,
/// failed; the best start's iterations; time.
pub fn starts_line(result: &Identification) -> String {
    let s = &result.starts;
    format!(
        "starts: {} run ({} of them around the best so far), {} converged, {} reached the best fit (F within one noise variance; {} of the exploring starts, {} by their own run), {} the best objective to 1e-6 ({} by their own polished run), {} abandoned, {} not polished, {} failed; {} iterations; {}",
        s.total,
        s.refined,
        s.converged,
        s.reached_best_fit,
        s.explored_best_fit,
        s.reached_best_fit_alone,
        s.reached_best,
        s.reached_best_alone,
        s.abandoned,
        s.unpolished,
        s.failed,
        result.iterations,
        format_quantity(result.run_time, Dimension::Time)
    )
}

/// The DOF with the lowest BIC among `results` (the recommended model
/// order: the fit gained by a further mass must pay for its parameters).
pub fn recommended_dof(results: &[Identification]) -> Option<usize> {
    results
        .iter()
        .filter(|r| r.bic.is_finite())
        .min_by(|a, b| a.bic.total_cmp(&b.bic))
        .map(|r| r.dof)
}

/// The thesis's table 1: DOF, objective, fit %, AIC, BIC, time.
pub fn dof_table(results: &[Identification]) -> String {
    let mut out = format!(
        "{:>4} {:>14} {:>9} {:>12} {:>12} {:>10}\n",
        "DOF", "objective m²", "fit %", "AIC", "BIC", "time"
    );
    for r in results {
        out += &format!(
            "{:>4} {:>14} {:>9} {:>12} {:>12} {:>10}\n",
            r.dof,
            format_number(r.objective, 5),
            format_number(r.fit_percent, 4),
            format_number(r.aic, 6),
            format_number(r.bic, 6),
            format_quantity(r.run_time, Dimension::Time)
        );
    }
    if let Some(dof) = recommended_dof(results) {
        out += &format!("recommended: {dof} DOF (lowest BIC)\n");
    }
    out
}
