//! The local executor: up to N task processes at once on this machine.
//!
//! A task is `sh run-point.sh POINT_FOLDER`, its job id `local:PID`, in a
//! process group of its own: a Ctrl-C or a kill of the controller leaves
//! the tasks running, as on a cluster; a restarted controller adopts them
//! by pid (`/proc/PID` still running `run-point.sh`) and learns their
//! outcome from the exit marker they write. `campaign abort` stops them.

use super::{Executor, TaskState};
use crate::error::{CampaignError, Result};
use crate::init::TASK_SCRIPT;
use crate::state::Point;
use std::collections::HashMap;
use std::os::unix::process::CommandExt;
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::Duration;

/// A process pool.
#[derive(Debug)]
pub struct Local {
    slots: usize,
    children: HashMap<usize, Child>,
}

impl Local {
    /// A pool of `slots` processes.
    pub fn new(slots: usize) -> Local {
        Local {
            slots: slots.max(1),
            children: HashMap::new(),
        }
    }

    fn state(&mut self, point: &Point) -> TaskState {
        if let Some(child) = self.children.get_mut(&point.run) {
            return match child.try_wait() {
                Ok(None) => TaskState::Running,
                Ok(Some(status)) => {
                    self.children.remove(&point.run);
                    TaskState::Gone(format!(
                        "the task ended ({status}) without recording an exit status"
                    ))
                }
                Err(e) => TaskState::Gone(format!("cannot wait for the task: {e}")),
            };
        }
        match point
            .job
            .strip_prefix("local:")
            .and_then(|p| p.parse::<u32>().ok())
        {
            Some(pid) if task_alive(pid) => TaskState::Running,
            _ => TaskState::Gone(
                "the task's process ended without recording an exit status (controller restarted)"
                    .into(),
            ),
        }
    }
}

/// Stops the task of `point` (SIGTERM by `kill`, when its pid is still a
/// campaign task): the task's shell, its solver, and whatever the solver
/// started (the task's process group: a solver script's own children,
/// an MPI launcher's ranks).
pub fn terminate(point: &Point) {
    let pid = point
        .job
        .strip_prefix("local:")
        .and_then(|p| p.parse::<u32>().ok());
    if let Some(pid) = pid.filter(|&pid| task_alive(pid)) {
        // the task shell first (so it records no exit status), then the
        // solver, its child, found before the shell goes, then the rest of
        // the task's group (its shell leads it: spawned with
        // `process_group(0)`)
        let group = own_group(pid);
        let children = Command::new("pgrep")
            .args(["-P", &pid.to_string()])
            .output()
            .map(|o| String::from_utf8_lossy(&o.stdout).into_owned())
            .unwrap_or_default();
        let _ = Command::new("kill")
            .args(["-TERM", &pid.to_string()])
            .status();
        for child in children.split_whitespace() {
            let _ = Command::new("kill").args(["-TERM", child]).status();
        }
        if group {
            signal_group(pid, "-TERM");
        }
    }
}

/// Whether `pid` leads its own process group (a task shell does; the
/// controller's group is never signalled).
fn own_group(pid: u32) -> bool {
    // /proc/<pid>/stat: "pid (comm) state ppid pgrp ..."; comm may hold
    // spaces and parentheses, so the fields are counted after the last ')'
    std::fs::read_to_string(format!("/proc/{pid}/stat")).is_ok_and(|stat| {
        stat.rsplit_once(')')
            .and_then(|(_, rest)| rest.split_whitespace().nth(2)?.parse::<u32>().ok())
            == Some(pid)
    })
}

/// Sends `signal` (`-TERM`, `-KILL`) to every process of the group `pgid`.
fn signal_group(pgid: u32, signal: &str) {
    let _ = Command::new("kill")
        .args([signal, "--", &format!("-{pgid}")])
        .stderr(Stdio::null())
        .status();
}

/// Whether `pid` is still a task of a campaign (`run-point.sh` in its command line).
fn task_alive(pid: u32) -> bool {
    std::fs::read(format!("/proc/{pid}/cmdline"))
        .is_ok_and(|c| String::from_utf8_lossy(&c).contains(TASK_SCRIPT))
}

/// The running task processes on this machine: pid and arguments.
fn running_tasks() -> Vec<(u32, Vec<String>)> {
    let Ok(entries) = std::fs::read_dir("/proc") else {
        return Vec::new();
    };
    entries
        .flatten()
        .filter_map(|e| {
            let pid: u32 = e.file_name().to_str()?.parse().ok()?;
            let raw = std::fs::read(e.path().join("cmdline")).ok()?;
            let args: Vec<String> = raw
                .split(|b| *b == 0)
                .filter(|a| !a.is_empty())
                .map(|a| String::from_utf8_lossy(a).into_owned())
                .collect();
            args.iter()
                .any(|a| a.ends_with(TASK_SCRIPT))
                .then_some((pid, args))
        })
        .collect()
}

impl Executor for Local {
    fn name(&self) -> &'static str {
        "local"
    }

    fn free(&self, in_flight: usize) -> usize {
        self.slots.saturating_sub(in_flight)
    }

    fn submit(&mut self, dir: &Path, points: &[&Point]) -> Result<Vec<String>> {
        let mut ids = Vec::new();
        for p in points {
            let child = Command::new("sh")
                .process_group(0)
                .arg(dir.join(TASK_SCRIPT))
                .arg(dir.join(&p.folder))
                .stdin(Stdio::null())
                .stdout(Stdio::null())
                .stderr(Stdio::null())
                .spawn()
                .map_err(|source| CampaignError::Spawn {
                    program: "sh".into(),
                    source,
                })?;
            ids.push(format!("local:{}", child.id()));
            self.children.insert(p.run, child);
        }
        Ok(ids)
    }

    fn poll(&mut self, _dir: &Path, points: &[&Point]) -> Result<Vec<TaskState>> {
        Ok(points.iter().map(|p| self.state(p)).collect())
    }

    fn adopt(&mut self, dir: &Path, points: &[&Point]) -> Result<Vec<Option<String>>> {
        let tasks = running_tasks();
        Ok(points
            .iter()
            .map(|p| {
                let folder = dir.join(&p.folder).to_string_lossy().into_owned();
                tasks
                    .iter()
                    .find(|(_, args)| args.last() == Some(&folder))
                    .map(|(pid, _)| format!("local:{pid}"))
            })
            .collect())
    }

    fn cancel(&mut self, points: &[&Point]) -> Result<()> {
        for p in points {
            if let Some(mut child) = self.children.remove(&p.run) {
                // the task's whole group: the solver and its children too
                let leads = own_group(child.id());
                let _ = child.kill();
                if leads {
                    signal_group(child.id(), "-KILL");
                }
                let _ = child.wait();
            }
        }
        Ok(())
    }

    fn interval(&self) -> Duration {
        Duration::from_millis(5)
    }
}
