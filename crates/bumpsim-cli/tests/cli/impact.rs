//! `bumpsim synth`, `bumpsim impact` and `bumpsim mass-reduction`.

use std::path::{Path, PathBuf};

use crate::util::*;

#[test]
fn synth_remakes_the_bundled_series_bit_for_bit() {
    let dir = scratch("synth").join("series");
    let series = root().join("examples/identify/series.toml");
    let run = bumpsim(&[
        "synth",
        series.to_str().unwrap(),
        "-o",
        dir.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    // each channel's ISO/TS 18571 rating against the noise-free signal
    // (issue 33), printed and in its header's Comments
    assert_contains(
        &text(&run.stdout),
        &[
            "FLAT P0IMPA000000FOXP: synthetic (bumpsim synth): ISO/TS 18571 rating against the noise-free signal 0.",
        ],
    );
    for head in ["FLAT", "P600", "POLE"] {
        for file in [
            format!("{head}.mme"),
            format!("Channel/{head}.chn"),
            format!("Channel/{head}.001"),
            format!("Channel/{head}.002"),
            format!("Channel/{head}.003"),
        ] {
            let made = std::fs::read(dir.join(head).join(&file)).unwrap();
            let bundled =
                std::fs::read(root().join("examples/identify").join(head).join(&file)).unwrap();
            assert!(
                made == bundled,
                "{head}/{file} differs from the bundled file"
            );
        }
        assert!(dir.join(format!("{head}.csv")).exists());
    }
    let refused = bumpsim(&[
        "synth",
        series.to_str().unwrap(),
        "-o",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(
        refused.status.code(),
        Some(2),
        "an existing folder is not overwritten"
    );
}

/// A rigid 1050 kg vehicle (a UTV) in `dir`.
fn rigid_car(dir: &Path) -> PathBuf {
    let car = dir.join("utv.toml");
    let text = "name = \"UTV\"\nmasses = [1050.0]\ndampers = []\nsprings = []\n";
    std::fs::write(&car, text).unwrap();
    car
}

/// `bumpsim impact --car CAR --bumper BUMPER` followed by `rest`.
fn impact(car: &Path, bumper: &Path, rest: &[&str]) -> std::process::Output {
    let mut args = vec!["impact", "--car", car.to_str().unwrap()];
    args.extend(["--bumper", bumper.to_str().unwrap()]);
    args.extend_from_slice(rest);
    bumpsim(&args)
}

fn impact_example(name: &str) -> PathBuf {
    root().join("examples/impact").join(name)
}

#[test]
fn impact_json_and_report_for_a_rigid_vehicle_into_a_barrier() {
    let dir = scratch("impact");
    let car = rigid_car(&dir);
    let json = dir.join("impact.json");
    let report = dir.join("report");
    let run = impact(
        &car,
        &impact_example("bumper-a.toml"),
        &[
            "--barrier",
            "--speed",
            "8 km/h",
            "--json",
            json.to_str().unwrap(),
            "--report",
            report.to_str().unwrap(),
        ],
    );
    let stdout = text(&run.stdout);
    assert!(run.status.success(), "{stdout}{}", text(&run.stderr));
    assert_contains(
        &stdout,
        &[
            "peak force",
            "kN",
            "maximum compression",
            "mm",
            "contact time",
            "ms",
        ],
    );
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    // a rigid mass on a three-part bumper: ½ m V0² = area under the loading curve
    let (m, v0, s, fmax) = (1050.0, 8.0 / 3.6, 6.0e6, 110.0e3);
    let knee = fmax / s;
    let expected = (0.5 * m * v0 * v0 - 0.5 * fmax * knee) / fmax + knee;
    let got = v["max_compression"].as_f64().unwrap();
    assert!(
        (got / expected - 1.0).abs() < 1e-3,
        "max compression {got} vs {expected}"
    );
    for key in ["peak_force", "remaining_compression", "contact_time"] {
        assert!(v[key].as_f64().is_some_and(|x| x > 0.0), "{key}");
    }
    assert!(
        std::fs::read_to_string(report.join("index.html"))
            .unwrap()
            .contains("<svg")
    );
    let list = bumpsim(&[
        "impact",
        "--car",
        car.to_str().unwrap(),
        "--bumper",
        impact_example("bumper-a.toml").to_str().unwrap(),
        "--case",
        "list",
    ]);
    assert!(text(&list.stdout).contains("thesis-pole") && text(&list.stdout).contains("paper A"));
}

#[test]
fn mass_reduction_of_the_paper_a_example_and_its_sweep() {
    let dir = scratch("mass-reduction");
    let json = dir.join("mr.json");
    let grid = dir.join("grid.csv");
    let run = bumpsim(&[
        "mass-reduction",
        "--m1",
        "650",
        "--m2",
        "400",
        "--k",
        "4e6",
        "--bumper",
        impact_example("bumper-a.toml").to_str().unwrap(),
        "--speed",
        "8 km/h",
        "--criterion",
        "remaining",
        "--json",
        json.to_str().unwrap(),
        "--sweep",
        "bumper",
        "--points",
        "6",
        "-o",
        grid.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let factor = v["scale_factor"].as_f64().unwrap();
    assert!(factor > 650.0 / 1050.0 && factor < 1.0, "{factor}");
    let mass = v["equivalent_mass"].as_f64().unwrap();
    assert!((mass / 1050.0 - factor).abs() < 1e-12);
    let csv = std::fs::read_to_string(&grid).unwrap();
    assert_eq!(csv.lines().count(), 1 + 36);
    assert!(csv.starts_with("ramp slope s [N/m],plateau F_max [N],scale factor [-]"));
}

#[test]
fn impact_errors_exit_2() {
    let dir = scratch("impact-errors");
    let bad = dir.join("bad.toml");
    std::fs::write(&bad, "ramp = -1.0e6\nplateau = 5.0e4\nunloading = 5.0e6\n").unwrap();
    let car = root().join("examples/simulate/car-3dof.toml");
    let run = impact(&car, &bad, &["--barrier", "--speed", "2"]);
    assert_eq!(run.status.code(), Some(2));
    assert!(
        text(&run.stderr).contains("bad.toml") && text(&run.stderr).contains("ramp"),
        "{}",
        text(&run.stderr)
    );
    let bumper = impact_example("bumper-a.toml");
    let zero = impact(&car, &bumper, &["--barrier", "--speed", "0"]);
    assert_user_error(&zero, "speed");
}

/// Issue 34: `--report rep --json rep/index.html` wrote the JSON, then
/// refused the report; one command's outputs are now all or nothing.
#[test]
fn a_refused_report_leaves_no_json_behind() {
    let dir = scratch("impact-transaction");
    let car = rigid_car(&dir);
    let (report, csv) = (dir.join("rep"), dir.join("o.csv"));
    let run = impact(
        &car,
        &impact_example("bumper-a.toml"),
        &[
            "--barrier",
            "--speed",
            "8 km/h",
            "--csv",
            csv.to_str().unwrap(),
            "--report",
            report.to_str().unwrap(),
            "--json",
            report.join("index.html").to_str().unwrap(),
        ],
    );
    assert_user_error(&run, "two outputs to one path");
    assert!(
        !report.exists() && !csv.exists(),
        "the refused command left outputs"
    );
    let run = impact(&car, Path::new("/dev/zero"), &["--barrier"]);
    assert_user_error(&run, "not a regular file");
    // -o without --sweep wrote nothing and said nothing
    let grid = dir.join("g.csv");
    let bumper = impact_example("bumper-a.toml");
    let (b, g) = (bumper.to_str().unwrap(), grid.to_str().unwrap());
    let run = bumpsim(&["mass-reduction", "--bumper", b, "-o", g]);
    assert_user_error(&run, "--sweep");
    // --points without --sweep did nothing and said nothing (hostile pass)
    let run = bumpsim(&["mass-reduction", "--bumper", b, "--points", "7"]);
    assert_user_error(&run, "--sweep");
}

/// Issue 34: `--speed 1e-300` and `--pendulum 1e308` ran with exit 0 and a
/// NaN or infinite energy; they are refused before the run, naming the
/// parameter and its range.
#[test]
fn impacts_outside_the_physical_ranges_are_refused() {
    let dir = scratch("impact-ranges");
    let car = rigid_car(&dir);
    let heavy = dir.join("heavy.toml");
    std::fs::write(
        &heavy,
        "masses = [1e308, 1e308]\ndampers = [1]\nsprings = [1e6]\n",
    )
    .unwrap();
    let bumper = impact_example("bumper-a.toml");
    let cases: [(&Path, &[&str], &str); 8] = [
        (
            &car,
            &["--pendulum", "1000", "--speed", "1e-300"],
            "speed (m/s) = 1e-300: from 0.001 to 1000 m/s",
        ),
        (
            &car,
            &["--pendulum", "1e308", "--speed", "2"],
            "impactor mass (kg) = 1e308: from 0.001 to 1e7 kg",
        ),
        (
            &car,
            &["--pendulum", "1e-300", "--speed", "2"],
            "impactor mass (kg) = 1e-300",
        ),
        (
            &car,
            &["--barrier", "--speed", "1e200"],
            "speed (m/s) = 1e200",
        ),
        (
            &car,
            &["--case", "thesis-flat", "--speed", "1e-9"],
            "speed (m/s) = 1e-9",
        ),
        (
            &heavy,
            &["--barrier", "--speed", "2"],
            "initial kinetic energy (J) = inf",
        ),
        (&car, &["--barrier", "--speed=-2"], "speed (m/s) = -2.0"),
        // clap said "unexpected argument '-2'" without naming the flag
        (&car, &["--barrier", "--speed", "-2"], "speed (m/s) = -2.0"),
    ];
    for (car, extra, needle) in cases {
        assert_user_error(&impact(car, &bumper, extra), needle);
    }
}

/// A car too stiff for its light front mass: the refusal names the car and
/// bumper files and the stable step (it said "integration steps (duration /
/// stable step) = 71780000.0" and neither file).
#[test]
fn a_car_too_stiff_to_integrate_is_named_with_its_step() {
    let car = root().join("examples/simulate/car-3dof.toml");
    let bumper = root().join("examples/impact/bumper-a.toml");
    let run = impact(&car, &bumper, &["--barrier", "--speed", "2"]);
    assert_user_error(&run, "car-3dof.toml with --bumper");
    assert_user_error(&run, "need a stable step of");
    assert_user_error(&run, "at most 5e7 (limit MAX_STEPS)");
}

/// Issue 34: a bumper curve point with three values lost its third without
/// a word; it is refused with the file, line and what a point holds.
#[test]
fn a_curve_point_with_three_values_is_refused() {
    let dir = scratch("impact-curve-points");
    let car = rigid_car(&dir);
    let bumper = dir.join("three.toml");
    let curve = "unloading = 1e7\ncurve = [\n  [0, 0],\n  [0.01, 1e4, 5],\n  [0.05, 5e4],\n]\n";
    std::fs::write(&bumper, curve).unwrap();
    let barrier = ["--barrier", "--speed", "2"];
    let run = impact(&car, &bumper, &barrier);
    assert_user_error(&run, "three.toml: TOML parse error at line 4");
    assert_user_error(
        &run,
        "invalid length 3, expected an array of exactly 2 numbers",
    );
    std::fs::write(&bumper, curve.replace(", 5]", "]").replace("[0, 0]", "[0]")).unwrap();
    let run = impact(&car, &bumper, &barrier);
    assert_user_error(&run, "line 3");
}

/// Issue 34: `synth` accepted `force_noise = -1` and three biases for two
/// accelerometers (the third dropped); a pendulum of 1e308 kg made a series.
#[test]
fn synth_refuses_negative_noise_extra_biases_and_absurd_heads() {
    let dir = scratch("synth-hostile");
    for file in [
        "series.toml",
        "car-truth.toml",
        "bumper-flat.toml",
        "bumper-p600.toml",
        "bumper-pole.toml",
    ] {
        std::fs::copy(root().join("examples/identify").join(file), dir.join(file)).unwrap();
    }
    let series = std::fs::read_to_string(dir.join("series.toml")).unwrap();
    let cases = [
        (
            "force_noise = 150.0",
            "force_noise = -1.0",
            "[chain] force_noise = -1.0 N",
        ),
        (
            "force_noise = 150.0",
            "force_noise = nan",
            "force_noise = NaN",
        ),
        (
            "acceleration_noise = 0.2",
            "acceleration_noise = 1e300",
            "acceleration_noise = 1e300 g",
        ),
        (
            "biases = [0.15, -0.10]",
            "biases = [0.15, -0.10, 7]",
            "exactly 2 numbers",
        ),
        (
            "biases = [0.15, -0.10]",
            "biases = [0.15, inf]",
            "biases = inf g",
        ),
        (
            "mass = 1450.0",
            "mass = 1e308",
            "impactor mass (kg) = 1e308",
        ),
        (
            "speed = \"6 km/h\"",
            "speed = 1e-300",
            "speed (m/s) = 1e-300",
        ),
        // a duration below one step made tests of one sample (hostile pass)
        (
            "duration = 0.16",
            "duration = 1e-308",
            "[chain] duration = 1e-308 s",
        ),
    ];
    synth_refuses_each(&dir, &series, &cases);
}

/// A rigid 1000 kg mass and a linear elastic bumper of 1 MN/m (peak force
/// `v √(k m)` at v) with log-normal spreads of k (20 %) and m (10 %) in `dir`.
fn linear_spring(dir: &Path) -> [PathBuf; 3] {
    let car = dir.join("rigid.toml");
    std::fs::write(&car, "masses = [1000.0]\ndampers = []\nsprings = []\n").unwrap();
    let bumper = dir.join("linear.toml");
    std::fs::write(&bumper, "ramp = 1e6\nplateau = 1e9\nunloading = 1e6\n").unwrap();
    let spreads = dir.join("spreads.toml");
    let text = "[uncertainty]\n\"bumper.force\" = 0.2\n\"masses[0]\" = 0.1\n";
    std::fs::write(&spreads, text).unwrap();
    [car, bumper, spreads]
}

/// The prediction band of the peak force against the analytic log-normal:
/// `v √(k m)` with independent log-normal k, m has ln-sd
/// `0.5 √(σk² + σm²)` = 0.1118; with 2000 draws the 5 %, 50 % and 95 %
/// quantiles are within 1.5 % of the analytic ones (Monte Carlo error
/// about 0.5 %). The JSON carries the spreads, the force's band and the
/// Sobol indices (S of the force ≈ 0.8, of the mass ≈ 0.2, analytic
/// 0.7996 and 0.1988 within their bootstrap intervals plus 0.05); the
/// report its page; the same seed the same bytes.
#[test]
fn impact_predicts_the_analytic_band_and_sobol_indices() {
    let dir = scratch("impact-uncertainty");
    let [car, bumper, spreads] = linear_spring(&dir);
    let json = dir.join("prediction.json");
    let report = dir.join("report");
    let args = |json: &Path| {
        let mut a = vec!["--barrier", "--speed", "2", "--uncertainty"];
        a.push(spreads.to_str().unwrap());
        a.extend([
            "--samples",
            "2000",
            "--seed",
            "5",
            "--sobol",
            "--sobol-base",
            "256",
        ]);
        a.extend(["--json", json.to_str().unwrap()]);
        a.iter().map(|s| s.to_string()).collect::<Vec<_>>()
    };
    let mut first = args(&json);
    first.extend(["--report".into(), report.to_str().unwrap().into()]);
    let first: Vec<&str> = first.iter().map(String::as_str).collect();
    let run = impact(&car, &bumper, &first);
    let stdout = text(&run.stdout);
    assert!(run.status.success(), "{stdout}{}", text(&run.stderr));
    assert_contains(
        &stdout,
        &[
            "(2000 draws, seed 5, 0 failed; log-normal spreads bumper.force 20.0 %, masses[0] 10.0 %): median and 90 % interval",
            "peak force",
            "median 63.",
            "kN",
            "Sobol indices over independent log-normal parameters (N = 256, 1024 impacts",
        ],
    );
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let peak = &v["prediction"]["outputs"][0];
    assert_eq!(peak["name"], "peak force");
    assert_eq!(peak["unit"], "N");
    let median = 2.0 * (1e6f64 * 1000.0).sqrt();
    let s = 0.5 * (0.2f64.powi(2) + 0.1f64.powi(2)).sqrt();
    let z = 1.644_853_626_951_472_2;
    for (key, want) in [
        ("median", median),
        ("low", median * (-z * s).exp()),
        ("high", median * (z * s).exp()),
    ] {
        let got = peak["spread"][key].as_f64().unwrap();
        assert!(
            (got / want - 1.0).abs() < 0.015,
            "{key}: {got} against {want}"
        );
    }
    let band = &v["prediction"]["bands"][0];
    assert_eq!(band["name"], "force");
    let n = band["time"].as_array().unwrap().len();
    assert!(n > 100 && band["band"]["high"].as_array().unwrap().len() == n);
    let i = &v["sensitivity"]["outputs"][0]["indices"];
    let (a, b) = (0.01f64, 0.0025f64);
    let analytic = [
        (a.exp() - 1.0) / ((a + b).exp() - 1.0),
        (b.exp() - 1.0) / ((a + b).exp() - 1.0),
    ];
    for (k, want) in analytic.iter().enumerate() {
        let got = i["first"][k].as_f64().unwrap();
        let half = i["first_conf"][k].as_f64().unwrap();
        assert!(
            (got - want).abs() < half + 0.05,
            "S{k} {got} against {want} ± {half}"
        );
    }
    let page = std::fs::read_to_string(report.join("uncertainty.html")).unwrap();
    assert!(page.contains("force: nominal (solid) and the 90 % band"));
    // the band is one shaded area under the nominal curve
    let band = std::fs::read_to_string(report.join("force-band.svg")).unwrap();
    assert_eq!(band.matches("<polygon opacity=\"0.3\"").count(), 1);
    assert!(page.contains("band over the draws (shaded, pointwise)"));
    // the index shows the distributions and says where the bands are
    let index = std::fs::read_to_string(report.join("index.html")).unwrap();
    assert!(index.contains("uncertainty.html in this folder"), "{index}");
    let again = dir.join("again.json");
    let second = args(&again);
    let second: Vec<&str> = second.iter().map(String::as_str).collect();
    let rerun = impact(&car, &bumper, &second);
    assert_eq!(text(&rerun.stdout).lines().next(), stdout.lines().next());
    assert_eq!(
        std::fs::read(&json).unwrap(),
        std::fs::read(&again).unwrap()
    );
    // one thread gives the same bytes as the default pool
    let single = dir.join("single.json");
    let mut one = vec![
        "impact".to_string(),
        "--car".into(),
        car.to_str().unwrap().into(),
    ];
    one.extend(["--bumper".into(), bumper.to_str().unwrap().into()]);
    one.extend(args(&single));
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_bumpsim"))
        .args(&one)
        .env("RAYON_NUM_THREADS", "1")
        .output()
        .unwrap();
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert_eq!(
        std::fs::read(&json).unwrap(),
        std::fs::read(&single).unwrap()
    );
}

/// Hostile --uncertainty, --samples, --level and --sobol-base: exit 2
/// naming the flag, file or parameter, nothing written.
#[test]
fn impact_refuses_hostile_uncertainty_options() {
    let dir = scratch("impact-uncertainty-hostile");
    let [car, bumper, spreads] = linear_spring(&dir);
    let file = |name: &str, text: &str| {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        path.to_str().unwrap().to_string()
    };
    let spreads = spreads.to_str().unwrap().to_string();
    let planar = r#"{"result": {"parameters": [{"name": "body.mass", "value": 1000, "standard_error": 10}], "uncertainty": {"correlation": [[1]]}}}"#;
    let cases: Vec<(Vec<String>, &str)> = vec![
        (
            vec![spreads.clone(), "--samples".into(), "NaN".into()],
            "--samples",
        ),
        (
            vec![spreads.clone(), "--samples".into(), "-5".into()],
            "--samples",
        ),
        (
            vec![spreads.clone(), "--samples".into(), "1e9".into()],
            "--samples",
        ),
        (
            vec![spreads.clone(), "--samples".into(), "1000000".into()],
            "--samples: samples = 1000000",
        ),
        (
            vec![spreads.clone(), "--samples".into(), "5".into()],
            "--samples: samples = 5",
        ),
        (
            vec![spreads.clone(), "--level".into(), "1.5".into()],
            "--level: level = 1.5",
        ),
        (
            vec![spreads.clone(), "--level".into(), "0".into()],
            "--level: level = 0",
        ),
        (
            vec![spreads.clone(), "--level".into(), "NaN".into()],
            "--level: level = NaN",
        ),
        (
            vec![
                spreads.clone(),
                "--sobol".into(),
                "--sobol-base".into(),
                "3".into(),
            ],
            "--sobol-base",
        ),
        (
            vec![file(
                "unknown.toml",
                "[uncertainty]\n\"wheel.size\" = 0.1\n",
            )],
            "'wheel.size' is not a parameter of the car",
        ),
        (
            vec![file("nan.toml", "[uncertainty]\n\"masses[0]\" = nan\n")],
            "nan.toml: masses[0] = NaN",
        ),
        (
            vec![file(
                "negative.toml",
                "[uncertainty]\n\"masses[0]\" = -0.1\n",
            )],
            "masses[0] = -0.1",
        ),
        (
            vec![file("absent.toml", "[uncertainty]\n\"springs[0]\" = 0.1\n")],
            "springs[0] is missing: a parameter of the car: masses[0], bumper.force",
        ),
        (
            vec![file("planar.json", planar)],
            "expected a 1-D chain identification's JSON",
        ),
        (
            vec![file("garbled.toml", "[uncertainty\n")],
            "not valid TOML",
        ),
        (
            vec![dir.join("none.toml").to_str().unwrap().into()],
            "none.toml",
        ),
    ];
    let json = dir.join("out.json");
    for (extra, needle) in cases {
        let mut args = vec![
            "--barrier",
            "--speed",
            "2",
            "--json",
            json.to_str().unwrap(),
        ];
        args.push("--uncertainty");
        args.extend(extra.iter().map(String::as_str));
        let run = impact(&car, &bumper, &args);
        assert_user_error(&run, needle);
        assert!(!json.exists(), "{needle}: nothing written");
    }
    let collide = impact(
        &car,
        &bumper,
        &["--barrier", "--uncertainty", &spreads, "--json", &spreads],
    );
    assert_user_error(&collide, "it would overwrite the input");
    let without = impact(&car, &bumper, &["--barrier", "--samples", "10"]);
    assert_eq!(
        without.status.code(),
        Some(2),
        "--samples needs --uncertainty"
    );
}

/// `[ranges]`: the bumper's force uniform on ×0.5 .. ×1.5 and the mass on
/// ×0.8 .. ×1.2 of the linear-spring car. The lines and the Sobol header
/// name the uniform law, the JSON each parameter's law; the peak force
/// lies within `v √(k_lo m_lo)` .. `v √(k_hi m_hi)`; the force's first
/// order index is the analytic 0.866 (`Var(√a) E[√b]² / V`, see the
/// library's test) within its bootstrap interval plus 0.05.
#[test]
fn impact_over_uniform_ranges_names_the_law() {
    let dir = scratch("impact-ranges-sobol");
    let [car, bumper, _] = linear_spring(&dir);
    let ranges = dir.join("ranges.toml");
    let contents = "[ranges]\n\"bumper.force\" = [0.5, 1.5]\n\"masses[0]\" = [0.8, 1.2]\n";
    std::fs::write(&ranges, contents).unwrap();
    let json = dir.join("prediction.json");
    let mut args = vec!["--barrier", "--speed", "2", "--uncertainty"];
    args.extend([ranges.to_str().unwrap(), "--samples", "200", "--sobol"]);
    args.extend(["--sobol-base", "128", "--json", json.to_str().unwrap()]);
    let run = impact(&car, &bumper, &args);
    let stdout = text(&run.stdout);
    assert!(run.status.success(), "{stdout}{}", text(&run.stderr));
    assert_contains(
        &stdout,
        &[
            "(200 draws, seed 1, 0 failed; uniform ranges bumper.force ×0.5 .. ×1.5, masses[0] ×0.8 .. ×1.2): median and 90 % interval",
            "Sobol indices over independent uniform parameters (N = 128, 512 impacts",
        ],
    );
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let law = &v["prediction"]["uncertainty"]["laws"][0];
    assert_eq!(
        (&law["law"], &law["low"], &law["high"]),
        (&"uniform".into(), &0.5.into(), &1.5.into())
    );
    assert_eq!(v["sensitivity"]["laws"][1]["law"], "uniform");
    let nominal = 2.0 * (1e6f64 * 1000.0).sqrt();
    let peak = &v["prediction"]["outputs"][0]["spread"];
    let (low, high) = (
        peak["low"].as_f64().unwrap(),
        peak["high"].as_f64().unwrap(),
    );
    assert!(nominal * 0.4f64.sqrt() * 0.999 < low && high < nominal * 1.8f64.sqrt() * 1.001);
    let i = &v["sensitivity"]["outputs"][0]["indices"];
    let (got, half) = (
        i["first"][0].as_f64().unwrap(),
        i["first_conf"][0].as_f64().unwrap(),
    );
    assert!(
        (got - 0.866).abs() < half + 0.05,
        "S of the force {got} ± {half}"
    );
}

/// Bad `[ranges]`: a reversed, NaN, non-positive or too wide range, one
/// that is not two numbers, a parameter in both tables and an unknown
/// name exit 2 naming the file and the key, nothing written.
#[test]
fn impact_refuses_bad_ranges_naming_the_key() {
    let dir = scratch("impact-ranges-hostile");
    let [car, bumper, _] = linear_spring(&dir);
    let json = dir.join("out.json");
    let cases = [
        (
            "[1.2, 0.8]",
            "ranges.\"masses[0]\" = [1.2, 0.8]: expected two factors",
        ),
        ("[nan, 1.2]", "ranges.\"masses[0]\" = [NaN, 1.2]"),
        ("[0, 1.2]", "ranges.\"masses[0]\" = [0, 1.2]"),
        (
            "[0.5, 1e4]",
            "ranges.\"masses[0]\" = [0.5, 10000]: expected two factors of the car file's value, 0.001 <= low < high <= 1000",
        ),
        (
            "[0.8]",
            "ranges.\"masses[0]\" = [0.8]: expected [low, high], two numbers",
        ),
        ("0.1", "ranges.\"masses[0]\" = 0.1: expected [low, high]"),
    ];
    let mut files: Vec<(String, &str)> = cases
        .iter()
        .map(|(range, says)| (format!("[ranges]\n\"masses[0]\" = {range}\n"), *says))
        .collect();
    files.push((
        "[uncertainty]\n\"masses[0]\" = 0.1\n[ranges]\n\"masses[0]\" = [0.8, 1.2]\n".into(),
        "'masses[0]' is in both [uncertainty] and [ranges]",
    ));
    files.push((
        "[ranges]\n\"wheel.size\" = [0.8, 1.2]\n".into(),
        "'wheel.size' is not a parameter of the car",
    ));
    for (k, (contents, says)) in files.iter().enumerate() {
        let file = dir.join(format!("bad-{k}.toml"));
        std::fs::write(&file, contents).unwrap();
        let mut args = vec!["--barrier", "--speed", "2", "--uncertainty"];
        args.push(file.to_str().unwrap());
        args.extend(["--sobol", "--json", json.to_str().unwrap()]);
        let run = impact(&car, &bumper, &args);
        assert_user_error(&run, &format!("bad-{k}.toml: {says}"));
        assert!(!json.exists(), "{says}: nothing written");
    }
}
