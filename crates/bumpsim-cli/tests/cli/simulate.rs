//! `bumpsim simulate`: the bundled example, malformed inputs and scipy.

use std::path::Path;
use std::process::Command;

use crate::util::*;

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
    // issue 34: both reached `unreachable!` in the table reader
    (
        "huge",
        "time [s],force [kN]\n0,0\n0.001,1e308\n0.002,0\n",
        ":3: column 'force [kN]' holds '1e308', beyond the largest number once converted to SI",
    ),
    (
        "late",
        "time [s],force [N]\n1e15,0\n1.000000000000000125e15,1\n1.00000000000000025e15,0\n",
        "small enough that the sample interval is resolved",
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
        // issue 34: "the simulation diverged", naming no file
        (
            "huge",
            "masses = [1.8, 74.8, 1670]\ndampers = [1e308, 1.97e5]\nsprings = [4.75e5, 5e5]\n",
            "huge.toml with the force of",
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

/// Whether python3 with scipy is available.
fn scipy_available() -> bool {
    peer_available("scipy", "python3", &["-c", "import scipy"])
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

/// Issue 34: stdout on a full device panicked (the hook knew only a broken
/// pipe) and a car file on a device was read until memory ran out.
#[cfg(target_os = "linux")]
#[test]
fn a_full_stdout_and_a_device_for_a_car_are_errors_not_panics() {
    let dir = scratch("dev-full");
    let csv = dir.join("r.csv");
    let run = Command::new(env!("CARGO_BIN_EXE_bumpsim"))
        .args(["simulate", "--car"])
        .arg(example("car-3dof.toml"))
        .arg("--force")
        .arg(example("pendulum-force.csv"))
        .arg("-o")
        .arg(&csv)
        .stdout(std::fs::File::create("/dev/full").unwrap())
        .output()
        .unwrap();
    assert_user_error(&run, "cannot print the results");
    assert!(
        !text(&run.stderr).contains("panicked"),
        "{}",
        text(&run.stderr)
    );
    assert!(
        !csv.exists(),
        "results that could not be printed were half delivered"
    );
    let run = simulate(Path::new("/dev/zero"), &example("pendulum-force.csv"), &[]);
    assert_user_error(
        &run,
        "/dev/zero: is a device, pipe or socket, not a regular file",
    );
}

#[test]
fn a_force_table_beyond_the_row_limit_is_refused_naming_file_and_line() {
    let dir = scratch("simulate-rows");
    std::fs::create_dir_all(&dir).unwrap();
    let limit = bumpsim_core::files::MAX_INPUT_SAMPLES;
    // the rows are refused while read, before the (equal) times are checked
    let mut text = String::with_capacity(10 * limit);
    text.push_str("time [s],force [N]\n");
    for _ in 0..=limit {
        text.push_str("0,0\n");
    }
    let force = dir.join("long.csv");
    std::fs::write(&force, text).unwrap();
    let out = dir.join("r.csv");
    let car = root().join("examples/simulate/car-3dof.toml");
    let run = simulate(&car, &force, &["-o", out.to_str().unwrap()]);
    assert_user_error(
        &run,
        &format!("long.csv:{}: more than {limit} data rows", limit + 2),
    );
    assert!(!out.exists());
}
