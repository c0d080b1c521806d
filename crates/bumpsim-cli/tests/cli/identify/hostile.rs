//! Issue 44's hostile pass over its new inputs, through the binary: a
//! chain study's objective, bias windows, sensor kinds and displacement
//! channels; a planar study's `[priors]`. Each exits 2 with the file or
//! case and the key named, never a panic, a NaN in the message or a fit
//! of garbage. (The ones that ran to exit 0 before: a bias window past the
//! record, a lateral accelerometer averaged into a chain study, a prior of
//! 1e300 or 1e-300; a prior of an unknown name printed "= NaN -".)

use crate::util::*;
use std::path::{Path, PathBuf};

/// The bundled chain study in `dir`, edited.
fn chain_study(dir: &Path, edit: impl Fn(String) -> String) -> PathBuf {
    copy_tree(&root().join("examples/identify"), dir);
    let path = dir.join("study.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    std::fs::write(&path, edit(text)).unwrap();
    path
}

fn identify(study: &Path) -> std::process::Output {
    let args = ["identify", study.to_str().unwrap(), "--dof", "1"];
    bumpsim(&[&args[..], &["--starts", "1", "--quiet"]].concat())
}

/// `assert_user_error`, and no NaN or panic in what it printed.
fn refused(run: &std::process::Output, needle: &str) {
    assert_user_error(run, needle);
    let printed = text(&run.stdout) + &text(&run.stderr);
    assert!(
        // (a NaN sample is quoted from its file as 'NaN')
        !printed.replace("'NaN'", "").contains("NaN") && !printed.contains("panicked"),
        "{printed}"
    );
}

#[test]
fn hostile_objectives_and_bias_windows_of_a_chain_study() {
    let dir = scratch("identify-hostile-objective");
    for (objective, needle) in [
        (
            "\"speed\"",
            "[identification] objective \"speed\": expected \"displacement\", \"velocity\" or \"acceleration\"",
        ),
        ("3", "invalid type: integer `3`, expected a string"),
        (
            "[\"velocity\"]",
            "invalid type: sequence, expected a string",
        ),
    ] {
        let study = chain_study(&dir, |t| {
            format!("[identification]\nobjective = {objective}\n{t}")
        });
        refused(&identify(&study), needle);
    }
    for (bias, needle) in [
        ("[-0.01, 1e300]", "reaches beyond the record"),
        ("[-1e308, 1e308]", "reaches beyond the record"),
        ("[]", "expected an array of exactly 2 numbers"),
        (
            "[0.0, 0.0]",
            "bias = [0, 0]: expected two finite times in s, the first below the second",
        ),
        ("[-inf, 0.0]", "bias = [-inf, 0]: expected two finite times"),
    ] {
        let study = chain_study(&dir, |t| {
            t.replacen("cfc = 180\n", &format!("cfc = 180\nbias = {bias}\n"), 1)
        });
        refused(&identify(&study), needle);
    }
}

/// The flat test's right accelerometer recoded as `code` (`direction`,
/// `dimension`, `unit`), its samples passed through `samples`.
fn recode(dir: &Path, code: &str, fields: [&str; 3], samples: impl Fn(usize, &str) -> String) {
    let chn = dir.join("FLAT/Channel/FLAT.chn");
    let list = std::fs::read_to_string(&chn).unwrap();
    std::fs::write(&chn, list.replace("10SIMERI0000ACXP", code)).unwrap();
    let path = dir.join("FLAT/Channel/FLAT.003");
    let file = std::fs::read_to_string(&path).unwrap();
    let (head, body) = file.split_at(file.find("Data status").unwrap());
    let (status, data) = body.split_at(body.find('\n').unwrap() + 1);
    let mut head = head.replace("10SIMERI0000ACXP", code);
    for (key, value) in ["Direction", "Dimension", "Unit"].iter().zip(fields) {
        let at = head.find(&format!("\n{key} ")).unwrap() + 1;
        let end = at + head[at..].find('\n').unwrap();
        let colon = at + head[at..].find(':').unwrap();
        head.replace_range(colon + 1..end, value);
    }
    let data: String = data
        .lines()
        .enumerate()
        .map(|(i, l)| samples(i, l) + "\n")
        .collect();
    std::fs::write(&path, format!("{head}{status}{data}")).unwrap();
}

#[test]
fn sensors_a_chain_study_cannot_use_are_refused_by_channel() {
    let dir = scratch("identify-hostile-sensors");
    let same = |_: usize, l: &str| l.to_string();
    let cases: [(&str, [&str; 3], bool, &str); 3] = [
        (
            "10SIMERI0000ACYP",
            ["Y", "AC", "m/s**2"],
            false,
            "the acceleration channel 10SIMERI0000ACYP measures along Y",
        ),
        (
            "10VEHC0000CGAVZP",
            ["Z", "AV", "deg/s"],
            false,
            "10VEHC0000CGAVZP measures along Z",
        ),
        (
            "10VEHC0000CGAVZP",
            ["Z", "AV", "deg/s"],
            true,
            "'NaN' is not a finite number",
        ),
    ];
    for (code, fields, nan, needle) in cases {
        let study = chain_study(&dir, |t| t.replacen("10SIMERI0000ACXP", code, 1));
        recode(&dir, code, fields, |i, l| match nan && i == 900 {
            true => "NaN".into(),
            false => same(i, l),
        });
        refused(&identify(&study), needle);
        std::fs::remove_dir_all(&dir).unwrap();
    }
    // a displacement of 1e300 m: refused, the value printed short
    let study = chain_study(&dir, |t| {
        let start = t.find("acceleration = [").unwrap();
        let end = start + t[start..].find("]\n").unwrap() + 2;
        format!(
            "{}displacement = {{ path = \"x.csv\", channel = \"x1\" }}\n{}",
            &t[..start],
            &t[end..]
        )
    });
    let rows: String = (0..2100)
        .map(|k| format!("{:.4},1e300\n", -0.05 + k as f64 * 1e-4))
        .collect();
    std::fs::write(dir.join("x.csv"), format!("time [s],x1 [m]\n{rows}")).unwrap();
    let run = identify(&study);
    refused(
        &run,
        "case 'flat': displacement sample 0 (t = 0 s) is 1.000e300 m: expected at most 1.000e6 m in size",
    );
    // it printed all 301 digits of 1e300
    assert!(
        !text(&run.stderr).contains("0000000000"),
        "{}",
        text(&run.stderr)
    );
}

/// A planar study's `[priors]`: out of range, unknown, not estimated.
#[test]
fn hostile_priors_of_a_planar_study_name_their_key() {
    let dir = scratch("identify-hostile-priors");
    let series = root().join("examples/planar/identify/series.toml");
    let tests = dir.join("tests");
    let run = bumpsim(&[
        "synth",
        series.to_str().unwrap(),
        "-o",
        tests.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let study = tests.join("study.toml");
    let text_of = std::fs::read_to_string(&study).unwrap();
    for (prior, needle) in [
        (
            "body.yaw_inertia = { value = 1e300 }",
            "study.toml: [priors] body.yaw_inertia: value = 1e300: must be from 1e-12 to 1e15",
        ),
        (
            "body.yaw_inertia = { value = 1e-300 }",
            "[priors] body.yaw_inertia: value = 1e-300: must be from 1e-12",
        ),
        (
            "body.yaw_inertia = { spread = 1e-300 }",
            "[priors] body.yaw_inertia: spread = 1e-300: must be from 1e-6 to 1e2",
        ),
        (
            "body.yaw_inertia = { spread = 1e300 }",
            "[priors] body.yaw_inertia: spread = 1e300: must be from 1e-6",
        ),
        (
            "body.yaw_inertia = { value = nan }",
            "[priors] body.yaw_inertia: value = NaN: must be finite and positive",
        ),
        (
            "body.yaw_inertia = { spread = -0.1 }",
            "spread = -0.1: must be finite and positive",
        ),
        (
            "body.yaw_inertia = { spread = 0.0 }",
            "spread = 0: must be finite and positive",
        ),
        (
            "body.yaw = { value = 2300.0 }",
            "[priors] body.yaw: no such estimated car parameter; known: total_mass",
        ),
        (
            "tyres.cornering_stiffness = { value = 6e4 }",
            "[priors] tyres.cornering_stiffness: no such estimated car parameter",
        ),
    ] {
        std::fs::write(&study, format!("{text_of}\n[priors]\n{prior}\n")).unwrap();
        let args = [
            "identify",
            study.to_str().unwrap(),
            "--starts",
            "1",
            "--quiet",
        ];
        let run = bumpsim(&args);
        assert_user_error(&run, needle);
        // the NaN a value left out printed ("[priors] body.yaw = NaN -")
        assert!(
            !text(&run.stderr).contains("NaN -"),
            "{}",
            text(&run.stderr)
        );
    }
}
