//! The Slurm executor: each submission round is one job array,
//! `sbatch --parsable --array=RUNS%K slurm/array-N.sh`, whose task
//! `SLURM_ARRAY_TASK_ID` is the point's run number; job ids are
//! `slurm:JOB_RUN`. Per-task resources, partition, account, modules and
//! setup lines come from `[executor.slurm]`.
//!
//! Status: `squeue -r -t all` lists queued, running and recently ended
//! tasks (Slurm keeps ended jobs for `MinJobAge`, 300 s by default) with
//! their state and reason; a task that is gone from it without having
//! recorded an exit status is lost (cancelled, timed out, pre-empted, node
//! failure) and retried. A task purged from `squeue` is looked up with
//! `sacct` for its final state and reason where the cluster keeps
//! accounting; without accounting it is simply lost (and retried).

use super::{Executor, TaskState, command_output};
use crate::error::{CampaignError, Result};
use crate::init::{TASK_SCRIPT, quote};
use crate::spec::{SlurmSpec, find_program};
use crate::state::Point;
use std::collections::HashMap;
use std::path::Path;
use std::time::Duration;

/// Job arrays on a Slurm cluster.
#[derive(Debug)]
pub struct Slurm {
    spec: SlurmSpec,
    name: String,
    poll: Duration,
}

impl Slurm {
    /// An executor for campaign `name` in folder `dir`; fails when
    /// `sbatch`, `squeue` or `scancel` is not on PATH. The job name is
    /// `bumpsim-NAME-ID`, ID from the folder's path, so that a restarted
    /// controller finds its campaign's tasks by name.
    pub fn new(spec: &SlurmSpec, name: &str, dir: &Path, poll_seconds: f64) -> Result<Slurm> {
        check_programs()?;
        let id = crate::state::short_hash(dir.to_string_lossy().as_bytes());
        Ok(Slurm {
            spec: spec.clone(),
            name: format!("bumpsim-{name}-{id}"),
            poll: Duration::from_secs_f64(poll_seconds),
        })
    }

    /// The job script of one array.
    pub fn script(&self, dir: &Path) -> String {
        let mut text = String::from(
            "#!/bin/sh\n# written by bumpsim campaign run: one array task per design point\n",
        );
        for module in &self.spec.modules {
            text += &format!("module load {module}\n");
        }
        for line in &self.spec.setup {
            text += &format!("{line}\n");
        }
        let task = quote(&dir.join(TASK_SCRIPT).to_string_lossy());
        let points = quote(&dir.join("points").to_string_lossy());
        text += &format!("exec sh {task} {points}/$(printf %04d \"$SLURM_ARRAY_TASK_ID\")\n");
        text
    }

    fn sbatch_args(&self, dir: &Path, script: &Path, runs: &[usize]) -> Vec<String> {
        let mut array = format!("--array={}", ranges(runs));
        if let Some(k) = self.spec.max_concurrent {
            array += &format!("%{k}");
        }
        let log = dir.join("slurm").join("%A_%a.out");
        let mut args = vec![
            "--parsable".to_string(),
            format!("--job-name={}", self.name),
            array,
            format!("--output={}", log.display()),
            format!("--chdir={}", dir.display()),
        ];
        let s = &self.spec;
        let optional = [
            s.partition.as_ref().map(|v| format!("--partition={v}")),
            s.account.as_ref().map(|v| format!("--account={v}")),
            s.time.as_ref().map(|v| format!("--time={v}")),
            s.cpus_per_task.map(|v| format!("--cpus-per-task={v}")),
            s.mem.as_ref().map(|v| format!("--mem={v}")),
        ];
        args.extend(optional.into_iter().flatten());
        args.extend(s.options.iter().cloned());
        args.push(script.display().to_string());
        args
    }
}

/// Sorted run numbers as Slurm's array list with ranges (`1-8,10,12-13`).
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

/// The job id of `slurm:JOB_RUN`.
fn job_of(point: &Point) -> Option<&str> {
    point.job.strip_prefix("slurm:")?.split('_').next()
}

impl Executor for Slurm {
    fn name(&self) -> &'static str {
        "slurm"
    }

    fn free(&self, _in_flight: usize) -> usize {
        usize::MAX
    }

    fn submit(&mut self, dir: &Path, points: &[&Point]) -> Result<Vec<String>> {
        if points.is_empty() {
            return Ok(Vec::new());
        }
        let folder = dir.join("slurm");
        let round = std::fs::read_dir(&folder).map_or(0, |d| d.count()) + 1;
        let script = folder.join(format!("array-{round}.sh"));
        bumpsim_io::output::write_atomic(&script, self.script(dir).as_bytes())?;
        let runs: Vec<usize> = points.iter().map(|p| p.run).collect();
        let out = command_output("sbatch", &self.sbatch_args(dir, &script, &runs))?;
        let job = out
            .trim()
            .split(';')
            .next()
            .unwrap_or("")
            .trim()
            .to_string();
        if job.is_empty() || !job.chars().all(|c| c.is_ascii_digit()) {
            return Err(CampaignError::Scheduler {
                command: "sbatch --parsable".into(),
                message: format!("unexpected answer '{}'", out.trim()),
            });
        }
        Ok(runs.iter().map(|r| format!("slurm:{job}_{r}")).collect())
    }

    fn poll(&mut self, _dir: &Path, points: &[&Point]) -> Result<Vec<TaskState>> {
        let mut jobs: Vec<&str> = points.iter().filter_map(|p| job_of(p)).collect();
        jobs.sort_unstable();
        jobs.dedup();
        let mut known = squeue(&jobs)?;
        let id = |p: &Point| p.job.trim_start_matches("slurm:").to_string();
        let unknown: Vec<String> = points
            .iter()
            .map(|p| id(p))
            .filter(|i| !known.contains_key(i))
            .collect();
        if !unknown.is_empty() {
            // purged from squeue (MinJobAge): ask accounting, where there is one
            known.extend(sacct(&unknown));
        }
        Ok(points
            .iter()
            .map(|p| match known.get(&id(p)) {
                Some((state, reason)) => task_state(state, reason),
                None => TaskState::Gone(
                    "no longer known to Slurm (squeue, sacct) and no exit status recorded".into(),
                ),
            })
            .collect())
    }

    fn adopt(&mut self, _dir: &Path, points: &[&Point]) -> Result<Vec<Option<String>>> {
        let args = ["-h", "-r", "-t", "all", "-o", "%i", "--name"].map(String::from);
        let mut args = args.to_vec();
        args.push(self.name.clone());
        let out = command_output("squeue", &args)?;
        let tasks: Vec<&str> = out.lines().map(str::trim).collect();
        Ok(points
            .iter()
            .map(|p| {
                let suffix = format!("_{}", p.run);
                // the newest task of this point (job ids increase)
                tasks
                    .iter()
                    .filter(|t| t.ends_with(&suffix))
                    .max_by_key(|t| t.split('_').next().and_then(|j| j.parse::<u64>().ok()))
                    .map(|t| format!("slurm:{t}"))
            })
            .collect())
    }

    fn cancel(&mut self, points: &[&Point]) -> Result<()> {
        let ids: Vec<String> = points
            .iter()
            .map(|p| p.job.trim_start_matches("slurm:").to_string())
            .collect();
        if !ids.is_empty() {
            command_output("scancel", &ids)?;
        }
        Ok(())
    }

    fn interval(&self) -> Duration {
        self.poll
    }
}

/// Task id (`JOB_RUN`) → (state, reason) of the given jobs, ended ones included.
fn squeue(jobs: &[&str]) -> Result<HashMap<String, (String, String)>> {
    let mut known = HashMap::new();
    if jobs.is_empty() {
        return Ok(known);
    }
    let args = ["-h", "-r", "-t", "all", "-o", "%i|%T|%r", "-j"].map(String::from);
    let mut args = args.to_vec();
    args.push(jobs.join(","));
    let out = match command_output("squeue", &args) {
        Ok(out) => out,
        // every job purged already: squeue refuses the ids
        Err(CampaignError::Scheduler { message, .. }) if message.contains("Invalid job id") => {
            String::new()
        }
        Err(e) => return Err(e),
    };
    for line in out.lines() {
        let mut parts = line.trim().splitn(3, '|');
        if let (Some(id), Some(state), reason) = (parts.next(), parts.next(), parts.next()) {
            known.insert(
                id.to_string(),
                (state.to_string(), reason.unwrap_or("").to_string()),
            );
        }
    }
    Ok(known)
}

/// Task id → (state, reason) from `sacct` for tasks squeue no longer
/// lists; empty where accounting is disabled or fails.
fn sacct(tasks: &[String]) -> HashMap<String, (String, String)> {
    let args = ["-n", "-P", "-X", "-o", "JobID,State,Reason", "-j"].map(String::from);
    let mut args = args.to_vec();
    args.push(tasks.join(","));
    let Ok(out) = command_output("sacct", &args) else {
        return HashMap::new();
    };
    out.lines()
        .filter_map(|line| {
            let mut parts = line.trim().splitn(3, '|');
            let (id, state) = (parts.next()?, parts.next()?);
            // "CANCELLED by 0" → CANCELLED
            let state = state.split_whitespace().next()?.to_string();
            Some((
                id.to_string(),
                (state, parts.next().unwrap_or("").to_string()),
            ))
        })
        .collect()
}

/// A Slurm job state as a task state.
fn task_state(state: &str, reason: &str) -> TaskState {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn array_lists_use_ranges() {
        assert_eq!(ranges(&[1, 2, 3, 5, 7, 8]), "1-3,5,7-8");
        assert_eq!(ranges(&[4]), "4");
        assert_eq!(ranges(&(1..=1000).collect::<Vec<_>>()), "1-1000");
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
    fn the_array_carries_resources_and_limit() {
        let spec = SlurmSpec {
            partition: Some("short".into()),
            account: Some("bumper".into()),
            time: Some("02:00:00".into()),
            cpus_per_task: Some(8),
            mem: Some("16G".into()),
            max_concurrent: Some(4),
            modules: vec!["calculix/2.21".into()],
            setup: vec!["export OMP_NUM_THREADS=8".into()],
            options: vec!["--qos=normal".into()],
        };
        let s = Slurm {
            spec,
            name: "c".into(),
            poll: Duration::from_secs(1),
        };
        let args = s
            .sbatch_args(
                Path::new("/c"),
                Path::new("/c/slurm/array-1.sh"),
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
        ] {
            assert!(args.contains(piece), "{piece} in {args}");
        }
        let script = s.script(Path::new("/c"));
        assert!(
            script.contains("module load calculix/2.21\nexport OMP_NUM_THREADS=8\n"),
            "{script}"
        );
        assert!(
            script.contains("'/c/points'/$(printf %04d \"$SLURM_ARRAY_TASK_ID\")"),
            "{script}"
        );
    }
}
