//! Hostile-user reproductions of issue 13 (and the stiff model of issue 14)
//! run against the real binary: data-loss cases leave inputs byte-identical
//! and old outputs intact; panic/abort/hang cases exit 2 with a message
//! naming the parameter or limit within 5 s; silent cases warn (exit 2 under
//! `--strict`); a SIGKILL during a write leaves the complete old or the
//! complete new file.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::{Duration, Instant};

use crate::util::{copy_tree, root};

mod careful;
mod commit;
mod flags;
mod inputs;
mod ranges;
mod refusals;
mod silent;

fn scratch(test: &str) -> PathBuf {
    crate::util::scratch(&format!("robustness-{test}"))
}

/// A copy of `examples/` as `ex/` inside a scratch folder (the issue's setup).
fn examples(test: &str) -> PathBuf {
    let dir = scratch(test);
    copy_tree(&root().join("examples"), &dir.join("ex"));
    dir
}

fn run_in(dir: &Path, args: &[&str]) -> (Output, Duration) {
    let clock = Instant::now();
    let out = Command::new(env!("CARGO_BIN_EXE_bumpsim"))
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap();
    (out, clock.elapsed())
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Exit 2 within 5 s with a message holding `needle`.
fn user_error(dir: &Path, args: &[&str], needle: &str) {
    let (out, took) = run_in(dir, args);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert!(took < Duration::from_secs(5), "{args:?} took {took:?}");
    assert!(
        err.to_lowercase().contains(&needle.to_lowercase()),
        "{args:?}: '{needle}' not in: {err}"
    );
}

fn snapshot(path: &Path) -> Vec<u8> {
    std::fs::read(path).unwrap()
}

#[test]
fn outputs_never_land_on_inputs() {
    let dir = examples("inputs");
    let channel = "ex/identify/FLAT/Channel/FLAT.001";
    let study = "ex/identify/study.toml";
    let car = "ex/simulate/car-3dof.toml";
    let bumper = "ex/impact/bumper-a.toml";
    let before: Vec<(&str, Vec<u8>)> = [channel, study, car, bumper]
        .iter()
        .map(|p| (*p, snapshot(&dir.join(p))))
        .collect();
    let cases: Vec<Vec<&str>> = vec![
        vec![
            "signal",
            "export",
            "ex/identify/FLAT",
            "-c",
            "1",
            "-o",
            channel,
        ],
        vec!["identify", study, "--json", study],
        vec!["impact", "--car", car, "--bumper", bumper, "--json", car],
        vec!["impact", "--car", car, "--bumper", bumper, "--csv", bumper],
        vec!["export", "lsdyna", car, "-o", car],
    ];
    for args in &cases {
        user_error(&dir, args, "overwrite the input");
    }
    // a hard link to an input is the input
    std::fs::hard_link(dir.join(car), dir.join("link.toml")).unwrap();
    user_error(
        &dir,
        &[
            "impact",
            "--car",
            car,
            "--bumper",
            bumper,
            "--json",
            "link.toml",
        ],
        "overwrite the input",
    );
    // and a hard link to a file inside an input test folder
    std::fs::hard_link(dir.join(channel), dir.join("channel-link")).unwrap();
    user_error(
        &dir,
        &[
            "signal",
            "export",
            "ex/identify/FLAT",
            "-c",
            "1",
            "-o",
            "channel-link",
        ],
        "overwrite the input",
    );
    for (path, bytes) in before {
        assert_eq!(snapshot(&dir.join(path)), bytes, "{path} changed");
    }
}

#[test]
fn a_refused_second_output_leaves_the_first_untouched() {
    let dir = examples("second-output");
    std::fs::write(dir.join("a.json"), "old").unwrap();
    std::fs::write(dir.join("existing_file"), "mine").unwrap();
    user_error(
        &dir,
        &[
            "identify",
            "ex/identify/study.toml",
            "--json",
            "a.json",
            "--report",
            "existing_file",
        ],
        "not a folder",
    );
    assert_eq!(snapshot(&dir.join("a.json")), b"old");
    assert_eq!(snapshot(&dir.join("existing_file")), b"mine");
    std::fs::write(dir.join("keep.csv"), "old").unwrap();
    std::fs::create_dir_all(dir.join("nonempty")).unwrap();
    std::fs::write(dir.join("nonempty/x"), "x").unwrap();
    user_error(
        &dir,
        &[
            "signal",
            "export",
            "ex/identify/FLAT",
            "-c",
            "1",
            "-o",
            "keep.csv",
            "--iso-mme",
            "nonempty",
        ],
        "not empty",
    );
    assert_eq!(snapshot(&dir.join("keep.csv")), b"old");
}

#[test]
fn synth_keeps_every_file_inside_its_folder() {
    let dir = examples("synth");
    let series = snapshot(&dir.join("ex/identify/series.toml"));
    let text = String::from_utf8(series).unwrap();
    for (bad, needle) in [
        ("../../x", "not a plain name"),
        ("/tmp/bumpsim-escape", "not a plain name"),
        ("P600", "name 'P600' is already used by 'P600'"),
        (" p600", "(they differ only in case, surrounding spaces"),
        ("   ", "[[head]] number 1: an empty name"),
        (
            "FL\\u001B[31mAT",
            r#"the name "FL\u001B[31mAT" holds control"#,
        ),
        ("FL\\u2028AT", r#"the name "FL\u2028AT" holds control"#),
        (" FLAT", "spaces before or after it"),
    ] {
        let file = dir.join("ex/identify/bad.toml");
        std::fs::write(
            &file,
            text.replacen("name = \"FLAT\"", &format!("name = \"{bad}\""), 1),
        )
        .unwrap();
        user_error(
            &dir,
            &["synth", "ex/identify/bad.toml", "-o", "out"],
            needle,
        );
        assert!(!dir.join("out").exists());
    }
    assert!(!Path::new("/tmp/bumpsim-escape").exists());
}

#[test]
fn absurd_sizes_and_values_are_refused_quickly() {
    let dir = examples("limits");
    let study = std::fs::read_to_string(dir.join("ex/identify/study.toml")).unwrap();
    std::fs::write(
        dir.join("ex/identify/dof0.toml"),
        study.replacen("dof = 3", "dof = 0", 1),
    )
    .unwrap();
    std::fs::write(
        dir.join("ex/identify/dof10000.toml"),
        study.replacen("dof = 3", "dof = 10000", 1),
    )
    .unwrap();
    user_error(&dir, &["identify", "ex/identify/dof0.toml"], "dof = 0");
    user_error(&dir, &["identify", "ex/identify/dof10000.toml"], "MAX_DOF");
    user_error(
        &dir,
        &[
            "identify",
            "ex/identify/study.toml",
            "--starts",
            "18446744073709551615",
        ],
        "--starts",
    );
    user_error(
        &dir,
        &[
            "doe",
            "design",
            "lhs",
            "--factors",
            "A:0:1",
            "--runs",
            "1000000000",
            "-o",
            "d.csv",
        ],
        "--runs",
    );
    user_error(
        &dir,
        &[
            "doe",
            "design",
            "full",
            "--factors",
            "A:-inf:inf",
            "-o",
            "d.csv",
        ],
        "finite",
    );
    std::fs::write(dir.join("t.csv"), "A,B,y\n-1,-1,1\n1,-1,2\n-1,1,4\n1,1,7\n").unwrap();
    user_error(
        &dir,
        &[
            "doe",
            "fit",
            "t.csv",
            "--factors",
            "A,B",
            "--responses",
            "y",
            "--high",
            "inf,1",
        ],
        "finite",
    );
    std::fs::write(dir.join("c.csv"), "A,B,y\n-1,-1,3\n1,-1,3\n-1,1,3\n1,1,3\n").unwrap();
    user_error(
        &dir,
        &[
            "doe",
            "fit",
            "c.csv",
            "--factors",
            "A,B",
            "--responses",
            "y",
        ],
        "constant",
    );
    let model = r#"{"factors":[{"name":"A","low":0,"high":1}],
        "responses":[{"name":"y","coefficients":{"intercept":1,"A":2},
        "residual_sd":1,"dof_residual":2,"terms":["intercept","A"],"xtx_inverse":[[1]]}]}"#;
    std::fs::write(dir.join("m.json"), model).unwrap();
    user_error(
        &dir,
        &["doe", "predict", "m.json", "--at", "A=0.5"],
        "xtx_inverse",
    );
    std::fs::write(dir.join("m2.json"), model.replace("[[1]]", "[[1,0],[0,1]]")).unwrap();
    user_error(
        &dir,
        &["doe", "predict", "m2.json", "--at", "A=nan"],
        "finite",
    );
    std::fs::write(
        dir.join("m3.json"),
        model
            .replace("[[1]]", "[[1,0],[0,1]]")
            .replace("\"residual_sd\":1", "\"residual_sd\":-1"),
    )
    .unwrap();
    user_error(
        &dir,
        &["doe", "predict", "m3.json", "--at", "A=0.5"],
        "residual_sd",
    );
    user_error(
        &dir,
        &[
            "doe",
            "reach",
            "m2.json",
            "--x",
            "y",
            "--y",
            "y",
            "--samples",
            "10000000000",
        ],
        "--samples",
    );
}

#[test]
fn impact_with_featherweight_masses_ends_with_a_clear_error() {
    let dir = examples("feather");
    std::fs::write(
        dir.join("light.toml"),
        "masses = [1e-9, 1e-9]\ndampers = [1.0]\nsprings = [1e6]\n",
    )
    .unwrap();
    user_error(
        &dir,
        &[
            "impact",
            "--car",
            "light.toml",
            "--bumper",
            "ex/impact/bumper-a.toml",
            "--speed",
            "4 km/h",
            "--barrier",
        ],
        "need a stable step of",
    );
}

#[test]
fn simulate_warns_on_a_stiff_model_and_strict_exits_2() {
    let dir = examples("stiff");
    std::fs::write(
        dir.join("stiff.toml"),
        "masses = [1e-9, 74.8, 1670.0]\ndampers = [6.46e6, 1.97e5]\nsprings = [1e15, 5.0e5]\n",
    )
    .unwrap();
    let args = [
        "simulate",
        "--car",
        "stiff.toml",
        "--force",
        "ex/simulate/pendulum-force.csv",
    ];
    let (out, _) = run_in(&dir, &args);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("warning: energy balance error"),
        "{}",
        stderr(&out)
    );
    let strict: Vec<&str> = std::iter::once("--strict").chain(args).collect();
    user_error(&dir, &strict, "--strict");
    // NaN is never printed with exit 0
    let mut huge: Vec<&str> = args.to_vec();
    huge[2] = "ex/simulate/car-3dof.toml";
    huge.extend(["--initial-velocity", "1e308"]);
    user_error(&dir, &huge, "non-finite");
}

#[test]
fn every_command_refuses_its_input_as_output() {
    let dir = examples("inputs-2");
    std::fs::write(dir.join("p.toml"), "input = \"ex/identify/FLAT\"\n").unwrap();
    std::fs::write(dir.join("d.csv"), "A,B,y\n-1,-1,1\n1,-1,2\n-1,1,4\n1,1,7\n").unwrap();
    std::fs::write(dir.join("design.csv"), "A,y\n1,2\n").unwrap();
    std::fs::write(dir.join("car.inp"), "** deck\n").unwrap();
    let bumper = "ex/impact/bumper-a.toml";
    let cases: Vec<Vec<&str>> = vec![
        vec!["signal", "process", "p.toml", "-o", "p.toml"],
        vec!["mass-reduction", "--bumper", bumper, "--json", bumper],
        vec![
            "doe",
            "fit",
            "d.csv",
            "--factors",
            "A,B",
            "--responses",
            "y",
            "--json",
            "d.csv",
        ],
        vec![
            "doe",
            "collect",
            "design.csv",
            "--results",
            "d.csv",
            "-o",
            "design.csv",
        ],
        vec!["export", "read-calculix", "car.inp", "-o", "car.inp"],
    ];
    let files = ["p.toml", bumper, "d.csv", "design.csv", "car.inp"];
    let before: Vec<Vec<u8>> = files.iter().map(|f| snapshot(&dir.join(f))).collect();
    for args in &cases {
        user_error(&dir, args, "overwrite the input");
    }
    for (file, bytes) in files.iter().zip(before) {
        assert_eq!(snapshot(&dir.join(file)), bytes, "{file} changed");
    }
}

#[test]
fn more_limits_and_hostile_values() {
    let dir = examples("limits-2");
    let flat = "ex/identify/FLAT";
    user_error(
        &dir,
        &[
            "signal",
            "export",
            flat,
            "-c",
            "1",
            "--resample",
            "1e-11",
            "-o",
            "r.csv",
        ],
        "MAX_INPUT_SAMPLES",
    );
    user_error(
        &dir,
        &[
            "export",
            "lsdyna",
            "ex/simulate/car-3dof.toml",
            "--id-offset",
            "18446744073709551615",
            "-o",
            "x.k",
        ],
        "id offset",
    );
    user_error(
        &dir,
        &[
            "mass-reduction",
            "--bumper",
            "ex/impact/bumper-a.toml",
            "--sweep",
            "car",
            "--points",
            "1000000",
        ],
        "--points",
    );
    // a TOML error does not echo the file's content
    std::fs::write(
        dir.join("secret.toml"),
        "password-hunter2\nmasses = [1.0,\n",
    )
    .unwrap();
    let (out, _) = run_in(
        &dir,
        &[
            "simulate",
            "--car",
            "secret.toml",
            "--force",
            "ex/simulate/pendulum-force.csv",
        ],
    );
    assert_eq!(out.status.code(), Some(2));
    assert!(!stderr(&out).contains("hunter2"), "{}", stderr(&out));
    assert!(stderr(&out).contains("line 1"), "{}", stderr(&out));
    // synth duration beyond the sample limit
    let series = std::fs::read_to_string(dir.join("ex/identify/series.toml")).unwrap();
    std::fs::write(
        dir.join("ex/identify/long.toml"),
        series.replacen("duration = 0.16", "duration = 1e6", 1),
    )
    .unwrap();
    user_error(
        &dir,
        &["synth", "ex/identify/long.toml", "-o", "out"],
        "MAX_SAMPLES",
    );
    // constant displacement has no stiffness
    std::fs::write(
        dir.join("flat.csv"),
        "d [mm],f [kN]\n5,1\n5,2\n5,3\n5,4\n5,5\n",
    )
    .unwrap();
    user_error(&dir, &["doe", "stiffness", "flat.csv"], "does not vary");
    // a 1e300 bumper: refused (no figure printed)
    std::fs::write(
        dir.join("b300.toml"),
        "ramp = 1e300\nplateau = 1e300\nunloading = 1e300\n",
    )
    .unwrap();
    user_error(
        &dir,
        &[
            "impact",
            "--car",
            "ex/simulate/car-3dof.toml",
            "--bumper",
            "b300.toml",
            "--barrier",
            "--speed",
            "4 km/h",
        ],
        "need a stable step of",
    );
    // predict with k = 1e300
    std::fs::write(
        dir.join("k300.toml"),
        "masses = [1.8, 74.8, 1670.0]\ndampers = [6.46e6, 1.97e5]\nsprings = [1e300, 5.0e5]\n",
    )
    .unwrap();
    user_error(
        &dir,
        &["predict", "k300.toml", "ex/identify/study.toml"],
        "not finite",
    );
    // a first-sample time of 1e308 s would collapse every sample
    let channel = dir.join("ex/identify/FLAT/Channel/FLAT.001");
    let text = std::fs::read_to_string(&channel).unwrap();
    let start = text
        .lines()
        .find(|l| l.starts_with("Time of first sample"))
        .unwrap()
        .to_string();
    std::fs::write(
        &channel,
        text.replacen(&start, "Time of first sample        :1e308", 1),
    )
    .unwrap();
    user_error(
        &dir,
        &["signal", "export", flat, "-c", "1", "-o", "t.csv"],
        "start time",
    );
}

#[test]
fn identify_refuses_all_zero_and_constant_data() {
    let dir = scratch("zero-data");
    let mut csv = String::from("time [s],f [N],x [m]\n");
    for k in 0..200 {
        csv.push_str(&format!(
            "{},{},0\n",
            k as f64 * 1e-3,
            1000.0 * (k as f64 * 0.03).sin()
        ));
    }
    std::fs::write(dir.join("zero.csv"), &csv).unwrap();
    std::fs::write(
        dir.join("study.toml"),
        "[model]\ndof = 1\nstarts = 2\n[[case]]\nname = \"zero\"\nforce = { path = \"zero.csv\", channel = \"f\" }\ndisplacement = { path = \"zero.csv\", channel = \"x\" }\nwindow = [0.0, 0.19]\n",
    )
    .unwrap();
    user_error(&dir, &["identify", "study.toml", "--quiet"], "constant");
}

#[test]
fn read_calculix_refuses_corrupt_results() {
    let dir = examples("calculix");
    let (out, _) = run_in(
        &dir,
        &[
            "export",
            "calculix",
            "ex/simulate/car-3dof.toml",
            "-o",
            "car.inp",
        ],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let deck = std::fs::read_to_string(dir.join("car.inp")).unwrap();
    let block = |t: &str, v: &str| {
        format!(
            " displacements (vx,vy,vz) for set BUMPSIM_NALL and time  {t}\n\n         1  {v}  0.0  0.0\n         2  {v}  0.0  0.0\n         3  {v}  0.0  0.0\n\n"
        )
    };
    let cases = [
        (block("1e-4", "nan") + &block("2e-4", "1e-3"), "finite"),
        (block("nan", "1e-3"), "finite time"),
        (block("1e-4", "1e-3") + &block("1e-4", "1e-3"), "duplicate"),
        (
            block("1e-4", "1e-3")
                + " displacements (vx,vy,vz) for set BUMPSIM_NALL and time  2e-4\n\n         1  1e-3 0.0 0.0\n",
            "truncated",
        ),
    ];
    for (dat, needle) in cases {
        std::fs::write(dir.join("car.dat"), dat).unwrap();
        user_error(
            &dir,
            &["export", "read-calculix", "car.inp", "-o", "r.csv"],
            needle,
        );
    }
    let absurd = deck.replacen("dof=3", "dof=18446744073709551615", 1);
    assert_ne!(absurd, deck, "the deck names its dof");
    std::fs::write(dir.join("car.inp"), absurd).unwrap();
    std::fs::write(dir.join("car.dat"), block("1e-4", "1e-3")).unwrap();
    user_error(
        &dir,
        &["export", "read-calculix", "car.inp", "-o", "r.csv"],
        "dof",
    );
}

#[test]
fn plots_of_degenerate_or_huge_models_do_not_panic() {
    let dir = scratch("reach-plot");
    for (name, a) in [("zero", "0"), ("huge", "1e308")] {
        let model = format!(
            r#"{{"factors":[{{"name":"A","low":0,"high":1}},{{"name":"B","low":0,"high":1}}],
            "responses":[{{"name":"x","coefficients":{{"intercept":1,"A":{a},"B":0}}}},
                         {{"name":"y","coefficients":{{"intercept":1,"A":0,"B":{a}}}}}]}}"#
        );
        std::fs::write(dir.join(format!("{name}.json")), model).unwrap();
        let file = format!("{name}.json");
        let plot = format!("plot-{name}");
        let args = [
            "doe",
            "reach",
            &file,
            "--x",
            "x",
            "--y",
            "y",
            "--samples",
            "100",
            "--plot",
            &plot,
        ];
        let (out, took) = run_in(&dir, &args);
        assert!(took < Duration::from_secs(5));
        assert!(
            matches!(out.status.code(), Some(0) | Some(2)),
            "{name}: {}",
            stderr(&out)
        );
        if out.status.code() == Some(2) {
            assert!(
                stderr(&out).contains("reach") || stderr(&out).contains("axis"),
                "{}",
                stderr(&out)
            );
        }
    }
}

#[test]
fn zip_bombs_are_refused() {
    let dir = scratch("zip");
    let script = r#"
import zipfile, sys
with zipfile.ZipFile(sys.argv[1], "w", zipfile.ZIP_DEFLATED) as z:
    z.writestr("T/T.mme", "Data format edition number  :1.6\r\n")
    z.writestr("T/Channel/T.chn", "Number of channels          :1\r\n")
    z.writestr("T/Channel/T.001", b"0" * (300 * 1024 * 1024))
"#;
    let made = Command::new("python3")
        .args(["-c", script, dir.join("bomb.zip").to_str().unwrap()])
        .status();
    if !made.is_ok_and(|s| s.success()) {
        eprintln!("skipped: python3 cannot write the zip");
        return;
    }
    user_error(&dir, &["signal", "info", "bomb.zip"], "zip bomb");
}

#[test]
fn ten_thousand_masses_are_refused() {
    let dir = examples("dof");
    let n = 10_000;
    let list = |v: &str, k: usize| vec![v; k].join(", ");
    std::fs::write(
        dir.join("big.toml"),
        format!(
            "masses = [{}]\ndampers = [{}]\nsprings = [{}]\n",
            list("1.0", n),
            list("1.0", n - 1),
            list("1.0", n - 1)
        ),
    )
    .unwrap();
    user_error(
        &dir,
        &[
            "simulate",
            "--car",
            "big.toml",
            "--force",
            "ex/simulate/pendulum-force.csv",
        ],
        "MAX_DOF",
    );
}

/// `bumpsim ... | head`: a closed pipe ends the command quietly (exit 141,
/// as a shell reports other tools), not with a panic.
#[test]
fn a_closed_pipe_ends_the_command_without_a_panic() {
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let car = crate::util::root().join("examples/planar/saloon.toml");
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_bumpsim"))
        .args([
            "planar",
            "--car",
            car.to_str().unwrap(),
            "--case",
            "rcar-structural-front",
        ])
        .stdout(writer)
        .stderr(std::process::Stdio::piped())
        .output()
        .unwrap();
    let stderr = crate::util::text(&run.stderr);
    assert_eq!(run.status.code(), Some(141), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}
