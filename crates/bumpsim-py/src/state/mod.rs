//! Pickling (issue 38): every public class pickles, and
//! `pickle.loads(pickle.dumps(x)) == x`. A class with a Python constructor
//! pickles as its constructor's arguments; the others as `(cls._from_state,
//! (state,))`, the state being the object's library values as CBOR bytes
//! (exact floats, NaN and infinities included), so a worker process sends
//! its result whole and nothing is computed again when it is loaded.
//!
//! The library's result types serialise (for the CLI's JSON) but do not
//! deserialise; the submodules mirror them field by field with serde's
//! `remote` derive, which names every field both ways, so a field added to
//! a library type fails the build here instead of being dropped silently.

pub mod campaign;
pub mod doe;
pub mod ident;
pub mod impact;
pub mod verdict;

use crate::errors::invalid;
use pyo3::prelude::*;
use pyo3::types::PyBytes;
use serde::Serialize;
use serde::de::DeserializeOwned;

/// `value` as CBOR bytes.
pub fn encode<T: Serialize>(value: &T) -> PyResult<Vec<u8>> {
    let mut bytes = Vec::new();
    ciborium::into_writer(value, &mut bytes).map_err(|e| invalid(format!("cannot pickle: {e}")))?;
    Ok(bytes)
}

/// Whether two states are the same, bit for bit (NaN equal to NaN): the
/// equality of classes whose state holds floats that may be NaN.
pub fn same<T: Serialize>(a: &T, b: &T) -> PyResult<bool> {
    Ok(encode(a)? == encode(b)?)
}

/// A value from CBOR bytes made by [`encode`]; `what` names the class.
pub fn decode<T: DeserializeOwned>(bytes: &[u8], what: &str) -> PyResult<T> {
    ciborium::from_reader(bytes).map_err(|e| {
        invalid(format!(
            "cannot unpickle a {what}: {e} (pickled by another bumpsim version?)"
        ))
    })
}

/// `(type(obj)._from_state, (state,))`, what `__reduce__` returns.
pub fn reduce<'py>(
    obj: &Bound<'py, PyAny>,
    state: &[u8],
) -> PyResult<(Bound<'py, PyAny>, (Bound<'py, PyBytes>,))> {
    let restore = obj.get_type().getattr("_from_state")?;
    Ok((restore, (PyBytes::new(obj.py(), state),)))
}

/// A `with` module for a `Vec` of a remote type: `remote_seq!(name, Type, "Def")`.
macro_rules! remote_seq {
    ($module:ident, $ty:ty, $def:literal) => {
        mod $module {
            use super::*;
            #[derive(serde::Serialize, serde::Deserialize)]
            struct Item(#[serde(with = $def)] $ty);
            pub fn serialize<S: serde::Serializer>(
                values: &[$ty],
                s: S,
            ) -> Result<S::Ok, S::Error> {
                s.collect_seq(values.iter().map(|v| Item(v.clone())))
            }
            pub fn deserialize<'de, D: serde::Deserializer<'de>>(
                d: D,
            ) -> Result<Vec<$ty>, D::Error> {
                let items: Vec<Item> = serde::Deserialize::deserialize(d)?;
                Ok(items.into_iter().map(|i| i.0).collect())
            }
        }
    };
}

/// A `with` module for an `Option` of a remote type.
macro_rules! remote_option {
    ($module:ident, $ty:ty, $def:literal) => {
        mod $module {
            use super::*;
            #[derive(serde::Serialize, serde::Deserialize)]
            struct Item(#[serde(with = $def)] $ty);
            pub fn serialize<S: serde::Serializer>(
                value: &Option<$ty>,
                s: S,
            ) -> Result<S::Ok, S::Error> {
                serde::Serialize::serialize(&value.clone().map(Item), s)
            }
            pub fn deserialize<'de, D: serde::Deserializer<'de>>(
                d: D,
            ) -> Result<Option<$ty>, D::Error> {
                let item: Option<Item> = serde::Deserialize::deserialize(d)?;
                Ok(item.map(|i| i.0))
            }
        }
    };
}

pub(crate) use {remote_option, remote_seq};
