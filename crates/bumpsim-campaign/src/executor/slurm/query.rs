//! What the Slurm executor asks the cluster: its limits (`scontrol show
//! config`), the state, reason and restart count of a campaign's tasks
//! (`squeue -r -t all -O JobArrayID,State,RestartCnt,Reason`), their
//! history where the cluster keeps accounting (`sacct -D`: every instance
//! of a requeued task, with the state that ended it), and the tasks of a
//! job name (`squeue --name`). The answers' formats are Slurm's
//! (slurm.schedmd.com: squeue, sacct, scontrol man pages, 22.05+).

use crate::error::{CampaignError, Result};
use crate::executor::{Task, TaskState, command_output};
use std::collections::HashMap;

/// The cluster's limits that shape the arrays.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(super) struct Config {
    /// `MaxArraySize`: array indices stay below it.
    pub max_array_size: Option<usize>,
    /// `MaxJobCount`: jobs the controller keeps at once.
    pub max_job_count: Option<usize>,
    /// `KillWait`, s: how long a node waits between a cancelled task's
    /// SIGTERM and its SIGKILL.
    pub kill_wait: Option<u64>,
    /// `UnkillableStepTimeout`, s: how long a node then waits for a task
    /// that ignores SIGKILL before it gives up on it.
    pub unkillable_step_timeout: Option<u64>,
}

impl Config {
    /// How long `abort` waits after `scancel` for its tasks to end: the
    /// longer of `floor` and `KillWait + UnkillableStepTimeout` plus a
    /// margin of [`CANCEL_MARGIN`] for the node's report to reach squeue.
    pub fn cancel_wait(&self, floor: std::time::Duration) -> std::time::Duration {
        let known = (self.kill_wait.unwrap_or(0))
            .saturating_add(self.unkillable_step_timeout.unwrap_or(0))
            .saturating_add(CANCEL_MARGIN);
        floor.max(std::time::Duration::from_secs(known))
    }
}

/// Seconds added to the cluster's kill timeouts when waiting for a
/// cancelled task to leave squeue ([`Config::cancel_wait`]).
pub(super) const CANCEL_MARGIN: u64 = 30;

/// `scontrol show config`'s limits (none known if it fails).
pub(super) fn config() -> Config {
    let text = command_output("scontrol", &["show".into(), "config".into()]).unwrap_or_default();
    parse_config(&text)
}

fn parse_config(text: &str) -> Config {
    // `KEY = VALUE [unit]` (`KillWait = 30 sec`): the value's first word
    let word = |key: &str| {
        text.lines()
            .filter_map(|l| l.split_once('='))
            .find(|(k, _)| k.trim() == key)
            .and_then(|(_, v)| v.split_whitespace().next().map(str::to_owned))
    };
    let count = |key: &str| word(key).and_then(|v| v.parse::<usize>().ok());
    let seconds = |key: &str| word(key).and_then(|v| v.parse::<u64>().ok());
    Config {
        max_array_size: count("MaxArraySize"),
        max_job_count: count("MaxJobCount"),
        kill_wait: seconds("KillWait"),
        unkillable_step_timeout: seconds("UnkillableStepTimeout"),
    }
}

/// A task as `squeue` lists it.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Row {
    pub state: String,
    pub reason: String,
    pub restarts: u32,
}

/// Task id (`JOB_INDEX`) → its row, for every task of the array jobs
/// `jobs` that `squeue` still lists (ended ones included), in one call.
pub(super) fn squeue(jobs: &[&str]) -> Result<HashMap<String, Row>> {
    if jobs.is_empty() {
        return Ok(HashMap::new());
    }
    let mut args: Vec<String> = ["-h", "-r", "-t", "all", "-O"].map(String::from).to_vec();
    args.push("JobArrayID:|,State:|,RestartCnt:|,Reason:".into());
    args.extend(["-j".into(), jobs.join(",")]);
    let out = match command_output("squeue", &args) {
        Ok(out) => out,
        // every job purged already: squeue refuses the ids
        Err(CampaignError::Scheduler { message, .. }) if message.contains("Invalid job id") => {
            String::new()
        }
        Err(e) => return Err(e),
    };
    Ok(out.lines().filter_map(parse_row).collect())
}

fn parse_row(line: &str) -> Option<(String, Row)> {
    let mut parts = line.trim().splitn(4, '|');
    let id = parts.next()?.trim().to_string();
    let state = parts.next()?.trim().to_string();
    let restarts = parts.next()?.trim().parse().ok()?;
    let reason = parts.next().unwrap_or("").trim().to_string();
    Some((
        id,
        Row {
            state,
            reason,
            restarts,
        },
    ))
}

/// One record of a task in the accounting: its state and reason.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Record {
    pub state: String,
    pub reason: String,
}

/// Task id → its accounting records, oldest first (a requeued task has one
/// per ended run; a pending run has none yet), for every task of the array
/// jobs `jobs`; `None` where the cluster keeps no accounting or `sacct` fails.
pub(super) fn sacct(jobs: &[&str]) -> Option<HashMap<String, Vec<Record>>> {
    let mut jobs = jobs.to_vec();
    jobs.sort_unstable();
    jobs.dedup();
    if jobs.is_empty() {
        return Some(HashMap::new());
    }
    let mut args: Vec<String> = ["-n", "-P", "-D", "-X", "-o", "JobID,State,Reason", "-j"]
        .map(String::from)
        .to_vec();
    args.push(jobs.join(","));
    command_output("sacct", &args)
        .ok()
        .map(|out| parse_sacct(&out))
}

fn parse_sacct(out: &str) -> HashMap<String, Vec<Record>> {
    let mut history: HashMap<String, Vec<Record>> = HashMap::new();
    for line in out.lines() {
        let mut parts = line.trim().splitn(3, '|');
        let (Some(id), Some(state)) = (parts.next(), parts.next()) else {
            continue;
        };
        // "CANCELLED by 0" → CANCELLED; "123_[4-9]" is the unsplit pending rest
        let Some(state) = state.split_whitespace().next() else {
            continue;
        };
        if id.contains('[') {
            continue;
        }
        history.entry(id.to_string()).or_default().push(Record {
            state: state.to_string(),
            reason: parts.next().unwrap_or("").trim().to_string(),
        });
    }
    history
}

/// The task `id` as the queue and the accounting (`None`: none answers)
/// know it. With accounting, only the requeues whose cause it already
/// records are counted; the others follow at a later poll.
pub(super) fn task(
    id: &str,
    queue: &HashMap<String, Row>,
    history: Option<&HashMap<String, Vec<Record>>>,
) -> Task {
    let records = history
        .and_then(|h| h.get(id))
        .map_or(&[][..], Vec::as_slice);
    let known = |restarts: u32, earlier: &[Record]| match history {
        Some(_) => restarts.min(earlier.len() as u32),
        None => restarts,
    };
    let (state, requeues, reason, earlier) = match (queue.get(id), records.split_last()) {
        // the accounting lists the current run once it started (not while pending)
        (Some(row), Some((last, earlier))) if last.state == row.state => (
            task_state(&row.state, &row.reason),
            known(row.restarts, earlier),
            &row.reason,
            earlier,
        ),
        (Some(row), _) => (
            task_state(&row.state, &row.reason),
            known(row.restarts, records),
            &row.reason,
            records,
        ),
        (None, Some((last, earlier))) => (
            task_state(&last.state, &last.reason),
            earlier.len() as u32,
            &last.reason,
            earlier,
        ),
        (None, None) => {
            return Task::new(TaskState::Gone(
                "no longer known to Slurm (squeue, sacct) and no exit status recorded".into(),
            ));
        }
    };
    Task {
        state,
        requeues,
        requeue_reason: requeue_reason(earlier, reason),
    }
}

/// Why a task was requeued: the states that ended its earlier runs in the
/// accounting, else what `squeue` says.
fn requeue_reason(earlier: &[Record], reason: &str) -> String {
    if earlier.is_empty() {
        return format!("no accounting record says why (squeue reason: {reason})");
    }
    let causes: Vec<String> = earlier
        .iter()
        .map(|r| match r.state.as_str() {
            "NODE_FAIL" => "a node failure (sacct: NODE_FAIL)".into(),
            "PREEMPTED" => "pre-emption (sacct: PREEMPTED)".into(),
            "REQUEUED" => "a requeue (sacct: REQUEUED: scontrol requeue or the scheduler)".into(),
            other => format!("sacct: {other}"),
        })
        .collect();
    causes.join(", then ")
}

/// A Slurm job state as a task state.
pub(super) fn task_state(state: &str, reason: &str) -> TaskState {
    match state {
        "PENDING" | "CONFIGURING" | "REQUEUED" | "REQUEUE_HOLD" | "REQUEUE_FED" | "RESIZING"
        | "SUSPENDED" => TaskState::Queued,
        "RUNNING" | "COMPLETING" | "STAGE_OUT" | "SIGNALING" => TaskState::Running,
        // the marker is written before the task ends: COMPLETED without it
        // is a task whose folder was not writable or a lost write
        _ => TaskState::Gone(format!(
            "Slurm state {state} (reason: {reason}) without an exit status"
        )),
    }
}

/// A task found by its job name.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Named {
    pub job: u64,
    pub index: usize,
    pub name: String,
}

/// The tasks (queued, running, recently ended) of the jobs named `names`.
pub(super) fn named(names: &[String]) -> Result<Vec<Named>> {
    let mut args: Vec<String> = ["-h", "-r", "-t", "all", "-o", "%i|%j"]
        .map(String::from)
        .to_vec();
    args.push(format!("--name={}", names.join(",")));
    let out = command_output("squeue", &args)?;
    Ok(out
        .lines()
        .filter_map(|line| {
            let (id, name) = line.trim().split_once('|')?;
            let (job, index) = id.split_once('_')?;
            Some(Named {
                job: job.parse().ok()?,
                index: index.parse().ok()?,
                name: name.to_string(),
            })
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn limits_come_from_the_configuration() {
        let text = "MaxArraySize            = 10\nMaxJobCount             = 200000\nMaxStepCount = 40000\n";
        let config = parse_config(text);
        assert_eq!(
            (config.max_array_size, config.max_job_count),
            (Some(10), Some(200_000))
        );
        assert_eq!(parse_config("").max_array_size, None);
    }

    #[test]
    fn the_cancel_wait_covers_the_kill_timeouts() {
        let floor = std::time::Duration::from_secs(120);
        let text = "KillWait                = 300 sec\nUnkillableStepTimeout   = 60 sec\n";
        let config = parse_config(text);
        assert_eq!(
            (config.kill_wait, config.unkillable_step_timeout),
            (Some(300), Some(60))
        );
        assert_eq!(
            config.cancel_wait(floor).as_secs(),
            300 + 60 + CANCEL_MARGIN
        );
        // Slurm's defaults (30 s, 60 s) and an unknown configuration: the floor
        let defaults = parse_config("KillWait = 30 sec\nUnkillableStepTimeout = 60 sec\n");
        assert_eq!(defaults.cancel_wait(floor), floor);
        assert_eq!(parse_config("").cancel_wait(floor), floor);
        assert_eq!(parse_config("KillWait = soon\n").kill_wait, None);
        let huge = format!(
            "KillWait = {} sec\nUnkillableStepTimeout = 60 sec\n",
            u64::MAX
        );
        assert_eq!(parse_config(&huge).cancel_wait(floor).as_secs(), u64::MAX);
    }

    #[test]
    fn states_map_to_retryable_losses() {
        assert_eq!(task_state("PENDING", "Priority"), TaskState::Queued);
        assert_eq!(task_state("RUNNING", "None"), TaskState::Running);
        let TaskState::Gone(reason) = task_state("TIMEOUT", "TimeLimit") else {
            panic!()
        };
        assert!(reason.contains("TIMEOUT") && reason.contains("TimeLimit"));
    }

    #[test]
    fn a_requeue_is_counted_with_its_cause() {
        let queue: HashMap<String, Row> = ["7_3|PENDING|1|BeginTime", "7_4|RUNNING|0|None"]
            .iter()
            .filter_map(|l| parse_row(l))
            .collect();
        // as sacct -D lists a task requeued after a node failure and pending again
        let history = parse_sacct("7_3|NODE_FAIL|None\n7_[5-9]|PENDING|None\n7_4|RUNNING|None\n");
        let requeued = task("7_3", &queue, Some(&history));
        assert_eq!((requeued.state, requeued.requeues), (TaskState::Queued, 1));
        assert!(
            requeued
                .requeue_reason
                .contains("node failure (sacct: NODE_FAIL)")
        );
        // without accounting: the count, and squeue's reason
        let bare = task("7_3", &queue, None);
        assert_eq!(bare.requeues, 1);
        assert!(
            bare.requeue_reason.contains("squeue reason: BeginTime"),
            "{}",
            bare.requeue_reason
        );
        let running = task("7_4", &queue, Some(&history));
        assert_eq!((running.state, running.requeues), (TaskState::Running, 0));
        // a requeue whose cause the accounting does not hold yet waits a poll
        assert_eq!(task("7_3", &queue, Some(&HashMap::new())).requeues, 0);
        // purged from squeue: the accounting's last record
        let purged = parse_sacct("7_5|PREEMPTED|None\n7_5|CANCELLED by 0|None\n");
        let t = task("7_5", &queue, Some(&purged));
        assert!(matches!(t.state, TaskState::Gone(ref r) if r.contains("CANCELLED")));
        assert_eq!(t.requeues, 1);
        assert!(t.requeue_reason.contains("pre-emption"));
        assert!(matches!(
            task("7_6", &queue, Some(&purged)).state,
            TaskState::Gone(_)
        ));
    }
}
