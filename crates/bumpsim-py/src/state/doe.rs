//! The pickled states of a `Design` and a `DoeModel` (bumpsim-doe).

use bumpsim_doe::design::Design;
use bumpsim_doe::model::{Factor, ModelFile};
use serde::{Deserialize, Serialize};

/// What a `Design` holds.
#[derive(Serialize, Deserialize, PartialEq)]
pub struct DesignState {
    /// Factor names and coded runs in standard order.
    #[serde(with = "DesignDef")]
    pub design: Design,
    /// The factors' ranges.
    pub factors: Vec<Factor>,
    /// Run order (indices into the standard order).
    pub order: Vec<usize>,
    /// Resolution of a fractional design.
    pub resolution: Option<usize>,
}

#[derive(Serialize, Deserialize)]
#[serde(remote = "Design")]
struct DesignDef {
    factors: Vec<String>,
    runs: Vec<Vec<f64>>,
}

/// What a `DoeModel` holds (its model file; CBOR keeps non-finite values).
#[derive(Serialize, Deserialize, PartialEq)]
pub struct DoeModelState(pub ModelFile);
