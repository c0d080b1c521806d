//! The protocol library against a table written from the sources, the
//! worked example of examples/verdict/ (one failing criterion named with
//! its margin; the target region contains the passing bumper and excludes
//! the failing one) and hostile limits (issue 36).

use bumpsim_impact::bumper::Bumper;
use bumpsim_verdict::prelude::*;
use bumpsim_verdict::protocol::{Height, INCH, select, test};
use std::path::{Path, PathBuf};

const MPH: f64 = 1.609344;

/// Name, speed km/h, striker mass as a multiple of the car's (None: the
/// car moves into a fixed face), face angle °, overlap, impact height
/// (bottom, top) m (None: a full-height face or not checked). Written from
/// 49 CFR 581.5-581.7 (GPO text), RCAR Bumper Test Issue 2.0 and IIHS
/// Bumper test protocol Version I; UN R42 (1980) annex 3 §2.3.3, 2.3.6,
/// 2.7.5, 2.8.3, 2.8.4.
#[allow(clippy::type_complexity)]
const SOURCES: &[(&str, f64, Option<f64>, f64, f64, Option<(f64, f64)>)] = &[
    (
        "part581-pendulum-front",
        2.5 * MPH,
        Some(1.0),
        0.0,
        1.0,
        Some((16.0 * INCH, 20.0 * INCH)),
    ),
    (
        "part581-pendulum-rear",
        2.5 * MPH,
        Some(1.0),
        0.0,
        1.0,
        Some((16.0 * INCH, 20.0 * INCH)),
    ),
    (
        "part581-corner-front-left",
        1.5 * MPH,
        Some(1.0),
        30.0,
        1.0,
        Some((20.0 * INCH, 20.0 * INCH)),
    ),
    (
        "part581-corner-front-right",
        1.5 * MPH,
        Some(1.0),
        -30.0,
        1.0,
        Some((16.0 * INCH, 20.0 * INCH)),
    ),
    ("part581-barrier-front", 2.5 * MPH, None, 0.0, 1.0, None),
    ("part581-barrier-rear", 2.5 * MPH, None, 0.0, 1.0, None),
    (
        "r42-longitudinal-front",
        4.0,
        Some(1.0),
        0.0,
        1.0,
        Some((0.445, 0.445)),
    ),
    (
        "r42-corner-front-left",
        2.5,
        Some(1.0),
        30.0,
        1.0,
        Some((0.445, 0.445)),
    ),
    (
        "rcar-bumper-front",
        10.0,
        None,
        0.0,
        1.0,
        Some((0.455, 0.555)),
    ),
    (
        "rcar-bumper-rear",
        10.0,
        None,
        0.0,
        1.0,
        Some((0.455, 0.555)),
    ),
    (
        "rcar-bumper-corner-front",
        5.0,
        None,
        10.0,
        0.15,
        Some((0.455, 0.555)),
    ),
    (
        "rcar-bumper-corner-rear",
        5.0,
        None,
        -10.0,
        0.15,
        Some((0.455, 0.555)),
    ),
    (
        "iihs-bumper-front",
        6.0 * MPH,
        None,
        0.0,
        1.0,
        Some((0.455, 0.555)),
    ),
    (
        "iihs-bumper-corner-front",
        3.0 * MPH,
        None,
        10.0,
        0.15,
        Some((0.455, 0.555)),
    ),
    ("iihs-flat-front", 5.0 * MPH, None, 0.0, 1.0, None),
];

#[test]
fn every_preset_matches_the_table_written_from_its_source() {
    for &(name, kmh, mass, degrees, overlap, height) in SOURCES {
        let t = test(name).unwrap_or_else(|| panic!("{name} is missing"));
        assert!(
            (t.speed() * 3.6 - kmh).abs() < 1e-9,
            "{name}: speed {}",
            t.speed() * 3.6
        );
        assert_eq!(t.mass(1234.0), mass.map(|m| m * 1234.0), "{name}: mass");
        assert!(
            (t.angle().to_degrees() - degrees).abs() < 1e-9,
            "{name}: angle"
        );
        assert!((t.overlap() - overlap).abs() < 1e-12, "{name}: overlap");
        let range = match t.height {
            Height::Ridge { low, high } => Some((low, high)),
            Height::Face { bottom, top } => Some((bottom, top)),
            Height::Full | Height::Unknown => None,
        };
        assert_eq!(range, height, "{name}: height");
        assert!(!t.source.is_empty() && !t.uncertain.is_empty(), "{name}");
    }
    // the market sets the RCAR barrier's lower edge, not the end struck
    let europe = bumpsim_verdict::protocol::select_in(
        &[
            "rcar-bumper-front",
            "rcar-bumper-rear",
            "iihs-bumper-corner-front",
        ],
        bumpsim_io::protocols::Market::Europe,
    )
    .unwrap();
    for t in europe {
        assert_eq!(
            t.height,
            Height::Face {
                bottom: 0.405,
                top: 0.505
            },
            "{}",
            t.name
        );
    }
    // CMVSS 215 runs 49 CFR 581's tests
    assert_eq!(
        select(&["cmvss215"]).unwrap(),
        select(&["part581"]).unwrap()
    );
}

/// The guided equivalent of a corner pendulum pushes along the face's
/// normal with the real pendulum's normal speed and energy.
#[test]
fn the_corner_pendulum_keeps_its_normal_speed_and_energy() {
    let t = test("part581-corner-front-left").unwrap();
    let (real, guided) = (t.nominal(1500.0).unwrap(), t.striker(1500.0).unwrap());
    let cos = 30f64.to_radians().cos();
    let energy = |s: &bumpsim_planar::Striker, m: f64| 0.5 * m * s.motion.speed().powi(2);
    assert!((guided.motion.speed() * cos - real.motion.speed()).abs() < 1e-12);
    let (m_real, m_guided) = (1500.0, 1500.0 * cos * cos);
    assert!((energy(&guided, m_guided) - energy(&real, m_real)).abs() < 1e-9);
}

fn example() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/verdict/car.toml")
}

fn setup(plateau: Option<f64>) -> Setup {
    let car = bumpsim_planar::PlanarCar::read(&example()).unwrap();
    let mut end = CarEnd::new(car, Damageability::read(&example()).unwrap()).unwrap();
    if let Some(force) = plateau {
        end = end
            .with_bumper(&Bumper::three_part(3e6, force, 2e7).unwrap())
            .unwrap();
    }
    Setup::new(vec![end], select(&["part581", "rcar-bumper"]).unwrap(), 0.0).unwrap()
}

#[test]
fn the_worked_example_fails_one_criterion_and_its_target_region_says_why() {
    let failing = bumpsim_verdict::verdict(&setup(None)).unwrap();
    let failures = failing.failures();
    assert_eq!(failures.len(), 1, "{failures:?}");
    let (name, criterion) = failures[0];
    assert_eq!(
        (name, criterion.name.as_str()),
        ("rcar-bumper-corner-front", "bumper stroke")
    );
    // 80.7 mm of the 80 mm the bumper can crush: it bottoms and blocks
    // (issue 45; 82.6 mm before the block)
    assert!(
        criterion.value > 0.0805 && criterion.value < 0.0815,
        "{criterion:?}"
    );
    assert!(!failing.passed());
    let passing = bumpsim_verdict::verdict(&setup(Some(200e3))).unwrap();
    assert!(passing.passed(), "{:?}", passing.failures());
    let options = TargetOptions {
        stiffness: Some([2e6, 4.5e6]),
        force: Some([50e3, 800e3]),
        rows: 4,
        levels: 7,
        tolerance: 0.02,
    };
    let region = bumpsim_verdict::target::search(&setup(None), &options).unwrap();
    assert!(region.contains(3e6, 200e3), "{:?}", region.rows);
    assert!(!region.contains(3e6, 120e3), "{:?}", region.rows);
    let lower = region.rows[1].interval.as_ref().unwrap()[0].binding.clone();
    assert!(
        lower
            .unwrap()
            .contains("bumper stroke (rcar-bumper-corner-front)")
    );
}

fn limits(extra: &str) -> Result<Damageability, VerdictError> {
    let text = format!("[damageability]\nrail_yield = 300e3\ncrash_box_stroke = 0.05\n{extra}");
    Damageability::parse(&text, "car.toml".as_ref())
}

#[test]
fn hostile_limits_and_names_get_errors_naming_the_key() {
    let message = |e: VerdictError| e.to_string();
    let none = message(limits("").unwrap_err());
    assert!(none.contains("damageability.clearance"), "{none}");
    let clearance =
        "[[damageability.clearance]]\nname = \"radiator\"\ngap = 0.08\nfrom = \"beam\"\n";
    assert!(limits(clearance).is_ok());
    let twice = message(limits(&format!("{clearance}{clearance}")).unwrap_err());
    assert!(
        twice.contains("clearance[1]") && twice.contains("clearance[2]"),
        "{twice}"
    );
    let gone = Damageability::parse(
        "[damageability]\ncrash_box_stroke = 0.05\n",
        "car.toml".as_ref(),
    );
    assert!(message(gone.unwrap_err()).contains("damageability.rail_yield"));
    let negative = limits(&clearance.replace("gap = 0.08", "gap = -0.08"));
    assert!(message(negative.unwrap_err()).contains("gap"));
    // a third value of a pair is refused, not dropped (issue 34)
    let three = limits("beam_height = [0.40, 0.50, 0.60]\n").unwrap_err();
    assert!(message(three).contains("exactly 2 numbers"));
    let lateral = limits(&format!("{clearance}lateral = [-0.3, 0.3, 0.9]\n")).unwrap_err();
    assert!(message(lateral).contains("exactly 2 numbers"));
    assert!(
        limits(&format!(
            "beam_height = [0.40, 0.50]\n{clearance}lateral = [-0.3, 0.3]\n"
        ))
        .is_ok()
    );
    let unknown = message(select(&["part581", "fmvss-999"]).unwrap_err());
    assert!(
        unknown.contains("fmvss-999") && unknown.contains("part581"),
        "{unknown}"
    );
}

/// A constant deceleration `a` long enough: the occupant's relative speed
/// a·t₁ after 65 mm of free flight (t₁ = √(0.13/a)) is taken out over
/// 235 mm, so OLC = a (1 + 0.13/0.47) exactly (TB027's definition).
#[test]
fn olc_of_a_constant_deceleration_is_the_closed_form() {
    let a = 100.0;
    let time: Vec<f64> = (0..60_000).map(|k| k as f64 * 1e-5).collect();
    let v: Vec<f64> = time.iter().map(|t| 60.0 - a * t).collect();
    let olc = bumpsim_verdict::pulse::olc(&time, &v).unwrap();
    let exact = a * (1.0 + 0.13 / 0.47);
    assert!(
        (olc.value / exact - 1.0).abs() < 1e-3,
        "{} {exact}",
        olc.value
    );
    assert!((olc.t1 - (0.13 / a).sqrt()).abs() < 2e-5, "{}", olc.t1);
}

/// ASI of a half-sine pulse: the largest 50 ms mean of A sin(πt/T) over a
/// window centred on the peak, 2AT/(π·0.05)·sin(π·0.05/(2T)), over 12 g.
#[test]
fn asi_of_a_half_sine_is_the_closed_form() {
    let (peak, duration) = (20.0 * 9.81, 0.1);
    let time: Vec<f64> = (0..=20_000).map(|k| k as f64 * 1e-5).collect();
    let pi = std::f64::consts::PI;
    let ax: Vec<f64> = time
        .iter()
        .map(|&t| {
            if t < duration {
                peak * (pi * t / duration).sin()
            } else {
                0.0
            }
        })
        .collect();
    let zeros = vec![0.0; time.len()];
    let method = bumpsim_verdict::pulse::AsiMethod::En1998;
    let asi = bumpsim_verdict::pulse::asi(&time, [&ax, &zeros, &zeros], method).unwrap();
    let mean = 2.0 * peak * duration / (pi * 0.05) * (pi * 0.05 / (2.0 * duration)).sin();
    let exact = mean / (12.0 * 9.81);
    assert!((asi / exact - 1.0).abs() < 1e-3, "{asi} {exact}");
}

/// The probability of passing against an independent route: the bumper's
/// crush in the 49 CFR 581 barrier test falls as its force scale `m`
/// rises, so with `ln m ~ N(0, σ²)` the criterion "crush ≤ 20 mm" passes
/// with probability `Φ(−ln m*/σ)`, `m*` the scale whose crush is 20 mm
/// (found here by bisection of deterministic verdicts). The Monte Carlo
/// probability of 300 draws lies within 3 of its standard errors.
#[test]
fn the_probability_of_passing_is_the_normal_cdf_at_the_threshold() {
    let text = std::fs::read_to_string(example())
        .unwrap()
        .replace("bumper_stroke = 80.0", "bumper_stroke = 20.0");
    let car = bumpsim_planar::PlanarCar::read(&example()).unwrap();
    let limits = Damageability::parse(&text, &example()).unwrap();
    let end = CarEnd::new(car, limits).unwrap();
    let tests = select(&["part581-barrier-front"]).unwrap();
    let setup = Setup::new(vec![end.clone()], tests.clone(), 0.0).unwrap();
    let crush = |m: f64| {
        let segments = end.car.beam().segments.iter();
        let scaled = segments.map(|s| bumpsim_planar::car::scaled(s, m).unwrap());
        let scaled_end = end.with_segments(scaled.collect()).unwrap();
        let v =
            bumpsim_verdict::verdict(&Setup::new(vec![scaled_end], tests.clone(), 0.0).unwrap());
        let v = v.unwrap();
        let c = v.tests[0]
            .criteria
            .iter()
            .find(|c| c.name == "bumper stroke");
        c.unwrap().value
    };
    let (mut low, mut high) = (-0.5f64, 0.5f64);
    assert!(crush(low.exp()) > 0.02 && crush(high.exp()) < 0.02);
    while high - low > 1e-5 {
        let mid = 0.5 * (low + high);
        match crush(mid.exp()) > 0.02 {
            true => low = mid,
            false => high = mid,
        }
    }
    let sigma = 0.1;
    let normal = statrs::distribution::Normal::standard();
    let exact = statrs::distribution::ContinuousCDF::cdf(&normal, -0.5 * (low + high) / sigma);
    let mut v = bumpsim_verdict::verdict(&setup).unwrap();
    let u = bumpsim_verdict::probability::Uncertainty::independent(
        "spread",
        vec![("bumper.force".into(), sigma)],
    )
    .unwrap();
    let sampling = bumpsim_verdict::probability::Sampling {
        samples: 300,
        seed: 5,
    };
    bumpsim_verdict::probability::propagate(&setup, &mut v, &u, sampling).unwrap();
    let c = v.tests[0]
        .criteria
        .iter()
        .find(|c| c.name == "bumper stroke");
    let p = c.unwrap().probability.unwrap();
    let se = (exact * (1.0 - exact) / 300.0).sqrt();
    assert!(
        exact > 0.2 && exact < 0.8,
        "a threshold inside the spread: {exact}"
    );
    assert!(
        (p.probability - exact).abs() < 3.0 * se,
        "Monte Carlo {p:?} against Φ = {exact}"
    );
    assert_eq!(v.propagation.as_ref().unwrap().failed, 0);
    assert_eq!(v.tests[0].probability.unwrap().count, 300);
}
