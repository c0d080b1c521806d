//! `bumpsim export`: CalculiX and LS-DYNA decks.

use std::process::Command;

use crate::util::*;

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
    let cases: [(&[&str], &str); 6] = [
        (&["--units", "imperial"], "expected si, mm-s-t or mm-ms-kg"),
        (
            &["--attach", "1001,1001", "--id-offset", "5000"],
            "attachment node 1001 is given twice",
        ),
        (
            &["--output-interval", "-1"],
            "time increment -1 s must be positive",
        ),
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

/// Whether python3 with ansys-dyna-core is available (required under
/// `BUMPSIM_REQUIRE_PEERS`).
fn dyna_core_available() -> bool {
    let found = Command::new("python3")
        .args(["-c", "import ansys.dyna.core"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !found {
        assert!(
            std::env::var_os("BUMPSIM_REQUIRE_PEERS").is_none(),
            "BUMPSIM_REQUIRE_PEERS is set but python3 cannot import ansys.dyna.core"
        );
        eprintln!("skipped: ansys-dyna-core not found (scripts/test installs it)");
    }
    found
}

/// The verdict of tests/peers/dyna_deck.py on a deck.
fn dyna_core(deck: &std::path::Path, external: &[&str]) -> serde_json::Value {
    let run = Command::new("python3")
        .arg(root().join("tests/peers/dyna_deck.py"))
        .arg(deck)
        .args(external)
        .output()
        .unwrap();
    assert!(run.status.success(), "dyna_deck.py: {}", text(&run.stderr));
    serde_json::from_slice(&run.stdout).unwrap()
}

#[test]
fn every_lsdyna_deck_parses_in_ansys_dyna_core_with_its_ids_defined() {
    if !dyna_core_available() {
        return;
    }
    let dir = scratch("lsdyna-dyna-core");
    let one = dir.join("rigid.toml");
    std::fs::write(&one, "masses = [1050.0]\ndampers = []\nsprings = []\n").unwrap();
    let (car, force) = (example("car-3dof.toml"), example("pendulum-force.csv"));
    let (force_path, car_path, one_path) = (
        force.to_str().unwrap(),
        car.to_str().unwrap(),
        one.to_str().unwrap(),
    );
    // the example force: time [ms], force [kN] after a comment and the header
    let csv = std::fs::read_to_string(&force).unwrap();
    let rows: Vec<(f64, f64)> = csv
        .lines()
        .filter(|l| !l.starts_with('#'))
        .skip(1)
        .map(|l| l.split_once(',').unwrap())
        .map(|(t, f)| {
            (
                t.parse::<f64>().unwrap() * 1e-3,
                f.parse::<f64>().unwrap() * 1e3,
            )
        })
        .collect();
    let seconds: Vec<f64> = rows.iter().map(|r| r.0).collect();
    let newtons: Vec<f64> = rows.iter().map(|r| r.1).collect();
    let full: &[&str] = &[
        "--force",
        force_path,
        "--output-interval",
        "0.1 ms",
        "--standalone",
        "--attach",
        "91,92",
        "--id-offset",
        "100",
        "--initial-velocity",
        "2",
    ];
    // (units, time factor, force factor) of the deck against SI
    for (units, time, newton) in [
        ("si", 1.0, 1.0),
        ("mm-s-t", 1.0, 1.0),
        ("mm-ms-kg", 1e3, 1e-3),
    ] {
        for (name, model, extra) in [
            ("car", car_path, &[][..]),
            ("full", car_path, full),
            ("rigid", one_path, full),
        ] {
            let deck = dir.join(format!("{name}-{units}.k"));
            let mut args = vec![
                "export",
                "lsdyna",
                model,
                "-o",
                deck.to_str().unwrap(),
                "--units",
                units,
            ];
            args.extend_from_slice(extra);
            let run = bumpsim(&args);
            assert!(
                run.status.success(),
                "{name} {units}: {}",
                text(&run.stderr)
            );
            let verdict = dyna_core(&deck, &["91", "92"]);
            let what = format!("{name} {units}: {verdict}");
            assert_eq!(verdict["unprocessed"], serde_json::json!([]), "{what}");
            assert_eq!(verdict["strings"], 0, "{what}");
            assert_eq!(verdict["errors"], serde_json::json!([]), "{what}");
            assert_eq!(verdict["undefined"], serde_json::json!([]), "{what}");
            let dof = if name == "rigid" { 1 } else { 3 };
            assert_eq!(
                verdict["mass_nodes"].as_array().unwrap().len(),
                dof,
                "{what}"
            );
            let curve = verdict["curve"].as_array().unwrap();
            if name == "car" {
                assert!(curve.is_empty(), "{what}");
                continue;
            }
            assert_eq!(
                verdict["history_nodes"].as_array().unwrap().len(),
                dof,
                "{what}"
            );
            assert_eq!(curve.len(), newtons.len(), "{what}");
            let peak = newtons.iter().fold(0.0f64, |a, f| a.max(f.abs()));
            for (k, point) in curve.iter().enumerate() {
                let (t, f) = (point[0].as_f64().unwrap(), point[1].as_f64().unwrap());
                assert!(
                    (t - time * (seconds[k] - seconds[0])).abs() < 1e-9 * time,
                    "{what}: t[{k}]"
                );
                assert!(
                    (f - newton * newtons[k]).abs() < 1e-6 * newton * peak,
                    "{what}: F[{k}]"
                );
            }
            let deck_text = std::fs::read_to_string(&deck).unwrap();
            assert!(deck_text.contains("*CONTROL_TERMINATION"), "{what}");
            assert_eq!(deck_text.contains("*SECTION_DISCRETE"), dof > 1, "{what}");
        }
    }
}
