//! A planar impact result (`planar --json`, `impact --json` of a planar
//! car) as the page animates it: the body's travel x, lateral y and yaw
//! over time, the bumper's width from its segment centres (the span of the
//! centres plus one segment), and the striker's force and the yaw beside
//! it. A result that carries the car's `body` (`planar --json` writes it)
//! places the outline from the car's own numbers: the bumper line
//! `cg_behind_bumper` ahead of the CG, the front axle
//! `cg_behind_front_axle` ahead of it and the rear axle `wheelbase −
//! cg_behind_front_axle` behind it, the wheels `±track/2` aside. The car
//! file gives no overall length or width, so the outline ends at the rear
//! axle and is as wide as the wider of bumper and track, and the page says
//! so. Without `body` the outline is schematic (2.6 bumper widths long).

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
    /// The car's body geometry, when the result carries it.
    pub body: Option<BodyGeometry>,
}

/// Where the car's bumper, CG and axles lie, mm.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BodyGeometry {
    /// Bumper line ahead of the CG, mm.
    pub cg_behind_bumper: f64,
    /// Front axle ahead of the CG, mm.
    pub cg_behind_front_axle: f64,
    /// Wheelbase, mm.
    pub wheelbase: f64,
    /// Track, mm.
    pub track: f64,
}

fn body_geometry(body: &Value) -> Option<BodyGeometry> {
    let mm = |key: &str| {
        body[key]
            .as_f64()
            .filter(|v| v.is_finite() && *v > 0.0)
            .map(|v| v * 1e3)
    };
    let geometry = BodyGeometry {
        cg_behind_bumper: mm("cg_behind_bumper")?,
        cg_behind_front_axle: mm("cg_behind_front_axle")?,
        wheelbase: mm("wheelbase")?,
        track: mm("track")?,
    };
    (geometry.cg_behind_front_axle < geometry.wheelbase).then_some(geometry)
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
        body: body_geometry(&value["body"]),
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
