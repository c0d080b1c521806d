//! The ISO/TS 18571 rating against pyisomme's (`Correlation_ISO18571`, which
//! calls objective_rating_metrics): overall and sub-ratings within 1e-6 on
//! crash-like signal pairs at 10 kHz, at 1 kHz and 50 kHz (interpolated to
//! 10 kHz by both), a noisy one, and the NHTSA test 10146's left and right
//! crossmember pulses (skipped with a message when `../shared` is absent).

use bumpsim_io::test_data::TestData;
use bumpsim_signal::filter::{Cfc, CfcStandard};
use bumpsim_signal::rating::{Rating, rate};
use std::f64::consts::PI;
use std::path::{Path, PathBuf};
use std::process::Command;

const TOLERANCE: f64 = 1e-6;

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// A half-sine crash pulse of `peak` and `duration` s starting at `delay` s.
fn half_sine(t: f64, delay: f64, duration: f64, peak: f64) -> f64 {
    let s = t - delay;
    if (0.0..duration).contains(&s) {
        peak * (PI * s / duration).sin()
    } else {
        0.0
    }
}

fn sampled(n: usize, step: f64, f: impl Fn(f64) -> f64) -> Vec<f64> {
    (0..n).map(|k| f(k as f64 * step)).collect()
}

/// A repeatable pseudo-random sequence in [−1, 1] (a linear congruential generator).
fn noise(n: usize) -> Vec<f64> {
    let mut state: u64 = 2024;
    (0..n)
        .map(|_| {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        })
        .collect()
}

/// A pair of signals to rate, and its step, s.
struct Pair {
    name: &'static str,
    reference: Vec<f64>,
    candidate: Vec<f64>,
    step: f64,
}

/// pyisomme's ratings of every pair, in one process (its warping compiles once).
fn pyisomme(pairs: &[Pair]) -> Vec<Rating> {
    let mut command = Command::new("python3");
    command.arg(repo().join("tests/peers/pyisomme_rating.py"));
    let mut inputs = Vec::new();
    for pair in pairs {
        let input = std::env::temp_dir().join(format!(
            "bumpsim-rating-{}-{}.txt",
            std::process::id(),
            pair.name
        ));
        let lines: String = (pair.reference.iter().zip(&pair.candidate))
            .map(|(r, c)| format!("{r:.17e} {c:.17e}\n"))
            .collect();
        std::fs::write(&input, lines).unwrap();
        command.arg(format!("{:e}", pair.step)).arg(&input);
        inputs.push(input);
    }
    let out = command.output().unwrap();
    inputs.iter().for_each(|i| drop(std::fs::remove_file(i)));
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(parse)
        .collect()
}

fn parse(line: &str) -> Rating {
    let v: Vec<f64> = line
        .split_whitespace()
        .map(|w| w.parse().unwrap())
        .collect();
    Rating {
        overall: v[0],
        corridor: v[1],
        phase: v[2],
        magnitude: v[3],
        slope: v[4],
    }
}

/// Rates every pair with bumpsim and pyisomme and compares all five ratings.
fn assert_as_pyisomme(pairs: &[Pair]) -> Vec<Rating> {
    let theirs = pyisomme(pairs);
    assert_eq!(theirs.len(), pairs.len());
    let mut ratings = Vec::new();
    for (pair, theirs) in pairs.iter().zip(theirs) {
        let ours = rate(&pair.reference, &pair.candidate, pair.step).unwrap();
        let both = [
            ("overall", ours.overall, theirs.overall),
            ("corridor", ours.corridor, theirs.corridor),
            ("phase", ours.phase, theirs.phase),
            ("magnitude", ours.magnitude, theirs.magnitude),
            ("slope", ours.slope, theirs.slope),
        ];
        for (what, a, b) in both {
            assert!(
                (a - b).abs() < TOLERANCE,
                "{}: {what} {a} vs pyisomme {b}",
                pair.name
            );
        }
        eprintln!("{}: bumpsim {ours}, pyisomme {theirs}", pair.name);
        ratings.push(ours);
    }
    ratings
}

fn peer() -> bool {
    bumpsim_peers::python_available("pyisomme, objective_rating_metrics, dtwalign")
}

/// Five synthetic pairs: a late low model of a half-sine pulse, an early
/// triangle (the candidate leads), a stiffer model of a noisy damped
/// oscillation, and a pulse pair at 1 kHz and at 50 kHz.
fn synthetic_pairs() -> Vec<Pair> {
    let step = 1e-4;
    let test = sampled(1500, step, |t| half_sine(t, 0.01, 0.08, -300.0));
    let late = sampled(1500, step, |t| half_sine(t, 0.013, 0.08, -255.0));
    let triangle = sampled(1500, step, |t| {
        let s = (t - 0.008) / 0.04;
        -300.0 * (1.0 - (s - 1.0).abs()).max(0.0)
    });
    let jitter = noise(2000);
    let ringing = sampled(2000, step, |t| {
        (-25.0 * t).exp() * (2.0 * PI * 40.0 * t).sin()
    });
    let noisy: Vec<f64> = ringing
        .iter()
        .zip(&jitter)
        .map(|(r, n)| r + 0.05 * n)
        .collect();
    let stiffer = sampled(2000, step, |t| {
        0.9 * (-30.0 * t).exp() * (2.0 * PI * 44.0 * t).sin()
    });
    let mut pairs = vec![
        Pair {
            name: "late-low",
            reference: test.clone(),
            candidate: late,
            step,
        },
        Pair {
            name: "early-triangle",
            reference: test,
            candidate: triangle,
            step,
        },
        Pair {
            name: "noisy-ringing",
            reference: noisy,
            candidate: stiffer,
            step,
        },
    ];
    for (step, name) in [(1e-3, "1kHz"), (2e-5, "50kHz")] {
        let n = (0.12 / step) as usize;
        let reference = sampled(n, step, |t| half_sine(t, 0.01, 0.08, 200.0));
        let candidate = sampled(n, step, |t| half_sine(t, 0.012, 0.07, 230.0));
        pairs.push(Pair {
            name,
            reference,
            candidate,
            step,
        });
    }
    pairs
}

/// The NHTSA test 10146's left crossmember pulse (channel 93, CFC 60)
/// against the right one (94) at CFC 60 and raw; none when `../shared` is absent.
fn nhtsa_pairs() -> Vec<Pair> {
    let path = repo().join("../shared/data/nhtsa-10146/v10146.EV5");
    if !path.exists() {
        eprintln!(
            "SKIPPED (NHTSA pairs only): {} is absent (the NHTSA test 10146 is read from ../shared, not copied)",
            path.display()
        );
        return Vec::new();
    }
    let test = TestData::open(&path).unwrap();
    let raw = |channel: &str| {
        test.load(test.select(channel).unwrap().indices[0])
            .unwrap()
            .series
    };
    let cfc = Cfc::new(60.0, CfcStandard::SaeJ211).unwrap();
    let (left, right) = (raw("93"), raw("94"));
    let step = left.step();
    assert_eq!(left.len(), 3500);
    let filtered = |s: &[f64]| cfc.filter(s, step).unwrap();
    let reference = filtered(left.values());
    vec![
        Pair {
            name: "nhtsa-10146",
            reference: reference.clone(),
            candidate: filtered(right.values()),
            step,
        },
        Pair {
            name: "nhtsa-10146-raw",
            reference,
            candidate: right.values().to_vec(),
            step,
        },
    ]
}

#[test]
fn ratings_equal_pyisomme_on_seven_pairs_with_the_nhtsa_pulse() {
    if !peer() {
        return;
    }
    let mut pairs = synthetic_pairs();
    pairs.extend(nhtsa_pairs());
    let ratings = assert_as_pyisomme(&pairs);
    let late = ratings[0];
    assert!(
        late.phase < 1.0 && late.magnitude < 1.0 && late.slope < 1.0,
        "{late}"
    );
    if let Some(sides) = ratings.get(5) {
        assert!(sides.overall > 0.8, "two sides of one crossmember: {sides}");
    }
}
