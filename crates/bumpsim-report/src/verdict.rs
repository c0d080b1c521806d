//! The verdict report (issue 36): the table of tests × criteria with each
//! criterion's value, limit, margin (with its unit) and verdict coloured
//! pass/fail, its probability of passing when the verdict was propagated
//! (issue 39, [`bumpsim_verdict::probability`]), the assumptions, then per test the top view of the car at
//! peak force, the forces (striker, side members, the rails' yield force)
//! and the bumper's crush against its stroke; with a target search, the
//! force–deflection corridor of the passing bumpers and the table of the
//! passing force levels with the criterion binding at each boundary
//! ([`bumpsim_verdict::target`]); with Sobol indices, their table and
//! per test the total indices of its binding criterion as bars with their
//! 95 % bootstrap intervals ([`bumpsim_verdict::sensitivity`], issue 39).

use crate::bar::BarPlot;
use crate::html::Html;
use crate::plot::{Band, LinePlot, PlotError, Series, Style};
use bumpsim_core::units::Dimension;
use bumpsim_planar::PlanarResult;
use bumpsim_verdict::sensitivity::{self, Sensitivity};
use bumpsim_verdict::target::{Bound, Region};
use bumpsim_verdict::verdict::{TestVerdict, Verdict};

/// Background colours of the verdict cells: pass, fail, reported only.
const COLOURS: [(&str, &str); 3] = [
    (
        "<td>pass</td>",
        "<td style=\"background:#d8f0d8\">pass</td>",
    ),
    (
        "<td>FAIL</td>",
        "<td style=\"background:#f8cfcc;font-weight:bold\">FAIL</td>",
    ),
    (
        "<td>info</td>",
        "<td style=\"background:#eeeeee\">info</td>",
    ),
];

/// The verdict report: the HTML page and its figures (file name, SVG).
///
/// ```
/// use bumpsim_verdict::prelude::*;
/// let v = Verdict { car: "car".into(), margin: 0.0, tests: vec![], propagation: None, requirements: vec![] };
/// let (html, figures) = bumpsim_report::verdict::verdict_report(&v, None, None).unwrap();
/// assert!(html.contains("every assessed test passes") && figures.is_empty());
/// ```
pub fn verdict_report(
    v: &Verdict,
    region: Option<&Region>,
    indices: Option<&Sensitivity>,
) -> Result<(String, Vec<(String, String)>), PlotError> {
    let mut page = Html::new(&format!("bumpsim verdict: {}", v.car));
    page.heading("Verdict");
    page.paragraph(&format!(
        "Each criterion passes when its margin is at least {} % of its limit: the margin column's share, 100 % being the limit; a row that says \"of …\" takes that as its 100 % (a pendulum's beam engagement, whose limit is 0 mm, takes the ridge's height range).",
        100.0 * v.margin
    ));
    let (headers, rows) = bumpsim_verdict::text::columns(v);
    page.table(&headers, &rows);
    let text = bumpsim_verdict::text::summary(v) + &bumpsim_verdict::text::propagation(v);
    page.preformatted(&text);
    assumptions(&mut page, v);
    requirements(&mut page, v);
    let mut figures = Vec::new();
    for t in &v.tests {
        test_figures(&mut page, &mut figures, t)?;
    }
    if let Some(s) = indices {
        sobol(&mut page, &mut figures, s, v)?;
    }
    if let Some(r) = region {
        target(&mut page, &mut figures, r, v)?;
    }
    let mut html = page.finish();
    for (plain, coloured) in COLOURS {
        html = html.replace(plain, coloured);
    }
    Ok((html, figures))
}

/// Each test's assumptions, notes and warnings.
fn assumptions(page: &mut Html, v: &Verdict) {
    page.heading("Assumptions");
    let mut stated: Vec<String> = Vec::new();
    for t in v.tests.iter().filter(|t| t.skipped.is_none()) {
        for a in t.assumptions.iter().chain(&t.notes) {
            stated.push(format!("{}: {a}", t.test.name));
        }
    }
    page.notes(&stated);
    let warnings: Vec<String> = v
        .tests
        .iter()
        .flat_map(|t| t.warnings.iter().map(|w| format!("{}: {w}", t.test.name)))
        .collect();
    page.warnings(&warnings);
}

/// What the protocols run require, each judged by the model, by a proxy
/// or not judged ([`bumpsim_verdict::requirements`]).
fn requirements(page: &mut Html, v: &Verdict) {
    if v.requirements.is_empty() {
        return;
    }
    page.heading("What is judged and what is not");
    let headers = [
        "protocol",
        "clause",
        "requirement",
        "judged",
        "by",
        "why",
        "wording checked",
    ];
    let rows: Vec<Vec<String>> = v
        .requirements
        .iter()
        .flat_map(|r| r.list.iter().map(move |q| (r.protocol, q)))
        .map(|(protocol, q)| {
            let j = &q.judgement;
            vec![
                protocol.to_string(),
                q.clause.to_string(),
                q.requirement.to_string(),
                j.word().to_string(),
                j.by().unwrap_or("the engineer must check it").to_string(),
                j.why().unwrap_or("").to_string(),
                if q.verified { "yes" } else { "no" }.to_string(),
            ]
        })
        .collect();
    page.table(&headers, &rows);
}

/// A test's top view at peak force, its forces and its crush.
fn test_figures(
    page: &mut Html,
    figures: &mut Vec<(String, String)>,
    t: &TestVerdict,
) -> Result<(), PlotError> {
    let (Some(r), Some((car, striker))) = (&t.result, &t.run) else {
        return Ok(());
    };
    let name = t.test.name;
    page.heading(&format!("{name}: {}", t.test.description));
    page.paragraph(&format!("Striker: {}", t.striker));
    let stem = crate::file_name(name);
    let k = bumpsim_planar::picture::peak_sample(r);
    let caption = format!(
        "{name}: top view at peak force, t = {:.2} ms",
        r.time[k] * 1e3
    );
    let view =
        bumpsim_planar::picture::top_view(car, striker, r, k).map_err(|e| PlotError::Draw {
            title: caption.clone(),
            message: e.to_string(),
        })?;
    let drawn = [
        (
            "top-view",
            crate::topview::top_view_svg(&view, &caption)?,
            format!("{caption}: {}", crate::topview::legend(&view)),
        ),
        (
            "forces",
            forces(name, r, limit(t, "rail force")).svg()?,
            format!("{name}: striker force and side-member forces against the rails' yield force"),
        ),
        (
            "crush",
            crush(name, r, limit(t, "bumper stroke")).svg()?,
            format!("{name}: the largest crush of a bumper segment against the bumper's stroke"),
        ),
    ];
    for (what, svg, caption) in drawn {
        page.figure(&svg, &caption);
        figures.push((format!("{stem}-{what}.svg"), svg));
    }
    Ok(())
}

/// The limit of a test's criterion, SI.
fn limit(t: &TestVerdict, criterion: &str) -> Option<f64> {
    t.criteria
        .iter()
        .find(|c| c.name == criterion)
        .map(|c| c.limit)
}

/// A constant line at `value` over the impact's time.
fn level(name: &str, time: &[f64], value: f64) -> Series {
    let ends = vec![time[0], time[time.len() - 1]];
    Series::new(name, ends, vec![value; 2], Style::Dashed)
}

fn forces(test: &str, r: &PlanarResult, yield_force: Option<f64>) -> LinePlot {
    let mut plot = LinePlot::new(
        &format!("Forces, {test}"),
        Dimension::Time,
        Dimension::Force,
    );
    for (name, history) in [
        ("striker force", &r.force),
        ("left side member", &r.side_force_left),
        ("right side member", &r.side_force_right),
    ] {
        plot.add(Series::new(
            name,
            r.time.clone(),
            history.clone(),
            Style::Solid,
        ));
    }
    if let Some(f) = yield_force {
        plot.add(level("rail yield force (limit)", &r.time, f));
    }
    plot
}

fn crush(test: &str, r: &PlanarResult, stroke: Option<f64>) -> LinePlot {
    let mut plot = LinePlot::new(
        &format!("Crush, {test}"),
        Dimension::Time,
        Dimension::Length,
    )
    .quantities(None, Some("crush"));
    let largest = (0..r.time.len())
        .map(|k| r.crush.iter().map(|c| c[k]).fold(0.0, f64::max))
        .collect();
    plot.add(Series::new(
        "largest segment crush",
        r.time.clone(),
        largest,
        Style::Solid,
    ));
    if let Some(s) = stroke {
        plot.add(level("bumper stroke (limit)", &r.time, s));
    }
    plot
}

/// The Sobol indices: their table, and per test the total indices of its
/// binding criterion with their intervals.
fn sobol(
    page: &mut Html,
    figures: &mut Vec<(String, String)>,
    s: &Sensitivity,
    v: &Verdict,
) -> Result<(), PlotError> {
    page.heading("Sensitivity: Sobol indices");
    page.paragraph(&sensitivity::caption(s));
    let rows: Vec<Vec<String>> = sensitivity::rows(s).into_iter().map(Vec::from).collect();
    page.table(&sensitivity::HEADERS, &rows);
    if sensitivity::clipped(s) {
        page.paragraph(sensitivity::CLIPPED);
    }
    for t in &v.tests {
        let Some(binding) = t.binding() else { continue };
        let found = s
            .criteria
            .iter()
            .find(|c| c.test == t.test.name && c.criterion == binding.name && c.indices.is_some());
        let Some(i) = found.and_then(|c| c.indices.as_ref()) else {
            continue;
        };
        let name = format!("{}: {}", t.test.name, binding.name);
        let plot = BarPlot {
            title: format!("{name}: total Sobol indices"),
            y_label: format!(
                "share of the {} variance, total index S_T [1]",
                binding.name
            ),
            labels: i.names.clone(),
            values: i.total.clone(),
            errors: (i.total.iter().zip(&i.total_conf))
                .map(|(t, c)| Some([t - c, t + c]))
                .collect(),
        };
        let svg = plot.svg()?;
        page.figure(&svg, &format!("{name} (the test's binding criterion): the total Sobol index of each parameter, the share of the value's variance it takes part in, with its 95 % bootstrap interval"));
        let stem = crate::file_name(t.test.name);
        figures.push((format!("{stem}-sobol.svg"), svg));
    }
    Ok(())
}

/// The target region: its corridor plot and its table of limits.
fn target(
    page: &mut Html,
    figures: &mut Vec<(String, String)>,
    r: &Region,
    v: &Verdict,
) -> Result<(), PlotError> {
    page.heading("Bumper target");
    page.paragraph(&format!(
        "The whole bumper's characteristic scaled in force and deflection around the car's own ({:.2} kN/mm, {:.1} kN); every candidate runs every test and must keep a margin of {} % on every criterion. {} impacts in {:.2} s.",
        r.origin[0] / 1e6,
        r.origin[1] / 1e3,
        100.0 * r.margin,
        r.impacts,
        r.seconds
    ));
    let svg = pass_region(r, v).svg()?;
    page.figure(&svg, &format!("the pass region (whole bumper): at each stiffness searched, the force levels whose bumper passes every test (shaded; a stiffness where nothing passes is a marker at the car's force level), and the car's own bumper, which {}; between the rows the region is interpolated, so check a bumper with the verdict", own_outcome(v)));
    figures.push(("pass-region.svg".into(), svg));
    if let Some(line) = Some(bumpsim_verdict::text::own(r)).filter(|l| !l.is_empty()) {
        page.paragraph(line.trim());
    }
    if !r.corridor.deflection.is_empty() {
        let svg = corridor(r, v).svg()?;
        page.figure(&svg, "force–deflection envelope of the passing bumpers (whole bumper): the least and the largest force of any passing characteristic at each deflection; an envelope, not a pass region: a curve inside it can fail (the car's own, dashed, does when the verdict fails), so read what passes from the pass region above");
        figures.push(("corridor.svg".into(), svg));
    }
    let headers = [
        "stiffness [kN/mm]",
        "least force [kN]",
        "binding below",
        "largest force [kN]",
        "binding above",
        "stroke needed [mm]",
    ];
    page.table(&headers, &limits(r));
    Ok(())
}

/// Whether the car's own bumper passes, as the figures say it.
fn own_outcome(v: &Verdict) -> String {
    match v.failures().first() {
        None => "passes every test".into(),
        Some((test, c)) => format!("fails ({} in {test})", c.name),
    }
}

/// The pass region in the plane of the whole bumper's initial stiffness
/// and force level: a band per run of rows with a passing interval,
/// markers at the stiffnesses where nothing passes, the car's bumper.
fn pass_region(r: &Region, v: &Verdict) -> LinePlot {
    let mut plot = LinePlot::new(
        "Bumper target: pass region",
        Dimension::Stiffness,
        Dimension::Force,
    )
    .quantities(
        Some("whole-bumper initial stiffness"),
        Some("whole-bumper force level"),
    );
    let runs = r
        .rows
        .chunk_by(|a, b| a.interval.is_some() == b.interval.is_some());
    for run in runs.filter(|run| run[0].interval.is_some()) {
        let bounds = |k: usize| {
            let at = |row: &bumpsim_verdict::target::Row| {
                row.interval.as_ref().map_or(f64::NAN, |i| i[k].force)
            };
            run.iter().map(at).collect::<Vec<f64>>()
        };
        let x: Vec<f64> = run.iter().map(|row| row.stiffness).collect();
        let (low, high) = (bounds(0), bounds(1));
        if x.len() == 1 {
            // one row: its interval as a vertical line
            plot.add(Series::new(
                "passes every test",
                vec![x[0]; 2],
                vec![low[0], high[0]],
                Style::Solid,
            ));
        } else {
            plot.band(Band {
                name: "passes every test".into(),
                x,
                low,
                high,
            });
        }
    }
    let empty: Vec<f64> = r
        .rows
        .iter()
        .filter(|row| row.interval.is_none())
        .map(|row| row.stiffness)
        .collect();
    if !empty.is_empty() {
        let n = empty.len();
        plot.add(Series::new(
            "nothing passes at this stiffness",
            empty,
            vec![r.origin[1]; n],
            Style::Points,
        ));
    }
    let name = format!("the car's bumper: {}", own_outcome(v));
    plot.add(Series::new(
        &name,
        vec![r.origin[0]],
        vec![r.origin[1]],
        Style::Points,
    ));
    plot
}

fn corridor(r: &Region, v: &Verdict) -> LinePlot {
    let c = &r.corridor;
    let mut plot = LinePlot::new(
        "Bumper target corridor",
        Dimension::Length,
        Dimension::Force,
    )
    .quantities(Some("deflection"), Some("bumper force"));
    plot.add(Series::new(
        "largest passing force",
        c.deflection.clone(),
        c.upper.clone(),
        Style::Solid,
    ));
    plot.add(Series::new(
        "least passing force",
        c.deflection.clone(),
        c.lower.clone(),
        Style::Solid,
    ));
    let own = v.tests.iter().find_map(|t| t.run.as_ref()).map(|(car, _)| {
        let segments = &car.beam().segments;
        let force = |d: f64| segments.iter().map(|s| s.loading_force(d)).sum::<f64>();
        c.deflection.iter().map(|&d| force(d)).collect::<Vec<f64>>()
    });
    if let Some(own) = own {
        plot.add(Series::new(
            &format!("the car's bumper ({})", own_outcome(v)),
            c.deflection.clone(),
            own,
            Style::Dashed,
        ));
    }
    plot
}

/// The rows of the table of limits: per stiffness the passing force
/// levels, the criterion binding at each, the stroke needed.
fn limits(r: &Region) -> Vec<Vec<String>> {
    let force = |b: &Bound| format!("{:.1}", b.force / 1e3);
    let binding = |b: &Bound| {
        b.binding
            .clone()
            .unwrap_or_else(|| "the search range".into())
    };
    r.rows
        .iter()
        .map(|row| {
            let own = if r.own_row() == Some(row) {
                " (the car's)"
            } else {
                ""
            };
            let stiffness = format!("{:.2}{own}", row.stiffness / 1e6);
            match &row.interval {
                Some([low, high]) => vec![
                    stiffness,
                    force(low),
                    binding(low),
                    force(high),
                    binding(high),
                    row.stroke.map_or("-".into(), |s| format!("{:.1}", s * 1e3)),
                ],
                None => vec![
                    stiffness,
                    "-".into(),
                    format!(
                        "nothing passes: {}",
                        row.failing.as_deref().unwrap_or("every level fails")
                    ),
                    "-".into(),
                    "-".into(),
                    "-".into(),
                ],
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use bumpsim_verdict::prelude::*;

    /// The bundled worked example in the RCAR corner test: one figure per
    /// kind, the failing criterion's cell coloured, units on every axis.
    #[test]
    fn the_worked_example_draws_its_test_and_colours_its_failure() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../examples/verdict/car.toml");
        let car = bumpsim_planar::PlanarCar::read(&path).unwrap();
        let end = CarEnd::new(car, Damageability::read(&path).unwrap()).unwrap();
        let tests = bumpsim_verdict::protocol::select(&["rcar-bumper-corner-front"]).unwrap();
        let v = verdict(&Setup::new(vec![end], tests, 0.0).unwrap()).unwrap();
        let (html, figures) = verdict_report(&v, None, None).unwrap();
        let names: Vec<&str> = figures.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(
            names,
            [
                "rcar-bumper-corner-front-top-view.svg",
                "rcar-bumper-corner-front-forces.svg",
                "rcar-bumper-corner-front-crush.svg"
            ]
        );
        assert!(
            html.contains("font-weight:bold\">FAIL</td>"),
            "coloured failure"
        );
        assert!(html.contains("background:#d8f0d8\">pass</td>"));
        assert!(figures[1].1.contains("force [kN]") && figures[2].1.contains("crush [mm]"));
        assert!(html.contains("Assumptions") && html.contains("absorber"));
    }

    /// The target's pass region (issue 45): the band of passing force
    /// levels per stiffness, a row at the car's own stiffness marked in the
    /// table, and the car's bumper named as failing where the verdict fails
    /// (the force–deflection envelope is captioned as no pass region).
    #[test]
    fn the_pass_region_shows_what_passes_and_the_failing_car() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../examples/verdict/car.toml");
        let end = CarEnd::read(&path, None).unwrap();
        let tests = bumpsim_verdict::protocol::select(&["rcar-bumper-corner-front"]).unwrap();
        let setup = Setup::new(vec![end], tests, 0.0).unwrap();
        let v = verdict(&setup).unwrap();
        let options = TargetOptions {
            stiffness: Some([2e6, 4.5e6]),
            force: Some([60e3, 480e3]),
            rows: 4,
            levels: 5,
            tolerance: 0.05,
        };
        let r = bumpsim_verdict::target::search(&setup, &options).unwrap();
        let own = r.own_row().unwrap();
        assert!((own.stiffness / 3e6 - 1.0).abs() < 1e-12, "{own:?}");
        // 2, 2.62, 3.43 and 4.5 kN/mm, and the car's 3 kN/mm
        assert_eq!(r.rows.len(), 5);
        let [low, _] = own.interval.as_ref().unwrap();
        assert!(low.force > 120e3, "{low:?}: the car's 120 kN fails");
        let (html, figures) = verdict_report(&v, Some(&r), None).unwrap();
        let svg = |name: &str| &figures.iter().find(|(n, _)| n == name).unwrap().1;
        let region = svg("pass-region.svg");
        assert!(region.contains("passes every test") && region.contains("<polygon"));
        assert!(
            region.contains(
                "the car&apos;s bumper: fails (bumper stroke in rcar-bumper-corner-front)"
            ) || region
                .contains("the car's bumper: fails (bumper stroke in rcar-bumper-corner-front)"),
            "{region}"
        );
        assert!(region.contains("whole-bumper initial stiffness [N/mm]"));
        assert!(svg("corridor.svg").contains("fails (bumper stroke"));
        assert!(
            html.contains("3.00 (the car&apos;s)")
                || html.contains("3.00 (the car's)")
                || html.contains("3.00 (the car&#39;s)"),
            "marked row"
        );
        assert!(html.contains("below the least passing force"));
        assert!(html.contains("not a pass region"));
    }
}
