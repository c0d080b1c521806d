//! Issue 45 item 6 by the real binary: the bundled rear car assessed, an
//! identified car's limits merged with --damageability (and refused
//! without, or twice), another car's spreads refused with exit 2, the
//! margins' reference in the table and JSON, the target's row at the car's
//! own stiffness.

use super::verdict;
use crate::util::*;

fn example(name: &str) -> String {
    root()
        .join("examples")
        .join(name)
        .to_str()
        .unwrap()
        .to_string()
}

#[test]
fn the_bundled_rear_car_is_assessed_and_margins_name_their_reference() {
    let dir = scratch("verdict-rear");
    let json = dir.join("v.json");
    let (front, rear) = (example("verdict/car.toml"), example("verdict/rear.toml"));
    let run = verdict(&[
        "--car",
        &front,
        "--car",
        &rear,
        "--protocol",
        "part581",
        "--json",
        json.to_str().unwrap(),
    ]);
    let out = text(&run.stdout);
    assert_eq!(run.status.code(), Some(0), "{}", text(&run.stderr));
    assert!(!out.contains("no car file of the rear end"), "{out}");
    assert_contains(
        &out,
        &[
            "part581-barrier-rear passes",
            "every assessed test passes",
            "16.40 mm (+16.1 % of 101.6 mm)",
            "the margin's share is of the ridge's height range",
        ],
    );
    let document: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let criteria = &document["verdict"]["tests"][0]["criteria"];
    let names: Vec<&str> = criteria
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["reference_name"].as_str().unwrap())
        .collect();
    assert!(names.contains(&"the limit") && names.contains(&"the ridge's height range"));
}

#[test]
fn an_identified_car_takes_its_limits_from_a_damageability_file() {
    let saloon = example("planar/saloon.toml");
    let limits = example("verdict/damageability.toml");
    let test = ["--protocol", "part581-barrier-front"];
    let without = verdict(&[&["--car", saloon.as_str()], &test[..]].concat());
    assert_eq!(without.status.code(), Some(2));
    assert_contains(
        &text(&without.stderr),
        &["saloon.toml", "--damageability FILE"],
    );
    let merged = verdict(
        &[
            &["--car", saloon.as_str(), "--damageability", limits.as_str()],
            &test[..],
        ]
        .concat(),
    );
    assert_eq!(merged.status.code(), Some(0), "{}", text(&merged.stderr));
    assert_contains(&text(&merged.stdout), &["part581-barrier-front passes"]);
    let front = example("verdict/car.toml");
    let both = verdict(
        &[
            &["--car", front.as_str(), "--damageability", limits.as_str()],
            &test[..],
        ]
        .concat(),
    );
    assert_eq!(both.status.code(), Some(2));
    assert_contains(
        &text(&both.stderr),
        &["car.toml [damageability]", "an end has one set"],
    );
    let twice = verdict(
        &[
            &[
                "--car",
                saloon.as_str(),
                "--damageability",
                limits.as_str(),
                "--damageability",
                limits.as_str(),
            ],
            &test[..],
        ]
        .concat(),
    );
    assert_eq!(twice.status.code(), Some(2));
    assert_contains(
        &text(&twice.stderr),
        &["--damageability given 2 times for 1 --car"],
    );
}

#[test]
fn another_car_s_identified_spreads_are_refused() {
    let dir = scratch("verdict-foreign");
    let json = dir.join("id.json");
    std::fs::write(
        &json,
        r#"{"result": {"parameters": [{"name": "body.mass", "value": 1249.0, "standard_error": 2.7}],
            "uncertainty": {"correlation": [[1.0]]}}}"#,
    )
    .unwrap();
    let car = example("verdict/car.toml");
    let run = verdict(&[
        "--car",
        &car,
        "--protocol",
        "part581-barrier-front",
        "--uncertainty",
        json.to_str().unwrap(),
    ]);
    assert_eq!(run.status.code(), Some(2));
    assert_contains(
        &text(&run.stderr),
        &[
            "id.json",
            "these spreads belong to another car",
            "body.mass is 1300.00",
            "but 1249.00",
        ],
    );
    assert!(run.stdout.is_empty());
}

#[test]
fn the_target_has_a_row_at_the_car_s_stiffness() {
    let car = example("verdict/car.toml");
    let run = verdict(&[
        "--car",
        &car,
        "--protocol",
        "rcar-bumper-corner-front",
        "--target",
    ]);
    assert_eq!(run.status.code(), Some(0), "{}", text(&run.stderr));
    assert_contains(
        &text(&run.stdout),
        &[
            "stiffness 3.00 kN/mm (the car's): force from ",
            "the car's bumper (3.00 kN/mm, 120.0 kN): below the least passing force",
        ],
    );
}
