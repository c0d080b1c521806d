//! Crash-test signals: `read_test` (ISO-MME, NHTSA EV5, CSV through
//! bumpsim-io's `TestData`), `Channel` with the processing steps of
//! bumpsim-signal (the ones `bumpsim signal export` applies), and `cfc`.
//! A `Test` is a handle on its files: it pickles as its path and is opened
//! again; channels and entries pickle as their values.

use crate::arrays::{array1, cached1, vector};
use crate::errors::{file_or_input, input, reading};
use crate::frames;
use bumpsim_core::channel::Channel as CoreChannel;
use bumpsim_core::series::UniformSeries;
use bumpsim_core::units::Unit;
use bumpsim_io::test_data::{Entry as CoreEntry, TestData, Validity};
use bumpsim_signal::filter::{Cfc, CfcStandard};
use bumpsim_signal::pipeline::{Pipeline, PipelineResult};
use bumpsim_signal::process::{Step, align};
use bumpsim_signal::window::ContactThreshold;
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyDict, PyList, PyTuple, PyType};
use std::path::PathBuf;

/// What `__reduce__` returns: a callable and its arguments.
type Reduced<'py> = (Bound<'py, PyAny>, Bound<'py, PyTuple>);

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
fn run_pipeline(py: Python<'_>, path: &Bound<'_, PyAny>) -> PyResult<PipelineRun> {
    let path = crate::convert::path(path, "path", "a pipeline")?;
    let pipeline = Pipeline::read(&path).map_err(|e| reading(&path, e))?;
    let result = py.detach(|| pipeline.run()).map_err(file_or_input)?;
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
        self.inner
            .signals
            .iter()
            .cloned()
            .map(Channel::of)
            .collect()
    }
    /// The signals as read, before processing.
    #[getter]
    fn raw(&self) -> Vec<Channel> {
        self.inner.raw.iter().cloned().map(Channel::of).collect()
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
    /// The processed signals on their common times, as `bumpsim signal
    /// process -o` writes them (SI): index `time [s]`, a column `CODE
    /// [unit]` per signal; attrs: warnings, balance.
    fn to_pandas<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let signals = &self.inner.signals;
        let (time, columns) = align(signals).map_err(input)?;
        let columns = signals
            .iter()
            .zip(columns)
            .map(|(s, values)| (header(s), array1(py, values).into_bound(py).into_any()))
            .collect();
        let attrs = PyDict::new(py);
        attrs.set_item("warnings", &self.inner.warnings)?;
        attrs.set_item("balance", self.balance(py)?)?;
        let index = (
            "time [s]".to_string(),
            array1(py, time).into_bound(py).into_any(),
        );
        frames::frame(py, columns, Some(index), &attrs)
    }
    fn __eq__(&self, other: &Self) -> bool {
        let (a, b) = (&self.inner, &other.inner);
        (&a.signals, &a.raw, &a.warnings, &a.balance)
            == (&b.signals, &b.raw, &b.warnings, &b.balance)
    }
    /// Pickles as its signals, raw signals, warnings and balance.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Reduced<'py>> {
        let py = slf.py();
        let r = &slf.get().inner;
        let balance = r.balance.map(|b| {
            (
                b.window,
                b.mass,
                b.impulse,
                b.momentum_change,
                b.relative_difference,
            )
        });
        let args = (
            slf.getattr("signals")?,
            slf.getattr("raw")?,
            r.warnings.clone(),
            balance,
        );
        Ok((
            slf.get_type().getattr("_from_state")?,
            (args,).into_pyobject(py)?,
        ))
    }
    #[classmethod]
    fn _from_state(_cls: &Bound<'_, PyType>, state: RunState<'_>) -> PipelineRun {
        let (signals, raw, warnings, balance) = state;
        let channels =
            |list: Vec<PyRef<'_, Channel>>| list.iter().map(|c| c.inner.clone()).collect();
        let balance = balance.map(
            |(window, mass, impulse, momentum_change, relative_difference)| {
                bumpsim_signal::pipeline::Balance {
                    window,
                    mass,
                    impulse,
                    momentum_change,
                    relative_difference,
                }
            },
        );
        PipelineRun {
            inner: PipelineResult {
                signals: channels(signals),
                raw: channels(raw),
                warnings,
                balance,
            },
        }
    }
    fn __repr__(&self) -> String {
        let codes: Vec<&str> = self.inner.signals.iter().map(|s| s.code.as_str()).collect();
        format!(
            "PipelineRun(signals={codes:?}, warnings={}, balance={})",
            self.inner.warnings.len(),
            self.inner.balance.is_some()
        )
    }
}

/// A pipeline run's pickled state: signals, raw signals, warnings, balance.
type RunState<'py> = (
    Vec<PyRef<'py, Channel>>,
    Vec<PyRef<'py, Channel>>,
    Vec<String>,
    Option<([f64; 2], f64, f64, f64, f64)>,
);

/// The column header `CODE [unit]` of a channel in SI (as the CLI's CSV).
fn header(channel: &CoreChannel) -> String {
    format!("{} [{}]", channel.code, channel.dimension.si_symbol())
}

fn standard(name: &str) -> PyResult<CfcStandard> {
    match name {
        "sae-j211" => Ok(CfcStandard::SaeJ211),
        "iso-6487" => Ok(CfcStandard::Iso6487),
        other => Err(crate::errors::invalid(format!(
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
    crate::convert::from_json(py, &rating)
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
fn read_test(py: Python<'_>, path: &Bound<'_, PyAny>) -> PyResult<Test> {
    let path = crate::convert::path(path, "path", "a test")?;
    let test = py
        .detach(|| TestData::open(&path))
        .map_err(|e| reading(&path, e))?;
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
        Ok(channels.into_iter().map(Channel::of).collect())
    }

    /// Every usable channel (valid, samples present), loaded in SI units.
    #[getter]
    fn channels(&self, py: Python<'_>) -> PyResult<Vec<Channel>> {
        self.select(py, "*")
    }

    /// One channel by its number (as listed in `entries`), even if marked invalid.
    fn channel(&self, py: Python<'_>, number: &Bound<'_, PyAny>) -> PyResult<Channel> {
        let number = crate::convert::count(number, "number", 1, usize::MAX)?;
        self.select(py, &format!("#{number}"))?
            .into_iter()
            .next()
            .ok_or_else(|| {
                crate::errors::invalid(format!(
                    "{}: no usable channel number {number}",
                    self.inner.path.display()
                ))
            })
    }

    /// The channel list: index `number`, columns code, name, unit (as
    /// written), invalid (the lab's reason, or None), present, absence;
    /// attrs: path, format, title, speed [m/s], mass [kg], metadata.
    fn to_pandas<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let rows = PyList::empty(py);
        for e in &self.inner.entries {
            rows.append(Entry { inner: e.clone() }.row(py)?)?;
        }
        let attrs = PyDict::new(py);
        attrs.set_item("path", &self.inner.path)?;
        attrs.set_item("format", self.format())?;
        attrs.set_item("title", &self.inner.title)?;
        attrs.set_item("speed [m/s]", self.inner.speed)?;
        attrs.set_item("mass [kg]", self.inner.mass)?;
        attrs.set_item("metadata", dict(py, &self.inner.metadata)?)?;
        frames::records(py, rows, &["number"], &attrs)
    }
    fn __eq__(&self, other: &Self) -> bool {
        let key = |t: &TestData| {
            (
                t.path.clone(),
                t.format.to_string(),
                t.title.clone(),
                t.metadata.clone(),
                t.speed,
                t.mass,
            )
        };
        key(&self.inner) == key(&other.inner) && self.inner.entries == other.inner.entries
    }
    /// Pickles as its path: a test is a handle on its files, opened again.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Reduced<'py>> {
        let args = (slf.get().inner.path.clone(),).into_pyobject(slf.py())?;
        Ok((slf.get_type().getattr("_from_state")?, args))
    }
    #[classmethod]
    fn _from_state(
        _cls: &Bound<'_, PyType>,
        py: Python<'_>,
        path: &Bound<'_, PyAny>,
    ) -> PyResult<Self> {
        read_test(py, path)
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
    fn __eq__(&self, other: &Self) -> bool {
        self.inner == other.inner
    }
    /// Pickles as its values.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Reduced<'py>> {
        let py = slf.py();
        let e = &slf.get().inner;
        let state = (
            e.number,
            e.code.clone(),
            e.name.clone(),
            e.unit.clone(),
            slf.get().invalid(),
            e.present,
            e.absence.clone(),
            e.metadata.clone(),
        );
        Ok((
            slf.get_type().getattr("_from_state")?,
            (state,).into_pyobject(py)?,
        ))
    }
    #[classmethod]
    fn _from_state(_cls: &Bound<'_, PyType>, state: EntryState) -> Self {
        let (number, code, name, unit, invalid, present, absence, metadata) = state;
        let validity = invalid.map_or(Validity::Valid, Validity::Invalid);
        Entry {
            inner: CoreEntry {
                number,
                code,
                name,
                unit,
                validity,
                present,
                absence,
                metadata,
            },
        }
    }
    fn __repr__(&self) -> String {
        format!(
            "Entry({} {:?} [{}] {:?})",
            self.inner.number, self.inner.code, self.inner.unit, self.inner.name
        )
    }
}

/// An entry's pickled values: number, code, name, unit, invalid, present,
/// absence, metadata.
type EntryState = (
    usize,
    String,
    String,
    String,
    Option<String>,
    bool,
    Option<String>,
    Vec<(String, String)>,
);

impl Entry {
    /// The entry as a row of `Test.to_pandas`.
    fn row<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let e = &self.inner;
        let row = PyDict::new(py);
        row.set_item("number", e.number)?;
        row.set_item("code", &e.code)?;
        row.set_item("name", &e.name)?;
        row.set_item("unit", &e.unit)?;
        row.set_item("invalid", self.invalid())?;
        row.set_item("present", e.present)?;
        row.set_item("absence", &e.absence)?;
        Ok(row)
    }
}

/// A loaded channel: code, name, SI unit, uniform time base and samples.
#[pyclass(frozen, module = "bumpsim")]
pub struct Channel {
    inner: CoreChannel,
    time: PyOnceLock<Py<PyArray1<f64>>>,
    data: PyOnceLock<Py<PyArray1<f64>>>,
}

/// A channel's pickled values: code, name, SI unit, start (s), step (s),
/// samples, unit as written, metadata.
type ChannelState = (
    String,
    String,
    String,
    f64,
    f64,
    Vec<f64>,
    String,
    Vec<(String, String)>,
);

impl Channel {
    fn of(inner: CoreChannel) -> Channel {
        Channel {
            inner,
            time: PyOnceLock::new(),
            data: PyOnceLock::new(),
        }
    }

    fn apply(&self, py: Python<'_>, step: Step) -> PyResult<Channel> {
        let channel = py.detach(|| step.apply(&self.inner)).map_err(input)?;
        Ok(Channel::of(channel))
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
        cached1(py, &self.time, || self.inner.series.times())
    }
    /// Samples, SI.
    #[getter]
    fn data(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        cached1(py, &self.data, || self.inner.series.values().to_vec())
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
    fn moving_average(&self, py: Python<'_>, points: &Bound<'_, PyAny>) -> PyResult<Channel> {
        let points = crate::convert::count(points, "points", 1, usize::MAX)?;
        self.apply(py, Step::MovingAverage(points))
    }
    /// The samples as a `pandas.Series` named `CODE [unit]` (as the CLI's
    /// CSV header), indexed by `time [s]`; attrs: code, name, unit,
    /// source_unit, metadata.
    fn to_pandas<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let attrs = PyDict::new(py);
        attrs.set_item("code", &self.inner.code)?;
        attrs.set_item("name", &self.inner.name)?;
        attrs.set_item("unit", self.unit())?;
        attrs.set_item("source_unit", &self.inner.source_unit)?;
        attrs.set_item("metadata", dict(py, &self.inner.metadata)?)?;
        let index = (
            "time [s]".to_string(),
            self.time(py).into_bound(py).into_any(),
        );
        let data = self.data(py).into_bound(py).into_any();
        frames::series(py, &header(&self.inner), data, index, &attrs)
    }
    fn __eq__(&self, other: &Self) -> bool {
        self.inner == other.inner
    }
    /// Pickles as its values.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Reduced<'py>> {
        let c = &slf.get().inner;
        let state: ChannelState = (
            c.code.clone(),
            c.name.clone(),
            c.dimension.si_symbol().to_string(),
            c.series.start(),
            c.series.step(),
            c.series.values().to_vec(),
            c.source_unit.clone(),
            c.metadata.clone(),
        );
        Ok((
            slf.get_type().getattr("_from_state")?,
            (state,).into_pyobject(slf.py())?,
        ))
    }
    #[classmethod]
    fn _from_state(_cls: &Bound<'_, PyType>, state: ChannelState) -> PyResult<Self> {
        let (code, name, unit, start, step, values, source_unit, metadata) = state;
        let dimension = Unit::parse(&unit).map_err(input)?.dimension;
        let series = UniformSeries::new(start, step, values).map_err(input)?;
        Ok(Channel::of(CoreChannel {
            code,
            name,
            dimension,
            series,
            source_unit,
            metadata,
        }))
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
