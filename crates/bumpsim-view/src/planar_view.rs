//! A planar impact result (`planar --json`, `impact --json` of a planar
//! car) as the page animates it: the body's travel x, lateral y and yaw
//! over time, the bumper's width from its segment centres (the span of the
//! centres plus one segment), and the striker's force and the yaw beside
//! it. The JSON holds no body length, so the page draws the outline
//! schematically (2.6 bumper widths long) and says so.

use serde::Serialize;
use serde_json::Value;

/// What the top view needs, in the units the page shows: ms, mm, deg, kN.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlanarView {
    /// Times, s.
    pub time: Vec<f64>,
    /// Body travel x, mm.
    pub x: Vec<f64>,
    /// Body lateral y, mm.
    pub y: Vec<f64>,
    /// Yaw, deg.
    pub yaw: Vec<f64>,
    /// Striker force, kN.
    pub force: Vec<f64>,
    /// Bumper width, mm.
    pub width: f64,
}

fn series(value: &Value, key: &str, factor: f64) -> Option<Vec<f64>> {
    value[key]
        .as_array()?
        .iter()
        .map(|v| v.as_f64().map(|x| x * factor))
        .collect()
}

/// The top view of a planar result, if `value` is one.
pub fn planar_view(value: &Value) -> Option<PlanarView> {
    let r = &value["result"];
    let time = series(r, "time", 1.0)?;
    let view = PlanarView {
        x: series(r, "x", 1e3)?,
        y: series(r, "y", 1e3)?,
        yaw: series(r, "yaw", 180.0 / std::f64::consts::PI)?,
        force: series(r, "force", 1e-3)?,
        width: width(r),
        time,
    };
    let n = view.time.len();
    let same = [&view.x, &view.y, &view.yaw, &view.force]
        .iter()
        .all(|s| s.len() == n);
    (same && n > 1).then_some(view)
}

fn width(r: &Value) -> f64 {
    let centres = series(r, "segment_centres", 1e3).unwrap_or_default();
    let low = centres.iter().copied().fold(f64::INFINITY, f64::min);
    let high = centres.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    match centres.len() {
        0 | 1 => 1500.0,
        n => (high - low) * n as f64 / (n - 1) as f64,
    }
}
