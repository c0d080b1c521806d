//! Issue 44: the README's main job propagated into an impact. The bundled
//! example is identified (the default velocity objective, intervals from
//! the random walk of the integrated accelerometer noise, the stated
//! priors: the test sheet's mass and each element near the start), each of
//! its seven 95 % intervals must contain the true car's value
//! (`examples/identify/car-truth.toml`, the car the bundled tests were
//! synthesised from), its spreads are propagated through a barrier impact
//! (docs/uncertainty.md's command, the default 90 % level), and the same
//! impact of the true car must lie inside the band of the peak force, as
//! of every other scalar result. (Without the priors the peak force lay
//! 0.1 % below the 90 % band: docs/uncertainty.md says why.)

use crate::util::*;

/// The scalar results an impact JSON carries, by the name its
/// `prediction.outputs` give them.
const RESULTS: [(&str, &str); 4] = [
    ("peak force", "peak_force"),
    ("maximum compression", "max_compression"),
    ("remaining compression", "remaining_compression"),
    ("contact time", "contact_time"),
];

fn json(path: &std::path::Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
fn the_bundled_examples_force_band_contains_the_true_cars_force() {
    let dir = scratch("identify-band");
    let id = dir.join("id.json");
    let study = root().join("examples/identify/study.toml");
    let run = bumpsim(&[
        "identify",
        study.to_str().unwrap(),
        "--json",
        id.to_str().unwrap(),
        "--quiet",
    ]);
    assert_eq!(run.status.code(), Some(0), "{}", text(&run.stderr));
    let bumper = root().join("examples/impact/bumper-a.toml");
    let impact = |car: &std::path::Path, out: &std::path::Path, uncertain: bool| {
        let mut args = vec![
            "impact",
            "--car",
            car.to_str().unwrap(),
            "--bumper",
            bumper.to_str().unwrap(),
            "--barrier",
            "--speed",
            "8 km/h",
            "--json",
            out.to_str().unwrap(),
        ];
        if uncertain {
            args.extend(["--uncertainty", id.to_str().unwrap()]);
        }
        let run = bumpsim(&args);
        assert_eq!(run.status.code(), Some(0), "{}", text(&run.stderr));
        json(out)
    };
    let found = json(&id);
    let truth_parameters = [30.0, 250.0, 1170.0, 8e3, 2.5e4, 1.5e6, 6e5];
    for (i, truth) in truth_parameters.iter().enumerate() {
        let interval = &found["uncertainty"]["ci95"][i];
        let (low, high) = (interval[0].as_f64().unwrap(), interval[1].as_f64().unwrap());
        assert!(
            low <= *truth && *truth <= high,
            "parameter {i}: the truth {truth} outside its 95 % interval {low} .. {high}"
        );
    }
    let identified = impact(&id, &dir.join("identified.json"), true);
    let truth = impact(
        &root().join("examples/identify/car-truth.toml"),
        &dir.join("truth.json"),
        false,
    );
    let outputs = identified["prediction"]["outputs"].as_array().unwrap();
    for (name, key) in RESULTS {
        let spread = &outputs.iter().find(|o| o["name"] == name).unwrap()["spread"];
        let (low, high) = (
            spread["low"].as_f64().unwrap(),
            spread["high"].as_f64().unwrap(),
        );
        let true_value = truth[key].as_f64().unwrap();
        assert!(
            low <= true_value && true_value <= high,
            "{name}: the true car's {true_value} outside the 90 % band {low} .. {high}"
        );
    }
}
