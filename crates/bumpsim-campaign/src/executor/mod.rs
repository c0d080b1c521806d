//! Executors: where the points' tasks run. Both run the campaign's task
//! script (`run-point.sh POINT_FOLDER`), which records the solver's exit
//! status in the point folder; the controller reads that marker first and
//! asks the executor only about tasks that have not recorded one.
//!
//! - [`local::Local`]: a process pool of N slots on this machine;
//! - [`slurm::Slurm`]: one `sbatch --array=...%K` per submission round,
//!   status from `squeue` (recently ended tasks included), `scancel` on abort.

pub mod local;
pub mod slurm;

use crate::error::Result;
use crate::state::Point;
use std::path::Path;
use std::time::Duration;

/// What an executor knows about a task that has not recorded an exit status.
#[derive(Debug, Clone, PartialEq)]
pub enum TaskState {
    /// Waiting in a queue.
    Queued,
    /// Running.
    Running,
    /// Ended without an exit status (killed, cancelled, timed out,
    /// pre-empted, node failure, lost): the reason.
    Gone(String),
}

/// A place to run tasks.
pub trait Executor {
    /// `local` or `slurm`.
    fn name(&self) -> &'static str;

    /// How many more tasks may be handed over now, with `in_flight` out.
    fn free(&self, in_flight: usize) -> usize;

    /// Starts the task of each point (campaign folder `dir`); returns their
    /// job ids in the same order.
    fn submit(&mut self, dir: &Path, points: &[&Point]) -> Result<Vec<String>>;

    /// The state of each in-flight point's task.
    fn poll(&mut self, dir: &Path, points: &[&Point]) -> Result<Vec<TaskState>>;

    /// The job ids of tasks already started for these points by a
    /// controller that died before it recorded them (`None`: no such task).
    fn adopt(&mut self, dir: &Path, points: &[&Point]) -> Result<Vec<Option<String>>>;

    /// Stops the tasks of these points (abort).
    fn cancel(&mut self, points: &[&Point]) -> Result<()>;

    /// Time between polls.
    fn interval(&self) -> Duration;
}

/// Runs `program args` and returns its standard output, or an error with
/// its standard error.
pub(crate) fn command_output(program: &str, args: &[String]) -> Result<String> {
    let line = format!("{program} {}", args.join(" "));
    let output = std::process::Command::new(program)
        .args(args)
        .output()
        .map_err(|source| crate::error::CampaignError::Spawn {
            program: program.into(),
            source,
        })?;
    if !output.status.success() {
        return Err(crate::error::CampaignError::Scheduler {
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
