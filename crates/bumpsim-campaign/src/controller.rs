//! The controller loop of `campaign run`: learn the outcome of every
//! in-flight task (its exit marker first, then the executor), read a
//! finished point's responses, count Slurm's requeues, retry failures up to
//! the limit, submit what is pending while the executor has room, and
//! append every change to the state journal — synced before a task is
//! started, so a killed controller never loses a task it started.
//!
//! The cost per point is constant, whatever the campaign's size: the
//! pending and in-flight points are kept as ordered sets and the counts
//! per status as they change, so a poll touches the points in flight only,
//! and the journal takes one record per change ([`crate::state`]).

use crate::error::{CampaignError, Result};
use crate::executor::{Executor, Task, TaskState};
use crate::readers;
use crate::spec::Spec;
use crate::state::{Journal, Point, State, Status, now};
use crate::task::{EXIT_MARKER, Marker, exit_reason, marker};
use std::collections::BTreeSet;
use std::path::Path;
use std::time::{Duration, Instant};

/// How long the scheduler's status queries may keep failing (a slurmctld
/// restart, a timeout) before the controller gives up; the state stays
/// consistent and a later `run` resumes.
pub const MAX_SCHEDULER_OUTAGE: Duration = Duration::from_secs(300);

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

/// The controller of one run.
pub(crate) struct Controller<'a> {
    dir: &'a Path,
    spec: &'a Spec,
    state: State,
    journal: Journal,
    executor: &'a mut dyn Executor,
    submitted: usize,
    /// Since when status queries have been failing.
    outage: Option<Instant>,
    pending: BTreeSet<usize>,
    flying: BTreeSet<usize>,
    counts: [usize; 5],
    /// Points changed since the last journal record.
    changed: Vec<usize>,
}

impl<'a> Controller<'a> {
    /// A controller of `state` (read from `journal`).
    pub(crate) fn new(
        dir: &'a Path,
        spec: &'a Spec,
        state: State,
        journal: Journal,
        executor: &'a mut dyn Executor,
    ) -> Self {
        let with = |s: Status| -> BTreeSet<usize> {
            (0..state.points.len())
                .filter(|&i| state.points[i].status == s)
                .collect()
        };
        let mut flying = with(Status::Submitted);
        flying.extend(with(Status::Running));
        Controller {
            dir,
            spec,
            pending: with(Status::Pending),
            flying,
            counts: state.counts(),
            state,
            journal,
            executor,
            submitted: 0,
            outage: None,
            changed: Vec::new(),
        }
    }

    /// Runs until every point is done or failed.
    pub(crate) fn drive(mut self, progress: bool) -> Result<RunSummary> {
        let bar = progress_bar(progress, self.state.points.len());
        let mut idle = 0;
        while !(self.pending.is_empty() && self.flying.is_empty()) {
            self.reconcile_tolerant()?;
            // a failed submission is not retried here: sbatch errors are
            // mostly settings (partition, account, limits) to fix first
            let started = self.submitted;
            self.submit()?;
            idle = match self.changed.is_empty() {
                true => idle + 1,
                false => 0,
            };
            // one sync per round: a submission has synced this round's
            // outcomes before its tasks started; the job ids it got follow
            // with the next round's (lost, they are found again by adopt)
            if self.submitted == started {
                self.flush()?;
            }
            let [_, submitted, running, done, failed] = self.counts;
            bar.set_position((done + failed) as u64);
            bar.set_message(format!(
                "{running} running, {submitted} queued, {failed} failed"
            ));
            if !self.flying.is_empty() {
                std::thread::sleep(self.executor.interval(idle));
            }
        }
        bar.finish_and_clear();
        // a clean snapshot for readers (and a short journal for the next run)
        self.journal.compact(&mut self.state)?;
        Ok(self.summary())
    }

    fn summary(&self) -> RunSummary {
        let points = &self.state.points;
        RunSummary {
            done: self.counts[Status::Done as usize],
            failed: points
                .iter()
                .filter(|p| p.status == Status::Failed)
                .map(|p| (p.run, p.reason.clone()))
                .collect(),
            submitted: self.submitted,
        }
    }

    /// Moves point `i` to `status`, keeping the sets and counts.
    fn set(&mut self, i: usize, status: Status) {
        let old = self.state.points[i].status;
        self.counts[old as usize] -= 1;
        self.counts[status as usize] += 1;
        self.state.points[i].status = status;
        match old {
            Status::Pending => self.pending.remove(&i),
            s if s.in_flight() && !status.in_flight() => {
                self.executor.release(&self.state.points[i]);
                self.flying.remove(&i)
            }
            s if s.in_flight() => self.flying.remove(&i),
            _ => false,
        };
        match status {
            Status::Pending => self.pending.insert(i),
            s if s.in_flight() => self.flying.insert(i),
            _ => false,
        };
        self.changed.push(i);
    }

    /// Appends the changed points to the journal (synced).
    fn flush(&mut self) -> Result<()> {
        self.changed.sort_unstable();
        self.changed.dedup();
        let changed = std::mem::take(&mut self.changed);
        self.journal.record(&mut self.state, &changed)
    }

    /// [`Self::reconcile`], riding out scheduler query failures for up to
    /// [`MAX_SCHEDULER_OUTAGE`].
    fn reconcile_tolerant(&mut self) -> Result<()> {
        match self.reconcile() {
            Ok(()) => {
                self.outage = None;
                Ok(())
            }
            Err(CampaignError::Scheduler { .. })
                if self.outage.get_or_insert_with(Instant::now).elapsed()
                    < MAX_SCHEDULER_OUTAGE =>
            {
                Ok(())
            }
            Err(e) => Err(e),
        }
    }

    /// Learns the outcome of every in-flight point: a success recorded by
    /// its marker at once, anything else (no marker, a failure, a restart
    /// not yet counted) as the executor sees it.
    fn reconcile(&mut self) -> Result<()> {
        let mut ask = Vec::new();
        for i in self.flying.iter().copied().collect::<Vec<_>>() {
            let point = &self.state.points[i];
            match marker(self.dir, point) {
                Some(m) if m.code == 0 && m.restarts <= point.requeues => self.ended(i, 0),
                m => ask.push((i, m)),
            }
        }
        if ask.is_empty() {
            return Ok(());
        }
        let points: Vec<&Point> = ask.iter().map(|&(i, _)| &self.state.points[i]).collect();
        let tasks = self.executor.poll(self.dir, &points)?;
        for ((i, m), task) in ask.into_iter().zip(tasks) {
            self.task(i, m, task);
        }
        Ok(())
    }

    /// Point `i`'s task as the executor sees it, with the marker it may have left.
    fn task(&mut self, i: usize, seen: Option<Marker>, task: Task) {
        let restarts = task.requeues.max(seen.map_or(0, |m| m.restarts));
        if restarts > self.state.points[i].requeues {
            self.requeued(i, restarts, &task.requeue_reason);
        }
        let status = self.state.points[i].status;
        match (seen.map(|m| m.code), task.state) {
            (Some(0), _) => self.ended(i, 0),
            // requeued (the marker, if any, is its killed run's)
            (_, TaskState::Queued) if status == Status::Running => self.set(i, Status::Submitted),
            (_, TaskState::Queued) => {}
            (_, TaskState::Running) if status != Status::Running => self.set(i, Status::Running),
            (_, TaskState::Running) => {}
            // the marker may have landed between the two looks
            (_, TaskState::Gone(reason)) => match marker(self.dir, &self.state.points[i]) {
                Some(m) => self.ended(i, m.code),
                None => self.failure(i, reason),
            },
            (_, TaskState::Killed(reason)) => match marker(self.dir, &self.state.points[i]) {
                Some(m) if m.code == 0 => self.ended(i, 0),
                _ => self.failure(i, reason),
            },
        }
    }

    /// Slurm requeued point `i`'s task (`restarts` times in all): each
    /// requeue is an attempt, recorded with its cause.
    fn requeued(&mut self, i: usize, restarts: u32, cause: &str) {
        let limit = 1 + self.spec.executor.retries;
        let point = &mut self.state.points[i];
        let new = restarts.saturating_sub(point.requeues);
        point.attempts = point.attempts.saturating_add(new);
        point.requeues = restarts;
        let cause = match cause.is_empty() {
            true => format!("restart {restarts} in the task's exit marker"),
            false => cause.to_string(),
        };
        point.reason = format!(
            "attempt {} of {limit}: requeued by Slurm: {cause}",
            point.attempts
        );
        self.changed.push(i);
    }

    /// A task that recorded exit status `code`.
    fn ended(&mut self, i: usize, code: i32) {
        if code != 0 {
            let folder = self.state.points[i].folder.clone();
            let reason = format!("{} (see {folder}/solver.log)", exit_reason(code));
            return self.failure(i, reason);
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
        self.state.points[i].finished = now();
        match read {
            // a retried point keeps the reason of its last failed attempt
            Ok(()) => self.set(i, Status::Done),
            // corrupt or missing output: failed, never read as zeros; a
            // deterministic solver would write it again, so no retry
            Err(e) => {
                self.state.points[i].reason = format!("output: {e}");
                self.set(i, Status::Failed);
            }
        }
    }

    /// A failed attempt: retried while attempts remain, else failed.
    fn failure(&mut self, i: usize, reason: String) {
        let limit = 1 + self.spec.executor.retries;
        let point = &mut self.state.points[i];
        let attempts = point.attempts;
        if attempts < limit {
            point.reason = format!("attempt {attempts} of {limit}: {reason}; retried");
            self.set(i, Status::Pending);
        } else {
            point.finished = now();
            point.reason = format!("attempt {attempts} of {limit}: {reason}");
            self.set(i, Status::Failed);
        }
    }

    /// Submits pending points while the executor has room; the submission
    /// is recorded (and synced) before the tasks start, so a controller
    /// killed between the two finds them submitted and adopts their tasks.
    fn submit(&mut self) -> Result<()> {
        let room = self.executor.free(self.flying.len());
        let chosen: Vec<usize> = self.pending.iter().take(room).copied().collect();
        if chosen.is_empty() {
            return Ok(());
        }
        let time = now();
        for &i in &chosen {
            let p = &mut self.state.points[i];
            let _ = std::fs::remove_file(self.dir.join(&p.folder).join(EXIT_MARKER));
            p.attempts = p.attempts.saturating_add(1);
            p.job.clear();
            p.submitted = time.clone();
            self.set(i, Status::Submitted);
        }
        self.flush()?;
        let points: Vec<&Point> = chosen.iter().map(|&i| &self.state.points[i]).collect();
        let outcome = self.executor.submit(self.dir, &points);
        for (&i, job) in chosen.iter().zip(&outcome.jobs) {
            self.state.points[i].job = job.clone();
            self.changed.push(i);
        }
        self.submitted += outcome.jobs.len();
        for &i in &chosen[outcome.jobs.len()..] {
            self.state.points[i].attempts -= 1;
            self.set(i, Status::Pending);
        }
        match outcome.error {
            Some(e) => {
                self.flush()?;
                Err(e)
            }
            None => Ok(()),
        }
    }
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
