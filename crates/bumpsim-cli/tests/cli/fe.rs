//! `bumpsim fe impact`: the bumper mesh coupled to the car, run in CalculiX
//! by the real binary (pendulum here; barrier cases in bumpsim-fe's tests),
//! and its hostile inputs.

use crate::util::*;

fn ccx_available() -> bool {
    peer_available("ccx (calculix-ccx)", "sh", &["-c", "command -v ccx"])
}

fn fe(args: &[&str]) -> std::process::Output {
    let mut all = vec!["fe", "impact"];
    all.extend_from_slice(args);
    bumpsim(&all)
}

/// A 1000 kg pendulum at 2.2 m/s on the bundled car with the elastic mesh:
/// summary with units, JSON, CSV and report; the FE peak force within 2 %
/// and the largest compression within 4 % of `impact` with the equivalent
/// spring (the beam's own 5.5 kg sits between face and spring here), energy
/// closed within 2 %.
#[test]
fn a_pendulum_run_in_calculix_writes_the_impact_results() {
    if !ccx_available() {
        return;
    }
    let dir = scratch("fe-pendulum");
    let (car, mesh) = (
        root().join("examples/identify/car-truth.toml"),
        root().join("examples/fe/bumper-elastic.toml"),
    );
    let (json, csv, report, work) = (
        dir.join("fe.json"),
        dir.join("fe.csv"),
        dir.join("report"),
        dir.join("work"),
    );
    let run = fe(&[
        "--car",
        car.to_str().unwrap(),
        "--bumper",
        mesh.to_str().unwrap(),
        "--pendulum",
        "1000",
        "--speed",
        "7.92 km/h",
        "--work",
        work.to_str().unwrap(),
        "--json",
        json.to_str().unwrap(),
        "--csv",
        csv.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
    ]);
    let out = text(&run.stdout);
    assert!(run.status.success(), "{out}{}", text(&run.stderr));
    assert_contains(
        &out,
        &[
            "1000 kg pendulum",
            "peak force",
            " kN",
            "maximum compression",
            " mm",
            "equivalent characteristic",
        ],
    );
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let get = |k: &str| v[k].as_f64().unwrap();
    let eq = |k: &str| v["equivalent"][k].as_f64().unwrap();
    assert!(
        (get("peak_force") - eq("peak_force")).abs() <= 0.02 * eq("peak_force"),
        "{v}"
    );
    assert!(
        (get("max_compression") - eq("max_compression")).abs() <= 0.04 * eq("max_compression"),
        "{v}"
    );
    assert!(
        v["energy"]["relative_error"].as_f64().unwrap() < 0.02,
        "{v}"
    );
    assert!(get("peak_force_unfiltered") >= get("peak_force"));
    // issue 33: the 1-D model rated against the FE run (ISO/TS 18571)
    for what in ["force", "compression"] {
        let rating = &v["ratings"][what];
        let overall = rating["overall"].as_f64().unwrap_or(0.0);
        assert!(overall > 0.8 && overall <= 1.0, "{what}: {v}");
        assert!(rating["corridor"].is_number() && rating["slope"].is_number());
        assert_contains(
            &out,
            &[&format!(
                "ISO/TS 18571 rating of the 1-D model's {what} against FE: 0."
            )],
        );
    }
    let (header, rows) = read_csv(&csv);
    assert_eq!(header[..3], ["time [s]", "force [N]", "compression [m]"]);
    assert!(header.iter().any(|h| h == "x impactor [m]") && rows.len() > 100);
    let html = std::fs::read_to_string(report.join("index.html")).unwrap();
    assert!(html.contains("<svg") && html.contains("ISO/TS 18571 rating"));
    // the page lists its inputs and says why the force starts above zero
    assert!(
        html.contains("<h2>Inputs</h2>")
            && html.contains("bumper-elastic.toml")
            && html.contains("k_contact · v · Δt"),
        "inputs section and the note on the force at t = 0"
    );
    assert!(work.join("bumper.inp").exists() && work.join("bumper.dat").exists());
}

/// Hostile inputs: exit 2 with the parameter or file named, before
/// CalculiX runs.
#[test]
fn bad_fe_input_is_a_user_error() {
    let dir = scratch("fe-bad");
    let car = root().join("examples/identify/car-truth.toml");
    let good = std::fs::read_to_string(root().join("examples/fe/bumper-elastic.toml")).unwrap();
    let write = |name: &str, text: &str| {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        path
    };
    let wall = write("wall.toml", &good.replace("wall = 0.0015", "wall = 0.05"));
    let nan = write(
        "nan.toml",
        &good.replace("youngs_modulus = 3.2e8", "youngs_modulus = nan"),
    );
    let huge = write(
        "huge.toml",
        &good.replace("elements = 6", "elements = 100000000000"),
    );
    let plastic = std::fs::read_to_string(root().join("examples/fe/bumper-plastic.toml")).unwrap();
    let three = write(
        "three.toml",
        &plastic.replace("[40e6, 0.0]", "[40e6, 0.0, 1.0]"),
    );
    let mesh = root().join("examples/fe/bumper-elastic.toml");
    let work = dir.join("work");
    let (c, w) = (car.to_str().unwrap(), work.to_str().unwrap());
    let m3 = three.to_str().unwrap();
    let cases: Vec<(Vec<&str>, String)> = vec![
        (
            vec![
                "--bumper",
                wall.to_str().unwrap(),
                "--barrier",
                "--speed",
                "2",
            ],
            "crash_boxes.section.wall (m) = 0.05".into(),
        ),
        (
            vec![
                "--bumper",
                nan.to_str().unwrap(),
                "--barrier",
                "--speed",
                "2",
            ],
            "crash_boxes.material.youngs_modulus (Pa) = NaN".into(),
        ),
        (
            vec![
                "--bumper",
                huge.to_str().unwrap(),
                "--barrier",
                "--speed",
                "2",
            ],
            "beam.elements".into(),
        ),
        (
            vec![
                "--bumper",
                mesh.to_str().unwrap(),
                "--barrier",
                "--speed",
                "nan",
            ],
            "--speed 'nan'".into(),
        ),
        (
            vec![
                "--bumper",
                mesh.to_str().unwrap(),
                "--barrier",
                "--speed",
                "2",
                "--increment",
                "1e-300",
            ],
            "increments (duration / increment)".into(),
        ),
        (
            vec![
                "--bumper",
                mesh.to_str().unwrap(),
                "--barrier",
                "--speed",
                "2",
                "--solver",
                "/nonexistent/ccx",
            ],
            "/nonexistent/ccx: cannot start".into(),
        ),
        (
            vec![
                "--bumper",
                mesh.to_str().unwrap(),
                "--pendulum",
                "-5",
                "--speed",
                "2",
            ],
            "pendulum mass (kg) = -5".into(),
        ),
        // without the estimate (a given duration) a zero speed gave NaN energies
        (
            vec![
                "--bumper",
                mesh.to_str().unwrap(),
                "--barrier",
                "--speed",
                "0",
                "--duration",
                "0.1",
            ],
            "speed (m/s) = 0: expected positive and finite".into(),
        ),
        // issue 34: the ranges every impact keeps, and a point of three values
        (
            vec![
                "--bumper",
                mesh.to_str().unwrap(),
                "--barrier",
                "--speed",
                "1e-300",
                "--duration",
                "0.1",
            ],
            "speed (m/s) = 1e-300: from 0.001 to 1000 m/s".into(),
        ),
        (
            vec!["--bumper", m3, "--barrier", "--speed", "2"],
            "three.toml: TOML parse error at line 28".into(),
        ),
    ];
    for (extra, needle) in cases {
        let mut args = vec!["--car", c, "--work", w];
        args.extend_from_slice(&extra);
        let run = fe(&args);
        assert_user_error(&run, &needle);
    }
    // the work folder may not be an input's folder
    // a work folder with the user's files in it (here the inputs' own
    // folder) is refused: the run would write next to them
    let examples = root().join("examples/fe");
    let (m, e) = (mesh.to_str().unwrap(), examples.to_str().unwrap());
    let run = fe(&[
        "--car",
        c,
        "--bumper",
        m,
        "--barrier",
        "--speed",
        "2",
        "--work",
        e,
    ]);
    assert_user_error(&run, "which is not a file of a previous run");
    assert!(!examples.join("bumper.inp").exists());
}

/// The coupled model as LS-DYNA decks (barrier and pendulum, three unit
/// systems) parses in ansys-dyna-core: every keyword processed, validate()
/// clean, every node, part, section, material and set referenced defined.
#[test]
fn the_coupled_lsdyna_decks_parse_in_ansys_dyna_core() {
    if !crate::export::dyna_core_available() {
        return;
    }
    let dir = scratch("fe-lsdyna");
    let car = root().join("examples/identify/car-truth.toml");
    let mesh = root().join("examples/fe/bumper-plastic.toml");
    for units in ["si", "mm-s-t", "mm-ms-kg"] {
        for (case, striker) in [
            (vec!["--barrier"], "RigidwallPlanar"),
            (vec!["--pendulum", "1000"], "RigidwallPlanarMoving"),
        ] {
            let deck = dir.join(format!("fe-{units}-{striker}.k"));
            let mut args = vec![
                "fe",
                "lsdyna",
                "--car",
                car.to_str().unwrap(),
                "--bumper",
                mesh.to_str().unwrap(),
                "--speed",
                "8 km/h",
                "--units",
                units,
                "-o",
                deck.to_str().unwrap(),
            ];
            args.extend_from_slice(&case);
            let run = bumpsim(&args);
            assert!(run.status.success(), "{}", text(&run.stderr));
            assert_contains(&text(&run.stdout), &["termination", " ms"]);
            let v = crate::export::dyna_core(&deck, &[]);
            for key in ["unprocessed", "errors", "undefined"] {
                assert_eq!(
                    v[key],
                    serde_json::json!([]),
                    "{units} {striker} {key}: {v}"
                );
            }
            assert_eq!(v["strings"], 0, "{v}");
            let keywords: Vec<&str> = v["keywords"]
                .as_array()
                .unwrap()
                .iter()
                .map(|k| k.as_str().unwrap())
                .collect();
            for needed in [
                striker,
                "ElementBeam",
                "SectionBeam",
                "MatResultantPlasticity",
                "ConstrainedNodalRigidBodySpc",
                "ControlTermination",
                "DatabaseRwforc",
            ] {
                assert!(
                    keywords.contains(&needed),
                    "{units}: no {needed} in {keywords:?}"
                );
            }
        }
    }
}

/// A stand-in for CalculiX: writes part of its results, waits `seconds`,
/// then exits with `status` (no ccx needed).
fn fake_solver(dir: &std::path::Path, seconds: f64, status: i32) -> std::path::PathBuf {
    use std::os::unix::fs::PermissionsExt;
    let path = dir.join(format!("fake-ccx-{status}.sh"));
    let script = format!(
        "#!/bin/sh\necho ' displacements (vx,vy,vz) for set BUMPSIM_NALL and time  0.1' > bumper.dat\necho 'half a run' > bumper.frd\nsleep {seconds}\n[ {status} = 0 ] || echo '*ERROR in the fake solver'\nexit {status}\n"
    );
    std::fs::write(&path, script).unwrap();
    std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o755)).unwrap();
    path
}

/// Every entry of `dir` with its content (files) or `/` (folders), hidden
/// ones included.
fn listing(dir: &std::path::Path) -> Vec<(String, Vec<u8>)> {
    let mut all: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .map(|e| {
            let name = e.file_name().to_string_lossy().into_owned();
            (
                name,
                std::fs::read(e.path()).unwrap_or_else(|_| b"/".to_vec()),
            )
        })
        .collect();
    all.sort();
    all
}

/// Issue 34: `fe impact` wrote its deck and CalculiX's files straight into
/// --work, outside the command's transaction. A failing solver, results it
/// cannot read, or a kill mid-run now leave the work folder (and every
/// other output) as it was; the run works in a hidden staging folder.
#[test]
fn a_failed_or_killed_run_leaves_the_work_folder_as_it_was() {
    let dir = scratch("fe-transaction");
    let car = root().join("examples/identify/car-truth.toml");
    let mesh = root().join("examples/fe/bumper-elastic.toml");
    let (work, json) = (dir.join("work"), dir.join("fe.json"));
    std::fs::create_dir_all(&work).unwrap();
    std::fs::write(work.join("bumper.dat"), "the previous run's results\n").unwrap();
    let before = (listing(&dir), listing(&work));
    let args = |solver: &std::path::Path| -> Vec<String> {
        let mut all = vec!["fe", "impact", "--car", car.to_str().unwrap()];
        all.extend(["--bumper", mesh.to_str().unwrap(), "--barrier"]);
        all.extend(["--speed", "2", "--duration", "0.05", "--work"]);
        all.extend([work.to_str().unwrap(), "--json", json.to_str().unwrap()]);
        all.extend(["--solver", solver.to_str().unwrap()]);
        all.into_iter().map(String::from).collect()
    };
    // the solver fails: its output is quoted, nothing is left
    let failing = fake_solver(&dir, 0.0, 3);
    let run = bumpsim(
        &args(&failing)
            .iter()
            .map(String::as_str)
            .collect::<Vec<_>>(),
    );
    assert_user_error(&run, "*ERROR in the fake solver");
    assert_user_error(&run, "the work folder is left as it was");
    // the solver ends well, its results do not read: nothing is left
    let garbled = fake_solver(&dir, 0.0, 0);
    let run = bumpsim(
        &args(&garbled)
            .iter()
            .map(String::as_str)
            .collect::<Vec<_>>(),
    );
    assert_user_error(&run, "bumper.dat");
    let mut after = (listing(&dir), listing(&work));
    after.0.retain(|(name, _)| !name.starts_with("fake-ccx"));
    assert_eq!(after, before, "a failed run changed the outputs");
    // killed mid-run: the old work folder, no output, no staging left visible
    let slow = fake_solver(&dir, 3.0, 0);
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_bumpsim"))
        .args(args(&slow))
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    // kill once the solver has written part of its results (in staging)
    let solving = || {
        std::fs::read_dir(&dir).unwrap().flatten().any(|e| {
            let name = e.file_name().to_string_lossy().into_owned();
            name.starts_with(".work.") && e.path().join("bumper.frd").exists()
        })
    };
    let start = std::time::Instant::now();
    while !solving() && start.elapsed().as_secs() < 20 {
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    assert!(solving(), "the solver never started");
    child.kill().unwrap();
    child.wait().unwrap();
    assert_eq!(
        listing(&work),
        before.1,
        "a killed run changed the work folder"
    );
    assert!(!json.exists());
    let visible: Vec<String> = listing(&dir)
        .into_iter()
        .map(|(name, _)| name)
        .filter(|name| !name.starts_with('.') && !name.starts_with("fake-ccx"))
        .collect();
    assert_eq!(visible, ["work"]);
    // an output named like one of the run's files in --work is refused
    // before the run, not after it
    let mut clash = args(&slow);
    let at = clash.iter().position(|a| a == "--json").unwrap() + 1;
    clash[at] = work.join("bumper.inp").to_str().unwrap().to_string();
    let start = std::time::Instant::now();
    let run = bumpsim(&clash.iter().map(String::as_str).collect::<Vec<_>>());
    assert_user_error(&run, "the run writes a file of this name in --work");
    assert!(start.elapsed().as_secs_f64() < 2.5, "refused after the run");
    assert_eq!(listing(&work), before.1);
}

/// Issue 34, a hostile pass: `fe lsdyna --duration 1e308` wrote a deck
/// terminating at "inf ms", and an output interval of 1e-300 s or 1e308 s
/// or a 1e308 kg pendulum (the estimate skipped) made a deck with exit 0.
#[test]
fn lsdyna_decks_refuse_absurd_times_and_strikers() {
    let dir = scratch("fe-lsdyna-hostile");
    let car = root().join("examples/identify/car-truth.toml");
    let mesh = root().join("examples/fe/bumper-elastic.toml");
    let deck = dir.join("x.k");
    let cases: [(&[&str], &str); 6] = [
        (
            &["--barrier", "--duration", "1e308"],
            "duration (s) = 1e308",
        ),
        (
            &["--barrier", "--duration", "1e-308"],
            "duration (s) = 1e-308: expected from 1e-6 s (MIN_DURATION) to 100 s",
        ),
        (
            &[
                "--barrier",
                "--duration",
                "1",
                "--output-interval",
                "1e-300",
            ],
            "output intervals (duration / output interval)",
        ),
        (
            &["--barrier", "--duration", "1", "--output-interval", "1e308"],
            "at most the duration",
        ),
        (
            &["--pendulum", "1e308", "--duration", "1"],
            "impactor mass (kg) = 1e308",
        ),
        (
            &["--barrier", "--speed", "1e-300", "--duration", "1"],
            "speed (m/s) = 1e-300",
        ),
    ];
    for (extra, needle) in cases {
        let mut args = vec!["fe", "lsdyna", "--car", car.to_str().unwrap()];
        args.extend([
            "--bumper",
            mesh.to_str().unwrap(),
            "-o",
            deck.to_str().unwrap(),
        ]);
        if !extra.contains(&"--speed") {
            args.extend(["--speed", "2"]);
        }
        args.extend_from_slice(extra);
        assert_user_error(&bumpsim(&args), needle);
        assert!(!deck.exists(), "{needle}: a deck was written");
    }
}
