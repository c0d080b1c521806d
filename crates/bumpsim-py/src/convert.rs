//! Python arguments that are not arrays: whole numbers (a negative count is
//! an `InputError` naming the argument and its range, as the CLI's
//! `--starts` says it, never an `OverflowError`), DOF numbers, ranges and
//! lists (the CLI's `--dof` forms, parsed by bumpsim-ident), and paths;
//! and library values as Python objects through their JSON.

use crate::errors::{input, invalid, message};
use bumpsim_ident::dofs::DofList;
use pyo3::prelude::*;
use std::path::PathBuf;

/// `value` as a whole number from `low` to `high`; `name` is the argument.
pub fn whole(value: &Bound<'_, PyAny>, name: &str, low: u64, high: u64) -> PyResult<u64> {
    let n = value.extract::<i128>().ok().filter(|_| !is_bool(value));
    match n {
        Some(n) if n >= i128::from(low) && n <= i128::from(high) => Ok(n as u64),
        _ => Err(invalid(format!(
            "{name} {}: expected a whole number from {low} to {high}",
            shown(value)
        ))),
    }
}

/// [`whole`] as a `usize` (every range here fits).
pub fn count(value: &Bound<'_, PyAny>, name: &str, low: usize, high: usize) -> PyResult<usize> {
    whole(value, name, low as u64, high as u64).map(|n| n as usize)
}

/// An optional [`count`].
pub fn count_or(
    value: Option<&Bound<'_, PyAny>>,
    name: &str,
    low: usize,
    high: usize,
) -> PyResult<Option<usize>> {
    value.map(|v| count(v, name, low, high)).transpose()
}

/// A seed: any whole number from 0 to 2⁶⁴ − 1.
pub fn seed(value: Option<&Bound<'_, PyAny>>) -> PyResult<Option<u64>> {
    value.map(|v| whole(v, "seed", 0, u64::MAX)).transpose()
}

/// Whole numbers (ids, node numbers) from 0 to 2⁶⁴ − 1.
pub fn ids(values: &Bound<'_, PyAny>, name: &str) -> PyResult<Vec<u64>> {
    values
        .try_iter()
        .map_err(|_| invalid(format!("{name}: expected a sequence of whole numbers")))?
        .map(|v| whole(&v?, name, 0, u64::MAX))
        .collect()
}

fn is_bool(value: &Bound<'_, PyAny>) -> bool {
    value.is_instance_of::<pyo3::types::PyBool>()
}

/// The value as Python prints it.
fn shown(value: &Bound<'_, PyAny>) -> String {
    value.repr().map_or_else(|_| "?".into(), |r| r.to_string())
}

/// Model orders: a number (`3`), a range (`"1..5"`) or a list (`[1, 2]` or
/// `"1,2"`), each from 1 to the library's limit, as the CLI's `--dof`.
pub fn dofs(value: &Bound<'_, PyAny>) -> PyResult<Vec<usize>> {
    let text = match value.extract::<String>() {
        Ok(text) => text,
        Err(_) => match value.extract::<Vec<i128>>() {
            Ok(list) if !is_bool(value) => list
                .iter()
                .map(i128::to_string)
                .collect::<Vec<_>>()
                .join(","),
            _ => match value.extract::<i128>() {
                Ok(n) if !is_bool(value) => n.to_string(),
                _ => shown(value),
            },
        },
    };
    text.parse::<DofList>()
        .map(|d| d.0)
        .map_err(|e| invalid(format!("dof {}", message(&e))))
}

/// A path argument: `str` or `os.PathLike`; anything else is a `TypeError`
/// naming the argument.
pub fn path(value: &Bound<'_, PyAny>, name: &str, what: &str) -> PyResult<PathBuf> {
    value.extract::<PathBuf>().map_err(|_| {
        let kind = value
            .get_type()
            .name()
            .map_or("?".into(), |n| n.to_string());
        pyo3::exceptions::PyTypeError::new_err(format!(
            "{name}: expected {what} or the path of its file (str or os.PathLike), got {kind}"
        ))
    })
}

/// Parses JSON the library serialised into Python objects.
pub fn from_json<'py>(
    py: Python<'py>,
    value: &impl serde::Serialize,
) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value).map_err(input)?;
    py.import("json")?.call_method1("loads", (text,))
}
