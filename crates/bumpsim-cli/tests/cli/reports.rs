//! The reports as an engineer reads them (issue 35): four workflows write
//! their HTML reports (identify, impact, planar, doe fit); each page is
//! rendered in headless Chromium with a probe that lists every text box
//! whose content is wider than the box (it would scroll or be cut), and
//! every SVG's axis labels must name the quantity with its unit and its
//! scatter legends must show markers; each page leads with its answer.

use crate::util::{bumpsim, chromium, overflowing, root, scratch, text};
use std::path::{Path, PathBuf};

fn ok(args: &[&str]) {
    let run = bumpsim(args);
    assert!(run.status.success(), "{args:?}: {}", text(&run.stderr));
}

/// Writes the four reports into `dir`; their folders.
fn reports(dir: &Path) -> Vec<PathBuf> {
    let path = |p: &Path| p.to_str().unwrap().to_string();
    let example = |p: &str| path(&root().join("examples").join(p));
    let out = |name: &str| dir.join(name);
    ok(&[
        "identify",
        &example("identify/study.toml"),
        "--starts",
        "4",
        "--quiet",
        "--report",
        &path(&out("identify")),
    ]);
    ok(&[
        "impact",
        "--car",
        &example("identify/car-truth.toml"),
        "--bumper",
        &example("impact/bumper-a.toml"),
        "--barrier",
        "--speed",
        "8 km/h",
        "--report",
        &path(&out("impact")),
    ]);
    ok(&[
        "planar",
        "--car",
        &example("planar/saloon.toml"),
        "--case",
        "rcar-structural-front",
        "--report",
        &path(&out("planar")),
    ]);
    let mut csv = String::from("a,b,peak_force [N]\n");
    for (a, b, f) in [
        (-1, -1, 60e3),
        (1, -1, 70e3),
        (-1, 1, 65e3),
        (1, 1, 76e3),
        (0, 0, 68.2e3),
    ] {
        csv += &format!("{a},{b},{f}\n");
    }
    std::fs::write(dir.join("runs.csv"), csv).unwrap();
    ok(&[
        "doe",
        "fit",
        &path(&dir.join("runs.csv")),
        "--factors",
        "a,b",
        "--responses",
        "peak_force",
        "--report",
        &path(&out("doe")),
    ]);
    ["identify", "impact", "planar", "doe"].map(out).to_vec()
}

/// The texts of an SVG's `<text>` elements.
fn texts(svg: &str) -> Vec<String> {
    svg.split("<text")
        .skip(1)
        .filter_map(|t| Some(t.split('>').nth(1)?.split('<').next()?.trim().to_string()))
        .collect()
}

fn check_svg(name: &str, svg: &str) {
    for label in texts(svg).iter().filter(|t| t.ends_with(']')) {
        // a bare dimension says which unit, not which quantity
        assert!(
            !label.starts_with("length [") && !label.starts_with("dimensionless ["),
            "{name}: axis '{label}' does not name its quantity"
        );
    }
    let elements = |tag: &str| -> Vec<String> {
        svg.split(&format!("<{tag}"))
            .skip(1)
            .map(|e| e.split("/>").next().unwrap_or("").to_string())
            .collect()
    };
    let colour = |e: &str, key: &str| {
        e.split(&format!("{key}=\""))
            .nth(1)
            .map(|r| r.split('"').next().unwrap_or("").to_string())
    };
    // a colour drawn only as markers has no line in the legend
    let marker_colours: Vec<String> = elements("circle")
        .iter()
        .filter_map(|c| colour(c, "fill"))
        .collect();
    let line_colours: Vec<String> = elements("polyline")
        .iter()
        .filter_map(|l| colour(l, "stroke"))
        .collect();
    for c in marker_colours.iter().filter(|c| c.starts_with('#')) {
        assert!(
            !line_colours.contains(c),
            "{name}: markers of {c} also have a line sample"
        );
    }
}

#[test]
fn reports_name_their_axes_show_their_marks_and_nothing_overflows() {
    let dir = scratch("reports-read");
    let folders = reports(&dir);
    for folder in &folders {
        for entry in std::fs::read_dir(folder).unwrap().filter_map(|e| e.ok()) {
            let name = entry.file_name().to_string_lossy().into_owned();
            if name.ends_with(".svg") {
                check_svg(&name, &std::fs::read_to_string(entry.path()).unwrap());
            }
        }
    }
    answers_first(&folders);
    let Some(browser) = chromium() else { return };
    for folder in &folders {
        let wide = overflowing(&browser, &folder.join("index.html"));
        assert_eq!(
            wide,
            "[]",
            "{}: text boxes wider than their box",
            folder.display()
        );
    }
}

/// Each page opens with what was found and ends with its inputs (issue
/// 47): the first and last section titles of the identify, impact,
/// planar and doe pages; the pages whose data the viewer opens name it
/// under every figure (their result kept beside the page).
fn answers_first(folders: &[PathBuf]) {
    let expected = [
        ("Result", "Inputs", true),
        ("Results", "Results", true),
        ("Results", "Bumper segments", true),
        ("peak_force [N]", "Inputs", false),
    ];
    for (folder, (first, last, viewed)) in folders.iter().zip(expected) {
        let html = std::fs::read_to_string(folder.join("index.html")).unwrap();
        let titles: Vec<&str> = html
            .split("<h2>")
            .skip(1)
            .filter_map(|s| s.split("</h2>").next())
            .collect();
        let name = folder.display();
        assert_eq!(titles.first(), Some(&first), "{name}: {titles:?}");
        assert_eq!(titles.last(), Some(&last), "{name}: {titles:?}");
        let figures = html.matches("<figure").count();
        let command = format!("bumpsim view {}", folder.join("result.json").display());
        let named = html.matches(&command).count();
        assert_eq!(named, if viewed { figures } else { 0 }, "{name}");
        assert_eq!(folder.join("result.json").is_file(), viewed, "{name}");
    }
}
