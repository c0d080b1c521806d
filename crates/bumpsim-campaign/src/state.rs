//! The state file (`state.toml` in the campaign folder): one `[[point]]`
//! per design run with its status (pending, submitted, running, done,
//! failed), job id, attempts, timestamps (UTC), the SHA-256 of its inputs
//! and the reason of its last failure. Human-readable TOML, written whole
//! or not at all (temporary file + rename). The format is in
//! docs/campaign.md.
//!
//! The lock (`.lock` beside it) keeps a second controller off a campaign:
//! created with `O_EXCL`, holding the pid and host; a lock whose process is
//! gone on this host is stale and taken over.

use crate::error::{CampaignError, Result, read_error};
use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};
use std::path::{Path, PathBuf};

/// The state file's name in the campaign folder.
pub const STATE_FILE: &str = "state.toml";
/// The lock file's name in the campaign folder.
pub const LOCK_FILE: &str = ".lock";

/// Where a point is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    /// Not submitted yet (or to be retried).
    Pending,
    /// Handed to the executor.
    Submitted,
    /// Running.
    Running,
    /// Finished and its responses read.
    Done,
    /// Failed for good (reason recorded).
    Failed,
}

impl Status {
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
    /// Its folder, relative to the campaign folder.
    pub folder: String,
    /// Status.
    pub status: Status,
    /// Submissions so far.
    pub attempts: u32,
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
    /// Why the last attempt failed.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub reason: String,
}

/// The whole state.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct State {
    /// Format version.
    pub format: u32,
    /// Campaign name.
    pub campaign: String,
    /// Last write, UTC.
    pub updated: String,
    /// The points in run order.
    #[serde(rename = "point")]
    pub points: Vec<Point>,
}

impl State {
    /// Reads the state file of campaign folder `dir`.
    pub fn read(dir: &Path) -> Result<State> {
        let path = dir.join(STATE_FILE);
        let text = std::fs::read_to_string(&path).map_err(|e| read_error(&path, e))?;
        let state: State = toml::from_str(&text).map_err(|e| CampaignError::State {
            path: path.clone(),
            message: e.to_string(),
        })?;
        let numbered = state.points.iter().enumerate().all(|(i, p)| p.run == i + 1);
        if state.format != 1 || !numbered {
            let message = "format 1 with points numbered 1, 2, ... expected".into();
            return Err(CampaignError::State { path, message });
        }
        Ok(state)
    }

    /// Writes the state file atomically (temporary file + rename).
    pub fn write(&mut self, dir: &Path) -> Result<()> {
        self.updated = now();
        let text = toml::to_string(self).map_err(|e| CampaignError::State {
            path: dir.join(STATE_FILE),
            message: e.to_string(),
        })?;
        let header = "# bumpsim campaign state (docs/campaign.md): one [[point]] per design run\n";
        bumpsim_io::output::write_atomic(
            &dir.join(STATE_FILE),
            (header.to_string() + &text).as_bytes(),
        )?;
        Ok(())
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

/// The SHA-256 (hex, `sha256:` prefixed) of a point's input files and command.
pub fn input_hash(folder: &Path, files: &[String], command: &[String]) -> Result<String> {
    let mut hasher = Sha256::new();
    for name in files {
        let path = folder.join(name);
        let bytes = std::fs::read(&path).map_err(|e| read_error(&path, e))?;
        hasher.update((name.len() as u64).to_le_bytes());
        hasher.update(name.as_bytes());
        hasher.update((bytes.len() as u64).to_le_bytes());
        hasher.update(&bytes);
    }
    for word in command {
        hasher.update((word.len() as u64).to_le_bytes());
        hasher.update(word.as_bytes());
    }
    let digest = hasher.finalize();
    Ok(format!(
        "sha256:{}",
        digest
            .iter()
            .map(|b| format!("{b:02x}"))
            .collect::<String>()
    ))
}

/// The first 8 hex digits of the SHA-256 of `bytes` (a short stable id).
pub fn short_hash(bytes: &[u8]) -> String {
    Sha256::digest(bytes)[..4]
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
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

/// The campaign's lock: held while a controller runs; removed on drop.
#[derive(Debug)]
pub struct Lock {
    path: PathBuf,
}

impl Lock {
    /// Takes the lock of campaign folder `dir`, or says who holds it. A
    /// lock left by a process that no longer exists on this host is taken over.
    pub fn acquire(dir: &Path) -> Result<Lock> {
        let path = dir.join(LOCK_FILE);
        let host = hostname();
        let me = format!("pid {} on {host} since {}\n", std::process::id(), now());
        for _ in 0..2 {
            let created = std::fs::OpenOptions::new()
                .write(true)
                .create_new(true)
                .open(&path);
            match created {
                Ok(mut file) => {
                    use std::io::Write;
                    file.write_all(me.as_bytes())
                        .map_err(|e| read_error(&path, e))?;
                    return Ok(Lock { path });
                }
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {
                    let holder = std::fs::read_to_string(&path).unwrap_or_default();
                    if !stale(&holder, &host) {
                        let holder = holder.trim().to_string();
                        return Err(CampaignError::Locked { path, holder });
                    }
                    let _ = std::fs::remove_file(&path);
                }
                Err(e) => return Err(read_error(&path, e)),
            }
        }
        Err(CampaignError::Locked {
            path,
            holder: "a controller that keeps taking it".into(),
        })
    }
}

/// Who holds the lock of campaign folder `dir` (`pid N on HOST since T`),
/// and whether that controller is gone (a stale lock on this host).
pub fn lock_holder(dir: &Path) -> Option<(String, bool)> {
    let holder = std::fs::read_to_string(dir.join(LOCK_FILE)).ok()?;
    let gone = stale(&holder, &hostname());
    Some((holder.trim().to_string(), gone))
}

impl Drop for Lock {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.path);
    }
}

/// Whether a lock's holder (`pid N on HOST since T`) is gone: same host and
/// no such process. A lock of another host is never stale.
fn stale(holder: &str, host: &str) -> bool {
    let words: Vec<&str> = holder.split_whitespace().collect();
    match words.as_slice() {
        ["pid", pid, "on", h, ..] if *h == host => {
            pid.parse::<u32>().is_ok_and(|pid| !process_alive(pid))
        }
        _ => holder.trim().is_empty(),
    }
}

/// Whether process `pid` exists (Linux: `/proc/PID`).
/// A zombie (ended, not yet reaped by its parent) counts as gone.
pub fn process_alive(pid: u32) -> bool {
    match std::fs::read_to_string(format!("/proc/{pid}/stat")) {
        // the state follows the command name in parentheses: "PID (NAME) S ..."
        Ok(stat) => stat
            .rsplit_once(')')
            .is_some_and(|(_, rest)| !rest.trim_start().starts_with(['Z', 'X'])),
        Err(_) => false,
    }
}

/// This machine's host name.
pub fn hostname() -> String {
    std::fs::read_to_string("/proc/sys/kernel/hostname")
        .map(|h| h.trim().to_string())
        .unwrap_or_else(|_| "localhost".into())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn timestamps_are_utc_calendar_dates() {
        assert_eq!(utc(0), "1970-01-01T00:00:00Z");
        assert_eq!(utc(951_782_400), "2000-02-29T00:00:00Z");
        assert_eq!(utc(1_795_000_000), "2026-11-18T11:06:40Z");
    }

    #[test]
    fn a_second_controller_is_refused_and_a_stale_lock_taken_over() {
        let dir = std::env::temp_dir().join(format!("bumpsim-lock-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let lock = Lock::acquire(&dir).unwrap();
        let err = Lock::acquire(&dir).unwrap_err().to_string();
        assert!(
            err.contains("another controller")
                && err.contains(&format!("pid {}", std::process::id())),
            "{err}"
        );
        drop(lock);
        // a lock of a process that is gone (pid beyond pid_max)
        std::fs::write(
            dir.join(LOCK_FILE),
            format!("pid 4999999 on {} since x\n", hostname()),
        )
        .unwrap();
        let lock = Lock::acquire(&dir).unwrap();
        drop(lock);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
