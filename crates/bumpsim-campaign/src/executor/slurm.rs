//! The Slurm executor: the pending points of a submission round go out as
//! job arrays, `sbatch --parsable --array=INDICES%K slurm/array.sh OFFSET`,
//! whose task `OFFSET + SLURM_ARRAY_TASK_ID` is the point's run number.
//! An array index must stay below the cluster's `MaxArraySize` (read from
//! `scontrol show config`), so runs are cut into blocks of
//! `MaxArraySize − 1`: block b holds runs `b·(M−1) + 1 ..= (b+1)·(M−1)`
//! at indices 1 ..= M−1, one array per block and round (index = run in the
//! first block). Job ids are `slurm:JOB_INDEX`, the job name
//! `bumpsim-NAME-ID` (`+OFFSET` after it beyond the first block), so that
//! a restarted controller finds its tasks. At most `max_queued` tasks of a
//! campaign are queued or running at once; more go out as they end.
//!
//! Status: one `squeue -r -t all` per poll for all the campaign's arrays
//! lists queued, running and recently ended tasks (Slurm keeps ended jobs
//! for `MinJobAge`) with state, reason and restart count. A task whose
//! restart count grew was requeued (node failure, pre-emption,
//! `scontrol requeue`): the requeue is counted and its cause looked up in
//! the accounting (`sacct -D`, one call per poll, only then and for tasks
//! purged from `squeue`). A task gone from both without an exit status is
//! lost (cancelled, timed out, pre-empted, node failure) and retried.

mod query;

use super::{Executor, Submitted, Task, TaskState, command_output};
use crate::error::{CampaignError, Result};
use crate::spec::{ExecutorSpec, SlurmSpec, find_program};
use crate::state::Point;
use crate::task::{TASK_SCRIPT, quote};
use std::path::Path;
use std::time::Duration;

/// Slurm's default `MaxArraySize`.
pub const DEFAULT_MAX_ARRAY_SIZE: usize = 1001;
/// Tasks of a campaign queued or running at once unless `max_queued` says.
pub const DEFAULT_MAX_QUEUED: usize = 10_000;

/// Job arrays on a Slurm cluster.
#[derive(Debug)]
pub struct Slurm {
    spec: SlurmSpec,
    time: Option<String>,
    name: String,
    poll: Duration,
    /// The cluster's `MaxArraySize`.
    max_array: usize,
    /// Tasks queued or running at once.
    max_queued: usize,
}

impl Slurm {
    /// An executor for campaign `name` in folder `dir`; fails when
    /// `sbatch`, `squeue` or `scancel` is not on PATH. The job name is
    /// `bumpsim-NAME-ID`, ID from the folder's path, so that a restarted
    /// controller finds its campaign's tasks by name.
    pub fn new(executor: &ExecutorSpec, name: &str, dir: &Path) -> Result<Slurm> {
        check_programs()?;
        let id = crate::state::short_hash(dir.to_string_lossy().as_bytes());
        let config = query::config();
        let job_limit = config.max_job_count.map_or(usize::MAX, |n| (n / 2).max(1));
        Ok(Slurm {
            spec: executor.slurm.clone(),
            time: executor.slurm_time().cloned(),
            name: format!("bumpsim-{name}-{id}"),
            poll: Duration::from_secs_f64(executor.poll_seconds),
            max_array: config.max_array_size.unwrap_or(DEFAULT_MAX_ARRAY_SIZE),
            max_queued: executor
                .slurm
                .max_queued
                .unwrap_or(DEFAULT_MAX_QUEUED)
                .min(job_limit),
        })
    }

    /// The job script of the arrays: `$1` is the run of array index 0.
    pub fn script(&self, dir: &Path) -> String {
        let mut text = String::from(
            "#!/bin/sh\n# written by bumpsim campaign run: one array task per design point; \
             the point's run is $1 + SLURM_ARRAY_TASK_ID\n",
        );
        for module in &self.spec.modules {
            text += &format!("module load {module}\n");
        }
        for line in &self.spec.setup {
            text += &format!("{line}\n");
        }
        let task = quote(&dir.join(TASK_SCRIPT).to_string_lossy());
        let points = quote(&dir.join("points").to_string_lossy());
        text += &format!(
            "run=$(( $1 + SLURM_ARRAY_TASK_ID ))\nexec sh {task} {points}/$(printf %04d \"$run\")\n"
        );
        text
    }

    /// The job name of the array whose index 0 is run `offset`.
    fn job_name(&self, offset: usize) -> String {
        match offset {
            0 => self.name.clone(),
            _ => format!("{}+{offset}", self.name),
        }
    }

    /// The block of run `run`: its array's offset and its index there.
    pub fn place(&self, run: usize) -> (usize, usize) {
        let width = self.max_array.saturating_sub(1).max(1);
        let offset = (run - 1) / width * width;
        (offset, run - offset)
    }

    fn sbatch_args(
        &self,
        dir: &Path,
        script: &Path,
        offset: usize,
        indices: &[usize],
    ) -> Vec<String> {
        let mut array = format!("--array={}", ranges(indices));
        if let Some(k) = self.spec.max_concurrent {
            array += &format!("%{k}");
        }
        let log = dir.join("slurm").join("%A_%a.out");
        let mut args = vec![
            "--parsable".to_string(),
            format!("--job-name={}", self.job_name(offset)),
            array,
            format!("--output={}", log.display()),
            format!("--chdir={}", dir.display()),
        ];
        let s = &self.spec;
        let optional = [
            s.partition.as_ref().map(|v| format!("--partition={v}")),
            s.account.as_ref().map(|v| format!("--account={v}")),
            self.time.as_ref().map(|v| format!("--time={v}")),
            s.cpus_per_task.map(|v| format!("--cpus-per-task={v}")),
            s.mem.as_ref().map(|v| format!("--mem={v}")),
        ];
        args.extend(optional.into_iter().flatten());
        args.extend(s.options.iter().cloned());
        args.push(script.display().to_string());
        args.push(offset.to_string());
        args
    }

    /// Submits one array: runs `runs` (one block) → their job ids.
    fn array(&self, dir: &Path, script: &Path, runs: &[usize]) -> Result<Vec<String>> {
        let offset = self.place(runs[0]).0;
        let indices: Vec<usize> = runs.iter().map(|r| r - offset).collect();
        let out = command_output("sbatch", &self.sbatch_args(dir, script, offset, &indices))?;
        let job = out.trim().split(';').next().unwrap_or("").trim();
        if job.is_empty() || !job.chars().all(|c| c.is_ascii_digit()) {
            return Err(CampaignError::Scheduler {
                command: "sbatch --parsable".into(),
                message: format!("unexpected answer '{}'", out.trim()),
            });
        }
        Ok(indices.iter().map(|i| format!("slurm:{job}_{i}")).collect())
    }
}

/// Sorted numbers as Slurm's array list with ranges (`1-8,10,12-13`).
///
/// ```
/// assert_eq!(bumpsim_campaign::executor::slurm::ranges(&[1, 2, 3, 5]), "1-3,5");
/// ```
pub fn ranges(runs: &[usize]) -> String {
    let mut parts: Vec<String> = Vec::new();
    let mut i = 0;
    while i < runs.len() {
        let mut j = i;
        while j + 1 < runs.len() && runs[j + 1] == runs[j] + 1 {
            j += 1;
        }
        parts.push(match j > i {
            true => format!("{}-{}", runs[i], runs[j]),
            false => runs[i].to_string(),
        });
        i = j + 1;
    }
    parts.join(",")
}

/// Checks that `sbatch`, `squeue` and `scancel` are on PATH.
pub fn check_programs() -> Result<()> {
    for program in ["sbatch", "squeue", "scancel"] {
        if find_program(program, Path::new(".")).is_none() {
            return Err(CampaignError::Program {
                what: "executor = \"slurm\" needs".into(),
                program: program.into(),
                hint: "run on a Slurm login node, load the Slurm module, or use --executor local"
                    .into(),
            });
        }
    }
    Ok(())
}

/// The least time `abort` waits for cancelled tasks to end (the floor of
/// `query::Config::cancel_wait`). `scancel` returns before Slurm has
/// stopped them: their node signals them, and kills them `KillWait` (30 s
/// by default) later, while squeue shows them COMPLETING. `abort` waits the
/// longer of this and the cluster's `KillWait + UnkillableStepTimeout`
/// (`scontrol show config`) plus 30 s.
pub const CANCEL_WAIT: Duration = Duration::from_secs(120);

/// Waits until no task of `points` is queued or running any more (squeue),
/// so a point marked pending is not still being solved; an error naming
/// them after `limit`.
fn wait_ended(points: &[&Point], limit: Duration) -> Result<()> {
    let mut jobs: Vec<&str> = points.iter().filter_map(|p| job_of(p)).collect();
    jobs.sort_unstable();
    jobs.dedup();
    let start = std::time::Instant::now();
    loop {
        let queue = query::squeue(&jobs)?;
        let live: Vec<&str> = (points.iter().map(|p| task_of(p)))
            .filter(|id| {
                queue.get(*id).is_some_and(|row| {
                    let state = query::task_state(&row.state, &row.reason);
                    matches!(state, TaskState::Queued | TaskState::Running)
                })
            })
            .collect();
        if live.is_empty() {
            return Ok(());
        }
        if start.elapsed() >= limit {
            return Err(CampaignError::Scheduler {
                command: "scancel".into(),
                message: format!(
                    "{} still queued or running {} s after the cancel; their points stay in flight: run `campaign abort` again once Slurm has stopped them",
                    live.join(", "),
                    limit.as_secs()
                ),
            });
        }
        std::thread::sleep(Duration::from_millis(200));
    }
}

/// The array job id of `slurm:JOB_INDEX`.
fn job_of(point: &Point) -> Option<&str> {
    point.job.strip_prefix("slurm:")?.split('_').next()
}

/// The task id (`JOB_INDEX`) of a point's job.
fn task_of(point: &Point) -> &str {
    point.job.trim_start_matches("slurm:")
}

impl Executor for Slurm {
    fn name(&self) -> &'static str {
        "slurm"
    }

    fn free(&self, in_flight: usize) -> usize {
        self.max_queued.saturating_sub(in_flight)
    }

    fn submit(&mut self, dir: &Path, points: &[&Point]) -> Submitted {
        let mut jobs = Vec::new();
        if points.is_empty() {
            return Submitted { jobs, error: None };
        }
        if self.max_array < 2 {
            let error = Some(CampaignError::Scheduler {
                command: "scontrol show config".into(),
                message: format!(
                    "MaxArraySize = {}: the cluster allows no job arrays of 2 tasks",
                    self.max_array
                ),
            });
            return Submitted { jobs, error };
        }
        let script = dir.join("slurm").join("array.sh");
        if let Err(e) = bumpsim_io::output::write_atomic(&script, self.script(dir).as_bytes()) {
            return Submitted {
                jobs,
                error: Some(e.into()),
            };
        }
        let runs: Vec<usize> = points.iter().map(|p| p.run).collect();
        for block in runs.chunk_by(|a, b| self.place(*a).0 == self.place(*b).0) {
            match self.array(dir, &script, block) {
                Ok(ids) => jobs.extend(ids),
                Err(e) => {
                    return Submitted {
                        jobs,
                        error: Some(e),
                    };
                }
            }
        }
        Submitted { jobs, error: None }
    }

    fn poll(&mut self, _dir: &Path, points: &[&Point]) -> Result<Vec<Task>> {
        let mut jobs: Vec<&str> = points.iter().filter_map(|p| job_of(p)).collect();
        jobs.sort_unstable();
        jobs.dedup();
        let queue = query::squeue(&jobs)?;
        // purged from squeue (MinJobAge), or requeued: ask the accounting
        let history: Vec<&str> = points
            .iter()
            .filter(|p| {
                queue
                    .get(task_of(p))
                    .is_none_or(|row| row.restarts > p.requeues)
            })
            .filter_map(|p| job_of(p))
            .collect();
        let accounting = query::sacct(&history);
        Ok(points
            .iter()
            .map(|p| query::task(task_of(p), &queue, accounting.as_ref()))
            .collect())
    }

    fn adopt(&mut self, _dir: &Path, points: &[&Point]) -> Result<Vec<Option<String>>> {
        let mut offsets: Vec<usize> = points.iter().map(|p| self.place(p.run).0).collect();
        offsets.sort_unstable();
        offsets.dedup();
        let names: Vec<String> = offsets.iter().map(|&o| self.job_name(o)).collect();
        let tasks = query::named(&names)?;
        Ok(points
            .iter()
            .map(|p| {
                let (offset, index) = self.place(p.run);
                let name = self.job_name(offset);
                // the newest task of this point (job ids increase)
                tasks
                    .iter()
                    .filter(|t| t.name == name && t.index == index)
                    .max_by_key(|t| t.job)
                    .map(|t| format!("slurm:{}_{index}", t.job))
            })
            .collect())
    }

    fn cancel(&mut self, points: &[&Point]) -> Result<()> {
        let ids: Vec<String> = points.iter().map(|p| task_of(p).to_string()).collect();
        if ids.is_empty() {
            return Ok(());
        }
        command_output("scancel", &ids)?;
        wait_ended(points, query::config().cancel_wait(CANCEL_WAIT))
    }

    fn interval(&self, _idle: u32) -> Duration {
        self.poll
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn slurm(max_array: usize) -> Slurm {
        let spec = SlurmSpec {
            partition: Some("short".into()),
            account: Some("bumper".into()),
            time: Some("02:00:00".into()),
            cpus_per_task: Some(8),
            mem: Some("16G".into()),
            max_concurrent: Some(4),
            max_queued: None,
            modules: vec!["calculix/2.21".into()],
            setup: vec!["export OMP_NUM_THREADS=8".into()],
            options: vec!["--qos=normal".into()],
        };
        Slurm {
            time: spec.time.clone(),
            spec,
            name: "c".into(),
            poll: Duration::from_secs(1),
            max_array,
            max_queued: DEFAULT_MAX_QUEUED,
        }
    }

    #[test]
    fn array_lists_use_ranges() {
        assert_eq!(ranges(&[1, 2, 3, 5, 7, 8]), "1-3,5,7-8");
        assert_eq!(ranges(&[4]), "4");
        assert_eq!(ranges(&(1..=1000).collect::<Vec<_>>()), "1-1000");
    }

    #[test]
    fn runs_are_cut_into_blocks_below_max_array_size() {
        let s = slurm(10);
        assert_eq!(s.place(1), (0, 1));
        assert_eq!(s.place(9), (0, 9));
        assert_eq!(s.place(10), (9, 1));
        assert_eq!(s.place(21), (18, 3));
        assert_eq!((s.job_name(0), s.job_name(18)), ("c".into(), "c+18".into()));
        // the default leaves runs 1..=1000 their own index, as before
        assert_eq!(slurm(DEFAULT_MAX_ARRAY_SIZE).place(1000), (0, 1000));
        assert_eq!(slurm(DEFAULT_MAX_ARRAY_SIZE).place(1001), (1000, 1));
    }

    #[test]
    fn the_array_carries_resources_limit_and_offset() {
        let s = slurm(DEFAULT_MAX_ARRAY_SIZE);
        let args = s
            .sbatch_args(
                Path::new("/c"),
                Path::new("/c/slurm/array.sh"),
                0,
                &[1, 3, 4],
            )
            .join(" ");
        for piece in [
            "--array=1,3-4%4",
            "--partition=short",
            "--account=bumper",
            "--time=02:00:00",
            "--cpus-per-task=8",
            "--mem=16G",
            "--qos=normal",
            "/c/slurm/array.sh 0",
        ] {
            assert!(args.contains(piece), "{piece} in {args}");
        }
        let script = s.script(Path::new("/c"));
        assert!(
            script.contains("module load calculix/2.21\nexport OMP_NUM_THREADS=8\n"),
            "{script}"
        );
        assert!(
            script.contains("run=$(( $1 + SLURM_ARRAY_TASK_ID ))\nexec sh '/c/run-point.sh' '/c/points'/$(printf %04d \"$run\")"),
            "{script}"
        );
    }
}
