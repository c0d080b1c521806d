//! NHTSA "EV5 ASCII X-Y" test data (spec §4).
//!
//! `<v>.EV5` holds sections `----- TEST -----`, `----- VEHICLE -----`,
//! `----- INSTRUMENTATION -----`, ... with `|`-separated fields. Used here:
//! - TEST: field 2 title, 15 closing speed (km/h), 19 number of curves;
//! - VEHICLE: field 1 vehicle number, 11 test mass (kg);
//! - INSTRUMENTATION, one row per curve: 1 vehicle number (0 = barrier),
//!   2 curve number, 3 sensor type (`AC`, `LC`), 5 sensor location, 6 axis,
//!   7 time unit, 8 value unit (`G'S`, `NWT`), 14 initial velocity (km/h),
//!   15 and 16 first and last point, 17 sample interval (µs), 18 status
//!   (`NO` = not installed), 19 primary/redundant (`P`/`R`), 20 comment.
//!
//! Each curve's samples are in `<v>.NNN` (curve number, 3 digits), one
//! `time<TAB>value` line per sample. Channel codes are
//! `VEHICLE-SENSOR-LOCATION-AXIS` (e.g. `0-LC-LC0601-XG`, `1-AC-FLLR-XG`),
//! with `-R` appended for a redundant sensor. A curve whose comment says
//! `No valid data` or whose status is `NO` is marked invalid.

use super::{Entry, Format, Store, TestData, Validity};
use crate::signal_error::{SignalFileError, parse_number, read_text};
use bumpsim_core::channel::Channel;
use bumpsim_core::series::UniformSeries;
use bumpsim_core::units::Unit;
use std::path::{Path, PathBuf};

/// The instrumentation field names, in order (1-based field = index + 1).
const FIELDS: [&str; 20] = [
    "Vehicle number",
    "Curve number",
    "Sensor type",
    "Occupant location",
    "Sensor location",
    "Axis",
    "Time unit",
    "Units",
    "Prefilter (Hz)",
    "Sensor",
    "Calibration date",
    "Range",
    "Channel",
    "Initial velocity (km/h)",
    "First point",
    "Last point",
    "Sample interval (us)",
    "Status",
    "Primary/redundant",
    "Comment",
];

/// Opens an `.EV5` file; channel files are looked for beside it.
pub fn open(path: &Path) -> Result<TestData, SignalFileError> {
    let text = read_text(path)?;
    let sections = sections(&text);
    let test = first_row(&sections, "TEST").unwrap_or_default();
    let vehicle = first_row(&sections, "VEHICLE").unwrap_or_default();
    let field = |row: &[String], i: usize| {
        row.get(i - 1)
            .map(|s| s.trim().to_string())
            .unwrap_or_default()
    };
    let rows: Vec<_> = sections
        .iter()
        .filter(|(name, ..)| name == "INSTRUMENTATION")
        .collect();
    if rows.is_empty() {
        return Err(SignalFileError::file(path, not_a_test(&text)));
    }
    let mut entries = Vec::new();
    let mut files = Vec::new();
    let mut lines: Vec<(usize, usize)> = Vec::new();
    for (_, line, row) in rows {
        let entry = instrument(row, path, *line)?;
        // two rows of one number would share one channel file
        if let Some((_, first)) = lines.iter().find(|(n, _)| *n == entry.number) {
            let message = format!(
                "curve number {} is also the number of line {first}: each curve needs its own (its samples are the file .{:03})",
                entry.number, entry.number
            );
            return Err(SignalFileError::line(path, *line, message));
        }
        lines.push((entry.number, *line));
        let file = channel_file(path, entry.number);
        let empty = file
            .as_deref()
            .is_some_and(|f| std::fs::metadata(f).is_ok_and(|m| m.len() == 0));
        entries.push(Entry {
            present: file.is_some() && !empty,
            absence: empty.then(|| "empty channel file".to_string()),
            ..entry
        });
        files.push(file);
    }
    let metadata = vec![
        ("Title".to_string(), field(&test, 2)),
        ("Test date".to_string(), field(&test, 4)),
        ("Laboratory".to_string(), field(&test, 5)),
        ("Closing speed (km/h)".to_string(), field(&test, 15)),
        ("Number of curves".to_string(), field(&test, 19)),
        ("Vehicle test mass (kg)".to_string(), field(&vehicle, 11)),
    ];
    Ok(TestData {
        path: path.to_path_buf(),
        format: Format::NhtsaEv5,
        title: field(&test, 2),
        speed: parse_number(&field(&test, 15)).map(|v| v / 3.6),
        mass: parse_number(&field(&vehicle, 11)),
        metadata,
        entries,
        store: Store::Ev5(files),
    })
}

/// Why a file without instrumentation rows is refused: junk or an empty
/// file is no EV5 test; a test without channels has nothing to read.
fn not_a_test(text: &str) -> String {
    let section = text.lines().any(|l| {
        let l = l.trim();
        l.starts_with("-----") && l.ends_with("-----") && l.contains("INSTRUMENTATION")
    });
    match section {
        true => "the INSTRUMENTATION section lists no channel (curve): nothing to read".into(),
        false => {
            "not an NHTSA EV5 test: no '----- INSTRUMENTATION -----' section listing its channels"
                .into()
        }
    }
}

/// The 1-based line of curve `number`'s instrumentation row (0 if not found).
fn instrumentation_line(ev5: &Path, number: usize) -> usize {
    let text = read_text(ev5).unwrap_or_default();
    sections(&text)
        .into_iter()
        .find(|(name, _, row)| {
            name == "INSTRUMENTATION"
                && row.get(1).and_then(|f| f.trim().parse().ok()) == Some(number)
        })
        .map_or(0, |(_, line, _)| line)
}

/// Rows of each section: (section name, 1-based line, fields).
fn sections(text: &str) -> Vec<(String, usize, Vec<String>)> {
    let mut current = String::new();
    let mut rows = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let trimmed = line.trim();
        if let Some(name) = trimmed
            .strip_prefix("-----")
            .and_then(|s| s.strip_suffix("-----"))
        {
            current = name.trim().to_string();
        } else if !trimmed.is_empty() && !trimmed.starts_with('#') {
            rows.push((
                current.clone(),
                i + 1,
                line.split('|').map(str::to_string).collect(),
            ));
        }
    }
    rows
}

fn first_row(sections: &[(String, usize, Vec<String>)], name: &str) -> Option<Vec<String>> {
    sections
        .iter()
        .find(|(n, ..)| n == name)
        .map(|(_, _, row)| row.clone())
}

fn instrument(row: &[String], path: &Path, line: usize) -> Result<Entry, SignalFileError> {
    if row.len() < FIELDS.len() {
        let message = format!(
            "instrumentation row has {} fields, expected {}",
            row.len(),
            FIELDS.len()
        );
        return Err(SignalFileError::line(path, line, message));
    }
    let f = |i: usize| row[i - 1].trim();
    let number = f(2).parse().map_err(|_| {
        SignalFileError::line(
            path,
            line,
            format!("curve number '{}' is not a number", f(2)),
        )
    })?;
    let mut code = format!("{}-{}-{}-{}", f(1), f(3), f(5), f(6));
    if f(19).eq_ignore_ascii_case("R") {
        code += "-R";
    }
    let comment = row[FIELDS.len() - 1..].join("|").trim().to_string();
    let validity = match (f(18), comment.to_lowercase().contains("no valid data")) {
        (_, true) => Validity::Invalid(comment.clone()),
        (status, false) if status.eq_ignore_ascii_case("NO") => {
            Validity::Invalid(format!("status NO: {comment}"))
        }
        _ => Validity::Valid,
    };
    let metadata = FIELDS
        .iter()
        .zip(row)
        .map(|(k, v)| (k.to_string(), v.trim().to_string()))
        .collect();
    Ok(Entry {
        number,
        code,
        name: comment,
        unit: f(8).to_string(),
        validity,
        present: false,
        absence: None,
        metadata,
    })
}

fn channel_file(ev5: &Path, number: usize) -> Option<PathBuf> {
    let stem = ev5.file_stem()?.to_string_lossy().into_owned();
    let path = ev5.with_file_name(format!("{stem}.{number:03}"));
    path.is_file().then_some(path)
}

/// Reads the samples of one curve in SI units.
pub(crate) fn load(
    entry: &Entry,
    file: Option<&Path>,
    ev5: &Path,
) -> Result<Channel, SignalFileError> {
    let file = file.ok_or_else(|| {
        let stem = ev5
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        let expected = ev5.with_file_name(format!("{stem}.{:03}", entry.number));
        SignalFileError::file(
            expected,
            format!(
                "curve {} ({}) has no channel file",
                entry.number, entry.code
            ),
        )
    })?;
    let unit_line = instrumentation_line(ev5, entry.number);
    let unit = Unit::parse(&entry.unit).map_err(|e| {
        SignalFileError::line(
            ev5,
            unit_line,
            format!("curve {}: unit {}: {e}", entry.number, entry.unit),
        )
    })?;
    let (times, values) = read_xy(file)?;
    let meta = |key: &str| {
        entry
            .metadata
            .iter()
            .find(|(k, _)| k == key)
            .and_then(|(_, v)| parse_number(v))
    };
    check_count(entry, &meta, values.len(), file)?;
    let what = format!("curve {}: 'Sample interval (us)' gives", entry.number);
    let step = meta("Sample interval (us)")
        .map(|us| super::check_interval(us * 1e-6, ev5, unit_line, &what))
        .transpose()?;
    let (start, step) =
        time_base(&times, step).map_err(|(line, m)| SignalFileError::line(file, line, m))?;
    super::check_interval(step, file, 2, "the times give a sampling interval of")?;
    let values = values.into_iter().map(|v| unit.to_si(v)).collect();
    let series = UniformSeries::new(start, step, values)
        .map_err(|e| SignalFileError::file(file, e.to_string()))?;
    let mut channel = Channel::new(&entry.code, &entry.name, unit.dimension, series);
    channel.source_unit = entry.unit.clone();
    channel.metadata = entry.metadata.clone();
    Ok(channel)
}

fn check_count(
    entry: &Entry,
    meta: &dyn Fn(&str) -> Option<f64>,
    found: usize,
    file: &Path,
) -> Result<(), SignalFileError> {
    let (Some(first), Some(last)) = (meta("First point"), meta("Last point")) else {
        return Ok(());
    };
    let expected = (last - first + 1.0).max(0.0) as usize;
    if expected == found {
        return Ok(());
    }
    let message = format!(
        "curve {}: the EV5 header declares points {first}..{last} ({expected} samples) but the file holds {found} (truncated or sample count mismatch)",
        entry.number
    );
    Err(SignalFileError::line(file, found, message))
}

/// Reads `time<TAB>value` lines.
fn read_xy(file: &Path) -> Result<(Vec<f64>, Vec<f64>), SignalFileError> {
    let text = read_text(file)?;
    let mut times = Vec::new();
    let mut values = Vec::new();
    for (i, line) in text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty())
    {
        super::check_sample_count(times.len(), file, i + 1)?;
        let mut cells = line.split(['\t', ' ', ',']).filter(|c| !c.is_empty());
        match (
            cells.next().and_then(parse_number),
            cells.next().and_then(parse_number),
            cells.next(),
        ) {
            (Some(t), Some(v), None) => {
                times.push(t);
                values.push(v);
            }
            _ => {
                let message = format!(
                    "'{}': expected time<TAB>value, two finite numbers and nothing more",
                    line.trim()
                );
                return Err(SignalFileError::line(file, i + 1, message));
            }
        }
    }
    Ok((times, values))
}

/// Start and interval, checked against the printed times (rounded to 1 µs).
fn time_base(times: &[f64], step: Option<f64>) -> Result<(f64, f64), (usize, String)> {
    let n = times.len();
    if n < 2 {
        return Err((n, format!("{n} samples: a curve needs at least 2")));
    }
    let step = step.unwrap_or((times[n - 1] - times[0]) / (n - 1) as f64);
    let tolerance = 0.01 * step + 1e-6;
    match (0..n).find(|&k| (times[k] - times[0] - k as f64 * step).abs() > tolerance) {
        Some(k) => Err((
            k + 1,
            format!("time {} s breaks the uniform interval {step} s", times[k]),
        )),
        None => Ok((times[0], step)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unit_codes_map_to_units() {
        assert_eq!(Unit::parse("G'S").unwrap().symbol, "g");
        assert_eq!(Unit::parse("NWT").unwrap().symbol, "N");
        assert_eq!(Unit::parse("NWM").unwrap().symbol, "Nm");
        assert!(Unit::parse("XYZ").is_err());
    }

    #[test]
    fn channel_lines_hold_two_numbers_and_at_most_the_sample_limit() {
        let dir = std::env::temp_dir().join(format!("bumpsim-ev5-xy-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("v1.093");
        std::fs::write(&file, "0.0398\t1.1\n0.0399\t1.2\t7.5\n").unwrap();
        let e = read_xy(&file).unwrap_err().to_string();
        assert!(e.ends_with("v1.093:2: '0.0399\t1.2\t7.5': expected time<TAB>value, two finite numbers and nothing more"), "{e}");
        let limit = bumpsim_core::files::MAX_INPUT_SAMPLES;
        std::fs::write(&file, "0 1\n".repeat(limit)).unwrap();
        assert_eq!(read_xy(&file).unwrap().0.len(), limit);
        std::fs::write(&file, "0 1\n".repeat(limit + 1)).unwrap();
        let e = read_xy(&file).unwrap_err().to_string();
        assert!(
            e.contains(&format!("v1.093:{}: more than {limit} samples", limit + 1)),
            "{e}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_file_without_channels_is_no_test() {
        let dir = std::env::temp_dir().join(format!("bumpsim-ev5-junk-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("j.EV5");
        let junk: Vec<u8> = (0..1000u32).map(|i| (i * 7919 % 251) as u8).collect();
        for (bytes, needle) in [
            (junk, "not an NHTSA EV5 test"),
            (Vec::new(), "not an NHTSA EV5 test"),
            (
                b"----- TEST -----\nV5|t\n".to_vec(),
                "not an NHTSA EV5 test",
            ),
            (
                b"----- INSTRUMENTATION -----\n".to_vec(),
                "INSTRUMENTATION section lists no channel",
            ),
        ] {
            std::fs::write(&file, bytes).unwrap();
            let e = open(&file).unwrap_err().to_string();
            assert!(e.contains("j.EV5: ") && e.contains(needle), "{e}");
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn time_base_checks_uniformity() {
        assert_eq!(
            time_base(&[-0.0002, -0.0001, 0.0], Some(1e-4)).unwrap().0,
            -0.0002
        );
        assert_eq!(time_base(&[0.0, 0.0001, 0.0005], None).unwrap_err().0, 2);
    }
}
