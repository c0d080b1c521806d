//! Issue 44, item 1: a planar study takes the sensors a test carries. A
//! series of the bundled truth car made with a yaw-rate sensor
//! (`[chain] yaw_rate`) is read back with it, weighted by its pre-trigger
//! noise, and the truth car's replay follows it; hostile sensors (an
//! unknown direction, a missing channel, NaN samples, no noise to weigh by)
//! are refused naming the sensor; wall cells need no `lateral`.

use bumpsim_planar::drive::Sensor;
use bumpsim_planar::identify::predict;
use bumpsim_planar::series::make_series;
use bumpsim_planar::study::PlanarStudy;
use std::path::{Path, PathBuf};

/// The ANGLED and OFFSET-RIGHT tests of the bundled car with a yaw-rate
/// sensor of 0.1 deg/s, written as synth writes them.
fn series() -> &'static PathBuf {
    static MADE: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();
    MADE.get_or_init(|| {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/planar/identify");
        let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("planar-sensors");
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        for car in ["car-truth.toml", "start.toml"] {
            std::fs::copy(root.join(car), dir.join(car)).unwrap();
        }
        let text = "planar_car = \"car-truth.toml\"\nstart = \"start.toml\"\nseed = 7\n\
            [chain]\nyaw_rate = \"0.1 deg/s\"\n\
            [[test]]\nname = \"ANGLED\"\nangle = 10.0\nspeed = \"8 km/h\"\n\
            [[test]]\nname = \"OFFSET-RIGHT\"\noverlap = 40.0\nside = \"right\"\nspeed = \"15 km/h\"\nvalidate = true\n";
        std::fs::write(dir.join("series.toml"), text).unwrap();
        let series = make_series(&dir.join("series.toml")).unwrap();
        for test in &series.tests {
            let folder = dir.join(&test.name);
            bumpsim_io::isomme::write(&folder, &test.name, &test.test_header(), &test.channels)
                .unwrap();
        }
        std::fs::write(dir.join("study.toml"), &series.study).unwrap();
        dir
    })
}

/// The series' study with `from` replaced by `to`, read.
fn edited(from: &str, to: &str) -> Result<PlanarStudy, String> {
    let dir = series();
    let text = std::fs::read_to_string(dir.join("study.toml")).unwrap();
    assert!(text.contains(from), "{from} in {text}");
    let path = dir.join(format!("edited-{}.toml", to.len() + 7 * from.len()));
    std::fs::write(&path, text.replacen(from, to, 1)).unwrap();
    PlanarStudy::read(&path).map_err(|e| e.to_string())
}

#[test]
fn a_synthetic_yaw_rate_channel_is_read_weighted_and_followed_by_the_truth() {
    let dir = series();
    let study = PlanarStudy::read(&dir.join("study.toml")).unwrap();
    // forces at given lateral positions, no wall cells: the data do not
    // see the bumper's effective width, so the study keeps the start's
    assert!(!study.setup.width, "no cells, no effective width");
    let truth = bumpsim_planar::car::PlanarCar::read(&dir.join("car-truth.toml")).unwrap();
    for case in study.cases.iter().chain(&study.validation) {
        let k = case.yaw_rate().expect("the yaw-rate sensor");
        assert_eq!(case.drive.sensors[k], Sensor::YawRate);
        // the sills weigh 1; the yaw rate by the sills' displacement noise
        // over its own: 0.05 g against 0.1 deg/s
        assert!(
            case.weights[..k].iter().all(|w| *w == 1.0),
            "{:?}",
            case.weights
        );
        assert!(
            case.weights[k] > 1e-4 && case.weights[k] < 1.0,
            "{:?}",
            case.weights
        );
        let fit = predict(&truth, case).unwrap().fit;
        eprintln!(
            "{}: truth's yaw {:.2} % against the yaw-rate channel",
            case.name, fit.fit_yaw
        );
        assert!(fit.fit_yaw > 97.0 && fit.fit_x > 99.0, "{fit:?}");
        // the fit says its yaw is the sensor's, and the summary marks it
        assert!(fit.yaw_rate_sensor, "{fit:?}");
        let json = serde_json::to_string(&fit).unwrap();
        assert!(json.contains("\"yaw_rate_sensor\":true"), "{json}");
    }
}

#[test]
fn hostile_sensors_are_refused_naming_the_sensor() {
    let yaw = "channel = \"10VEHC0000CGAVZP\"";
    let e = edited(yaw, "channel = \"10VEHC0000CGAVZP\", axis = \"w\"").unwrap_err();
    assert!(
        e.contains("10VEHC0000CGAVZP") && e.contains("axis = \"w\""),
        "{e}"
    );
    let e = edited(yaw, "channel = \"10VEHC0000CGAVZP\", axis = \"x\"").unwrap_err();
    assert!(e.contains("ISO code's direction is Z"), "{e}");
    let e = edited(yaw, "channel = \"10VEHC0000CGAVZP\", chain = 0").unwrap_err();
    assert!(
        e.contains("10VEHC0000CGAVZP") && e.contains("no chain"),
        "{e}"
    );
    let e = edited(yaw, "channel = \"10VEHC0000CGAVXP\"").unwrap_err();
    assert!(e.contains("10VEHC0000CGAVXP"), "a missing channel: {e}");
    for bad in ["\"-0.1 deg/s\"", "\"nan deg/s\"", "\"1 m\""] {
        let e = edited(yaw, &format!("{yaw}, noise = {bad}")).unwrap_err();
        assert!(e.contains("noise"), "{bad}: {e}");
    }
    let given = edited(yaw, &format!("{yaw}, noise = \"0.2 deg/s\"")).unwrap();
    let k = given.cases[0].yaw_rate().unwrap();
    let estimated = PlanarStudy::read(&series().join("study.toml")).unwrap();
    let ratio = estimated.cases[0].weights[k] / given.cases[0].weights[k];
    assert!(
        (ratio - 2.0).abs() < 0.3,
        "twice the noise, half the weight: {ratio}"
    );
}

#[test]
fn a_yaw_rate_channel_with_nan_or_without_a_pre_trigger_is_refused() {
    // a CSV test of one force, two sills and a yaw rate
    let dir = series().join("csv");
    std::fs::create_dir_all(&dir).unwrap();
    let write = |name: &str, start: i64, nan: bool| {
        let mut text = String::from("time [s],force [N],left [m/s^2],right [m/s^2],yaw [rad/s]\n");
        for k in start..600 {
            let t = k as f64 * 1e-4;
            let f = if (0..300).contains(&k) {
                4e4 * (std::f64::consts::PI * k as f64 / 300.0).sin()
            } else {
                0.0
            };
            let noise = 0.01 * ((k * 7919 % 101) as f64 / 101.0 - 0.5);
            let yaw = if nan && k == 200 {
                "NaN".to_string()
            } else {
                format!("{}", noise)
            };
            text += &format!(
                "{t},{f},{},{},{yaw}\n",
                -f / 1200.0 + noise,
                -f / 1200.0 - noise
            );
        }
        std::fs::write(dir.join(name), text).unwrap();
    };
    write("nan.csv", -200, true);
    write("short.csv", -5, false);
    let start =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/planar/identify/start.toml");
    let study = |file: &str| {
        let text = format!(
            "[model]\nplanar = {start:?}\n[[case]]\nname = \"T\"\nspeed = 2.0\n\
             forces = [{{ path = {file:?}, channel = \"force\", lateral = 0.2, direction = [-1.0, 0.0] }}]\n\
             sensors = [{{ path = {file:?}, channel = \"left\", body = [0.6, 0.7], noise = \"0.05 g\" }},\n\
             {{ path = {file:?}, channel = \"right\", body = [0.6, -0.7], noise = \"0.05 g\" }},\n\
             {{ path = {file:?}, channel = \"yaw\" }}]\n"
        );
        let path = dir.join(format!("{file}.toml"));
        std::fs::write(&path, text).unwrap();
        PlanarStudy::read(&path).map_err(|e| e.to_string())
    };
    let e = study("nan.csv").unwrap_err();
    eprintln!("NaN: {e}");
    assert!(e.contains("yaw") && e.contains("nan.csv"), "NaN: {e}");
    let e = study("short.csv").unwrap_err();
    assert!(
        e.contains("sensor yaw") && e.contains("noise"),
        "no pre-trigger: {e}"
    );
}

#[test]
fn wall_cells_need_only_cell_and_anchor_and_a_force_needs_one_place() {
    // docs/planar.md documents a wall cell by `cell` and `anchor`: a study
    // of such cells reads (the pole's anchored forces, without `lateral`)
    let dir = series();
    let text = std::fs::read_to_string(dir.join("study.toml")).unwrap();
    let stripped: String = text
        .lines()
        .map(|l| match l.contains("anchor") {
            true => {
                let at = l.find("lateral = ").unwrap();
                let end = at + l[at..].find(", ").unwrap() + 2;
                format!("{}{}", &l[..at], &l[end..])
            }
            false => l.to_string(),
        })
        .collect::<Vec<_>>()
        .join("\n");
    let path = dir.join("no-lateral.toml");
    std::fs::write(&path, &stripped).unwrap();
    let read = PlanarStudy::read(&path).unwrap();
    let original = PlanarStudy::read(&dir.join("study.toml")).unwrap();
    assert_eq!(read.cases.len(), original.cases.len());
    let line = text
        .lines()
        .find(|l| l.contains("FOXP") && !l.contains("anchor"))
        .unwrap();
    let at = line.find("lateral = ").unwrap();
    let end = at + line[at..].find(", ").unwrap() + 2;
    let e = edited(line, &format!("{}{}", &line[..at], &line[end..])).unwrap_err();
    assert!(
        e.contains("give `lateral`") && e.contains("or `anchor`"),
        "{e}"
    );
}
