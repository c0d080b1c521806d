//! `campaign status`: the points per status, the controller (running, or a
//! stale lock), the tasks in flight, and failed or retried points with
//! their reasons; as text, or as a JSON document (`--json`) with every
//! point's record (the state journal's fields, docs/campaign.md).

use crate::error::Result;
use crate::lock::lock_holder;
use crate::state::{Point, State, Status};
use serde::Serialize;
use std::fmt::Write as _;
use std::path::Path;

/// The status of a campaign.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CampaignStatus {
    /// The campaign's name.
    pub campaign: String,
    /// Points of the design.
    pub points: usize,
    /// Points per status.
    pub counts: Counts,
    /// The state's last change, UTC.
    pub updated: String,
    /// The controller holding the lock, if any.
    pub controller: Option<Controller>,
    /// Every point's record, in run order.
    pub runs: Vec<Point>,
}

/// Points per status.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Counts {
    /// Not submitted yet, or to be retried.
    pub pending: usize,
    /// Queued.
    pub submitted: usize,
    /// Running.
    pub running: usize,
    /// Done.
    pub done: usize,
    /// Failed for good.
    pub failed: usize,
}

/// The holder of a campaign's lock.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Controller {
    /// `pid N on HOST since T`.
    pub holder: String,
    /// Whether it still runs (false: a stale lock of a controller that is gone).
    pub running: bool,
}

/// The status of campaign folder `dir`.
pub fn status(dir: &Path) -> Result<CampaignStatus> {
    let state = State::read(dir)?;
    let [pending, submitted, running, done, failed] = state.counts();
    Ok(CampaignStatus {
        campaign: state.campaign,
        points: state.points.len(),
        counts: Counts {
            pending,
            submitted,
            running,
            done,
            failed,
        },
        updated: state.updated,
        controller: lock_holder(dir).map(|(holder, gone)| Controller {
            holder,
            running: !gone,
        }),
        runs: state.points,
    })
}

impl CampaignStatus {
    /// The status as text: counts, controller, in-flight tasks, failures.
    pub fn text(&self) -> String {
        let c = &self.counts;
        let mut text = format!(
            "campaign '{}': {} points: {} done, {} failed, {} running, {} submitted, {} pending (state of {})\n",
            self.campaign,
            self.points,
            c.done,
            c.failed,
            c.running,
            c.submitted,
            c.pending,
            self.updated
        );
        let _ = match &self.controller {
            Some(c) if c.running => writeln!(text, "  controller: {}", c.holder),
            Some(c) => writeln!(
                text,
                "  controller: none running (stale lock of {})",
                c.holder
            ),
            None => writeln!(text, "  controller: none running"),
        };
        for p in self.runs.iter().filter(|p| p.status.in_flight()) {
            let _ = writeln!(
                text,
                "  run {}: {} as {} since {} (attempt {})",
                p.run,
                p.status.name(),
                p.job,
                p.submitted,
                p.attempts
            );
        }
        let noted = |p: &&Point| {
            p.status == Status::Failed || (p.status != Status::Done && !p.reason.is_empty())
        };
        for p in self.runs.iter().filter(noted) {
            let _ = writeln!(text, "  run {}: {}: {}", p.run, p.status.name(), p.reason);
        }
        text
    }
}
