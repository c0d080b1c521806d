//! Crash-test signals: `read_test` (ISO-MME, NHTSA EV5, CSV through
//! bumpsim-io's `TestData`), `Channel` with the processing steps of
//! bumpsim-signal (the ones `bumpsim signal export` applies), and `cfc`.

use crate::arrays::{array1, vector};
use crate::errors::{file_or_input, input};
use bumpsim_core::channel::Channel as CoreChannel;
use bumpsim_io::test_data::{Entry as CoreEntry, TestData, Validity};
use bumpsim_signal::filter::{Cfc, CfcStandard};
use bumpsim_signal::pipeline::{Pipeline, PipelineResult};
use bumpsim_signal::process::Step;
use bumpsim_signal::window::ContactThreshold;
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;

/// Registers the classes and functions of this module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Test>()?;
    m.add_class::<Entry>()?;
    m.add_class::<Channel>()?;
    m.add_function(wrap_pyfunction!(read_test, m)?)?;
    m.add_function(wrap_pyfunction!(cfc, m)?)?;
    m.add_function(wrap_pyfunction!(run_pipeline, m)?)?;
    m.add_function(wrap_pyfunction!(contact_window, m)?)?;
    m.add_function(wrap_pyfunction!(iso18571, m)?)?;
    m.add_class::<PipelineRun>()?;
    Ok(())
}

/// Runs a processing pipeline file (TOML), as `bumpsim signal process`.
#[pyfunction]
fn run_pipeline(py: Python<'_>, path: PathBuf) -> PyResult<PipelineRun> {
    let result = py
        .detach(|| Pipeline::read(&path).and_then(|p| p.run()))
        .map_err(file_or_input)?;
    Ok(PipelineRun { inner: result })
}

/// The signals of a pipeline run, the raw ones, warnings and the momentum balance.
#[pyclass(frozen, module = "bumpsim")]
pub struct PipelineRun {
    inner: PipelineResult,
}

#[pymethods]
impl PipelineRun {
    /// The processed signals, in file order.
    #[getter]
    fn signals(&self) -> Vec<Channel> {
        let wrap = |c: &CoreChannel| Channel { inner: c.clone() };
        self.inner.signals.iter().map(wrap).collect()
    }
    /// The signals as read, before processing.
    #[getter]
    fn raw(&self) -> Vec<Channel> {
        let wrap = |c: &CoreChannel| Channel { inner: c.clone() };
        self.inner.raw.iter().map(wrap).collect()
    }
    /// Warnings of the run.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.inner.warnings.clone()
    }
    /// The momentum balance (window s, mass kg, impulse and momentum change
    /// N·s, relative difference), or None when the pipeline asks for none.
    #[getter]
    fn balance<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        let Some(b) = &self.inner.balance else {
            return Ok(None);
        };
        let d = PyDict::new(py);
        d.set_item("window", (b.window[0], b.window[1]))?;
        d.set_item("mass", b.mass)?;
        d.set_item("impulse", b.impulse)?;
        d.set_item("momentum_change", b.momentum_change)?;
        d.set_item("relative_difference", b.relative_difference)?;
        Ok(Some(d))
    }
}

fn standard(name: &str) -> PyResult<CfcStandard> {
    match name {
        "sae-j211" => Ok(CfcStandard::SaeJ211),
        "iso-6487" => Ok(CfcStandard::Iso6487),
        other => Err(crate::errors::InputError::new_err(format!(
            "standard '{other}': expected 'sae-j211' or 'iso-6487'"
        ))),
    }
}

/// Filters `x` sampled at `fs` Hz with a CFC filter of class `cls` (SAE
/// J211-1 constant, or ISO 6487's), zero phase, as the pipelines do.
#[pyfunction]
#[pyo3(signature = (x, fs, cls, standard = "sae-j211"))]
fn cfc(
    py: Python<'_>,
    x: &Bound<'_, PyAny>,
    fs: f64,
    cls: f64,
    standard: &str,
) -> PyResult<Py<PyArray1<f64>>> {
    let values = vector(x, "x")?;
    let standard = self::standard(standard)?;
    let filtered = py
        .detach(|| Cfc::new(cls, standard).and_then(|f| f.filter(&values, 1.0 / fs)))
        .map_err(input)?;
    Ok(array1(py, filtered))
}

/// The ISO/TS 18571 rating of `candidate` against `reference`, both
/// sampled every `step` s at the same instants: a dict of the overall,
/// corridor, phase, magnitude and slope ratings (bumpsim-signal's `rating`).
#[pyfunction]
fn iso18571<'py>(
    py: Python<'py>,
    reference: &Bound<'py, PyAny>,
    candidate: &Bound<'py, PyAny>,
    step: f64,
) -> PyResult<Bound<'py, PyAny>> {
    let (reference, candidate) = (
        vector(reference, "reference")?,
        vector(candidate, "candidate")?,
    );
    let rating = py
        .detach(|| bumpsim_signal::rating::rate(&reference, &candidate, step))
        .map_err(input)?;
    crate::ident::from_json(py, &rating)
}

/// The contact window of a force (any sign): first and last sample index
/// (inclusive) where |F| rises to `rise` and last stays at `fall` of its peak.
#[pyfunction]
#[pyo3(signature = (force, rise = 0.05, fall = 0.02))]
fn contact_window(force: &Bound<'_, PyAny>, rise: f64, fall: f64) -> PyResult<(usize, usize)> {
    let values = vector(force, "force")?;
    let window = ContactThreshold { rise, fall }
        .detect(&values)
        .map_err(input)?;
    Ok((window.first, window.last))
}

/// Opens a crash test: an ISO-MME folder, `.mme` or `.zip`, an NHTSA `.EV5`
/// file or a CSV file with `name [unit]` headers.
#[pyfunction]
fn read_test(py: Python<'_>, path: PathBuf) -> PyResult<Test> {
    let test = py.detach(|| TestData::open(&path)).map_err(file_or_input)?;
    Ok(Test { inner: test })
}

fn dict<'py>(py: Python<'py>, pairs: &[(String, String)]) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (k, v) in pairs {
        d.set_item(k, v)?;
    }
    Ok(d)
}

/// A crash test: metadata, channel list, and channels loaded on demand.
#[pyclass(frozen, module = "bumpsim")]
pub struct Test {
    inner: TestData,
}

#[pymethods]
impl Test {
    /// The path it was opened from.
    #[getter]
    fn path(&self) -> PathBuf {
        self.inner.path.clone()
    }

    /// `ISO-MME`, `NHTSA EV5` or `CSV`.
    #[getter]
    fn format(&self) -> String {
        self.inner.format.to_string()
    }

    /// Test title or name.
    #[getter]
    fn title(&self) -> String {
        self.inner.title.clone()
    }

    /// Test-level fields, in file order.
    #[getter]
    fn metadata<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        dict(py, &self.inner.metadata)
    }

    /// Impact speed, m/s, when the file states it.
    #[getter]
    fn speed(&self) -> Option<f64> {
        self.inner.speed
    }

    /// Test mass, kg, when the file states it.
    #[getter]
    fn mass(&self) -> Option<f64> {
        self.inner.mass
    }

    /// The channel list (before samples are read).
    #[getter]
    fn entries(&self) -> Vec<Entry> {
        self.inner
            .entries
            .iter()
            .map(|e| Entry { inner: e.clone() })
            .collect()
    }

    /// The usable channels a selector picks (number, code with `?`/`*`
    /// wildcards, or name substring), loaded in SI units.
    fn select(&self, py: Python<'_>, selector: &str) -> PyResult<Vec<Channel>> {
        let channels = py
            .detach(|| {
                let selection = self.inner.select(selector)?;
                self.inner.load_all(&selection)
            })
            .map_err(file_or_input)?;
        Ok(channels.into_iter().map(|c| Channel { inner: c }).collect())
    }

    /// Every usable channel (valid, samples present), loaded in SI units.
    #[getter]
    fn channels(&self, py: Python<'_>) -> PyResult<Vec<Channel>> {
        self.select(py, "*")
    }

    /// One channel by its number (as listed in `entries`), even if marked invalid.
    fn channel(&self, py: Python<'_>, number: usize) -> PyResult<Channel> {
        self.select(py, &format!("#{number}"))?
            .into_iter()
            .next()
            .ok_or_else(|| {
                crate::errors::InputError::new_err(format!(
                    "{}: no usable channel number {number}",
                    self.inner.path.display()
                ))
            })
    }

    fn __repr__(&self) -> String {
        format!(
            "Test({} {:?}, {} channels: {:?})",
            self.inner.format,
            self.inner.path,
            self.inner.entries.len(),
            self.inner.title
        )
    }
}

/// A channel as the test lists it, before its samples are read.
#[pyclass(frozen, module = "bumpsim")]
pub struct Entry {
    inner: CoreEntry,
}

#[pymethods]
impl Entry {
    /// Channel number (1-based).
    #[getter]
    fn number(&self) -> usize {
        self.inner.number
    }
    /// Channel code.
    #[getter]
    fn code(&self) -> String {
        self.inner.code.clone()
    }
    /// Name.
    #[getter]
    fn name(&self) -> String {
        self.inner.name.clone()
    }
    /// The unit as written in the file.
    #[getter]
    fn unit(&self) -> String {
        self.inner.unit.clone()
    }
    /// None when usable, else the lab's reason for marking it invalid.
    #[getter]
    fn invalid(&self) -> Option<String> {
        match &self.inner.validity {
            Validity::Valid => None,
            Validity::Invalid(why) => Some(why.clone()),
        }
    }
    /// Whether its samples are present.
    #[getter]
    fn present(&self) -> bool {
        self.inner.present
    }
    /// Why the samples are absent, when they are.
    #[getter]
    fn absence(&self) -> Option<String> {
        self.inner.absence.clone()
    }
    /// Channel-level fields.
    #[getter]
    fn metadata<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        dict(py, &self.inner.metadata)
    }
    fn __repr__(&self) -> String {
        format!(
            "Entry({} {:?} [{}] {:?})",
            self.inner.number, self.inner.code, self.inner.unit, self.inner.name
        )
    }
}

/// A loaded channel: code, name, SI unit, uniform time base and samples.
#[pyclass(frozen, module = "bumpsim")]
pub struct Channel {
    inner: CoreChannel,
}

impl Channel {
    fn apply(&self, py: Python<'_>, step: Step) -> PyResult<Channel> {
        let channel = py.detach(|| step.apply(&self.inner)).map_err(input)?;
        Ok(Channel { inner: channel })
    }
}

#[pymethods]
impl Channel {
    /// Channel code (follows the processing: filter class letter, ...).
    #[getter]
    fn code(&self) -> String {
        self.inner.code.clone()
    }
    /// Name.
    #[getter]
    fn name(&self) -> String {
        self.inner.name.clone()
    }
    /// The SI unit of the samples (`N`, `m/s^2`, ...).
    #[getter]
    fn unit(&self) -> String {
        self.inner.dimension.si_symbol().to_string()
    }
    /// The unit the file wrote.
    #[getter]
    fn source_unit(&self) -> String {
        self.inner.source_unit.clone()
    }
    /// Channel-level fields (ISO/TS 13499 header).
    #[getter]
    fn metadata<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        dict(py, &self.inner.metadata)
    }
    /// Time of the first sample, s.
    #[getter]
    fn start(&self) -> f64 {
        self.inner.series.start()
    }
    /// Sample interval, s.
    #[getter]
    fn step(&self) -> f64 {
        self.inner.series.step()
    }
    /// Sample times, s.
    #[getter]
    fn time(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        array1(py, self.inner.series.times())
    }
    /// Samples, SI.
    #[getter]
    fn data(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        array1(py, self.inner.series.values().to_vec())
    }
    /// CFC filter of class `cls` (SAE J211-1 or ISO 6487 constant), as `signal export --cfc`.
    #[pyo3(signature = (cls, standard = "sae-j211"))]
    fn cfc(&self, py: Python<'_>, cls: f64, standard: &str) -> PyResult<Channel> {
        let step = match self::standard(standard)? {
            CfcStandard::SaeJ211 => Step::Cfc(cls),
            CfcStandard::Iso6487 => Step::CfcIso(cls),
        };
        self.apply(py, step)
    }
    /// Removes the mean of the samples before t = 0 (`signal export --bias`).
    fn bias(&self, py: Python<'_>) -> PyResult<Channel> {
        self.apply(py, Step::PretriggerBias(true))
    }
    /// Multiplies by `factor`.
    fn scale(&self, py: Python<'_>, factor: f64) -> PyResult<Channel> {
        self.apply(py, Step::Scale(factor))
    }
    /// Integrates so that the result equals `initial` (SI) at t = 0.
    #[pyo3(signature = (initial = 0.0))]
    fn integrate(&self, py: Python<'_>, initial: f64) -> PyResult<Channel> {
        self.apply(py, Step::Integrate(initial))
    }
    /// Keeps only the samples in [t0, t1] s (`signal export --trim`).
    fn trim(&self, py: Python<'_>, t0: f64, t1: f64) -> PyResult<Channel> {
        self.apply(py, Step::Trim([t0, t1]))
    }
    /// Resamples to the interval `step` s (`signal export --resample`).
    fn resample(&self, py: Python<'_>, step: f64) -> PyResult<Channel> {
        self.apply(py, Step::Resample(step))
    }
    /// Centred moving average over `points` samples.
    fn moving_average(&self, py: Python<'_>, points: usize) -> PyResult<Channel> {
        self.apply(py, Step::MovingAverage(points))
    }
    /// The samples as a `pandas.Series` indexed by time (s), named by the code.
    fn to_pandas<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let pandas = py.import("pandas")?;
        let index = pandas.call_method1("Index", (self.time(py),))?;
        let kwargs = PyDict::new(py);
        kwargs.set_item("index", index)?;
        kwargs.set_item("name", self.code())?;
        pandas
            .getattr("Series")?
            .call((self.data(py),), Some(&kwargs))
    }
    fn __len__(&self) -> usize {
        self.inner.series.len()
    }
    fn __repr__(&self) -> String {
        format!(
            "Channel({:?} {:?} [{}], {} samples at {} s)",
            self.inner.code,
            self.inner.name,
            self.inner.dimension.si_symbol(),
            self.inner.series.len(),
            self.inner.series.step()
        )
    }
}
