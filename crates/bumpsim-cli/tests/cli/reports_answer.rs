//! Reports lead with the answer (issue 47 item 7): the identification
//! report opens with the model, its fits (each with its fitted window) and
//! the warnings, marks each case's fitted window on its plot at the times
//! the identification JSON gives, names under every plot the viewer's
//! command, and ends with its inputs; read as written and as Chromium
//! lays it out.

use crate::util::{bumpsim, chromium, root, scratch, text};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

/// `identify` of the bundled study with a report and its JSON: the study,
/// the report folder, the JSON.
fn identified(dir: &Path) -> (PathBuf, PathBuf, Value) {
    let study = root().join("examples/identify/study.toml");
    let (report, json) = (dir.join("report"), dir.join("r.json"));
    let run = bumpsim(&[
        "identify",
        study.to_str().unwrap(),
        "--starts",
        "4",
        "--quiet",
        "--json",
        json.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let json = serde_json::from_str(&std::fs::read_to_string(json).unwrap()).unwrap();
    (study, report, json)
}

/// The page's sections in order: each `<h2>`'s title and what follows it.
fn sections(html: &str) -> Vec<(String, String)> {
    html.split("<h2>")
        .skip(1)
        .map(|s| {
            let (title, body) = s.split_once("</h2>").unwrap();
            (title.to_string(), body.to_string())
        })
        .collect()
}

/// The cells of the table rows of `html` (the header row left out).
fn rows(html: &str) -> Vec<Vec<String>> {
    html.split("<tr>")
        .skip(1)
        .filter(|r| r.contains("<td>"))
        .map(|r| {
            r.split("<td>")
                .skip(1)
                .map(|c| c.split("</td>").next().unwrap().to_string())
                .collect()
        })
        .collect()
}

fn number(text: &str) -> f64 {
    text.parse()
        .unwrap_or_else(|_| panic!("'{text}' is not a number"))
}

#[test]
fn the_identification_report_opens_with_the_model_and_its_fits_and_ends_with_its_inputs() {
    let dir = scratch("report-answer");
    let (study, report, json) = identified(&dir);
    let html = std::fs::read_to_string(report.join("index.html")).unwrap();
    let sections = sections(&html);
    let titles: Vec<&str> = sections.iter().map(|(t, _)| t.as_str()).collect();
    assert_eq!(titles.first(), Some(&"Result"), "{titles:?}");
    assert_eq!(titles.last(), Some(&"Inputs"), "{titles:?}");
    let (_, answer) = &sections[0];
    assert!(!answer.contains("<figure"), "a plot before the answer");
    // the model table: every mass with its value in kg as the JSON has it
    for (k, m) in json["masses"].as_array().unwrap().iter().enumerate() {
        let line = answer
            .lines()
            .find(|l| l.starts_with(&format!("m{}  ", k + 1)))
            .unwrap_or_else(|| panic!("m{} missing from the answer", k + 1));
        let value = number(line.split_whitespace().nth(1).unwrap());
        assert!(
            (value - m.as_f64().unwrap()).abs() <= 5e-4 * value,
            "{line}"
        );
        assert!(line.contains(" kg"), "{line}");
    }
    // the fits: one row per case, its window, fit and rating as in the JSON
    let cases = json["cases"].as_array().unwrap();
    let table = rows(answer);
    assert_eq!(table.len(), cases.len());
    for (row, case) in table.iter().zip(cases) {
        assert_eq!(row[0], case["name"].as_str().unwrap());
        let (start, end) = row[1].split_once('–').unwrap();
        for (shown, t) in [start, end]
            .into_iter()
            .zip(case["window"].as_array().unwrap())
        {
            assert!(
                (number(shown) - 1e3 * t.as_f64().unwrap()).abs() <= 0.005,
                "{row:?}"
            );
        }
        let fit = case["fit_percent"].as_f64().unwrap();
        assert!((number(&row[2]) - fit).abs() <= 0.01, "{row:?}");
        let rating = case["rating"]["overall"].as_f64().unwrap();
        assert!(row[4].starts_with(&format!("{rating:.3} (")), "{row:?}");
    }
    // the warnings: as many boxes as the JSON has, or the word that there are none
    let warnings = json["warnings"].as_array().unwrap().len();
    assert_eq!(answer.matches("class=\"warning\"").count(), warnings);
    assert_eq!(answer.contains("No warnings."), warnings == 0);
    // the inputs last: the settings and the study's own text
    let (_, inputs) = sections.last().unwrap();
    assert!(inputs.contains("4 starts, seed 1"), "{inputs}");
    assert!(
        inputs.contains("window = &quot;contact&quot;"),
        "the study's text"
    );
    assert!(!inputs.contains("<figure"));
    // under every plot, the viewer's command: the JSON and the study
    let figures = html.matches("<figure class=\"plot\"").count();
    let command = format!(
        "<code>bumpsim view {} {}</code>",
        dir.join("r.json").display(),
        study.display()
    );
    assert!(figures >= cases.len() + 2, "{figures} figures");
    assert_eq!(html.matches(&command).count(), figures, "{command}");
}

/// The attributes of an SVG's elements `<tag ...>`, each list led by a space.
fn elements(svg: &str, tag: &str) -> Vec<String> {
    svg.split(&format!("<{tag} "))
        .skip(1)
        .map(|e| format!(" {}", e.split('>').next().unwrap()))
        .collect()
}

fn attribute(element: &str, key: &str) -> Option<String> {
    let rest = element.split(&format!(" {key}=\"")).nth(1)?;
    Some(rest.split('"').next()?.to_string())
}

/// The x axis of a plot as pixels per ms and the pixel of 0 ms, fitted to
/// its tick labels (centred numbers on the lowest row of labels).
fn time_axis(svg: &str) -> (f64, f64) {
    let ticks: Vec<(f64, f64, f64)> = svg
        .split("<text ")
        .skip(1)
        .filter(|t| t.contains("text-anchor=\"middle\""))
        .filter_map(|t| {
            let (head, rest) = t.split_once('>')?;
            let head = format!(" {head}");
            let value: f64 = rest.split('<').next()?.trim().parse().ok()?;
            let x = attribute(&head, "x")?.parse().ok()?;
            let y = attribute(&head, "y")?.parse().ok()?;
            Some((value, x, y))
        })
        .collect();
    let bottom = ticks.iter().map(|t| t.2).fold(f64::MIN, f64::max);
    let row: Vec<&(f64, f64, f64)> = ticks.iter().filter(|t| t.2 == bottom).collect();
    assert!(row.len() >= 3, "x ticks: {row:?}");
    let (first, last) = (row[0], row[row.len() - 1]);
    let scale = (last.1 - first.1) / (last.0 - first.0);
    (scale, first.1 - scale * first.0)
}

#[test]
fn every_fit_plot_shades_the_fitted_window_at_the_json_s_times() {
    let dir = scratch("report-window");
    let (_, report, json) = identified(&dir);
    let dof = json["dof"].as_u64().unwrap();
    for case in json["cases"].as_array().unwrap() {
        let name = case["name"].as_str().unwrap();
        let file = format!("fit-{dof}dof-{}.svg", name.replace(' ', "_"));
        let svg = std::fs::read_to_string(report.join(&file)).unwrap();
        let window: Vec<f64> = case["window"]
            .as_array()
            .unwrap()
            .iter()
            .map(|t| 1e3 * t.as_f64().unwrap())
            .collect();
        let legend = format!("fitted window {:.2}–{:.2} ms", window[0], window[1]);
        assert!(svg.contains(&legend), "{file}: no legend '{legend}'");
        // the shaded span, the largest amber rectangle, spans the window
        let span = elements(&svg, "rect")
            .into_iter()
            .filter(|r| attribute(r, "fill").as_deref() == Some("#E6A000"))
            .max_by_key(|r| attribute(r, "height").unwrap().parse::<u32>().unwrap())
            .unwrap_or_else(|| panic!("{file}: no shaded window"));
        let px = |key: &str| attribute(&span, key).unwrap().parse::<f64>().unwrap();
        let (scale, zero) = time_axis(&svg);
        let (left, right) = (px("x"), px("x") + px("width"));
        for (edge, t) in [(left, window[0]), (right, window[1])] {
            let shown = (edge - zero) / scale;
            assert!(
                (shown - t).abs() <= 1.5 / scale,
                "{file}: an edge at {shown:.2} ms, the window's at {t:.2} ms"
            );
        }
        // a line at each end of the window, over the axes' height
        let edges = elements(&svg, "polyline")
            .into_iter()
            .filter(|l| attribute(l, "stroke").as_deref() == Some("#E6A000"))
            .count();
        assert_eq!(edges, 2, "{file}: the window's end lines");
    }
}

/// A probe that writes, into the page, each section title with its top
/// and each figure with its top and the width of its shaded window, as
/// Chromium lays the page out.
const LAYOUT_PROBE: &str = "<script>addEventListener('load',()=>{const top=e=>Math.round(e.getBoundingClientRect().top+scrollY);const h=[...document.querySelectorAll('h2')].map(e=>[e.textContent,top(e)]);const f=[...document.querySelectorAll('figure')].map(e=>{const r=[...e.querySelectorAll('rect[fill=\"#E6A000\"]')].map(r=>r.getBoundingClientRect().width);return [top(e),Math.max(0,...r)]});const o=document.createElement('output');o.id='layout';o.textContent=JSON.stringify({h,f});document.body.appendChild(o)});</script>";

#[test]
fn in_chromium_the_answer_is_on_top_every_fit_plot_shows_its_window_and_the_inputs_close_the_page()
{
    let dir = scratch("report-layout");
    let (_, report, json) = identified(&dir);
    let Some(browser) = chromium() else { return };
    let page = report.join("index.html");
    let probed = report.join("probed.html");
    let html = std::fs::read_to_string(&page).unwrap();
    std::fs::write(
        &probed,
        html.replace("</body>", &format!("{LAYOUT_PROBE}</body>")),
    )
    .unwrap();
    let dom = Command::new(browser)
        .args(["--headless", "--no-sandbox", "--disable-gpu"])
        .arg("--window-size=1280,900")
        .arg(format!("--user-data-dir={}", dir.join("profile").display()))
        .arg("--dump-dom")
        .arg(format!(
            "file://{}",
            probed.canonicalize().unwrap().display()
        ))
        .output()
        .unwrap();
    let dom = text(&dom.stdout);
    let layout = dom
        .split("<output id=\"layout\">")
        .nth(1)
        .and_then(|r| r.split("</output>").next())
        .unwrap_or_else(|| panic!("the probe did not run:\n{dom}"));
    let layout: Value = serde_json::from_str(layout).unwrap();
    let headings = layout["h"].as_array().unwrap();
    let top = |i: usize| headings[i][1].as_f64().unwrap();
    assert_eq!(headings[0][0], "Result");
    assert_eq!(headings[headings.len() - 1][0], "Inputs");
    let figures = layout["f"].as_array().unwrap();
    let (first, inputs) = (top(1), top(headings.len() - 1));
    for f in figures {
        let y = f[0].as_f64().unwrap();
        assert!(
            first <= y && y < inputs,
            "a figure at {y} px outside {first}..{inputs} px"
        );
    }
    // the fit plots (one per case, first in the model's section) show a
    // shaded window some tens of pixels wide
    let cases = json["cases"].as_array().unwrap().len();
    for f in &figures[..cases] {
        let width = f[1].as_f64().unwrap();
        assert!(width > 50.0, "a fit plot's window {width} px wide");
    }
}
