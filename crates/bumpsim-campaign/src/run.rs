//! `campaign run`: the controller. Takes the lock, checks the solver (and
//! the scheduler), then loops: learn the outcome of every in-flight task
//! (exit marker first, then the executor), read a finished point's
//! responses, retry failures up to the limit, submit what is pending, and
//! write the state after every change. A restarted controller continues
//! from the state file: done points whose input hash still matches are
//! never run again; in-flight ones are adopted, not resubmitted.

use crate::error::{CampaignError, Result};
use crate::executor::local::Local;
use crate::executor::slurm::Slurm;
use crate::executor::{Executor, TaskState};
use crate::init::{EXIT_MARKER, SPEC_FILE, check_solver, input_files};
use crate::readers;
use crate::spec::Spec;
use crate::state::{Lock, Point, State, Status, input_hash, now};
use std::path::Path;

/// Options of a run (overriding the campaign file's executor settings).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct RunOptions {
    /// `local` or `slurm` (default: the campaign file's).
    pub executor: Option<String>,
    /// Local slots (default: the campaign file's).
    pub slots: Option<usize>,
    /// Give failed points a new set of attempts.
    pub retry_failed: bool,
    /// Show a progress bar (on a terminal).
    pub progress: bool,
}

/// What a run ended with.
#[derive(Debug, Clone, PartialEq)]
pub struct RunSummary {
    /// Points done.
    pub done: usize,
    /// Points failed, with their reasons.
    pub failed: Vec<(usize, String)>,
    /// Tasks submitted by this run.
    pub submitted: usize,
}

/// Reads the campaign file copied into campaign folder `dir`.
pub fn spec_of(dir: &Path) -> Result<Spec> {
    Spec::read(&dir.join(SPEC_FILE))
}

/// The executor the options and the campaign file ask for (checked: sbatch on PATH).
pub fn executor(spec: &Spec, dir: &Path, options: &RunOptions) -> Result<Box<dyn Executor>> {
    let kind = options.executor.as_deref().unwrap_or(&spec.executor.kind);
    match kind {
        "local" => Ok(Box::new(Local::new(
            options.slots.unwrap_or(spec.executor.slots),
        ))),
        "slurm" => Ok(Box::new(Slurm::new(
            &spec.executor.slurm,
            &spec.name,
            dir,
            spec.executor.poll_seconds,
        )?)),
        other => Err(CampaignError::Invalid {
            path: SPEC_FILE.into(),
            key: "executor".into(),
            message: format!("'{other}': expected local or slurm"),
        }),
    }
}

/// Runs campaign folder `dir` until every point is done or failed.
pub fn run(dir: &Path, options: &RunOptions) -> Result<RunSummary> {
    // absolute: job scripts run elsewhere (Slurm's --chdir, the task's own cd)
    let dir = &absolute(dir)?;
    let spec = spec_of(dir)?;
    check_solver(&spec, dir)?;
    let mut executor = executor(&spec, dir, options)?;
    let _lock = Lock::acquire(dir)?;
    let mut state = State::read(dir)?;
    let mut changed = prepare(dir, &spec, &mut state, options.retry_failed)?;
    changed |= adopt(dir, &mut state, executor.as_mut())?;
    if changed {
        state.write(dir)?;
    }
    Controller {
        dir,
        spec: &spec,
        state,
        executor: executor.as_mut(),
        submitted: 0,
        outage: None,
    }
    .drive(options.progress)
}

/// Resets points whose inputs changed since they ran (hash mismatch) and,
/// with `retry_failed`, failed points.
fn prepare(dir: &Path, spec: &Spec, state: &mut State, retry_failed: bool) -> Result<bool> {
    let files = input_files(spec);
    let mut changed = false;
    for p in &mut state.points {
        let hash = input_hash(&dir.join(&p.folder), &files, &spec.solver.command)?;
        if hash != p.input_hash && !p.status.in_flight() {
            p.status = Status::Pending;
            p.attempts = 0;
            p.reason = "inputs changed since the last run".into();
            p.input_hash = hash;
            changed = true;
        } else if retry_failed && p.status == Status::Failed {
            p.status = Status::Pending;
            p.attempts = 0;
            changed = true;
        }
    }
    Ok(changed)
}

/// Finds the tasks of points that a killed controller submitted without
/// recording their job ids.
fn adopt(dir: &Path, state: &mut State, executor: &mut dyn Executor) -> Result<bool> {
    let orphans: Vec<usize> = (0..state.points.len())
        .filter(|&i| state.points[i].status.in_flight() && state.points[i].job.is_empty())
        .collect();
    if orphans.is_empty() {
        return Ok(false);
    }
    let points: Vec<&Point> = orphans.iter().map(|&i| &state.points[i]).collect();
    let jobs = executor.adopt(dir, &points)?;
    for (&i, job) in orphans.iter().zip(jobs) {
        // no task found: the poll reports it lost, and it is retried
        state.points[i].job = job.unwrap_or_default();
    }
    Ok(true)
}

/// How long the scheduler's status queries may keep failing (a slurmctld
/// restart, a timeout) before the controller gives up; the state stays
/// consistent and a later `run` resumes.
pub const MAX_SCHEDULER_OUTAGE: std::time::Duration = std::time::Duration::from_secs(300);

struct Controller<'a> {
    dir: &'a Path,
    spec: &'a Spec,
    state: State,
    executor: &'a mut dyn Executor,
    submitted: usize,
    /// Since when status queries have been failing.
    outage: Option<std::time::Instant>,
}

impl Controller<'_> {
    fn drive(mut self, progress: bool) -> Result<RunSummary> {
        let bar = progress_bar(progress, self.state.points.len());
        loop {
            let mut changed = self.reconcile_tolerant()?;
            // a failed submission is not retried here: sbatch errors are
            // mostly settings (partition, account, limits) to fix first
            changed |= self.submit()?;
            if changed {
                self.state.write(self.dir)?;
            }
            let [pending, submitted, running, done, failed] = self.state.counts();
            bar.set_position((done + failed) as u64);
            bar.set_message(format!(
                "{running} running, {submitted} queued, {failed} failed"
            ));
            if pending + submitted + running == 0 {
                break;
            }
            std::thread::sleep(self.executor.interval());
        }
        bar.finish_and_clear();
        Ok(self.summary())
    }

    fn summary(&self) -> RunSummary {
        let points = &self.state.points;
        RunSummary {
            done: points.iter().filter(|p| p.status == Status::Done).count(),
            failed: points
                .iter()
                .filter(|p| p.status == Status::Failed)
                .map(|p| (p.run, p.reason.clone()))
                .collect(),
            submitted: self.submitted,
        }
    }

    /// [`Self::reconcile`], riding out scheduler query failures for up to
    /// [`MAX_SCHEDULER_OUTAGE`].
    fn reconcile_tolerant(&mut self) -> Result<bool> {
        match self.reconcile() {
            Ok(changed) => {
                self.outage = None;
                Ok(changed)
            }
            Err(CampaignError::Scheduler { .. })
                if self
                    .outage
                    .get_or_insert_with(std::time::Instant::now)
                    .elapsed()
                    < MAX_SCHEDULER_OUTAGE =>
            {
                Ok(false)
            }
            Err(e) => Err(e),
        }
    }

    /// Learns the outcome of every in-flight point.
    fn reconcile(&mut self) -> Result<bool> {
        let flying: Vec<usize> = (0..self.state.points.len())
            .filter(|&i| self.state.points[i].status.in_flight())
            .collect();
        let mut ask = Vec::new();
        let mut changed = false;
        for &i in &flying {
            match exit_marker(self.dir, &self.state.points[i]) {
                Some(code) => changed |= self.ended(i, code),
                None => ask.push(i),
            }
        }
        if ask.is_empty() {
            return Ok(changed);
        }
        let points: Vec<&Point> = ask.iter().map(|&i| &self.state.points[i]).collect();
        let states = self.executor.poll(self.dir, &points)?;
        for (&i, task) in ask.iter().zip(states) {
            changed |= self.task(i, task);
        }
        Ok(changed)
    }

    fn task(&mut self, i: usize, task: TaskState) -> bool {
        let point = &mut self.state.points[i];
        match task {
            TaskState::Queued => false,
            TaskState::Running if point.status == Status::Running => false,
            TaskState::Running => {
                point.status = Status::Running;
                true
            }
            // the marker may have landed between the two looks
            TaskState::Gone(reason) => match exit_marker(self.dir, point) {
                Some(code) => self.ended(i, code),
                None => self.failure(i, reason),
            },
        }
    }

    /// A task that recorded exit status `code`.
    fn ended(&mut self, i: usize, code: i32) -> bool {
        if code != 0 {
            let folder = self.state.points[i].folder.clone();
            return self.failure(
                i,
                format!("{} (see {folder}/solver.log)", exit_reason(code)),
            );
        }
        let folder = self.dir.join(&self.state.points[i].folder);
        let run = self.state.points[i].run;
        let read = self.spec.responses.iter().try_for_each(|r| {
            readers::read(&folder, r)
                .map(|_| ())
                .map_err(|source| CampaignError::Output {
                    run,
                    response: r.name.clone(),
                    source: Box::new(source),
                })
        });
        let point = &mut self.state.points[i];
        point.finished = now();
        match read {
            // a retried point keeps the reason of its last failed attempt
            Ok(()) => point.status = Status::Done,
            // corrupt or missing output: failed, never read as zeros; a
            // deterministic solver would write it again, so no retry
            Err(e) => {
                point.status = Status::Failed;
                point.reason = format!("output: {e}");
            }
        }
        true
    }

    /// A failed attempt: retried while attempts remain, else failed.
    fn failure(&mut self, i: usize, reason: String) -> bool {
        let limit = 1 + self.spec.executor.retries;
        let point = &mut self.state.points[i];
        if point.attempts < limit {
            point.status = Status::Pending;
            point.reason = format!("attempt {} of {limit}: {reason}; retried", point.attempts);
        } else {
            point.status = Status::Failed;
            point.finished = now();
            point.reason = format!("attempt {} of {limit}: {reason}", point.attempts);
        }
        true
    }

    /// Submits pending points while the executor has room.
    fn submit(&mut self) -> Result<bool> {
        let in_flight = self
            .state
            .points
            .iter()
            .filter(|p| p.status.in_flight())
            .count();
        let room = self.executor.free(in_flight);
        let chosen: Vec<usize> = (0..self.state.points.len())
            .filter(|&i| self.state.points[i].status == Status::Pending)
            .take(room)
            .collect();
        if chosen.is_empty() {
            return Ok(false);
        }
        // recorded before the tasks start: a controller killed between
        // the two finds them submitted and adopts their tasks on restart
        let time = now();
        for &i in &chosen {
            let p = &mut self.state.points[i];
            let _ = std::fs::remove_file(self.dir.join(&p.folder).join(EXIT_MARKER));
            p.status = Status::Submitted;
            p.attempts += 1;
            p.job.clear();
            p.submitted = time.clone();
        }
        self.state.write(self.dir)?;
        let points: Vec<&Point> = chosen.iter().map(|&i| &self.state.points[i]).collect();
        let jobs = match self.executor.submit(self.dir, &points) {
            Ok(jobs) => jobs,
            Err(e) => {
                for &i in &chosen {
                    self.state.points[i].status = Status::Pending;
                    self.state.points[i].attempts -= 1;
                }
                self.state.write(self.dir)?;
                return Err(e);
            }
        };
        for (&i, job) in chosen.iter().zip(jobs) {
            self.state.points[i].job = job;
        }
        self.submitted += chosen.len();
        Ok(true)
    }
}

/// The campaign folder as an absolute path (it must exist).
fn absolute(dir: &Path) -> Result<std::path::PathBuf> {
    dir.canonicalize()
        .map_err(|e| crate::error::read_error(dir, e))
}

/// Why a solver with exit status `code` failed; above 128 the shell's code
/// for a signal (SIGTERM is what scancel, time limits and pre-emption send).
pub fn exit_reason(code: i32) -> String {
    match code {
        143 => "solver killed by signal 15, SIGTERM (exit code 143: cancelled, timed out or pre-empted?)".into(),
        129..=192 => format!("solver killed by signal {} (exit code {code})", code - 128),
        _ => format!("solver exit code {code}"),
    }
}

/// The exit status a point's task recorded, if any.
pub fn exit_marker(dir: &Path, point: &Point) -> Option<i32> {
    let text = std::fs::read_to_string(dir.join(&point.folder).join(EXIT_MARKER)).ok()?;
    text.trim().strip_prefix("exit ")?.trim().parse().ok()
}

fn progress_bar(show: bool, total: usize) -> indicatif::ProgressBar {
    if !show {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new(total as u64);
    if let Ok(style) =
        indicatif::ProgressStyle::with_template("{bar:30} {pos}/{len} points ({elapsed}) {msg}")
    {
        bar.set_style(style);
    }
    bar
}

/// Cancels every in-flight task of campaign folder `dir` and marks those
/// points pending again: Slurm tasks by `scancel`, local ones by SIGTERM
/// (by each point's job id, whichever executor submitted it). Stop the
/// controller first (Ctrl-C): abort takes the lock.
pub fn abort(dir: &Path) -> Result<usize> {
    let dir = &absolute(dir)?;
    let spec = spec_of(dir)?;
    let _lock = Lock::acquire(dir)?;
    let mut state = State::read(dir)?;
    let flying = |prefix: &str| -> Vec<&Point> {
        let in_flight = state.points.iter().filter(|p| p.status.in_flight());
        in_flight.filter(|p| p.job.starts_with(prefix)).collect()
    };
    let slurm = flying("slurm:");
    if !slurm.is_empty() {
        let slurm_options = RunOptions {
            executor: Some("slurm".into()),
            ..RunOptions::default()
        };
        executor(&spec, dir, &slurm_options)?.cancel(&slurm)?;
    }
    for p in flying("local:") {
        crate::executor::local::terminate(p);
    }
    let mut n = 0;
    for p in state.points.iter_mut().filter(|p| p.status.in_flight()) {
        p.status = Status::Pending;
        p.reason = "cancelled by campaign abort".into();
        n += 1;
    }
    state.write(dir)?;
    Ok(n)
}
