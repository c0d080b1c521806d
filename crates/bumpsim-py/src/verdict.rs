//! Damageability verdicts and bumper targets: the engine's verdict request
//! (`bumpsim_engine::verdict`), the one `bumpsim verdict` makes: one planar
//! car file per end with its
//! `[damageability]`, a protocol set and a margin → per test and criterion
//! the value, limit, margin and outcome; with `target=True` also the region
//! of bumper characteristics that passes every criterion. The results come
//! back as data: the JSON's fields, pandas rows (test × criterion; one row
//! per stiffness of the target region) and the CLI's text.

use crate::convert::from_json;
use crate::errors::{input, invalid};
use crate::frames;
use crate::impact::bumper_of;
use crate::planar::planar_car_of;
use crate::state::verdict::{CriterionView, RegionState, TestView, VerdictState};
use crate::state::{decode, encode, reduce, same};
use bumpsim_engine::model::Unwatched;
use bumpsim_engine::{End, HeldCar, VerdictRequest};
use bumpsim_verdict::criteria::{Criterion, Quantity};
use bumpsim_verdict::target::Region;
use bumpsim_verdict::text;
use bumpsim_verdict::verdict::{TestVerdict, Verdict as CoreVerdict};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList, PyTuple, PyType};

/// What `__reduce__` returns.
type Reduced<'py> = (Bound<'py, PyAny>, (Bound<'py, PyBytes>,));

/// Registers the classes and functions of this module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Verdict>()?;
    m.add_class::<BumperTarget>()?;
    m.add_function(wrap_pyfunction!(judge, m)?)?;
    m.add_function(wrap_pyfunction!(protocols, m)?)?;
    Ok(())
}

/// The ends of `car` as held cars: one car (a `PlanarCar` or the path of
/// its file), or a list or tuple of them (one per end).
fn car_ends(car: &Bound<'_, PyAny>) -> PyResult<Vec<HeldCar>> {
    if car.is_instance_of::<PyList>() || car.is_instance_of::<PyTuple>() {
        return car.try_iter()?.map(|c| planar_car_of(&c?)).collect();
    }
    Ok(vec![planar_car_of(car)?])
}

/// Protocol and test names: one string, comma-separated as the CLI's
/// `--protocol`, or a sequence of them.
fn protocol_names(value: Option<&Bound<'_, PyAny>>) -> PyResult<Vec<String>> {
    let Some(value) = value else {
        return Ok(vec!["all".into()]);
    };
    let names: Vec<String> = match value.extract::<String>() {
        Ok(text) => vec![text],
        Err(_) => value.extract::<Vec<String>>().map_err(|_| {
            invalid("protocol: expected a protocol or test name, comma-separated names or a list of them")
        })?,
    };
    Ok(names
        .iter()
        .flat_map(|n| n.split(','))
        .map(str::to_string)
        .collect())
}

/// The verdict of a car and its bumper in a set of protocols, as `bumpsim
/// verdict --car CAR.toml --protocol P --margin M [--target]`: `car` a
/// `PlanarCar` or the path of a planar car file with a `[damageability]`
/// table, or a list of them (one per end); `protocol` names protocols or
/// tests (`"part581,rcar-bumper"`, a list, or `"all"`); `bumper` (a `Bumper`
/// or its file) replaces the car's bumper, shared equally by its segments;
/// `target` also searches the region of passing bumpers; `sequence` runs
/// the tests in order on one car per end, each from the damage the earlier
/// ones left (`--sequence`, `bumpsim_verdict::sequence`).
#[pyfunction]
#[pyo3(name = "verdict", signature = (car, protocol = None, margin = 0.0, bumper = None, target = false, sequence = false))]
fn judge(
    py: Python<'_>,
    car: &Bound<'_, PyAny>,
    protocol: Option<&Bound<'_, PyAny>>,
    margin: f64,
    bumper: Option<&Bound<'_, PyAny>>,
    target: bool,
    sequence: bool,
) -> PyResult<Verdict> {
    let names = protocol_names(protocol)?;
    let held = car_ends(car)?;
    let ends: Vec<End> = held.iter().map(HeldCar::end).collect();
    let bumper = bumper.map(bumper_of).transpose()?;
    let request = VerdictRequest {
        ends: &ends,
        bumper: bumper.as_ref(),
        protocols: &names,
        market: Default::default(),
        margin,
        target,
        sequence,
        asi_method: Default::default(),
        uncertainty: None,
        report: false,
        progress: &Unwatched,
    };
    // the request `bumpsim verdict` makes, the cars held here
    let judged = py
        .detach(|| bumpsim_engine::verdict::judged(&request))
        .map_err(input)?;
    Ok(Verdict {
        data: state(&judged.verdict, judged.region)?,
    })
}

/// The protocols and their tests, each with its source and what is
/// uncertain, as `bumpsim verdict --list` prints them.
#[pyfunction]
fn protocols() -> String {
    text::protocols()
}

/// The SI unit of a criterion's quantity.
fn si_unit(quantity: Quantity) -> &'static str {
    match quantity {
        Quantity::Length => "m",
        Quantity::Force => "N",
        Quantity::Acceleration => "m/s^2",
        Quantity::Ratio => "1",
    }
}

/// The state of a verdict (see [`crate::state::verdict`]).
fn state(v: &CoreVerdict, target: Option<Region>) -> PyResult<VerdictState> {
    let failures = v.failures();
    Ok(VerdictState {
        car: v.car.clone(),
        margin: v.margin,
        passed: v.passed(),
        failures: failures
            .iter()
            .map(|(t, c)| (t.to_string(), c.name.clone()))
            .collect(),
        tests: v.tests.iter().map(test_view).collect(),
        json: serde_json::to_string(v).map_err(input)?,
        text: text::table(v),
        target,
    })
}

fn test_view(t: &TestVerdict) -> TestView {
    TestView {
        name: t.test.name.into(),
        end: t.test.end.name().into(),
        striker: t.striker.clone(),
        skipped: t.skipped.clone(),
        passed: t.passed(),
        binding: t.binding().map(|c| (c.name.clone(), c.ratio)),
        criteria: t.criteria.iter().map(criterion_view).collect(),
        metrics: t
            .metrics
            .as_ref()
            .map(|m| [Some(m.peak), Some(m.clip), Some(m.delta_v), m.olc, m.asi]),
        energies: t.energies.as_ref().map(|e| {
            [
                e.initial,
                e.bumper,
                e.absorber,
                e.structure,
                e.kinetic,
                e.tyres,
                e.bumper_share,
            ]
        }),
    }
}

fn criterion_view(c: &Criterion) -> CriterionView {
    CriterionView {
        name: c.name.clone(),
        detail: c.detail.clone(),
        unit: si_unit(c.quantity).into(),
        value: c.value,
        limit: c.limit,
        upper: c.upper,
        margin: c.margin,
        ratio: c.ratio,
        outcome: text::outcome(c).to_lowercase(),
    }
}

/// The verdict of a car in a set of tests (`bumpsim verdict`): per test its
/// criteria with value, limit, margin and outcome, its pulse metrics and
/// energies, the assumptions; and the bumper target region when searched.
#[pyclass(frozen, module = "bumpsim")]
pub struct Verdict {
    data: VerdictState,
}

#[pymethods]
impl Verdict {
    /// The car's name.
    #[getter]
    fn car(&self) -> String {
        self.data.car.clone()
    }
    /// The margin each criterion had to keep, a share of its limit.
    #[getter]
    fn margin(&self) -> f64 {
        self.data.margin
    }
    /// Whether every assessed test passes.
    #[getter]
    fn passed(&self) -> bool {
        self.data.passed
    }
    /// The failing criteria as (test, criterion) names.
    #[getter]
    fn failures(&self) -> Vec<(String, String)> {
        self.data.failures.clone()
    }
    /// Every test as the JSON's `verdict.tests`: the test (its figures,
    /// source, what is uncertain), criteria, metrics, energies, notes.
    #[getter]
    fn tests<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.document(py)?.get_item("tests")
    }
    /// The bumper target region, when `target=True` searched it, else None.
    #[getter]
    fn target(&self) -> Option<BumperTarget> {
        self.data
            .target
            .clone()
            .map(|region| BumperTarget { data: region })
    }
    /// The tables `bumpsim verdict` prints (and the region's, when searched).
    fn to_text(&self) -> String {
        let region = self.data.target.as_ref().map(text::region);
        self.data.text.clone() + &region.unwrap_or_default()
    }
    /// The verdict (and the region) as `bumpsim verdict --json` writes it.
    fn to_json(&self) -> PyResult<String> {
        let verdict: serde_json::Value = serde_json::from_str(&self.data.json).map_err(input)?;
        let document = serde_json::json!({ "verdict": verdict, "target": self.data.target });
        serde_json::to_string_pretty(&document).map_err(input)
    }
    /// The criteria: index (`test`, `criterion`); columns `value`, `limit`,
    /// `margin` (SI, in the row's `unit`), `ratio [1]` (margin over the
    /// limit), `upper` (the value must stay at or below the limit),
    /// `outcome` (pass, fail, info), `pass` (None: reported, not judged),
    /// `detail`. A test not assessed is one row, criterion `not assessed`,
    /// its reason in `detail`. attrs: car, margin [1], passed.
    fn to_pandas<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let rows = PyList::empty(py);
        for t in &self.data.tests {
            if let Some(why) = &t.skipped {
                rows.append(skipped_row(py, &t.name, why)?)?;
            }
            for c in &t.criteria {
                rows.append(criterion_row(py, &t.name, c)?)?;
            }
        }
        let attrs = PyDict::new(py);
        attrs.set_item("car", self.car())?;
        attrs.set_item("margin [1]", self.margin())?;
        attrs.set_item("passed", self.passed())?;
        frames::records(py, rows, &["test", "criterion"], &attrs)
    }
    /// One row per test: index `test`; `end`, `striker`, `passed` (None:
    /// not assessed), `binding` (the judged criterion of least margin) and
    /// its `binding ratio [1]`, the pulse metrics `peak [m/s^2]`, `clip 3 ms
    /// [m/s^2]`, `delta_v [m/s]`, `olc [m/s^2]`, `asi [1]`, the energies
    /// `initial [J]` ... `bumper share [1]`, and `skipped` (why not assessed).
    fn tests_to_pandas<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let rows = PyList::empty(py);
        for t in &self.data.tests {
            rows.append(test_row(py, t)?)?;
        }
        let attrs = PyDict::new(py);
        attrs.set_item("car", self.car())?;
        frames::records(py, rows, &["test"], &attrs)
    }
    fn __eq__(&self, other: &Self) -> PyResult<bool> {
        same(&self.data, &other.data)
    }
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Reduced<'py>> {
        reduce(slf.as_any(), &encode(&slf.get().data)?)
    }
    #[classmethod]
    fn _from_state(_cls: &Bound<'_, PyType>, state: &[u8]) -> PyResult<Self> {
        Ok(Verdict {
            data: decode(state, "Verdict")?,
        })
    }
    fn __repr__(&self) -> String {
        let v = &self.data;
        let assessed = v.tests.iter().filter(|t| t.skipped.is_none()).count();
        let failing: Vec<String> = v
            .failures
            .iter()
            .map(|(t, c)| format!("{c} in {t}"))
            .collect();
        format!(
            "Verdict({:?}, {} tests, {assessed} assessed, margin={}, passed={}, failing={failing:?}, target={})",
            v.car,
            v.tests.len(),
            v.margin,
            if v.passed { "True" } else { "False" },
            if v.target.is_some() {
                "searched"
            } else {
                "None"
            }
        )
    }
}

impl Verdict {
    /// The library's JSON of the verdict as Python objects.
    fn document<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        py.import("json")?
            .call_method1("loads", (self.data.json.as_str(),))
    }
}

/// The row of a test not assessed.
fn skipped_row<'py>(py: Python<'py>, test: &str, why: &str) -> PyResult<Bound<'py, PyDict>> {
    let row = PyDict::new(py);
    row.set_item("test", test)?;
    row.set_item("criterion", "not assessed")?;
    for key in ["value", "limit", "margin", "ratio [1]"] {
        row.set_item(key, f64::NAN)?;
    }
    row.set_item("unit", "")?;
    row.set_item("upper", py.None())?;
    row.set_item("outcome", "not assessed")?;
    row.set_item("pass", py.None())?;
    row.set_item("detail", why)?;
    Ok(row)
}

/// The row of a criterion; `pass` is None for one reported, not judged.
fn criterion_row<'py>(
    py: Python<'py>,
    test: &str,
    c: &CriterionView,
) -> PyResult<Bound<'py, PyDict>> {
    let row = PyDict::new(py);
    row.set_item("test", test)?;
    row.set_item("criterion", &c.name)?;
    row.set_item("value", c.value)?;
    row.set_item("limit", c.limit)?;
    row.set_item("margin", c.margin)?;
    row.set_item("ratio [1]", c.ratio)?;
    row.set_item("unit", &c.unit)?;
    row.set_item("upper", c.upper)?;
    row.set_item("outcome", &c.outcome)?;
    let pass = match c.outcome.as_str() {
        "info" => None,
        outcome => Some(outcome == "pass"),
    };
    row.set_item("pass", pass)?;
    row.set_item("detail", &c.detail)?;
    Ok(row)
}

/// The columns of a test's pulse metrics and energies, in the views' order.
const METRICS: [&str; 5] = [
    "peak [m/s^2]",
    "clip 3 ms [m/s^2]",
    "delta_v [m/s]",
    "olc [m/s^2]",
    "asi [1]",
];
const ENERGIES: [&str; 7] = [
    "initial [J]",
    "bumper [J]",
    "absorber [J]",
    "structure [J]",
    "kinetic [J]",
    "tyres [J]",
    "bumper share [1]",
];

/// The row of a test: its verdict, binding criterion, pulse and energies.
fn test_row<'py>(py: Python<'py>, t: &TestView) -> PyResult<Bound<'py, PyDict>> {
    let row = PyDict::new(py);
    row.set_item("test", &t.name)?;
    row.set_item("end", &t.end)?;
    row.set_item("striker", &t.striker)?;
    row.set_item("passed", t.passed)?;
    row.set_item("binding", t.binding.as_ref().map(|b| b.0.clone()))?;
    row.set_item(
        "binding ratio [1]",
        t.binding.as_ref().map_or(f64::NAN, |b| b.1),
    )?;
    for (k, name) in METRICS.iter().enumerate() {
        let value = t.metrics.and_then(|m| m[k]);
        row.set_item(*name, value.unwrap_or(f64::NAN))?;
    }
    for (k, name) in ENERGIES.iter().enumerate() {
        row.set_item(*name, t.energies.map_or(f64::NAN, |e| e[k]))?;
    }
    row.set_item("skipped", t.skipped.clone())?;
    Ok(row)
}

/// The region of bumper characteristics that passes every criterion with
/// the margin asked for (`bumpsim verdict --target`): per whole-bumper
/// initial stiffness the passing force levels and the criterion binding at
/// each boundary, and the force–deflection corridor.
#[pyclass(frozen, module = "bumpsim")]
pub struct BumperTarget {
    data: Region,
}

#[pymethods]
impl BumperTarget {
    /// The car's own bumper: (initial stiffness N/m, force level N).
    #[getter]
    fn origin(&self) -> (f64, f64) {
        (self.data.origin[0], self.data.origin[1])
    }
    /// Whether the family is tabulated (else three-part: ramp and plateau).
    #[getter]
    fn tabulated(&self) -> bool {
        self.data.tabulated
    }
    /// The margin each criterion had to keep.
    #[getter]
    fn margin(&self) -> f64 {
        self.data.margin
    }
    /// Impacts simulated by the search.
    #[getter]
    fn impacts(&self) -> usize {
        self.data.impacts
    }
    /// Wall time of the search, s.
    #[getter]
    fn seconds(&self) -> f64 {
        self.data.seconds
    }
    /// The rows as the JSON's `target.rows`.
    #[getter]
    fn rows<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        from_json(py, &self.data.rows)
    }
    /// Whether a whole-bumper initial stiffness (N/m) and force level (N)
    /// lie in the region.
    fn contains(&self, stiffness: f64, force: f64) -> bool {
        self.data.contains(stiffness, force)
    }
    /// The region as `bumpsim verdict --target` prints it.
    fn to_text(&self) -> String {
        text::region(&self.data)
    }
    /// The region as the JSON's `target`.
    fn to_json(&self) -> PyResult<String> {
        serde_json::to_string_pretty(&self.data).map_err(input)
    }
    /// The limits per characteristic: index `stiffness [N/m]` (whole
    /// bumper); columns `force low [N]`, `binding low`, `force high [N]`,
    /// `binding high` (None: the search range's edge), `stroke [m]` (the
    /// crush needed at the lower bound) and `failing` (the criterion failing
    /// when nothing passes: the forces are NaN). attrs: origin, margin,
    /// tabulated, impacts.
    fn to_pandas<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let rows = PyList::empty(py);
        for r in &self.data.rows {
            let row = PyDict::new(py);
            let bound = |k: usize| r.interval.as_ref().map(|i| &i[k]);
            row.set_item("stiffness [N/m]", r.stiffness)?;
            row.set_item("force low [N]", bound(0).map_or(f64::NAN, |b| b.force))?;
            row.set_item("binding low", bound(0).and_then(|b| b.binding.clone()))?;
            row.set_item("force high [N]", bound(1).map_or(f64::NAN, |b| b.force))?;
            row.set_item("binding high", bound(1).and_then(|b| b.binding.clone()))?;
            row.set_item("stroke [m]", r.stroke.unwrap_or(f64::NAN))?;
            row.set_item("failing", r.failing.clone())?;
            rows.append(row)?;
        }
        let attrs = PyDict::new(py);
        attrs.set_item("origin [N/m, N]", self.origin())?;
        attrs.set_item("margin [1]", self.data.margin)?;
        attrs.set_item("tabulated", self.data.tabulated)?;
        attrs.set_item("impacts", self.data.impacts)?;
        frames::records(py, rows, &["stiffness [N/m]"], &attrs)
    }
    /// The force–deflection corridor of the passing characteristics (whole
    /// bumper): index `deflection [m]`, columns `lower [N]`, `upper [N]`.
    fn corridor_to_pandas<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let c = &self.data.corridor;
        let columns = vec![
            (
                "lower [N]".into(),
                c.lower.clone().into_pyobject(py)?.into_any(),
            ),
            (
                "upper [N]".into(),
                c.upper.clone().into_pyobject(py)?.into_any(),
            ),
        ];
        let index = (
            "deflection [m]".into(),
            c.deflection.clone().into_pyobject(py)?.into_any(),
        );
        frames::frame(py, columns, Some(index), &PyDict::new(py))
    }
    fn __eq__(&self, other: &Self) -> bool {
        self.data == other.data
    }
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Reduced<'py>> {
        let state = RegionState(slf.get().data.clone());
        reduce(slf.as_any(), &encode(&state)?)
    }
    #[classmethod]
    fn _from_state(_cls: &Bound<'_, PyType>, state: &[u8]) -> PyResult<Self> {
        let RegionState(data) = decode(state, "BumperTarget")?;
        Ok(BumperTarget { data })
    }
    fn __repr__(&self) -> String {
        let r = &self.data;
        let passing = r.rows.iter().filter(|r| r.interval.is_some()).count();
        format!(
            "BumperTarget({} stiffness rows, {passing} with a passing interval, margin={}, origin=({} N/m, {} N), {} impacts)",
            r.rows.len(),
            r.margin,
            r.origin[0],
            r.origin[1],
            r.impacts
        )
    }
}
