//! The pickled states of a campaign's status and collection (bumpsim-campaign).

use bumpsim_campaign::state::{Point, point_folder};
use bumpsim_campaign::status::{CampaignStatus, Controller, Counts};
use serde::{Deserialize, Serialize};

/// What a `CampaignStatus` holds.
#[derive(Serialize, Deserialize, PartialEq)]
pub struct StatusState(#[serde(with = "CampaignStatusDef")] pub CampaignStatus);

/// What a `Collected` holds: the library's summary and the table it wrote.
#[derive(Serialize, Deserialize, PartialEq, Clone)]
pub struct CollectedState {
    /// Rows in the table.
    pub rows: usize,
    /// Points left out, with why.
    pub missing: Vec<(usize, String)>,
    /// The regression's summary text.
    pub fit_text: String,
    /// The `doe fit` command equal to the regression.
    pub fit_command: String,
    /// `results/table.csv` as written.
    pub table: String,
}

#[derive(Serialize, Deserialize)]
#[serde(remote = "Counts")]
struct CountsDef {
    pending: usize,
    submitted: usize,
    running: usize,
    done: usize,
    failed: usize,
}

#[derive(Serialize, Deserialize)]
#[serde(remote = "Controller")]
struct ControllerDef {
    holder: String,
    running: bool,
}

super::remote_option!(controller, Controller, "ControllerDef");

/// Points through their own serde, each with its journal line (which
/// their serde does not store); the folder (not stored) follows from the run.
mod runs {
    use super::*;
    pub fn serialize<S: serde::Serializer>(runs: &[Point], s: S) -> Result<S::Ok, S::Error> {
        s.collect_seq(runs.iter().map(|p| (p, p.line)))
    }
    pub fn deserialize<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Vec<Point>, D::Error> {
        let runs = Vec::<(Point, usize)>::deserialize(d)?;
        let restore = |(mut p, line): (Point, usize)| {
            p.folder = point_folder(p.run);
            p.line = line;
            p
        };
        Ok(runs.into_iter().map(restore).collect())
    }
}

#[derive(Serialize, Deserialize)]
#[serde(remote = "CampaignStatus")]
struct CampaignStatusDef {
    campaign: String,
    points: usize,
    #[serde(with = "CountsDef")]
    counts: Counts,
    updated: String,
    #[serde(with = "controller")]
    controller: Option<Controller>,
    #[serde(with = "runs")]
    runs: Vec<Point>,
}
