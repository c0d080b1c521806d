//! OLC against pyisomme's `calculate_olc` (tests/peers/pyisomme_olc.py)
//! and the EN 1317-1:1998 ASI against an independent numpy/scipy
//! implementation (tests/peers/numpy_asi.py), each within 0.1 %, and the
//! EN 1317-1:2010 ASI against scipy's `butter` + `filtfilt`
//! (tests/peers/scipy_asi_2010.py) within 1e-6, on
//!
//! - three simulated pulses of the worked example (examples/verdict/: the
//!   RCAR full-width and corner tests, the 49 CFR 581 barrier) and a
//!   constant deceleration (OLC);
//! - measured pulses: the struck car of each of the bundled pendulum
//!   series (examples/identify/: FLAT, P600, POLE; mean of the side-member
//!   accelerometers) and NHTSA test 10146's rear-seat crossmember (channels
//!   93 and 94; a 57 km/h barrier test, read from ../shared/data, skipped
//!   with a message when absent). Each is bias-removed and CFC 60 filtered
//!   by bumpsim-signal; bumpsim integrates its velocity, pyisomme
//!   integrates the same acceleration itself (`Channel.integrate`), and
//!   the record is continued at its last velocity as the verdict does.
//!
//! Skip without the Python modules (fail under BUMPSIM_REQUIRE_PEERS).

use bumpsim_peers::python_available;
use bumpsim_signal::Pipeline;
use bumpsim_verdict::prelude::*;
use bumpsim_verdict::protocol::{select, test};
use bumpsim_verdict::pulse::{ASI_WINDOW, AsiMethod, Pulse, asi, olc};
use std::path::{Path, PathBuf};
use std::process::Command;

/// The worked example's three pulses (name, pulse as simulated).
fn simulated() -> Vec<(String, Pulse)> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/verdict/car.toml");
    let car = bumpsim_planar::PlanarCar::read(&path).unwrap();
    let end = CarEnd::new(car, Damageability::read(&path).unwrap()).unwrap();
    let setup = Setup::new(vec![end], select(&["part581"]).unwrap(), 0.0).unwrap();
    let front = setup.front.as_ref().unwrap();
    [
        "rcar-bumper-front",
        "rcar-bumper-corner-front",
        "part581-barrier-front",
    ]
    .iter()
    .map(|name| {
        let (_, _, r) =
            bumpsim_verdict::verdict::run(front, test(name).unwrap(), &setup.settings).unwrap();
        (name.to_string(), Pulse::of(&r))
    })
    .collect()
}

/// A measured pulse: the filtered vehicle acceleration along x (m/s²) and
/// the velocity bumpsim integrates from it (m/s), and the speed at t = 0.
struct Measured {
    name: String,
    speed: f64,
    acceleration: Vec<f64>,
    pulse: Pulse,
}

fn repository() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Runs a two-signal pipeline (acceleration: mean of `channels`, bias
/// removed, CFC 60; velocity: its integral, `speed` at t = 0) on `test`;
/// `sign` −1 turns accelerometers that read positive along the striker's
/// travel into the verdict's frame (x towards the struck end).
fn measured(name: &str, test: &Path, channels: [&str; 2], speed: f64, sign: f64) -> Measured {
    let text = format!(
        "[[signal]]\nname = \"acceleration\"\npath = {:?}\nchannels = {:?}\ncombine = \"mean\"\n\
         steps = [{{ pretrigger_bias = true }}, {{ cfc = 60 }}]\n\n\
         [[signal]]\nname = \"velocity\"\nfrom = \"acceleration\"\nsteps = [{{ integrate = {speed:?} }}]\n",
        test.display().to_string(),
        channels,
    );
    // one file per call: tests that read the same test in parallel wrote,
    // read and removed one shared file (a test read it empty)
    static CALLS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let call = CALLS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let file = std::env::temp_dir().join(format!(
        "bumpsim-verdict-pipeline-{}-{call}-{name}.toml",
        std::process::id()
    ));
    std::fs::write(&file, text).unwrap();
    let result = Pipeline::read(&file).and_then(|p| p.run());
    drop(std::fs::remove_file(&file));
    let signals = result.unwrap().signals;
    let (a, v) = (&signals[0].series, &signals[1].series);
    let acceleration: Vec<f64> = a.values().iter().map(|x| sign * x).collect();
    let velocity: Vec<f64> = v.values().iter().map(|x| sign * x).collect();
    let time = v.times();
    let pulse = Pulse {
        contact_end: time[time.len() - 1],
        time,
        deceleration: acceleration.iter().map(|x| -x).collect(),
        lateral: vec![0.0; velocity.len()],
        delta_v: (velocity[velocity.len() - 1] - velocity[0]).abs(),
        velocity,
    };
    Measured {
        name: name.into(),
        speed: sign * speed,
        acceleration,
        pulse,
    }
}

/// The bundled pendulum series' struck car (its accelerometers read
/// positive along the pendulum's travel) and, when ../shared holds it,
/// NHTSA test 10146 (57.09 km/h into a rigid barrier, x forward).
fn measured_pulses() -> Vec<Measured> {
    let sides = ["10SIMELE0000ACXP", "10SIMERI0000ACXP"];
    let mut out: Vec<Measured> = ["FLAT", "P600", "POLE"]
        .iter()
        .map(|head| {
            let test = repository().join(format!("examples/identify/{head}/{head}.mme"));
            measured(&format!("bundled {head}"), &test, sides, 0.0, -1.0)
        })
        .collect();
    let nhtsa = repository().join("../shared/data/nhtsa-10146/v10146.EV5");
    match nhtsa.exists() {
        true => out.push(measured(
            "NHTSA 10146",
            &nhtsa,
            ["93", "94"],
            57.09 / 3.6,
            1.0,
        )),
        false => eprintln!(
            "SKIPPED (NHTSA 10146 pulse only): {} is absent (the NHTSA test 10146 is read from ../shared, not copied; see examples/nhtsa-10146/README.md)",
            nhtsa.display()
        ),
    }
    out
}

/// Runs `script` of tests/peers/ with `args`, each file written from its
/// lines (removed afterwards); one number per line of its output.
fn peer(script: &str, args: Vec<(Option<String>, String)>) -> Vec<f64> {
    let mut command = Command::new("python3");
    command.arg(
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/peers")
            .join(script),
    );
    let mut files = Vec::new();
    for (k, (flag, lines)) in args.into_iter().enumerate() {
        let file = std::env::temp_dir().join(format!(
            "bumpsim-verdict-{script}-{}-{k}.txt",
            std::process::id()
        ));
        std::fs::write(&file, lines).unwrap();
        command.args(flag).arg(&file);
        files.push(file);
    }
    let out = command.output().unwrap();
    files.iter().for_each(|f| drop(std::fs::remove_file(f)));
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(|l| l.trim().parse().unwrap())
        .collect()
}

fn columns(time: &[f64], values: &[&[f64]]) -> String {
    (0..time.len())
        .map(|i| {
            let row: Vec<String> = std::iter::once(time[i])
                .chain(values.iter().map(|v| v[i]))
                .map(|x| format!("{x:.17e}"))
                .collect();
            row.join(" ") + "\n"
        })
        .collect()
}

fn assert_within_a_tenth_of_a_percent(what: &str, ours: &[(String, f64)], theirs: &[f64]) {
    assert_eq!(theirs.len(), ours.len());
    for ((name, ours), reference) in ours.iter().zip(theirs) {
        assert!(
            (ours / reference - 1.0).abs() < 1e-3,
            "{name}: {what} {ours} here, {reference} by the peer"
        );
        let off = ours / reference - 1.0;
        eprintln!("{name}: {what} {ours:.6} here, {reference:.6} by the peer ({off:.1e})");
    }
}

/// The seconds pyisomme's velocity is continued by at its last value (the
/// verdict tries 0.5, 2 and 8 s: the first that reaches the restraint).
const CONTINUED: f64 = 2.0;

#[test]
fn olc_equals_pyisommes_within_a_tenth_of_a_percent() {
    if !python_available("pyisomme") {
        return;
    }
    let (mut args, mut ours) = (Vec::new(), Vec::new());
    for (name, p) in simulated() {
        let p = p.extended(p.time.last().unwrap() + 0.5);
        args.push((None, columns(&p.time, &[&p.velocity])));
        ours.push((name, olc(&p.time, &p.velocity).unwrap().value));
    }
    let time: Vec<f64> = (0..6000).map(|k| k as f64 * 1e-4).collect();
    let v: Vec<f64> = time.iter().map(|t| 60.0 - 100.0 * t).collect();
    args.push((None, columns(&time, &[&v])));
    ours.push(("constant 100 m/s²".into(), olc(&time, &v).unwrap().value));
    for m in measured_pulses() {
        // the verdict's metric: the record continued at its last velocity
        let (metrics, notes) = m.pulse.metrics(true, AsiMethod::En1998);
        let value = metrics
            .olc
            .unwrap_or_else(|| panic!("{}: {notes:?}", m.name));
        let flag = Some(format!("--acceleration={:?},{CONTINUED:?}", m.speed));
        args.push((flag, columns(&m.pulse.time, &[&m.acceleration])));
        ours.push((m.name, value));
    }
    let theirs = peer("pyisomme_olc.py", args);
    assert_within_a_tenth_of_a_percent("OLC (m/s²)", &ours, &theirs);
}

/// The simulated pulses and the measured ones, by name.
fn every_pulse() -> Vec<(String, Pulse)> {
    let mut pulses = simulated();
    pulses.extend(measured_pulses().into_iter().map(|m| (m.name, m.pulse)));
    pulses
}

#[test]
fn asi_equals_an_independent_implementation_within_a_tenth_of_a_percent() {
    if !python_available("scipy") {
        return;
    }
    let (mut args, mut ours) = (Vec::new(), Vec::new());
    for (name, p) in every_pulse() {
        // the verdict's record: continued by the ASI window
        let p = p.extended(p.time.last().unwrap() + ASI_WINDOW);
        let zeros = vec![0.0; p.time.len()];
        let a = [&p.deceleration[..], &p.lateral, &zeros];
        let value = asi(&p.time, a, AsiMethod::En1998).unwrap();
        args.push((None, columns(&p.time, &[&p.deceleration, &p.lateral])));
        ours.push((name, value));
    }
    let theirs = peer("numpy_asi.py", args);
    assert_within_a_tenth_of_a_percent("ASI", &ours, &theirs);
}

/// The EN 1317-1:2010 ASI of the simulated pulses (as the verdict runs
/// them: to the contact end) and the measured ones equals scipy's
/// 2-pole 13 Hz Butterworth run forward and backward within 1e-6.
#[test]
fn asi_2010_equals_scipys_filtfilt_within_1e_6() {
    if !python_available("scipy") {
        return;
    }
    let (mut args, mut ours) = (Vec::new(), Vec::new());
    for (name, p) in every_pulse() {
        let zeros = vec![0.0; p.time.len()];
        let a = [&p.deceleration[..], &p.lateral, &zeros];
        let value = asi(&p.time, a, AsiMethod::En2010).unwrap();
        args.push((None, columns(&p.time, &[&p.deceleration, &p.lateral])));
        ours.push((name, value));
    }
    assert!(ours.len() >= 2);
    let theirs = peer("scipy_asi_2010.py", args);
    for ((name, ours), reference) in ours.iter().zip(&theirs) {
        let off = ours / reference - 1.0;
        eprintln!("{name}: ASI 2010 {ours:.9} here, {reference:.9} by scipy ({off:.1e})");
        assert!(
            off.abs() < 1e-6,
            "{name}: {ours} here, {reference} by scipy"
        );
    }
}
