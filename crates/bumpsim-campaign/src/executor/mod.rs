//! Executors: where the points' tasks run. Both run the campaign's task
//! script (`run-point.sh POINT_FOLDER`), which records the solver's exit
//! status (and, on Slurm, the task's restart count) in the point folder;
//! the controller reads that marker first and asks the executor about
//! tasks that have not recorded a success.
//!
//! - [`local::Local`]: a process pool of N slots on this machine, with a
//!   time limit per task;
//! - [`slurm::Slurm`]: job arrays cut to the cluster's `MaxArraySize`,
//!   status of all of them from one `squeue` (and `sacct`) call per poll,
//!   `scancel` on abort.

pub mod local;
pub mod slurm;

use crate::error::{CampaignError, Result};
use crate::state::Point;
use std::path::Path;
use std::time::Duration;

/// What an executor knows about a task that has not recorded an exit status.
#[derive(Debug, Clone, PartialEq)]
pub enum TaskState {
    /// Waiting in a queue (a requeued task too).
    Queued,
    /// Running.
    Running,
    /// Ended without an exit status (killed, cancelled, timed out,
    /// pre-empted, node failure, lost): the reason.
    Gone(String),
    /// Ended by the executor itself (the local time limit): the reason,
    /// whatever exit status the task may have recorded as it died.
    Killed(String),
}

/// A task as the executor sees it.
#[derive(Debug, Clone, PartialEq)]
pub struct Task {
    /// Its state.
    pub state: TaskState,
    /// How often the scheduler has requeued it (Slurm's restart count).
    pub requeues: u32,
    /// Why it was requeued, where the scheduler says.
    pub requeue_reason: String,
}

impl Task {
    /// A task in `state` that was never requeued.
    pub fn new(state: TaskState) -> Task {
        Task {
            state,
            requeues: 0,
            requeue_reason: String::new(),
        }
    }
}

/// What a submission achieved: the job ids of the points it started (in
/// order; fewer than asked when it stopped), and why it stopped.
#[derive(Debug)]
pub struct Submitted {
    /// Job ids of the first points, in order.
    pub jobs: Vec<String>,
    /// The error that stopped it before the rest.
    pub error: Option<CampaignError>,
}

/// A place to run tasks.
pub trait Executor {
    /// `local` or `slurm`.
    fn name(&self) -> &'static str;

    /// How many more tasks may be handed over now, with `in_flight` out.
    fn free(&self, in_flight: usize) -> usize;

    /// Starts the task of each point (campaign folder `dir`), in order,
    /// until one cannot be started.
    fn submit(&mut self, dir: &Path, points: &[&Point]) -> Submitted;

    /// The state of each in-flight point's task.
    fn poll(&mut self, dir: &Path, points: &[&Point]) -> Result<Vec<Task>>;

    /// The job ids of tasks already started for these points by a
    /// controller that died before it recorded them (`None`: no such task).
    fn adopt(&mut self, dir: &Path, points: &[&Point]) -> Result<Vec<Option<String>>>;

    /// Stops the tasks of these points (abort).
    fn cancel(&mut self, points: &[&Point]) -> Result<()>;

    /// Forgets the task of `point`, which is no longer in flight (its
    /// outcome is recorded): a local executor reaps its process.
    fn release(&mut self, point: &Point) {
        let _ = point;
    }

    /// Time to wait before the next poll, after `idle` polls that changed nothing.
    fn interval(&self, idle: u32) -> Duration;
}

/// Runs `program args` and returns its standard output, or an error with
/// its standard error.
pub(crate) fn command_output(program: &str, args: &[String]) -> Result<String> {
    let line = format!("{program} {}", args.join(" "));
    let output = std::process::Command::new(program)
        .args(args)
        .output()
        .map_err(|source| CampaignError::Spawn {
            program: program.into(),
            source,
        })?;
    if !output.status.success() {
        return Err(CampaignError::Scheduler {
            command: line,
            message: format!(
                "{} ({})",
                String::from_utf8_lossy(&output.stderr).trim(),
                output.status
            ),
        });
    }
    Ok(String::from_utf8_lossy(&output.stdout).into_owned())
}
