//! One view of a crash test, whatever file it came in: ISO-MME
//! ([`isomme`]), NHTSA EV5 ([`ev5`]) or CSV
//! ([`table`](crate::table)).
//!
//! [`TestData::open`] reads the test metadata and the list of channels
//! ([`Entry`]); [`TestData::load`] reads one channel into SI units.
//! [`TestData::select`] picks channels by
//! - number: `93` or `#93`;
//! - code, exactly or with `?` (one character) and `*` (any run) wildcards,
//!   case-insensitive: `0-LC-*-XG`, `10SIME??0000ACXP`;
//! - name substring, case-insensitive: `crossmember`.
//!
//! Channels marked invalid by the lab (NHTSA comment `No valid data`, status
//! `NO`) or whose file is missing or unusable are left out of wildcard and name
//! selections and reported in [`Selection::excluded`]; asked for by number or
//! exact code an invalid channel is returned with a warning, and an absent
//! one is an error naming it and why ([`Entry::absence`]: missing, empty or
//! truncated file). A test with some unusable channel files still opens:
//! the rest is readable.
//!
//! ```no_run
//! use bumpsim_io::test_data::TestData;
//! let test = TestData::open("v10146.EV5".as_ref())?;
//! let cells = test.select("0-LC-*-XG")?;
//! let first = test.load(cells.indices[0])?;
//! println!("{} {}", first.code, first.series.len());
//! # Ok::<(), bumpsim_io::signal_error::SignalFileError>(())
//! ```

pub mod csv;
pub mod ev5;
pub mod iso_header;
pub mod isomme;

use crate::signal_error::SignalFileError;
use crate::table::Table;
use bumpsim_core::channel::Channel;
use bumpsim_core::files::MAX_INPUT_SAMPLES;
use bumpsim_core::units::short;
use std::path::{Path, PathBuf};

pub use crate::table::SAMPLING_INTERVAL;

/// `path:line` refused when `step` (s) is outside [`SAMPLING_INTERVAL`];
/// `what` says where the interval came from.
pub(crate) fn check_interval(
    step: f64,
    path: &Path,
    line: usize,
    what: &str,
) -> Result<f64, SignalFileError> {
    if SAMPLING_INTERVAL.contains(&step) {
        return Ok(step);
    }
    let (low, high) = SAMPLING_INTERVAL.into_inner();
    let message = format!(
        "{what} {} s: expected {} to {} s (SAMPLING_INTERVAL)",
        short(step),
        short(low),
        short(high)
    );
    Err(SignalFileError::line(path, line, message))
}

/// `path:line` refused when a channel already holds [`MAX_INPUT_SAMPLES`]
/// samples and `line` would add one more (checked before it is kept).
pub(crate) fn check_sample_count(
    count: usize,
    path: &Path,
    line: usize,
) -> Result<(), SignalFileError> {
    if count < MAX_INPUT_SAMPLES {
        return Ok(());
    }
    let message = format!(
        "more than {MAX_INPUT_SAMPLES} samples, the most a channel may have (MAX_INPUT_SAMPLES): shorten the record or resample it"
    );
    Err(SignalFileError::line(path, line, message))
}

/// The file format a test came in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// ISO/TS 13499 ISO-MME (folder, `.mme` or `.zip`).
    IsoMme,
    /// NHTSA EV5 ASCII X-Y.
    NhtsaEv5,
    /// CSV with `name [unit]` headers.
    Csv,
}

impl std::fmt::Display for Format {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Format::IsoMme => "ISO-MME",
            Format::NhtsaEv5 => "NHTSA EV5",
            Format::Csv => "CSV",
        })
    }
}

/// Whether the lab marked a channel as usable.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Validity {
    /// Usable.
    Valid,
    /// Marked invalid, with the lab's reason.
    Invalid(String),
}

/// A channel as listed by the test, before its samples are read.
#[derive(Debug, Clone, PartialEq)]
pub struct Entry {
    /// Channel number (1-based; NHTSA curve number).
    pub number: usize,
    /// Channel code.
    pub code: String,
    /// Human-readable name.
    pub name: String,
    /// The unit as written in the file.
    pub unit: String,
    /// The lab's validity mark.
    pub validity: Validity,
    /// Whether its samples are available (NHTSA downloads may omit files).
    pub present: bool,
    /// Why the samples are not usable when the file is missing, empty or
    /// truncated (`None` for a present channel, and for an NHTSA curve that
    /// is simply not part of the download).
    pub absence: Option<String>,
    /// Header fields of the channel.
    pub metadata: Vec<(String, String)>,
}

/// Where the samples of the channels are.
#[derive(Debug)]
pub(crate) enum Store {
    /// Parsed ISO-MME channel files.
    IsoMme(Vec<isomme::RawChannel>),
    /// EV5 channel file per entry (absent: `None`).
    Ev5(Vec<Option<PathBuf>>),
    /// A CSV table; entry `i` is column `i`.
    Csv(Table),
}

/// A crash test: metadata, channel list, and access to the samples.
#[derive(Debug)]
pub struct TestData {
    /// The path the test was opened from.
    pub path: PathBuf,
    /// The format.
    pub format: Format,
    /// Test title or name.
    pub title: String,
    /// Test-level fields (key, value) in file order.
    pub metadata: Vec<(String, String)>,
    /// Impact speed, m/s, when the file states it.
    pub speed: Option<f64>,
    /// Test mass of the vehicle, kg, when the file states it.
    pub mass: Option<f64>,
    /// The channels.
    pub entries: Vec<Entry>,
    pub(crate) store: Store,
}

/// The channels a selector picked, as indices into [`TestData::entries`].
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Selection {
    /// Usable channels.
    pub indices: Vec<usize>,
    /// Channels that matched but are marked invalid, left out.
    pub excluded: Vec<usize>,
    /// Channels that matched but whose samples are absent, left out.
    pub absent: Vec<usize>,
    /// Notes for the user (an invalid channel asked for explicitly).
    pub warnings: Vec<String>,
}

impl TestData {
    /// Opens a test: an ISO-MME folder, `.mme` file or `.zip`; an NHTSA
    /// `.EV5` file; or a CSV file.
    pub fn open(path: &Path) -> Result<TestData, SignalFileError> {
        crate::output::register_input(path);
        let extension = path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase());
        match extension.as_deref() {
            _ if path.is_dir() => isomme::open_folder(path),
            Some("mme") => isomme::open_mme(path),
            Some("zip") => isomme::open_zip(path),
            Some("ev5") => ev5::open(path),
            Some("csv" | "txt") => csv::open(path),
            _ if !path.exists() => Err(SignalFileError::file(path, "no such file or folder")),
            _ => Err(SignalFileError::file(
                path,
                "unknown test format: expected an ISO-MME folder, .mme or .zip, an NHTSA .EV5 file, or a .csv file",
            )),
        }
    }

    /// Reads channel `index` (into [`TestData::entries`]) in SI units.
    pub fn load(&self, index: usize) -> Result<Channel, SignalFileError> {
        let entry = self.entries.get(index).ok_or_else(|| {
            SignalFileError::file(&self.path, format!("no channel at index {index}"))
        })?;
        let mut channel = match &self.store {
            _ if !entry.present && entry.absence.is_some() => Err(absent_error(&self.path, entry)),
            Store::IsoMme(raw) => raw[index].to_channel(entry, raw),
            Store::Ev5(files) => ev5::load(entry, files[index].as_deref(), &self.path),
            Store::Csv(table) => csv::channel(table, index),
        }?;
        let stated = channel
            .meta("Data status")
            .is_some_and(|s| !s.trim().is_empty() && !s.eq_ignore_ascii_case("NOVALUE"));
        if matches!(entry.validity, Validity::Invalid(_)) && !stated {
            channel.set_meta("Data status", iso_header::FAILED);
        }
        Ok(channel)
    }

    /// Loads every channel of a selection.
    pub fn load_all(&self, selection: &Selection) -> Result<Vec<Channel>, SignalFileError> {
        selection.indices.iter().map(|&i| self.load(i)).collect()
    }

    /// Picks channels by number, code (with wildcards) or name substring.
    pub fn select(&self, selector: &str) -> Result<Selection, SignalFileError> {
        let text = selector.trim();
        if text.is_empty() {
            // as a name substring it would pick every channel, time included
            return Err(SignalFileError::Select {
                path: self.path.clone(),
                selector: selector.to_string(),
                reason: "an empty selector: give a channel number, code or name".into(),
            });
        }
        let number = text.strip_prefix('#').unwrap_or(text);
        let matched: Vec<usize> = if let Ok(n) = number.parse::<usize>() {
            self.matching(|e| e.number == n)
        } else if text.contains(['*', '?']) {
            return self.collect(selector, self.matching(|e| glob(text, &e.code)), false);
        } else {
            self.matching(|e| e.code.eq_ignore_ascii_case(text))
        };
        if !matched.is_empty() {
            return self.collect(selector, matched, true);
        }
        let lower = text.to_lowercase();
        self.collect(
            selector,
            self.matching(|e| e.name.to_lowercase().contains(&lower)),
            false,
        )
    }

    fn matching(&self, keep: impl Fn(&Entry) -> bool) -> Vec<usize> {
        (0..self.entries.len())
            .filter(|&i| keep(&self.entries[i]))
            .collect()
    }

    fn collect(
        &self,
        selector: &str,
        matched: Vec<usize>,
        explicit: bool,
    ) -> Result<Selection, SignalFileError> {
        let mut selection = Selection::default();
        for i in matched {
            let entry = &self.entries[i];
            match (&entry.validity, entry.present, explicit) {
                (_, false, true) => {
                    return Err(SignalFileError::Select {
                        path: self.path.clone(),
                        selector: selector.to_string(),
                        reason: absent_reason(entry),
                    });
                }
                (_, false, false) => selection.absent.push(i),
                (Validity::Invalid(why), true, true) => {
                    selection.warnings.push(format!(
                        "channel {} ({}) is marked invalid: {why}",
                        entry.number, entry.code
                    ));
                    selection.indices.push(i);
                }
                (Validity::Invalid(_), true, false) => selection.excluded.push(i),
                (Validity::Valid, true, _) => selection.indices.push(i),
            }
        }
        if selection.indices.is_empty() {
            return Err(self.no_match(selector, &selection));
        }
        Ok(selection)
    }

    fn no_match(&self, selector: &str, selection: &Selection) -> SignalFileError {
        let left_out = selection.excluded.len() + selection.absent.len();
        let reason = if left_out == 0 {
            let examples: Vec<String> = self
                .entries
                .iter()
                .take(5)
                .map(|e| format!("{} {}", e.number, e.code))
                .collect();
            format!(
                "matches no channel number, code or name ({} channels, e.g. {})",
                self.entries.len(),
                examples.join(", ")
            )
        } else {
            format!(
                "matches only channels that are marked invalid or whose file is missing or unusable ({left_out} of them)"
            )
        };
        SignalFileError::Select {
            path: self.path.clone(),
            selector: selector.to_string(),
            reason,
        }
    }
}

/// Why an absent channel cannot be read, naming it.
fn absent_reason(entry: &Entry) -> String {
    format!(
        "channel {} ({}) has no usable samples: {}",
        entry.number,
        entry.code,
        entry
            .absence
            .as_deref()
            .unwrap_or("its file is absent (not part of the download)")
    )
}

fn absent_error(path: &Path, entry: &Entry) -> SignalFileError {
    SignalFileError::file(path, absent_reason(entry))
}

/// Case-insensitive wildcard match: `?` one character, `*` any run.
pub fn glob(pattern: &str, text: &str) -> bool {
    let p: Vec<char> = pattern.to_uppercase().chars().collect();
    let t: Vec<char> = text.to_uppercase().chars().collect();
    let (mut pi, mut ti, mut star, mut mark) = (0, 0, None, 0);
    while ti < t.len() {
        if pi < p.len() && (p[pi] == '?' || p[pi] == t[ti]) {
            (pi, ti) = (pi + 1, ti + 1);
        } else if pi < p.len() && p[pi] == '*' {
            (star, mark, pi) = (Some(pi), ti, pi + 1);
        } else if let Some(s) = star {
            (pi, mark, ti) = (s + 1, mark + 1, mark + 1);
        } else {
            return false;
        }
    }
    p[pi..].iter().all(|&c| c == '*')
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wildcards() {
        assert!(glob("0-LC-*-XG", "0-lc-LC0601-XG"));
        assert!(glob("10SIME??0000ACXP", "10SIMELE0000ACXP"));
        assert!(!glob("10SIME??0000ACXP", "10SIMELE0000ACYP"));
        assert!(glob("*", ""));
        assert!(!glob("a*b", "acbd"));
        assert!(glob("a*b*", "acbd"));
    }
}
