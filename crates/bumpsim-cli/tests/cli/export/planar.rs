//! `bumpsim export planar`: the planar car's LS-DYNA include and
//! CalculiX deck, and hostile input.

use super::{ccx_available, dyna_core, dyna_core_available, run_ccx};
use crate::util::*;
use std::path::Path;

/// The bundled planar car.
fn saloon() -> std::path::PathBuf {
    root().join("examples/planar/saloon.toml")
}

/// `bumpsim export planar SALOON` with `args`.
fn export_planar(args: &[&str]) -> std::process::Output {
    let car = saloon();
    let mut all = vec!["export", "planar", car.to_str().unwrap()];
    all.extend_from_slice(args);
    bumpsim(&all)
}

#[test]
fn export_planar_include_parses_and_calculix_deck_runs() {
    let dir = scratch("export-planar");
    let (k, inp) = (dir.join("planar.k"), dir.join("planar.inp"));
    let force = example("pendulum-force.csv");
    let common = [
        "--force",
        force.to_str().unwrap(),
        "--lateral",
        "300 mm",
        "--direction",
        "-0.94,0.34",
        "--units",
        "mm-s-t",
        "--attach-left",
        "101,102",
        "--attach-right",
        "201",
        "--initial-velocity",
        "8 km/h",
    ];
    let mut args = vec!["--solver", "lsdyna", "-o", k.to_str().unwrap()];
    args.extend_from_slice(&common);
    args.extend_from_slice(&["--id-offset", "900000", "--output-interval", "0.1 ms"]);
    let run = export_planar(&args);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert_contains(
        &text(&run.stdout),
        &[
            "LS-DYNA include of the planar car, 2 chain masses, ids from 900001",
            "units mm-s-t",
        ],
    );
    if dyna_core_available() {
        let verdict = dyna_core(&k, &["101", "102", "201"]);
        for empty in ["unprocessed", "errors", "undefined"] {
            assert_eq!(verdict[empty], serde_json::json!([]), "{empty}: {verdict}");
        }
        assert_eq!(verdict["strings"], 0, "{verdict}");
    }
    // dense ids: ccx sizes its arrays by the largest node id
    let mut args = vec!["--solver", "calculix", "-o", inp.to_str().unwrap()];
    args.extend_from_slice(&common);
    args.extend_from_slice(&["--id-offset", "1000", "--output-every", "10"]);
    let run = export_planar(&args);
    assert!(run.status.success(), "{}", text(&run.stderr));
    if !ccx_available() {
        return;
    }
    // the user's attachment nodes: free nodes of a main deck that includes the car
    let main = "*NODE\n101, 0.0, 500.0, 0.0\n102, 0.0, 400.0, 0.0\n201, 0.0, -500.0, 0.0\n*BOUNDARY\n101, 3, 3\n102, 3, 3\n201, 3, 3\n*INCLUDE, INPUT=planar.inp\n";
    std::fs::write(dir.join("main.inp"), main).unwrap();
    run_ccx(&dir, "main");
    let dat = std::fs::read_to_string(dir.join("main.dat")).unwrap();
    // a displacement block every 10 increments: 1601 samples, 0.1 ms apart
    assert_eq!(
        dat.matches("displacements (vx,vy,vz) for set BUMPSIM_NOUT")
            .count(),
        160
    );
}

#[test]
fn export_planar_refuses_hostile_input_naming_the_parameter() {
    let dir = scratch("export-planar-hostile");
    let out = dir.join("out.k");
    let out = out.to_str().unwrap();
    let bad_car = |name: &str, from: &str, to: &str| {
        let path = dir.join(name);
        let text = std::fs::read_to_string(saloon())
            .unwrap()
            .replacen(from, to, 1);
        std::fs::write(&path, text).unwrap();
        path
    };
    let nan = bad_car("nan.toml", "mass = 1300.0", "mass = nan");
    let negative = bad_car(
        "negative.toml",
        "yaw_inertia = 2200.0",
        "yaw_inertia = -2200.0",
    );
    for (car, needle) in [
        (&nan, "body.mass = NaN"),
        (&negative, "body.yaw_inertia = -2200"),
    ] {
        let run = bumpsim(&[
            "export",
            "planar",
            car.to_str().unwrap(),
            "--solver",
            "lsdyna",
            "-o",
            out,
        ]);
        assert_user_error(&run, needle);
    }
    let csv = dir.join("nan.csv");
    std::fs::write(&csv, "time [s],force [N]\n0.0,0.0\n0.001,nan\n0.002,0.0\n").unwrap();
    let csv = csv.to_str().unwrap();
    let car = saloon();
    let car = car.to_str().unwrap();
    let cases: &[(&[&str], &str)] = &[
        (&["--solver", "calculix", "-o", out, "--force", csv], "nan"),
        (
            &["--solver", "lsdyna", "-o", car],
            "would overwrite the input",
        ),
        (
            &["--solver", "lsdyna", "-o", out, "--attach-left", "3"],
            "clashes with the include's nodes",
        ),
        (
            &[
                "--solver",
                "calculix",
                "-o",
                out,
                "--id-offset",
                "10",
                "--attach-left",
                "7",
                "--attach-right",
                "7",
            ],
            "node 7 is given twice",
        ),
        (
            &["--solver", "lsdyna", "-o", out, "--id-offset", "99999990"],
            "8-column",
        ),
        (
            &[
                "--solver",
                "calculix",
                "-o",
                out,
                "--id-offset",
                "2147483640",
            ],
            "CalculiX 32-bit id limit",
        ),
        (
            &[
                "--solver",
                "lsdyna",
                "-o",
                out,
                "--units",
                "mm-s-t",
                "--origin",
                "1e307,0,0",
            ],
            "does not fit the deck's units",
        ),
        (
            &["--solver", "lsdyna", "-o", out, "--spacing", "-5 mm"],
            "--spacing",
        ),
        (
            &["--solver", "calculix", "-o", out, "--prefix", "1 BAD"],
            "name prefix",
        ),
        (
            &["--solver", "calculix", "-o", out, "--output-every", "0"],
            "at least 1 increment",
        ),
    ];
    for (args, needle) in cases {
        assert_user_error(&export_planar(args), needle);
    }
    let force = example("pendulum-force.csv");
    let force = force.to_str().unwrap();
    for (extra, needle) in [
        (["--direction", "0,0"], "load[0].direction"),
        (["--direction", "a,b"], "--direction 'a,b'"),
        (["--lateral", "nan"], "--lateral"),
        (
            ["--increment", "1e-300"],
            "increment = 1e-300 s: expected finite and at least 1e-9 s",
        ),
        // beyond the force: a deck whose one increment overshoots its loads
        (
            ["--increment", "1"],
            "expected at most the force's duration",
        ),
    ] {
        let mut args = vec!["--solver", "calculix", "-o", out, "--force", force];
        args.extend_from_slice(&extra);
        assert_user_error(&export_planar(&args), needle);
    }
    for interval in ["1e-308", "1e308"] {
        let args = [
            "--solver",
            "lsdyna",
            "-o",
            out,
            "--force",
            force,
            "--output-interval",
            interval,
        ];
        assert_user_error(
            &export_planar(&args),
            "output interval (--output-interval) = ",
        );
    }
    assert!(
        !std::path::Path::new(out).exists(),
        "no deck after a refusal"
    );
}

/// A flag the chosen solver's deck has no use for did nothing with exit 0.
#[test]
fn export_planar_and_bumper_refuse_flags_of_the_other_solver() {
    let dir = scratch("export-other-solver");
    let out = dir.join("out.k");
    let out = out.to_str().unwrap();
    let force = root().join("examples/simulate/pendulum-force.csv");
    let force = force.to_str().unwrap();
    let cases: &[(&[&str], &str)] = &[
        (
            &["--solver", "lsdyna", "--increment", "1e-4"],
            "--increment applies to --solver calculix only",
        ),
        (
            &["--solver", "lsdyna", "--prefix", "X_"],
            "--prefix applies to --solver calculix only",
        ),
        (
            &["--solver", "lsdyna", "--output-every", "2"],
            "--output-every applies to --solver calculix only",
        ),
        (
            &["--solver", "calculix", "--output-interval", "1e-4"],
            "--output-interval applies to --solver lsdyna only",
        ),
    ];
    for (flags, needle) in cases {
        let run = export_planar(&[&["-o", out, "--force", force], *flags].concat());
        assert_user_error(&run, needle);
        assert!(!Path::new(out).exists(), "{flags:?}");
    }
    let bumper = root().join("examples/impact/bumper-a.toml");
    let spring = |solver: &str| {
        let args = [
            "export",
            "bumper",
            bumper.to_str().unwrap(),
            "--solver",
            solver,
        ];
        bumpsim(&[&args[..], &["--prefix", "X_", "-o", out]].concat())
    };
    assert_user_error(
        &spring("lsdyna"),
        "--prefix applies to --solver calculix only",
    );
    assert!(!Path::new(out).exists());
    let run = spring("calculix");
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(std::fs::read_to_string(out).unwrap().contains("X_BUMPER"));
}
