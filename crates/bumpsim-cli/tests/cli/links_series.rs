//! `bumpsim synth` of a `kind = "links"` series (issue 46 item 2): the
//! example series `examples/links/series.toml` made by the real binary and
//! checked against `bumpsim impact` of the same car into the barrier (peak
//! force, the output mass's ΔV, the force's impulse against the car's
//! momentum change), remade bit for bit, its study read by the study
//! reader, hostile series refused; and `impact`'s warning when a link's
//! unloading slope is replaced by the rule.

use crate::util::*;
use std::path::Path;

/// The example series and car.
fn series() -> std::path::PathBuf {
    root().join("examples/links/series.toml")
}

/// The speeds of the example's tests, m/s.
const TESTS: [(&str, f64); 3] = [("B15", 15.0), ("B32", 32.0), ("B56", 56.0)];

/// The record's duration after contact and the step of the example, s.
const DURATION: f64 = 0.25;
const STEP: f64 = 1e-4;

/// A CSV `synth` or `impact` wrote: its column names and columns.
fn columns(path: &Path) -> Vec<(String, Vec<f64>)> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let mut out: Vec<(String, Vec<f64>)> = lines
        .next()
        .unwrap()
        .split(',')
        .map(|name| (name.to_string(), Vec::new()))
        .collect();
    for line in lines {
        for (cell, (_, column)) in line.split(',').zip(out.iter_mut()) {
            column.push(cell.parse().unwrap());
        }
    }
    out
}

fn column<'a>(table: &'a [(String, Vec<f64>)], start: &str) -> &'a [f64] {
    &table
        .iter()
        .find(|(name, _)| name.starts_with(start))
        .unwrap_or_else(|| panic!("no column {start}"))
        .1
}

fn synth(out: &Path, series: &Path) -> std::process::Output {
    bumpsim(&[
        "synth",
        series.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ])
}

/// `bumpsim impact` of the example car into the barrier at `kmh`: its JSON
/// and its histories.
fn impact(dir: &Path, kmh: f64) -> (serde_json::Value, Vec<(String, Vec<f64>)>) {
    let (json, csv) = (
        dir.join(format!("{kmh}.json")),
        dir.join(format!("{kmh}.csv")),
    );
    let car = root().join("examples/links/car.toml");
    let speed = format!("{kmh} km/h");
    let run = bumpsim(&[
        "impact",
        "--car",
        car.to_str().unwrap(),
        "--barrier",
        "--speed",
        &speed,
        "--json",
        json.to_str().unwrap(),
        "--csv",
        csv.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let doc = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    (doc, columns(&csv))
}

#[test]
fn synth_of_a_links_series_agrees_with_impact_and_keeps_momentum() {
    let dir = scratch("links-series");
    let out = dir.join("made");
    let run = synth(&out, &series());
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert_contains(
        &text(&run.stdout),
        &["B56 B0LOMASU0000FOXP: synthetic (bumpsim synth): ISO/TS 18571 rating"],
    );
    let masses = [6.0, 180.0, 1250.0];
    for (name, kmh) in TESTS {
        let speed = kmh / 3.6;
        let made = columns(&out.join(format!("{name}.csv")));
        let time = column(&made, "time");
        let force = column(&made, "B0LOMASU0000FOXP");
        let (left, right) = (
            column(&made, "10SECMLE0000ACXP"),
            column(&made, "10SECMRI0000ACXP"),
        );
        assert!((time[1] - time[0] - STEP).abs() < 1e-12);
        assert!(time[0] < 0.0, "a pre-trigger");
        let (doc, history) = impact(&dir, kmh);
        // peak force: the made force is the wall's on the car, negative;
        // within 2 % (anti-alias filter, 300 N noise, the impact's 0.1 ms
        // samples) of impact's
        let made_peak = -force.iter().fold(0.0_f64, |m, f| m.min(*f));
        let peak = doc["peak_force"].as_f64().unwrap();
        assert!(
            (made_peak - peak).abs() < 0.02 * peak,
            "{name}: made peak {made_peak} N, impact {peak} N"
        );
        // at the record's end, impact's row (0.1 ms samples)
        let end = (DURATION / STEP).round() as usize;
        let at_end = |start: &str| column(&history, start)[end];
        // the body's ΔV from its two accelerometers (pre-trigger mean
        // removed, integrated): within 1 % of it plus 3 σ of the bias
        // estimate's error over the record, σ = 0.4 g / √(2 · pre) · 0.25 s
        // (0.07 m/s; the example's noise, two sensors averaged)
        let pre = time.iter().filter(|t| **t < 0.0).count();
        let mean: Vec<f64> = left.iter().zip(right).map(|(l, r)| 0.5 * (l + r)).collect();
        let bias = mean[..pre].iter().sum::<f64>() / pre as f64;
        let made_dv: f64 = mean[pre..].iter().map(|a| (a - bias) * STEP).sum();
        let dv = at_end("v m3") - speed;
        let sigma = 0.4 * 9.80665 / (2.0 * pre as f64).sqrt() * DURATION;
        assert!(
            (made_dv - dv).abs() < 0.01 * dv.abs() + 3.0 * sigma,
            "{name}: made ΔV {made_dv} m/s, impact {dv} m/s"
        );
        assert!(dv < -0.5 * speed, "{name}: the body slows ({dv} m/s)");
        // the force's impulse over the record is the car's momentum change
        // within 0.5 %
        let impulse: f64 = force[pre..].iter().sum::<f64>() * STEP;
        let momentum: f64 = masses
            .iter()
            .enumerate()
            .map(|(i, m)| m * (at_end(&format!("v m{}", i + 1)) - speed))
            .sum();
        assert!(
            (impulse - momentum).abs() < 0.005 * momentum.abs(),
            "{name}: impulse {impulse} N·s, momentum change {momentum} N·s"
        );
    }
    // the study names every test's channels and reads as a study
    let study = std::fs::read_to_string(out.join("study.toml")).unwrap();
    assert_contains(
        &study,
        &[
            "kind = \"links\"",
            "channel = \"B0LOMASU0000FOXP\"",
            "channel = \"10SECMRI0000ACXP\"",
            "output_dof = 3",
            "[links] table",
        ],
    );
    let read = bumpsim_ident::Study::read(&out.join("study.toml")).unwrap();
    let loaded = read.load_named(3, &[]).unwrap();
    assert_eq!(loaded.cases.len(), 3);
    for (case, (_, kmh)) in loaded.cases.iter().zip(TESTS) {
        assert!((case.initial_velocity - kmh / 3.6).abs() < 1e-12);
        assert!(case.force.iter().any(|f| *f < -1e4), "{}", case.name);
    }
}

#[test]
fn a_links_series_is_remade_bit_for_bit_and_its_seed_changes_the_noise() {
    let dir = scratch("links-series-seed");
    let (one, two) = (dir.join("one"), dir.join("two"));
    for out in [&one, &two] {
        let run = synth(out, &series());
        assert!(run.status.success(), "{}", text(&run.stderr));
    }
    let files = |root: &Path| {
        let mut out = Vec::new();
        let mut stack = vec![root.to_path_buf()];
        while let Some(folder) = stack.pop() {
            for entry in std::fs::read_dir(&folder).unwrap().flatten() {
                match entry.path().is_dir() {
                    true => stack.push(entry.path()),
                    false => out.push(entry.path()),
                }
            }
        }
        out.sort();
        out
    };
    let made = files(&one);
    assert!(made.len() > 10, "{made:?}");
    for file in &made {
        let twin = two.join(file.strip_prefix(&one).unwrap());
        assert!(
            std::fs::read(file).unwrap() == std::fs::read(&twin).unwrap(),
            "{} differs between two runs",
            file.display()
        );
    }
    let reseeded = dir.join("series.toml");
    let text_of = std::fs::read_to_string(series()).unwrap();
    let car = root().join("examples/links/car.toml");
    let edited = text_of.replace("seed = 1", "seed = 2").replace(
        "car = \"car.toml\"",
        &format!("car = {:?}", car.to_str().unwrap()),
    );
    std::fs::write(&reseeded, edited).unwrap();
    let three = dir.join("three");
    let run = synth(&three, &reseeded);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let channel = "B15/Channel/B15.001";
    assert_ne!(
        std::fs::read(one.join(channel)).unwrap(),
        std::fs::read(three.join(channel)).unwrap(),
        "another seed, other noise"
    );
}

#[test]
fn hostile_links_series_are_refused_by_name() {
    let dir = scratch("links-series-hostile");
    let car = root().join("examples/links/car.toml");
    let base = std::fs::read_to_string(series()).unwrap().replace(
        "car = \"car.toml\"",
        &format!("car = {:?}", car.to_str().unwrap()),
    );
    synth_refuses_each(
        &dir,
        &base,
        &[
            (
                "speed = \"15 km/h\"",
                "speed = nan",
                "test 'B15': 'nan' is not a finite number",
            ),
            (
                "speed = \"15 km/h\"",
                "speed = \"-15 km/h\"",
                "test 'B15': speed -4.1",
            ),
            (
                "speed = \"15 km/h\"",
                "speed = 0",
                "a positive speed of 0.001 to 1000 m/s",
            ),
            (
                "speed = \"15 km/h\"",
                "speed = 1e300",
                "test 'B15': speed 1e300 m/s",
            ),
            ("step = 1e-4", "step = 1e-12", "samples per channel"),
            (
                "duration = 0.25",
                "duration = 60.0",
                "history values per test",
            ),
            (
                "accelerometers = [3]",
                "accelerometers = [4]",
                "accelerometers: mass 4: the car's masses are 1 to 3",
            ),
            (
                "accelerometers = [3]",
                "accelerometers = [3, 3]",
                "mass 3 is given twice",
            ),
            ("name = \"B32\"", "name = \"B15\"", "[[test]]"),
            ("name = \"B32\"", "name = \"../B32\"", "test name"),
            (
                car.to_str().unwrap(),
                "no-such-car.toml",
                "no-such-car.toml",
            ),
            ("seed = 1", "seed = 1\nheads = 2", "unknown field `heads`"),
        ],
    );
    // onto its input: the series file, and the folder holding it
    let file = dir.join("series.toml");
    std::fs::write(&file, &base).unwrap();
    for out in [file.clone(), dir.clone()] {
        let run = synth(&out, &file);
        assert_eq!(run.status.code(), Some(2), "{}", text(&run.stderr));
        assert_eq!(std::fs::read_to_string(&file).unwrap(), base);
    }
}

#[test]
fn impact_warns_when_the_rule_replaces_a_links_unloading_slope() {
    let dir = scratch("links-unloading-replaced");
    let car = dir.join("car.toml");
    let example = std::fs::read_to_string(root().join("examples/links/car.toml")).unwrap();
    std::fs::write(
        &car,
        example.replace("unloading = \"2000 N/mm\"", "unloading = \"1e-300 N/mm\""),
    )
    .unwrap();
    let args = ["--barrier", "--speed", "15 km/h"];
    let run = bumpsim(&[&["impact", "--car", car.to_str().unwrap()][..], &args[..]].concat());
    assert!(run.status.success(), "{}", text(&run.stderr));
    let all = text(&run.stdout) + &text(&run.stderr);
    assert_contains(
        &all,
        &[
            "front link: unloading = 1.000e-300 N/mm is below the rule k_e = max(k_u, F_max/δ_max, F_max²/(2 E_L)) at its largest compression ",
            "it unloads at ",
            "plastic set 0 mm",
        ],
    );
    // the example car's slopes are kept: no such warning
    let example = root().join("examples/links/car.toml");
    let run = bumpsim(
        &[
            &["impact", "--car", example.to_str().unwrap()][..],
            &args[..],
        ]
        .concat(),
    );
    assert!(run.status.success(), "{}", text(&run.stderr));
    let all = text(&run.stdout) + &text(&run.stderr);
    assert!(!all.contains("is below the rule"), "{all}");
}
