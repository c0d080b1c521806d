//! Issue 45 item 6: the bundled examples an engineer signs from. The rear
//! car is assessed, the front car's limits merge into a car file without
//! them (an identified car), an identification's spreads are refused on
//! another car, and every margin says what its 100 % is.

use bumpsim_verdict::prelude::*;
use bumpsim_verdict::protocol::select;
use std::path::{Path, PathBuf};

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name)
}

fn run(ends: Vec<CarEnd>, tests: &[&str]) -> Verdict {
    let setup = Setup::new(ends, select(tests).unwrap(), 0.0).unwrap();
    bumpsim_verdict::verdict(&setup).unwrap()
}

fn criterion<'a>(v: &'a Verdict, test: &str, name: &str) -> &'a Criterion {
    let t = v.tests.iter().find(|t| t.test.name == test).unwrap();
    t.criteria.iter().find(|c| c.name == name).unwrap()
}

/// The margin ratio is the margin over its reference: the limit, or, for
/// a pendulum's beam engagement (limit 0 mm), the ridge's height range
/// (16-20 in: 101.6 mm) or 50 mm where the ridge is set at one height.
#[test]
fn every_margin_states_what_its_hundred_percent_is() {
    let front = CarEnd::read(&example("verdict/car.toml"), None).unwrap();
    let v = run(
        vec![front],
        &["part581-pendulum-front", "part581-corner-front-left"],
    );
    let ridge = criterion(&v, "part581-pendulum-front", "beam engagement");
    assert_eq!(ridge.limit, 0.0);
    assert!((ridge.reference - 4.0 * 0.0254).abs() < 1e-12, "{ridge:?}");
    assert!((ridge.ratio - ridge.margin / ridge.reference).abs() < 1e-12);
    assert_eq!(ridge.reference_name, "the ridge's height range");
    let cell = bumpsim_verdict::text::margin(ridge);
    assert_eq!(cell, "6.400 mm (+6.3 % of 101.6 mm)");
    assert!(
        ridge
            .detail
            .contains("the margin's share is of the ridge's height range")
    );
    let corner = criterion(&v, "part581-corner-front-left", "beam engagement");
    assert_eq!(corner.reference, 0.05);
    assert!(
        corner.reference_name.contains("set at one height"),
        "{corner:?}"
    );
    // every other criterion's share is of its limit
    for c in v.tests.iter().flat_map(|t| &t.criteria) {
        if c.name != "beam engagement" {
            assert_eq!(c.reference, c.limit.abs(), "{c:?}");
            assert!(c.of_limit() && !bumpsim_verdict::text::margin(c).contains(" of "));
        }
    }
    let json = serde_json::to_value(ridge).unwrap();
    assert_eq!(json["reference_name"], "the ridge's height range");
    assert!((json["reference"].as_f64().unwrap() - 0.1016).abs() < 1e-12);
}

/// The bundled rear end is assessed in the rear tests (no "not assessed")
/// and passes 49 CFR 581's rear tests; the front file still runs the front.
#[test]
fn the_bundled_rear_car_is_assessed_in_the_rear_tests() {
    let front = CarEnd::read(&example("verdict/car.toml"), None).unwrap();
    let rear = CarEnd::read(&example("verdict/rear.toml"), None).unwrap();
    assert_eq!(rear.limits.end, End::Rear);
    let v = run(vec![front, rear], &["part581"]);
    for t in &v.tests {
        assert!(t.skipped.is_none(), "{}: {:?}", t.test.name, t.skipped);
        assert_eq!(t.passed(), Some(true), "{}: {:?}", t.test.name, t.binding());
    }
    assert!(
        v.tests
            .iter()
            .any(|t| t.test.name == "part581-barrier-rear")
    );
}

/// A car file without limits takes a damageability file's; the table of
/// examples/verdict/damageability.toml is car.toml's own; a car file with
/// its own table and a damageability file is refused naming both.
#[test]
fn a_damageability_file_merges_into_a_car_without_limits() {
    let own = CarEnd::read(&example("verdict/car.toml"), None).unwrap();
    let file = example("verdict/damageability.toml");
    assert_eq!(Damageability::read(&file).unwrap(), own.limits);
    let saloon = example("planar/saloon.toml");
    let e = CarEnd::read(&saloon, None).unwrap_err().to_string();
    assert!(
        e.contains("saloon.toml") && e.contains("--damageability"),
        "{e}"
    );
    let merged = CarEnd::read(&saloon, Some(&file)).unwrap();
    assert_eq!(merged.limits, own.limits);
    assert_eq!(merged.car.body(), own.car.body());
    let both = CarEnd::read(&example("verdict/car.toml"), Some(&file))
        .unwrap_err()
        .to_string();
    assert!(
        both.contains("car.toml [damageability]") && both.contains("damageability.toml"),
        "{both}"
    );
}

fn identification(mass: f64) -> String {
    format!(
        r#"{{"result": {{"parameters": [
            {{"name": "body.mass", "value": {mass}, "standard_error": 2.7}},
            {{"name": "left.springs[0]", "value": 3e6, "standard_error": 3e4}}],
          "uncertainty": {{"correlation": [[1.0, 0.2], [0.2, 1.0]]}}}}}}"#
    )
}

/// An identification's spreads (SE/value) belong to the car it identified:
/// on a car whose body mass is 1300 kg, the spreads of a 1249 kg
/// identification are refused naming the parameter and both values; those
/// of a 1300 kg one run; a TOML table of relative spreads runs on any car.
#[test]
fn spreads_identified_on_another_car_are_refused() {
    let end = CarEnd::read(&example("verdict/car.toml"), None).unwrap();
    let setup = Setup::new(vec![end], select(&["part581-barrier-front"]).unwrap(), 0.0).unwrap();
    let sampling = Sampling {
        samples: 10,
        seed: 1,
    };
    let propagate = |u: &Uncertainty| {
        let mut v = bumpsim_verdict::verdict(&setup).unwrap();
        bumpsim_verdict::probability::propagate(&setup, &mut v, u, sampling)
    };
    let other = Uncertainty::parse(&identification(1249.0), "id.json".as_ref()).unwrap();
    let e = propagate(&other).unwrap_err().to_string();
    for needle in [
        "id.json",
        "another car",
        "body.mass is 1300",
        "but 1249",
        "+4.1 %",
    ] {
        assert!(e.contains(needle), "{needle}: {e}");
    }
    let own = Uncertainty::parse(&identification(1300.0), "id.json".as_ref()).unwrap();
    assert!(propagate(&own).is_ok());
    // within 0.1 %: a value rounded by hand is the same car
    let rounded = Uncertainty::parse(&identification(1300.9), "id.json".as_ref()).unwrap();
    assert!(propagate(&rounded).is_ok());
    let spreads = Uncertainty::read(&example("verdict/uncertainty.toml")).unwrap();
    assert!(propagate(&spreads).is_ok());
}
