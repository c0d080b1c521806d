//! The bumper's contact law beyond its characteristic: other segments, and
//! a rate term (the fitted bumper, [`crate::identify::fit_bumper`]).
//!
//! Rate term (Hunt & Crossley 1975, as their contact `F = k dⁿ (1 + 3/2 α ḋ)`
//! writes it): each segment's force from its characteristic and block,
//! `F(d)`, is multiplied by `max(0, 1 + c ḋ)`, `ḋ` the segment's crush rate
//! over the last step and `c = 3/2 α` (s/m, ≥ 0). It stiffens the contact
//! while the bumper is crushed and softens it while the bumper springs
//! back: the work it takes is part of the crush work. `c = 0` (every car
//! unless asked) leaves the characteristic as it is.

use super::{PlanarCar, PlanarError, require};
use bumpsim_impact::bumper::Bumper;

/// Largest rate coefficient a car may carry, s/m.
pub const MAX_CONTACT_RATE: f64 = 10.0;

impl PlanarCar {
    /// The same car with other bumper segments (checked: as many as before).
    pub fn with_segments(mut self, segments: Vec<Bumper>) -> Result<PlanarCar, PlanarError> {
        let n = self.beam.segments.len();
        require(
            "bumper.segments",
            segments.len() as f64,
            "",
            "as many as the car's",
            segments.len() == n,
        )?;
        self.beam.segments = segments;
        super::check_beam(&self.beam)?;
        Ok(self)
    }

    /// The same car with the contact's rate coefficient `c` (s/m, from 0 to
    /// [`MAX_CONTACT_RATE`]; see the module).
    pub fn with_contact_rate(mut self, rate: f64) -> Result<PlanarCar, PlanarError> {
        require(
            "bumper.rate",
            rate,
            "s/m",
            "from 0 to 10 s/m",
            (0.0..=MAX_CONTACT_RATE).contains(&rate),
        )?;
        self.contact_rate = rate;
        Ok(self)
    }

    /// The contact's rate coefficient `c`, s/m (0: none).
    pub fn contact_rate(&self) -> f64 {
        self.contact_rate
    }
}

/// Each segment's characteristic force multiplied by `max(0, 1 + rate ·
/// (crush − previous)/step)`, its total (with the bending coupling) moved
/// by as much.
pub(crate) fn rated(c: &mut crate::dynamics::Contact, previous: &[f64], rate: f64, step: f64) {
    for (j, p) in previous.iter().enumerate() {
        let factor = (1.0 + rate * (c.crush[j] - p) / step).max(0.0);
        let added = c.force[j] * (factor - 1.0);
        c.force[j] += added;
        c.total[j] += added;
    }
}
