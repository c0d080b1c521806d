//! `campaign run` and `campaign abort`. `run` takes the lock, checks the
//! solver (and the scheduler), opens the state journal, resets points whose
//! inputs changed, adopts tasks a killed controller started without
//! recording them, and hands over to the controller loop
//! ([`crate::controller`]). A restarted controller continues from the
//! journal: done points whose input hash still matches are never run
//! again; in-flight ones are adopted, not resubmitted.

pub use crate::controller::{MAX_SCHEDULER_OUTAGE, RunSummary};

use crate::controller::Controller;
use crate::error::{CampaignError, Result};
use crate::executor::Executor;
use crate::executor::local::Local;
use crate::executor::slurm::Slurm;
use crate::init::{SPEC_FILE, check_solver, input_files};
use crate::lock::Lock;
use crate::spec::Spec;
use crate::state::{Journal, Point, State, Status, input_hash};
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
            spec.executor.local_time(),
        ))),
        "slurm" => Ok(Box::new(Slurm::new(&spec.executor, &spec.name, dir)?)),
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
    let (mut state, mut journal) = Journal::open(dir)?;
    check_design(dir, &spec, &state)?;
    let mut changed = prepare(dir, &spec, &mut state, options.retry_failed)?;
    changed.extend(adopt(dir, &mut state, executor.as_mut())?);
    journal.record(&mut state, &changed)?;
    Controller::new(dir, &spec, state, journal, executor.as_mut()).drive(options.progress)
}

/// Refuses a state of another number of points than the design of the
/// campaign file (a journal of a smaller design would leave the points
/// beyond it never run, and the run end as if complete).
fn check_design(dir: &Path, spec: &Spec, state: &State) -> Result<()> {
    let (design, _) = crate::init::points(spec, &dir.join(SPEC_FILE))?;
    if design.len() == state.points.len() {
        return Ok(());
    }
    Err(CampaignError::Damaged {
        path: dir.join(crate::state::STATE_FILE),
        dir: dir.into(),
        problem: format!(
            "it holds {} points (header, line 1) where the design of {SPEC_FILE} has {} (the state of another design?)",
            state.points.len(),
            design.len()
        ),
    })
}

/// Resets points whose inputs changed since they ran (hash mismatch) and,
/// with `retry_failed`, failed points; returns the points changed.
fn prepare(dir: &Path, spec: &Spec, state: &mut State, retry_failed: bool) -> Result<Vec<usize>> {
    let files = input_files(spec);
    let mut changed = Vec::new();
    for (i, p) in state.points.iter_mut().enumerate() {
        let hash = input_hash(&dir.join(&p.folder), &files, &spec.solver.command)
            .map_err(|e| damaged_folder(dir, p, &e))?;
        if hash != p.input_hash && !p.status.in_flight() {
            p.status = Status::Pending;
            p.attempts = 0;
            p.reason = "inputs changed since the last run".into();
            p.input_hash = hash;
            changed.push(i);
        } else if retry_failed && p.status == Status::Failed {
            p.status = Status::Pending;
            p.attempts = 0;
            changed.push(i);
        }
    }
    Ok(changed)
}

/// A point folder whose inputs cannot be read, named by the state record
/// that points to it.
fn damaged_folder(dir: &Path, p: &Point, e: &CampaignError) -> CampaignError {
    let folder = dir.join(&p.folder);
    let problem = match e {
        CampaignError::Read { path, source } => {
            let name = path.strip_prefix(&folder).unwrap_or(path);
            format!("{}: {source}", name.display())
        }
        other => other.to_string(),
    };
    CampaignError::PointFolder {
        journal: dir.join(crate::state::STATE_FILE),
        line: p.line,
        run: p.run,
        folder,
        dir: dir.into(),
        problem,
    }
}

/// Finds the tasks of points that a killed controller submitted without
/// recording their job ids; returns the points changed.
fn adopt(dir: &Path, state: &mut State, executor: &mut dyn Executor) -> Result<Vec<usize>> {
    let orphans: Vec<usize> = (0..state.points.len())
        .filter(|&i| state.points[i].status.in_flight() && state.points[i].job.is_empty())
        .collect();
    if orphans.is_empty() {
        return Ok(orphans);
    }
    let points: Vec<&Point> = orphans.iter().map(|&i| &state.points[i]).collect();
    let jobs = executor.adopt(dir, &points)?;
    for (&i, job) in orphans.iter().zip(jobs) {
        // no task found: the poll reports it lost, and it is retried
        state.points[i].job = job.unwrap_or_default();
    }
    Ok(orphans)
}

/// The campaign folder as an absolute path (it must exist).
pub(crate) fn absolute(dir: &Path) -> Result<std::path::PathBuf> {
    dir.canonicalize()
        .map_err(|e| crate::error::read_error(dir, e))
}

/// Cancels every in-flight task of campaign folder `dir` and marks those
/// points pending again: Slurm tasks by `scancel`, waiting until Slurm has
/// stopped them (an error after the longer of `CANCEL_WAIT` and the
/// cluster's kill timeouts plus 30 s, their points left in
/// flight), local ones by SIGTERM (by each point's job id, whichever
/// executor submitted it). Stop the controller first (Ctrl-C): abort takes
/// the lock.
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The zombies among this process's children (ended, not reaped).
    fn zombies() -> usize {
        let me = std::process::id().to_string();
        let Ok(entries) = std::fs::read_dir("/proc") else {
            return 0;
        };
        entries
            .flatten()
            .filter_map(|e| std::fs::read_to_string(e.path().join("stat")).ok())
            .filter(|stat| {
                let rest: Vec<&str> = stat
                    .rsplit_once(')')
                    .map_or(vec![], |(_, r)| r.split_whitespace().collect());
                rest.first() == Some(&"Z") && rest.get(1) == Some(&me.as_str())
            })
            .count()
    }

    /// Every task process is reaped (a campaign of 100 000 points would
    /// otherwise run out of processes), and a run ends with a snapshot.
    #[test]
    fn a_run_leaves_no_zombie_and_a_compact_journal() {
        let dir = std::env::temp_dir().join(format!("bumpsim-run-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("deck.tmpl"), "k = {{k}}\n").unwrap();
        let spec = "name = \"z\"\n[design]\nkind = \"lhs\"\nruns = 60\nfactors = [{ name = \"k\", low = 1, high = 2 }]\n\
                    [template]\nfile = \"deck.tmpl\"\n[solver]\ncommand = [\"true\"]\n[executor]\nslots = 2\n";
        std::fs::write(dir.join("c.toml"), spec).unwrap();
        let c = dir.join("c");
        crate::init::init(&dir.join("c.toml"), &c).unwrap();
        let summary = run(&c, &RunOptions::default()).unwrap();
        assert_eq!((summary.done, summary.submitted), (60, 60));
        // Other tests of this binary spawn and wait for short commands at
        // the same time; their children are zombies for a moment until
        // waited. A leaked task stays a zombie for good, so wait out the
        // transient ones (up to 5 s) before counting.
        let settled = (0..50).any(|_| {
            let calm = zombies() <= 2;
            if !calm {
                std::thread::sleep(std::time::Duration::from_millis(100));
            }
            calm
        });
        assert!(settled, "{} zombies", zombies());
        let journal = std::fs::read_to_string(c.join(crate::state::STATE_FILE)).unwrap();
        assert_eq!(journal.lines().count(), 1 + 60);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
