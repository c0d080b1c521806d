//! The local executor: up to N task processes at once on this machine.
//!
//! A task is `sh run-point.sh POINT_FOLDER`, its job id `local:PID`, in a
//! process group of its own (POSIX `setpgid`): a Ctrl-C or a kill of the
//! controller leaves the tasks running, as on a cluster; a restarted
//! controller adopts them by pid (`/proc/PID` still running
//! `run-point.sh`) and learns their outcome from the exit marker they
//! write. `campaign abort` stops them.
//!
//! A task that outlives the campaign's time limit (`[executor] time`, in
//! Slurm's form) is ended as Slurm ends one: SIGTERM to its whole process
//! group (the task's shell, the solver and whatever the solver started),
//! SIGKILL [`KILL_WAIT`] later or as soon as the shell is gone; the
//! controller then retries it with the reason recorded.

use super::{Executor, Submitted, Task, TaskState};
use crate::error::CampaignError;
use crate::state::{Point, seconds};
use crate::task::TASK_SCRIPT;
use std::collections::HashMap;
use std::os::unix::process::CommandExt;
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// Between SIGTERM and SIGKILL of a task at its time limit (Slurm's `KillWait`).
pub const KILL_WAIT: Duration = Duration::from_secs(10);

/// A process pool.
#[derive(Debug)]
pub struct Local {
    slots: usize,
    limit: Option<(String, Duration)>,
    tasks: HashMap<usize, Running>,
    /// Released tasks whose process has not been reaped yet (it was
    /// exiting as its outcome was read): reaped at the next submission.
    exiting: Vec<Child>,
}

/// A task this controller started or adopted.
#[derive(Debug)]
struct Running {
    pid: u32,
    /// Present when this controller started it.
    child: Option<Child>,
    /// When its time limit is reached.
    deadline: Option<Instant>,
    /// When it was sent SIGTERM at its limit.
    terminated: Option<Instant>,
}

impl Local {
    /// A pool of `slots` processes, each task limited to `limit` (its text
    /// as the campaign file gives it, and its length), if any.
    pub fn new(slots: usize, limit: Option<(String, Duration)>) -> Local {
        Local {
            slots: slots.max(1),
            limit,
            tasks: HashMap::new(),
            exiting: Vec::new(),
        }
    }

    fn state(&mut self, point: &Point) -> TaskState {
        let limit = self.limit.as_ref().map(|(_, l)| *l);
        let Some(task) = self.task(point, limit) else {
            return TaskState::Gone(
                "the task's process ended without recording an exit status (controller restarted)"
                    .into(),
            );
        };
        match task.alive() {
            Ok(()) => {
                task.enforce();
                TaskState::Running
            }
            Err(ended) => {
                let task = self.tasks.remove(&point.run);
                match (task.and_then(|t| t.terminated), &self.limit) {
                    (Some(_), Some((text, _))) => {
                        signal_group(ended.pid, "-KILL");
                        TaskState::Killed(format!(
                            "time limit {text} reached: the task's process group was terminated"
                        ))
                    }
                    _ => TaskState::Gone(ended.message),
                }
            }
        }
    }

    /// The task of `point`: this controller's, or an adopted one still
    /// running (its limit counted from its submission).
    fn task(&mut self, point: &Point, limit: Option<Duration>) -> Option<&mut Running> {
        use std::collections::hash_map::Entry;
        match self.tasks.entry(point.run) {
            Entry::Occupied(task) => Some(task.into_mut()),
            Entry::Vacant(slot) => {
                let pid = pid_of(point).filter(|&pid| task_alive(pid))?;
                let since = seconds(&point.submitted).unwrap_or(0);
                let now = seconds(&crate::state::now()).unwrap_or(0);
                let elapsed = Duration::from_secs(now.saturating_sub(since));
                Some(slot.insert(Running {
                    pid,
                    child: None,
                    deadline: limit.map(|l| Instant::now() + l.saturating_sub(elapsed)),
                    terminated: None,
                }))
            }
        }
    }
}

/// How a task ended: its pid and what is known about its end.
struct Ended {
    pid: u32,
    message: String,
}

impl Running {
    fn alive(&mut self) -> Result<(), Ended> {
        let pid = self.pid;
        let message = match &mut self.child {
            Some(child) => match child.try_wait() {
                Ok(None) => return Ok(()),
                Ok(Some(status)) => {
                    format!("the task ended ({status}) without recording an exit status")
                }
                Err(e) => format!("cannot wait for the task: {e}"),
            },
            None if task_alive(pid) => return Ok(()),
            None => {
                "the task's process ended without recording an exit status (controller restarted)"
                    .into()
            }
        };
        Err(Ended { pid, message })
    }

    /// SIGTERM to the task's group at its deadline, SIGKILL [`KILL_WAIT`] later.
    fn enforce(&mut self) {
        let now = Instant::now();
        match self.terminated {
            None if self.deadline.is_some_and(|d| now >= d) => {
                signal_group(self.pid, "-TERM");
                self.terminated = Some(now);
            }
            Some(at) if now.duration_since(at) >= KILL_WAIT => signal_group(self.pid, "-KILL"),
            _ => {}
        }
    }
}

fn pid_of(point: &Point) -> Option<u32> {
    point.job.strip_prefix("local:")?.parse().ok()
}

/// Stops the task of `point` (SIGTERM by `kill`, when its pid is still a
/// campaign task): the task's shell, its solver, and whatever the solver
/// started (the task's process group: a solver script's own children,
/// an MPI launcher's ranks).
pub fn terminate(point: &Point) {
    if let Some(pid) = pid_of(point).filter(|&pid| task_alive(pid)) {
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

/// Sends `signal` (`-TERM`, `-KILL`) to every process of the group `pgid`
/// (a task's: never the controller's own).
fn signal_group(pgid: u32, signal: &str) {
    if pgid == std::process::id() {
        return;
    }
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

    fn submit(&mut self, dir: &Path, points: &[&Point]) -> Submitted {
        self.exiting
            .retain_mut(|child| !matches!(child.try_wait(), Ok(Some(_)) | Err(_)));
        let mut jobs = Vec::new();
        for p in points {
            let spawned = Command::new("sh")
                .process_group(0)
                .arg(dir.join(TASK_SCRIPT))
                .arg(dir.join(&p.folder))
                .stdin(Stdio::null())
                .stdout(Stdio::null())
                .stderr(Stdio::null())
                .spawn();
            let child = match spawned {
                Ok(child) => child,
                Err(source) => {
                    let program = "sh".into();
                    let error = Some(CampaignError::Spawn { program, source });
                    return Submitted { jobs, error };
                }
            };
            jobs.push(format!("local:{}", child.id()));
            let task = Running {
                pid: child.id(),
                child: Some(child),
                deadline: self.limit.as_ref().map(|(_, l)| Instant::now() + *l),
                terminated: None,
            };
            self.tasks.insert(p.run, task);
        }
        Submitted { jobs, error: None }
    }

    fn poll(&mut self, _dir: &Path, points: &[&Point]) -> crate::Result<Vec<Task>> {
        Ok(points.iter().map(|p| Task::new(self.state(p))).collect())
    }

    fn adopt(&mut self, dir: &Path, points: &[&Point]) -> crate::Result<Vec<Option<String>>> {
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

    fn cancel(&mut self, points: &[&Point]) -> crate::Result<()> {
        for p in points {
            if let Some(mut child) = self.tasks.remove(&p.run).and_then(|t| t.child) {
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

    fn release(&mut self, point: &Point) {
        let child = self.tasks.remove(&point.run).and_then(|t| t.child);
        if let Some(mut child) = child
            && !matches!(child.try_wait(), Ok(Some(_)) | Err(_))
        {
            self.exiting.push(child);
        }
    }

    /// Half a millisecond while tasks end often (a no-op solver ends in
    /// about 2 ms), doubling after 20 quiet polls up to 0.1 s.
    fn interval(&self, idle: u32) -> Duration {
        let doublings = idle.saturating_sub(20).min(8);
        Duration::from_micros(500 << doublings).min(Duration::from_millis(100))
    }
}
