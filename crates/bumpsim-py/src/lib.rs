//! The `bumpsim` Python package: the extension module `bumpsim._bumpsim`.
//!
//! Bindings hold no logic (house rules, spec §11): every function converts
//! its Python arguments (numpy arrays, paths, numbers), calls the library
//! crates exactly as the CLI does, and converts the results back (numpy
//! arrays, objects with the JSON's fields, pandas frames on request).
//! Library errors become Python exceptions on Python's own bases
//! (`ValueError`, `OSError`, `FileNotFoundError`; [`errors`]) carrying the
//! library's message; every object pickles ([`state`]), compares equal to
//! its copy and has read-only arrays ([`arrays`]). Long calls release the
//! GIL. `python/bumpsim/__init__.pyi` documents the Python API;
//! docs/python.md is the tour.

mod arrays;
mod campaign;
mod convert;
mod doe;
mod errors;
mod export;
mod frames;
mod ident;
mod identification;
mod identified;
mod impact;
mod model;
mod planar;
mod posterior;
mod signal;
mod state;
mod uncertain;
mod verdict;

use pyo3::prelude::*;

/// The extension module; `python/bumpsim/__init__.py` re-exports it.
#[pymodule]
fn _bumpsim(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    errors::register(m)?;
    model::register(m)?;
    signal::register(m)?;
    ident::register(m)?;
    identified::register(m)?;
    impact::register(m)?;
    doe::register(m)?;
    export::register(m)?;
    planar::register(m)?;
    posterior::register(m)?;
    campaign::register(m)?;
    verdict::register(m)?;
    Ok(())
}
