//! The state of a campaign: one [`Point`] per design run with its status
//! (pending, submitted, running, done, failed), job id, attempts, Slurm
//! requeues, timestamps (UTC), the SHA-256 of its inputs and the reason of
//! its last failure.
//!
//! It is kept in `state.journal` (framing in [`crate::journal`]): a header
//! record (format, campaign, number of points), a snapshot of every point,
//! then one record per change of a point, appended and flushed to disk
//! (`fdatasync`) before the controller acts on it, the last record of a
//! point being its state. When the changes outnumber the points the
//! controller compacts the journal into a new snapshot (temporary file,
//! `fsync`, rename), so the cost of a change stays constant and the file
//! at most about twice its snapshot, whatever the campaign's size. A
//! damaged record (checksum) or a missing point (a truncated file) makes
//! the state unreadable, never smaller: `bumpsim campaign repair`
//! rebuilds it from the point folders ([`crate::repair`]). Why a journal
//! and not SQLite: docs/campaign.md.

use crate::error::{CampaignError, Result, read_error};
use crate::journal::{Appender, frame, records};
use crate::spec::MAX_POINTS;
use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};
use std::collections::BTreeMap;
use std::path::Path;

/// The state journal's name in the campaign folder.
pub const STATE_FILE: &str = "state.journal";
/// The state file of campaigns made before the journal (TOML, format 1).
pub const LEGACY_STATE_FILE: &str = "state.toml";
/// The journal's format.
pub const FORMAT: u32 = 2;
/// Attempts and requeues of a point at most (a record beyond is damage).
pub const MAX_ATTEMPTS: u32 = 1_000_000;
/// The journal is compacted when it holds more changes than this or than points.
pub const COMPACT_AFTER: usize = 1000;

/// Where a point is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    /// Not submitted yet (or to be retried).
    Pending,
    /// Handed to the executor (queued).
    Submitted,
    /// Running.
    Running,
    /// Finished and its responses read.
    Done,
    /// Failed for good (reason recorded).
    Failed,
}

impl Status {
    /// Every status, in the order of [`State::counts`].
    pub const ALL: [Status; 5] = [
        Status::Pending,
        Status::Submitted,
        Status::Running,
        Status::Done,
        Status::Failed,
    ];

    /// Whether the point is with the executor.
    pub fn in_flight(self) -> bool {
        matches!(self, Status::Submitted | Status::Running)
    }

    /// The lower-case name.
    pub fn name(self) -> &'static str {
        match self {
            Status::Pending => "pending",
            Status::Submitted => "submitted",
            Status::Running => "running",
            Status::Done => "done",
            Status::Failed => "failed",
        }
    }
}

/// One design point.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Point {
    /// Run number (1-based, the design table's `run`).
    pub run: usize,
    /// Its folder, relative to the campaign folder (`points/0007`; not
    /// stored: it follows from the run).
    #[serde(skip)]
    pub folder: String,
    /// The journal line of its state (`state.journal:LINE`; 0: not in a
    /// journal yet; not stored).
    #[serde(skip)]
    pub line: usize,
    /// Status.
    pub status: Status,
    /// Attempts so far: submissions, and requeues by Slurm.
    pub attempts: u32,
    /// How often Slurm requeued its task (node failure, pre-emption).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub requeues: u32,
    /// The executor's id of the last submission (`local:PID`, `slurm:JOB_TASK`).
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub job: String,
    /// SHA-256 of the point's inputs (deck, copied files, command).
    pub input_hash: String,
    /// Last submission, UTC.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub submitted: String,
    /// Last end (done or failed), UTC.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub finished: String,
    /// Why the last attempt failed or was requeued.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub reason: String,
}

fn is_zero(n: &u32) -> bool {
    *n == 0
}

impl Point {
    /// A pending point that has never run.
    pub fn new(run: usize, input_hash: String) -> Point {
        Point {
            run,
            folder: point_folder(run),
            line: 0,
            status: Status::Pending,
            attempts: 0,
            requeues: 0,
            job: String::new(),
            input_hash,
            submitted: String::new(),
            finished: String::new(),
            reason: String::new(),
        }
    }
}

/// The folder of run `run` (`points/0007`), relative to the campaign folder.
pub fn point_folder(run: usize) -> String {
    format!("points/{run:04}")
}

/// The journal's first record.
#[derive(Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Header {
    format: u32,
    campaign: String,
    points: usize,
    /// Point records after the header at least (rewritten in place, see
    /// [`Journal::record`]); absent in journals of earlier bumpsims.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    records: Option<usize>,
}

impl Header {
    /// The header's framed line, always of one length for one campaign
    /// (the count padded with spaces), so that it can be rewritten in place.
    fn line(campaign: &str, points: usize, records: usize, dir: &Path) -> Result<String> {
        let header = Header {
            format: FORMAT,
            campaign: campaign.into(),
            points,
            records: Some(records),
        };
        let text = json(&header, dir)?;
        let digits = records.to_string().len();
        let padded = format!("{}{}}}", &text[..text.len() - 1], " ".repeat(20 - digits));
        Ok(frame(&padded))
    }
}

/// The whole state.
#[derive(Debug, Clone, PartialEq)]
pub struct State {
    /// Campaign name.
    pub campaign: String,
    /// Last write, UTC.
    pub updated: String,
    /// The points in run order.
    pub points: Vec<Point>,
}

impl State {
    /// A state of `points`.
    pub fn new(campaign: &str, points: Vec<Point>) -> State {
        State {
            campaign: campaign.into(),
            updated: now(),
            points,
        }
    }

    /// Reads the state of campaign folder `dir`; a damaged or truncated
    /// journal is an error ([`CampaignError::Damaged`]).
    pub fn read(dir: &Path) -> Result<State> {
        load(dir).map(|(state, _)| state)
    }

    /// The state of `dir` if it has one (`None`: a new campaign folder).
    pub fn existing(dir: &Path) -> Result<Option<State>> {
        let some = dir.join(STATE_FILE).exists() || dir.join(LEGACY_STATE_FILE).exists();
        some.then(|| State::read(dir)).transpose()
    }

    /// Writes the state as a new snapshot (temporary file, `fsync`, rename).
    pub fn write(&mut self, dir: &Path) -> Result<()> {
        let text = self.snapshot(dir)?;
        bumpsim_io::output::write_atomic(&dir.join(STATE_FILE), text.as_bytes())?;
        Ok(())
    }

    /// The journal's text of a snapshot of this state (for campaign
    /// folder `dir`): the header and one record per point.
    pub fn snapshot(&mut self, dir: &Path) -> Result<String> {
        self.updated = now();
        let n = self.points.len();
        let mut text = Header::line(&self.campaign, n, n, dir)?;
        for (i, p) in self.points.iter_mut().enumerate() {
            text += &frame(&json(p, dir)?);
            p.line = i + 2;
        }
        Ok(text)
    }

    /// Points per status: pending, submitted, running, done, failed.
    pub fn counts(&self) -> [usize; 5] {
        let mut counts = [0; 5];
        for p in &self.points {
            counts[p.status as usize] += 1;
        }
        counts
    }
}

fn json<T: Serialize>(value: &T, dir: &Path) -> Result<String> {
    serde_json::to_string(value).map_err(|e| damaged(dir, e.to_string()))
}

fn damaged(dir: &Path, problem: String) -> CampaignError {
    CampaignError::Damaged {
        path: dir.join(STATE_FILE),
        dir: dir.into(),
        problem,
    }
}

/// What [`load`] found besides the state.
struct Loaded {
    /// Bytes of whole lines.
    whole: usize,
    /// Point records after the header.
    records: usize,
    /// Whether the header counts its records (is rewritten in place).
    counted: bool,
    /// Bytes of the header's line (its newline included).
    head: usize,
}

/// The state of `dir` and what its journal holds.
fn load(dir: &Path) -> Result<(State, Loaded)> {
    let path = dir.join(STATE_FILE);
    if !path.exists() && dir.join(LEGACY_STATE_FILE).exists() {
        let problem = "only a state.toml of an earlier bumpsim (format 1)".into();
        return Err(damaged(dir, problem));
    }
    let text = std::fs::read_to_string(&path).map_err(|e| read_error(&path, e))?;
    let journal = records(&text);
    if let Some((line, what)) = journal.damage.first() {
        return Err(damaged(dir, format!("line {line}: {what}")));
    }
    let header = header(dir, journal.lines.first())?;
    let mut points: Vec<Option<Point>> = vec![None; header.points];
    for &(line, text) in &journal.lines[1..] {
        let point = parse_point(dir, line, text, header.points)?;
        let i = point.run - 1;
        points[i] = Some(point);
    }
    let found = points.iter().flatten().count();
    if found < header.points {
        let first = points.iter().position(Option::is_none).map_or(0, |i| i + 1);
        let problem = format!(
            "records of {found} of its {} points (truncated?): none of run {first}",
            header.points
        );
        return Err(damaged(dir, problem));
    }
    let records = journal.lines.len() - 1;
    if let Some(counted) = header.records.filter(|&n| n > records) {
        let problem = format!(
            "{records} point records where its header (line 1) counts {counted} at least (cut at a record's end?)"
        );
        return Err(damaged(dir, problem));
    }
    let mut state = State::new(&header.campaign, points.into_iter().flatten().collect());
    state.updated = modified(&path);
    let loaded = Loaded {
        whole: journal.whole,
        records,
        counted: header.records.is_some(),
        head: text.find('\n').map_or(0, |n| n + 1),
    };
    Ok((state, loaded))
}

fn header(dir: &Path, first: Option<&(usize, &str)>) -> Result<Header> {
    let header = match first {
        Some((1, text)) => serde_json::from_str::<Header>(text).ok(),
        _ => None,
    };
    match header {
        Some(h) if h.format == FORMAT && (1..=MAX_POINTS).contains(&h.points) => Ok(h),
        _ => Err(damaged(
            dir,
            format!("line 1: not a format-{FORMAT} header of 1 to {MAX_POINTS} points"),
        )),
    }
}

/// The point record on line `line` of a campaign of `points` points.
fn parse_point(dir: &Path, line: usize, text: &str, points: usize) -> Result<Point> {
    let problem = |what: String| damaged(dir, format!("line {line}: {what}"));
    let mut point: Point = serde_json::from_str(text).map_err(|e| problem(e.to_string()))?;
    if !(1..=points).contains(&point.run) {
        let what = format!("run {} of a campaign of {points} points", point.run);
        return Err(problem(what));
    }
    for (key, value) in [("attempts", point.attempts), ("requeues", point.requeues)] {
        if value > MAX_ATTEMPTS {
            return Err(problem(format!(
                "run {}: {key} {value}: at most {MAX_ATTEMPTS}",
                point.run
            )));
        }
    }
    point.folder = point_folder(point.run);
    point.line = line;
    Ok(point)
}

/// The last change of `path`, UTC.
fn modified(path: &Path) -> String {
    let seconds = std::fs::metadata(path)
        .and_then(|m| m.modified())
        .ok()
        .and_then(|t| t.duration_since(std::time::UNIX_EPOCH).ok());
    seconds.map_or_else(now, |d| utc(d.as_secs()))
}

/// What can be read of a damaged journal: every record whose checksum
/// holds, the last one of each run (for `repair`).
pub fn salvage(dir: &Path) -> BTreeMap<usize, Point> {
    let text = std::fs::read(dir.join(STATE_FILE)).unwrap_or_default();
    let text = String::from_utf8_lossy(&text);
    records(&text)
        .lines
        .iter()
        .filter_map(|&(line, json)| parse_point(dir, line, json, MAX_POINTS).ok())
        .map(|p| (p.run, p))
        .collect()
}

/// The state journal of a running controller: changes appended and synced,
/// compacted into a new snapshot when they outnumber the points.
///
/// The header counts the point records after it, rewritten in place with
/// each append: the records of the rounds before (synced already), so
/// that the count never exceeds what is on disk, even when the append is
/// cut off by a crash. A journal cut at a record's end, which its framing
/// cannot tell from a whole one, then falls short of its count and is
/// refused, unless the cut takes exactly the last round's records.
///
/// The header is rewritten in place only at the length it has in the
/// file, which a kill -9 or a power loss cannot tear across lines (one
/// write of about 100 bytes at offset 0, in one disk sector); a header of
/// any other length (a valid one written without its padding, by hand or
/// by another tool) would spill over the records after it, so the
/// journal is compacted instead (temporary file, `fsync`, rename).
#[derive(Debug)]
pub struct Journal {
    appender: Appender,
    appended: usize,
    /// Point records in the file (snapshot and changes).
    records: usize,
    /// The header's campaign and points.
    campaign: String,
    points: usize,
    /// Bytes of the header's line in the file.
    head: usize,
}

impl Journal {
    /// Reads the state of `dir` and opens its journal for appending (an
    /// unfinished last line, never acted upon, is cut off); a journal
    /// whose header does not count its records (an earlier bumpsim's), or
    /// is not of its padded length, is compacted into one that does.
    pub fn open(dir: &Path) -> Result<(State, Journal)> {
        let (mut state, loaded) = load(dir)?;
        let path = dir.join(STATE_FILE);
        let appender = Appender::open(&path, loaded.whole).map_err(|e| journal_error(&path, e))?;
        let mut journal = Journal {
            appender,
            appended: loaded.records - state.points.len(),
            records: loaded.records,
            campaign: state.campaign.clone(),
            points: state.points.len(),
            head: loaded.head,
        };
        let padded = Header::line(&state.campaign, state.points.len(), 0, dir)?.len();
        if !loaded.counted || loaded.head != padded {
            journal.compact(&mut state)?;
        }
        Ok((state, journal))
    }

    /// Appends the points `changed` of `state` (one record each) and
    /// flushes them to disk; compacts when the changes outnumber the points.
    pub fn record(&mut self, state: &mut State, changed: &[usize]) -> Result<()> {
        let dir = self.dir();
        let mut text = String::new();
        for (k, &i) in changed.iter().enumerate() {
            text += &frame(&json(&state.points[i], &dir)?);
            state.points[i].line = self.records + 2 + k;
        }
        if text.is_empty() {
            return Ok(());
        }
        let path = self.appender.path().to_path_buf();
        let head = Header::line(&self.campaign, self.points, self.records, &dir)?;
        if head.len() != self.head {
            // never shift the records after the header: a new snapshot
            return self.compact(state);
        }
        self.appender
            .overwrite_head(head.as_bytes())
            .and_then(|()| self.appender.append(&text))
            .map_err(|e| journal_error(&path, e))?;
        self.appended += changed.len();
        self.records += changed.len();
        if self.appended > COMPACT_AFTER.max(state.points.len()) {
            self.compact(state)?;
        }
        Ok(())
    }

    /// Writes a new snapshot of `state` and appends after it.
    pub fn compact(&mut self, state: &mut State) -> Result<()> {
        let dir = self.dir();
        state.write(&dir)?;
        let path = dir.join(STATE_FILE);
        let whole = std::fs::metadata(&path)
            .map_err(|e| read_error(&path, e))?
            .len() as usize;
        self.appender = Appender::open(&path, whole).map_err(|e| journal_error(&path, e))?;
        self.appended = 0;
        self.records = state.points.len();
        self.head = Header::line(&self.campaign, self.points, 0, &dir)?.len();
        Ok(())
    }

    fn dir(&self) -> std::path::PathBuf {
        let path = self.appender.path();
        path.parent().unwrap_or(Path::new(".")).to_path_buf()
    }
}

fn journal_error(path: &Path, source: std::io::Error) -> CampaignError {
    CampaignError::Journal {
        path: path.into(),
        source,
    }
}

/// The SHA-256 (hex, `sha256:` prefixed) of a point's input files and command.
pub fn input_hash(folder: &Path, files: &[String], command: &[String]) -> Result<String> {
    let mut contents = Vec::with_capacity(files.len());
    for name in files {
        let path = folder.join(name);
        let bytes = std::fs::read(&path).map_err(|e| read_error(&path, e))?;
        contents.push((name.as_str(), bytes));
    }
    let named = contents.iter().map(|(n, b)| (*n, b.as_slice()));
    Ok(hash_inputs(named, command))
}

/// [`input_hash`] of files given by name and contents, in that order.
pub fn hash_inputs<'a>(
    files: impl IntoIterator<Item = (&'a str, &'a [u8])>,
    command: &[String],
) -> String {
    let mut hasher = Sha256::new();
    for (name, bytes) in files {
        hasher.update((name.len() as u64).to_le_bytes());
        hasher.update(name.as_bytes());
        hasher.update((bytes.len() as u64).to_le_bytes());
        hasher.update(bytes);
    }
    for word in command {
        hasher.update((word.len() as u64).to_le_bytes());
        hasher.update(word.as_bytes());
    }
    let digest = hasher.finalize();
    let hex: String = digest.iter().map(|b| format!("{b:02x}")).collect();
    format!("sha256:{hex}")
}

/// The first 8 hex digits of the SHA-256 of `bytes` (a short stable id).
pub fn short_hash(bytes: &[u8]) -> String {
    crate::journal::checksum(bytes)
}

/// The current time, UTC, as `YYYY-MM-DDThh:mm:ssZ`.
pub fn now() -> String {
    let seconds = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    utc(seconds)
}

/// Seconds since 1970 as a UTC timestamp (the civil-from-days algorithm of
/// H. Hinnant, `chrono`'s too).
///
/// ```
/// assert_eq!(bumpsim_campaign::state::utc(951_782_400), "2000-02-29T00:00:00Z");
/// ```
pub fn utc(seconds: u64) -> String {
    let (days, rest) = ((seconds / 86_400) as i64, seconds % 86_400);
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    let (h, m, s) = (rest / 3600, rest % 3600 / 60, rest % 60);
    format!("{year:04}-{month:02}-{day:02}T{h:02}:{m:02}:{s:02}Z")
}

/// A UTC timestamp of [`utc`] as seconds since 1970 (Hinnant's
/// days-from-civil), `None` if it is not of that form.
///
/// ```
/// use bumpsim_campaign::state::{seconds, utc};
/// assert_eq!(seconds("2000-02-29T00:00:00Z"), Some(951_782_400));
/// assert_eq!(seconds(&utc(1_795_000_000)), Some(1_795_000_000));
/// ```
pub fn seconds(utc: &str) -> Option<u64> {
    let number = |range: std::ops::Range<usize>| utc.get(range)?.parse::<i64>().ok();
    let shape = utc.len() == 20 && utc.ends_with('Z');
    let (y, m, d) = (number(0..4)?, number(5..7)?, number(8..10)?);
    let (h, min, s) = (number(11..13)?, number(14..16)?, number(17..19)?);
    if !shape || !(1..=12).contains(&m) {
        return None;
    }
    let y = if m <= 2 { y - 1 } else { y };
    let era = y.div_euclid(400);
    let yoe = y - era * 400;
    let doy = (153 * ((m + 9) % 12) + 2) / 5 + d - 1;
    let doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    let days = era * 146_097 + doe - 719_468;
    u64::try_from(days * 86_400 + h * 3600 + min * 60 + s).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn folder(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("bumpsim-state-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn nine(dir: &Path) -> State {
        let points = (1..=9)
            .map(|r| Point::new(r, format!("sha256:{r}")))
            .collect();
        let mut state = State::new("c", points);
        state.write(dir).unwrap();
        state
    }

    #[test]
    fn changes_are_appended_and_compacted_into_a_snapshot() {
        let dir = folder("journal");
        nine(&dir);
        let (mut state, mut journal) = Journal::open(&dir).unwrap();
        for round in 0..=COMPACT_AFTER {
            let i = round % 9;
            state.points[i].attempts += 1;
            state.points[i].status = Status::Running;
            journal.record(&mut state, &[i]).unwrap();
            assert_eq!(State::read(&dir).unwrap().points, state.points);
        }
        // the last record of a point is its state; compacted past the limit
        let lines = std::fs::read_to_string(dir.join(STATE_FILE))
            .unwrap()
            .lines()
            .count();
        assert_eq!(lines, 1 + 9, "compacted after {COMPACT_AFTER} changes");
        assert_eq!(State::read(&dir).unwrap().counts(), [0, 0, 9, 0, 0]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// A cut at a record's end among the changes (every line whole, every
    /// checksum right) falls short of the header's count: refused (issue
    /// 34), unless it takes exactly the last round's records, which the
    /// count does not cover yet.
    #[test]
    fn a_journal_cut_at_a_record_end_falls_short_of_its_count() {
        let dir = folder("cut");
        nine(&dir);
        let (mut state, mut journal) = Journal::open(&dir).unwrap();
        for i in 0..3 {
            state.points[i].status = Status::Done;
            journal.record(&mut state, &[i]).unwrap();
        }
        let path = dir.join(STATE_FILE);
        let text = std::fs::read_to_string(&path).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 1 + 9 + 3);
        let cut = |n: usize| {
            lines[..n]
                .iter()
                .map(|l| format!("{l}\n"))
                .collect::<String>()
        };
        std::fs::write(&path, cut(1 + 9 + 1)).unwrap();
        let err = State::read(&dir).unwrap_err().to_string();
        assert!(
            err.contains("line 1) counts 11 at least (cut at a record's end?)"),
            "{err}"
        );
        assert!(err.contains("10 point records"), "{err}");
        std::fs::write(&path, cut(1 + 9 + 2)).unwrap();
        assert_eq!(State::read(&dir).unwrap().counts(), [7, 0, 0, 2, 0]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// A valid header written without its padding (its checksum right)
    /// was rewritten in place at its padded length, over the start of the
    /// first point's record: "line 2: not a journal record" (issue 48,
    /// item 6). It is compacted into a padded one before any append.
    #[test]
    fn a_header_without_its_padding_is_never_rewritten_over_a_record() {
        let dir = folder("unpadded");
        nine(&dir);
        let path = dir.join(STATE_FILE);
        let text = std::fs::read_to_string(&path).unwrap();
        let (head, rest) = text.split_once('\n').unwrap();
        let json = head.split_once(' ').unwrap().1.replace(' ', "");
        std::fs::write(&path, frame(&json) + rest).unwrap();
        assert_eq!(
            State::read(&dir).unwrap().points.len(),
            9,
            "a valid journal"
        );
        let (mut state, mut journal) = Journal::open(&dir).unwrap();
        state.points[0].status = Status::Running;
        journal.record(&mut state, &[0]).unwrap();
        let now = std::fs::read_to_string(&path).unwrap();
        let r = records(&now);
        assert!(r.damage.is_empty(), "{:?}\n{now}", r.damage);
        assert_eq!(now.split_once('\n').unwrap().0, head, "padded again");
        assert_eq!(State::read(&dir).unwrap().counts(), [8, 0, 1, 0, 0]);
        // and a header of any other length is never written over a record
        journal.head += 1;
        state.points[1].status = Status::Running;
        journal.record(&mut state, &[1]).unwrap();
        let now = std::fs::read_to_string(&path).unwrap();
        assert!(records(&now).damage.is_empty(), "{now}");
        assert_eq!(State::read(&dir).unwrap().counts(), [7, 0, 2, 0, 0]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_damaged_or_truncated_journal_is_refused_never_read_as_fewer_points() {
        let dir = folder("damaged");
        nine(&dir);
        let path = dir.join(STATE_FILE);
        let text = std::fs::read_to_string(&path).unwrap();
        // cut after the fifth point's record
        let cut: usize = text.lines().take(6).map(|l| l.len() + 1).sum();
        std::fs::write(&path, &text[..cut]).unwrap();
        let err = State::read(&dir).unwrap_err().to_string();
        assert!(
            err.contains("records of 5 of its 9 points (truncated?): none of run 6"),
            "{err}"
        );
        assert!(err.contains("campaign repair"), "{err}");
        // one digit changed in a record
        std::fs::write(&path, text.replacen("\"attempts\":0", "\"attempts\":1", 1)).unwrap();
        let err = State::read(&dir).unwrap_err().to_string();
        assert!(err.contains("line 2: checksum mismatch"), "{err}");
        // an append cut mid-line (a writer at work, or killed) is left out
        std::fs::write(&path, text.clone() + "12ab {\"run\":1,").unwrap();
        assert_eq!(State::read(&dir).unwrap().points.len(), 9);
        // and cut off before the next append
        let (mut state, mut journal) = Journal::open(&dir).unwrap();
        journal.record(&mut state, &[0]).unwrap();
        let r = records(&std::fs::read_to_string(&path).unwrap()).damage;
        assert!(r.is_empty(), "{r:?}");
        // salvage keeps what is readable
        std::fs::write(&path, text.replacen("\"attempts\":0", "\"attempts\":1", 1)).unwrap();
        assert_eq!(salvage(&dir).len(), 8);
        // a state of an earlier bumpsim is named as such
        std::fs::remove_file(&path).unwrap();
        std::fs::write(dir.join(LEGACY_STATE_FILE), "format = 1\n").unwrap();
        let err = State::existing(&dir).unwrap_err().to_string();
        assert!(err.contains("state.toml of an earlier bumpsim"), "{err}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn timestamps_are_utc_calendar_dates() {
        assert_eq!(utc(0), "1970-01-01T00:00:00Z");
        assert_eq!(utc(951_782_400), "2000-02-29T00:00:00Z");
        assert_eq!(utc(1_795_000_000), "2026-11-18T11:06:40Z");
        for t in [0, 86_399, 951_782_400, 1_795_000_000, 4_102_444_800] {
            assert_eq!(seconds(&utc(t)), Some(t));
        }
        assert_eq!(seconds("2026-13-01T00:00:00Z"), None);
    }
}
