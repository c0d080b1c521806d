//! `campaign repair`: a new state built from what the point folders show,
//! for a state journal that is damaged, truncated, or of an earlier
//! bumpsim. The folders are the ground truth (the tasks write their exit
//! markers and outputs there); the old journal's readable records add what
//! the folders cannot tell (attempts, job ids, reasons). Per point:
//!
//! - exit 0 in its marker, outputs readable, inputs unchanged since: done,
//!   kept (never run again); outputs unreadable: failed, as a run decides;
//! - a task of it still queued or running (local processes by their
//!   command line, Slurm's by the campaign's job names): adopted;
//! - a failed exit or a task that started and vanished: pending again
//!   (re-queued), its attempts kept; a point the old state had failed for
//!   good stays failed;
//! - never started: pending;
//! - a task Slurm could not be asked about: left submitted (undecided) for
//!   the next `run`, which asks again and retries it if it is gone.
//!
//! The damaged journal is kept beside the new one (`state.journal.damaged-TIME`).

use crate::error::Result;
use crate::executor::Executor;
use crate::executor::local::Local;
use crate::executor::slurm::Slurm;
use crate::init::{self, SPEC_FILE, input_files};
use crate::lock::Lock;
use crate::readers;
use crate::run::{absolute, spec_of};
use crate::spec::Spec;
use crate::state::{LEGACY_STATE_FILE, Point, STATE_FILE, State, Status, input_hash, salvage};
use crate::task::{Marker, exit_reason, marker};
use std::collections::BTreeMap;
use std::path::Path;

/// What `repair` made of each point.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Repaired {
    /// Done points kept.
    pub kept: Vec<usize>,
    /// Points whose task still runs: run and job id.
    pub adopted: Vec<(usize, String)>,
    /// Points pending again: run and why.
    pub requeued: Vec<(usize, String)>,
    /// Points failed: run and why.
    pub failed: Vec<(usize, String)>,
    /// Points left submitted for the next run to ask Slurm: run and why.
    pub undecided: Vec<(usize, String)>,
    /// Points that never ran.
    pub pending: usize,
    /// Records read from the old state.
    pub salvaged: usize,
}

/// Rebuilds the state of campaign folder `dir` from its point folders.
pub fn repair(dir: &Path) -> Result<Repaired> {
    let dir = &absolute(dir)?;
    let spec = spec_of(dir)?;
    let _lock = Lock::acquire(dir)?;
    let (values, _) = init::points(&spec, &dir.join(SPEC_FILE))?;
    let old = salvage(dir);
    let mut report = Repaired {
        salvaged: old.len(),
        ..Repaired::default()
    };
    let mut points = Vec::with_capacity(values.len());
    let mut open = Vec::new();
    for run in 1..=values.len() {
        let (mut point, seen) = rebuild(dir, &spec, run, old.get(&run))?;
        if judge(dir, &spec, &mut point, seen, &mut report) {
            open.push((points.len(), seen));
        }
        points.push(point);
    }
    ask(dir, &spec, &old, &mut points, &open, &mut report);
    keep_damaged(dir);
    State::new(&spec.name, points).write(dir)?;
    Ok(report)
}

/// Point `run` with its current input hash and what the old state knew,
/// and the exit marker in its folder.
fn rebuild(
    dir: &Path,
    spec: &Spec,
    run: usize,
    old: Option<&Point>,
) -> Result<(Point, Option<Marker>)> {
    let folder = dir.join(crate::state::point_folder(run));
    let hash = input_hash(&folder, &input_files(spec), &spec.solver.command)?;
    let mut point = Point::new(run, hash.clone());
    if let Some(o) = old {
        point = o.clone();
        point.input_hash = hash;
    }
    let seen = marker(dir, &point);
    Ok((point, seen))
}

/// Decides a point from its marker where it can (done, failed, or inputs
/// changed since); `true` when the executors must be asked about it.
fn judge(
    dir: &Path,
    spec: &Spec,
    p: &mut Point,
    seen: Option<Marker>,
    report: &mut Repaired,
) -> bool {
    if seen.map(|m| m.code) != Some(0) {
        return true;
    }
    let folder = dir.join(&p.folder);
    let read = spec
        .responses
        .iter()
        .try_for_each(|r| readers::read(&folder, r).map(|_| ()));
    match read {
        Err(e) => fail(p, format!("output: {e}"), report),
        Ok(()) if !result_of_inputs(&folder, spec) => {
            requeue(p, "the inputs are newer than the result".into(), report);
        }
        Ok(()) => {
            p.status = Status::Done;
            p.attempts = p.attempts.max(1);
            report.kept.push(p.run);
        }
    }
    false
}

/// Whether the exit marker is newer than every input file of the point.
fn result_of_inputs(folder: &Path, spec: &Spec) -> bool {
    let time = |name: &str| std::fs::metadata(folder.join(name)).and_then(|m| m.modified());
    let Ok(ended) = time(crate::task::EXIT_MARKER) else {
        return false;
    };
    input_files(spec)
        .iter()
        .all(|f| time(f).is_ok_and(|t| t <= ended))
}

/// Asks the executors about the open points (`(index, marker)`): a local
/// task still running, or a Slurm task under the campaign's job names.
fn ask(
    dir: &Path,
    spec: &Spec,
    old: &BTreeMap<usize, Point>,
    points: &mut [Point],
    open: &[(usize, Option<Marker>)],
    report: &mut Repaired,
) {
    let asked: Vec<&Point> = open.iter().map(|&(i, _)| &points[i]).collect();
    let local = Local::new(1, None).adopt(dir, &asked).unwrap_or_default();
    let slurm_used =
        spec.executor.kind == "slurm" || old.values().any(|p| p.job.starts_with("slurm:"));
    let slurm = match slurm_used {
        true => {
            Some(Slurm::new(&spec.executor, &spec.name, dir).and_then(|mut s| s.adopt(dir, &asked)))
        }
        false => None,
    };
    for (k, &(i, seen)) in open.iter().enumerate() {
        let found = local.get(k).cloned().flatten().or_else(|| match &slurm {
            Some(Ok(jobs)) => jobs.get(k).cloned().flatten(),
            _ => None,
        });
        let p = &mut points[i];
        // a queued task may exist where the old state does not say otherwise
        let maybe_queued = old.get(&p.run).is_none_or(|o| o.status.in_flight());
        match (found, &slurm) {
            (Some(job), _) => {
                p.status = Status::Submitted;
                p.attempts = p.attempts.max(1);
                p.job = job.clone();
                report.adopted.push((p.run, job));
            }
            (None, Some(Err(e))) if maybe_queued && seen.is_none_or(|m| m.code != 0) => {
                let why = format!("Slurm cannot be asked: {e}");
                p.status = Status::Submitted;
                p.attempts = p.attempts.max(1);
                p.reason = format!("repair: {why}");
                report.undecided.push((p.run, why));
            }
            (None, _) => lost(dir, p, seen, report),
        }
    }
}

/// A point with no task: its marker's failure, a task that vanished, or none.
fn lost(dir: &Path, p: &mut Point, seen: Option<Marker>, report: &mut Repaired) {
    let started = dir.join(&p.folder).join("solver.log").exists();
    match (seen, p.status) {
        (_, Status::Failed) => {
            let why = p.reason.clone();
            fail(p, why, report);
        }
        (Some(m), _) => requeue(
            p,
            format!("{} before the repair", exit_reason(m.code)),
            report,
        ),
        (None, _) if started || p.status.in_flight() => {
            requeue(
                p,
                "started, but left no exit status and no task".into(),
                report,
            );
        }
        (None, _) => {
            p.status = Status::Pending;
            report.pending += 1;
        }
    }
}

fn fail(p: &mut Point, why: String, report: &mut Repaired) {
    p.status = Status::Failed;
    p.reason = why.clone();
    report.failed.push((p.run, why));
}

fn requeue(p: &mut Point, why: String, report: &mut Repaired) {
    p.status = Status::Pending;
    p.attempts = p.attempts.max(1);
    p.reason = format!("repair: {why}; requeued");
    report.requeued.push((p.run, why));
}

/// Keeps the damaged journal (and a state of an earlier bumpsim) beside the new one.
fn keep_damaged(dir: &Path) {
    let stamp = crate::state::now().replace(':', "");
    for name in [STATE_FILE, LEGACY_STATE_FILE] {
        let path = dir.join(name);
        if path.exists() {
            let _ = std::fs::rename(&path, dir.join(format!("{name}.damaged-{stamp}")));
        }
    }
}
