//! The one table of tests (issue 45 item 3): `impact --case list`, `planar
//! --case list` and `verdict --list` list the same tests; old names are
//! refused by every command with the new one named; `--market` sets the
//! RCAR barrier's heights.

use crate::util::{assert_contains, assert_user_error, bumpsim, root, scratch, text};
use std::collections::BTreeSet;

/// A rigid 1050 kg car and the bundled bumper, as `impact` arguments.
fn impact_car(test: &str) -> [String; 4] {
    let car = scratch(&format!("presets-{test}")).join("utv.toml");
    let text = "name = \"UTV\"\nmasses = [1050.0]\ndampers = []\nsprings = []\n";
    std::fs::write(&car, text).unwrap();
    [
        "--car".into(),
        car.display().to_string(),
        "--bumper".into(),
        root()
            .join("examples/impact/bumper-a.toml")
            .display()
            .to_string(),
    ]
}

fn run(args: &[&str]) -> String {
    let out = bumpsim(args);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{args:?}: {}",
        text(&out.stderr)
    );
    text(&out.stdout)
}

/// The names `--case list` prints: the first word of each unindented line
/// that is not a protocol heading.
fn case_names(listing: &str) -> BTreeSet<String> {
    listing
        .lines()
        .filter(|l| !l.starts_with([' ', '#']) && !l.is_empty())
        .filter_map(|l| l.split_whitespace().next().map(str::to_string))
        .collect()
}

/// The test names `verdict --list` prints: `  name: description` lines.
fn verdict_names(listing: &str) -> BTreeSet<String> {
    listing
        .lines()
        .filter_map(|l| l.strip_prefix("  "))
        .filter(|l| !l.starts_with(' '))
        .filter_map(|l| l.split_once(": ").map(|(name, _)| name))
        .filter(|name| !name.contains(' '))
        .map(str::to_string)
        .collect()
}

#[test]
fn impact_planar_and_verdict_list_the_same_tests_from_one_table() {
    // exactly the command: no car is needed to list the tests
    let impact = case_names(&run(&["impact", "--case", "list"]));
    let car = impact_car("lists");
    let mut args: Vec<&str> = vec!["impact"];
    args.extend(car.iter().map(String::as_str));
    args.extend(["--case", "list"]);
    assert_eq!(case_names(&run(&args)), impact, "with a car too");
    let planar = case_names(&run(&["planar", "--case", "list"]));
    let verdict = verdict_names(&run(&["verdict", "--list"]));
    assert_eq!(impact, planar);
    assert_eq!(impact, verdict);
    for name in [
        "thesis-flat",
        "part581-corner-front-left",
        "r42-longitudinal-rear",
        "r42-laden-longitudinal-front",
        "rcar-structural-front",
        "iihs-bumper-corner-rear",
    ] {
        assert!(impact.contains(name), "{name} in {impact:?}");
    }
    assert_eq!(impact.len(), 35, "{impact:?}");
}

#[test]
fn old_names_are_refused_with_exit_2_naming_the_new_one() {
    let car = impact_car("old-names");
    for (old, new) in [
        ("rcar-16", "rcar-structural-front"),
        ("fmvss-581", "part581-pendulum-front"),
        ("cmvss-215", "part581-pendulum-front"),
        ("iihs-corner-front", "iihs-bumper-corner-front"),
    ] {
        let mut args: Vec<&str> = vec!["impact"];
        args.extend(car.iter().map(String::as_str));
        args.extend(["--case", old]);
        assert_user_error(&bumpsim(&args), new);
        let saloon = root().join("examples/planar/saloon.toml");
        let planar = bumpsim(&["planar", "--car", saloon.to_str().unwrap(), "--case", old]);
        assert_user_error(&planar, new);
        let verdict_car = root().join("examples/verdict/car.toml");
        let verdict = bumpsim(&[
            "verdict",
            "--car",
            verdict_car.to_str().unwrap(),
            "--protocol",
            old,
        ]);
        assert_user_error(&verdict, new);
    }
}

#[test]
fn a_1d_impact_says_what_it_drops_of_the_test() {
    let car = impact_car("dropped");
    let mut args: Vec<&str> = vec!["impact"];
    args.extend(car.iter().map(String::as_str));
    args.extend(["--case", "rcar-structural-front"]);
    assert_contains(
        &run(&args),
        &["1-D: run head-on along the centre line, without the 10° angle, the 40 % overlap"],
    );
}

#[test]
fn the_market_sets_the_rcar_barrier_heights() {
    let america = run(&["verdict", "--list"]);
    let europe = run(&["verdict", "--list", "--market", "europe"]);
    assert_contains(
        &america,
        &[
            "market north-america",
            "height: face 455-555 mm",
            "rigid backstop 200 mm tall above it, 25 mm behind the face",
        ],
    );
    assert_contains(&europe, &["market europe", "height: face 405-505 mm"]);
    assert!(!europe.contains("height: face 455-555 mm"), "{europe}");
    for hedge in ["from memory", "as recalled"] {
        assert!(!america.contains(hedge), "{hedge}");
    }
    let wrong = bumpsim(&["verdict", "--list", "--market", "mars"]);
    assert_eq!(wrong.status.code(), Some(2));
}
