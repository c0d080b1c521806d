//! Car files: an MSD car model in TOML (docs/formats.md).
//!
//! ```toml
//! name = "Volvo S40 2004, thesis 3-DOF result"   # optional
//! masses = [1.8, 74.8, 1670.0]                   # kg, m1 carries the bumper
//! dampers = [6.46e6, 1.97e5]                     # N·s/m, c1 between m1 and m2, ...
//! springs = [4.75e5, 5.0e5]                      # N/m
//! ```
//!
//! Values are SI. A one-mass car (a rigid vehicle) has empty or absent
//! `dampers` and `springs`. Unknown keys are errors, so a typo such as
//! `spring = [...]` is never silently ignored. The model is validated by
//! [`bumpsim_core::model::MsdModel::new`]; its error names the parameter.
//!
//! ```
//! use bumpsim_io::car::Car;
//! let car = Car::parse("masses = [1000.0]", "rigid.toml".as_ref()).unwrap();
//! assert_eq!(car.model.dof(), 1);
//! assert!(Car::parse("masses = [1000.0]\nspring = [1.0]", "typo.toml".as_ref()).is_err());
//! ```

use bumpsim_core::model::{ModelError, ModelFields, MsdModel};
use std::path::{Path, PathBuf};

/// A named car model.
#[derive(Debug, Clone, PartialEq)]
pub struct Car {
    /// Optional name from the file.
    pub name: Option<String>,
    /// The validated model.
    pub model: MsdModel,
}

/// A car file that cannot be used.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum CarError {
    /// The file cannot be read.
    #[error("{path}: cannot read: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// Not valid TOML, a key missing or unknown, or a value of the wrong type.
    #[error("{path}: {message}")]
    Syntax {
        /// The file.
        path: PathBuf,
        /// The parser's message, with line and column.
        message: String,
    },
    /// The values do not make a valid model.
    #[error("{path}: {source}")]
    Model {
        /// The file.
        path: PathBuf,
        /// Which parameter and why.
        source: ModelError,
    },
    /// A key of a nonlinear link (or of a car with links) is missing,
    /// unknown or out of range ([`crate::link_car`]).
    #[error("{path}: {link}: {key}: {reason}")]
    LinkKey {
        /// The file.
        path: PathBuf,
        /// `link j`, `front link` or `car`.
        link: String,
        /// The key.
        key: String,
        /// What is wrong.
        reason: String,
    },
    /// A link's values do not make a valid link.
    #[error("{path}: {link}: {source}")]
    Link {
        /// The file.
        path: PathBuf,
        /// `link j` or `front link`.
        link: String,
        /// Which parameter and why.
        source: bumpsim_core::link::LinkError,
    },
    /// A car with nonlinear links given to a reader of linear cars.
    #[error(
        "{path}: a chain with nonlinear links ([[links]] or [front]): this command reads linear cars (springs = [...]) only; `bumpsim export lsdyna` and `bumpsim export calculix` read this file"
    )]
    NonlinearLinks {
        /// The file.
        path: PathBuf,
    },
    /// The file cannot be written.
    #[error("{path}: cannot write: {source}")]
    Write {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// The output is refused (it would land on an input) or cannot be written.
    #[error(transparent)]
    Output(#[from] crate::output::OutputError),
    /// The file is not a regular file, too large or not text.
    #[error(transparent)]
    Read(#[from] bumpsim_core::files::ReadError),
}

/// Refuses a JSON model whose `dof` (as an identification result states
/// it) is not its number of masses: the model would run with another DOF
/// than the file says.
fn check_dof(
    object: &serde_json::Map<String, serde_json::Value>,
    path: &Path,
) -> Result<(), CarError> {
    let masses = object
        .get("masses")
        .and_then(|m| m.as_array())
        .map(Vec::len);
    match (object.get("dof"), masses) {
        (Some(dof), Some(n)) if dof.is_number() && dof.as_u64() != Some(n as u64) => {
            Err(CarError::Syntax {
                path: path.into(),
                message: format!("\"dof\": {dof}, but {n} masses are given: one of them is wrong"),
            })
        }
        _ => Ok(()),
    }
}

/// A car file's fields ([`ModelFields`]: the model's, and the car's name)
/// as the car it gives, the model validated.
fn into_car(fields: ModelFields, path: &Path) -> Result<Car, CarError> {
    let name = fields.name.clone();
    let model = fields.into_model().map_err(|source| CarError::Model {
        path: path.into(),
        source,
    })?;
    Ok(Car { name, model })
}

/// Whether a car file's TOML holds nonlinear links (`[[links]]` or
/// `[front]`, [`crate::link_car`]): the chain's two file forms, told apart
/// by the chain's own reader.
pub fn has_links(table: &toml::Table) -> bool {
    table.contains_key("links") || table.contains_key("front")
}

fn read_text(path: &Path) -> Result<String, CarError> {
    Ok(bumpsim_core::files::read_text(path)?)
}

impl Car {
    /// Reads a car file (at most `bumpsim_core::files::MAX_CAR_BYTES`).
    pub fn read(path: &Path) -> Result<Car, CarError> {
        Self::parse(&bumpsim_core::files::read_car_text(path)?, path)
    }

    /// Reads a model from a car TOML file or, for a `.json` file, from the
    /// `masses`, `dampers`, `springs` (SI) and optional `name` fields of a JSON
    /// object such as an identification result; its other fields are not model
    /// data and are left alone.
    pub fn read_model_file(path: &Path) -> Result<Car, CarError> {
        if path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("json"))
        {
            return Self::parse_json(&read_text(path)?, path);
        }
        Self::read(path)
    }

    /// Parses the model fields of a JSON object; `path` is used in messages.
    pub fn parse_json(text: &str, path: &Path) -> Result<Car, CarError> {
        let syntax = |e: serde_json::Error| CarError::Syntax {
            path: path.into(),
            message: e.to_string(),
        };
        let mut object: serde_json::Map<String, serde_json::Value> =
            serde_json::from_str(text).map_err(syntax)?;
        check_dof(&object, path)?;
        // the model fields only: a result's other fields are not car-file keys
        object.retain(|key, _| ["name", "masses", "dampers", "springs"].contains(&key.as_str()));
        let fields: ModelFields =
            serde_json::from_value(serde_json::Value::Object(object)).map_err(syntax)?;
        into_car(fields, path)
    }

    /// Parses car TOML; `path` is used in messages.
    pub fn parse(text: &str, path: &Path) -> Result<Car, CarError> {
        let fields: ModelFields =
            toml::from_str(text).map_err(|e| match toml::from_str::<toml::Table>(text) {
                Ok(table) if has_links(&table) => CarError::NonlinearLinks { path: path.into() },
                _ => CarError::Syntax {
                    path: path.into(),
                    message: crate::toml_message(text, &e),
                },
            })?;
        into_car(fields, path)
    }

    /// The car as TOML text, in the format [`Car::parse`] reads.
    pub fn to_toml(&self) -> String {
        let fields = ModelFields {
            name: self.name.clone(),
            ..ModelFields::from(self.model.clone())
        };
        let body = toml::to_string(&fields).unwrap_or_default();
        format!("# bumpsim car model: masses kg, dampers N*s/m, springs N/m\n{body}")
    }

    /// Writes the car as TOML.
    pub fn write(&self, path: &Path) -> Result<(), CarError> {
        crate::output::write_file(path, self.to_toml().as_bytes())?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Car, CarError> {
        Car::parse(text, Path::new("car.toml"))
    }

    #[test]
    fn round_trips_through_toml() {
        let car = parse("name = \"S40\"\nmasses = [1.8, 74.8, 1670]\ndampers = [6.46e6, 1.97e5]\nsprings = [4.75e5, 5e5]\n").unwrap();
        assert_eq!(parse(&car.to_toml()).unwrap(), car);
    }

    #[test]
    fn json_results_provide_the_model_fields() {
        let json = r#"{"dof": 2, "masses": [1.0, 2.0], "dampers": [3.0], "springs": [4.0], "objective": 0.5}"#;
        // issue 34: "dof": 3 with two masses ran as 2-DOF
        let three = json.replacen("\"dof\": 2", "\"dof\": 3", 1);
        let e = Car::parse_json(&three, Path::new("r.json")).unwrap_err();
        assert!(e.to_string().contains("\"dof\": 3, but 2 masses"), "{e}");
        let car = Car::parse_json(json, Path::new("r.json")).unwrap();
        assert_eq!(car.model.parameters(), vec![1.0, 2.0, 3.0, 4.0]);
        let err = Car::parse_json(r#"{"masses": [0.0]}"#, Path::new("r.json")).unwrap_err();
        assert!(err.to_string().starts_with("r.json: m1 = 0 kg"), "{err}");
        let err = Car::parse_json("{", Path::new("r.json")).unwrap_err();
        assert!(err.to_string().contains("line 1"), "{err}");
    }

    use proptest::prelude::*;

    /// A positive finite value from 1e-300 to 1e300.
    fn positive() -> impl Strategy<Value = f64> {
        (1.0..10.0f64, -300..300i32).prop_map(|(m, e)| m * 10f64.powi(e))
    }

    /// A drawn car: 1 to 6 masses, dampers 0 or positive, any name TOML
    /// must escape (quotes, backslashes, controls, non-ASCII) or none.
    fn car() -> impl Strategy<Value = Car> {
        let name = proptest::option::of("[a-zA-Z0-9 \"\\\\\t\u{1}\u{e9}\u{3a9}#=\\[\\]]{0,20}");
        (1..7usize, name).prop_flat_map(|(dof, name)| {
            let damper = prop_oneof![Just(0.0), positive()];
            (
                prop::collection::vec(positive(), dof),
                prop::collection::vec(damper, dof - 1),
                prop::collection::vec(positive(), dof - 1),
                Just(name),
            )
                .prop_map(|(m, c, k, name)| Car {
                    name,
                    model: MsdModel::new(m, c, k).unwrap(),
                })
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// Issue 34: a car bumpsim writes reads back equal, bit for bit.
        #[test]
        fn whatever_car_is_written_reads_back_equal(car in car()) {
            let text = car.to_toml();
            prop_assert_eq!(parse(&text).unwrap(), car);
        }
    }

    #[test]
    fn errors_name_file_and_problem() {
        let cases = [
            (
                "masses = [1.0, 2.0]\nsprings = [1.0]\n",
                "0 dampers given for 2 masses",
            ),
            (
                "masses = [1.0, -2.0]\ndampers = [0.0]\nsprings = [1.0]\n",
                "m2 = -2 kg",
            ),
            ("masses = [1.0]\nmass = 2\n", "unknown field `mass`"),
            ("dampers = []\n", "missing field `masses`"),
            ("masses = [1.0,\n", "line 1"),
            ("masses = [\"heavy\"]\n", "invalid type"),
            ("masses = [nan]\n", "m1 = NaN kg"),
        ];
        for (text, expected) in cases {
            let err = parse(text).unwrap_err().to_string();
            assert!(
                err.starts_with("car.toml: ") && err.contains(expected),
                "{text:?}: {err}"
            );
        }
    }
}
