//! DOE plots: coefficients with 95 % error bars (MODDE style), observed
//! against predicted, and the normal probability plot of the residuals.

use crate::bar::BarPlot;
use crate::plot::{LinePlot, PlotError, Series, Style};
use bumpsim_core::units::Dimension;
use bumpsim_doe::regression::{Fit, normal_scores};

/// A plot: file name, SVG, caption.
pub type Figure = (String, String, String);

/// The plots of one fitted response with observations `y`.
pub fn fit_plots(response: &str, unit: &str, f: &Fit, y: &[f64]) -> Result<Vec<Figure>, PlotError> {
    let file = crate::file_name(response);
    let skip_intercept = 1.min(f.terms.len());
    let bars = BarPlot {
        title: format!("{response}: coded coefficients with 95 % intervals"),
        y_label: format!("coefficient [{unit}]"),
        labels: f.terms[skip_intercept..].to_vec(),
        values: f.coefficients[skip_intercept..].to_vec(),
        errors: f.ci95[skip_intercept..].to_vec(),
    };
    let label = format!("{response} [{unit}]");
    let mut observed = LinePlot::new(
        &format!("{response}: observed against predicted"),
        Dimension::Dimensionless,
        Dimension::Dimensionless,
    )
    .with_labels(
        Some(&format!("predicted {label}")),
        Some(&format!("observed {label}")),
    );
    let lo = y
        .iter()
        .chain(&f.fitted)
        .copied()
        .fold(f64::INFINITY, f64::min);
    let hi = y
        .iter()
        .chain(&f.fitted)
        .copied()
        .fold(f64::NEG_INFINITY, f64::max);
    observed.add(Series::new(
        "runs",
        f.fitted.clone(),
        y.to_vec(),
        Style::Points,
    ));
    observed.add(Series::new(
        "y = x",
        vec![lo, hi],
        vec![lo, hi],
        Style::Dashed,
    ));
    let scores = normal_scores(&f.residuals);
    let mut normal = LinePlot::new(
        &format!("{response}: residuals, normal probability"),
        Dimension::Dimensionless,
        Dimension::Dimensionless,
    )
    .with_labels(
        Some("normal quantile [-]"),
        Some(&format!("residual [{unit}]")),
    );
    normal.add(Series::new(
        "residuals",
        scores.iter().map(|s| s.0).collect(),
        scores.iter().map(|s| s.1).collect(),
        Style::Points,
    ));
    let mut out = Vec::new();
    if bars.values.is_empty() {
        return Ok(out);
    }
    out.push((
        format!("{file}-coefficients.svg"),
        bars.svg()?,
        format!("{response}: coefficients (coded units) with 95 % intervals"),
    ));
    out.push((
        format!("{file}-observed.svg"),
        observed.svg()?,
        format!("{response}: observed against predicted"),
    ));
    if f.residuals.iter().any(|r| r.abs() > 0.0) {
        out.push((
            format!("{file}-residuals.svg"),
            normal.svg()?,
            format!("{response}: normal probability plot of the residuals"),
        ));
    }
    Ok(out)
}
