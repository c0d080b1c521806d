//! pandas objects for every tabular result (issue 38). pandas stays
//! optional: it is imported here, when `to_pandas()` is called, never when
//! `bumpsim` is imported. Columns are named `name [unit]` as the CLI's CSV
//! headers; time histories are indexed by `time [s]`; what is not a column
//! (scenario, warnings, units of a mixed column) goes into `DataFrame.attrs`.
//! Tables the library writes as CSV text are read by pandas with exact
//! (round-trip) float parsing, so the frame holds the CSV's very numbers.

use pyo3::exceptions::PyImportError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

/// The pandas module, or an `ImportError` saying how to get it.
pub fn pandas(py: Python<'_>) -> PyResult<Bound<'_, PyModule>> {
    py.import("pandas").map_err(|e| {
        PyImportError::new_err(format!(
            "to_pandas() needs pandas, an optional dependency of bumpsim: pip install pandas (or bumpsim[pandas]); {e}"
        ))
    })
}

/// A column: its `name [unit]` header and its values (an array or a list).
pub type Column<'py> = (String, Bound<'py, PyAny>);

/// A DataFrame of `columns`, indexed by `index` (its name and values) or
/// by 0, 1, ...; `attrs` go into `DataFrame.attrs`.
pub fn frame<'py>(
    py: Python<'py>,
    columns: Vec<Column<'py>>,
    index: Option<Column<'py>>,
    attrs: &Bound<'py, PyDict>,
) -> PyResult<Bound<'py, PyAny>> {
    let pandas = pandas(py)?;
    let data = PyDict::new(py);
    for (name, values) in columns {
        data.set_item(name, values)?;
    }
    let kwargs = PyDict::new(py);
    if let Some((name, values)) = index {
        kwargs.set_item("index", named_index(&pandas, &name, values)?)?;
    }
    let df = pandas.getattr("DataFrame")?.call((data,), Some(&kwargs))?;
    df.getattr("attrs")?.call_method1("update", (attrs,))?;
    Ok(df)
}

/// A Series of `values` named `name`, indexed by `index`.
pub fn series<'py>(
    py: Python<'py>,
    name: &str,
    values: Bound<'py, PyAny>,
    index: Column<'py>,
    attrs: &Bound<'py, PyDict>,
) -> PyResult<Bound<'py, PyAny>> {
    let pandas = pandas(py)?;
    let kwargs = PyDict::new(py);
    kwargs.set_item("index", named_index(&pandas, &index.0, index.1)?)?;
    kwargs.set_item("name", name)?;
    let series = pandas.getattr("Series")?.call((values,), Some(&kwargs))?;
    series.getattr("attrs")?.call_method1("update", (attrs,))?;
    Ok(series)
}

fn named_index<'py>(
    pandas: &Bound<'py, PyModule>,
    name: &str,
    values: Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    let kwargs = PyDict::new(pandas.py());
    kwargs.set_item("name", name)?;
    pandas.getattr("Index")?.call((values,), Some(&kwargs))
}

/// A CSV table the library wrote (`name [unit]` headers) as a DataFrame
/// indexed by its first column, floats parsed exactly.
pub fn csv<'py>(
    py: Python<'py>,
    text: &str,
    attrs: &Bound<'py, PyDict>,
) -> PyResult<Bound<'py, PyAny>> {
    let pandas = pandas(py)?;
    let buffer = py.import("io")?.getattr("StringIO")?.call1((text,))?;
    let kwargs = PyDict::new(py);
    kwargs.set_item("index_col", 0)?;
    // pandas 3 parses floats exactly by default and deprecates the option
    let version: String = pandas.getattr("__version__")?.extract()?;
    if version
        .split('.')
        .next()
        .and_then(|m| m.parse::<u32>().ok())
        .is_some_and(|major| major < 3)
    {
        kwargs.set_item("float_precision", "round_trip")?;
    }
    kwargs.set_item("comment", "#")?;
    let df = pandas.call_method("read_csv", (buffer,), Some(&kwargs))?;
    df.getattr("attrs")?.call_method1("update", (attrs,))?;
    Ok(df)
}

/// Rows of records (dicts) as a DataFrame indexed by the columns `index`.
pub fn records<'py>(
    py: Python<'py>,
    rows: Bound<'py, PyList>,
    index: &[&str],
    attrs: &Bound<'py, PyDict>,
) -> PyResult<Bound<'py, PyAny>> {
    let pandas = pandas(py)?;
    let empty = rows.is_empty();
    let df = pandas
        .getattr("DataFrame")?
        .call_method1("from_records", (rows,))?;
    let df = match empty {
        false => df.call_method1("set_index", (index.to_vec(),))?,
        true => df,
    };
    df.getattr("attrs")?.call_method1("update", (attrs,))?;
    Ok(df)
}
