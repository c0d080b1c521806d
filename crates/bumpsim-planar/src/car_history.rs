//! What earlier impacts and the test's load leave on a planar car (issue 45
//! item 2): each bumper segment's history — its largest crush and force, so
//! its permanent set — and the passengers of a laden run, added at the body's
//! centre of gravity with the yaw inertia scaled by (M + m)/M.

use super::{PlanarCar, PlanarError, require};
use bumpsim_impact::bumper::BumperState;

impl PlanarCar {
    /// The same car carrying the damage earlier impacts left: each
    /// segment's history (largest crush and its force, so its permanent
    /// set), right to left; empty: undamaged. A test run after others on
    /// the same car starts from it (issue 45 item 2): a segment then
    /// carries no force until it is pushed past its set and reloads along
    /// its unloading line.
    pub fn with_damage(mut self, damage: Vec<BumperState>) -> Result<PlanarCar, PlanarError> {
        let n = self.beam.segments.len();
        require(
            "damage",
            damage.len() as f64,
            "segments",
            &format!("one history per segment ({n}), or none"),
            damage.is_empty() || damage.len() == n,
        )?;
        for (j, d) in damage.iter().enumerate() {
            require(
                &format!("damage[{j}].max_compression"),
                d.max_compression,
                "m",
                "must be finite and not negative",
                d.max_compression >= 0.0 && d.peak_force.is_finite() && d.peak_force >= 0.0,
            )?;
        }
        self.damage = damage;
        Ok(self)
    }

    /// The damage earlier impacts left (see [`PlanarCar::with_damage`]).
    pub fn damage(&self) -> &[BumperState] {
        &self.damage
    }

    /// The same car with `load` kg (≥ 0) more at the body's CG, `I_z` × (M + m)/M (R42's passengers).
    pub fn with_load(mut self, load: f64) -> Result<PlanarCar, PlanarError> {
        require("load", load, "kg", "finite and not negative", load >= 0.0)?;
        self.body.yaw_inertia *= (self.body.mass + load) / self.body.mass;
        self.body.mass += load;
        Ok(self)
    }
}
