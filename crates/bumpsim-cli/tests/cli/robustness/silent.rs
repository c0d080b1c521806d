//! Silent acceptances of the hostile pass: input that ran with exit 0
//! (a junk EV5 file, a Sobol base that is not a power of two, ...) is
//! refused with exit 2 naming the file, line, key or flag and the value,
//! or the output says what it cannot compute.

use super::{examples, run_in, stderr, user_error};

/// Random bytes or an empty file named `.EV5` listed "0 channels".
#[test]
fn a_junk_or_empty_ev5_file_is_no_test() {
    let dir = examples("silent-ev5");
    let junk: Vec<u8> = (0..1000u32).map(|i| (i * 7919 % 251) as u8).collect();
    std::fs::write(dir.join("j.EV5"), junk).unwrap();
    std::fs::write(dir.join("e.EV5"), b"").unwrap();
    for file in ["j.EV5", "e.EV5"] {
        let needle = format!("{file}: not an NHTSA EV5 test");
        user_error(&dir, &["signal", "info", file], &needle);
    }
}

/// `--sobol-base 100` and `17` ran while the help says "a power of two":
/// the Sobol sequence is balanced only over 2^m points.
#[test]
fn a_sobol_base_between_powers_of_two_is_refused() {
    let dir = examples("silent-sobol-base");
    std::fs::write(
        dir.join("u.toml"),
        "[uncertainty]\n\"bumper.force\" = 0.1\n",
    )
    .unwrap();
    let verdict = [
        "verdict",
        "--car",
        "ex/verdict/car.toml",
        "--protocol",
        "rcar-bumper-corner-front",
        "--uncertainty",
        "ex/verdict/uncertainty.toml",
        "--samples",
        "10",
        "--sobol",
        "--sobol-base",
    ];
    let impact = [
        "impact",
        "--car",
        "ex/simulate/car-3dof.toml",
        "--bumper",
        "ex/impact/bumper-a.toml",
        "--barrier",
        "--speed",
        "2",
        "--uncertainty",
        "u.toml",
        "--sobol",
        "--sobol-base",
    ];
    for (base, powers) in [("100", "64 or 128"), ("17", "16 or 32")] {
        let needle = format!("sobol-base = {base} samples: a power of two ({powers})");
        user_error(&dir, &[&verdict[..], &[base]].concat(), &needle);
        let needle = format!("--sobol-base: base = {base} samples: a power of two ({powers})");
        user_error(&dir, &[&impact[..], &[base]].concat(), &needle);
    }
}

/// Forces all 0 printed "R² 1.0000": R² is 0/0 for data that do not vary.
#[test]
fn the_r2_of_a_constant_force_is_undefined() {
    let dir = examples("silent-stiffness-r2");
    let rows: String = (0..20).map(|i| format!("{i},0\n")).collect();
    std::fs::write(dir.join("curve-0.csv"), format!("d [mm],f [kN]\n{rows}")).unwrap();
    let (out, _) = run_in(&dir, &["doe", "stiffness", "curve-0.csv"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(
        text.contains("R² undefined: the force does not vary"),
        "{text}"
    );
    assert!(!text.contains("R² 1"), "{text}");
}

/// A force CSV with times in steps of 1e-300 s ran, while the ISO-MME and
/// EV5 readers refuse a sampling interval outside 1 ns..1 s.
#[test]
fn a_csv_sampling_interval_outside_the_readers_range_is_refused() {
    let dir = examples("silent-csv-interval");
    let rows: String = (0..5).map(|k| format!("{}e-300,{k}\n", k)).collect();
    std::fs::write(dir.join("tiny.csv"), format!("time [s],force [N]\n{rows}")).unwrap();
    let args = [
        "simulate",
        "--car",
        "ex/simulate/car-3dof.toml",
        "--force",
        "tiny.csv",
    ];
    let needle = "tiny.csv:3: the times give a sampling interval of 1e-300 s: expected 1e-9 to 1 s";
    user_error(&dir, &args, needle);
}

/// `mass-reduction --m1 0.0001 --m2 0.0001` ran with 0.1 g masses while
/// `impact` refuses an impactor below 1 g: one range, naming the flag.
#[test]
fn mass_reduction_masses_share_the_impactor_range() {
    let dir = examples("silent-reduction-mass");
    let base = ["mass-reduction", "--bumper", "ex/impact/bumper-a.toml"];
    let m1 = [&base[..], &["--m1", "0.0001", "--m2", "0.0001"]].concat();
    user_error(&dir, &m1, "--m1: m1 = 0.0001 kg");
    let m2 = [&base[..], &["--m2", "0.0001"]].concat();
    user_error(&dir, &m2, "--m2: m2 = 0.0001 kg");
}

/// A car name with control characters went raw into the decks' comments
/// (a line break there ends the comment: the rest reads as a keyword).
#[test]
fn a_car_name_s_control_characters_are_escaped_in_decks() {
    let dir = examples("silent-deck-name");
    let car = std::fs::read_to_string(dir.join("ex/simulate/car-3dof.toml")).unwrap();
    let named: String = car
        .lines()
        .map(|l| match l.starts_with("name") {
            true => "name = \"evil\\n*END\\u001B[2J\"".to_string(),
            false => l.to_string(),
        })
        .collect::<Vec<_>>()
        .join("\n");
    assert_ne!(named, car.trim_end());
    std::fs::write(dir.join("car.toml"), named).unwrap();
    for (kind, deck) in [("lsdyna", "d.k"), ("calculix", "d.inp")] {
        let (out, _) = run_in(&dir, &["export", kind, "car.toml", "-o", deck]);
        assert_eq!(out.status.code(), Some(0), "{kind}: {}", stderr(&out));
        let text = std::fs::read_to_string(dir.join(deck)).unwrap();
        assert!(
            !text.contains('\u{1b}') && !text.contains("evil\n"),
            "{text}"
        );
        assert!(text.contains("evil\\u000A*END\\u001B[2J"), "{text}");
    }
}
