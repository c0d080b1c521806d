//! Issue 45 item 2: 49 CFR 581.5(a) as a sequence on one car. With an
//! elastic bumper (no permanent set) each test in the sequence reproduces
//! the test run alone; with the bundled car's plastic bumper the later
//! tests start from the set the earlier ones left, and say so.

use bumpsim_impact::bumper::Bumper;
use bumpsim_verdict::prelude::*;
use bumpsim_verdict::protocol::select;
use std::path::Path;

fn end() -> CarEnd {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/verdict/car.toml");
    let car = bumpsim_planar::PlanarCar::read(&path).unwrap();
    CarEnd::new(car, Damageability::read(&path).unwrap()).unwrap()
}

fn both(end: CarEnd) -> (Verdict, Verdict) {
    let mut setup = Setup::new(vec![end], select(&["part581"]).unwrap(), 0.0).unwrap();
    let alone = verdict(&setup).unwrap();
    setup.sequence = true;
    (alone, verdict(&setup).unwrap())
}

/// Relative tolerance of a reproduced value: the reloading along an
/// unloading line as steep as the loading differs from it by rounding only.
const TOLERANCE: f64 = 1e-9;

#[test]
fn an_elastic_bumper_in_sequence_reproduces_each_test_run_alone() {
    // the same slope loading and unloading, a plateau out of reach: no set
    let elastic = Bumper::three_part(3e6, 1e9, 3e6).unwrap();
    let (alone, sequence) = both(end().with_bumper(&elastic).unwrap());
    let assessed: Vec<_> = sequence
        .tests
        .iter()
        .filter(|t| t.skipped.is_none())
        .collect();
    assert_eq!(assessed.len(), 4, "the front tests of 581");
    assert!(
        assessed[0].inherited.is_none(),
        "the first starts undamaged"
    );
    for (a, s) in alone.tests.iter().zip(&sequence.tests) {
        assert_eq!(a.test.name, s.test.name);
        if s.skipped.is_some() {
            continue;
        }
        for (p, q) in a.criteria.iter().zip(&s.criteria) {
            assert_eq!(p.name, q.name);
            let scale = p.value.abs().max(1e-6);
            assert!(
                (p.value - q.value).abs() <= TOLERANCE * scale,
                "{} {}: {} alone, {} in sequence",
                s.test.name,
                p.name,
                p.value,
                q.value
            );
        }
    }
    for t in &assessed[1..] {
        let inherited = t.inherited.as_ref().expect("a later test inherits");
        assert!(
            inherited.set < 1e-9,
            "{}: set {}",
            t.test.name,
            inherited.set
        );
        assert!(inherited.changes.is_empty(), "{:?}", inherited.changes);
    }
}

#[test]
fn a_plastic_bumper_in_sequence_starts_each_test_from_the_set_left_before() {
    let (alone, sequence) = both(end());
    let barrier = |v: &Verdict| {
        v.tests
            .iter()
            .find(|t| t.test.name == "part581-barrier-front")
            .unwrap()
            .clone()
    };
    let (a, s) = (barrier(&alone), barrier(&sequence));
    assert!(a.inherited.is_none());
    let inherited = s.inherited.as_ref().unwrap();
    assert_eq!(
        inherited.from,
        [
            "part581-pendulum-front",
            "part581-corner-front-left",
            "part581-corner-front-right"
        ]
    );
    // the pendulum alone leaves about 11 mm (13.4 mm crush less its
    // 40 kN / 2e7 N/m spring-back), the corners more at the ends
    assert!(inherited.set > 0.010, "{}", inherited.set);
    // the set moves the beam's face back: the front travels further
    let change = |name: &str| {
        inherited
            .changes
            .iter()
            .find(|c| c.criterion == name)
            .cloned()
    };
    let lamp = change("clearance: left headlamp").expect("the front travel changed");
    assert!(lamp.sequence > lamp.alone + 1e-3, "{lamp:?}");
    let text = bumpsim_verdict::text::sequence(&sequence.tests);
    assert!(
        text.contains("part581-barrier-front in sequence after part581-pendulum-front, part581-corner-front-left, part581-corner-front-right: inherits a permanent set of up to"),
        "{text}"
    );
    assert!(
        text.contains("against the test run alone, the inherited damage changes: "),
        "{text}"
    );
    assert!(
        s.assumptions
            .iter()
            .all(|a| !a.starts_with("run on the undamaged car")),
        "{:?}",
        s.assumptions
    );
}
