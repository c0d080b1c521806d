//! Crash data to the letter, round 2 (issue 33): each finding reproduced
//! through the commands and read back with pyisomme
//! (tests/peers/pyisomme_headers.py), and every ISO-MME writer's complete
//! channel header through pyisomme and back.

use crate::util::*;
use bumpsim_io::test_data::{TestData, Validity};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

fn pyisomme_available() -> bool {
    peer_available("pyisomme", "python3", &["-c", "import pyisomme"])
}

/// tests/peers/pyisomme_headers.py `read PATH` or `copy PATH OUT`.
fn pyisomme(args: &[&Path]) -> Value {
    let mode = if args.len() == 1 { "read" } else { "copy" };
    let run = Command::new("python3")
        .arg(root().join("tests/peers/pyisomme_headers.py"))
        .arg(mode)
        .args(args)
        .output()
        .unwrap();
    assert!(run.status.success(), "pyisomme: {}", text(&run.stderr));
    serde_json::from_slice(&run.stdout).unwrap()
}

fn ok(args: &[&str]) -> (String, String) {
    let run = bumpsim(args);
    let (out, err) = (text(&run.stdout), text(&run.stderr));
    assert!(run.status.success(), "{args:?}: {out}{err}");
    (out, err)
}

/// The value of `key` in a pyisomme header list.
fn header<'v>(items: &'v Value, key: &str) -> Option<&'v str> {
    let items = items.as_array()?;
    let item = items.iter().find(|i| i[0] == key)?;
    item[1].as_str()
}

fn codes(read: &Value) -> Vec<String> {
    let channels = read["channels"].as_array().unwrap();
    channels
        .iter()
        .map(|c| c["code"].as_str().unwrap().to_string())
        .collect()
}

/// Items 1–3: a CSV cut to the common span says so; no two columns or ISO
/// codes are one; an invalid NHTSA channel reads back invalid.
#[test]
fn nhtsa_export_notes_its_span_keeps_codes_apart_and_marks_the_invalid_channel() {
    let Some(ev5) = nhtsa_ev5() else { return };
    if !pyisomme_available() {
        return;
    }
    let dir = scratch("letter-nhtsa");
    let (csv, mme) = (dir.join("raw.csv"), dir.join("RAW"));
    let (_, err) = ok(&[
        "signal",
        "export",
        ev5.to_str().unwrap(),
        "-c",
        "93",
        "-c",
        "94",
        "-c",
        "95",
        "-c",
        "96",
        "-o",
        csv.to_str().unwrap(),
        "--iso-mme",
        mme.to_str().unwrap(),
    ]);
    assert_contains(
        &err,
        &[
            "raw.csv: 4 channels put on one time base",
            "2330 samples each outside that span left out",
        ],
    );
    let (names, rows) = read_csv(&csv);
    assert_eq!(
        names[3..],
        ["1-AC-ENGN-XG#95 [m/s^2]", "1-AC-ENGN-XG#96 [m/s^2]"]
    );
    assert_eq!(rows.len(), 1170);
    let (info, _) = ok(&["signal", "info", csv.to_str().unwrap()]);
    assert_contains(&info, &["4 channels listed"]);
    let read = pyisomme(&[&mme]);
    assert_eq!(
        codes(&read),
        [
            "10SECMLE0000ACXP",
            "10SECMRI0000ACXP",
            "10ENGN000001ACXP",
            "10ENGN000002ACXP"
        ]
    );
    let lengths: Vec<usize> = read["channels"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["values"].as_array().unwrap().len())
        .collect();
    assert_eq!(
        lengths,
        [3500, 3500, 3500, 1170],
        "the ISO-MME keeps every sample"
    );
    assert_eq!(
        header(&read["channels"][3]["header"], "Data status"),
        Some("channel failed")
    );
    assert_eq!(
        header(&read["channels"][2]["header"], "Data status"),
        Some("NOVALUE")
    );
    let test = TestData::open(&mme).unwrap();
    assert!(
        matches!(test.entries[3].validity, Validity::Invalid(ref why) if why.contains("No valid data after 67ms"))
    );
    assert_eq!(
        test.select("10ENGN*").unwrap().indices,
        vec![2],
        "wildcards leave the failed channel out"
    );
}

/// Item 4: CFC 1000 on a CFC 60 channel keeps `D` and CFC 60, and warns.
#[test]
fn a_finer_cfc_on_a_cfc_60_channel_stays_cfc_60() {
    if !pyisomme_available() {
        return;
    }
    let dir = scratch("letter-refilter");
    let flat = root().join("examples/identify/FLAT");
    let (c60, c1000) = (dir.join("C60"), dir.join("C1000"));
    let csv = |name: &str| dir.join(name).to_str().unwrap().to_string();
    ok(&[
        "signal",
        "export",
        flat.to_str().unwrap(),
        "-c",
        "2",
        "--cfc",
        "60",
        "-o",
        &csv("a.csv"),
        "--iso-mme",
        c60.to_str().unwrap(),
    ]);
    let (_, err) = ok(&[
        "signal",
        "export",
        c60.to_str().unwrap(),
        "-c",
        "1",
        "--cfc",
        "1000",
        "-o",
        &csv("b.csv"),
        "--iso-mme",
        c1000.to_str().unwrap(),
    ]);
    assert_contains(&err, &["CFC 1000 after CFC 60 leaves it limited to CFC 60"]);
    let read = pyisomme(&[&c1000]);
    assert_eq!(codes(&read), ["10SIMELE0000ACXD"]);
    assert_eq!(read["channels"][0]["filter_class"], "D");
    assert_eq!(
        header(&read["channels"][0]["header"], "Channel frequency class"),
        Some("60")
    );
}

/// Item 5: the sum of the barrier cells is coded and named as a sum.
#[test]
fn a_sum_of_barrier_cells_is_written_as_a_sum() {
    let Some(ev5) = nhtsa_ev5() else { return };
    if !pyisomme_available() {
        return;
    }
    let dir = scratch("letter-sum");
    let mme = dir.join("SUM");
    let csv = dir.join("sum.csv");
    ok(&[
        "signal",
        "export",
        ev5.to_str().unwrap(),
        "-c",
        "0-LC-*-XG",
        "--combine",
        "sum",
        "-o",
        csv.to_str().unwrap(),
        "--iso-mme",
        mme.to_str().unwrap(),
    ]);
    let read = pyisomme(&[&mme]);
    assert_eq!(codes(&read), ["B0LOMASU0000FOXP"]);
    assert_eq!(read["channels"][0]["valid"], true);
    let h = &read["channels"][0]["header"];
    assert_eq!(
        header(h, "Name of the channel"),
        Some("sum of 174 channels 0-LC-*-XG")
    );
    assert!(
        header(h, "Comments")
            .unwrap()
            .starts_with("sum of 174 channels: B0LOMA")
    );
}

/// Item 9: a channel file without a time base is absent, the rest exports.
#[test]
fn a_channel_without_a_time_base_is_absent_and_the_rest_exports() {
    let dir = scratch("letter-timeless");
    let test = dir.join("FLAT");
    copy_tree(&root().join("examples/identify/FLAT"), &test);
    let file = test.join("Channel/FLAT.003");
    let kept: String = std::fs::read_to_string(&file)
        .unwrap()
        .lines()
        .filter(|l| !l.starts_with("Sampling interval") && !l.starts_with("Time of first sample"))
        .map(|l| format!("{l}\r\n"))
        .collect();
    std::fs::write(&file, kept).unwrap();
    let (info, _) = ok(&["signal", "info", test.to_str().unwrap()]);
    assert_contains(
        &info,
        &[
            "3 channels listed, 2 with samples present",
            "absent: channel 3 (",
        ],
    );
    let out = dir.join("all.csv");
    let (_, err) = ok(&[
        "signal",
        "export",
        test.to_str().unwrap(),
        "-c",
        "*",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_contains(&err, &["'*': left out channel 3 ("]);
    assert_eq!(
        read_csv(&out).0.len(),
        3,
        "time and the two readable channels"
    );
}

/// The 1-D synth (item 7: the car is test object 1, as its codes say) and
/// the planar synth (item 6: LOMA and SILB; item 7: its mass).
#[test]
fn synth_headers_number_the_test_objects_as_the_codes_do() {
    if !pyisomme_available() {
        return;
    }
    let read = pyisomme(&[&root().join("examples/identify/FLAT")]);
    assert_eq!(header(&read["test"], "Name of test object 1"), Some("car"));
    assert_eq!(header(&read["test"], "Velocity test object 1"), Some("0.0"));
    assert_eq!(
        header(&read["test"], "Name of test object 2"),
        Some("pendulum")
    );
    let numbers: Vec<Option<&str>> = (0..3)
        .map(|i| header(&read["channels"][i]["header"], "Test object number"))
        .collect();
    assert_eq!(numbers, [Some("2"), Some("1"), Some("1")]);
    let h = &read["channels"][1]["header"];
    assert_eq!(
        (
            header(h, "Test object"),
            header(h, "Position"),
            header(h, "Location")
        ),
        (Some("1"), Some("0"), Some("SIMELE0000"))
    );
    let test = TestData::open(&root().join("examples/identify/FLAT")).unwrap();
    let speed = test.speed.unwrap();
    assert!(
        (speed - 6.0 / 3.6).abs() < 1e-12,
        "the moving object's speed: {speed}"
    );
    let dir = scratch("letter-planar-synth").join("series");
    ok(&[
        "synth",
        root()
            .join("examples/planar/identify/series.toml")
            .to_str()
            .unwrap(),
        "-o",
        dir.to_str().unwrap(),
    ]);
    let mut seen = Vec::new();
    for entry in std::fs::read_dir(&dir)
        .unwrap()
        .flatten()
        .filter(|e| e.path().is_dir())
    {
        let read = pyisomme(&[&entry.path()]);
        let mass = header(&read["test"], "Mass test object 1").unwrap_or("absent");
        assert!(
            mass.parse::<f64>().is_ok_and(|m| m > 500.0),
            "{}: {mass}",
            entry.path().display()
        );
        for c in read["channels"].as_array().unwrap() {
            assert_eq!(
                c["valid"], true,
                "{} is not in the standard's table",
                c["code"]
            );
            seen.push(c["code"].as_str().unwrap()[2..6].to_string());
        }
    }
    assert!(
        seen.iter().any(|m| m == "LOMA") && seen.iter().any(|m| m == "SILB"),
        "{seen:?}"
    );
}

/// Build 3: a pipeline's derivative and mass steps written as ISO-MME show
/// their code changes (DS → VE → AC, AC → FO).
#[test]
fn pipeline_derivatives_and_mass_write_their_codes_to_iso_mme() {
    if !pyisomme_available() {
        return;
    }
    let dir = scratch("letter-pipeline");
    let flat = root().join("examples/identify/FLAT");
    let pipeline = dir.join("chain.toml");
    let toml = format!(
        "[[signal]]\nname = \"crush\"\npath = {:?}\nchannels = [\"10SIMELE0000ACXP\"]\nsteps = [{{ pretrigger_bias = true }}, {{ cfc = 180 }}, {{ integrate = 0.0 }}, {{ integrate = 0.0 }}]\n\n\
         [[signal]]\nname = \"velocity\"\nfrom = \"crush\"\nsteps = [{{ derivative = true }}]\n\n\
         [[signal]]\nname = \"acceleration\"\nfrom = \"velocity\"\nsteps = [{{ derivative = true }}]\n\n\
         [[signal]]\nname = \"force\"\nfrom = \"acceleration\"\nsteps = [{{ mass = 1450 }}]\n",
        flat.display().to_string()
    );
    std::fs::write(&pipeline, toml).unwrap();
    let (mme, csv) = (dir.join("CHAIN"), dir.join("chain.csv"));
    ok(&[
        "signal",
        "process",
        pipeline.to_str().unwrap(),
        "-o",
        csv.to_str().unwrap(),
        "--iso-mme",
        mme.to_str().unwrap(),
    ]);
    let read = pyisomme(&[&mme]);
    assert_eq!(
        codes(&read),
        [
            "10SIMELE0000DSXC",
            "10SIMELE0000VEXC",
            "10SIMELE0000ACXC",
            "10SIMELE0000FOXC"
        ]
    );
    let units: Vec<&str> = read["channels"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["unit"].as_str().unwrap())
        .collect();
    assert_eq!(units, ["m", "m / s", "m / s2", "N"]);
    let h = &read["channels"][0]["header"];
    assert_eq!(
        (
            header(h, "Start offset interval"),
            header(h, "End offset interval")
        ),
        (Some("-0.05"), Some("0.0"))
    );
    assert_eq!(header(h, "Laboratory channel code"), Some("crush"));
}

/// The round trip: bumpsim's header as pyisomme reads it, key for key, and
/// pyisomme's copy as bumpsim reads it, for each writer (export, process,
/// synth 1-D and planar).
#[test]
fn every_writer_keeps_the_complete_channel_header_through_pyisomme() {
    if !pyisomme_available() {
        return;
    }
    let dir = scratch("letter-roundtrip");
    let flat = root().join("examples/identify/FLAT");
    let exported = dir.join("EXP");
    ok(&[
        "signal",
        "export",
        flat.to_str().unwrap(),
        "-c",
        "*",
        "--bias",
        "--cfc",
        "180",
        "-o",
        dir.join("e.csv").to_str().unwrap(),
        "--iso-mme",
        exported.to_str().unwrap(),
    ]);
    let processed = dir.join("PROC");
    let pipeline = dir.join("p.toml");
    std::fs::write(&pipeline, format!("[[signal]]\nname = \"force\"\npath = {:?}\nchannels = [\"1\"]\nsteps = [{{ cfc = 60 }}]\n", flat.display().to_string())).unwrap();
    ok(&[
        "signal",
        "process",
        pipeline.to_str().unwrap(),
        "-o",
        dir.join("p.csv").to_str().unwrap(),
        "--iso-mme",
        processed.to_str().unwrap(),
    ]);
    let mut tests: Vec<PathBuf> = vec![exported, processed, flat];
    if let Some(ev5) = nhtsa_ev5() {
        let nh = dir.join("NH");
        ok(&[
            "signal",
            "export",
            ev5.to_str().unwrap(),
            "-c",
            "93",
            "-c",
            "587",
            "-o",
            dir.join("n.csv").to_str().unwrap(),
            "--iso-mme",
            nh.to_str().unwrap(),
        ]);
        tests.push(nh);
    }
    for test in &tests {
        round_trip(
            test,
            &dir.join(format!(
                "PY{}",
                tests.iter().position(|t| t == test).unwrap()
            )),
        );
    }
}

/// bumpsim's header keys and values = pyisomme's reading of them, and its
/// samples to the last bit; pyisomme's copy read by bumpsim has the same
/// keys and values (numbers to 1e-12) and samples to pyisomme's printing
/// (pandas' six decimals).
fn round_trip(test: &Path, copy: &Path) {
    let ours = TestData::open(test).unwrap();
    let read = pyisomme(&[test]);
    let channels = read["channels"].as_array().unwrap();
    assert_eq!(channels.len(), ours.entries.len());
    for (i, (entry, py)) in ours.entries.iter().zip(channels).enumerate() {
        let items = py["header"].as_array().unwrap();
        let theirs: Vec<(String, String)> = items
            .iter()
            .map(|i| {
                (
                    i[0].as_str().unwrap().to_string(),
                    i[1].as_str().unwrap().to_string(),
                )
            })
            .collect();
        same_header(&entry.metadata, &theirs, test);
        let values: Vec<f64> = py["values"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        assert_eq!(
            values,
            ours.load(i).unwrap().series.values(),
            "{}: samples",
            entry.code
        );
    }
    let copied = pyisomme(&[test, copy]);
    let back = TestData::open(copy).unwrap();
    assert_eq!(back.entries.len(), ours.entries.len());
    for (i, (a, b)) in ours.entries.iter().zip(&back.entries).enumerate() {
        assert_eq!(a.code, b.code);
        assert_eq!(copied["channels"][i]["code"], a.code.as_str());
        same_header(&a.metadata, &b.metadata, copy);
        let (x, y) = (ours.load(i).unwrap(), back.load(i).unwrap());
        let scale = x
            .series
            .values()
            .iter()
            .fold(0.0_f64, |m, v| m.max(v.abs()));
        let printed = x.series.values().iter().zip(y.series.values());
        assert!(
            printed
                .clone()
                .all(|(p, q)| (p - q).abs() <= 1e-6 * scale.max(1.0)),
            "{}: samples",
            a.code
        );
        assert_eq!(x.series.len(), y.series.len());
    }
}

/// Same keys in the same order, same values (numbers within 1e-12 relative).
fn same_header(a: &[(String, String)], b: &[(String, String)], test: &Path) {
    let keys = |h: &[(String, String)]| h.iter().map(|(k, _)| k.clone()).collect::<Vec<_>>();
    assert_eq!(keys(a), keys(b), "{}: header keys", test.display());
    for ((key, x), (_, y)) in a.iter().zip(b) {
        let unit = |u: &str| bumpsim_core::units::Unit::parse(u).map(|u| (u.dimension, u.factor));
        let same = match (x.trim().parse::<f64>(), y.trim().parse::<f64>()) {
            // pyisomme spells m/s**2 'm / s2': the same unit
            _ if key == "Unit" => unit(x).is_ok() && unit(x).ok() == unit(y).ok(),
            (Ok(p), Ok(q)) => (p - q).abs() <= 1e-12 * p.abs().max(q.abs()),
            _ => x.trim() == y.trim(),
        };
        assert!(same, "{}: '{key}' is '{x}' and '{y}'", test.display());
    }
}
