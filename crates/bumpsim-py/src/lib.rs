//! The `bumpsim` Python package: the extension module `bumpsim._bumpsim`.
//!
//! Bindings hold no logic (house rules, spec §11): every function converts
//! its Python arguments (numpy arrays, paths, numbers), calls the library
//! crates exactly as the CLI does, and converts the results back (numpy
//! arrays, objects with the JSON's fields). Library errors become
//! `bumpsim.InputError` (bad values) or `bumpsim.FileError` (a file that
//! cannot be read), both `bumpsim.Error`, carrying the library's message.
//! Long calls release the GIL. `python/bumpsim/__init__.pyi` documents the
//! Python API; docs/python.md is the tour.

mod arrays;
mod doe;
mod errors;
mod export;
mod ident;
mod impact;
mod model;
mod planar;
mod signal;

use pyo3::prelude::*;

/// The extension module; `python/bumpsim/__init__.py` re-exports it.
#[pymodule]
fn _bumpsim(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("Error", py.get_type::<errors::Error>())?;
    m.add("InputError", py.get_type::<errors::InputError>())?;
    m.add("FileError", py.get_type::<errors::FileError>())?;
    model::register(m)?;
    signal::register(m)?;
    ident::register(m)?;
    impact::register(m)?;
    doe::register(m)?;
    export::register(m)?;
    planar::register(m)?;
    Ok(())
}
