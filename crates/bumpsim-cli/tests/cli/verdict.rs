//! `bumpsim verdict` by the real binary: the worked example's table with
//! its one failing criterion and margin, its JSON, exit 0 on a failing
//! verdict, the protocol list, and hostile inputs (exit 2 naming the key).

use crate::util::*;

fn car() -> std::path::PathBuf {
    root().join("examples/verdict/car.toml")
}

fn verdict(args: &[&str]) -> std::process::Output {
    let mut all = vec!["verdict"];
    all.extend_from_slice(args);
    bumpsim(&all)
}

#[test]
fn the_worked_example_fails_one_criterion_with_its_margin_and_exits_0() {
    let dir = scratch("verdict-example");
    let json = dir.join("verdict.json");
    let car = car();
    let run = verdict(&[
        "--car",
        car.to_str().unwrap(),
        "--protocol",
        "part581,rcar-bumper",
        "--json",
        json.to_str().unwrap(),
    ]);
    let out = text(&run.stdout);
    assert_eq!(run.status.code(), Some(0), "{}", text(&run.stderr));
    assert_contains(
        &out,
        &[
            "1 criterion/criteria fail: bumper stroke in rcar-bumper-corner-front (margin -",
            "rcar-bumper-corner-front FAILS",
            "part581-barrier-front passes",
            "override or underride",
            "no car file of the rear end was given",
            "mm",
            "kN",
            "km/h",
        ],
    );
    let bad = |w: &str| {
        w.contains("NaN") || w.trim_start_matches(['+', '-']).starts_with("inf") && w != "info"
    };
    assert!(!out.split_whitespace().any(bad), "{out}");
    let document: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(document["verdict"]["tests"].as_array().unwrap().len(), 12);
    assert!(document["target"].is_null());
}

#[test]
fn the_protocol_list_names_each_source() {
    let run = verdict(&["--list"]);
    assert_eq!(run.status.code(), Some(0), "{}", text(&run.stderr));
    assert_contains(
        &text(&run.stdout),
        &[
            "part581:",
            "cmvss215:",
            "r42:",
            "rcar-bumper:",
            "49 CFR 581",
            "uncertain:",
        ],
    );
}

#[test]
fn hostile_inputs_exit_2_naming_the_key() {
    let dir = scratch("verdict-hostile");
    let car = car();
    let car_arg = car.to_str().unwrap();
    let unknown = verdict(&["--car", car_arg, "--protocol", "fmvss-999"]);
    assert_user_error(&unknown, "unknown protocol or test 'fmvss-999'");
    let margin = verdict(&["--car", car_arg, "--margin", "-0.1"]);
    assert_user_error(&margin, "margin");
    let text = std::fs::read_to_string(&car).unwrap();
    let cut = text.split("[damageability]").next().unwrap();
    let bare = dir.join("bare.toml");
    std::fs::write(&bare, cut).unwrap();
    let missing = verdict(&["--car", bare.to_str().unwrap()]);
    assert_user_error(&missing, "damageability");
    let no_clearance = dir.join("no-clearance.toml");
    let head = text.split("[[damageability.clearance]]").next().unwrap();
    std::fs::write(&no_clearance, head).unwrap();
    let run = verdict(&["--car", no_clearance.to_str().unwrap()]);
    assert_user_error(&run, "damageability.clearance");
    let twice = verdict(&["--car", car_arg, "--car", car_arg]);
    assert_user_error(&twice, "damageability.end");
    // the radiator (beam clearance 60 mm) inside the 80 mm crash-box stroke
    let contradiction = dir.join("contradiction.toml");
    let long = text.replace("crash_box_stroke = 40.0", "crash_box_stroke = 70.0");
    std::fs::write(&contradiction, long).unwrap();
    let run = verdict(&["--car", contradiction.to_str().unwrap()]);
    assert_user_error(&run, "contradict");
}
