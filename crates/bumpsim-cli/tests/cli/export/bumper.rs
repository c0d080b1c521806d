//! `bumpsim export bumper`: the bumper characteristic as a nonlinear
//! spring for LS-DYNA (ansys-dyna-core) and CalculiX (run in ccx).

use std::process::Command;

use super::{ccx_available, dyna_core, dyna_core_available};
use crate::util::*;

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
