//! ISO-MME headers and codes checked by pyisomme, partial tests, units
//! (N·m, --unit ms), and the figures docs/signals.md quotes (issue 14).

use crate::util::*;
use bumpsim_core::units::Dimension;
use bumpsim_io::test_data::TestData;
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Whether python3 with pyisomme is available.
fn pyisomme_available() -> bool {
    peer_available("pyisomme", "python3", &["-c", "import pyisomme"])
}

fn pyisomme(args: &[&str]) -> Value {
    let script = root().join("tests/peers/pyisomme_isomme.py");
    let run = Command::new("python3")
        .arg(script)
        .args(args)
        .output()
        .unwrap();
    assert!(run.status.success(), "pyisomme: {}", text(&run.stderr));
    serde_json::from_slice(&run.stdout).unwrap()
}

fn export(dir: &Path, name: &str, test: &Path, flags: &[&str]) -> PathBuf {
    let folder = dir.join(name);
    let csv = dir.join(format!("{name}.csv"));
    let mut args = vec!["signal", "export", test.to_str().unwrap()];
    args.extend_from_slice(flags);
    args.extend(["-o", csv.to_str().unwrap()]);
    args.extend(["--iso-mme", folder.to_str().unwrap()]);
    let run = bumpsim(&args);
    assert!(run.status.success(), "{}", text(&run.stderr));
    folder
}

fn number(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

fn close(a: f64, b: f64, scale: f64) -> bool {
    (a - b).abs() <= 1e-12 * scale.max(f64::MIN_POSITIVE)
}

/// pyisomme reads `folder` with the codes (and CFC) bumpsim meant, SI
/// units that agree with each code's dimension, and the same time base
/// and values as bumpsim reads.
fn pyisomme_agrees(folder: &Path, meant: &[(&str, Option<f64>)]) -> Value {
    let read = pyisomme(&["read", folder.to_str().unwrap()]);
    let test = TestData::open(folder).unwrap();
    let channels = read["channels"].as_array().unwrap();
    assert_eq!(channels.len(), meant.len(), "{}", folder.display());
    for (i, (py, (code, cfc))) in channels.iter().zip(meant).enumerate() {
        let ours = test.load(i).unwrap();
        assert_eq!(py["code"], *code, "channel {}", i + 1);
        assert_eq!(ours.code, *code);
        assert_eq!(py["filter_class"], code[15..].to_string());
        assert_eq!(py["unit_to_default"], 1.0, "{code}: unit {}", py["unit"]);
        match cfc {
            Some(class) => assert_eq!(number(&py["channel_frequency_class"]), *class),
            None => assert!(py["channel_frequency_class"].is_null()),
        }
        let s = &ours.series;
        assert_eq!(py["samples"].as_u64(), Some(s.len() as u64));
        assert!(close(number(&py["time_of_first_sample"]), s.start(), 1.0));
        let step = number(&py["sampling_interval"]);
        assert!((step - s.step()).abs() <= 1e-9 * s.step(), "{code}: {step}");
        let scale = s.values().iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        for (k, v) in py["values"].as_array().unwrap().iter().enumerate() {
            assert!(close(number(v), s.values()[k], scale), "{code}[{k}]");
        }
    }
    read
}

#[test]
fn pyisomme_reads_every_channel_bumpsim_writes() {
    if !pyisomme_available() {
        return;
    }
    let dir = scratch("formats-pyisomme");
    let flat = root().join("examples/identify/FLAT");
    let raw = export(&dir, "RAW", &flat, &["--channel", "1", "--channel", "2"]);
    pyisomme_agrees(
        &raw,
        &[("P0IMPA000000FOXP", None), ("10SIMELE0000ACXP", None)],
    );
    let filtered = export(&dir, "CFC", &flat, &["--channel", "2", "--cfc", "180"]);
    pyisomme_agrees(&filtered, &[("10SIMELE0000ACXC", Some(180.0))]);
    let flags = ["--channel", "2", "--bias", "--cfc", "180"];
    let velocity = export(
        &dir,
        "VEL",
        &flat,
        &[&flags[..], &["--integrate", "0"]].concat(),
    );
    pyisomme_agrees(&velocity, &[("10SIMELE0000VEXC", Some(180.0))]);
    let twice = ["--integrate", "0", "--integrate", "0"];
    let crush = export(&dir, "INT", &flat, &[&flags[..], &twice].concat());
    pyisomme_agrees(&crush, &[("10SIMELE0000DSXC", Some(180.0))]);
    let synth = pyisomme_agrees(
        &flat,
        &[
            ("P0IMPA000000FOXP", None),
            ("10SIMELE0000ACXP", None),
            ("10SIMERI0000ACXP", None),
        ],
    );
    // test object 1 is the parked car, as the `1…` codes say (issue 33);
    // the pendulum (6 km/h) is test object 2 (formats_letter checks it)
    assert_eq!(number(&synth["velocity_test_object_1"]), 0.0);
    assert_eq!(number(&synth["mass_test_object_1"]), 1450.0);
    let Some(ev5) = nhtsa_ev5() else { return };
    let nhtsa = ["--channel", "93", "--channel", "587", "--cfc", "60"];
    let converted = export(&dir, "NH", &ev5, &nhtsa);
    let read = pyisomme_agrees(
        &converted,
        &[
            ("10SECMLE0000ACXD", Some(60.0)),
            ("B0LOMA010100FOXD", Some(60.0)),
        ],
    );
    assert!(close(
        number(&read["velocity_test_object_1"]),
        57.09 / 3.6,
        16.0
    ));
    assert_eq!(number(&read["mass_test_object_1"]), 1719.0);
    assert_eq!(read["channels"][0]["unit"], "m / s2");
    let header = std::fs::read_to_string(converted.join("Channel/NH.001")).unwrap();
    assert_contains(
        &header,
        &[
            "Unit                        :m/s**2",
            "Laboratory channel code     :1-AC-FLLR-XG",
            "Comments                    :LEFT REAR SEAT CROSSMEMBER X",
            "converted from G'S to m/s**2",
            "Transducer type             :MFG:",
        ],
    );
    assert!(!header.contains("G'S\r\n"), "stale unit line:\n{header}");
}

#[test]
fn bumpsim_reads_what_pyisomme_writes_folder_and_zip() {
    if !pyisomme_available() {
        return;
    }
    let dir = scratch("formats-pyisomme-writes");
    let flat = root().join("examples/identify/FLAT");
    let written = pyisomme(&["rewrite", flat.to_str().unwrap(), dir.to_str().unwrap()]);
    let dimensions = [
        Dimension::Force,
        Dimension::Acceleration,
        Dimension::Acceleration,
        Dimension::Moment,
    ];
    for (form, path) in [("folder", dir.join("PY")), ("zip", dir.join("PY.zip"))] {
        let test = TestData::open(&path).unwrap();
        let channels = written[form]["channels"].as_array().unwrap();
        assert_eq!(test.entries.len(), channels.len());
        for (i, py) in channels.iter().enumerate() {
            let ours = test.load(i).unwrap();
            assert_eq!(ours.code, py["code"].as_str().unwrap());
            assert_eq!(ours.dimension, dimensions[i], "{form} {}", ours.code);
            let times = ours.series.times();
            let scale = ours
                .series
                .values()
                .iter()
                .fold(0.0_f64, |m, v| m.max(v.abs()));
            let py_times = py["times"].as_array().unwrap();
            for (k, v) in py["values"].as_array().unwrap().iter().enumerate() {
                assert!(
                    close(number(v), ours.series.values()[k], scale),
                    "{form} {i} {k}"
                );
                assert!(close(number(&py_times[k]), times[k], 1.0), "{form} t {k}");
            }
        }
        let units: Vec<&str> = test.entries.iter().map(|e| e.unit.as_str()).collect();
        assert_eq!(
            units,
            ["N", "m / s2", "m / s2", "N m"],
            "pyisomme's spellings"
        );
    }
}

/// Spoils a channel file.
type Damage = fn(&Path);

#[test]
fn a_missing_empty_or_truncated_channel_file_leaves_the_rest_readable() {
    let dir = scratch("formats-partial");
    let cases: [(&str, Damage); 3] = [
        ("missing", |f| std::fs::remove_file(f).unwrap()),
        ("empty", |f| std::fs::write(f, "").unwrap()),
        ("truncated", |f| {
            let text = std::fs::read_to_string(f).unwrap();
            std::fs::write(f, &text[..text.len() / 2]).unwrap();
        }),
    ];
    for (what, damage) in cases {
        let test = dir.join(what).join("FLAT");
        copy_tree(&root().join("examples/identify/FLAT"), &test);
        damage(&test.join("Channel/FLAT.003"));
        let info = bumpsim(&["signal", "info", test.to_str().unwrap()]);
        let stdout = text(&info.stdout);
        assert!(info.status.success(), "{what}: {}", text(&info.stderr));
        assert_contains(
            &stdout,
            &[
                "3 channels listed, 2 with samples present",
                "absent: channel 3 (",
            ],
        );
        let out = dir.join(what).join("ok.csv");
        let run = bumpsim(&[
            "signal",
            "export",
            test.to_str().unwrap(),
            "--channel",
            "1",
            "--channel",
            "2",
            "-o",
            out.to_str().unwrap(),
        ]);
        assert!(run.status.success(), "{what}: {}", text(&run.stderr));
        let asked = bumpsim(&[
            "signal",
            "export",
            test.to_str().unwrap(),
            "--channel",
            "3",
            "-o",
            out.to_str().unwrap(),
        ]);
        assert_user_error(&asked, "channel 3 ");
        assert_user_error(&asked, "has no usable samples");
    }
    let stdout =
        text(&bumpsim(&["signal", "info", dir.join("missing/FLAT").to_str().unwrap()]).stdout);
    assert_contains(&stdout, &["FLAT.003"]);
}

#[test]
fn a_moment_in_nm_stays_a_moment() {
    let dir = scratch("formats-moment");
    let test = dir.join("LAB01");
    copy_tree(&root().join("tests/data/isomme/LAB01"), &test);
    let file = test.join("Channel/LAB01.001");
    let bytes = std::fs::read(&file).unwrap();
    let text_latin1: String = bytes.iter().map(|&b| b as char).collect();
    let moment = text_latin1
        .replace(":P0IMPA000000FOXP", ":P0IMPA000000MOXP")
        .replace(
            "Unit                        :kN",
            "Unit                        :Nm",
        );
    std::fs::write(&file, moment.chars().map(|c| c as u8).collect::<Vec<u8>>()).unwrap();
    let out = dir.join("moment.csv");
    let run = bumpsim(&[
        "signal",
        "export",
        test.to_str().unwrap(),
        "--channel",
        "1",
        "-o",
        out.to_str().unwrap(),
    ]);
    let stdout = text(&run.stdout);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(
        stdout.contains(" Nm at") && !stdout.contains(" J"),
        "{stdout}"
    );
    let csv = std::fs::read_to_string(&out).unwrap();
    assert!(csv.starts_with("time [s],P0IMPA000000MOXP [Nm]\n"), "{csv}");
}

#[test]
fn unit_ms_applies_to_the_time_column_and_an_unused_unit_is_refused() {
    let dir = scratch("formats-unit");
    let flat = root().join("examples/identify/FLAT");
    let out = dir.join("ms.csv");
    let run = bumpsim(&[
        "signal",
        "export",
        flat.to_str().unwrap(),
        "--channel",
        "1",
        "--unit",
        "ms",
        "--unit",
        "kN",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let (header, rows) = read_csv(&out);
    assert_eq!(header, ["time [ms]", "P0IMPA000000FOXP [kN]"]);
    assert!((rows[0][0] - -50.0).abs() < 1e-9, "{}", rows[0][0]);
    assert!((rows[1][0] - rows[0][0] - 0.1).abs() < 1e-9);
    let unused = bumpsim(&[
        "signal",
        "export",
        flat.to_str().unwrap(),
        "--channel",
        "1",
        "--unit",
        "deg",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_user_error(&unused, "--unit deg: no column measures angle");
}

#[test]
fn the_figures_docs_signals_quotes_are_what_the_command_prints() {
    let Some(_) = nhtsa_ev5() else { return };
    let docs = std::fs::read_to_string(root().join("docs/signals.md")).unwrap();
    let command = "bumpsim signal process examples/nhtsa-10146/pipeline.toml";
    let after = &docs[docs.find(command).expect("the documented command")..];
    let block = after
        .split("```text\n")
        .nth(1)
        .unwrap()
        .split("```")
        .next()
        .unwrap();
    let csv = scratch("formats-docs").join("signals.csv");
    let pipeline = root().join("examples/nhtsa-10146/pipeline.toml");
    let run = bumpsim(&[
        "signal",
        "process",
        pipeline.to_str().unwrap(),
        "-o",
        csv.to_str().unwrap(),
    ]);
    let stdout = text(&run.stdout);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let quoted: Vec<&str> = block.lines().filter(|l| !l.trim().is_empty()).collect();
    assert_eq!(quoted.len(), 4, "{block}");
    for line in quoted {
        assert!(
            stdout.lines().any(|l| l == line),
            "docs/signals.md quotes\n{line}\nbut the command prints\n{stdout}"
        );
    }
    assert_contains(
        &docs,
        &[
            "crush is 746 mm at 74 ms",
            "min -2.605 m/s",
            "peak 746.0 mm",
        ],
    );
}

/// A copy of the bundled FLAT test whose channel 3 header line
/// `Sampling interval` says `value` (the files are written, not copied:
/// a copy would keep a read-only source's permissions).
fn flat_with_interval(dir: &Path, value: &str) -> PathBuf {
    let test = dir.join("FLAT");
    copy_tree(&root().join("examples/identify/FLAT"), &test);
    let file = test.join("Channel/FLAT.003");
    let spoiled: String = std::fs::read_to_string(&file)
        .unwrap()
        .lines()
        .map(|l| match l.starts_with("Sampling interval") {
            true => format!("Sampling interval           :{value}\r\n"),
            false => format!("{l}\r\n"),
        })
        .collect();
    std::fs::write(&file, spoiled).unwrap();
    test
}

#[test]
fn an_iso_mme_sampling_interval_outside_1ns_to_1s_is_refused_naming_the_line() {
    let dir = scratch("formats-interval");
    for value in ["1e308", "1e-12", "2"] {
        let test = flat_with_interval(&dir.join(value), value);
        let out = dir.join(value).join("o.csv");
        let args = ["signal", "export", test.to_str().unwrap(), "-c", "3"];
        let run = bumpsim(&[&args[..], &["-o", out.to_str().unwrap()]].concat());
        assert_user_error(&run, "FLAT.003:23: 'Sampling interval' ");
        assert_user_error(&run, "expected 1e-9 to 1 s");
        assert!(!out.exists(), "{value}");
    }
    let test = flat_with_interval(&dir.join("ok"), "1e-5");
    let out = dir.join("ok/o.csv");
    let args = ["signal", "export", test.to_str().unwrap(), "-c", "3"];
    let run = bumpsim(&[&args[..], &["-o", out.to_str().unwrap()]].concat());
    assert!(run.status.success(), "{}", text(&run.stderr));
}

#[test]
fn an_ev5_channel_line_with_a_third_value_is_refused_naming_the_line() {
    let Some(ev5) = nhtsa_ev5() else { return };
    let dir = scratch("formats-ev5-third");
    std::fs::create_dir_all(&dir).unwrap();
    let copy = |name: &str, edit: &dyn Fn(String) -> String| {
        let text = std::fs::read_to_string(ev5.with_file_name(name)).unwrap();
        std::fs::write(dir.join(name), edit(text)).unwrap();
    };
    copy("v10146.EV5", &|t| t);
    let third = |t: String| {
        let mut lines: Vec<String> = t.lines().map(str::to_string).collect();
        lines[49].push_str("\t7.5");
        lines.join("\n") + "\n"
    };
    copy("v10146.093", &third);
    let out = dir.join("o.csv");
    let test = dir.join("v10146.EV5");
    let args = ["signal", "export", test.to_str().unwrap(), "-c", "93"];
    let run = bumpsim(&[&args[..], &["-o", out.to_str().unwrap()]].concat());
    assert_user_error(&run, "v10146.093:50: ");
    assert_user_error(&run, "two finite numbers and nothing more");
    assert!(!out.exists());
}
