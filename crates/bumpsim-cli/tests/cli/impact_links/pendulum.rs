//! `bumpsim impact --pendulum` of the bundled links car against an
//! independent integration (tests/peers/scipy_links_pendulum.py: the link
//! laws written again from the format's text, the history d_max a state
//! of the ODE, DOP853 at rtol 1e-10 instead of the leapfrog), and the
//! presets of the pendulum and moving-barrier kinds.

use crate::util::*;
use bumpsim_peers::python_available;
use std::process::Command;

/// 25 km/h: the crash zone (80 kN) yields and the tabulated link keeps a set.
const SPEED: f64 = 25.0 / 3.6;
const MASS: f64 = 1500.0;

#[test]
fn a_pendulum_into_the_links_car_matches_an_independent_scipy_integration() {
    let dir = scratch("impact-links-pendulum");
    let car = root().join("examples/links/car.toml");
    let json = dir.join("r.json");
    let run = bumpsim(&[
        "impact",
        "--car",
        car.to_str().unwrap(),
        "--pendulum",
        "1500",
        "--speed",
        "25 km/h",
        "--json",
        json.to_str().unwrap(),
    ]);
    let stdout = text(&run.stdout);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert_contains(
        &stdout,
        &[
            "links example: yielding crash boxes, 3 masses: pendulum of 1500 kg into the car at rest at 25.00 km/h\n",
            "  peak contact force ",
            "  front link (crush zone): largest compression ",
            "; speeds at the end along the impact: striker ",
        ],
    );
    let doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert!(doc["warnings"].as_array().unwrap().is_empty(), "{doc}");
    // the balance with the striker's ½ M V² at the start
    let e = &doc["energy"];
    let initial = 0.5 * MASS * SPEED * SPEED;
    assert!((e["initial"].as_f64().unwrap() - initial).abs() < 1e-9 * initial);
    assert!(e["relative_error"].as_f64().unwrap() < 1e-3, "{e}");
    // momentum: M V = M v_s + Σ m v_car
    let s = &doc["striker"];
    let total = 6.0 + 180.0 + 1250.0;
    let momentum =
        MASS * s["final_speed"].as_f64().unwrap() + total * s["car_final_speed"].as_f64().unwrap();
    assert!(
        (momentum - MASS * SPEED).abs() < 1e-9 * MASS * SPEED,
        "{momentum}"
    );
    if !python_available("scipy") {
        return;
    }
    let script = root().join("tests/peers/scipy_links_pendulum.py");
    let peer = Command::new("python3")
        .arg(&script)
        .arg(&car)
        .args([
            MASS.to_string(),
            SPEED.to_string(),
            "1e-4".into(),
            "0.25".into(),
        ])
        .output()
        .unwrap();
    assert!(peer.status.success(), "{}", text(&peer.stderr));
    let scipy: serde_json::Value = serde_json::from_str(&text(&peer.stdout)).unwrap();
    let number = |v: &serde_json::Value| v.as_f64().unwrap();
    // the leapfrog's O((ωT)²) with ωT ≤ 0.08 on the 6 kg beam, and the
    // samples' maxima at 0.1 ms: 0.2 % of the forces, speeds and crushes
    // (measured: at most 2.4e-4 of them, on the sets)
    let close = |ours: f64, theirs: f64, scale: f64, what: &str| {
        assert!(
            (ours - theirs).abs() <= 0.002 * scale,
            "{what}: bumpsim {ours}, scipy {theirs}"
        );
    };
    let peak = number(&scipy["peak_force"]);
    close(number(&doc["peak_force"]), peak, peak, "peak force");
    let links = doc["links"].as_array().unwrap();
    let crush = number(&scipy["max_compression"][0]);
    for (j, link) in links.iter().enumerate() {
        let reached = number(&scipy["max_compression"][j]);
        let what = link["name"].as_str().unwrap();
        close(number(&link["max_compression"]), reached, reached, what);
        // a set is a difference: 0.2 % of the largest crush
        let set = number(&scipy["plastic_set"][j]);
        close(number(&link["plastic_set"]), set, crush, what);
    }
    // the crash zone yielded and the tabulated link kept a set
    assert!(number(&scipy["plastic_set"][0]) > 0.05 && number(&scipy["plastic_set"][2]) > 0.03);
    let speed = |key: &str| number(&scipy[key]);
    close(
        number(&s["final_speed"]),
        speed("striker_final_speed"),
        SPEED,
        "striker",
    );
    close(
        number(&s["car_final_speed"]),
        speed("car_final_speed"),
        SPEED,
        "car",
    );
    let plastic = speed("plastic");
    close(number(&e["plastic"]), plastic, plastic, "plastic work");
}

#[test]
fn the_pendulum_and_moving_barrier_presets_run_into_a_links_car() {
    let car = root().join("examples/links/car.toml");
    for (case, needle) in [
        ("part581-pendulum-front", "pendulum of the vehicle's mass"),
        ("rcar-structural-rear", "1400 kg mobile barrier"),
    ] {
        let run = bumpsim(&["impact", "--car", car.to_str().unwrap(), "--case", case]);
        let stdout = text(&run.stdout);
        assert!(run.status.success(), "{case}: {}", text(&run.stderr));
        assert_contains(
            &stdout,
            &[case, needle, "  peak contact force ", "striker "],
        );
    }
}
