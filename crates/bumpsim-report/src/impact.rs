//! Impact and mass-reduction plots and pages: force against time and
//! compression, displacements, and the heat map of a sweep.

use crate::heatmap::HeatMap;
use crate::html::Html;
use crate::plot::{LinePlot, PlotError, Series, Style};
use bumpsim_core::units::Dimension;
use bumpsim_impact::impact::ImpactResult;
use bumpsim_impact::reduction::Grid;

/// The impact report: the HTML page and its figures (file name, SVG).
pub fn impact_report(
    title: &str,
    summary: &str,
    r: &ImpactResult,
) -> Result<(String, Vec<(String, String)>), PlotError> {
    impact_page(title, &[], &[], summary, r)
}

/// The impact report: the results and notes on reading them (e.g. the FE
/// run's force at t = 0) first, the plots, and its inputs (name, value)
/// last.
pub fn impact_page(
    title: &str,
    inputs: &[(String, String)],
    notes: &[&str],
    summary: &str,
    r: &ImpactResult,
) -> Result<(String, Vec<(String, String)>), PlotError> {
    let mut page = Html::new(&format!("bumpsim impact: {title}"));
    page.heading("Results");
    page.preformatted(summary);
    notes.iter().for_each(|n| page.paragraph(n));
    let mut force = LinePlot::new("Bumper force", Dimension::Time, Dimension::Force);
    force.add(Series::new(
        "force",
        r.time.clone(),
        r.force.clone(),
        Style::Solid,
    ));
    let mut curve = LinePlot::new(
        "Force against compression",
        Dimension::Length,
        Dimension::Force,
    )
    .quantities(Some("compression"), None);
    curve.add(Series::new(
        "bumper",
        r.compression.clone(),
        r.force.clone(),
        Style::Solid,
    ));
    let mut motion = LinePlot::new("Displacements", Dimension::Time, Dimension::Length)
        .quantities(None, Some("displacement"));
    for (b, x) in r.bodies.iter().zip(&r.displacements) {
        motion.add(Series::new(b, r.time.clone(), x.clone(), Style::Solid));
    }
    let mut figures = Vec::new();
    for (name, plot, caption) in [
        ("force.svg", force, "bumper force"),
        ("force-compression.svg", curve, "force against compression"),
        ("displacements.svg", motion, "displacements of the bodies"),
    ] {
        let svg = plot.svg()?;
        page.figure(&svg, caption);
        figures.push((name.to_string(), svg));
    }
    if !inputs.is_empty() {
        page.heading("Inputs");
        let rows: Vec<Vec<String>> = inputs
            .iter()
            .map(|(k, v)| vec![k.clone(), v.clone()])
            .collect();
        page.table(&["input", "value"], &rows);
    }
    Ok((page.finish(), figures))
}

/// The heat map of a mass-reduction sweep (N/m and N shown as kN/m and kN).
pub fn heat_map(grid: &Grid) -> HeatMap {
    let scale = |label: &str, v: &[f64]| match label.contains("[N/m]") || label.contains("[N]") {
        true => (
            label.replace("[N/m]", "[kN/m]").replace("[N]", "[kN]"),
            v.iter().map(|x| x / 1e3).collect(),
        ),
        false => (label.to_string(), v.to_vec()),
    };
    let (x_label, x) = scale(&grid.x_label, &grid.x);
    let (y_label, y) = scale(&grid.y_label, &grid.y);
    HeatMap {
        title: "Scale factor for mass (paper A)".into(),
        x_label,
        y_label,
        value_label: "M*/(M1+M2) [-]".into(),
        x,
        y,
        values: grid.values.clone(),
    }
}
