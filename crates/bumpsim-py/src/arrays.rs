//! numpy ↔ Rust conversion. Inputs are 1-D float64 numpy arrays (read
//! in place, one copy into the library's owned vectors) or sequences of
//! numbers; any other dtype or shape is an `InputError` naming the argument,
//! its dtype and shape, never a silent cast. Outputs are numpy arrays that
//! take over the library's vectors (1-D, no copy) or stack them (2-D, one
//! copy, one row per mass or link).

use crate::errors::InputError;
use numpy::ndarray::Array2;
use numpy::{
    IntoPyArray, PyArray1, PyArray2, PyArrayMethods, PyUntypedArray, PyUntypedArrayMethods,
};
use pyo3::prelude::*;

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
        return Err(InputError::new_err(format!(
            "{what}: expected a 1-D numpy array of float64, got a {}-D array of {} with shape ({}); convert with numpy.asarray({what}, dtype=float).ravel() if that is what you mean",
            array.ndim(),
            array.dtype(),
            python_shape(array.shape())
        )));
    }
    obj.extract::<Vec<f64>>().map_err(|_| {
        let kind = obj.get_type().name().map_or("?".into(), |n| n.to_string());
        InputError::new_err(format!(
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

/// A vector as a 1-D numpy array (takes the vector over, no copy).
pub fn array1(py: Python<'_>, values: Vec<f64>) -> Py<PyArray1<f64>> {
    values.into_pyarray(py).unbind()
}

/// Rows of equal length `columns` as a 2-D numpy array (rows × columns).
pub fn array2(py: Python<'_>, rows: &[Vec<f64>], columns: usize) -> Py<PyArray2<f64>> {
    let flat: Vec<f64> = rows.concat();
    match Array2::from_shape_vec((rows.len(), columns), flat) {
        Ok(a) => a.into_pyarray(py).unbind(),
        // the library's rows all have one value per sample
        Err(e) => unreachable!("rows of unequal length: {e}"),
    }
}
