//! Campaigns (bumpsim-campaign), the calls `bumpsim campaign init | run |
//! status | collect | abort | repair` make, on the same library code: a
//! `Campaign` is a handle on its folder; `status()` and `collect()` return
//! objects with the CLI's text, JSON and table (`results/table.csv`, the
//! very file the library wrote) and pandas frames. Errors of the run's
//! environment (another controller holds the lock, the scheduler failed,
//! nothing to collect yet) are `RunError`s; a solver not on PATH is a
//! `MissingFileError`, as `subprocess` makes it.

use crate::convert::{count_or, path};
use crate::errors::{Kind, file_or_input, raise};
use crate::frames;
use crate::state::campaign::{CollectedState, StatusState};
use crate::state::{decode, encode, reduce};
use bumpsim_campaign::CampaignError;
use bumpsim_campaign::run::RunOptions;
use bumpsim_campaign::{collect, init, repair, run, status};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList, PyTuple, PyType};
use std::path::PathBuf;

/// Local process slots at most, as the CLI's `--slots`.
const MAX_SLOTS: usize = 1024;

/// What `__reduce__` returns.
type Reduced<'py> = (Bound<'py, PyAny>, (Bound<'py, PyBytes>,));

/// Registers the classes of this module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Campaign>()?;
    m.add_class::<CampaignStatus>()?;
    m.add_class::<Collected>()?;
    Ok(())
}

/// The Python exception of a campaign error.
fn campaign_error(error: CampaignError) -> PyErr {
    let message = crate::errors::message(&error);
    match error {
        CampaignError::Locked { .. } | CampaignError::Scheduler { .. } => raise(Kind::Run, message),
        CampaignError::Collect(_) => raise(Kind::Run, message),
        CampaignError::Program { .. } => raise(Kind::Missing, message),
        other => file_or_input(other),
    }
}

/// A campaign folder (made by `Campaign.init` or `bumpsim campaign init`).
#[pyclass(frozen, module = "bumpsim")]
pub struct Campaign {
    folder: PathBuf,
}

#[pymethods]
impl Campaign {
    /// The campaign in `folder` (as `bumpsim campaign run|status|... DIR`).
    #[new]
    fn new(folder: &Bound<'_, PyAny>) -> PyResult<Self> {
        let folder = path(folder, "folder", "a campaign folder")?;
        Ok(Campaign { folder })
    }
    /// Makes the campaign folder of the campaign file `spec` (default
    /// folder: the file's name without `.toml`), as `bumpsim campaign
    /// init`: design, one folder per point with its deck, the state.
    /// Points done or running with unchanged inputs are kept.
    #[staticmethod]
    #[pyo3(signature = (spec, folder = None))]
    fn init(
        py: Python<'_>,
        spec: &Bound<'_, PyAny>,
        folder: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Campaign> {
        let spec = path(spec, "spec", "a campaign file")?;
        let folder = match folder {
            Some(f) => path(f, "folder", "a campaign folder")?,
            None => spec.with_extension(""),
        };
        py.detach(|| init::init(&spec, &folder))
            .map_err(campaign_error)?;
        Ok(Campaign { folder })
    }
    /// The campaign folder.
    #[getter]
    fn folder(&self) -> PathBuf {
        self.folder.clone()
    }
    /// Runs what is not done until every point is done or failed, as
    /// `bumpsim campaign run`: `executor` local or slurm and `slots`
    /// (default: the campaign file's), `retry_failed` gives failed points
    /// new attempts. Returns a dict: done, failed ([(run, reason)]),
    /// submitted (tasks submitted by this run).
    #[pyo3(signature = (executor = None, slots = None, retry_failed = false))]
    fn run<'py>(
        &self,
        py: Python<'py>,
        executor: Option<String>,
        slots: Option<&Bound<'py, PyAny>>,
        retry_failed: bool,
    ) -> PyResult<Bound<'py, PyDict>> {
        let options = RunOptions {
            executor,
            slots: count_or(slots, "slots", 1, MAX_SLOTS)?,
            retry_failed,
            progress: false,
        };
        let summary = py
            .detach(|| run::run(&self.folder, &options))
            .map_err(campaign_error)?;
        let d = PyDict::new(py);
        d.set_item("done", summary.done)?;
        d.set_item("failed", summary.failed)?;
        d.set_item("submitted", summary.submitted)?;
        Ok(d)
    }
    /// The points per status, the controller, every point's record.
    fn status(&self, py: Python<'_>) -> PyResult<CampaignStatus> {
        let status = py
            .detach(|| status::status(&self.folder))
            .map_err(campaign_error)?;
        Ok(CampaignStatus {
            data: StatusState(status),
        })
    }
    /// Reads the results into the design table, fits the regression and
    /// writes `results/` (table.csv, model.json, the report), as `bumpsim
    /// campaign collect`.
    fn collect(&self, py: Python<'_>) -> PyResult<Collected> {
        let table = self.folder.join("results").join("table.csv");
        let data = py.detach(|| {
            let c = collect::collect(&self.folder).map_err(campaign_error)?;
            let table = std::fs::read_to_string(&table).map_err(|e| {
                let error = CampaignError::Read {
                    path: table.clone(),
                    source: e,
                };
                campaign_error(error)
            })?;
            let collect::Collected {
                rows,
                missing,
                fit_text,
                fit_command,
            } = c;
            Ok::<_, PyErr>(CollectedState {
                rows,
                missing,
                fit_text,
                fit_command,
                table,
            })
        })?;
        Ok(Collected { data })
    }
    /// Stops the campaign's running tasks (scancel, SIGTERM) and marks them
    /// pending, as `bumpsim campaign abort`; returns how many were cancelled.
    fn abort(&self, py: Python<'_>) -> PyResult<usize> {
        py.detach(|| run::abort(&self.folder))
            .map_err(campaign_error)
    }
    /// Rebuilds a damaged or truncated state from the point folders, as
    /// `bumpsim campaign repair`: a dict of the runs kept, adopted,
    /// requeued, failed and undecided (with why), and the counts pending and
    /// salvaged.
    fn repair<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let r = py
            .detach(|| repair::repair(&self.folder))
            .map_err(campaign_error)?;
        let d = PyDict::new(py);
        d.set_item("kept", r.kept)?;
        d.set_item("adopted", r.adopted)?;
        d.set_item("requeued", r.requeued)?;
        d.set_item("failed", r.failed)?;
        d.set_item("undecided", r.undecided)?;
        d.set_item("pending", r.pending)?;
        d.set_item("salvaged", r.salvaged)?;
        Ok(d)
    }
    fn __eq__(&self, other: &Self) -> bool {
        self.folder == other.folder
    }
    /// Pickles as its folder.
    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        let args = (slf.get().folder.clone(),).into_pyobject(slf.py())?;
        Ok((slf.get_type().into_any(), args))
    }
    fn __repr__(&self) -> String {
        format!("Campaign({:?})", self.folder)
    }
}

/// The state of a campaign: points per status, the controller, every
/// point's record (the fields of `bumpsim campaign status --json`).
#[pyclass(frozen, module = "bumpsim")]
pub struct CampaignStatus {
    data: StatusState,
}

#[pymethods]
impl CampaignStatus {
    /// The campaign's name.
    #[getter]
    fn campaign(&self) -> String {
        self.data.0.campaign.clone()
    }
    /// Points of the design.
    #[getter]
    fn points(&self) -> usize {
        self.data.0.points
    }
    /// Points per status: pending, submitted, running, done, failed.
    #[getter]
    fn counts<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        crate::convert::from_json(py, &self.data.0.counts)
    }
    /// The state's last change, UTC.
    #[getter]
    fn updated(&self) -> String {
        self.data.0.updated.clone()
    }
    /// The controller holding the lock (holder, running), or None.
    #[getter]
    fn controller<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        crate::convert::from_json(py, &self.data.0.controller)
    }
    /// Every point's record (run, status, attempts, job, input_hash, ...).
    #[getter]
    fn runs<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        crate::convert::from_json(py, &self.data.0.runs)
    }
    /// The status as `bumpsim campaign status` prints it.
    fn text(&self) -> String {
        self.data.0.text()
    }
    /// The status as `bumpsim campaign status --json` prints it.
    fn to_json(&self) -> PyResult<String> {
        serde_json::to_string_pretty(&self.data.0).map_err(crate::errors::input)
    }
    /// Every point's record: index `run`, columns status, attempts, job,
    /// input_hash, submitted, finished, reason, requeues; attrs: campaign,
    /// counts, updated, controller.
    fn to_pandas<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let rows = self.runs(py)?.cast_into::<PyList>()?;
        let attrs = PyDict::new(py);
        attrs.set_item("campaign", self.campaign())?;
        attrs.set_item("counts", self.counts(py)?)?;
        attrs.set_item("updated", self.updated())?;
        attrs.set_item("controller", self.controller(py)?)?;
        frames::records(py, rows, &["run"], &attrs)
    }
    fn __eq__(&self, other: &Self) -> bool {
        self.data == other.data
    }
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Reduced<'py>> {
        reduce(slf.as_any(), &encode(&slf.get().data)?)
    }
    #[classmethod]
    fn _from_state(_cls: &Bound<'_, PyType>, state: &[u8]) -> PyResult<Self> {
        Ok(CampaignStatus {
            data: decode(state, "CampaignStatus")?,
        })
    }
    fn __repr__(&self) -> String {
        let s = &self.data.0;
        let c = &s.counts;
        format!(
            "CampaignStatus({:?}: {} points, {} done, {} failed, {} running, {} submitted, {} pending)",
            s.campaign, s.points, c.done, c.failed, c.running, c.submitted, c.pending
        )
    }
}

/// What `Campaign.collect` did: rows, points left out, the regression's
/// summary and `doe fit` command, and the table it wrote.
#[pyclass(frozen, module = "bumpsim")]
pub struct Collected {
    data: CollectedState,
}

#[pymethods]
impl Collected {
    /// Rows in the table.
    #[getter]
    fn rows(&self) -> usize {
        self.data.rows
    }
    /// Points left out of the table: [(run, why)].
    #[getter]
    fn missing(&self) -> Vec<(usize, String)> {
        self.data.missing.clone()
    }
    /// The regression's summary, as `bumpsim campaign collect` prints it.
    #[getter]
    fn fit_text(&self) -> String {
        self.data.fit_text.clone()
    }
    /// The `bumpsim doe fit` command that gives the same model from the table.
    #[getter]
    fn fit_command(&self) -> String {
        self.data.fit_command.clone()
    }
    /// `results/table.csv` as the library wrote it (the CLI's, byte for byte).
    #[getter]
    fn table(&self) -> String {
        self.data.table.clone()
    }
    /// The table: index `run`, columns `standard order`, the factors and
    /// derived quantities `NAME [unit]`, `NAME (coded)`, the responses
    /// `NAME [unit]`; attrs: missing, fit_command.
    fn to_pandas<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let attrs = PyDict::new(py);
        attrs.set_item("missing", self.missing())?;
        attrs.set_item("fit_command", &self.data.fit_command)?;
        frames::csv(py, &self.data.table, &attrs)
    }
    fn __eq__(&self, other: &Self) -> bool {
        self.data == other.data
    }
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Reduced<'py>> {
        reduce(slf.as_any(), &encode(&slf.get().data)?)
    }
    #[classmethod]
    fn _from_state(_cls: &Bound<'_, PyType>, state: &[u8]) -> PyResult<Self> {
        Ok(Collected {
            data: decode(state, "Collected")?,
        })
    }
    fn __repr__(&self) -> String {
        format!(
            "Collected(rows={}, missing={})",
            self.data.rows,
            self.data.missing.len()
        )
    }
}
