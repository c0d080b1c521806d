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
