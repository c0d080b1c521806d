//! OLC against pyisomme's `calculate_olc` (tests/peers/pyisomme_olc.py) on
//! three simulated pulses of the worked example (examples/verdict/: the
//! RCAR full-width and corner tests, the 49 CFR 581 barrier) and a
//! constant deceleration: equal within 0.1 %; ASI against an independent
//! numpy/scipy implementation (tests/peers/numpy_asi.py) on the same
//! pulses, within 0.1 %. Skip without the Python modules (fail under
//! BUMPSIM_REQUIRE_PEERS).

use bumpsim_peers::python_available;
use bumpsim_verdict::prelude::*;
use bumpsim_verdict::protocol::{select, test};
use bumpsim_verdict::pulse::{ASI_WINDOW, Pulse, asi, olc};
use std::path::Path;
use std::process::Command;

/// The body's velocity pulses of three of the example's tests, continued
/// 0.5 s at the last velocity as the verdict does.
fn pulses() -> Vec<(String, Vec<f64>, Vec<f64>)> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/verdict/car.toml");
    let car = bumpsim_planar::PlanarCar::read(&path).unwrap();
    let end = CarEnd::new(car, Damageability::read(&path).unwrap()).unwrap();
    let setup = Setup::new(vec![end], select(&["part581"]).unwrap(), 0.0).unwrap();
    let front = setup.front.as_ref().unwrap();
    let mut out = Vec::new();
    for name in [
        "rcar-bumper-front",
        "rcar-bumper-corner-front",
        "part581-barrier-front",
    ] {
        let (_, _, r) =
            bumpsim_verdict::verdict::run(front, test(name).unwrap(), &setup.settings).unwrap();
        let p = Pulse::of(&r);
        let p = p.extended(p.time.last().unwrap() + 0.5);
        out.push((name.to_string(), p.time, p.velocity));
    }
    let time: Vec<f64> = (0..6000).map(|k| k as f64 * 1e-4).collect();
    let v = time.iter().map(|t| 60.0 - 100.0 * t).collect();
    out.push(("constant 100 m/s²".into(), time, v));
    out
}

#[test]
fn olc_equals_pyisommes_within_a_tenth_of_a_percent() {
    if !python_available("pyisomme") {
        return;
    }
    let pulses = pulses();
    let mut command = Command::new("python3");
    command.arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/peers/pyisomme_olc.py"));
    let dir = std::env::temp_dir();
    let mut files = Vec::new();
    for (k, (_, time, v)) in pulses.iter().enumerate() {
        let file = dir.join(format!("bumpsim-olc-{}-{k}.txt", std::process::id()));
        let lines: String = time
            .iter()
            .zip(v)
            .map(|(t, v)| format!("{t:.17e} {v:.17e}\n"))
            .collect();
        std::fs::write(&file, lines).unwrap();
        command.arg(&file);
        files.push(file);
    }
    let out = command.output().unwrap();
    files.iter().for_each(|f| drop(std::fs::remove_file(f)));
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let theirs: Vec<f64> = String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(|l| l.trim().parse().unwrap())
        .collect();
    assert_eq!(theirs.len(), pulses.len());
    for ((name, time, v), reference) in pulses.iter().zip(theirs) {
        let ours = olc(time, v).unwrap().value;
        assert!(
            (ours / reference - 1.0).abs() < 1e-3,
            "{name}: OLC {ours} m/s² here, {reference} m/s² by pyisomme"
        );
    }
}

/// The three pulses' deceleration and lateral acceleration, continued by
/// the ASI window as the verdict does.
fn accelerations() -> Vec<(String, Pulse)> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/verdict/car.toml");
    let car = bumpsim_planar::PlanarCar::read(&path).unwrap();
    let end = CarEnd::new(car, Damageability::read(&path).unwrap()).unwrap();
    let settings = bumpsim_planar::Settings::default();
    [
        "rcar-bumper-front",
        "rcar-bumper-corner-front",
        "part581-barrier-front",
    ]
    .iter()
    .map(|name| {
        let (_, _, r) =
            bumpsim_verdict::verdict::run(&end, test(name).unwrap(), &settings).unwrap();
        let p = Pulse::of(&r);
        (
            name.to_string(),
            p.extended(p.time.last().unwrap() + ASI_WINDOW),
        )
    })
    .collect()
}

#[test]
fn asi_equals_an_independent_implementation_within_a_tenth_of_a_percent() {
    if !python_available("scipy") {
        return;
    }
    let pulses = accelerations();
    let mut command = Command::new("python3");
    command.arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/peers/numpy_asi.py"));
    let mut files = Vec::new();
    for (k, (_, p)) in pulses.iter().enumerate() {
        let file = std::env::temp_dir().join(format!("bumpsim-asi-{}-{k}.txt", std::process::id()));
        let lines: String = (0..p.time.len())
            .map(|i| {
                format!(
                    "{:.17e} {:.17e} {:.17e}\n",
                    p.time[i], p.deceleration[i], p.lateral[i]
                )
            })
            .collect();
        std::fs::write(&file, lines).unwrap();
        command.arg(&file);
        files.push(file);
    }
    let out = command.output().unwrap();
    files.iter().for_each(|f| drop(std::fs::remove_file(f)));
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let theirs: Vec<f64> = String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(|l| l.trim().parse().unwrap())
        .collect();
    assert_eq!(theirs.len(), pulses.len());
    for ((name, p), reference) in pulses.iter().zip(theirs) {
        let zeros = vec![0.0; p.time.len()];
        let ours = asi(&p.time, [&p.deceleration, &p.lateral, &zeros]).unwrap();
        assert!(
            (ours / reference - 1.0).abs() < 1e-3,
            "{name}: ASI {ours} here, {reference} by numpy"
        );
    }
}
