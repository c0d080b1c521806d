//! The text every model prints of an estimate (the 1-D chain and the planar
//! car alike): the parameter table with units, standard errors, intervals
//! and a note (fixed, at bound, not determined), and the line of start
//! statistics.

use crate::multistart::Starts;
use crate::uncertainty::{Parameter, Uncertainty};
use bumpsim_core::units::{Dimension, format_number, format_quantity};

/// The parameter table: name, value, standard error, 95 % interval, and a
/// note: fixed, at bound, or not determined by the data
/// ([`crate::uncertainty::is_determined`]).
///
/// ```
/// use bumpsim_core::units::Dimension;
/// use bumpsim_estimate::text::parameter_table;
/// use bumpsim_estimate::uncertainty::{Correlation, Parameter, Uncertainty};
/// let u = Uncertainty {
///     names: vec!["m1".into()], standard_errors: vec![Some(2.0)],
///     ci95: vec![Some([96.0, 104.0])], at_bound: vec![false], fixed: vec![false],
///     correlation: vec![vec![Some(1.0)]], residual_std: 1e-4, degrees_of_freedom: 99,
///     singular_values: vec![1.0], condition: 1.0, scales: vec![], determined: vec![Some(true)],
///     weakest_direction: vec![], error_model: Correlation::Independent,
///     residual_correlation: 0.0, inflation: 1.0, warnings: vec![],
/// };
/// let table = parameter_table(&[Parameter::new("m1", Dimension::Mass)], &[100.0], &u);
/// assert!(table.lines().nth(1).unwrap().contains("100.0 kg"), "{table}");
/// ```
pub fn parameter_table(parameters: &[Parameter], theta: &[f64], u: &Uncertainty) -> String {
    let width = parameters
        .iter()
        .map(|p| p.name.chars().count())
        .max()
        .unwrap_or(0)
        .max(5);
    let mut out = format!(
        "{:<width$} {:>14} {:>14} {:>32}  note\n",
        "", "value", "std. error", "95 % interval"
    );
    for (i, (p, &value)) in parameters.iter().zip(theta).enumerate() {
        let se = u.standard_errors[i].map_or("-".to_string(), |s| p.format(s));
        let ci = u.ci95[i].map_or("-".to_string(), |[a, b]| {
            format!("{} .. {}", p.format(a), p.format(b))
        });
        let note = match (u.fixed[i], u.at_bound[i], u.determined.get(i)) {
            (true, _, _) => "fixed",
            (_, true, _) => "at bound",
            (_, _, Some(Some(false))) => "not determined",
            _ => "",
        };
        let value = p.format(value);
        out += &format!("{:<width$} {value:>14} {se:>14} {ci:>32}  {note}\n", p.name);
    }
    out
}

/// The start statistics: run (and refined around the best), converged,
/// abandoned, not polished, failed; the best start's iterations; time (s);
/// reached the best fit (within the noise) and the best objective (to
/// 1e-6), and by how many runs of their own; with κ stated, a fifth: the
/// starts within κ noise variances. Lines of at most about 100 characters
/// (one line ran to 300), the later ones indented by four spaces under the
/// caller's own two.
pub fn starts_line(s: &Starts, iterations: usize, run_time: f64) -> String {
    [
        format!(
            "starts: {} run ({} of them around the best so far); {iterations} iterations; {}",
            s.total,
            s.refined,
            format_quantity(run_time, Dimension::Time)
        ),
        format!(
            "  {} converged, {} abandoned, {} not polished, {} failed",
            s.converged, s.abandoned, s.unpolished, s.failed
        ),
        format!(
            "  {} reached the best fit (F within the noise): {} exploring, {} by their own run",
            s.reached_best_fit, s.explored_best_fit, s.reached_best_fit_alone
        ),
        format!(
            "  {} reached the best objective to 1e-6, {} by their own polished run",
            s.reached_best, s.reached_best_alone
        ),
    ]
    .into_iter()
    .chain(correlated_line(s))
    .collect::<Vec<_>>()
    .join("\n  ")
}

/// With the residuals' correlation stated (κ > 1), how many starts the data
/// cannot tell from the best ([`Starts::reached_correlated`]).
fn correlated_line(s: &Starts) -> Option<String> {
    (s.inflation > 1.0).then(|| {
        format!(
            "  {} reached a fit the data cannot tell from the best (F within κ = {} noise variances)",
            s.reached_correlated,
            format_number(s.inflation, 4)
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_starts_lines_are_at_most_100_characters() {
        let many = 10_000;
        let s = Starts {
            total: many,
            converged: many,
            failed: many,
            reached_best: many,
            reached_best_alone: many,
            reached_best_fit: many,
            reached_best_fit_alone: many,
            reached_correlated: many,
            explored_correlated: many,
            inflation: 1.0,
            abandoned: many,
            merged: many,
            unpolished: many,
            refined: many,
            explored_best_fit: many,
            best: 0,
        };
        let text = starts_line(&s, 123_456, 1234.5);
        assert_eq!(text.lines().count(), 4, "{text}");
        let inflated = Starts {
            inflation: 1234.567,
            ..s
        };
        let correlated = starts_line(&inflated, 123_456, 1234.5);
        assert_eq!(correlated.lines().count(), 5, "{correlated}");
        assert!(
            correlated.ends_with("10000 reached a fit the data cannot tell from the best (F within κ = 1235 noise variances)"),
            "{correlated}"
        );
        for line in text.lines().chain(correlated.lines()) {
            // printed after the caller's two-space indent
            assert!(
                line.chars().count() + 2 <= 100,
                "{} characters: {line}",
                line.len()
            );
        }
        assert!(text.starts_with("starts: 10000 run (10000 of them around the best so far)"));
        assert!(
            text.contains("\n    10000 converged, 10000 abandoned"),
            "{text}"
        );
    }
}
