//! Issue 48: ambiguous channel codes, names from files on the terminal,
//! pipeline and design values out of range, messages that name the flag,
//! and printed paths, times and relative quantities.

use crate::util::*;
use std::path::{Path, PathBuf};

/// The bundled ISO-MME test LAB01 copied into `dir` (force channel 1,
/// side-member acceleration channel 2, time channel 3); returns the folder.
fn lab01(dir: &Path) -> PathBuf {
    let test = dir.join("LAB01");
    copy_tree(&root().join("tests/data/isomme/LAB01"), &test);
    test
}

/// Latin-1 text of an ISO-MME file edited by `edit` (the files are not UTF-8).
fn edit_latin1(path: &Path, edit: impl Fn(String) -> String) {
    let text: String = std::fs::read(path)
        .unwrap()
        .iter()
        .map(|&b| b as char)
        .collect();
    let bytes: Vec<u8> = edit(text).chars().map(|c| c as u8).collect();
    std::fs::write(path, bytes).unwrap();
}

fn pipeline(dir: &Path, toml: &str) -> PathBuf {
    let path = dir.join("p.toml");
    std::fs::write(&path, toml).unwrap();
    path
}

const FORCE: &str =
    "[[signal]]\nname = \"force\"\npath = \"LAB01\"\nchannels = [\"P0IMPA000000FOXP\"]\n";

/// Item 1: the force channel's file given twice (channel 2 a copy of
/// channel 1) was summed without a word by an exact code; it is refused
/// naming both channels. A wildcard still sums by design.
#[test]
fn an_exact_code_that_two_channels_carry_is_refused_naming_both() {
    let dir = scratch("issue48-twice");
    let test = lab01(&dir);
    let channels = test.join("Channel");
    std::fs::copy(channels.join("LAB01.001"), channels.join("LAB01.002")).unwrap();
    edit_latin1(&channels.join("LAB01.chn"), |t| {
        let line = t
            .lines()
            .find(|l| l.starts_with("Name of channel 002"))
            .unwrap();
        t.replace(
            line,
            "Name of channel 002         :P0IMPA000000FOXP / Pendelkraft X\r",
        )
    });
    let out = dir.join("s.csv");
    let p = pipeline(&dir, &format!("{FORCE}combine = \"sum\"\n"));
    let run = bumpsim(&[
        "signal",
        "process",
        p.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_user_error(
        &run,
        "channel 'P0IMPA000000FOXP' is an exact code that 2 channels carry (channel 1 (P0IMPA000000FOXP), channel 2 (P0IMPA000000FOXP)): it is ambiguous",
    );
    assert!(!out.exists());
    let run = bumpsim(&[
        "signal",
        "export",
        test.to_str().unwrap(),
        "-c",
        "P0IMPA000000FOXP",
        "--combine",
        "sum",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_user_error(&run, "2 channels carry");
    let wildcard = FORCE.replace("P0IMPA000000FOXP", "P0IMPA*") + "combine = \"sum\"\n";
    let p = pipeline(&dir, &wildcard);
    let run = bumpsim(&[
        "signal",
        "process",
        p.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
}

/// Item 2: a car name and a channel name with control characters reached
/// the terminal raw (an escape sequence from a file); they are escaped.
#[test]
fn names_from_files_are_printed_with_control_characters_escaped() {
    let dir = scratch("issue48-escape");
    let car = std::fs::read_to_string(example("car-3dof.toml")).unwrap();
    let line = car.lines().find(|l| l.starts_with("name = ")).unwrap();
    let path = dir.join("car.toml");
    std::fs::write(&path, car.replace(line, r#"name = "a\u0007b\u001b[31m""#)).unwrap();
    let run = simulate(&path, &example("pendulum-force.csv"), &[]);
    let stdout = text(&run.stdout);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(
        !stdout.contains('\u{1b}') && !stdout.contains('\u{7}'),
        "{stdout:?}"
    );
    assert_contains(&stdout, &[r"car       a\u0007b\u001B[31m: 3 DOF"]);
    let test = lab01(&dir);
    edit_latin1(&test.join("Channel/LAB01.001"), |t| {
        t.replace("Pendelkraft X", "Pendel\u{1b}[2Jkraft")
    });
    let run = bumpsim(&["signal", "info", test.to_str().unwrap()]);
    let stdout = text(&run.stdout);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(!stdout.contains('\u{1b}'), "{stdout:?}");
    assert_contains(&stdout, &[r"Pendel\u001B[2Jkraft"]);
}

/// Item 2 in every command: a verdict's car and item names from the car
/// file reach standard output escaped (the CLI's `println!` goes through
/// `printable_lines`; the verdict table printed them raw).
#[test]
fn a_verdict_prints_the_car_file_names_escaped() {
    let dir = scratch("issue48-escape-verdict");
    let car = std::fs::read_to_string(root().join("examples/verdict/car.toml")).unwrap();
    let car = car.replace("name = \"radiator\"", "name = \"radiator\\u001b[31m\"");
    assert!(car.contains("radiator\\u001b"));
    let path = dir.join("car.toml");
    std::fs::write(&path, car).unwrap();
    let run = bumpsim(&["verdict", "--car", path.to_str().unwrap()]);
    let stdout = text(&run.stdout);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(!stdout.contains('\u{1b}'), "{stdout:?}");
    assert_contains(&stdout, &[r"clearance: radiator\u001B[31m"]);
}

/// Items 3 and 4: a moving average longer than the record and a reversed
/// balance window were accepted (exit 0).
#[test]
fn a_pipeline_refuses_an_overlong_average_and_a_reversed_window() {
    let dir = scratch("issue48-pipeline");
    lab01(&dir);
    let out = dir.join("s.csv");
    let average = format!("{FORCE}steps = [{{ moving_average = 1000000000 }}]\n");
    let run = bumpsim(&[
        "signal",
        "process",
        pipeline(&dir, &average).to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_user_error(
        &run,
        "step 'moving_average': 1000000000 points: at most the record's 40 samples",
    );
    let balance = format!(
        "{FORCE}[[signal]]\nname = \"velocity\"\npath = \"LAB01\"\nchannels = [\"10SIMELE0000ACXP\"]\nsteps = [{{ integrate = 0.0 }}]\n[balance]\nforce = \"force\"\nvelocity = \"velocity\"\nmass = 1000.0\nwindow = [0.003, 0.001]\n"
    );
    let run = bumpsim(&[
        "signal",
        "process",
        pipeline(&dir, &balance).to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_user_error(
        &run,
        "[balance] window = [0.003, 0.001]: expected two finite times in s, the start before the end",
    );
    assert!(!out.exists());
}

/// Items 5 and 11: levels beyond the largest number were written as `inf`,
/// and a generator given twice was named as a factor given twice.
#[test]
fn a_design_refuses_infinite_levels_and_names_a_repeated_generator() {
    let dir = scratch("issue48-doe");
    let out = dir.join("d.csv");
    let o = out.to_str().unwrap();
    let five = "A:-8.5e307:8.5e307,B:0:1,C:0:1,D:0:1,E:0:1";
    for (args, needle) in [
        (
            &["full", "--factors", "A:1e308:1.7e308"][..],
            "--factors 'A:1e308:1.7e308': expected NAME:LOW:HIGH",
        ),
        (
            &["ccc", "--factors", five],
            "factor 'A': the level at coded -2.3784 is -inf, not a finite number",
        ),
        (
            &[
                "fractional",
                "--factors",
                "A:0:1,B:0:1,C:0:1",
                "--generators",
                "C=AB,C=AB",
            ],
            "generator 'C=AB': factor 'C' is generated again (first by 'C=AB')",
        ),
    ] {
        let run = bumpsim(&[&["doe", "design"][..], args, &["-o", o]].concat());
        assert_user_error(&run, needle);
        assert!(!out.exists(), "{args:?}");
    }
}

/// Items 10 and 12: the messages name the flag and its bound.
#[test]
fn resample_and_output_interval_refusals_name_their_flags() {
    let dir = scratch("issue48-flags");
    let test = lab01(&dir);
    let out = dir.join("s.csv");
    let run = bumpsim(&[
        "signal",
        "export",
        test.to_str().unwrap(),
        "-c",
        "1",
        "--resample",
        "1",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_user_error(&run, "--resample 1");
    assert_user_error(&run, "at most 3.900 ms, two samples");
    let car = example("car-3dof.toml");
    for interval in ["0", "-1"] {
        let run = bumpsim(&[
            "export",
            "lsdyna",
            car.to_str().unwrap(),
            "-o",
            dir.join("x.k").to_str().unwrap(),
            "--output-interval",
            interval,
        ]);
        assert_user_error(
            &run,
            &format!("output interval (--output-interval) = {interval} s"),
        );
    }
}

/// Item 17: the CSV path was printed through the pipeline's folder
/// (`a/b/../../out/s.csv`); a channel left out for its missing file was
/// not named.
#[test]
fn process_prints_a_plain_path_and_names_a_left_out_channel() {
    let dir = scratch("issue48-paths");
    let folder = dir.join("a/b");
    let test = lab01(&folder);
    let toml = format!("output = \"../../out/s.csv\"\n{FORCE}");
    let p = pipeline(&folder, &toml);
    let run = bumpsim(&["signal", "process", p.to_str().unwrap()]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let all = text(&run.stdout) + &text(&run.stderr);
    let plain = dir.join("out/s.csv");
    assert_contains(&all, &[&format!("wrote {}", plain.display())]);
    assert!(!all.contains(".."), "{all}");
    assert!(plain.exists());
    std::fs::remove_file(test.join("Channel/LAB01.002")).unwrap();
    let out = dir.join("all.csv");
    let run = bumpsim(&[
        "signal",
        "export",
        test.to_str().unwrap(),
        "-c",
        "*",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert_contains(
        &text(&run.stderr),
        &["'*': left out channel 2 (10SIMELE0000ACXP) whose file is missing or unusable"],
    );
}

/// Item 18: a contact starting within the first 0.1 ms sample printed as
/// `0.03333 ms` (now to the sample: `0.0 ms`), and
/// the energy and momentum checks did not say they are relative.
#[test]
fn planar_times_are_rounded_to_the_sample_and_checks_say_relative() {
    let run = bumpsim(&[
        "planar",
        "--car",
        root().join("examples/planar/saloon.toml").to_str().unwrap(),
        "--case",
        "rcar-structural-front",
    ]);
    let stdout = text(&run.stdout);
    assert!(run.status.success(), "{}", text(&run.stderr));
    // (the integration step, 0.03333 ms, is printed as such)
    assert!(!stdout.contains("contact from 0.03333 ms"), "{stdout}");
    assert_contains(
        &stdout,
        &[
            "contact from 0.0 ms to ",
            "relative energy balance error ",
            "relative momentum residuals ",
        ],
    );
}
