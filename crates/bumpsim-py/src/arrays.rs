//! numpy ↔ Rust conversion. Inputs are 1-D float64 numpy arrays (read
//! in place, one copy into the library's owned vectors) or sequences of
//! numbers; any other dtype or shape is an `InputError` naming the argument,
//! its dtype and shape, never a silent cast. Outputs are numpy arrays that
//! take over the library's vectors (1-D, no copy) or stack them (2-D, one
//! copy, one row per mass or link).
//!
//! One rule for every class (docs/python.md, "Arrays and errors"): an
//! object's arrays are **read-only** and made once: every access returns the
//! same array (no copy after the first), and writing into it raises
//! `ValueError: assignment destination is read-only` instead of being lost
//! or changing the object behind its back; `.copy()` gives a writable one.

use crate::errors::invalid;
use numpy::ndarray::Array2;
use numpy::{
    IntoPyArray, PyArray1, PyArray2, PyArrayMethods, PyUntypedArray, PyUntypedArrayMethods,
};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;

/// A 1-D float64 array or a sequence of numbers as a vector.
pub fn vector(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<f64>> {
    if let Ok(array) = obj.cast::<PyArray1<f64>>() {
        let array = array.readonly();
        return Ok(match array.as_slice() {
            Ok(slice) => slice.to_vec(),
            Err(_) => array.as_array().to_vec(),
        });
    }
    if let Ok(array) = obj.cast::<PyUntypedArray>() {
        return Err(invalid(format!(
            "{what}: expected a 1-D numpy array of float64, got a {}-D array of {} with shape ({}); convert with numpy.asarray({what}, dtype=float).ravel() if that is what you mean",
            array.ndim(),
            array.dtype(),
            python_shape(array.shape())
        )));
    }
    obj.extract::<Vec<f64>>().map_err(|_| {
        let kind = obj.get_type().name().map_or("?".into(), |n| n.to_string());
        invalid(format!(
            "{what}: expected a 1-D numpy array of float64 or a sequence of numbers, got {kind}"
        ))
    })
}

/// A shape as Python prints it: `(10,)`, `(2, 5)`.
fn python_shape(shape: &[usize]) -> String {
    match shape {
        [n] => format!("{n},"),
        many => many
            .iter()
            .map(ToString::to_string)
            .collect::<Vec<_>>()
            .join(", "),
    }
}

/// A vector as a read-only 1-D numpy array (takes the vector over, no copy).
pub fn array1(py: Python<'_>, values: Vec<f64>) -> Py<PyArray1<f64>> {
    let array = values.into_pyarray(py);
    read_only(array.as_any());
    array.unbind()
}

/// Clears the array's WRITEABLE flag.
fn read_only(array: &Bound<'_, PyAny>) {
    // an array made here always owns its data: clearing the flag cannot fail
    let _ = array
        .getattr("flags")
        .and_then(|f| f.setattr("writeable", false));
}

/// The array in `cell`, made by `make` (and made read-only) on first access.
pub fn cached1(
    py: Python<'_>,
    cell: &PyOnceLock<Py<PyArray1<f64>>>,
    make: impl FnOnce() -> Vec<f64>,
) -> Py<PyArray1<f64>> {
    cell.get_or_init(py, || array1(py, make())).clone_ref(py)
}

/// The 2-D array in `cell` (rows × columns), made read-only on first access.
pub fn cached2(
    py: Python<'_>,
    cell: &PyOnceLock<Py<PyArray2<f64>>>,
    rows: &[Vec<f64>],
    columns: usize,
) -> Py<PyArray2<f64>> {
    cell.get_or_init(py, || array2(py, rows, columns))
        .clone_ref(py)
}

/// The rows of a 2-D array (equality and pickling of objects holding arrays).
pub fn rows(py: Python<'_>, array: &Py<PyArray2<f64>>) -> Vec<Vec<f64>> {
    let array = array.bind(py).readonly();
    array.as_array().outer_iter().map(|r| r.to_vec()).collect()
}

/// The values of a 1-D array (equality and pickling of objects holding arrays).
pub fn values(py: Python<'_>, array: &Py<PyArray1<f64>>) -> Vec<f64> {
    array.bind(py).to_vec().unwrap_or_default()
}

/// Rows of equal length `columns` as a 2-D numpy array (rows × columns).
pub fn array2(py: Python<'_>, rows: &[Vec<f64>], columns: usize) -> Py<PyArray2<f64>> {
    let flat: Vec<f64> = rows.concat();
    match Array2::from_shape_vec((rows.len(), columns), flat) {
        Ok(a) => {
            let array = a.into_pyarray(py);
            read_only(array.as_any());
            array.unbind()
        }
        // the library's rows all have one value per sample
        Err(e) => unreachable!("rows of unequal length: {e}"),
    }
}
