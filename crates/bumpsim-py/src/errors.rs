//! The Python exceptions: `Error` (base), `InputError` (values or files
//! the library refuses) and its subclass `FileError` (a file that cannot be
//! read at all). Each carries the library error's message with its causes,
//! each cause once, as the CLI prints them.

use pyo3::PyErr;
use pyo3::create_exception;
use pyo3::exceptions::PyException;

create_exception!(
    bumpsim,
    Error,
    PyException,
    "Base class of every bumpsim error."
);
create_exception!(
    bumpsim,
    InputError,
    Error,
    "A value, array or file that the bumpsim library refuses; the message names the parameter, file or line."
);
create_exception!(
    bumpsim,
    FileError,
    InputError,
    "A file or folder that cannot be read (missing, unreadable)."
);

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
    InputError::new_err(message(&error))
}

/// `FileError` when the cause is an I/O error (file missing, unreadable),
/// `InputError` otherwise.
pub fn file_or_input(error: impl std::error::Error + 'static) -> PyErr {
    let text = message(&error);
    let mut cause: Option<&dyn std::error::Error> = Some(&error);
    while let Some(c) = cause {
        if c.is::<std::io::Error>() {
            return FileError::new_err(text);
        }
        cause = c.source();
    }
    InputError::new_err(text)
}
