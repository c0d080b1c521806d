//! Integration tests of the test-data readers and writers: the hand-written
//! ISO-MME lab sample, an ISO-MME round trip (folder and zip), bad input, and
//! the real NHTSA test 10146 (skipped with a message when `../shared` is absent).

use approx::assert_relative_eq;
use bumpsim_core::units::{Dimension, STANDARD_GRAVITY};
#[cfg(feature = "zip")]
use bumpsim_io::isomme;
use bumpsim_io::test_data::{Format, TestData, Validity};
use std::path::{Path, PathBuf};

#[path = "readers/roundtrip.rs"]
mod roundtrip;

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn sample() -> PathBuf {
    repo().join("tests/data/isomme/LAB01")
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("bumpsim-io-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap().flatten() {
        let target = to.join(entry.file_name());
        match entry.path().is_dir() {
            true => copy_dir(&entry.path(), &target),
            false => drop(std::fs::copy(entry.path(), target).unwrap()),
        }
    }
}

#[test]
fn lab_sample_reads_latin1_crlf_novalue_and_explicit_time() {
    let test = TestData::open(&sample()).unwrap();
    assert_eq!(test.format, Format::IsoMme);
    assert_eq!(test.title, "Pendel gegen Stoßfänger, flacher Kopf");
    assert_relative_eq!(test.mass.unwrap(), 1450.0);
    assert_relative_eq!(test.speed.unwrap(), 1.6667);
    assert_eq!(test.entries.len(), 3);
    assert_eq!(test.entries[1].name, "Längsträger links X");
    let force = test.load(0).unwrap();
    assert_eq!(force.dimension, Dimension::Force);
    assert_eq!(force.source_unit, "kN");
    assert_relative_eq!(force.series.peak().1, 20_000.0, max_relative = 3e-3);
    assert_relative_eq!(force.series.start(), -1e-3, max_relative = 1e-12);
    let accel = test.load(1).unwrap();
    assert_eq!(accel.dimension, Dimension::Acceleration);
    assert_relative_eq!(accel.series.step(), 1e-4, max_relative = 1e-9);
    assert_relative_eq!(accel.series.start(), -1e-3, max_relative = 1e-9);
    let min = accel.series.values().iter().cloned().fold(0.0, f64::min);
    assert_relative_eq!(min, -3.0 * STANDARD_GRAVITY, max_relative = 3e-3);
    assert_eq!(accel.meta("Laboratory channel code"), None);
    assert_eq!(force.meta("Laboratory channel code"), Some("NOVALUE"));
}

#[test]
fn the_mme_file_and_selection_by_code_number_and_name() {
    let test = TestData::open(&sample().join("LAB01.mme")).unwrap();
    assert_eq!(test.select("10SIME??0000ACXP").unwrap().indices, vec![1]);
    assert_eq!(test.select("#1").unwrap().indices, vec![0]);
    assert_eq!(test.select("p0impa000000foxp").unwrap().indices, vec![0]);
    assert_eq!(test.select("längsträger").unwrap().indices, vec![1]);
    let err = test.select("11HEAD*").unwrap_err().to_string();
    assert!(
        err.contains("LAB01.mme") && err.contains("11HEAD*") && err.contains("matches no channel"),
        "{err}"
    );
}

#[cfg(feature = "zip")]
#[test]
fn round_trip_folder_and_zip() {
    let a = TestData::open(&sample()).unwrap();
    let channels_a: Vec<_> = (0..3).map(|i| a.load(i).unwrap()).collect();
    let out = scratch("roundtrip");
    isomme::write(&out.join("B"), "B", &a.metadata, &channels_a).unwrap();
    let b = TestData::open(&out.join("B")).unwrap();
    let channels_b: Vec<_> = (0..3).map(|i| b.load(i).unwrap()).collect();
    assert_eq!(b.metadata, a.metadata);
    for (x, y) in channels_a.iter().zip(&channels_b) {
        assert_eq!(
            x.series.values(),
            y.series.values(),
            "values must be bit-identical"
        );
        assert_eq!(
            (x.code.as_str(), x.name.as_str(), x.dimension),
            (y.code.as_str(), y.name.as_str(), y.dimension)
        );
        assert_relative_eq!(x.series.start(), y.series.start(), max_relative = 1e-12);
        assert_relative_eq!(x.series.step(), y.series.step(), max_relative = 1e-12);
        for (key, value) in x.metadata.iter().filter(|(k, _)| !is_own_key(k)) {
            let written = y.meta(key).unwrap_or_default();
            assert!(
                written.starts_with(value.as_str()),
                "metadata {key}: {written}"
            );
        }
        if x.source_unit != y.source_unit {
            let note = format!(
                "converted from {} to {}",
                x.source_unit,
                y.source_unit.replace('^', "**")
            );
            assert!(y.meta("Comments").unwrap().contains(&note), "{note}");
        }
    }
    isomme::write(&out.join("C"), "C", &b.metadata, &channels_b).unwrap();
    let c = TestData::open(&out.join("C/C.mme")).unwrap();
    for (i, channel) in channels_b.iter().enumerate() {
        assert_eq!(
            &c.load(i).unwrap(),
            channel,
            "second round trip is exact, metadata included"
        );
    }
    let zipped = out.join("B.zip");
    zip_folder(&out.join("B"), &zipped);
    let z = TestData::open(&zipped).unwrap();
    assert_eq!(
        z.load(1).unwrap().series.values(),
        channels_a[1].series.values()
    );
}

#[cfg(feature = "zip")]
fn is_own_key(key: &str) -> bool {
    [
        "Unit",
        "Reference channel",
        "Reference channel name",
        "Time of first sample",
        "Sampling interval",
    ]
    .contains(&key)
}

#[cfg(feature = "zip")]
fn zip_folder(folder: &Path, zip_path: &Path) {
    let file = std::fs::File::create(zip_path).unwrap();
    let mut zip = zip::ZipWriter::new(file);
    let options =
        zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Stored);
    let mut add = |name: String, path: &Path| {
        zip.start_file(name, options).unwrap();
        std::io::Write::write_all(&mut zip, &std::fs::read(path).unwrap()).unwrap();
    };
    add("B/B.mme".into(), &folder.join("B.mme"));
    for entry in std::fs::read_dir(folder.join("Channel")).unwrap().flatten() {
        add(
            format!("B/Channel/{}", entry.file_name().to_string_lossy()),
            &entry.path(),
        );
    }
    zip.finish().unwrap();
}

/// Copies the sample, applies `edit` to one file, and returns the error of loading channel `index`.
fn broken(name: &str, file: &str, edit: impl Fn(&str) -> String, index: usize) -> String {
    let dir = scratch(name).join("LAB01");
    copy_dir(&sample(), &dir);
    let path = dir.join(file);
    match edit(&String::from_utf8_lossy(&std::fs::read(&path).unwrap())) {
        text if text.is_empty() => std::fs::remove_file(&path).unwrap(),
        text => std::fs::write(&path, text).unwrap(),
    }
    match TestData::open(&dir) {
        Err(e) => e.to_string(),
        Ok(test) => test.load(index).unwrap_err().to_string(),
    }
}

#[test]
fn truncated_channel_file_names_file_and_line() {
    let err = broken(
        "trunc",
        "Channel/LAB01.001",
        |t| t.lines().take(30).collect::<Vec<_>>().join("\r\n"),
        0,
    );
    assert!(
        err.contains("LAB01.001:30:") && err.contains("declares 40 samples but the file holds 19"),
        "{err}"
    );
}

#[test]
fn sample_count_mismatch_is_reported() {
    let err = broken(
        "count",
        "Channel/LAB01.001",
        |t| {
            t.replace(
                "Number of samples           :40",
                "Number of samples           :41",
            )
        },
        0,
    );
    assert!(
        err.contains("LAB01.001:") && err.contains("declares 41 samples but the file holds 40"),
        "{err}"
    );
}

#[test]
fn missing_chn_names_the_expected_file() {
    let err = broken("chn", "Channel/LAB01.chn", |_| String::new(), 0);
    assert!(
        err.contains("LAB01.chn") && err.contains("missing"),
        "{err}"
    );
}

#[test]
fn unknown_unit_names_the_line() {
    let err = broken(
        "unit",
        "Channel/LAB01.001",
        |t| t.replace(":kN", ":furlong"),
        0,
    );
    assert!(
        err.contains("LAB01.001:5:") && err.contains("furlong"),
        "{err}"
    );
}

#[test]
fn bad_value_names_the_line() {
    let err = broken(
        "value",
        "Channel/LAB01.003",
        |t| t.replacen("-0.001", "oops", 1),
        1,
    );
    assert!(
        err.contains("LAB01.003:7:") && err.contains("'oops' is not a finite number"),
        "{err}"
    );
}

fn nhtsa() -> Option<PathBuf> {
    let path = repo().join("../shared/data/nhtsa-10146/v10146.EV5");
    if !path.exists() {
        eprintln!(
            "SKIPPED: {} is absent (the NHTSA test 10146 is read from ../shared, not copied)",
            path.display()
        );
        return None;
    }
    Some(path)
}

#[test]
fn nhtsa_header_channels_and_invalid_cells() {
    let Some(path) = nhtsa() else { return };
    let test = TestData::open(&path).unwrap();
    assert_eq!(test.format, Format::NhtsaEv5);
    assert_eq!(test.entries.len(), 634);
    assert_eq!(test.entries.iter().filter(|e| e.present).count(), 184);
    assert_relative_eq!(test.speed.unwrap(), 57.09 / 3.6, max_relative = 1e-12);
    assert_relative_eq!(test.mass.unwrap(), 1719.0);
    let cells = test.select("0-LC-*-XG").unwrap();
    assert_eq!(cells.indices.len(), 174);
    let excluded: Vec<usize> = cells
        .excluded
        .iter()
        .map(|&i| test.entries[i].number)
        .collect();
    assert_eq!(excluded, vec![347, 500]);
    assert_eq!(
        cells.absent.len(),
        1,
        "curve 109 is an Mz cell labelled XG whose file is absent"
    );
    assert!(
        matches!(test.entries[346].validity, Validity::Invalid(ref why) if why.contains("No valid data"))
    );
    let left = test.load(test.select("93").unwrap().indices[0]).unwrap();
    assert_eq!(left.code, "1-AC-FLLR-XG");
    assert_eq!(left.series.len(), 3500);
    assert_relative_eq!(left.series.start(), -0.05, max_relative = 1e-12);
    assert_relative_eq!(left.series.step(), 1e-4, max_relative = 1e-12);
    let explicit = test.select("347").unwrap();
    assert_eq!(explicit.warnings.len(), 1);
    let absent = test.select("1").unwrap_err().to_string();
    assert!(absent.contains("absent"), "{absent}");
    // a wildcard matching only channels without a file counts them (it
    // counted only the invalid ones: "0 of them")
    let none = test.select("1-AC-HDCG-*").unwrap_err().to_string();
    assert!(none.contains("missing or unusable (12 of them)"), "{none}");
}

/// Issue 34: two instrumentation rows numbered 93 put the left
/// crossmember's samples (`.093`) in the right one's column too.
#[test]
fn ev5_curve_numbers_given_twice_are_refused() {
    let Some(path) = nhtsa() else { return };
    let dir = scratch("ev5-twice");
    let bytes = std::fs::read(&path).unwrap();
    let (from, to) = (b"\n1|94|AC|NA|FLRR|", b"\n1|93|AC|NA|FLRR|");
    let at = bytes.windows(from.len()).position(|w| w == from).unwrap();
    let mut edited = bytes.clone();
    edited[at..at + to.len()].copy_from_slice(to);
    let copy = dir.join("v10146.EV5");
    std::fs::write(&copy, edited).unwrap();
    std::fs::copy(path.with_extension("093"), dir.join("v10146.093")).unwrap();
    let e = TestData::open(&copy).unwrap_err().to_string();
    assert!(
        e.contains("v10146.EV5:114: curve number 93 is also the number of line 113"),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
