//! DOE plots: coefficients with 95 % error bars (MODDE style), observed
//! against predicted, the normal probability plot of the residuals, and the
//! reachable region of two responses (random factor sets, exact boundary, cell).

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

/// The reachable region of responses `axes` (x, y): up to ~2000 of the
/// random `points`, the exact boundary `polygon` closed, and the cell
/// `[x0, x1, y0, y1]` dashed when given.
pub fn reach_plot(
    axes: [&str; 2],
    points: &[[f64; 2]],
    polygon: &[[f64; 2]],
    cell: Option<[f64; 4]>,
) -> Result<String, PlotError> {
    let mut p = LinePlot::new(
        "Reachable region",
        Dimension::Dimensionless,
        Dimension::Dimensionless,
    )
    .with_labels(Some(axes[0]), Some(axes[1]));
    let shown = points.iter().step_by((points.len() / 2000).max(1));
    let (sx, sy): (Vec<f64>, Vec<f64>) = shown.map(|p| (p[0], p[1])).unzip();
    p.add(Series::new("random factor sets", sx, sy, Style::Points));
    let closed: Vec<[f64; 2]> = polygon.iter().chain(polygon.first()).copied().collect();
    p.add(Series::new(
        "exact boundary",
        closed.iter().map(|v| v[0]).collect(),
        closed.iter().map(|v| v[1]).collect(),
        Style::Solid,
    ));
    if let Some([x0, x1, y0, y1]) = cell {
        p.add(Series::new(
            "cell",
            vec![x0, x1, x1, x0, x0],
            vec![y0, y0, y1, y1, y0],
            Style::Dashed,
        ));
    }
    p.svg()
}
