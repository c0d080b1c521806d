//! DOE plots: coefficients with 95 % error bars (MODDE style), observed
//! against predicted, the normal probability plot of the residuals, and the
//! reachable region of two responses (random factor sets, exact boundary, cell),
//! and the DOE fit report ([`fit_report`]): each response's fit with its
//! plots first, the inputs last.

use crate::bar::BarPlot;
use crate::html::Html;
use crate::plot::{LinePlot, PlotError, Series, Style};
use bumpsim_core::units::{Dimension, Unit};
use bumpsim_doe::regression::{Fit, normal_scores};

/// A plot: file name, SVG, caption.
pub type Figure = (String, String, String);

/// A response's unit for its plots: a known unit (`N`, `m`, `J`, ...) is
/// drawn in its dimension's display unit (kN, mm, J: docs/reports.md);
/// another unit as given. Returns the dimension, the unit shown, and the
/// factors from the response's values to SI and to the unit shown.
fn display(unit: &str) -> (Dimension, String, f64, f64) {
    match Unit::parse(unit) {
        Ok(u) if u.dimension != Dimension::Dimensionless => {
            let shown = u.dimension.display_unit();
            let symbol = shown.symbol.to_string();
            (u.dimension, symbol, u.factor, u.factor / shown.factor)
        }
        _ => (Dimension::Dimensionless, unit.to_string(), 1.0, 1.0),
    }
}

/// The plots of one fitted response with observations `y` (in `unit`).
pub fn fit_plots(response: &str, unit: &str, f: &Fit, y: &[f64]) -> Result<Vec<Figure>, PlotError> {
    let file = crate::file_name(response);
    let skip_intercept = 1.min(f.terms.len());
    let (dimension, shown, si, factor) = display(unit);
    let scaled = |v: &[f64]| -> Vec<f64> { v.iter().map(|x| x * factor).collect() };
    let bars = BarPlot {
        title: format!("{response}: coded coefficients with 95 % intervals"),
        y_label: format!("coefficient [{shown}]"),
        labels: f.terms[skip_intercept..].to_vec(),
        values: scaled(&f.coefficients[skip_intercept..]),
        errors: f.ci95[skip_intercept..]
            .iter()
            .map(|e| e.map(|[lo, hi]| [lo * factor, hi * factor]))
            .collect(),
    };
    // the line plots take SI values and draw them in the display unit
    let to_si = |v: &[f64]| -> Vec<f64> { v.iter().map(|x| x * si).collect() };
    let label = format!("{response} [{shown}]");
    let mut observed = LinePlot::new(
        &format!("{response}: observed against predicted"),
        dimension,
        dimension,
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
        to_si(&f.fitted),
        to_si(y),
        Style::Points,
    ));
    observed.add(Series::new(
        "y = x",
        to_si(&[lo, hi]),
        to_si(&[lo, hi]),
        Style::Dashed,
    ));
    let scores = normal_scores(&f.residuals);
    let mut normal = LinePlot::new(
        &format!("{response}: residuals, normal probability"),
        Dimension::Dimensionless,
        dimension,
    )
    .with_labels(
        Some("normal quantile [-]"),
        Some(&format!("residual [{shown}]")),
    );
    normal.add(Series::new(
        "residuals",
        scores.iter().map(|s| s.0).collect(),
        to_si(&scores.iter().map(|s| s.1).collect::<Vec<_>>()),
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

/// One fitted response in the report: its heading (name and unit), the
/// fit's text and its plots.
#[derive(Debug, Clone)]
pub struct ResponsePage {
    /// `peak_force [N]`.
    pub heading: String,
    /// The fit as the CLI prints it (coefficients, R², Q², ...).
    pub text: String,
    /// Its plots ([`fit_plots`]).
    pub figures: Vec<Figure>,
}

/// The DOE fit report: each response's fit and its plots, then the inputs
/// (the data file and the model's terms, as name and value).
///
/// ```
/// use bumpsim_report::doe::{ResponsePage, fit_report};
/// let r = ResponsePage { heading: "F [N]".into(), text: "R² 0.99".into(), figures: vec![] };
/// let page = fit_report("runs.csv", &[("factors".into(), "a, b".into())], &[r]);
/// assert!(page.find("R² 0.99") < page.find("runs.csv</td>"));
/// ```
pub fn fit_report(data: &str, inputs: &[(String, String)], responses: &[ResponsePage]) -> String {
    let mut page = Html::new(&format!("bumpsim DOE fit: {data}"));
    for r in responses {
        page.heading(&r.heading);
        page.preformatted(&r.text);
        for (_, svg, caption) in &r.figures {
            page.figure(svg, caption);
        }
    }
    page.heading("Inputs");
    let rows: Vec<Vec<String>> = std::iter::once(("data".to_string(), data.to_string()))
        .chain(inputs.iter().cloned())
        .map(|(k, v)| vec![k, v])
        .collect();
    page.table(&["input", "value"], &rows);
    page.finish()
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

#[cfg(test)]
mod tests {
    use super::*;
    use bumpsim_doe::regression::{fit, terms};

    /// A campaign's peak force in N: the plots draw it in kN (as
    /// docs/reports.md promises), not with ticks like "70000.0".
    #[test]
    fn a_force_in_newton_is_drawn_in_kilonewton() {
        let z: Vec<Vec<f64>> = [-1.0, 1.0, -1.0, 1.0, 0.0]
            .iter()
            .zip([-1.0, -1.0, 1.0, 1.0, 0.0])
            .map(|(a, b)| vec![*a, b])
            .collect();
        let y = [60e3, 70e3, 65e3, 76e3, 68.5e3];
        let f = fit(&z, &y, &terms(2, false, false), &["a".into(), "b".into()]).unwrap();
        let plots = fit_plots("peak_force", "N", &f, &y).unwrap();
        let observed = &plots
            .iter()
            .find(|p| p.0.ends_with("-observed.svg"))
            .unwrap()
            .1;
        assert!(observed.contains("observed peak_force [kN]"), "label in kN");
        let ticks: Vec<f64> = observed
            .split("<text")
            .skip(1)
            .filter_map(|t| t.split('>').nth(1)?.split('<').next()?.trim().parse().ok())
            .collect();
        assert!(
            !ticks.is_empty() && ticks.iter().all(|t| t.abs() < 1000.0),
            "{ticks:?}"
        );
        let bars = &plots[0].1;
        assert!(bars.contains("coefficient [kN]"), "coefficients in kN");
        // a unit bumpsim does not know is drawn as given
        let plots = fit_plots("score", "points", &f, &y).unwrap();
        assert!(plots[1].1.contains("observed score [points]"));
    }
}
