//! The Python exceptions, one hierarchy on Python's own bases (issue 38):
//!
//! ```text
//! bumpsim.Error (Exception)
//! ├── bumpsim.InputError (Error, ValueError)      a value, array or file content refused
//! ├── bumpsim.FileError (Error, OSError)          a file or folder that cannot be read
//! │   └── bumpsim.MissingFileError (FileError, FileNotFoundError)   it does not exist
//! └── bumpsim.RunError (Error, RuntimeError)      a campaign's controller or scheduler
//! ```
//!
//! so `except ValueError` catches every bad value and `except
//! FileNotFoundError` every missing file. Each carries the library error's
//! message with its causes, each cause once, as the CLI prints them. The
//! classes are Python code (multiple bases), made once when the module is
//! imported; an error is classified by its cause: an I/O error of kind
//! "not found" is a missing file, any other I/O error a file error, the rest
//! bad input.

use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyModule, PyType};
use std::path::Path;

/// The hierarchy, defined in Python (a class with two bases).
const CLASSES: &std::ffi::CStr = cr#"
class Error(Exception):
    """Base class of every bumpsim error; the message is the library's, as the CLI prints it."""
    __module__ = "bumpsim"

class InputError(Error, ValueError):
    """A value, array, option or file content the library refuses (a ValueError); the message names the parameter, file, line or channel."""
    __module__ = "bumpsim"

class FileError(Error, OSError):
    """A file or folder that cannot be read or written (an OSError; errno and filename set when known)."""
    __module__ = "bumpsim"

    def __str__(self):
        # the library's message, as the CLI prints it (OSError would print "[Errno 2] None: path")
        return str(self.args[0]) if self.args else ""

class MissingFileError(FileError, FileNotFoundError):
    """A file, folder or program that does not exist (a FileNotFoundError)."""
    __module__ = "bumpsim"

class RunError(Error, RuntimeError):
    """A campaign that cannot go on: another controller holds its lock, or the scheduler failed."""
    __module__ = "bumpsim"
"#;

/// Which exception an error becomes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// `InputError`.
    Input,
    /// `FileError`.
    File,
    /// `MissingFileError`.
    Missing,
    /// `RunError`.
    Run,
}

/// The names of the classes, in the order of [`TYPES`].
const NAMES: [&str; 5] = [
    "Error",
    "InputError",
    "FileError",
    "MissingFileError",
    "RunError",
];

static TYPES: PyOnceLock<Vec<Py<PyType>>> = PyOnceLock::new();

/// Makes the classes and adds them to the extension module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    let code = PyModule::from_code(py, CLASSES, c"bumpsim/errors.py", c"bumpsim._errors")?;
    let types = TYPES.get_or_try_init(py, || {
        NAMES
            .iter()
            .map(|name| Ok(code.getattr(*name)?.cast_into::<PyType>()?.unbind()))
            .collect::<PyResult<Vec<_>>>()
    })?;
    for (name, class) in NAMES.iter().zip(types) {
        m.add(*name, class.bind(py))?;
    }
    Ok(())
}

/// The exception of `kind` with `message`; for file errors, `errno` and
/// `filename` when known.
pub fn raise(kind: Kind, message: String) -> PyErr {
    raise_os(kind, message, None, None)
}

fn raise_os(kind: Kind, message: String, errno: Option<i32>, filename: Option<&Path>) -> PyErr {
    Python::attach(|py| {
        let Some(types) = TYPES.get(py) else {
            return PyRuntimeError::new_err(message);
        };
        let index = match kind {
            Kind::Input => 1,
            Kind::File => 2,
            Kind::Missing => 3,
            Kind::Run => 4,
        };
        let error = PyErr::from_type(types[index].bind(py).clone(), (message,));
        let value = error.value(py);
        // attributes of OSError: best effort, the message is what matters
        if let Some(errno) = errno {
            let _ = value.setattr("errno", errno);
        }
        if let Some(path) = filename {
            let _ = value.setattr("filename", path);
        }
        error
    })
}

/// `InputError` with `message`.
pub fn invalid(message: impl Into<String>) -> PyErr {
    raise(Kind::Input, message.into())
}

/// The error and its causes, each cause once (library errors often quote
/// their source in their own message), as the CLI prints them.
pub fn message(error: &dyn std::error::Error) -> String {
    let mut text = error.to_string();
    let mut cause = error.source();
    while let Some(c) = cause {
        let line = c.to_string();
        if !text.contains(&line) {
            text = format!("{text}: {line}");
        }
        cause = c.source();
    }
    text
}

/// `InputError` with the library's message.
pub fn input(error: impl std::error::Error) -> PyErr {
    invalid(message(&error))
}

/// The I/O error among the causes of `error`, if any.
fn io_cause<'a>(error: &'a (dyn std::error::Error + 'static)) -> Option<&'a std::io::Error> {
    let mut cause = Some(error);
    while let Some(c) = cause {
        if let Some(io) = c.downcast_ref::<std::io::Error>() {
            return Some(io);
        }
        cause = c.source();
    }
    None
}

/// The kind of an I/O error: missing (not found) or another file error.
fn io_kind(io: &std::io::Error) -> Kind {
    match io.kind() {
        std::io::ErrorKind::NotFound => Kind::Missing,
        _ => Kind::File,
    }
}

/// `MissingFileError` or `FileError` when a cause is an I/O error,
/// `InputError` otherwise, with the library's message.
pub fn file_or_input(error: impl std::error::Error + 'static) -> PyErr {
    let text = message(&error);
    match io_cause(&error) {
        Some(io) => raise_os(io_kind(io), text, io.raw_os_error(), None),
        None => invalid(text),
    }
}

/// An error of a reader given `path`: as [`file_or_input`], and, for the
/// readers that report an unreadable file in their own words (the study,
/// bumper, planar car and pipeline readers keep the I/O error's text, not
/// the error), `MissingFileError`/`FileError` when `path` itself cannot be
/// opened; the message stays the library's.
pub fn reading(path: &Path, error: impl std::error::Error + 'static) -> PyErr {
    let text = message(&error);
    if let Some(io) = io_cause(&error) {
        return raise_os(io_kind(io), text, io.raw_os_error(), Some(path));
    }
    match std::fs::metadata(path) {
        Err(io) => raise_os(io_kind(&io), text, io.raw_os_error(), Some(path)),
        Ok(_) => invalid(text),
    }
}
