//! Runs the real `bumpsim` binary on the bundled example and on malformed
//! inputs written here, and checks exit codes and messages.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn example(name: &str) -> PathBuf {
    root().join("examples/simulate").join(name)
}

fn scratch(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("cli")
        .join(test);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn bumpsim(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_bumpsim"))
        .args(args)
        .output()
        .unwrap()
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// Fails unless the run was refused as a user error (exit code 2) whose
/// message contains `needle`.
fn assert_user_error(run: &Output, needle: &str) {
    let stderr = text(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains(needle), "missing '{needle}' in:\n{stderr}");
}

/// Fails unless every expected piece is in `output`.
fn assert_contains(output: &str, expected: &[&str]) {
    for piece in expected {
        assert!(output.contains(piece), "missing '{piece}' in:\n{output}");
    }
}

fn simulate(car: &Path, force: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        "simulate",
        "--car",
        car.to_str().unwrap(),
        "--force",
        force.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    bumpsim(&args)
}

#[test]
fn simulates_the_bundled_example_and_writes_si_csv() {
    let dir = scratch("example");
    let out = dir.join("new-folder/response.csv");
    let run = simulate(
        &example("car-3dof.toml"),
        &example("pendulum-force.csv"),
        &["-o", out.to_str().unwrap()],
    );
    let stdout = text(&run.stdout);
    assert!(run.status.success(), "{stdout}{}", text(&run.stderr));
    assert_contains(
        &stdout,
        &[
            "3 DOF",
            "1601 samples",
            "peak 40.00 kN",
            "energy balance error",
            "wrote",
        ],
    );
    let csv = std::fs::read_to_string(&out).unwrap();
    let header = csv.lines().next().unwrap();
    assert!(
        header.starts_with("time [s],force [N],x1 [m],x2 [m],x3 [m],v1 [m/s]"),
        "{header}"
    );
    assert_eq!(csv.lines().count(), 1602);
    // the force in kN/ms came out in N/s
    let row: Vec<f64> = csv
        .lines()
        .nth(501)
        .unwrap()
        .split(',')
        .map(|c| c.parse().unwrap())
        .collect();
    assert!(
        (row[0] - 0.04).abs() < 1e-12 && (row[1] - 40_000.0).abs() < 1e-6,
        "{row:?}"
    );
}

#[test]
fn taylor1_refuses_the_thesis_model_with_the_cure() {
    let run = simulate(
        &example("car-3dof.toml"),
        &example("pendulum-force.csv"),
        &["--method", "taylor1"],
    );
    assert_eq!(run.status.code(), Some(2));
    let stderr = text(&run.stderr);
    assert!(
        stderr.contains("unstable") && stderr.contains("--substeps") && stderr.contains("zoh"),
        "{stderr}"
    );
    let auto = simulate(
        &example("car-3dof.toml"),
        &example("pendulum-force.csv"),
        &["--method", "taylor1", "--substeps", "auto"],
    );
    assert!(auto.status.success(), "{}", text(&auto.stderr));
    assert!(text(&auto.stdout).contains("sub-steps per sample"));
}

#[test]
fn initial_velocity_takes_units() {
    let run = simulate(
        &example("car-3dof.toml"),
        &example("pendulum-force.csv"),
        &["--initial-velocity", "16 km/h"],
    );
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(
        text(&run.stdout).contains("every mass at 4.444 m/s (16.00 km/h)"),
        "{}",
        text(&run.stdout)
    );
    let bad = simulate(
        &example("car-3dof.toml"),
        &example("pendulum-force.csv"),
        &["--initial-velocity", "16 kN"],
    );
    assert_user_error(&bad, "expected a velocity");
}

/// Each malformed force file: its text and a part of the expected message.
const BAD_FORCES: &[(&str, &str, &str)] = &[
    (
        "unknown-unit",
        "time [s],force [lbf]\n0,1\n0.1,2\n",
        "unknown unit 'lbf'",
    ),
    (
        "non-uniform",
        "time [s],force [N]\n0,1\n0.1,1\n0.3,1\n0.4,1\n",
        ":4: time is not uniformly sampled",
    ),
    (
        "nan",
        "time [s],force [N]\n0,1\n0.1,NaN\n",
        ":3: column 'force [N]' holds 'NaN'",
    ),
    ("empty", "", "no header row"),
    (
        "ragged",
        "time [s],force [N]\n0,1\n0.1\n",
        ":3: 1 cells, but the header has 2",
    ),
    (
        "no-force",
        "time [s],x [mm]\n0,1\n0.1,2\n",
        "no force column",
    ),
];

#[test]
fn malformed_force_files_exit_2_with_file_and_line() {
    let dir = scratch("bad-force");
    for (name, body, expected) in BAD_FORCES {
        let path = dir.join(format!("{name}.csv"));
        std::fs::write(&path, body).unwrap();
        let run = simulate(&example("car-3dof.toml"), &path, &[]);
        let stderr = text(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{name}: {stderr}");
        assert!(
            stderr.contains(&format!("{name}.csv")) && stderr.contains(expected),
            "{name}: {stderr}"
        );
    }
}

#[test]
fn malformed_car_files_exit_2_naming_the_parameter() {
    let dir = scratch("bad-car");
    let cases = [
        (
            "negative",
            "masses = [1.0, -5.0]\ndampers = [1.0]\nsprings = [1.0]\n",
            "m2 = -5 kg",
        ),
        (
            "typo",
            "masses = [1.0]\nspring = [1.0]\n",
            "unknown field `spring`",
        ),
        (
            "count",
            "masses = [1.0, 2.0]\ndampers = [1.0]\n",
            "0 springs given for 2 masses",
        ),
    ];
    for (name, body, expected) in cases {
        let path = dir.join(format!("{name}.toml"));
        std::fs::write(&path, body).unwrap();
        let run = simulate(&path, &example("pendulum-force.csv"), &[]);
        let stderr = text(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{name}: {stderr}");
        assert!(stderr.contains(expected), "{name}: {stderr}");
    }
}

#[test]
fn usage_errors_exit_2() {
    let missing = simulate(
        Path::new("does-not-exist.toml"),
        &example("pendulum-force.csv"),
        &[],
    );
    assert_eq!(missing.status.code(), Some(2));
    assert!(text(&missing.stderr).contains("does-not-exist.toml: cannot read"));
    let method = simulate(
        &example("car-3dof.toml"),
        &example("pendulum-force.csv"),
        &["--method", "rk45"],
    );
    assert_eq!(method.status.code(), Some(2));
    assert!(text(&method.stderr).contains("expected zoh, foh or taylor1"));
    let substeps = simulate(
        &example("car-3dof.toml"),
        &example("pendulum-force.csv"),
        &["--substeps", "4"],
    );
    assert_user_error(&substeps, "taylor1 only");
    let column = simulate(
        &example("car-3dof.toml"),
        &example("pendulum-force.csv"),
        &["--column", "Fx"],
    );
    assert_user_error(&column, "no column 'Fx'; columns: force [kN]");
}

#[test]
fn output_never_overwrites_an_input() {
    let dir = scratch("overwrite");
    let force = dir.join("force.csv");
    std::fs::copy(example("pendulum-force.csv"), &force).unwrap();
    let before = std::fs::read(&force).unwrap();
    let run = simulate(
        &example("car-3dof.toml"),
        &force,
        &["-o", force.to_str().unwrap()],
    );
    assert_eq!(run.status.code(), Some(2));
    assert!(text(&run.stderr).contains("would overwrite the input"));
    assert_eq!(std::fs::read(&force).unwrap(), before);
}

/// Whether python3 with scipy is available; with `BUMPSIM_REQUIRE_PEERS` set
/// (as `scripts/test` does) its absence is a failure, otherwise a skip.
fn scipy_available() -> bool {
    let found = Command::new("python3")
        .args(["-c", "import scipy"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !found {
        assert!(
            std::env::var_os("BUMPSIM_REQUIRE_PEERS").is_none(),
            "BUMPSIM_REQUIRE_PEERS is set but python3 cannot import scipy"
        );
        eprintln!("skipped: python3 with scipy not found (scripts/test installs it)");
    }
    found
}

#[test]
fn zoh_and_foh_match_scipy_cont2discrete() {
    if !scipy_available() {
        return;
    }
    let dir = scratch("scipy");
    let soft = dir.join("soft.toml");
    std::fs::write(
        &soft,
        "masses = [150.0, 500.0, 800.0]\ndampers = [100.0, 2e5]\nsprings = [5e5, 5e5]\n",
    )
    .unwrap();
    for car in [example("car-3dof.toml"), soft] {
        for method in ["zoh", "foh"] {
            let out = dir.join(format!("{method}.csv"));
            let run = simulate(
                &car,
                &example("pendulum-force.csv"),
                &["--method", method, "-o", out.to_str().unwrap()],
            );
            assert!(run.status.success(), "{}", text(&run.stderr));
            let script = root().join("tests/peers/scipy_simulate.py");
            let check = Command::new("python3")
                .args([
                    script.as_os_str(),
                    car.as_os_str(),
                    example("pendulum-force.csv").as_os_str(),
                    out.as_os_str(),
                    method.as_ref(),
                ])
                .output()
                .unwrap();
            assert!(
                check.status.success(),
                "{method} {}: {}{}",
                car.display(),
                text(&check.stdout),
                text(&check.stderr)
            );
        }
    }
}

/// Whether CalculiX's `ccx` is available; with `BUMPSIM_REQUIRE_PEERS` set its
/// absence is a failure, otherwise a skip.
fn ccx_available() -> bool {
    let found = Command::new("sh")
        .args(["-c", "command -v ccx"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !found {
        assert!(
            std::env::var_os("BUMPSIM_REQUIRE_PEERS").is_none(),
            "BUMPSIM_REQUIRE_PEERS is set but ccx is not installed"
        );
        eprintln!("skipped: ccx not found (scripts/test installs calculix-ccx)");
    }
    found
}

/// Reads a bumpsim CSV into its header and rows of numbers.
fn read_csv(path: &Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect();
    (
        header,
        lines
            .map(|l| l.split(',').map(|c| c.parse().unwrap()).collect())
            .collect(),
    )
}

#[test]
fn calculix_run_of_the_exported_deck_matches_simulate() {
    if !ccx_available() {
        return;
    }
    let dir = scratch("calculix");
    let deck = dir.join("car.inp");
    let force = example("pendulum-force.csv");
    let export = bumpsim(&[
        "export",
        "calculix",
        example("car-3dof.toml").to_str().unwrap(),
        "--force",
        force.to_str().unwrap(),
        "-o",
        deck.to_str().unwrap(),
    ]);
    assert!(export.status.success(), "{}", text(&export.stderr));
    let ccx = Command::new("ccx")
        .arg("car")
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(
        ccx.status.success() && !text(&ccx.stdout).contains("*ERROR"),
        "{}",
        text(&ccx.stdout)
    );
    let ccx_csv = dir.join("ccx.csv");
    let read = bumpsim(&[
        "export",
        "read-calculix",
        deck.to_str().unwrap(),
        "-o",
        ccx_csv.to_str().unwrap(),
    ]);
    assert!(read.status.success(), "{}", text(&read.stderr));
    let sim_csv = dir.join("sim.csv");
    let sim = simulate(
        &example("car-3dof.toml"),
        &force,
        &["-o", sim_csv.to_str().unwrap()],
    );
    assert!(sim.status.success());
    let ((_, ours), (header, theirs)) = (read_csv(&sim_csv), read_csv(&ccx_csv));
    assert_eq!(&header[..2], ["time [s]", "x1 [m]"]);
    // ccx prints from the first increment on: its row k is our row k + 1
    assert_eq!(theirs.len() + 1, ours.len());
    let peak = ours.iter().fold(0.0_f64, |m, r| m.max(r[2].abs()));
    let mut worst = 0.0_f64;
    for (a, b) in theirs.iter().zip(&ours[1..]) {
        assert!((a[0] - b[0]).abs() < 1e-9, "time {} vs {}", a[0], b[0]);
        worst = worst.max((a[1] - b[2]).abs());
    }
    assert!(
        worst <= 0.01 * peak,
        "m1 differs by {worst} m, peak {peak} m"
    );
}

#[test]
fn lsdyna_export_writes_the_include_and_refuses_bad_options() {
    let dir = scratch("lsdyna");
    let out = dir.join("car.k");
    let car = example("car-3dof.toml");
    let ok = bumpsim(&[
        "export",
        "lsdyna",
        car.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--units",
        "mm-s-t",
        "--id-offset",
        "800000",
        "--attach",
        "11,12",
        "--initial-velocity",
        "-16 km/h",
    ]);
    assert!(ok.status.success(), "{}", text(&ok.stderr));
    let deck = std::fs::read_to_string(&out).unwrap();
    assert!(
        deck.contains("*CONSTRAINED_NODAL_RIGID_BODY_SPC")
            && deck.contains("  800001        11        12"),
        "{deck}"
    );
    assert!(deck.contains("-4444.4"), "16 km/h in mm/s: {deck}");
    let cases: [(&[&str], &str); 4] = [
        (&["--units", "imperial"], "expected si, mm-s-t or mm-ms-kg"),
        (&["--id-offset", "0", "--attach", "2"], "clashes"),
        (&["--axis", "w"], "unknown axis"),
        (&["--spacing", "-1"], "must be positive"),
    ];
    for (extra, expected) in cases {
        let mut args = vec![
            "export",
            "lsdyna",
            car.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        let run = bumpsim(&args);
        assert_eq!(run.status.code(), Some(2), "{extra:?}");
        assert!(
            text(&run.stderr).contains(expected),
            "{extra:?}: {}",
            text(&run.stderr)
        );
    }
    let broken = dir.join("broken.toml");
    std::fs::write(&broken, "masses = [1.0,\n").unwrap();
    let run = bumpsim(&[
        "export",
        "lsdyna",
        broken.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_user_error(&run, "broken.toml: TOML parse error");
}

fn nhtsa_ev5() -> Option<PathBuf> {
    let path = root().join("../shared/data/nhtsa-10146/v10146.EV5");
    if !path.exists() {
        eprintln!(
            "SKIPPED: {} is absent (NHTSA test 10146 is read from ../shared)",
            path.display()
        );
        return None;
    }
    Some(path)
}

/// The number before `marker` on the line that holds `label`.
fn number_before(stdout: &str, label: &str, marker: &str) -> f64 {
    let line = stdout
        .lines()
        .find(|l| l.contains(label))
        .unwrap_or_else(|| panic!("no '{label}' in {stdout}"));
    let head = &line[..line
        .find(marker)
        .unwrap_or_else(|| panic!("no '{marker}' in {line}"))];
    head.rsplit(['(', ' '])
        .find(|s| !s.is_empty())
        .unwrap()
        .parse()
        .unwrap()
}

#[test]
fn signal_info_lists_the_nhtsa_curves_and_marks_the_invalid_cells() {
    let Some(ev5) = nhtsa_ev5() else { return };
    let run = bumpsim(&["signal", "info", ev5.to_str().unwrap()]);
    let stdout = text(&run.stdout);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(
        stdout.contains("634 channels listed, 184 with samples present"),
        "{stdout}"
    );
    assert!(stdout.contains("57.09 km/h") && stdout.contains("1719 kg"));
    for cell in ["347  0-LC-LC0601-XG", "500  0-LC-LC0304-XG"] {
        let line = stdout.lines().find(|l| l.contains(cell)).unwrap();
        assert!(
            line.contains("INVALID") && line.contains("No valid data"),
            "{line}"
        );
    }
    assert!(
        stdout
            .lines()
            .any(|l| l.contains("   93  1-AC-FLLR-XG") && l.contains("present"))
    );
}

#[test]
fn nhtsa_barrier_impulse_matches_the_momentum_change_of_the_test_mass() {
    let Some(_) = nhtsa_ev5() else { return };
    let dir = scratch("nhtsa-process");
    let pipeline = root().join("examples/nhtsa-10146/pipeline.toml");
    let csv = dir.join("signals.csv");
    let plots = dir.join("plots");
    let run = bumpsim(&[
        "signal",
        "process",
        pipeline.to_str().unwrap(),
        "-o",
        csv.to_str().unwrap(),
        "--plot",
        plots.to_str().unwrap(),
    ]);
    let (stdout, stderr) = (text(&run.stdout), text(&run.stderr));
    assert!(run.status.success(), "{stderr}");
    assert!(
        stderr.contains("left out channel 347") && stderr.contains("left out channel 500"),
        "{stderr}"
    );
    let difference = number_before(&stdout, "momentum balance", " %)");
    assert!(
        difference.abs() < 5.0,
        "impulse vs momentum change: {difference} %\n{stdout}"
    );
    assert!(stdout.contains("of 1719 kg"), "{stdout}");
    let peak = number_before(&stdout, "barrier force: peak", " kN at");
    assert!(
        (-800.0..-500.0).contains(&peak),
        "peak barrier force {peak} kN"
    );
    let peak_time = number_before(&stdout, "barrier force: peak", " ms;");
    assert!(
        (20.0..60.0).contains(&peak_time),
        "time of peak {peak_time} ms"
    );
    let crush = number_before(&stdout, "crush: peak", " mm at");
    assert!(
        (500.0..1000.0).contains(&crush),
        "maximum dynamic crush {crush} mm"
    );
    let header = std::fs::read_to_string(&csv)
        .unwrap()
        .lines()
        .next()
        .unwrap()
        .to_string();
    assert_eq!(
        header,
        "time [s],barrier force [N],crossmember velocity [m/s],crush [m]"
    );
    let svg = std::fs::read_to_string(plots.join("barrier_force.svg")).unwrap();
    assert!(svg.contains("force [kN]") && svg.contains("time [ms]"));
}

#[test]
fn signal_export_writes_si_columns_named_by_code() {
    let dir = scratch("signal-export");
    let out = dir.join("lab.csv");
    let mme = dir.join("mme");
    let sample = root().join("tests/data/isomme/LAB01");
    let run = bumpsim(&[
        "signal",
        "export",
        sample.to_str().unwrap(),
        "--channel",
        "P0IMPA*",
        "--channel",
        "längsträger",
        "--cfc",
        "1000",
        "-o",
        out.to_str().unwrap(),
        "--iso-mme",
        mme.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let csv = std::fs::read_to_string(&out).unwrap();
    assert_eq!(
        csv.lines().next().unwrap(),
        "time [s],P0IMPA000000FOXP [N],10SIMELE0000ACXP [m/s^2]"
    );
    assert_eq!(csv.lines().count(), 41);
    let again = bumpsim(&["signal", "info", mme.to_str().unwrap()]);
    assert!(
        text(&again.stdout).contains("2 channels listed"),
        "{}",
        text(&again.stdout)
    );
    let refused = bumpsim(&[
        "signal",
        "export",
        sample.to_str().unwrap(),
        "-c",
        "1",
        "-o",
        out.to_str().unwrap(),
        "--iso-mme",
        mme.to_str().unwrap(),
    ]);
    assert_eq!(refused.status.code(), Some(2));
    assert!(text(&refused.stderr).contains("not empty"));
}

#[test]
fn signal_errors_exit_2_with_the_path_and_selector() {
    let sample = root().join("tests/data/isomme/LAB01");
    let out = scratch("signal-errors").join("x.csv");
    let run = bumpsim(&[
        "signal",
        "export",
        sample.to_str().unwrap(),
        "-c",
        "11HEAD*",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(run.status.code(), Some(2));
    let stderr = text(&run.stderr);
    assert!(
        stderr.contains("LAB01")
            && stderr.contains("'11HEAD*'")
            && stderr.contains("matches no channel"),
        "{stderr}"
    );
    let missing = bumpsim(&["signal", "info", "no/such/test.mme"]);
    assert_eq!(missing.status.code(), Some(2));
    assert!(text(&missing.stderr).contains("no/such/test.mme"));
}

fn identify_example() -> PathBuf {
    root().join("examples/identify/study.toml")
}

#[test]
fn identify_the_bundled_example_writes_json_and_a_report() {
    let dir = scratch("identify-example");
    let json = dir.join("result.json");
    let report = dir.join("report");
    let run = bumpsim(&[
        "identify",
        identify_example().to_str().unwrap(),
        "--starts",
        "8",
        "--json",
        json.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
        "--quiet",
    ]);
    let stdout = text(&run.stdout);
    assert!(run.status.success(), "{stdout}{}", text(&run.stderr));
    assert_contains(
        &stdout,
        &[
            "3-DOF model",
            "m1",
            "kg",
            "N/mm",
            "Ns/mm",
            "95 % interval",
            "fit",
        ],
    );
    let result: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(result["dof"], 3);
    for key in ["masses", "dampers", "springs"] {
        assert!(
            result[key]
                .as_array()
                .is_some_and(|a| a.iter().all(|v| v.as_f64().is_some_and(|x| x >= 1.0))),
            "{key}"
        );
    }
    assert!(result["objective"].as_f64().is_some_and(f64::is_finite));
    let cases = result["cases"].as_array().unwrap();
    assert_eq!(cases.len(), 3);
    for case in cases {
        assert!(case["fit_percent"].as_f64().unwrap() > 97.0, "{case}");
        assert!(case["sse"].as_f64().is_some() && case["name"].is_string());
    }
    let html = std::fs::read_to_string(report.join("index.html")).unwrap();
    assert!(html.contains("<svg") && html.contains("bumpsim 0.1.0"));
    let predict = bumpsim(&[
        "predict",
        json.to_str().unwrap(),
        identify_example().to_str().unwrap(),
        "--case",
        "pole",
    ]);
    let out = text(&predict.stdout);
    assert!(
        predict.status.success() && out.starts_with("pole: fit"),
        "{out}{}",
        text(&predict.stderr)
    );
}

fn chromium() -> Option<PathBuf> {
    let found = ["/usr/bin/chromium", "/usr/bin/chromium-browser"]
        .into_iter()
        .map(PathBuf::from)
        .find(|p| p.exists());
    if found.is_none() {
        assert!(
            std::env::var_os("BUMPSIM_REQUIRE_PEERS").is_none(),
            "BUMPSIM_REQUIRE_PEERS is set but chromium is not installed"
        );
        eprintln!("skipped: chromium not found (scripts/test installs it)");
    }
    found
}

#[test]
fn the_identification_report_renders_in_headless_chromium() {
    let Some(browser) = chromium() else { return };
    let dir = scratch("report-browser");
    let report = dir.join("report");
    let run = bumpsim(&[
        "identify",
        identify_example().to_str().unwrap(),
        "--dof",
        "2,3",
        "--starts",
        "4",
        "--report",
        report.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let page = format!(
        "file://{}",
        report.join("index.html").canonicalize().unwrap().display()
    );
    let headless = |profile: &str, extra: &[&str]| {
        Command::new(&browser)
            .args([
                "--headless",
                "--no-sandbox",
                "--disable-gpu",
                "--enable-logging=stderr",
                "--v=0",
            ])
            .arg(format!("--user-data-dir={}", dir.join(profile).display()))
            .args(extra)
            .arg(&page)
            .output()
            .unwrap()
    };
    let dom = headless("profile-dom", &["--dump-dom"]);
    let (html, log) = (text(&dom.stdout), text(&dom.stderr));
    assert!(
        html.contains("bumpsim identification") && html.trim_end().ends_with("</html>"),
        "page did not load"
    );
    let svg_files = std::fs::read_dir(&report)
        .unwrap()
        .flatten()
        .filter(|e| e.path().extension().is_some_and(|x| x == "svg"))
        .count();
    let figures: Vec<&str> = html.split("<figure class=\"plot\"").skip(1).collect();
    assert_eq!(figures.len(), svg_files, "every plot is in the page");
    for figure in &figures {
        assert!(
            figure.contains("<svg") && figure.contains("<polyline"),
            "a plot is empty"
        );
    }
    let console: Vec<&str> = log
        .lines()
        .filter(|l| l.contains("CONSOLE") || l.contains("Uncaught"))
        .collect();
    assert!(console.is_empty(), "console errors: {console:?}");
    let artefacts = Path::new(env!("CARGO_TARGET_TMPDIR")).join("artefacts");
    std::fs::create_dir_all(&artefacts).unwrap();
    let shot = artefacts.join("identification-report.png");
    let screenshot = headless(
        "profile-shot",
        &[
            "--window-size=1200,2400",
            &format!("--screenshot={}", shot.display()),
        ],
    );
    assert!(screenshot.status.success(), "{}", text(&screenshot.stderr));
    assert!(
        std::fs::metadata(&shot).unwrap().len() > 10_000,
        "screenshot kept at {}",
        shot.display()
    );
}

#[test]
fn nhtsa_two_dof_fit_and_the_dof_table() {
    let Some(_) = nhtsa_ev5() else { return };
    let dir = scratch("identify-nhtsa");
    let json = dir.join("result.json");
    let study = root().join("examples/nhtsa-10146/study.toml");
    let run = bumpsim(&[
        "identify",
        study.to_str().unwrap(),
        "--dof",
        "1..3",
        "--json",
        json.to_str().unwrap(),
        "--quiet",
    ]);
    let stdout = text(&run.stdout);
    assert!(run.status.success(), "{stdout}{}", text(&run.stderr));
    assert!(
        stdout.contains(" DOF   objective m²     fit %          AIC          BIC       time"),
        "{stdout}"
    );
    let result: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let results = result["results"].as_array().unwrap();
    assert_eq!(results.len(), 3);
    let two = &results[1];
    assert_eq!(two["dof"], 2);
    let fit = two["cases"][0]["fit_percent"].as_f64().unwrap();
    assert!(fit >= 96.0, "2-DOF fit {fit} %");
}

#[test]
fn identify_errors_exit_2() {
    let missing = bumpsim(&["identify", "no/such/study.toml"]);
    assert_eq!(missing.status.code(), Some(2));
    assert!(text(&missing.stderr).contains("no/such/study.toml"));
    let bad_dof = bumpsim(&[
        "identify",
        identify_example().to_str().unwrap(),
        "--dof",
        "0",
    ]);
    assert_user_error(&bad_dof, "--dof '0'");
    let unknown_case = bumpsim(&["predict", "no.json", identify_example().to_str().unwrap()]);
    assert_eq!(unknown_case.status.code(), Some(2));
}

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

fn impact_example(name: &str) -> PathBuf {
    root().join("examples/impact").join(name)
}

#[test]
fn impact_json_and_report_for_a_rigid_vehicle_into_a_barrier() {
    let dir = scratch("impact");
    let car = dir.join("utv.toml");
    std::fs::write(
        &car,
        "name = \"UTV\"\nmasses = [1050.0]\ndampers = []\nsprings = []\n",
    )
    .unwrap();
    let json = dir.join("impact.json");
    let report = dir.join("report");
    let run = bumpsim(&[
        "impact",
        "--car",
        car.to_str().unwrap(),
        "--bumper",
        impact_example("bumper-a.toml").to_str().unwrap(),
        "--barrier",
        "--speed",
        "8 km/h",
        "--json",
        json.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
    ]);
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
    let run = bumpsim(&[
        "impact",
        "--car",
        car.to_str().unwrap(),
        "--bumper",
        bad.to_str().unwrap(),
        "--barrier",
        "--speed",
        "2",
    ]);
    assert_eq!(run.status.code(), Some(2));
    assert!(
        text(&run.stderr).contains("bad.toml") && text(&run.stderr).contains("ramp"),
        "{}",
        text(&run.stderr)
    );
    let zero = bumpsim(&[
        "impact",
        "--car",
        car.to_str().unwrap(),
        "--bumper",
        impact_example("bumper-a.toml").to_str().unwrap(),
        "--barrier",
        "--speed",
        "0",
    ]);
    assert_user_error(&zero, "speed");
}

fn doe_data(name: &str) -> PathBuf {
    root().join("tests/data/doe").join(name)
}

#[test]
fn doe_predict_reproduces_paper_c_table_4_and_flags_extrapolation() {
    let model = doe_data("paper-c-stage2.json");
    let run = bumpsim(&[
        "doe",
        "predict",
        model.to_str().unwrap(),
        "--at",
        "Kax=21747,Kbnd=20630,M=1681",
    ]);
    let stdout = text(&run.stdout);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert_contains(
        &stdout,
        &[
            "m1 = 1.000 kg",
            "m2 = 2230 kg",
            "c1 = 200.2 Ns/mm",
            "k1 = 3.920 N/mm",
        ],
    );
    let outside = bumpsim(&[
        "doe",
        "predict",
        model.to_str().unwrap(),
        "--at",
        "Kax=27000,Kbnd=20630,M=1681",
    ]);
    assert!(text(&outside.stdout).contains("warning: Kax = 27000 is outside the design region"));
    let missing = bumpsim(&[
        "doe",
        "predict",
        model.to_str().unwrap(),
        "--at",
        "Kax=23000",
    ]);
    assert_user_error(&missing, "no value for factor 'Kbnd'");
}

#[test]
fn doe_design_fit_report_and_saturated_model() {
    let dir = scratch("doe-fit");
    let design = dir.join("design.csv");
    let run = bumpsim(&[
        "doe",
        "design",
        "full",
        "--factors",
        "Kax:21210:25684,Kbnd:20217:23643,M:1375:1681",
        "--centre",
        "3",
        "-o",
        design.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    // responses from paper C's stage-2 coefficients plus a small deterministic disturbance
    let rows: Vec<Vec<f64>> = std::fs::read_to_string(&design)
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|c| c.parse().unwrap()).collect())
        .collect();
    let mut data = String::from("Kax [N/mm],Kbnd [N/mm],M [kg],m2 [kg],c1 [Ns/mm]\n");
    for (i, r) in rows.iter().enumerate() {
        let (z1, z2, z3) = (r[5], r[6], r[7]);
        let wobble = ((i * 7) as f64).sin();
        let m2 = 1987.0 - 52.38 * z1 + 16.63 * z2 + 215.63 * z3 + 3.0 * wobble;
        let c1 = 206.4 + 27.39 * z1 - 10.63 * z2 + 6.53 * z3 + 0.5 * wobble;
        data += &format!("{},{},{},{m2},{c1}\n", r[2], r[3], r[4]);
    }
    let csv = dir.join("data.csv");
    std::fs::write(&csv, data).unwrap();
    let json = dir.join("model.json");
    let report = dir.join("report");
    let fit = bumpsim(&[
        "doe",
        "fit",
        csv.to_str().unwrap(),
        "--factors",
        "Kax,Kbnd,M",
        "--responses",
        "m2,c1",
        "--json",
        json.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
    ]);
    let stdout = text(&fit.stdout);
    assert!(fit.status.success(), "{stdout}{}", text(&fit.stderr));
    assert!(
        stdout.contains("m2 [kg]: R²") && stdout.contains("lack of fit"),
        "{stdout}"
    );
    let model: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let m2 = &model["responses"][0];
    for key in [
        "coefficients",
        "std_errors",
        "ci95",
        "r2",
        "r2_adjusted",
        "q2",
        "press",
    ] {
        assert!(!m2[key].is_null(), "{key} in {m2}");
    }
    let coefficient = m2["coefficients"]["M"].as_f64().unwrap();
    assert!((coefficient - 215.63).abs() < 5.0, "{coefficient}");
    assert!(
        std::fs::read_to_string(report.join("index.html"))
            .unwrap()
            .matches("<svg")
            .count()
            >= 6
    );
    let predicted = bumpsim(&[
        "doe",
        "predict",
        json.to_str().unwrap(),
        "--at",
        "Kax=23447,Kbnd=21930,M=1528",
    ]);
    assert!(
        text(&predicted.stdout).contains("95 % PI"),
        "{}",
        text(&predicted.stdout)
    );
    // a saturated model: 2^2 runs for intercept, two mains and the interaction
    let small = dir.join("small.csv");
    std::fs::write(&small, "A,B,y\n-1,-1,1\n1,-1,2\n-1,1,4\n1,1,7\n").unwrap();
    let saturated = bumpsim(&[
        "doe",
        "fit",
        small.to_str().unwrap(),
        "--factors",
        "A,B",
        "--responses",
        "y",
        "--interactions",
    ]);
    assert!(saturated.status.success(), "{}", text(&saturated.stderr));
    assert!(
        text(&saturated.stdout).contains("Q² undefined: the model is saturated"),
        "{}",
        text(&saturated.stdout)
    );
}

#[test]
fn doe_reach_stiffness_and_fraction_resolution() {
    let dir = scratch("doe-reach");
    let run = bumpsim(&[
        "doe",
        "reach",
        doe_data("paper-c-stage1.json").to_str().unwrap(),
        "--x",
        "Kax",
        "--y",
        "Kbnd",
        "--cell",
        "21210,25684,20217,23643",
        "--plot",
        dir.to_str().unwrap(),
    ]);
    let stdout = text(&run.stdout);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert_eq!(
        stdout.matches(": reachable with coded").count(),
        4,
        "{stdout}"
    );
    assert!(dir.join("reachable.svg").exists());
    let curve = dir.join("curve.csv");
    let mut csv = String::from("displacement [mm],force [kN]\n");
    for i in 0..=40 {
        let d = i as f64 * 0.5;
        csv += &format!("{d},{}\n", 2.5 * d + 0.01 * (i as f64).sin());
    }
    std::fs::write(&curve, csv).unwrap();
    let stiff = bumpsim(&["doe", "stiffness", curve.to_str().unwrap()]);
    assert!(
        text(&stiff.stdout).starts_with("stiffness 2500 N/mm")
            || text(&stiff.stdout).starts_with("stiffness 2499")
            || text(&stiff.stdout).starts_with("stiffness 2501"),
        "{}",
        text(&stiff.stdout)
    );
    let fraction = bumpsim(&[
        "doe",
        "design",
        "fractional",
        "--factors",
        "A:-1:1,B:-1:1,C:-1:1,D:-1:1,E:-1:1,F:-1:1,G:-1:1",
        "--generators",
        "D=AB,E=AC,F=BC,G=ABC",
        "-o",
        dir.join("f.csv").to_str().unwrap(),
    ]);
    let out = text(&fraction.stdout);
    assert!(
        out.contains("resolution 3") && out.contains("8 runs of 7 factors"),
        "{out}{}",
        text(&fraction.stderr)
    );
}

#[test]
fn a_partial_identification_report_still_renders_and_says_what_failed() {
    let dir = scratch("partial-report");
    let example = root().join("examples/identify");
    let study = std::fs::read_to_string(example.join("study.toml"))
        .unwrap()
        .replace(
            "dof = 3",
            "dof = [1, 2]\nfixed = { k1 = 1e16 }   # no model can be simulated with this spring",
        )
        .replace("path = \"", &format!("path = \"{}/", example.display()));
    let path = dir.join("study.toml");
    std::fs::write(&path, study).unwrap();
    let report = dir.join("report");
    let run = bumpsim(&[
        "identify",
        path.to_str().unwrap(),
        "--starts",
        "2",
        "--report",
        report.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(
        run.status.success(),
        "a failed DOF does not end the sweep: {}",
        text(&run.stderr)
    );
    assert!(
        text(&run.stderr).contains("2-DOF model: all 2 starts failed"),
        "{}",
        text(&run.stderr)
    );
    let html = std::fs::read_to_string(report.join("index.html")).unwrap();
    assert!(
        html.contains("1-DOF model")
            && html.contains("class=\"failure\"")
            && html.contains("all 2 starts failed")
    );
    let Some(browser) = chromium() else { return };
    let page = format!(
        "file://{}",
        report.join("index.html").canonicalize().unwrap().display()
    );
    let dom = Command::new(browser)
        .args(["--headless", "--no-sandbox", "--disable-gpu", "--dump-dom"])
        .arg(format!("--user-data-dir={}", dir.join("profile").display()))
        .arg(page)
        .output()
        .unwrap();
    let rendered = text(&dom.stdout);
    assert!(
        rendered.contains("Failed: all 2 starts failed")
            && rendered.trim_end().ends_with("</html>"),
        "the failure is shown in the rendered page"
    );
}

#[test]
fn doe_collect_appends_identified_parameters_to_the_design() {
    let dir = scratch("doe-collect");
    let design = dir.join("design.csv");
    std::fs::write(&design, "Kax [N/mm],M [kg]\n21210,1375\n25684,1681\n").unwrap();
    let mut results = Vec::new();
    for (i, m2) in [1800.0, 2100.0].iter().enumerate() {
        let path = dir.join(format!("r{i}.json"));
        std::fs::write(&path, format!("{{\"dof\": 2, \"masses\": [1.0, {m2}], \"dampers\": [2.0e5], \"springs\": [4.0e6], \"objective\": 1e-4}}")).unwrap();
        results.push(path.to_str().unwrap().to_string());
    }
    let out = dir.join("data.csv");
    let run = bumpsim(&[
        "doe",
        "collect",
        design.to_str().unwrap(),
        "--results",
        &results.join(","),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let csv = std::fs::read_to_string(&out).unwrap();
    assert_eq!(
        csv.lines().next().unwrap(),
        "Kax [N/mm],M [kg],m1 [kg],m2 [kg],c1 [Ns/m],k1 [N/m]"
    );
    assert_eq!(
        csv.lines().nth(2).unwrap(),
        "25684,1681,1,2100,200000,4000000"
    );
    let short = bumpsim(&[
        "doe",
        "collect",
        design.to_str().unwrap(),
        "--results",
        &results[0],
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_user_error(&short, "1 results for 2 design runs");
}
