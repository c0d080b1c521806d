//! The JSON answers of the viewer (`/TOKEN/api/NAME?QUERY`):
//!
//! - `inputs`: the tests (format, title, speed, mass, channels with their
//!   codes decoded, units, invalid and absent marks) and the results;
//! - `series`: the selection processed and decimated for the window;
//! - `cursor`: readouts at cursors `ta` and `tb` and their difference;
//! - `metrics`: pulse metrics of the selected acceleration signals;
//! - `command`: the `bumpsim signal export` line that writes the selection;
//! - `export.csv`: the selection as CSV (bumpsim-io's table writer's text);
//! - `export-iso` (POST): the selection written as an ISO-MME test folder
//!   `name` in the export folder through bumpsim-io's staged writer.

use crate::decode::decode;
use crate::error::ViewError;
use crate::plot::{decimate, metrics, readout};
use crate::query::{Combination, Query};
use crate::session::{Session, Signal};
use bumpsim_core::units::Unit;
use bumpsim_io::table::{OutputColumn, table_text};
use bumpsim_io::test_data::{TestData, Validity};
use serde_json::{Value, json};
use std::path::{Path, PathBuf};

/// The channel list of a test.
fn test_json(index: usize, given: &Path, data: &TestData) -> Value {
    let channels: Vec<Value> = data
        .entries
        .iter()
        .enumerate()
        .map(|(i, e)| {
            json!({
                "i": i,
                "number": e.number,
                "code": e.code,
                "name": e.name,
                "unit": e.unit,
                "invalid": match &e.validity { Validity::Invalid(why) => Some(why.clone()), Validity::Valid => None },
                "present": e.present,
                "absence": e.absence,
                "decoded": decode(&e.code),
            })
        })
        .collect();
    json!({
        "index": index,
        "path": given.display().to_string(),
        "format": data.format.to_string(),
        "title": data.title,
        "speed_kmh": data.speed.map(|v| v * 3.6),
        "mass_kg": data.mass,
        "channels": channels,
    })
}

/// The inputs: tests and results.
pub fn inputs(session: &Session) -> Value {
    let tests: Vec<Value> = session
        .tests
        .iter()
        .enumerate()
        .map(|(i, t)| test_json(i, &t.given, &t.data))
        .collect();
    json!({ "tests": tests, "results": session.results })
}

fn signal_head(s: &Signal) -> Value {
    json!({
        "label": s.label,
        "test": s.test,
        "code": s.channel.code,
        "name": s.channel.name,
        "dimension": s.channel.dimension.name(),
        "unit": s.unit.symbol,
        "step": s.channel.series.step(),
        "samples": s.channel.series.len(),
    })
}

/// The selection processed, decimated for the window.
pub fn series(session: &mut Session, q: &Query) -> Result<Value, ViewError> {
    let signals = session.signals(q)?;
    let list: Vec<Value> = signals
        .iter()
        .map(|s| {
            let mut head = signal_head(s);
            head["drawn"] = json!(decimate(&s.channel.series, q.window, q.pixels, s.unit));
            head
        })
        .collect();
    Ok(json!({ "signals": list }))
}

/// Readouts at the cursors.
pub fn cursor(session: &mut Session, q: &Query) -> Result<Value, ViewError> {
    let signals = session.signals(q)?;
    Ok(json!({ "readouts": readout(&signals, q.cursors.0, q.cursors.1) }))
}

/// Pulse metrics of the selection's acceleration signals.
pub fn pulse(session: &mut Session, q: &Query) -> Result<Value, ViewError> {
    let signals = session.signals(q)?;
    let speeds: Vec<Option<f64>> = session.tests.iter().map(|t| t.data.speed).collect();
    let speed = |t: usize| speeds.get(t).copied().flatten();
    Ok(json!({ "metrics": metrics(&signals, q.window, &speed) }))
}

/// A shell word: quoted unless plain.
fn word(text: &str) -> String {
    let plain = text
        .chars()
        .all(|c| c.is_ascii_alphanumeric() || "-_./=:,+#".contains(c));
    if plain && !text.is_empty() {
        text.to_string()
    } else {
        format!("'{}'", text.replace('\'', "'\\''"))
    }
}

/// The `bumpsim signal export` lines that write the selection, one per test.
pub fn command(session: &Session, q: &Query) -> Result<Value, ViewError> {
    let p = &q.processing;
    let mut lines = Vec::new();
    let mut notes = Vec::new();
    for (t, test) in session.tests.iter().enumerate() {
        let picked: Vec<usize> = q
            .selected
            .iter()
            .filter(|s| s.0 == t)
            .map(|s| s.1)
            .collect();
        if picked.is_empty() {
            continue;
        }
        let mut line = format!(
            "bumpsim signal export {}",
            word(&test.given.display().to_string())
        );
        for &i in &picked {
            let entry = test.data.entries.get(i).ok_or_else(|| {
                ViewError::parameter("sel", format!("test {t} has no channel {i}"))
            })?;
            line += &format!(" -c '#{}'", entry.number);
        }
        if p.bias {
            line += " --bias";
        }
        if let Some(c) = p.cfc {
            line += &format!(" --cfc {c}");
            if p.iso_6487 {
                line += " --iso-6487";
            }
        }
        if let Some(s) = p.scale {
            line += &format!(" --scale {s}");
        }
        for v in &p.integrate {
            line += &format!(" --integrate {v}");
        }
        for u in &p.units {
            line += &format!(" --unit {}", word(u.symbol));
        }
        line += &format!(" -o test{}.csv", t + 1);
        lines.push(line);
    }
    if p.derivative {
        notes.push("signal export has no derivative: the line leaves it out".to_string());
    }
    if p.combine != Combination::None {
        notes.push("signal export combines the channels one selector picks (a wildcard, with --combine sum or mean); it has no resultant: the line exports the channels one by one".to_string());
    }
    Ok(json!({ "lines": lines, "notes": notes }))
}

/// The selection's signals on one time base, or why not.
fn one_base(signals: &[Signal]) -> Result<&Signal, ViewError> {
    let first = signals
        .first()
        .ok_or_else(|| ViewError::parameter("sel", "select channels to export"))?;
    let same = |s: &Signal| {
        let (a, b) = (&s.channel.series, &first.channel.series);
        a.len() == b.len() && a.start() == b.start() && a.step() == b.step()
    };
    if let Some(odd) = signals.iter().find(|s| !same(s)) {
        return Err(ViewError::parameter(
            "sel",
            format!(
                "{} and {} have different time bases: export them separately",
                first.label, odd.label
            ),
        ));
    }
    Ok(first)
}

/// The selection as CSV text, time in s, each signal in its display unit.
pub fn csv(session: &mut Session, q: &Query) -> Result<String, ViewError> {
    let signals = session.signals(q)?;
    let first = one_base(&signals)?;
    let time = first.channel.series.times();
    let columns: Vec<OutputColumn<'_>> = signals
        .iter()
        .map(|s| OutputColumn {
            name: &s.channel.code,
            unit: s.unit,
            values: s.channel.series.values(),
        })
        .collect();
    let time_unit = Unit::parse("s").map_err(|e| ViewError::parameter("unit", e.to_string()))?;
    Ok(table_text(
        Path::new("view.csv"),
        time_unit,
        &time,
        &columns,
    )?)
}

/// Writes the selection as the ISO-MME test folder `folder/name`.
pub fn iso_mme(session: &mut Session, q: &Query, folder: &Path) -> Result<Value, ViewError> {
    let name = q
        .name
        .clone()
        .ok_or_else(|| ViewError::parameter("name", "give the new test folder's name"))?;
    bumpsim_io::output::plain_name(&name)?;
    let target: PathBuf = folder.join(&name);
    if target.exists() {
        return Err(ViewError::parameter(
            "name",
            format!("{} exists: choose a new name", target.display()),
        ));
    }
    let signals = session.signals(q)?;
    let channels: Vec<_> = signals.iter().map(|s| s.channel.clone()).collect();
    let first = signals.first().map(|s| s.test).unwrap_or(0);
    let header = session
        .tests
        .get(first)
        .map(|t| bumpsim_io::isomme::test_header(&t.data))
        .unwrap_or_default();
    let mme = bumpsim_io::isomme::write(&target, &name, &header, &channels)?;
    Ok(json!({ "wrote": mme.display().to_string(), "channels": channels.len() }))
}
