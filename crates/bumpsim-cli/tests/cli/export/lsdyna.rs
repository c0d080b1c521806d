//! LS-DYNA includes of the MSD car: options, refusals, overflows, and
//! every deck through ansys-dyna-core.

use super::{dyna_core, dyna_core_available};
use crate::util::*;

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
    let force = example("pendulum-force.csv");
    let force = force.to_str().unwrap();
    let cases: [(&[&str], &str); 9] = [
        (&["--units", "imperial"], "expected si, mm-s-t or mm-ms-kg"),
        (
            &["--attach", "1001,1001", "--id-offset", "5000"],
            "attachment node 1001 is given twice",
        ),
        (
            &["--output-interval", "-1"],
            "output interval (--output-interval) = -1 s: expected finite and at least 1e-9 s",
        ),
        // 1e-308 s asked for 1e307 outputs; 1 s is beyond the 0.16 s force
        (
            &["--output-interval", "1e-308"],
            "output interval (--output-interval) = 1e-308 s: expected finite and at least 1e-9 s",
        ),
        (
            &["--force", force, "--output-interval", "1"],
            "output interval (--output-interval) = 1 s: expected at most the force's duration",
        ),
        (
            &["--force", force, "--output-interval", "1e-8"],
            "expected at least the force's duration / 1000000 = 1.6e-7 s",
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

/// Wave-2 hostile findings for `export lsdyna`: a force CSV whose time span
/// overflows panicked (exit 101); a force reaching 1e307 s was written as
/// `inf` ms with exit 0 (now refused as a CSV whose sampling interval lies
/// outside 1 ns..1 s, before the deck is built); `--min-time-step -1`
/// silently disabled the warning.
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
            "long.csv:3: the times give a sampling interval of 1e307 s",
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

/// Issue 33: with `--force` the car include's curve took id offset + 3n + 2,
/// beyond the documented k ≤ 3n + 1, so a bumper spring packed right after
/// it (offset 1010 + 3·3 + 1 = 1020) shared curve 1021. ansys-dyna-core
/// lists every id of both decks: within the documented range, none shared.
#[test]
fn includes_packed_by_the_documented_id_range_share_no_id() {
    if !dyna_core_available() {
        return;
    }
    let dir = scratch("lsdyna-id-range");
    let (car, force) = (example("car-3dof.toml"), example("pendulum-force.csv"));
    let deck = dir.join("car.k");
    let run = bumpsim(&[
        "export",
        "lsdyna",
        car.to_str().unwrap(),
        "-o",
        deck.to_str().unwrap(),
        "--force",
        force.to_str().unwrap(),
        "--output-interval",
        "0.1 ms",
        "--attach",
        "91,92",
        "--id-offset",
        "1010",
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let spring = dir.join("spring.k");
    let bumper = root().join("examples/impact/bumper-a.toml");
    let run = bumpsim(&[
        "export",
        "bumper",
        bumper.to_str().unwrap(),
        "--solver",
        "lsdyna",
        "-o",
        spring.to_str().unwrap(),
        "--id-offset",
        "1020",
        "--nodes",
        "91,1011",
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let (car_ids, spring_ids) = (
        dyna_core(&deck, &["91", "92"])["ids"].clone(),
        dyna_core(&spring, &["91", "1011"])["ids"].clone(),
    );
    let ids = |v: &serde_json::Value, kind: &str| -> Vec<u64> {
        v[kind]
            .as_array()
            .unwrap()
            .iter()
            .map(|i| i.as_u64().unwrap())
            .collect()
    };
    assert_eq!(ids(&car_ids, "curve"), [1020], "{car_ids}");
    for kind in [
        "node", "element", "part", "section", "material", "node set", "curve",
    ] {
        let mine = ids(&car_ids, kind);
        assert!(
            mine.iter().all(|&i| (1011..=1020).contains(&i)),
            "{kind}: {mine:?}"
        );
        let shared: Vec<u64> = ids(&spring_ids, kind)
            .into_iter()
            .filter(|i| mine.contains(i))
            .collect();
        assert!(shared.is_empty(), "{kind} ids in both includes: {shared:?}");
    }
}
