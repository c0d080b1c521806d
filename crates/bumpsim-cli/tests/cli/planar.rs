//! `bumpsim planar` on the bundled planar car: presets, explicit faces,
//! mirror symmetry through the JSON, outputs and hostile inputs.

use crate::util::{assert_contains, assert_user_error, bumpsim, root, scratch, text};
use serde_json::Value;
use std::path::{Path, PathBuf};

fn saloon() -> PathBuf {
    root().join("examples/planar/saloon.toml")
}

fn run_json(dir: &Path, name: &str, extra: &[&str]) -> Value {
    let json = dir.join(format!("{name}.json"));
    let car = saloon();
    let mut args = vec!["planar", "--car", car.to_str().unwrap()];
    args.extend_from_slice(extra);
    args.extend_from_slice(&["--json", json.to_str().unwrap()]);
    let run = bumpsim(&args);
    assert!(run.status.success(), "{}", text(&run.stderr));
    serde_json::from_str(&std::fs::read_to_string(json).unwrap()).unwrap()
}

fn number(v: &Value, path: &[&str]) -> f64 {
    path.iter()
        .fold(v, |v, k| &v[*k])
        .as_f64()
        .unwrap_or_else(|| panic!("{path:?} is not a number"))
}

#[test]
fn the_rcar_preset_prints_units_and_writes_json_csv_and_report() {
    let dir = scratch("planar-rcar");
    let (json, csv, report) = (dir.join("r.json"), dir.join("r.csv"), dir.join("report"));
    let car = saloon();
    let run = bumpsim(&[
        "planar",
        "--car",
        car.to_str().unwrap(),
        "--case",
        "rcar-structural-front",
        "--json",
        json.to_str().unwrap(),
        "--csv",
        csv.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
    ]);
    let stdout = text(&run.stdout);
    assert!(run.status.success(), "{stdout}{}", text(&run.stderr));
    assert_contains(
        &stdout,
        &[
            "mid-size saloon",
            "15 km/h",
            "10°, 40 % overlap from the left",
            "RCAR",
            "kN",
            "deg/s",
            " J",
        ],
    );
    let v: Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let result = &v["result"];
    assert!(number(result, &["peak_force"]) > 10e3);
    assert!(number(result, &["energy", "max_relative_error"]) < 1e-3);
    // the left corner is struck behind the CG's line: the car turns left
    assert!(number(result, &["peak_yaw_rate"]) > 0.0);
    let rows = std::fs::read_to_string(&csv).unwrap().lines().count();
    assert_eq!(rows, result["time"].as_array().unwrap().len() + 1);
    let html = std::fs::read_to_string(report.join("index.html")).unwrap();
    assert!(html.contains("<svg") && html.contains("remaining crush"));
    for svg in ["forces.svg", "yaw.svg", "path.svg", "crush.svg"] {
        assert!(report.join(svg).is_file(), "{svg}");
    }
}

#[test]
fn a_mirrored_face_mirrors_yaw_and_side_member_forces() {
    let dir = scratch("planar-mirror");
    let left = run_json(
        &dir,
        "l",
        &[
            "--angle",
            "10",
            "--overlap",
            "40",
            "--side",
            "left",
            "--speed",
            "15 km/h",
        ],
    );
    let right = run_json(
        &dir,
        "r",
        &[
            "--angle",
            "-10",
            "--overlap",
            "40",
            "--side",
            "right",
            "--speed",
            "15 km/h",
        ],
    );
    let (l, r) = (&left["result"], &right["result"]);
    let peak = number(l, &["peak_force"]);
    let tolerance = 1e-9;
    assert!((number(l, &["peak_force"]) - number(r, &["peak_force"])).abs() < tolerance * peak);
    let rate = number(l, &["peak_yaw_rate"]);
    assert!((rate + number(r, &["peak_yaw_rate"])).abs() < tolerance * rate.abs());
    let series = |v: &Value, k: &str| -> Vec<f64> {
        v[k].as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    };
    let (fl, fr) = (series(l, "side_force_left"), series(r, "side_force_right"));
    assert_eq!(fl.len(), fr.len());
    assert!(
        fl.iter()
            .zip(&fr)
            .all(|(a, b)| (a - b).abs() < tolerance * peak)
    );
}

#[test]
fn a_pendulum_pole_and_the_preset_list_run() {
    let dir = scratch("planar-pole");
    let v = run_json(
        &dir,
        "pole",
        &[
            "--pole",
            "178 mm",
            "--pole-offset",
            "-100 mm",
            "--pendulum",
            "1400",
            "--speed",
            "8 km/h",
        ],
    );
    assert!(number(&v["result"], &["peak_force"]) > 1e3);
    let list = bumpsim(&["planar", "--case", "list"]);
    assert!(list.status.success());
    assert_contains(
        &text(&list.stdout),
        &["rcar-structural-front", "iihs-pole-rear", "uncertain:"],
    );
}

fn planar(dir: &Path, car_text: &str, extra: &[&str]) -> std::process::Output {
    let car = dir.join("car.toml");
    std::fs::write(&car, car_text).unwrap();
    let mut args = vec!["planar", "--car", car.to_str().unwrap()];
    args.extend_from_slice(extra);
    bumpsim(&args)
}

#[test]
fn hostile_inputs_are_refused_with_exit_2_and_a_named_parameter() {
    let dir = scratch("planar-hostile");
    let good = std::fs::read_to_string(saloon()).unwrap();
    let speed = ["--speed", "4"];
    let with = |from: &str, to: &str| good.replacen(from, to, 1);
    let cases: [(String, Vec<&str>, &str); 13] = [
        (good.clone(), vec!["--overlap", "150"], "overlap"),
        // hostile pass: --side alone did nothing; a 1e-308 s duration ran
        // one sample with a warning
        (good.clone(), vec!["--side", "left"], "--overlap"),
        (good.clone(), vec!["--duration", "1e-308"], "duration"),
        (good.clone(), vec!["--angle", "NaN"], "barrier angle"),
        (
            good.clone(),
            vec!["--pole", "0.2", "--pole-offset", "5"],
            "cannot hit",
        ),
        (good.clone(), vec!["--pendulum", "-5"], "striker mass"),
        (good.clone(), vec!["--speed", "1e400"], "speed"),
        (
            with("yaw_inertia = 2200.0", "yaw_inertia = -2200.0"),
            vec![],
            "body.yaw_inertia",
        ),
        (
            with("segments = 10", "segments = 1000000000000"),
            vec![],
            "segments",
        ),
        (with("mass = 1300.0", "mass = nan"), vec![], "body.mass"),
        (with("springs = [3e6]", "springs = [3e30]"), vec![], "limit"),
        (with("[tyres]", "[tyres]\ngrip = 1.0"), vec![], "grip"),
        // issue 34: a curve point of three values lost its third
        (
            with("ramp = 3e6", "curve = [[0, 0], [0.02, 6e4, 1]]").replacen(
                "plateau = 200e3",
                "",
                1,
            ),
            vec![],
            "exactly 2 numbers",
        ),
    ];
    for (car, extra, needle) in cases {
        let mut args = extra.clone();
        if !extra.contains(&"--speed") {
            args.extend_from_slice(&speed);
        }
        let run = planar(&dir, &car, &args);
        assert_user_error(&run, needle);
        assert!(
            !text(&run.stdout).to_lowercase().contains("nan"),
            "{needle}"
        );
    }
    assert_user_error(&planar(&dir, &good, &[]), "--speed");
    assert_user_error(
        &planar(&dir, &good, &["--case", "nope"]),
        "rcar-structural-front",
    );
}

#[test]
fn outputs_never_land_on_inputs() {
    let dir = scratch("planar-outputs");
    let car = dir.join("car.toml");
    std::fs::copy(saloon(), &car).unwrap();
    let before = std::fs::read(&car).unwrap();
    for option in ["--json", "--csv"] {
        let run = bumpsim(&[
            "planar",
            "--car",
            car.to_str().unwrap(),
            "--speed",
            "4",
            option,
            car.to_str().unwrap(),
        ]);
        assert_eq!(
            run.status.code(),
            Some(2),
            "{option}: {}",
            text(&run.stderr)
        );
    }
    let report_on_file = bumpsim(&[
        "planar",
        "--car",
        car.to_str().unwrap(),
        "--speed",
        "4",
        "--report",
        car.to_str().unwrap(),
    ]);
    assert_eq!(report_on_file.status.code(), Some(2));
    assert_eq!(
        std::fs::read(&car).unwrap(),
        before,
        "the car file was changed"
    );
}

/// Wave-2 hostile findings: each of these ran to exit 0 with NaN or inf in
/// the printed result (energy balance error NaN, "inf kg", "diameter inf mm").
#[test]
fn strikers_that_overflow_or_underflow_are_refused_by_name() {
    let dir = scratch("planar-overflow");
    let good = std::fs::read_to_string(saloon()).unwrap();
    let cases: [(&[&str], &str); 4] = [
        (&["--speed", "1e-300"], "striker kinetic energy"),
        (
            &["--speed", "2", "--pendulum", "1e308"],
            "striker kinetic energy",
        ),
        (&["--speed", "2", "--pole", "1e308"], "pole radius"),
        (&["--speed", "2", "--pole", "1e7"], "use a plane"),
    ];
    for (extra, needle) in cases {
        let run = planar(&dir, &good, extra);
        assert_user_error(&run, needle);
        let out = text(&run.stdout);
        assert!(out.is_empty(), "{extra:?}: no result is printed: {out}");
    }
}

/// `--json x --csv x` ran with exit 0 and left only the CSV in x.
#[test]
fn two_outputs_on_one_path_are_refused() {
    let dir = scratch("planar-twice");
    let same = dir.join("same.out");
    let car = saloon();
    let run = bumpsim(&[
        "planar",
        "--car",
        car.to_str().unwrap(),
        "--speed",
        "4",
        "--json",
        same.to_str().unwrap(),
        "--csv",
        same.to_str().unwrap(),
    ]);
    assert_user_error(&run, "two outputs to one path");
    assert!(!same.exists());
}

/// Issue 15: `bumpsim impact` accepts the planar car and the new strikers,
/// and runs the same planar impact as `bumpsim planar`.
#[test]
fn impact_accepts_the_planar_car_and_its_strikers() {
    let dir = scratch("impact-planar");
    let car = saloon();
    let face = [
        "--angle",
        "-10",
        "--overlap",
        "40",
        "--side",
        "right",
        "--speed",
        "15 km/h",
    ];
    let mut outputs = Vec::new();
    for command in ["impact", "planar"] {
        let json = dir.join(format!("{command}.json"));
        let mut args = vec![command, "--car", car.to_str().unwrap()];
        args.extend_from_slice(&face);
        args.extend_from_slice(&["--json", json.to_str().unwrap()]);
        let run = bumpsim(&args);
        assert!(run.status.success(), "{}", text(&run.stderr));
        let v: Value = serde_json::from_str(&std::fs::read_to_string(json).unwrap()).unwrap();
        outputs.push(v["result"].clone());
    }
    assert_eq!(outputs[0], outputs[1], "the same planar impact");
    assert!(
        number(&outputs[0], &["peak_yaw_rate"]) < 0.0,
        "struck on the right: yaw to the right"
    );
    let rcar = bumpsim(&[
        "impact",
        "--car",
        car.to_str().unwrap(),
        "--case",
        "rcar-structural-front",
    ]);
    assert!(rcar.status.success(), "{}", text(&rcar.stderr));
    assert_contains(&text(&rcar.stdout), &["RCAR", "kN", "deg/s"]);
    let bumper = root().join("examples/impact/bumper-a.toml");
    let both = bumpsim(&[
        "impact",
        "--car",
        car.to_str().unwrap(),
        "--bumper",
        bumper.to_str().unwrap(),
        "--barrier",
        "--speed",
        "2",
    ]);
    assert_user_error(&both, "--bumper");
    let chain = root().join("examples/identify/car-truth.toml");
    let angled = bumpsim(&[
        "impact",
        "--car",
        chain.to_str().unwrap(),
        "--bumper",
        bumper.to_str().unwrap(),
        "--angle",
        "10",
        "--speed",
        "2",
    ]);
    assert_user_error(&angled, "planar car");
    let missing = bumpsim(&[
        "impact",
        "--car",
        chain.to_str().unwrap(),
        "--barrier",
        "--speed",
        "2",
    ]);
    assert_user_error(&missing, "--bumper");
}

/// Issue 15: a 1-D car TOML plus a width becomes a symmetric planar car;
/// in a full-width flat barrier it gives the 1-D impact's peak force and
/// compression (to the two integrators' different steps, 1e-4).
#[test]
fn a_1d_car_with_a_width_is_a_symmetric_planar_car() {
    let dir = scratch("impact-width");
    let car = root().join("examples/identify/car-truth.toml");
    let bumper = root().join("examples/impact/bumper-a.toml");
    let (c, b) = (car.to_str().unwrap(), bumper.to_str().unwrap());
    let (one, wide) = (dir.join("1d.json"), dir.join("planar.json"));
    let base = [
        "impact",
        "--car",
        c,
        "--bumper",
        b,
        "--barrier",
        "--speed",
        "8 km/h",
    ];
    for (json, extra) in [(&one, vec![]), (&wide, vec!["--width", "1600 mm"])] {
        let mut args = base.to_vec();
        args.extend(extra);
        args.extend(["--json", json.to_str().unwrap()]);
        let run = bumpsim(&args);
        assert!(run.status.success(), "{}", text(&run.stderr));
    }
    let read =
        |p: &Path| -> Value { serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap() };
    let (one, wide) = (read(&one), read(&wide));
    for key in ["peak_force", "max_compression"] {
        let (a, b) = (number(&one, &[key]), number(&wide, &["result", key]));
        assert!((a - b).abs() < 1e-4 * a, "{key}: 1-D {a}, planar {b}");
    }
    let angled = bumpsim(&[
        "impact",
        "--car",
        c,
        "--bumper",
        b,
        "--width",
        "1.6",
        "--angle",
        "10",
        "--overlap",
        "40",
        "--speed",
        "15 km/h",
    ]);
    assert!(angled.status.success(), "{}", text(&angled.stderr));
    assert_contains(&text(&angled.stdout), &["10°, 40 % overlap", "yaw"]);
    assert_user_error(
        &bumpsim(&[
            "impact",
            "--car",
            c,
            "--bumper",
            b,
            "--width",
            "nan m",
            "--barrier",
            "--speed",
            "2",
        ]),
        "--width",
    );
    // a 1e-308 m beam ran an angled impact (hostile pass of issue 34)
    assert_user_error(
        &bumpsim(&[
            "impact",
            "--car",
            c,
            "--bumper",
            b,
            "--width",
            "1e-308",
            "--angle",
            "10",
            "--barrier",
        ]),
        "--width: the symmetric planar car: bumper width = 1e-308 m: from 0.1 to 10 m",
    );
}

/// Issue 32's set-up: a gap delays the same impact (the record starts at
/// −gap/v, time zero stays the first touch); the preset states its tyres and
/// `--tyres sliding` locks them (more yaw against the wall's side force,
/// and the locked wheels' sliding grip takes energy);
/// bad gaps, durations and tyre words are refused by name.
#[test]
fn a_gap_a_duration_and_the_tyres_are_the_users_set_up() {
    let dir = scratch("planar-setup");
    let rcar = ["--case", "rcar-structural-front"];
    let touching = run_json(&dir, "touching", &rcar);
    let gap = run_json(&dir, "gap", &[&rcar[..], &["--gap", "50 mm"]].concat());
    let time = |v: &Value| v["result"]["time"][0].as_f64().unwrap();
    assert!(
        (time(&gap) + 0.05 / (15.0 / 3.6)).abs() < 1e-9,
        "{}",
        time(&gap)
    );
    let peak = |v: &Value| number(v, &["result", "peak_force"]);
    assert!((peak(&gap) - peak(&touching)).abs() < 1e-3 * peak(&touching));
    let sliding = run_json(
        &dir,
        "sliding",
        &[&rcar[..], &["--tyres", "sliding"]].concat(),
    );
    let yaw = |v: &Value| number(v, &["result", "peak_yaw_rate"]);
    assert!(
        yaw(&sliding) > 1.02 * yaw(&touching),
        "{} {}",
        yaw(&sliding),
        yaw(&touching)
    );
    // locked wheels slide with their grip (0.8), not the rolling
    // resistance (0.02): their tyres take several times the energy (issue 45)
    let tyres = |v: &Value| number(v, &["result", "energy", "friction"]);
    assert!(
        tyres(&sliding) > 5.0 * tyres(&touching),
        "{} {}",
        tyres(&sliding),
        tyres(&touching)
    );
    let car = saloon();
    let listed = bumpsim(&["planar", "--case", "list"]);
    assert_contains(&text(&listed.stdout), &["tyres: free rolling"]);
    let run = bumpsim(&[
        "planar",
        "--car",
        car.to_str().unwrap(),
        "--case",
        "rcar-structural-front",
    ]);
    assert_contains(
        &text(&run.stdout),
        &["tyres: free rolling", "brakes released"],
    );
    for (option, value, named) in [
        ("--gap", "nan", "--gap"),
        ("--gap", "-1 mm", "gap"),
        ("--gap", "1e300", "gap"),
        ("--gap", "5 m", "duration"),
        ("--duration", "0", "duration"),
        ("--duration", "1e9 s", "duration"),
        ("--tyres", "skid", "--tyres"),
    ] {
        let run = bumpsim(&[
            "planar",
            "--car",
            car.to_str().unwrap(),
            "--case",
            "rcar-structural-front",
            option,
            value,
        ]);
        assert_user_error(&run, named);
    }
}

/// `planar` and `impact` with a planar car over the car's uncertainty: the
/// spreads printed with units, the JSON's spreads (each 90 % interval holds
/// its median), the force's and crush's bands, Sobol indices (the bumper's
/// force drives the peak force: the largest total index), the report's
/// page; the same seed gives the same JSON bytes.
#[test]
fn planar_impacts_predict_spreads_bands_and_sobol_indices() {
    let dir = scratch("planar-uncertainty");
    let spreads = root().join("examples/verdict/uncertainty.toml");
    let report = dir.join("report");
    let extra = |report: &Option<String>| {
        let mut a = vec!["--case", "rcar-structural-front", "--uncertainty"];
        a.push(spreads.to_str().unwrap());
        a.extend([
            "--samples",
            "20",
            "--seed",
            "3",
            "--sobol",
            "--sobol-base",
            "16",
        ]);
        if let Some(r) = report {
            a.extend(["--report", r.as_str()]);
        }
        a.into_iter().map(String::from).collect::<Vec<String>>()
    };
    let first = extra(&Some(report.to_str().unwrap().to_string()));
    let v = run_json(
        &dir,
        "first",
        &first.iter().map(String::as_str).collect::<Vec<_>>(),
    );
    let outputs = v["prediction"]["outputs"].as_array().unwrap();
    assert_eq!(outputs.len(), 6);
    for o in outputs {
        let s = &o["spread"];
        assert!(number(s, &["low"]) <= number(s, &["median"]), "{o}");
        assert!(number(s, &["median"]) <= number(s, &["high"]), "{o}");
    }
    assert_eq!(v["prediction"]["bands"][0]["name"], "force");
    assert_eq!(v["prediction"]["bands"][1]["name"], "deepest crush");
    let peak = &v["sensitivity"]["outputs"][0]["indices"];
    let names: Vec<&str> = peak["names"]
        .as_array()
        .unwrap()
        .iter()
        .map(|n| n.as_str().unwrap())
        .collect();
    let total: Vec<f64> = peak["total"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t.as_f64().unwrap())
        .collect();
    let largest = (0..total.len())
        .max_by(|&a, &b| total[a].total_cmp(&total[b]))
        .unwrap();
    assert_eq!(names[largest], "bumper.force", "{total:?}");
    assert!(
        report.join("uncertainty.html").exists() && report.join("deepest-crush-band.svg").exists()
    );
    let second = extra(&None);
    let again = run_json(
        &dir,
        "again",
        &second.iter().map(String::as_str).collect::<Vec<_>>(),
    );
    assert_eq!(v, again);
    assert_eq!(
        std::fs::read(dir.join("first.json")).unwrap(),
        std::fs::read(dir.join("again.json")).unwrap()
    );
    let car = saloon();
    let run = bumpsim(&[
        "impact",
        "--car",
        car.to_str().unwrap(),
        "--case",
        "rcar-structural-front",
        "--uncertainty",
        spreads.to_str().unwrap(),
        "--samples",
        "10",
    ]);
    let stdout = text(&run.stdout);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert_contains(
        &stdout,
        &[
            "(10 draws, seed 1, 0 failed; log-normal spreads",
            "peak yaw rate",
            "deg/s   median",
        ],
    );
}

/// A chain identification's JSON, a chain's parameter name, a NaN spread
/// or a bad level for a planar car: exit 2 naming the file or parameter.
#[test]
fn planar_refuses_hostile_uncertainty_files() {
    let dir = scratch("planar-uncertainty-hostile");
    let file = |name: &str, text: &str| {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        path.to_str().unwrap().to_string()
    };
    let chain = r#"{"dof": 1, "masses": [1000.0], "uncertainty": {"names": ["m1"], "standard_errors": [10.0], "correlation": [[1.0]]}}"#;
    let spreads = file("ok.toml", "[uncertainty]\n\"body.mass\" = 0.05\n");
    let cases = [
        (file("chain.json", chain), vec![], "no result.parameters"),
        (
            file("chain.toml", "[uncertainty]\n\"masses[0]\" = 0.1\n"),
            vec![],
            "'masses[0]' is not a parameter of the car",
        ),
        (
            file("nan.toml", "[uncertainty]\n\"body.mass\" = nan\n"),
            vec![],
            "body.mass = NaN",
        ),
        (spreads.clone(), vec!["--level", "-0.5"], "--level"),
        (spreads, vec!["--samples", "0"], "--samples"),
    ];
    let car = saloon();
    let json = dir.join("out.json");
    for (uncertainty, extra, needle) in cases {
        let mut args = vec![
            "planar",
            "--car",
            car.to_str().unwrap(),
            "--speed",
            "2",
            "--uncertainty",
            &uncertainty,
        ];
        args.extend(extra);
        args.extend(["--json", json.to_str().unwrap()]);
        assert_user_error(&bumpsim(&args), needle);
        assert!(!json.exists(), "{needle}: nothing written");
    }
}
