//! The posterior of an identified chain (bumpsim-ident's
//! `posterior::{sampling, posterior}`, issue 39): the ensemble sampler run
//! around an `Identification` with its noise model, seeded, within the
//! bounds it was identified in; `Posterior` holds the means, intervals,
//! diagnostics and the kept draws (a read-only numpy array and a pandas
//! frame with the parameters' names and units).

use crate::arrays::{cached1, cached2};
use crate::convert::{count_or, from_json};
use crate::errors::input;
use crate::frames;
use crate::state::ident::{IdentificationState, PosteriorState};
use crate::state::{decode, encode, reduce, same};
use bumpsim_core::model::parameter_kind;
use bumpsim_estimate::posterior::Posterior as CorePosterior;
use bumpsim_ident::posterior::{self, Request, Summary, lines};
use bumpsim_ident::settings::Settings;
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyBytes, PyDict, PyList, PyType};

/// What `__reduce__` returns.
type Reduced<'py> = (Bound<'py, PyAny>, (Bound<'py, PyBytes>,));

/// Registers the class of this module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Posterior>()
}

/// The run the caller asked for (None: the library's default).
pub struct Run<'a, 'py> {
    /// Seed of the random stream (None: the identification's seed).
    pub seed: Option<&'a Bound<'py, PyAny>>,
    /// Steps of every walker, a quarter of them burnt.
    pub steps: Option<&'a Bound<'py, PyAny>>,
    /// Walkers (None: the library's choice).
    pub walkers: Option<&'a Bound<'py, PyAny>>,
}

/// Samples the posterior of the identification `data` as `bumpsim
/// identify --posterior --steps --walkers --seed` does (see the module).
pub fn sample(py: Python<'_>, data: &IdentificationState, run: Run) -> PyResult<Posterior> {
    let result = &data.result;
    let request = Request {
        walkers: count_or(run.walkers, "walkers", 0, usize::MAX)?,
        steps: count_or(run.steps, "steps", 0, usize::MAX)?,
        seed: crate::convert::seed(run.seed)?.unwrap_or(data.seed),
    };
    let settings = Settings {
        bounds: data.bounds.clone(),
        ..Settings::new(result.dof, 1)
    };
    let post = py
        .detach(|| posterior::run(&data.cases, &settings, result, &request, &|| {}))
        .map_err(input)?;
    Ok(Posterior::of(PosteriorState {
        posterior: post,
        result: result.clone(),
    }))
}

/// The posterior of an identified model's parameters (`Identification.
/// posterior()`): means, medians, deviations and equal-tailed 90 % and
/// 95 % intervals (SI, thesis order), the sampler's diagnostics and the kept
/// draws.
#[pyclass(frozen, module = "bumpsim")]
pub struct Posterior {
    data: PosteriorState,
    mean: PyOnceLock<Py<PyArray1<f64>>>,
    median: PyOnceLock<Py<PyArray1<f64>>>,
    sd: PyOnceLock<Py<PyArray1<f64>>>,
    samples: PyOnceLock<Py<PyArray2<f64>>>,
}

impl Posterior {
    fn of(data: PosteriorState) -> Posterior {
        Posterior {
            data,
            mean: PyOnceLock::new(),
            median: PyOnceLock::new(),
            sd: PyOnceLock::new(),
            samples: PyOnceLock::new(),
        }
    }

    fn core(&self) -> &CorePosterior {
        &self.data.posterior
    }

    /// `name [unit]` of every parameter.
    fn headers(&self) -> Vec<String> {
        let dof = self.data.result.dof;
        let names = self.core().names.iter().enumerate();
        names
            .map(|(i, n)| format!("{n} [{}]", parameter_kind(dof, i).0.unit()))
            .collect()
    }
}

#[pymethods]
impl Posterior {
    /// Parameter names (m1.., c1.., k1..).
    #[getter]
    fn names(&self) -> Vec<String> {
        self.core().names.clone()
    }
    /// Their SI units.
    #[getter]
    fn units(&self) -> Vec<&'static str> {
        let dof = self.data.result.dof;
        (0..self.core().names.len())
            .map(|i| parameter_kind(dof, i).0.unit())
            .collect()
    }
    /// Posterior means, SI.
    #[getter]
    fn mean(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        cached1(py, &self.mean, || self.core().mean.clone())
    }
    /// Posterior medians, SI.
    #[getter]
    fn median(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        cached1(py, &self.median, || self.core().median.clone())
    }
    /// Posterior standard deviations, SI.
    #[getter]
    fn sd(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        cached1(py, &self.sd, || self.core().sd.clone())
    }
    /// Equal-tailed 90 % intervals (5 % and 95 % quantiles), SI; None for a
    /// fixed parameter.
    #[getter]
    fn ci90(&self) -> Vec<Option<(f64, f64)>> {
        self.core()
            .ci90
            .iter()
            .map(|c| c.map(|[a, b]| (a, b)))
            .collect()
    }
    /// Equal-tailed 95 % intervals, SI; None for a fixed parameter.
    #[getter]
    fn ci95(&self) -> Vec<Option<(f64, f64)>> {
        self.core()
            .ci95
            .iter()
            .map(|c| c.map(|[a, b]| (a, b)))
            .collect()
    }
    /// Parameters held fixed.
    #[getter]
    fn fixed(&self) -> Vec<bool> {
        self.core().fixed.clone()
    }
    /// The likelihood's noise model (the JSON's `noise`).
    #[getter]
    fn noise<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        from_json(py, &self.core().noise)
    }
    /// The run: walkers, steps, burn and seed.
    #[getter]
    fn ensemble<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        from_json(py, &self.core().ensemble)
    }
    /// Integrated autocorrelation times, effective draws, split-R̂ (of the
    /// free parameters, in their order), acceptance, converged, warnings.
    #[getter]
    fn diagnostics<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        from_json(py, &self.core().diagnostics)
    }
    /// Whether the run has converged (the diagnostics' verdict).
    #[getter]
    fn converged(&self) -> bool {
        self.core().diagnostics.converged
    }
    /// What failed, and what to do (empty when the run converged).
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.core().diagnostics.warnings.clone()
    }
    /// The kept draws of θ, SI: one row per draw, one column per parameter
    /// (read-only).
    #[getter]
    fn samples(&self, py: Python<'_>) -> Py<PyArray2<f64>> {
        let columns = self.core().names.len();
        cached2(py, &self.samples, &self.core().draws, columns)
    }
    /// The posterior's lines of the summary: each parameter's median and
    /// 90 % and 95 % intervals next to its local 95 % interval, the
    /// diagnostics, warnings (the mean is in `mean` and the JSON).
    fn to_text(&self) -> String {
        lines(self.core(), &self.data.result)
    }
    /// The posterior as `bumpsim identify --posterior --json` writes it
    /// (its `posterior`: everything but the draws, with the units, the
    /// optimum and its local 95 % intervals).
    fn to_json(&self) -> PyResult<String> {
        let summary = Summary::new(self.core(), &self.data.result);
        serde_json::to_string_pretty(&summary).map_err(input)
    }
    /// The kept draws: one row per draw, columns `m1 [kg]`, ..., `k1
    /// [N/m]`; attrs: ensemble, noise, converged.
    fn to_pandas<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let samples = self.samples(py).into_bound(py);
        let columns: Vec<frames::Column<'py>> = self
            .headers()
            .into_iter()
            .enumerate()
            .map(|(i, h)| Ok((h, samples.get_item((pyo3::types::PySlice::full(py), i))?)))
            .collect::<PyResult<_>>()?;
        frames::frame(py, columns, None, &self.attrs(py)?)
    }
    /// The summary: index `parameter`; columns `mean`, `median`, `sd`,
    /// `ci90_low`, `ci90_high`, `ci95_low`, `ci95_high` (SI, in the row's
    /// `unit`), the identification's local `local_ci95_low`,
    /// `local_ci95_high`, `unit`, `fixed`; attrs as `to_pandas`.
    fn summary_to_pandas<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let p = self.core();
        let local = &self.data.result.uncertainty.ci95;
        let rows = PyList::empty(py);
        for (i, unit) in self.units().into_iter().enumerate() {
            let row = PyDict::new(py);
            let bound = |c: Option<[f64; 2]>, k: usize| c.map_or(f64::NAN, |c| c[k]);
            let local = local.get(i).copied().flatten();
            row.set_item("parameter", &p.names[i])?;
            row.set_item("mean", p.mean[i])?;
            row.set_item("median", p.median[i])?;
            row.set_item("sd", p.sd[i])?;
            row.set_item("ci90_low", bound(p.ci90[i], 0))?;
            row.set_item("ci90_high", bound(p.ci90[i], 1))?;
            row.set_item("ci95_low", bound(p.ci95[i], 0))?;
            row.set_item("ci95_high", bound(p.ci95[i], 1))?;
            row.set_item("local_ci95_low", bound(local, 0))?;
            row.set_item("local_ci95_high", bound(local, 1))?;
            row.set_item("unit", unit)?;
            row.set_item("fixed", p.fixed[i])?;
            rows.append(row)?;
        }
        frames::records(py, rows, &["parameter"], &self.attrs(py)?)
    }
    fn __eq__(&self, other: &Self) -> PyResult<bool> {
        same(&self.data, &other.data)
    }
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Reduced<'py>> {
        reduce(slf.as_any(), &encode(&slf.get().data)?)
    }
    #[classmethod]
    fn _from_state(_cls: &Bound<'_, PyType>, state: &[u8]) -> PyResult<Self> {
        Ok(Posterior::of(decode(state, "Posterior")?))
    }
    fn __repr__(&self) -> String {
        let p = self.core();
        let e = &p.ensemble;
        format!(
            "Posterior(dof={}, {} walkers × {} steps, {} burnt, seed {}, {} draws kept, converged={})",
            self.data.result.dof,
            e.walkers,
            e.steps,
            e.burn,
            e.seed,
            p.draws.len(),
            if p.diagnostics.converged {
                "True"
            } else {
                "False"
            }
        )
    }
}

impl Posterior {
    /// The frames' attrs: the run, the noise model, whether it converged.
    fn attrs<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let attrs = PyDict::new(py);
        attrs.set_item("ensemble", self.ensemble(py)?)?;
        attrs.set_item("noise", self.noise(py)?)?;
        attrs.set_item("converged", self.converged())?;
        attrs.set_item("warnings", self.warnings())?;
        Ok(attrs)
    }
}
