//! Planar impact pages: striker and side-member forces, yaw, the CG path and
//! the crush of each bumper segment (spec §9 outputs). Units as in
//! [`bumpsim_planar::result`]; plots show display units (kN, mm, deg).

use crate::bar::BarPlot;
use crate::html::Html;
use crate::plot::{Band, LinePlot, PlotError, Series, Span, Style};
use bumpsim_core::units::Dimension;
use bumpsim_planar::PlanarResult;
use bumpsim_planar::forward::Forward;
use bumpsim_planar::picture::TopView;

/// The planar impact report: the HTML page and its figures (file name, SVG).
///
/// `view`: the top view at peak force (`bumpsim_planar::picture`), drawn first.
pub fn planar_report(
    title: &str,
    summary: &str,
    r: &PlanarResult,
    view: Option<&TopView>,
) -> Result<(String, Vec<(String, String)>), PlotError> {
    let mut page = Html::new(&format!("bumpsim planar impact: {title}"));
    page.heading("Results");
    page.preformatted(summary);
    page.warnings(&r.warnings);
    let mut figures = Vec::new();
    if let Some(view) = view {
        let caption = format!("top view at peak force, t = {:.2} ms", view.time * 1e3);
        let svg = crate::topview::top_view_svg(view, &caption)?;
        let legend = crate::topview::legend(view);
        page.figure(&svg, &format!("{caption}: {legend}"));
        figures.push(("top-view.svg".to_string(), svg));
    }
    for (name, svg, caption) in [
        (
            "forces.svg",
            forces(r).svg()?,
            "striker force and side-member forces",
        ),
        ("yaw.svg", yaw(r).svg()?, "yaw angle of the body"),
        ("path.svg", path(r).svg()?, "body CG displacement"),
        (
            "crush.svg",
            crush(r).svg()?,
            "largest crush of each bumper segment (right to left)",
        ),
    ] {
        page.figure(&svg, caption);
        figures.push((name.to_string(), svg));
    }
    page.heading("Bumper segments");
    page.table(
        &[
            "segment",
            "lateral position [mm]",
            "largest crush [mm]",
            "remaining crush [mm]",
        ],
        &segment_rows(r),
    );
    Ok((page.finish(), figures))
}

fn line(name: &str, x: &[f64], y: &[f64], style: Style) -> Series {
    Series::new(name, x.to_vec(), y.to_vec(), style)
}

fn forces(r: &PlanarResult) -> LinePlot {
    let mut plot = LinePlot::new("Forces", Dimension::Time, Dimension::Force);
    plot.add(line("striker force", &r.time, &r.force, Style::Solid));
    plot.add(line(
        "left side member",
        &r.time,
        &r.side_force_left,
        Style::Dashed,
    ));
    plot.add(line(
        "right side member",
        &r.time,
        &r.side_force_right,
        Style::Dashed,
    ));
    plot
}

fn yaw(r: &PlanarResult) -> LinePlot {
    let mut plot = LinePlot::new("Yaw", Dimension::Time, Dimension::Angle);
    plot.add(line("yaw", &r.time, &r.yaw, Style::Solid));
    plot
}

fn path(r: &PlanarResult) -> LinePlot {
    let mut plot = LinePlot::new("Body CG", Dimension::Time, Dimension::Length)
        .quantities(None, Some("position"));
    plot.add(line("x", &r.time, &r.x, Style::Solid));
    plot.add(line("y", &r.time, &r.y, Style::Solid));
    plot
}

fn crush(r: &PlanarResult) -> BarPlot {
    let labels = r
        .segment_centres
        .iter()
        .enumerate()
        .map(|(j, y)| format!("{} ({:.0})", j + 1, y * 1e3));
    BarPlot {
        title: "Crush per segment (lateral position in mm)".into(),
        y_label: "crush [mm]".into(),
        labels: labels.collect(),
        values: r.max_crush.iter().map(|v| v * 1e3).collect(),
        errors: vec![None; r.max_crush.len()],
    }
}

fn segment_rows(r: &PlanarResult) -> Vec<Vec<String>> {
    let mm = |v: f64| format!("{:.2}", v * 1e3);
    (0..r.max_crush.len())
        .map(|j| {
            let y = r.segment_centres.get(j).copied().unwrap_or(0.0);
            let remaining = r.remaining_crush.get(j).copied().unwrap_or(0.0);
            vec![
                (j + 1).to_string(),
                mm(y),
                mm(r.max_crush[j]),
                mm(remaining),
            ]
        })
        .collect()
}

/// The x and yaw plots of a planar case, model against measurement, the
/// case's window shaded (named `fitted window` when `fitted`, else
/// `scored window`: the fit is only measured there): file name
/// (`<case>-x.svg`, `<case>-yaw.svg`), SVG and caption with the fit.
pub fn case_figures(
    p: &bumpsim_planar::identify::Prediction,
    fitted: bool,
) -> Result<Vec<(String, String, String)>, PlotError> {
    let window = Span::window(if fitted { "fitted" } else { "scored" }, p.fit.window);
    let mut x = LinePlot::new("x (mean of the sills)", Dimension::Time, Dimension::Length)
        .quantities(None, Some("displacement"));
    let measured = match p.fit.bias_x {
        Some(_) => "measured, less its bias read after the contact",
        None => "measured",
    };
    x.add(line(measured, &p.time, &p.x[1], Style::Solid));
    x.add(line("model", &p.time, &p.x[0], Style::Dashed));
    shaded(&mut x, &p.time, p.x_band.as_ref());
    x.span(window.clone());
    let mut yaw = LinePlot::new(
        "Yaw (difference of the sills)",
        Dimension::Time,
        Dimension::Angle,
    );
    yaw.add(line("measured", &p.time, &p.yaw[1], Style::Solid));
    yaw.add(line("model", &p.time, &p.yaw[0], Style::Dashed));
    shaded(&mut yaw, &p.time, p.yaw_band.as_ref());
    yaw.span(window.clone());
    let stem = crate::file_name(&p.fit.name);
    let at = |t: f64| p.time.iter().position(|s| *s >= t - 1e-12).unwrap_or(0);
    let samples = (at(p.fit.window[0]), at(p.fit.window[1]));
    [
        ("x", x, p.fit.fit_x, &p.x_band, &p.x[1]),
        ("yaw", yaw, p.fit.fit_yaw, &p.yaw_band, &p.yaw[1]),
    ]
    .into_iter()
    .map(|(what, plot, fit, band, measured)| {
        let svg = plot.svg()?;
        Ok((
            format!("{stem}-{what}.svg"),
            svg,
            format!(
                "{what}: fit {fit:.2} % over the shaded {}{}",
                window.name,
                inside(band.as_ref(), measured, samples)
            ),
        ))
    })
    .collect()
}

/// `band` shaded on `plot` at `time`, named by its level, when there is one.
fn shaded(plot: &mut LinePlot, time: &[f64], band: Option<&bumpsim_planar::bands::PredictiveBand>) {
    if let Some(b) = band {
        plot.band(Band {
            name: format!("{:.0} % predictive band", 100.0 * b.level),
            x: time.to_vec(),
            low: b.low.clone(),
            high: b.high.clone(),
        });
    }
}

/// `; 87 % of the measured samples inside the 90 % band`, or nothing without a band.
fn inside(
    band: Option<&bumpsim_planar::bands::PredictiveBand>,
    measured: &[f64],
    window: (usize, usize),
) -> String {
    band.map_or(String::new(), |b| {
        format!(
            "; {:.0} % of the measured samples inside the shaded {:.0} % predictive band",
            100.0 * b.inside(measured, window),
            100.0 * b.level
        )
    })
}

/// The forward prediction's plots of a case (force, x-acceleration, yaw
/// rate; simulated from car, bumper and striker against the measurement,
/// not fitted: the window its fit is scored over shaded): file name
/// (`<case>-forward-force.svg`, ...), SVG and caption with the fit and the
/// ISO/TS 18571 rating.
pub fn forward_figures(f: &Forward) -> Result<Vec<(String, String, String)>, PlotError> {
    let stem = crate::file_name(&f.case);
    f.channels
        .iter()
        .map(|c| {
            let dimension = match c.name {
                "force" => Dimension::Force,
                "yaw rate" => Dimension::AngularVelocity,
                _ => Dimension::Acceleration,
            };
            let mut plot =
                LinePlot::new(&format!("Forward {}", c.name), Dimension::Time, dimension);
            plot.add(line("measured", &c.time, &c.measured, Style::Solid));
            plot.add(line("forward model", &c.time, &c.simulated, Style::Dashed));
            shaded(&mut plot, &c.time, c.band.as_ref());
            let (a, b) = f.window;
            if let (Some(&start), Some(&end)) = (c.time.get(a), c.time.get(b)) {
                plot.span(Span::window("scored", [start, end]));
            }
            let rating = c.rating.map_or("-".into(), |r| format!("{:.3}", r.overall));
            Ok((
                format!("{stem}-forward-{}.svg", c.name.replace(' ', "-")),
                plot.svg()?,
                format!(
                    "forward {}: fit {:.2} %, ISO/TS 18571 {rating}{}",
                    c.name,
                    c.fit_percent,
                    inside(c.band.as_ref(), &c.measured, f.window)
                ),
            ))
        })
        .collect()
}

/// One case of a planar identification for the report: its prediction,
/// whether it was fitted or only predicted (validation), and its forward
/// prediction when the case names its striker.
pub struct CasePage<'a> {
    /// The replay against the measurement.
    pub prediction: &'a bumpsim_planar::identify::Prediction,
    /// Predicted only, not fitted.
    pub validation: bool,
    /// The whole test simulated from car, bumper and striker.
    pub forward: Option<&'a Forward>,
}

/// The planar identification report: the summary (the identified car,
/// the fits, the warnings) first, then x and yaw of every case, model
/// against measurement with its window shaded, and its forward
/// prediction's force, x-acceleration and yaw rate; the inputs (the notes
/// on the channels' time base, if any, and the study file's text) last
/// (file name, SVG).
///
/// `warnings`: those the summary does not print (the forward
/// predictions'), each in a box under it.
pub fn identification_report(
    (summary, warnings): (&str, &[String]),
    inputs: &str,
    notes: &[String],
    cases: &[CasePage],
) -> Result<(String, Vec<(String, String)>), PlotError> {
    let mut page = Html::new("bumpsim planar identification");
    page.heading("Results");
    page.preformatted(summary);
    page.warnings(warnings);
    let mut figures: Vec<(String, String)> = Vec::new();
    for case in cases {
        let p = case.prediction;
        let kind = if case.validation {
            "validation, not fitted"
        } else {
            "fitted"
        };
        page.heading(&format!("{} ({kind})", p.fit.name));
        let forward = case.forward.map(forward_figures).transpose()?;
        for (name, svg, caption) in case_figures(p, !case.validation)?
            .into_iter()
            .chain(forward.into_iter().flatten())
        {
            page.figure(&svg, &caption);
            let name = crate::unique_name(&name, |n| figures.iter().any(|(f, _)| f == n));
            figures.push((name, svg));
        }
    }
    page.heading("Inputs");
    if !notes.is_empty() {
        page.paragraph("Channel time base:");
        page.notes(notes);
    }
    page.preformatted(inputs);
    Ok((page.finish(), figures))
}

#[cfg(test)]
mod tests {
    use super::*;
    use bumpsim_core::model::MsdModel;
    use bumpsim_impact::bumper::Bumper;
    use bumpsim_planar::car::{Layout, PlanarCar};
    use bumpsim_planar::{Face, Settings, Side, Striker, simulate};

    #[test]
    fn the_page_holds_four_figures_and_the_segment_table() {
        let chain = MsdModel::new(vec![10.0, 1200.0], vec![2e3], vec![2e6]).unwrap();
        let bumper = Bumper::three_part(1.5e6, 60e3, 6e6).unwrap();
        let car = PlanarCar::symmetric(&chain, &bumper, &Layout::default()).unwrap();
        let face = Face::plane_in_degrees(10.0, 40.0, Side::Left);
        let r = simulate(
            &car,
            &Striker::barrier(face, 15.0 / 3.6),
            &Settings::default(),
        )
        .unwrap();
        let striker = Striker::barrier(face, 15.0 / 3.6);
        let k = bumpsim_planar::picture::peak_sample(&r);
        let view = bumpsim_planar::picture::top_view(&car, &striker, &r, k).unwrap();
        let (html, figures) = planar_report("RCAR", "summary", &r, Some(&view)).unwrap();
        assert_eq!(figures.len(), 5);
        assert!(figures[0].0 == "top-view.svg" && figures[0].1.contains("<polygon"));
        assert!(figures.iter().all(|(_, svg)| svg.starts_with("<svg")));
        assert!(html.contains("remaining crush [mm]") && html.contains("<svg"));
    }
}
