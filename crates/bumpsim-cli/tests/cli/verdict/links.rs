//! `bumpsim verdict` of a car with nonlinear links (issue 46): the bundled
//! links car (examples/verdict/links.toml) judged in the protocols' tests
//! along its centre line, its strokes checked against an independent
//! integration of the same pendulum test (tests/peers), and what only the
//! planar car's verdict has refused by name.

use super::verdict;
use crate::util::*;
use bumpsim_peers::python_available;
use std::process::Command;

fn links() -> std::path::PathBuf {
    root().join("examples/verdict/links.toml")
}

#[test]
fn a_links_car_is_judged_in_the_protocols_tests_along_its_centre_line() {
    let dir = scratch("verdict-links");
    let json = dir.join("verdict.json");
    let car = links();
    let run = verdict(&[
        "--car",
        car.to_str().unwrap(),
        "--protocol",
        "part581,rcar-bumper,rcar-structural",
        "--json",
        json.to_str().unwrap(),
    ]);
    let out = text(&run.stdout);
    assert_eq!(run.status.code(), Some(0), "{}", text(&run.stderr));
    assert_contains(
        &out,
        &[
            "part581-pendulum-front",
            "clearance: radiator",
            "clearance: bonnet latch",
            "rail force",
            "crash-box stroke",
            "bumper stroke",
            "beam engagement",
            "run along the car's centre line (1-D)",
            "no car file of the rear end was given",
        ],
    );
    let doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let tests = doc["verdict"]["tests"].as_array().unwrap();
    let test = |name: &str| tests.iter().find(|t| t["test"]["name"] == name).unwrap();
    let criterion = |t: &serde_json::Value, name: &str| {
        let c = t["criteria"].as_array().unwrap();
        c.iter().find(|c| c["name"] == name).unwrap()["value"]
            .as_f64()
            .unwrap()
    };
    // 49 CFR 581 at 2.5 mph: nothing yields, every criterion passes
    let pendulum = test("part581-pendulum-front");
    assert!(
        pendulum["criteria"]
            .as_array()
            .unwrap()
            .iter()
            .all(|c| c["outcome"] != "fail"),
        "{pendulum}"
    );
    // the pulse is the body's: an equal mass at 1.1176 m/s that nothing
    // yields under gives the car between the plastic impact's half and
    // the elastic exchange's whole of it (the links' vibration at the
    // contact's end a little more)
    let dv = pendulum["metrics"]["delta_v"].as_f64().unwrap();
    assert!(dv > 0.5 * 1.1176 && dv < 1.02 * 1.1176, "{dv}");
    // RCAR's structural test crushes the bumper further than its bumper test
    let bumper = |name: &str| criterion(test(name), "bumper stroke");
    assert!(bumper("rcar-structural-front") > bumper("rcar-bumper-front"));
    if !python_available("scipy") {
        return;
    }
    // the same pendulum test integrated independently: the bumper's and
    // the crash box's largest crush (1 % of the bumper's)
    let mass = 16.0 + 70.0 + 1250.0;
    let script = root().join("tests/peers/scipy_links_pendulum.py");
    let peer = Command::new("python3")
        .arg(&script)
        .arg(&car)
        .args([
            f64::to_string(&mass),
            "1.1176".into(),
            "1e-4".into(),
            "0.3".into(),
        ])
        .output()
        .unwrap();
    assert!(peer.status.success(), "{}", text(&peer.stderr));
    let scipy: serde_json::Value = serde_json::from_str(&text(&peer.stdout)).unwrap();
    let reached = |j: usize| scipy["max_compression"][j].as_f64().unwrap();
    let scale = reached(0);
    for (name, j) in [("bumper stroke", 0), ("crash-box stroke", 1)] {
        let ours = criterion(pendulum, name);
        assert!(
            (ours - reached(j)).abs() < 0.01 * scale,
            "{name}: bumpsim {ours}, scipy {}",
            reached(j)
        );
    }
}

#[test]
fn a_links_car_without_limits_or_with_planar_options_is_refused_by_name() {
    let dir = scratch("verdict-links-refused");
    let car = links();
    let car_arg = car.to_str().unwrap();
    let target = verdict(&["--car", car_arg, "--protocol", "part581", "--target"]);
    assert_user_error(&target, "--target: a car with nonlinear links");
    let text = std::fs::read_to_string(&car).unwrap();
    let bare = dir.join("bare.toml");
    std::fs::write(&bare, text.split("# Clearances").next().unwrap()).unwrap();
    let missing = verdict(&["--car", bare.to_str().unwrap()]);
    assert_user_error(&missing, "damageability");
    // the radiator (60 mm behind the beam) within a 70 mm crash-box stroke
    let long = dir.join("long.toml");
    let stroke = text.replace("crash_box_stroke = 40.0", "crash_box_stroke = 70.0");
    std::fs::write(&long, stroke).unwrap();
    let run = verdict(&["--car", long.to_str().unwrap()]);
    assert_user_error(&run, "contradict");
}
