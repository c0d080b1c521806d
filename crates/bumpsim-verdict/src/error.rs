//! Why a verdict cannot be given: every error names the key of the car
//! file, the protocol or the option it is about.

use bumpsim_planar::PlanarError;

/// Why a verdict or a target search cannot run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum VerdictError {
    /// A needed key is missing from the car file.
    #[error("{path}: {key} is missing: {expected}")]
    Missing {
        /// The car file.
        path: String,
        /// The key, as written in the file (`damageability.rail_yield`).
        key: String,
        /// What is needed.
        expected: String,
    },
    /// A value is out of range.
    #[error("{key} = {} {unit}: {expected}", bumpsim_core::units::short(*value))]
    Value {
        /// The key or option.
        key: String,
        /// The value given.
        value: f64,
        /// Its unit.
        unit: &'static str,
        /// What is allowed.
        expected: String,
    },
    /// Two limits contradict each other.
    #[error("{first} and {second} contradict each other: {reason}")]
    Contradiction {
        /// One key.
        first: String,
        /// The other key.
        second: String,
        /// Why.
        reason: String,
    },
    /// A protocol or test name that names none.
    #[error("unknown protocol or test '{name}': known protocols {known}")]
    Protocol {
        /// The name as given.
        name: String,
        /// The known protocol names.
        known: String,
    },
    /// The car file cannot be read or parsed.
    #[error("{path}: {message}")]
    File {
        /// The file.
        path: String,
        /// What is wrong.
        message: String,
    },
    /// A pulse metric cannot be computed from the record.
    #[error("{metric}: {reason}")]
    Pulse {
        /// The metric (OLC, ASI, ...).
        metric: &'static str,
        /// Why.
        reason: String,
    },
    /// The car file is not a valid planar car (the message names the file).
    #[error(transparent)]
    Car(PlanarError),
    /// The planar car, striker or simulation refused.
    #[error("{test}: {source}")]
    Planar {
        /// The test (or `car`).
        test: String,
        /// Why.
        source: PlanarError,
    },
}

impl VerdictError {
    /// Two car files given for the same end of one verdict (`end`: its
    /// name, `front` or `rear`).
    pub fn two_cars_for(end: &str) -> VerdictError {
        VerdictError::Contradiction {
            first: "damageability.end".into(),
            second: "damageability.end".into(),
            reason: format!("two car files describe the {end} end: give one car per end"),
        }
    }
}

impl From<bumpsim_planar::uncertainty::UncertaintyError> for VerdictError {
    fn from(e: bumpsim_planar::uncertainty::UncertaintyError) -> VerdictError {
        use bumpsim_planar::uncertainty::UncertaintyError as U;
        match e {
            U::File { path, message } => VerdictError::File { path, message },
            U::Value {
                key,
                value,
                unit,
                expected,
            } => VerdictError::Value {
                key,
                value,
                unit,
                expected,
            },
            U::Missing {
                path,
                key,
                expected,
            } => VerdictError::Missing {
                path,
                key,
                expected,
            },
            U::Foreign {
                path,
                key,
                car,
                identified,
            } => VerdictError::File {
                path,
                message: bumpsim_planar::uncertainty::foreign(&key, car, identified),
            },
            other => VerdictError::File {
                path: String::new(),
                message: other.to_string(),
            },
        }
    }
}

/// `Ok` when `value` is finite and `ok` holds, else a value error naming `key`.
pub(crate) fn require(
    key: &str,
    value: f64,
    unit: &'static str,
    expected: &str,
    ok: bool,
) -> Result<(), VerdictError> {
    match value.is_finite() && ok {
        true => Ok(()),
        false => Err(VerdictError::Value {
            key: key.into(),
            value,
            unit,
            expected: expected.into(),
        }),
    }
}
