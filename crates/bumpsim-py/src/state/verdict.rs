//! The state of a `Verdict` (bumpsim-verdict) and a `BumperTarget`.
//!
//! A verdict is kept as what the Python object shows: per test its
//! criteria (value, limit, margin and outcome as the library judged them),
//! pulse metrics, energies and binding criterion, read from the library's
//! result once; its JSON and text as the library wrote them. Nothing is
//! judged here, and a field the library adds to its result reaches the JSON
//! without a change here. The target region is kept whole, mirrored field
//! by field (serde's `remote` derive), so a field added to it fails the
//! build here instead of being dropped silently.

use bumpsim_verdict::target::{Bound, Corridor, Region, Row};
use serde::{Deserialize, Serialize};

/// What a `Verdict` holds.
#[derive(Serialize, Deserialize)]
pub struct VerdictState {
    /// The car's name.
    pub car: String,
    /// The margin ratio asked for.
    pub margin: f64,
    /// Whether every assessed test passes.
    pub passed: bool,
    /// The failing criteria: (test, criterion).
    pub failures: Vec<(String, String)>,
    /// Every test, in the order asked.
    pub tests: Vec<TestView>,
    /// The verdict as the library serialises it (the CLI's `verdict`).
    pub json: String,
    /// The tables `bumpsim verdict` prints.
    pub text: String,
    /// The bumper target region, when searched.
    #[serde(with = "region")]
    pub target: Option<Region>,
}

/// One test of a verdict.
#[derive(Serialize, Deserialize)]
pub struct TestView {
    /// The test's name.
    pub name: String,
    /// The end it strikes.
    pub end: String,
    /// The striker as run.
    pub striker: String,
    /// Why it was not assessed (None: it was).
    pub skipped: Option<String>,
    /// Whether every judged criterion passes (None: not assessed).
    pub passed: Option<bool>,
    /// The judged criterion of least margin ratio: its name and ratio.
    pub binding: Option<(String, f64)>,
    /// Its criteria.
    pub criteria: Vec<CriterionView>,
    /// Peak, 3 ms clip, delta-V, OLC, ASI (SI; None: not computed).
    pub metrics: Option<[Option<f64>; 5]>,
    /// Initial, bumper, absorber, structure, kinetic, tyres (J) and the
    /// bumper's share (1).
    pub energies: Option<[f64; 7]>,
}

/// One criterion of a test.
#[derive(Serialize, Deserialize)]
pub struct CriterionView {
    /// What it is.
    pub name: String,
    /// Where or how it was reached.
    pub detail: String,
    /// The SI unit of value, limit and margin.
    pub unit: String,
    /// The value reached, SI.
    pub value: f64,
    /// The limit, SI.
    pub limit: f64,
    /// Whether the value must stay at or below the limit.
    pub upper: bool,
    /// The margin, SI.
    pub margin: f64,
    /// The margin over the limit, 1.
    pub ratio: f64,
    /// pass, fail or info.
    pub outcome: String,
}

/// What a `BumperTarget` holds.
#[derive(Serialize, Deserialize)]
pub struct RegionState(#[serde(with = "RegionDef")] pub Region);

#[derive(Serialize, Deserialize)]
#[serde(remote = "Bound")]
struct BoundDef {
    force: f64,
    binding: Option<String>,
}

/// A row's passing interval: its two bounds, or None.
mod interval {
    use super::*;
    #[derive(Serialize, Deserialize)]
    struct Pair(
        #[serde(with = "BoundDef")] Bound,
        #[serde(with = "BoundDef")] Bound,
    );
    pub fn serialize<S: serde::Serializer>(
        value: &Option<[Bound; 2]>,
        s: S,
    ) -> Result<S::Ok, S::Error> {
        let pair = value.clone().map(|[a, b]| Pair(a, b));
        pair.serialize(s)
    }
    pub fn deserialize<'de, D: serde::Deserializer<'de>>(
        d: D,
    ) -> Result<Option<[Bound; 2]>, D::Error> {
        let pair: Option<Pair> = Option::deserialize(d)?;
        Ok(pair.map(|Pair(a, b)| [a, b]))
    }
}

#[derive(Serialize, Deserialize)]
#[serde(remote = "Row")]
struct RowDef {
    stiffness: f64,
    #[serde(with = "interval")]
    interval: Option<[Bound; 2]>,
    stroke: Option<f64>,
    failing: Option<String>,
}

super::remote_seq!(rows, Row, "RowDef");

#[derive(Serialize, Deserialize)]
#[serde(remote = "Corridor")]
struct CorridorDef {
    deflection: Vec<f64>,
    lower: Vec<f64>,
    upper: Vec<f64>,
}

#[derive(Serialize, Deserialize)]
#[serde(remote = "Region")]
struct RegionDef {
    origin: [f64; 2],
    tabulated: bool,
    margin: f64,
    #[serde(with = "rows")]
    rows: Vec<Row>,
    #[serde(with = "CorridorDef")]
    corridor: Corridor,
    impacts: usize,
    seconds: f64,
    #[serde(default)]
    diagnosis: Option<String>,
}

super::remote_option!(region, Region, "RegionDef");
