//! A car file a front end holds in memory (the Python module's car
//! objects): its path, its text and the kind of model it is read as, so
//! that every request reads it through the registered model
//! ([`crate::model::CarModel::car`]) as it would read the file. The front
//! end names no model's crate for it. No equations here.

use crate::EngineError;
use crate::model::{CarText, End};
use crate::registry::model;
use bumpsim_io::kind::{KindError, ModelKind};
use std::path::{Path, PathBuf};

/// A car file held in memory, read as a car of its kind.
#[derive(Debug, Clone)]
pub struct HeldCar {
    kind: ModelKind,
    path: PathBuf,
    text: String,
    read: CarText,
}

impl HeldCar {
    /// The car file at `path` read as a car of `kind` (the model the front
    /// end's object stands for): the model's reader refuses a file that is
    /// not such a car in its own words.
    pub fn read(path: &Path, kind: ModelKind) -> Result<HeldCar, EngineError> {
        let read = model(kind, "car")?.car(path, None)?;
        let text = std::fs::read_to_string(path).map_err(KindError::Read)?;
        Ok(HeldCar {
            kind,
            path: path.to_path_buf(),
            text,
            read,
        })
    }

    /// The car of a file's `text` (a file of `kind` at `path`, which names
    /// the files it refers to).
    pub fn parse(text: &str, path: &Path, kind: ModelKind) -> Result<HeldCar, EngineError> {
        let read = model(kind, "car")?.car(path, Some(text))?;
        Ok(HeldCar {
            kind,
            path: path.to_path_buf(),
            text: text.to_string(),
            read,
        })
    }

    /// The model kind it is read as.
    pub fn kind(&self) -> ModelKind {
        self.kind
    }

    /// The file it was read from (or that its text names).
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The file's text, as read.
    pub fn text(&self) -> &str {
        &self.text
    }

    /// The name the file gives, if any.
    pub fn name(&self) -> Option<&str> {
        self.read.name.as_deref()
    }

    /// The car as one end of a verdict's car.
    pub fn end(&self) -> End<'_> {
        End::Held {
            path: &self.path,
            text: &self.text,
            kind: self.kind,
        }
    }

    /// The car as its model writes its file (it reads back to the same car).
    pub fn to_toml(&self) -> &str {
        &self.read.toml
    }
}

/// Two held cars are the same car from the same path (their files may be
/// written differently).
impl PartialEq for HeldCar {
    fn eq(&self, other: &Self) -> bool {
        self.kind == other.kind && self.path == other.path && self.read == other.read
    }
}
