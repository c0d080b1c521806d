//! The campaign's lock (`.lock` in the campaign folder): it keeps a second
//! controller off a campaign. Created with `O_EXCL` (POSIX `open`), holding
//! the pid, host and start time of its holder; a lock whose process is gone
//! on this host is stale and taken over. `run`, `abort`, `repair` and a
//! re-`init` take it; `status` and `collect` only read.

use crate::error::{CampaignError, Result, read_error};
use crate::state::now;
use std::path::{Path, PathBuf};

/// The lock file's name in the campaign folder.
pub const LOCK_FILE: &str = ".lock";

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
