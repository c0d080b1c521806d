//! `bumpsim synth` on the bundled planar series and `bumpsim identify` on
//! the study it writes (issue 15): the identified car predicts the held-out
//! offset test, writes a car file `planar` reads, and hostile studies and
//! series get clear errors.

use crate::util::{
    assert_contains, assert_user_error, bumpsim, root, scratch, synth_refuses_each, text,
};
use serde_json::Value;
use std::path::{Path, PathBuf};

fn series() -> PathBuf {
    root().join("examples/planar/identify/series.toml")
}

/// Makes the bundled series into `dir/tests`.
fn synth(dir: &Path) -> PathBuf {
    let out = dir.join("tests");
    let run = bumpsim(&[
        "synth",
        series().to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    out
}

#[test]
fn the_planar_series_identifies_a_car_that_predicts_the_held_out_test() {
    let dir = scratch("planar-identify");
    let tests = synth(&dir);
    let (json, report, car) = (dir.join("r.json"), dir.join("report"), dir.join("car.toml"));
    let study = tests.join("study.toml");
    let run = bumpsim(&[
        "identify",
        study.to_str().unwrap(),
        "--quiet",
        "--json",
        json.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
        "--car",
        car.to_str().unwrap(),
    ]);
    let stdout = text(&run.stdout);
    assert!(run.status.success(), "{stdout}{}", text(&run.stderr));
    assert_contains(
        &stdout,
        &[
            "body.yaw_inertia",
            "kg·m²",
            "N/m",
            "validation",
            "OFFSET-RIGHT",
            " deg",
            // the estimation layer's table and start line, as the 1-D prints them
            "std. error",
            "95 % interval",
            "starts: 8 run",
        ],
    );
    let r: Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    // every channel of the series on one time base: nothing to note
    assert!(!stdout.contains("note:"), "{stdout}");
    assert_eq!(r["notes"], serde_json::json!([]));
    let inertia = &r["result"]["parameters"][1];
    assert_eq!(inertia["name"], "body.yaw_inertia");
    let (low, high) = (
        inertia["ci95"][0].as_f64().unwrap(),
        inertia["ci95"][1].as_f64().unwrap(),
    );
    assert!(
        low <= 1900.0 && 1900.0 <= high,
        "the truth's I_z in its interval: {inertia}"
    );
    let held = &r["validation"][0];
    let (x, yaw) = (
        held["fit_x"].as_f64().unwrap(),
        held["fit_yaw"].as_f64().unwrap(),
    );
    assert!(x >= 99.0 && yaw >= 95.0, "held-out fits {x} %, {yaw} %");
    let html = std::fs::read_to_string(report.join("index.html")).unwrap();
    assert!(
        html.contains("<svg") && html.contains("OFFSET-RIGHT (validation"),
        "report"
    );
    // the forward prediction of the held-out test (car, bumper, striker; no
    // measured force) in the summary, the JSON and the report
    assert_contains(&stdout, &["forward prediction", "yaw rate", "ISO"]);
    let forward = r["forward"].as_array().unwrap();
    let offset = forward
        .iter()
        .find(|f| f["case"] == "OFFSET-RIGHT")
        .unwrap();
    for channel in offset["channels"].as_array().unwrap() {
        let fit = channel["fit_percent"].as_f64().unwrap();
        assert!(fit >= 85.0, "forward {}: {fit} %", channel["name"]);
        assert!(channel["rating"]["overall"].as_f64().unwrap() > 0.9);
    }
    assert!(report.join("OFFSET-RIGHT-forward-yaw-rate.svg").is_file());
    assert!(html.contains("forward yaw rate: fit"));
    // the held-out replay and the forward predictions carry their 90 %
    // predictive bands (issue 44): judged in the summary and the JSON,
    // shaded in the report
    assert_contains(
        &stdout,
        &["90 % predictive bands", "of measured samples inside"],
    );
    let judged = r["bands"]["judged"].as_array().unwrap();
    let held_yaw = judged
        .iter()
        .find(|j| j["case"] == "OFFSET-RIGHT" && j["channel"] == "yaw")
        .unwrap();
    let inside = held_yaw["inside_percent"].as_f64().unwrap();
    assert!((0.0..=100.0).contains(&inside), "{held_yaw}");
    assert!(offset["channels"][0]["band"]["level"] == 0.9);
    assert!(html.contains("90 % predictive band") && html.contains("inside the shaded"));
    // the identified car is a planar car file the impact command reads
    let run = bumpsim(&[
        "planar",
        "--car",
        car.to_str().unwrap(),
        "--case",
        "rcar-structural-front",
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    predicts_the_held_out_test(&dir, &car, &study, held);
}

/// `predict` with the identified planar car on the planar study: the
/// held-out test's fits as the identification reported them, the JSON and
/// the plots; a planar car with a chain study (and the other way round) is
/// refused by name.
fn predicts_the_held_out_test(dir: &Path, car: &Path, study: &Path, held: &Value) {
    let (json, plots) = (dir.join("predict.json"), dir.join("predict-plots"));
    let run = bumpsim(&[
        "predict",
        car.to_str().unwrap(),
        study.to_str().unwrap(),
        "--case",
        "OFFSET-RIGHT",
        "--json",
        json.to_str().unwrap(),
        "--plot",
        plots.to_str().unwrap(),
    ]);
    let stdout = text(&run.stdout);
    assert!(run.status.success(), "{stdout}{}", text(&run.stderr));
    assert_contains(&stdout, &["OFFSET-RIGHT: fit x ", " %  yaw ", " deg)"]);
    let p: Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let case = &p["cases"][0];
    assert_eq!(p["cases"].as_array().unwrap().len(), 1);
    for key in ["fit_x", "fit_yaw"] {
        let (a, b) = (case[key].as_f64().unwrap(), held[key].as_f64().unwrap());
        assert!((a - b).abs() < 1e-6, "{key}: predict {a} %, identify {b} %");
    }
    assert!(plots.join("predict-OFFSET-RIGHT-yaw.svg").is_file());
    let chain_study = root().join("examples/identify/study.toml");
    let chain_model = root().join("examples/identify/car-truth.toml");
    for (model, study, needle) in [
        (
            car,
            chain_study.as_path(),
            "a planar car predicts a planar study",
        ),
        (
            chain_model.as_path(),
            study,
            "a planar study needs a planar car",
        ),
    ] {
        let run = bumpsim(&["predict", model.to_str().unwrap(), study.to_str().unwrap()]);
        assert_user_error(&run, needle);
    }
}

#[test]
fn a_planar_series_is_reproducible_bit_for_bit() {
    let (a, b) = (
        synth(&scratch("planar-series-a")),
        synth(&scratch("planar-series-b")),
    );
    for file in ["POLE/POLE.mme", "POLE.csv", "study.toml", "start.toml"] {
        let (x, y) = (
            std::fs::read(a.join(file)).unwrap(),
            std::fs::read(b.join(file)).unwrap(),
        );
        assert!(x == y, "{file} differs");
    }
    let pole = std::fs::read_to_string(a.join("study.toml")).unwrap();
    assert_contains(
        &pole,
        &[
            "B0POLE000000FOYP",
            "anchor = [",
            "chain = 1",
            "validate = true",
        ],
    );
}

/// The study the series wrote, changed by `edit`, in a copy of the tests.
fn edited_study(name: &str, edit: impl Fn(String) -> String) -> PathBuf {
    let dir = scratch(name);
    let tests = synth(&dir);
    let study = tests.join("study.toml");
    let text = std::fs::read_to_string(&study).unwrap();
    std::fs::write(&study, edit(text)).unwrap();
    study
}

/// A planar study put channels of different time bases on one without a
/// word (the 1-D study notes it).
#[test]
fn a_planar_channel_on_another_time_base_is_noted() {
    let dir = scratch("planar-resampled");
    let tests = synth(&dir);
    let channel = tests.join("FLAT/Channel/FLAT.001");
    let text = std::fs::read_to_string(&channel).unwrap();
    let shifted = text.replacen(":-5e-2", ":-4.995e-2", 1);
    assert_ne!(text, shifted, "the channel's first-sample time");
    std::fs::write(&channel, shifted).unwrap();
    let json = dir.join("r.json");
    let study = tests.join("study.toml");
    let run = bumpsim(&[
        "identify",
        study.to_str().unwrap(),
        "--quiet",
        "--starts",
        "1",
        "--json",
        json.to_str().unwrap(),
    ]);
    let stdout = crate::util::text(&run.stdout);
    assert!(
        run.status.success(),
        "{stdout}{}",
        crate::util::text(&run.stderr)
    );
    assert_contains(
        &stdout,
        &[
            "note: case 'FLAT': 14 channels put on one time base, every 0.1000 ms from -49.95 ms to 150.0 ms; B0LOMA010200FOXC, B0LOMA010300FOXC",
            "10SIMERI0000DSXC (every 0.1000 ms) interpolated linearly; B0LOMA010100FOXC: 1 sample outside that span left out; B0LOMA010200FOXC, ",
            ": 2 samples each outside",
        ],
    );
    let r: Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let notes = r["notes"].as_array().unwrap();
    assert_eq!(notes.len(), 1, "{notes:?}");
    assert!(notes[0].as_str().unwrap().starts_with("case 'FLAT': "));
}

#[test]
fn hostile_planar_studies_get_clear_errors() {
    let study = edited_study("planar-hostile", |t| {
        t.replacen("lateral = -0.72", "lateral = nan", 1)
    });
    let run = bumpsim(&["identify", study.to_str().unwrap(), "--quiet"]);
    assert_user_error(&run, "load[0].lateral");
    let study = edited_study("planar-hostile-channel", |t| {
        t.replacen("B0LOMA010100FOXP", "B0LOMA019900FOXP", 1)
    });
    assert_user_error(
        &bumpsim(&["identify", study.to_str().unwrap(), "--quiet"]),
        "B0LOMA019900FOXP",
    );
    let study = edited_study("planar-hostile-sensor", |t| {
        t.replacen("body = [0.6, 0.7]", "chain = 0", 1)
    });
    assert_user_error(
        &bumpsim(&["identify", study.to_str().unwrap(), "--quiet"]),
        "sensors",
    );
    let study = edited_study("planar-hostile-chain", |t| {
        t.replacen("chain = 1", "chain = 7", 1)
    });
    assert_user_error(
        &bumpsim(&["identify", study.to_str().unwrap(), "--quiet"]),
        "chain mass",
    );
    let study = edited_study("planar-hostile-starts", |t| {
        t.replacen("starts = 8", "starts = 100000000", 1)
    });
    assert_user_error(
        &bumpsim(&["identify", study.to_str().unwrap(), "--quiet"]),
        "starts",
    );
    let study = edited_study("planar-hostile-key", |t| {
        t.replacen("cfc = 180", "cfc = 180\nwindow = 3", 1)
    });
    assert_user_error(
        &bumpsim(&["identify", study.to_str().unwrap(), "--quiet"]),
        "window",
    );
    // case names name the report's files and lines, as in a centre-line study
    for (edit, expected) in [
        (
            r#"name = "POLE\u001B[31m""#,
            r#"the name "POLE\u001B[31m" holds control"#,
        ),
        (r#"name = "  ""#, "[[case]] number 3: an empty name"),
        (
            r#"name = "flat ""#,
            "name 'flat ' is already used by 'FLAT'",
        ),
    ] {
        let study = edited_study("planar-hostile-name", |t| {
            t.replacen(r#"name = "POLE""#, edit, 1)
        });
        assert_user_error(
            &bumpsim(&["identify", study.to_str().unwrap(), "--quiet"]),
            expected,
        );
    }
    let s = study.to_str().unwrap();
    assert_user_error(&bumpsim(&["identify", s, "--dof", "3"]), "--dof");
    // an output never lands on an input
    assert_user_error(&bumpsim(&["identify", s, "--car", s]), "study.toml");
}

#[test]
fn hostile_planar_series_get_clear_errors() {
    let dir = scratch("planar-series-hostile");
    let base = std::fs::read_to_string(series()).unwrap();
    let folder = root().join("examples/planar/identify");
    for car in ["car-truth.toml", "start.toml"] {
        std::fs::copy(folder.join(car), dir.join(car)).unwrap();
    }
    for (edit, needle) in [
        (
            base.replacen("name = \"POLE\"", "name = \"FLAT\"", 1),
            "[[test]] number 3: name 'FLAT' is already used by 'FLAT'",
        ),
        (
            base.replacen("name = \"POLE\"", "name = \" flat\"", 1),
            "is already used by 'FLAT' (they differ only in case",
        ),
        (
            base.replacen("name = \"POLE\"", "name = \"../escape\"", 1),
            "test name",
        ),
        (
            base.replacen("name = \"POLE\"", "name = \"POLE \"", 1),
            "test name \"POLE \": spaces before or after it",
        ),
        (
            base.replacen("name = \"POLE\"", "name = \"PO\\u001BLE\"", 1),
            r#"the name "PO\u001BLE" holds control"#,
        ),
        (
            base.replacen("name = \"POLE\"", "name = \"   \"", 1),
            "[[test]] number 3: an empty name",
        ),
        (
            base.replacen("duration = 0.15", "duration = 1e9", 1),
            "chain.duration",
        ),
        (
            base.replacen("pole_offset = -0.3", "pole_offset = -30.0", 1),
            "pole lateral position",
        ),
        (
            base.replacen("overlap = 40.0", "overlap = 140.0", 1),
            "overlap",
        ),
        (base.replacen("step = 1e-4", "step = nan", 1), "chain.step"),
    ] {
        let file = dir.join("series.toml");
        std::fs::write(&file, &edit).unwrap();
        let out = dir.join("out");
        let run = bumpsim(&["synth", file.to_str().unwrap(), "-o", out.to_str().unwrap()]);
        assert_user_error(&run, needle);
        assert!(!out.exists(), "nothing written on an error");
    }
}

/// Issue 32's new inputs (wall cells, estimated lines of action, strikers,
/// time zero, the test sheet's mass, the tyre laws of the start car) are
/// refused by name with exit 2, before any search runs.
#[test]
fn hostile_planar_test_set_ups_get_clear_errors() {
    let dir = scratch("planar-hostile-setup");
    let tests = synth(&dir);
    let text = std::fs::read_to_string(tests.join("study.toml")).unwrap();
    let start = std::fs::read_to_string(tests.join("start.toml")).unwrap();
    let flat = r#"striker = { speed = "8 km/h" }"#;
    let cell = "lateral = -0.72,";
    let tyre = "front = { rolling_resistance = 0.02, mu_lateral = 0.5 }";
    let cases: &[(&str, &str, &str)] = &[
        (
            "direction = [-1.0, 0.0] }",
            "direction = [-1.0, 0.0, 5.0] }",
            "expected two components",
        ),
        (
            "direction = [-1.0, 0.0] }",
            "direction = [nan, 0.0] }",
            "direction",
        ),
        (
            "direction = [-1.0, 0.0] }",
            "direction = [0.0, 0.0] }",
            "not both zero",
        ),
        (
            "direction = [-1.0, 0.0] }",
            "direction = [-1.0, 0.0], anchor = [2.0, 0.0, 1.0] }",
            "exactly 2 numbers",
        ),
        (
            "body = [0.6, 0.7]",
            "body = [0.6, 0.7, 0.2]",
            "exactly 2 numbers",
        ),
        (cell, r#"lateral = "guess","#, r#"lateral = "guess""#),
        (cell, "lateral = -0.72, cell = 0.4,", "cell"),
        (
            cell,
            "lateral = -0.72, cell = nan, anchor = [2.0, 0.0],",
            "cell",
        ),
        (
            cell,
            "lateral = -0.72, cell = 1e300, anchor = [2.0, 0.0],",
            "at most 10 m",
        ),
        ("mass = 1265.0", "mass = -5.0", "[model] mass"),
        ("mass = 1265.0", r#"mass = "1265 m""#, "[model] mass"),
        (
            flat,
            r#"striker = { speed = "8 km/h", angle = 95.0 }"#,
            "case 'FLAT': striker: barrier angle",
        ),
        (
            flat,
            r#"striker = { speed = "8 km/h", side = "up" }"#,
            "'up'",
        ),
        (
            flat,
            r#"striker = { speed = "8 km/h", pole = 0.254, pole_offset = 9.0 }"#,
            "case 'FLAT': striker",
        ),
        (flat, r#"striker = { sped = "8 km/h" }"#, "sped"),
        (flat, "time_zero = \"never\"", "time_zero"),
        (flat, "time_zero = 1e300", "lies outside the record"),
        (flat, "time_zero = nan", "time_zero"),
    ];
    for (k, (old, new, needle)) in cases.iter().enumerate() {
        assert!(text.contains(old), "{old}");
        let study = tests.join(format!("hostile-{k}.toml"));
        let edited = match new.starts_with("time_zero") {
            true => text.replacen(old, &format!("{old}\n{new}"), 1),
            false => text.replacen(old, new, 1),
        };
        std::fs::write(&study, edited).unwrap();
        assert_user_error(
            &bumpsim(&["identify", study.to_str().unwrap(), "--quiet"]),
            needle,
        );
    }
    for (k, (new, needle)) in [
        (r#"front = { law = "skid", mu_lateral = 0.5 }"#, "skid"),
        (
            "front = { cornering_stiffness = 0.0, mu_lateral = 0.5 }",
            "cornering",
        ),
        (
            "front = { cornering_stiffness = nan, mu_lateral = 0.5 }",
            "cornering",
        ),
        (
            "front = { relaxation_length = -0.1, mu_lateral = 0.5 }",
            "relaxation",
        ),
        (
            "front = { relaxation_length = 1e-320, mu_lateral = 0.5 }",
            "from 1e-6 m to 10 m",
        ),
        (
            "front = { shape = nan, mu_lateral = 0.5 }",
            "tyres.front.shape",
        ),
        (
            "front = { shape = 2.0, mu_lateral = 0.5 }",
            "tyres.front.shape",
        ),
        ("front = { shape = 0.9, mu_lateral = 0.5 }", "[1, 2)"),
        (
            r#"front = { shape = "1.3", mu_lateral = 0.5 }"#,
            "expected f64",
        ),
    ]
    .into_iter()
    .enumerate()
    {
        assert!(start.contains(tyre));
        std::fs::write(
            tests.join(format!("start-{k}.toml")),
            start.replacen(tyre, new, 1),
        )
        .unwrap();
        let study = tests.join(format!("tyres-{k}.toml"));
        let planar = format!("planar = \"start-{k}.toml\"");
        std::fs::write(&study, text.replacen("planar = \"start.toml\"", &planar, 1)).unwrap();
        assert_user_error(
            &bumpsim(&["identify", study.to_str().unwrap(), "--quiet"]),
            needle,
        );
    }
}

/// `--strict` turns an identification's warnings into exit 2: a flat test
/// alone leaves the tyres' grip undetermined, which the summary names.
#[test]
fn strict_refuses_an_undetermined_planar_identification() {
    let dir = scratch("planar-strict");
    let tests = synth(&dir);
    let whole = std::fs::read_to_string(tests.join("study.toml")).unwrap();
    let mut parts = whole.split("\n[[case]]\n");
    let head = parts.next().unwrap().to_string();
    let kept: Vec<&str> = parts
        .filter(|p| p.starts_with("name = \"FLAT\"") || p.starts_with("name = \"OFFSET-RIGHT\""))
        .collect();
    let study = tests.join("flat.toml");
    std::fs::write(
        &study,
        [vec![head.as_str()], kept].concat().join("\n[[case]]\n"),
    )
    .unwrap();
    let s = study.to_str().unwrap();
    let lenient = bumpsim(&["identify", s, "--quiet"]);
    assert!(lenient.status.success(), "{}", text_of(&lenient));
    assert_contains(
        &text(&lenient.stdout),
        &["tyres.mu_lateral", "not determined"],
    );
    let strict = bumpsim(&["identify", s, "--quiet", "--strict"]);
    assert_user_error(&strict, "--strict: the results carry");
}

fn text_of(run: &std::process::Output) -> String {
    format!("{}{}", text(&run.stdout), text(&run.stderr))
}

/// Issue 34: `identify study.toml --car start.toml` (or `--json`) wrote
/// over the start car the study names; the files a study names are inputs.
#[test]
fn identify_never_writes_over_the_start_car_its_study_names() {
    let dir = scratch("planar-identify-own-start");
    let tests = synth(&dir);
    let (study, start) = (tests.join("study.toml"), tests.join("start.toml"));
    let before = std::fs::read(&start).unwrap();
    for option in ["--car", "--json"] {
        let run = bumpsim(&[
            "identify",
            study.to_str().unwrap(),
            "--quiet",
            option,
            start.to_str().unwrap(),
        ]);
        assert_user_error(&run, "would overwrite the input");
        assert_eq!(std::fs::read(&start).unwrap(), before, "{option}");
    }
}

/// Issue 34: the planar series' chain refuses a negative or absurd noise
/// level and a third bias (two accelerometers), naming the key.
#[test]
fn a_planar_series_refuses_bad_noise_and_extra_biases() {
    let dir = scratch("planar-synth-chain");
    for file in ["series.toml", "car-truth.toml", "start.toml"] {
        let from = root().join("examples/planar/identify").join(file);
        std::fs::copy(from, dir.join(file)).unwrap();
    }
    let series = std::fs::read_to_string(dir.join("series.toml")).unwrap();
    let cases = [
        (
            "force_noise = 20.0",
            "force_noise = -1.0",
            "chain.force_noise = -1.0 N",
        ),
        (
            "acceleration_noise = 0.05",
            "acceleration_noise = 1e300",
            "chain.acceleration_noise = 1e300 g",
        ),
        (
            "biases = [0.03, -0.02]",
            "biases = [0.03, -0.02, 0.5]",
            "biases",
        ),
        ("sensor = [0.6, 0.7]", "sensor = [0.6, 0.7, 9.0]", "sensor"),
    ];
    synth_refuses_each(&dir, &series, &cases);
}

/// Issue 34 (hostile pass 2026-11-26, finding 20): `predict PLANAR-ID.json
/// planar-study.toml` was refused with "TOML parse error at line 1"; the
/// JSON holds the identified body, chains and tyres but not the beam, so it
/// is refused saying so and naming the planar car file to use instead.
#[test]
fn predict_with_a_planar_identification_json_says_to_use_the_car_file() {
    let dir = scratch("planar-predict-id-json");
    let (json, study) = (dir.join("r.json"), dir.join("study.toml"));
    let body = r#"{"mass": 1300.0, "yaw_inertia": 2200.0}"#;
    let chain = r#"{"masses": [8.0], "dampers": [1e3], "springs": [1e6]}"#;
    let document = format!(
        r#"{{"result": {{"car": {{"body": {body}, "left": {chain}, "right": {chain}, "tyres": {{}}}}, "parameters": []}}}}"#
    );
    std::fs::write(&json, document).unwrap();
    std::fs::write(&study, "[model]\nplanar = \"start.toml\"\n").unwrap();
    let run = bumpsim(&["predict", json.to_str().unwrap(), study.to_str().unwrap()]);
    assert_user_error(&run, "r.json: a planar identification's JSON");
    assert_user_error(&run, "--car CAR.toml");
    assert!(!text(&run.stderr).contains("TOML parse error"));
}
