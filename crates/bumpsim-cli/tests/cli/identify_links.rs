//! `bumpsim identify` and `bumpsim predict` of a links study (issue 46):
//! on NHTSA test 10146 the car with nonlinear links identified into the
//! barrier, its forward run into a rigid wall from the identified car
//! alone, the car file `--car` writes run by `impact` and `predict`; the
//! links example series `synth` writes identified with the `[links]`
//! defaults; and the `[links]` keys refused by name with exit code 2.

use crate::util::*;
use serde_json::Value;
use std::path::Path;

/// The example links study with its data read from wherever NHTSA 10146
/// is (`../shared` or `$BUMPSIM_SHARED`), written into `dir`.
pub(crate) fn links_study(dir: &Path, ev5: &Path) -> std::path::PathBuf {
    let text = std::fs::read_to_string(root().join("examples/nhtsa-10146/links.toml")).unwrap();
    let text = text.replace(
        "../../../shared/data/nhtsa-10146/v10146.EV5",
        ev5.to_str().unwrap(),
    );
    let path = dir.join("links.toml");
    std::fs::write(&path, text).unwrap();
    path
}

fn number(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("{v} is not a number"))
}

/// Issue 46's acceptance through the command: the crossmember fits
/// ≥ 99 %, the identified car alone run into a rigid wall at the test's
/// speed predicts the summed barrier force ≥ 90 % and the crossmember ΔV
/// within 3 %, every plastic set is printed with its interval; the car
/// file runs in `impact` to the same peak force and plastic sets, and in
/// `predict` to the same forward figures.
#[test]
fn the_links_study_of_nhtsa_10146_meets_the_acceptance_through_identify_impact_and_predict() {
    let Some(ev5) = nhtsa_ev5() else { return };
    let dir = scratch("identify-links-nhtsa");
    let study = links_study(&dir, &ev5);
    let (json, car, report) = (
        dir.join("identified.json"),
        dir.join("car.toml"),
        dir.join("report"),
    );
    let run = bumpsim(&[
        "identify",
        study.to_str().unwrap(),
        "--json",
        json.to_str().unwrap(),
        "--car",
        car.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
        "--quiet",
    ]);
    let stdout = text(&run.stdout);
    assert!(run.status.success(), "{stdout}{}", text(&run.stderr));
    assert_contains(
        &stdout,
        &[
            "linear chain, 2-DOF (the staged start)",
            "chain with nonlinear links into the barrier, 2 masses (20-knot front crush zone, a 8-knot second path, a rebound link on m2)",
            "forward into a rigid wall at 57.09 km/h from the identified car alone",
            "plastic set of the front crush zone after ncap-57kph: ",
            "plastic set of the second load path after ncap-57kph: ",
            "total mass ",
            "test sheet 1719 kg",
            "which links the data want",
            "BIC: linear ",
            // on the links car's residuals (32 effective of 1201)
            "the data want yielding links",
        ],
    );
    let doc: Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let fit = number(&doc["fits"][0][1]);
    let forward = &doc["forward"][0];
    let (force, dv) = (
        number(&forward["force_fit"]),
        number(&forward["delta_v_error"]),
    );
    assert!(fit >= 99.0, "crossmember fit {fit} %\n{stdout}");
    assert!(force >= 90.0, "forward force fit {force} %\n{stdout}");
    assert!(dv < 0.03, "ΔV {} % off\n{stdout}", 100.0 * dv);
    let sets = doc["plastic_sets"].as_array().unwrap();
    assert_eq!(
        sets.len(),
        4,
        "front, link 1, second path, rebound: {sets:?}"
    );
    for set in sets {
        let value = number(&set["value"]);
        let [lo, hi] = [number(&set["ci95"][0]), number(&set["ci95"][1])];
        assert!(lo <= value && value <= hi, "{set}");
        let name = set["name"].as_str().unwrap();
        let the = if name.starts_with("link") { "" } else { "the " };
        assert!(
            stdout.contains(&format!("plastic set of {the}{name} after")),
            "{set}"
        );
    }
    assert!(stdout.matches("  95 % [").count() >= 4, "{stdout}");
    for file in [
        "index.html",
        "force-ncap-57kph.svg",
        "output-ncap-57kph.svg",
    ] {
        assert!(report.join(file).is_file(), "{file}");
    }
    impact_agrees(&dir, &car, &doc);
    predict_agrees(&dir, &car, &study, forward);
}

/// `impact --car CAR --barrier --speed 57.09km/h` on the written car:
/// the peak force of the forward run, the plastic sets identify printed
/// (the impact's step is the test's 0.1 ms; 0.1 % and 1 µm for rounding).
fn impact_agrees(dir: &Path, car: &Path, identified: &Value) {
    let json = dir.join("impact.json");
    let run = bumpsim(&[
        "impact",
        "--car",
        car.to_str().unwrap(),
        "--barrier",
        "--speed",
        "57.09km/h",
        "--json",
        json.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let doc: Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let close = |a: f64, b: f64, what: &str| {
        assert!(
            (a - b).abs() <= 1e-3 * b.abs() + 1e-6,
            "{what}: impact {a}, identify {b}"
        );
    };
    close(
        number(&doc["peak_force"]),
        number(&identified["forward"][0]["peak_force"]),
        "peak force",
    );
    let links = doc["links"].as_array().unwrap();
    for set in identified["plastic_sets"].as_array().unwrap() {
        let name = match set["name"].as_str().unwrap() {
            "front crush zone" => "front",
            other => other,
        };
        let found = links
            .iter()
            .find(|l| l["name"] == name)
            .unwrap_or_else(|| panic!("no {name} in {links:?}"));
        close(
            number(&found["plastic_set"]),
            number(&set["value"]),
            &format!("plastic set of {name}"),
        );
    }
}

/// `predict CAR STUDY`: the forward run's figures again.
fn predict_agrees(dir: &Path, car: &Path, study: &Path, forward: &Value) {
    let json = dir.join("predict.json");
    let run = bumpsim(&[
        "predict",
        car.to_str().unwrap(),
        study.to_str().unwrap(),
        "--json",
        json.to_str().unwrap(),
    ]);
    let stdout = text(&run.stdout);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert_contains(
        &stdout,
        &[
            "ncap-57kph: into a rigid wall at 57.09 km/h: wall force fit ",
            "plastic set of the front crush zone: ",
        ],
    );
    let doc: Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let case = &doc["cases"][0];
    for key in ["force_fit", "output_fit", "delta_v", "peak_force"] {
        let (a, b) = (number(&case[key]), number(&forward[key]));
        assert!(
            (a - b).abs() <= 1e-9 * b.abs().max(1.0),
            "{key}: {a} vs {b}"
        );
    }
}

/// The `[links]` keys and the study around them, refused by name with
/// exit code 2 before any case is loaded (the bundled study's cases).
#[test]
fn hostile_links_keys_are_refused_by_name() {
    let dir = scratch("identify-links-hostile");
    let base = root().join("examples/identify");
    copy_tree(&base, &dir);
    let chain = std::fs::read_to_string(dir.join("study.toml")).unwrap();
    let links = format!("kind = \"links\"\n{}", chain.replace("dof = 3", "dof = 2"));
    let refused = [
        (
            "knots = -1",
            "[links] knots = -1: expected a whole number from 2 to 64",
        ),
        ("knots = 1e9", "[links] knots = 1000000000.0"),
        ("path_knots = 100000", "[links] path_knots = 100000"),
        ("rebound = \"first\"", "[links] rebound = \"first\""),
        ("mass_spread = nan", "[links] mass_spread = nan"),
        ("mass_spread = -0.5", "[links] mass_spread = -0.5"),
        ("floor = [0.1, inf]", "[links] floor = inf"),
        ("weighting = \"noise\"", "[links] weighting = \"noise\""),
        (
            "front_mass_min = \"-3 kg\"",
            "[links] front_mass_min = \"-3 kg\"",
        ),
        ("linear_starts = 0", "[links] linear_starts = 0"),
        ("nots = 3", "[links] nots: unknown key"),
        ("rebound = 5", "[links] rebound = 5: the chain has 2 masses"),
    ];
    for (k, (line, said)) in refused.iter().enumerate() {
        let study = dir.join(format!("hostile-{k}.toml"));
        std::fs::write(&study, format!("{links}\n[links]\n{line}\n")).unwrap();
        let run = bumpsim(&["identify", study.to_str().unwrap(), "--quiet"]);
        assert_user_error(&run, said);
    }
    // a [links] table in a study that is not a links study, several sizes
    let chain_with = dir.join("chain-with-links.toml");
    std::fs::write(&chain_with, format!("{chain}\n[links]\nknots = 4\n")).unwrap();
    let run = bumpsim(&["identify", chain_with.to_str().unwrap(), "--quiet"]);
    assert_user_error(&run, "[links] holds the settings of a links study");
    let sizes = dir.join("sizes.toml");
    std::fs::write(&sizes, links.replace("dof = 2", "dof = [2, 3]")).unwrap();
    let run = bumpsim(&["identify", sizes.to_str().unwrap(), "--quiet"]);
    assert_user_error(&run, "a links study identifies one model size");
    let posterior = dir.join("posterior.toml");
    std::fs::write(&posterior, &links).unwrap();
    let run = bumpsim(&["identify", posterior.to_str().unwrap(), "--posterior"]);
    assert_user_error(
        &run,
        "--posterior: a links study has no posterior sampling yet",
    );
}

/// A car with a second load path runs into the barrier with its plastic
/// set printed, and `export` writes the wall link exactly in both decks:
/// an inelastic spring in LS-DYNA, a brick behind a one-sided `SPRINGA`
/// in CalculiX; neither command warns of an approximation.
#[test]
fn a_car_with_a_second_path_runs_into_the_barrier_and_exports_it() {
    let dir = scratch("links-wall-path");
    let car = std::fs::read_to_string(root().join("examples/links/car.toml")).unwrap();
    let path = dir.join("car.toml");
    let wall = "\n[path]\nmass = 3\ngap = \"200 mm\"\ncurve = \"bilinear\"\nstiffness = \"2000 N/mm\"\nyield_force = \"60 kN\"\nunloading = \"4000 N/mm\"\n";
    std::fs::write(&path, format!("{car}{wall}")).unwrap();
    let run = bumpsim(&[
        "impact",
        "--car",
        path.to_str().unwrap(),
        "--barrier",
        "--speed",
        "40 km/h",
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert_contains(
        &text(&run.stdout),
        &["  second load path: largest compression "],
    );
    let deck = dir.join("car.k");
    let run = bumpsim(&[
        "export",
        "lsdyna",
        path.to_str().unwrap(),
        "-o",
        deck.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let written = std::fs::read_to_string(&deck).unwrap();
    assert_contains(&written, &["$ second load path: ", "*MAT_SPRING_INELASTIC"]);
    assert!(
        !text(&run.stderr).contains("approximates"),
        "{}",
        text(&run.stderr)
    );
    let inp = dir.join("car.inp");
    let run = bumpsim(&[
        "export",
        "calculix",
        path.to_str().unwrap(),
        "-o",
        inp.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(
        !text(&run.stderr).contains("approximates"),
        "{}",
        text(&run.stderr)
    );
    let written = std::fs::read_to_string(&inp).unwrap();
    assert_contains(
        &written,
        &[
            "** second load path: after the gap: exact in compression; never pulls",
            "*ELEMENT, TYPE=SPRINGA, ELSET=BUMPSIM_EPATH",
            "*ELEMENT, TYPE=C3D8, ELSET=BUMPSIM_EPATHB",
        ],
    );
}

/// The links example series identified as a user would (issue 46's last
/// gap): `bumpsim synth examples/links/series.toml` and `bumpsim identify`
/// of the study it writes, with the `[links]` defaults and its 16 starts
/// (84 to 133 s on the loaded 2-core machine: above the suite's minute,
/// as the NHTSA study's own test). The car is the
/// right way round (a bumper beam under 20 kg, the truth's is 6 kg, the
/// body heaviest and last: the staged start puts the linear chain's masses
/// lightest first and the default m1 floor is 0.2 % of the sheet's mass),
/// every output fits ≥ 98.5 %, the identified car alone run into the wall
/// predicts each wall force ≥ 90 % (measured 99.70/98.94/99.90 % and
/// 94.87/94.70/92.13 %; docs/benchmarks.md, "The links example's
/// defaults"), the two links' yield forces lie between 50 and 100 kN (the
/// truth's crash boxes yield at 80 kN, its longitudinal bends at 60 kN),
/// and the comparison says the data want yielding links.
#[test]
fn the_links_example_series_is_identified_with_the_defaults() {
    let dir = scratch("identify-links-example");
    let out = dir.join("series");
    let series = root().join("examples/links/series.toml");
    let run = bumpsim(&[
        "synth",
        series.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let study = out.join("study.toml");
    let json = dir.join("identified.json");
    let run = bumpsim(&[
        "identify",
        study.to_str().unwrap(),
        "--json",
        json.to_str().unwrap(),
        "--quiet",
    ]);
    let stdout = text(&run.stdout);
    assert!(run.status.success(), "{stdout}{}", text(&run.stderr));
    assert_contains(&stdout, &["the data want yielding links"]);
    let doc: Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(doc["verdict"]["yielding"], true, "{stdout}");
    let parameter = |name: &str| {
        let all = doc["parameters"].as_array().unwrap();
        let found = all.iter().find(|p| p["name"] == name).unwrap();
        number(&found["value"])
    };
    let (m1, m2, m3) = (parameter("m1"), parameter("m2"), parameter("m3"));
    assert!(
        m1 < 20.0 && m1 < m2 && m2 < m3,
        "m {m1} {m2} {m3} kg\n{stdout}"
    );
    for name in ["Fy1", "Fy2"] {
        let force = parameter(name);
        assert!((5e4..=1e5).contains(&force), "{name} {force} N\n{stdout}");
    }
    for (case, forward) in doc["forward"].as_array().unwrap().iter().enumerate() {
        let fit = number(&doc["fits"][case][1]);
        let force = number(&forward["force_fit"]);
        assert!(fit >= 98.5, "output fit {fit} %\n{stdout}");
        assert!(force >= 90.0, "forward force fit {force} %\n{stdout}");
    }
}
