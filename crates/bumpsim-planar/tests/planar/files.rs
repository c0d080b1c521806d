//! Issue 34, a property test per writer and reader: the planar study file
//! `bumpsim synth` writes for a planar series (`series::study_text`) reads
//! back (`PlanarStudy::read`) with the values it holds, bit for bit — every
//! case, which are validated, the test sheet's mass, the speeds, each
//! force's lateral position, direction and anchor (moved to the case's time
//! zero), and each sensor's place — over drawn set-ups of the bundled
//! series' tests (recorded once, written as ISO-MME as synth writes them).

use bumpsim_planar::drive::Sensor;
use bumpsim_planar::presets::StrikerFields;
use bumpsim_planar::series::{Series, TestSetup, make_series, study_text};
use bumpsim_planar::study::PlanarStudy;
use proptest::prelude::*;
use std::path::{Path, PathBuf};

/// The bundled series, made once, its tests and start car written to a
/// scratch folder as synth writes them, and each test's striker fields.
fn series() -> &'static (Series, PathBuf, Vec<StrikerFields>) {
    static MADE: std::sync::OnceLock<(Series, PathBuf, Vec<StrikerFields>)> =
        std::sync::OnceLock::new();
    MADE.get_or_init(|| {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
        let series = make_series(&root.join("examples/planar/identify/series.toml")).unwrap();
        // under target/tmp: emptied at the start of every run
        let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("planar-files");
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        for test in &series.tests {
            let folder = dir.join(&test.name);
            bumpsim_io::isomme::write(&folder, &test.name, &test.test_header(), &test.channels)
                .unwrap();
        }
        std::fs::write(dir.join("start.toml"), &series.start).unwrap();
        let study: toml::Table = toml::from_str(&series.study).unwrap();
        let strikers = study["case"]
            .as_array()
            .unwrap()
            .iter()
            .map(|case| case["striker"].clone().try_into().unwrap())
            .collect();
        (series, dir, strikers)
    })
}

/// A number as the study writer writes it (12 significant digits, no -0).
fn written(v: f64) -> f64 {
    format!("{v:.11e}").parse::<f64>().unwrap() + 0.0
}

/// Drawn values for one test: validated, speed, per load (lateral, angle
/// of the direction, anchor), per body sensor its place.
type Drawn = (bool, f64, Vec<(f64, f64, Option<[f64; 2]>)>, Vec<[f64; 2]>);

fn drawn_test() -> impl Strategy<Value = Drawn> {
    let load = (
        // on the 1.6 m start car's bumper line (a study refuses a load off it)
        -0.8..0.8f64,
        -3.1..3.1f64,
        proptest::option::of((-2.0..2.0f64, -2.0..2.0f64).prop_map(|(x, y)| [x, y])),
    );
    (
        any::<bool>(),
        0.5..20.0f64,
        prop::collection::vec(load, 4),
        prop::collection::vec((-2.0..2.0f64, -1.0..1.0f64).prop_map(|(x, y)| [x, y]), 2),
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    #[test]
    fn a_planar_study_bumpsim_writes_reads_back_equal(drawn in prop::collection::vec(drawn_test(), 5)) {
        let (series, dir, strikers) = series();
        let mut tests = series.tests.clone();
        let mut setups = Vec::new();
        for (k, (test, (validate, speed, loads, sensors))) in tests.iter_mut().zip(&drawn).enumerate() {
            test.car_speed = *speed;
            for (load, (lateral, angle, anchor)) in test.loads.iter_mut().zip(loads) {
                load.lateral = *lateral;
                load.direction = [angle.cos(), angle.sin()];
                load.anchor = *anchor;
            }
            let mut body = sensors.iter();
            for sensor in &mut test.sensors {
                if let (Sensor::Body(place), Some(new)) = (sensor, body.next()) {
                    *place = *new;
                }
            }
            // the first test is fitted: a study needs one
            setups.push(TestSetup { validate: *validate && k > 0, striker: strikers[k].clone() });
        }
        let text = study_text(&tests, &setups, Path::new("start.toml"), true);
        let path = dir.join(format!("study-{}.toml", std::thread::current().name().unwrap_or("t").replace("::", "-")));
        std::fs::write(&path, &text).unwrap();
        let study = PlanarStudy::read(&path).unwrap();
        prop_assert_eq!(study.setup.mass, Some(written(tests[0].car_mass)));
        prop_assert!(study.setup.friction);
        for (test, setup) in tests.iter().zip(&setups) {
            let fitted = study.cases.iter().find(|c| c.name == test.name);
            let validated = study.validation.iter().find(|c| c.name == test.name);
            prop_assert_eq!(validated.is_some(), setup.validate, "{}", test.name);
            let case = fitted.or(validated).unwrap();
            prop_assert_eq!(case.drive.speed, written(test.car_speed));
            prop_assert_eq!(case.drive.loads.len(), test.loads.len());
            // an anchor is given at the files' t = 0 and read at the case's
            // time zero: moved along x by the car's travel, one for the case
            let mut travel = None;
            for (read, load) in case.drive.loads.iter().zip(&test.loads) {
                prop_assert_eq!(read.lateral, written(load.lateral));
                prop_assert_eq!(read.anchor.is_some(), load.anchor.is_some());
                if let (Some([x, y]), Some(given)) = (read.anchor, load.anchor) {
                    let [gx, gy] = given.map(written);
                    prop_assert_eq!(y, gy);
                    let moved = *travel.get_or_insert(x - gx);
                    prop_assert!((x - gx - moved).abs() <= 1e-12, "{x} - {gx} vs {moved}");
                }
                prop_assert_eq!(read.direction, load.direction.map(written));
            }
            let places: Vec<Sensor> = test.sensors.iter().map(|s| match s {
                Sensor::Body(p) => Sensor::Body(p.map(written)),
                other => *other,
            }).collect();
            prop_assert_eq!(&case.drive.sensors, &places);
        }
    }
}

/// A speed (m/s, either sign, or 0) or mass (kg) over many decades.
fn magnitude() -> impl Strategy<Value = f64> {
    (1.0..10.0f64, -6..7i32).prop_map(|(m, e)| m * 10f64.powi(e))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// The test header of a planar series' test (the car as test object 1
    /// with its speed and mass, a pendulum as test object 2) reads back
    /// from the ISO-MME test synth writes: every line as written, and the
    /// impact's speed and mass (the moving object's) bit for bit.
    #[test]
    fn a_planar_test_header_reads_back_equal(
        car_speed in prop_oneof![Just(0.0), magnitude(), magnitude().prop_map(|v| -v)],
        car_mass in magnitude(),
        pendulum in proptest::option::of((magnitude(), magnitude())),
    ) {
        let (series, dir, _) = series();
        let mut test = series.tests[0].clone();
        test.car_speed = car_speed;
        test.car_mass = car_mass;
        test.striker = match pendulum {
            Some((speed, mass)) => (speed, Some(mass)),
            None => (0.0, None),
        };
        let header = test.test_header();
        // a fresh folder per case: a test read is an input of the process
        static CASE: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
        let case = CASE.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let folder = dir.join(format!("HEADER-{case}"));
        let mme = bumpsim_io::isomme::write(&folder, "HEADER", &header, &test.channels[..1]).unwrap();
        let read = bumpsim_io::test_data::TestData::open(&mme).unwrap();
        for line in &header {
            prop_assert!(read.metadata.contains(line), "{line:?} not in {:?}", read.metadata);
        }
        let (speed, mass) = match (car_speed, pendulum) {
            (0.0, Some((speed, mass))) => (speed, mass),
            _ => (car_speed, car_mass),
        };
        prop_assert_eq!(read.speed, Some(speed));
        prop_assert_eq!(read.mass, Some(mass));
    }
}
