//! `bumpsim export`: CalculiX and LS-DYNA decks.

use std::process::Command;

use crate::util::*;

/// Whether CalculiX's `ccx` is available (required under `BUMPSIM_REQUIRE_PEERS`).
fn ccx_available() -> bool {
    peer_available("ccx (calculix-ccx)", "sh", &["-c", "command -v ccx"])
}

/// Runs `ccx JOB` in `dir`; fails unless it ends cleanly; returns its log.
fn run_ccx(dir: &std::path::Path, job: &str) -> String {
    let run = Command::new("ccx")
        .arg(job)
        .current_dir(dir)
        .output()
        .unwrap();
    let log = text(&run.stdout);
    assert!(
        run.status.success() && !log.contains("*ERROR"),
        "{job}: {log}"
    );
    log
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
    run_ccx(&dir, "car");
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

/// Whether python3 with ansys-dyna-core is available.
pub(crate) fn dyna_core_available() -> bool {
    peer_available(
        "ansys-dyna-core",
        "python3",
        &["-c", "import ansys.dyna.core"],
    )
}

/// The verdict of tests/peers/dyna_deck.py on a deck.
pub(crate) fn dyna_core(deck: &std::path::Path, external: &[&str]) -> serde_json::Value {
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

/// ccx's equation count and the bumper's lateral displacements (nodes 2, 3)
/// of `main.inp` in `dir` with `include` pasted before the step.
fn bumper_under_lateral_load(
    dir: &std::path::Path,
    name: &str,
    include: &str,
) -> (usize, Vec<f64>) {
    let deck = format!(
        "*NODE, NSET=Nall\n1, 0.0, 0.0, 0.0\n2, 0.0, 1.0, 0.0\n3, 0.0, 2.0, 0.0\n\
         *ELEMENT, TYPE=SPRINGA, ELSET=Ebumper\n1, 1, 2\n2, 2, 3\n*SPRING, ELSET=Ebumper\n\n1000.0\n\
         *BOUNDARY\n1, 1, 3\nNall, 1, 1\nNall, 3, 3\n{include}\
         *STEP\n*STATIC\n*CLOAD\n3, 2, 10.0\n*NODE PRINT, NSET=Nall\nU\n*END STEP\n"
    );
    std::fs::write(dir.join(format!("{name}.inp")), deck).unwrap();
    let log = run_ccx(dir, name);
    let equations = log
        .split("number of equations")
        .nth(1)
        .and_then(|rest| rest.split_whitespace().next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("{name}: no equation count in {log}"));
    let dat = std::fs::read_to_string(dir.join(format!("{name}.dat"))).unwrap();
    let lateral = dat
        .lines()
        .map(|l| l.split_whitespace().collect::<Vec<_>>())
        .filter(|w| w.len() == 4 && (w[0] == "2" || w[0] == "3"))
        .map(|w| w[2].parse().unwrap())
        .collect();
    (equations, lateral)
}

#[test]
fn a_calculix_car_included_in_a_model_with_its_own_nall_leaves_that_model_alone() {
    if !ccx_available() {
        return;
    }
    let dir = scratch("calculix-include");
    let car = example("car-3dof.toml");
    let export = |prefix: &str| {
        let run = bumpsim(&[
            "export",
            "calculix",
            car.to_str().unwrap(),
            "-o",
            dir.join("car.inp").to_str().unwrap(),
            "--id-offset",
            "1000",
            "--initial-velocity",
            "1",
            "--prefix",
            prefix,
        ]);
        assert!(run.status.success(), "{}", text(&run.stderr));
    };
    // the bumper alone: two springs of 1000 N/m in y under 10 N
    let (alone, response) = bumper_under_lateral_load(&dir, "alone", "");
    assert_eq!(response.len(), 2);
    assert!(
        (response[0] - 0.01).abs() < 1e-9 && (response[1] - 0.02).abs() < 1e-9,
        "{response:?}"
    );
    // with the car included (its last mass grounded by the user: a static step)
    export("BUMPSIM_");
    let include = "*INCLUDE, INPUT=car.inp\n*BOUNDARY\n1003, 1, 1\n";
    let (with_car, response_with_car) = bumper_under_lateral_load(&dir, "with-car", include);
    assert_eq!(
        with_car,
        alone + 2,
        "the car adds its two free masses' x only"
    );
    assert_eq!(response_with_car.len(), 2);
    for (a, b) in response.iter().zip(&response_with_car) {
        assert!(
            (a - b).abs() <= 1e-12 * a.abs(),
            "{response:?} vs {response_with_car:?}"
        );
    }
    // control: without a prefix the car's set is NALL, the user's Nall: the
    // car's cross-axis constraints then hold the bumper, as before issue 16
    export("");
    let (clashed, clashed_response) = bumper_under_lateral_load(&dir, "clashed", include);
    assert!(clashed < with_car && clashed_response.iter().all(|u| u.abs() < 1e-12));
}

/// Wave-2 hostile findings for `export lsdyna`: a force CSV whose time span
/// overflows panicked (exit 101); a force reaching 1e307 s was written as
/// `inf` ms with exit 0; `--min-time-step -1` silently disabled the warning.
#[test]
fn lsdyna_force_and_time_step_overflows_are_user_errors() {
    let dir = scratch("export-overflow");
    let car = root().join("examples/simulate/car-3dof.toml");
    let out = dir.join("car.k");
    let force = |name: &str, rows: &str| {
        let path = dir.join(name);
        std::fs::write(&path, format!("time [s],force [N]\n{rows}")).unwrap();
        path
    };
    let span = force("span.csv", "-1e308,1\n1e308,1\n");
    let long = force("long.csv", "0,1\n1e307,2\n");
    let ok = force("ok.csv", "0,1\n0.001,2\n");
    let cases: [(Vec<&str>, &str); 3] = [
        (
            vec!["--force", span.to_str().unwrap()],
            "span.csv:3: time runs from -1e308 s to 1e308 s",
        ),
        (
            vec![
                "--force",
                long.to_str().unwrap(),
                "--standalone",
                "--units",
                "mm-ms-kg",
            ],
            "force sample 2",
        ),
        (
            vec!["--force", ok.to_str().unwrap(), "--min-time-step", "-1"],
            "--min-time-step '-1'",
        ),
    ];
    for (extra, needle) in cases {
        let mut args = vec![
            "export",
            "lsdyna",
            car.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ];
        args.extend_from_slice(&extra);
        let run = bumpsim(&args);
        assert_user_error(&run, needle);
        assert!(!out.exists(), "{extra:?} left a deck behind");
    }
}

/// Issue 16: the bumper characteristic as LS-DYNA MAT_S06 in every unit
/// system parses in ansys-dyna-core with its curves and ids defined, and
/// the curves are the characteristic in the deck's units.
#[test]
fn the_bumper_spring_deck_parses_in_ansys_dyna_core_in_every_unit_system() {
    if !dyna_core_available() {
        return;
    }
    let dir = scratch("bumper-spring-dyna");
    let bumper = root().join("examples/impact/bumper-a.toml"); // ramp 6e6, plateau 110e3, unloading 1.2e7
    for (units, length, force) in [
        ("si", 1.0, 1.0),
        ("mm-s-t", 1e3, 1.0),
        ("mm-ms-kg", 1e3, 1e-3),
    ] {
        let deck = dir.join(format!("bumper-{units}.k"));
        let run = bumpsim(&[
            "export",
            "bumper",
            bumper.to_str().unwrap(),
            "--solver",
            "lsdyna",
            "-o",
            deck.to_str().unwrap(),
            "--units",
            units,
            "--id-offset",
            "7000",
            "--nodes",
            "11,12",
        ]);
        assert!(run.status.success(), "{}", text(&run.stderr));
        let verdict = dyna_core(&deck, &["11", "12"]);
        assert_eq!(
            verdict["unprocessed"],
            serde_json::json!([]),
            "{units}: {verdict}"
        );
        assert_eq!(
            verdict["errors"],
            serde_json::json!([]),
            "{units}: {verdict}"
        );
        assert_eq!(
            verdict["undefined"],
            serde_json::json!([]),
            "{units}: {verdict}"
        );
        assert_eq!(verdict["strings"], 0, "{units}: {verdict}");
        let keywords = verdict["keywords"].to_string();
        assert!(
            keywords.contains("MatSpringGeneralNonlinear") && keywords.contains("ElementDiscrete")
        );
        let curve = |id: &str| -> Vec<(f64, f64)> {
            verdict["curves"][id]
                .as_array()
                .unwrap()
                .iter()
                .map(|p| (p[0].as_f64().unwrap(), p[1].as_f64().unwrap()))
                .collect()
        };
        // loading: knee at 110e3 / 6e6 m, plateau to 10 × the knee, zero in tension
        let (knee, plateau) = (110e3 / 6e6, 110e3);
        let loading = curve("7001");
        let expected = [
            (-10.0 * knee, -plateau),
            (-knee, -plateau),
            (0.0, 0.0),
            (10.0 * knee, 0.0),
        ];
        assert_eq!(loading.len(), expected.len(), "{units}: {loading:?}");
        for ((d, f), (ed, ef)) in loading.iter().zip(expected) {
            assert!(
                (d - ed * length).abs() <= 1e-9 * (ed * length).abs().max(1e-9),
                "{units}: {loading:?}"
            );
            assert!(
                (f - ef * force).abs() <= 1e-9 * (ef * force).abs().max(1e-9),
                "{units}: {loading:?}"
            );
        }
        // unloading: the line of slope 1.2e7 N/m from the plateau to 0
        let unloading = curve("7002");
        let slope = unloading[0].1 / force / (unloading[0].0 / length);
        assert!(
            (slope - 1.2e7).abs() <= 1e-6 * 1.2e7,
            "{units}: {unloading:?}"
        );
    }
}

/// Issue 16: bad bumper decks are user errors, and nothing is written.
#[test]
fn bumper_spring_and_calculix_attach_refuse_bad_input() {
    let dir = scratch("bumper-spring-bad");
    let falling = dir.join("falling.toml");
    std::fs::write(
        &falling,
        "curve = [[0.0, 0.0], [0.02, 5e4], [0.04, 3e4]]\nunloading = 1e7\n",
    )
    .unwrap();
    let out = dir.join("b.k");
    let run = bumpsim(&[
        "export",
        "bumper",
        falling.to_str().unwrap(),
        "--solver",
        "lsdyna",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_user_error(
        &run,
        "falling.toml: bumper curve point 3: the loading force falls (not monotone)",
    );
    assert!(!out.exists());
    let bumper = root().join("examples/impact/bumper-a.toml");
    let run = bumpsim(&[
        "export",
        "bumper",
        bumper.to_str().unwrap(),
        "--solver",
        "calculix",
        "-o",
        out.to_str().unwrap(),
        "--nodes",
        "5,5",
    ]);
    assert_user_error(&run, "attachment node 5 is given twice");
    let car = example("car-3dof.toml");
    let inp = dir.join("car.inp");
    for (attach, needle) in [
        ("7,7", "attachment node 7 is given twice"),
        (
            "1002",
            "attachment node 1002 clashes with the include's nodes 1001..1003",
        ),
        ("0", "attachment node 0 is not a valid node id"),
    ] {
        let run = bumpsim(&[
            "export",
            "calculix",
            car.to_str().unwrap(),
            "-o",
            inp.to_str().unwrap(),
            "--id-offset",
            "1000",
            "--attach",
            attach,
        ]);
        assert_user_error(&run, needle);
        assert!(!inp.exists());
    }
}

/// Issue 16: the CalculiX bumper spring, run in ccx with a rigid car of
/// 1500 kg striking a fixed node at 4 m/s, reaches the largest compression
/// of `bumpsim impact` with the same characteristic within 1 % (loading is
/// the same curve; CalculiX's spring then unloads elastically along it).
#[test]
fn the_calculix_bumper_spring_reaches_impacts_largest_compression() {
    if !ccx_available() {
        return;
    }
    let dir = scratch("bumper-spring-ccx");
    let bumper = root().join("examples/impact/bumper-b.toml");
    let spring = dir.join("spring.inp");
    let run = bumpsim(&[
        "export",
        "bumper",
        bumper.to_str().unwrap(),
        "--solver",
        "calculix",
        "-o",
        spring.to_str().unwrap(),
        "--nodes",
        "1,2",
        "--id-offset",
        "10",
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let car = dir.join("rigid.toml");
    std::fs::write(&car, "masses = [1500.0]\ndampers = []\nsprings = []\n").unwrap();
    let json = dir.join("impact.json");
    let run = bumpsim(&[
        "impact",
        "--car",
        car.to_str().unwrap(),
        "--bumper",
        bumper.to_str().unwrap(),
        "--barrier",
        "--speed",
        "4",
        "--json",
        json.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let impact: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let expected = impact["max_compression"].as_f64().unwrap();
    // node 1: the barrier (fixed); node 2: the car 1 m behind it, moving at it
    let main = "*NODE, NSET=ALL\n1, 0.0, 0.0, 0.0\n2, 1.0, 0.0, 0.0\n*INCLUDE, INPUT=spring.inp\n\
        *ELEMENT, TYPE=MASS, ELSET=CAR\n20, 2\n*MASS, ELSET=CAR\n1500.0\n\
        *BOUNDARY\n1, 1, 3\n2, 2, 3\n*INITIAL CONDITIONS, TYPE=VELOCITY\n2, 1, -4.0\n\
        *STEP, INC=10000\n*DYNAMIC, DIRECT\n1.0e-4, 0.12\n*NODE PRINT, NSET=ALL\nU\n*END STEP\n";
    std::fs::write(dir.join("main.inp"), main).unwrap();
    let ccx = Command::new("ccx")
        .args(["-i", "main"])
        .current_dir(&dir)
        .env("OMP_NUM_THREADS", "1")
        .output()
        .unwrap();
    assert!(ccx.status.success(), "{}", text(&ccx.stdout));
    let dat = std::fs::read_to_string(dir.join("main.dat")).unwrap();
    let largest = dat
        .lines()
        .map(|l| l.split_whitespace().collect::<Vec<_>>())
        .filter(|w| w.len() == 4 && w[0] == "2")
        .map(|w| -w[1].parse::<f64>().unwrap())
        .fold(0.0, f64::max);
    assert!(
        (largest - expected).abs() <= 0.01 * expected,
        "ccx {largest} m vs impact {expected} m"
    );
}

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
        (["--increment", "1e-300"], "choose a larger --increment"),
    ] {
        let mut args = vec!["--solver", "calculix", "-o", out, "--force", force];
        args.extend_from_slice(&extra);
        assert_user_error(&export_planar(&args), needle);
    }
    assert!(
        !std::path::Path::new(out).exists(),
        "no deck after a refusal"
    );
}
