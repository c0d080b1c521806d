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
//!
//! Wall cells' arm ([`crate::drive::Drive::arm`]): a replay driven by a
//! load-cell wall puts each cell's line of action at λ times the lateral
//! position its crushed segments give (their loading forces at their
//! penetrations weighing their centres). Where a real bumper's stiffness
//! ends is not known to the segments, so an identification estimates λ per
//! case as a nuisance with a stated prior ([`crate::identify::Unknowns`]).
//!
//! Effective width ([`PlanarCar::effective_width`], the car file's
//! `bumper.effective_width`): the width `w_e` the segments' contact points
//! and strips span, centred on the car's axis, segment j's centre at
//! `η_j = −w_e/2 + (j + ½) w_e/S`: where the beam's stiffness acts across
//! the car, a property of the car used by every run (impacts, forward
//! predictions, replays). It defaults to the drawn `bumper.width`, which
//! alone places a striker (an overlap is a fraction of the drawn width, as
//! a lab measures it). A beam whose stiff ends reach beyond the drawn
//! segments' centres (a continuous beam whose end points carry a whole
//! point's share) acts wider than drawn; an identification may estimate it
//! with a stated prior ([`crate::identify::Unknowns::with_width`]).

use super::{PlanarCar, PlanarError, require};
use bumpsim_impact::bumper::Bumper;

/// The wall cells' arms a replay takes: a line of action moved by half of
/// itself either way is no longer the bumper's.
pub const ARM_RANGE: std::ops::RangeInclusive<f64> = 0.5..=2.0;

/// Checks a replay's wall cells' arm against [`ARM_RANGE`].
pub(crate) fn check_arm(arm: f64) -> Result<(), PlanarError> {
    let (low, high) = (ARM_RANGE.start(), ARM_RANGE.end());
    let expected = format!("the wall cells' arm, from {low} to {high}");
    require("arm", arm, "1", &expected, ARM_RANGE.contains(&arm))
}

/// The effective widths a car takes, as a fraction of its drawn width: a
/// beam acting half or twice as wide as it is drawn is another beam.
pub const EFFECTIVE_WIDTH_RANGE: std::ops::RangeInclusive<f64> = 0.5..=2.0;

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

    /// The same car with its segments' contact points spread over `width`
    /// (m, within [`EFFECTIVE_WIDTH_RANGE`] of the drawn width; see the
    /// module).
    pub fn with_effective_width(mut self, width: f64) -> Result<PlanarCar, PlanarError> {
        let drawn = self.beam.width;
        let (low, high) = (EFFECTIVE_WIDTH_RANGE.start(), EFFECTIVE_WIDTH_RANGE.end());
        let expected = format!(
            "from {low} to {high} times bumper.width ({drawn} m): where the segments' contact points reach"
        );
        let ratio = width / drawn;
        let ok = EFFECTIVE_WIDTH_RANGE.contains(&ratio);
        require("bumper.effective_width", width, "m", &expected, ok)?;
        self.effective_width = width;
        Ok(self)
    }

    /// The width the segments' contact points span, m (the drawn
    /// `bumper.width` unless given; see the module).
    pub fn effective_width(&self) -> f64 {
        self.effective_width
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

#[cfg(test)]
mod tests {
    use crate::car::{Layout, PlanarCar};
    use crate::drive::{Drive, Load, drive};
    use crate::simulate::{Settings, simulate};
    use crate::striker::{Face, Striker};
    use bumpsim_core::model::MsdModel;
    use bumpsim_impact::bumper::Bumper;

    fn car() -> PlanarCar {
        let chain = MsdModel::new(vec![8.0, 1200.0], vec![2e3], vec![1.5e6]).unwrap();
        let bumper = Bumper::three_part(1.5e6, 60e3, 6e6).unwrap();
        PlanarCar::symmetric(&chain, &bumper, &Layout::default()).unwrap()
    }

    #[test]
    fn the_rate_is_checked_written_and_read_back() {
        for bad in [-0.1, f64::NAN, 11.0] {
            let err = car().with_contact_rate(bad).unwrap_err().to_string();
            assert!(err.contains("bumper.rate"), "{err}");
        }
        let rated = car().with_contact_rate(0.375).unwrap();
        let text = rated.to_toml();
        assert!(text.contains("rate = 0.375"), "{text}");
        assert_eq!(PlanarCar::parse(&text, "car.toml".as_ref()).unwrap(), rated);
        assert!(!car().to_toml().contains("rate ="), "no rate, no key");
    }

    /// Hunt–Crossley: the rate term stiffens the loading, so the force
    /// rises faster (its first 3 ms carry 1.5 times the impulse; the peak,
    /// at the largest crush where ḋ = 0, stays on the plateau), and the
    /// energy balance still closes (crush work from the rated force).
    #[test]
    fn the_rate_stiffens_the_loading_and_takes_energy() {
        let striker = Striker::pendulum(Face::flat(), 1000.0, 3.0);
        let settings = Settings {
            output_step: 1e-4,
            duration: 0.15,
            stop_after_contact: false,
            ..Settings::default()
        };
        let plain = simulate(&car(), &striker, &settings).unwrap();
        let rated = simulate(&car().with_contact_rate(0.4).unwrap(), &striker, &settings).unwrap();
        let peak = |f: &[f64]| f.iter().fold(0.0f64, |m, v| m.max(*v));
        let early = |f: &[f64]| f[..30].iter().sum::<f64>();
        eprintln!(
            "peaks {} {} N, early {} {}",
            peak(&rated.force),
            peak(&plain.force),
            early(&rated.force),
            early(&plain.force)
        );
        assert!(early(&rated.force) > 1.2 * early(&plain.force));
        assert!(
            rated.warnings.iter().all(|w| !w.contains("energy")),
            "{:?}",
            rated.warnings
        );
    }

    /// A wall cell's line of action times the drive's arm: a cell over the
    /// left half of a flat face 1 cm into the bumper (every segment in its
    /// band crushed alike: the line at the band's centre, 0.4 m) turns the
    /// car as a load at 0.4 m, and with arm 1.1 as one at 0.44 m (to the
    /// small shift the car's own motion gives the crushed segments: below
    /// 2 % of the yaw the 4 cm move it by; measured 1.2 and 1.4 %).
    #[test]
    fn a_wall_cells_line_of_action_moves_with_the_arm() {
        // a rigid car: its bumper line stays straight
        let chain = MsdModel::new(vec![1200.0], vec![], vec![]).unwrap();
        let bumper = Bumper::three_part(1.5e6, 60e3, 6e6).unwrap();
        let car = PlanarCar::symmetric(&chain, &bumper, &Layout::default()).unwrap();
        let x_f = car.body().cg_behind_bumper;
        let load = |lateral: f64, cell: bool| Load {
            lateral,
            anchor: cell.then_some([x_f - 0.01, 0.4]),
            cell: cell.then_some(0.8),
            direction: [-1.0, 0.0],
            force: vec![2e3; 501],
        };
        let yaw = |l: Load, arm: f64| {
            let input = Drive {
                step: 1e-4,
                loads: vec![l],
                speed: 0.0,
                arm,
                sensors: vec![],
            };
            *drive(&car, &input, 0.05).unwrap().yaw.last().unwrap()
        };
        let (fixed, moved) = (yaw(load(0.4, false), 1.0), yaw(load(0.44, false), 1.0));
        let (cell, armed) = (yaw(load(0.0, true), 1.0), yaw(load(0.0, true), 1.1));
        eprintln!("yaw: fixed {fixed:e} {moved:e}, cell {cell:e} {armed:e} rad");
        assert!((cell - fixed).abs() < 0.02 * (moved - fixed).abs());
        assert!((armed - moved).abs() < 0.02 * (moved - fixed).abs());
        for bad in [0.4, 2.5, f64::NAN] {
            let input = Drive {
                step: 1e-4,
                loads: vec![load(0.0, true)],
                speed: 0.0,
                arm: bad,
                sensors: vec![],
            };
            let err = drive(&car, &input, 0.05).unwrap_err().to_string();
            assert!(err.contains("arm"), "{err}");
        }
    }
    /// The effective width is checked, written and read back, and kept by
    /// a car made again from its chains; absent, it is the drawn width.
    #[test]
    fn the_effective_width_is_checked_written_and_read_back() {
        let drawn = car().beam().width;
        assert_eq!(car().effective_width(), drawn);
        for bad in [0.4 * drawn, 2.1 * drawn, f64::NAN, -1.0] {
            let err = car().with_effective_width(bad).unwrap_err().to_string();
            assert!(err.contains("bumper.effective_width"), "{err}");
        }
        let wide = car().with_effective_width(1.05 * drawn).unwrap();
        let text = wide.to_toml();
        assert!(text.contains("effective_width = "), "{text}");
        assert_eq!(PlanarCar::parse(&text, "car.toml".as_ref()).unwrap(), wide);
        assert!(!car().to_toml().contains("effective_width"), "none, no key");
        let bad = text.replace("effective_width = ", "effective_width = 9");
        let err = PlanarCar::parse(&bad, "car.toml".as_ref()).unwrap_err();
        assert!(err.to_string().contains("bumper.effective_width"), "{err}");
    }

    /// The effective width places the contact points as a beam drawn that
    /// wide does: a pole 0.6 m left of the axis strikes a 1.6 m beam acting
    /// 1.76 m wide exactly as it strikes a beam drawn 1.76 m wide (the same
    /// segments' centres, the same forces, the same yaw), and not as the
    /// 1.6 m beam (its segments 1.6–7.2 cm further in).
    #[test]
    fn the_effective_width_places_the_contact_points() {
        let drawn = car();
        let layout = Layout {
            bumper_width: 1.1 * drawn.beam().width,
            ..Layout::default()
        };
        let chain = MsdModel::new(vec![8.0, 1200.0], vec![2e3], vec![1.5e6]).unwrap();
        let bumper = Bumper::three_part(1.5e6, 60e3, 6e6).unwrap();
        let wider = PlanarCar::symmetric(&chain, &bumper, &layout).unwrap();
        let acting = car().with_effective_width(layout.bumper_width).unwrap();
        let striker = Striker::pendulum(Face::pole_of_diameter(0.2, 0.6), 1000.0, 3.0);
        let settings = Settings {
            output_step: 1e-4,
            duration: 0.05,
            ..Settings::default()
        };
        let run = |c: &PlanarCar| simulate(c, &striker, &settings).unwrap();
        let (a, b, c) = (run(&acting), run(&wider), run(&drawn));
        assert_eq!(a.segment_centres, b.segment_centres);
        let last = |r: &crate::result::PlanarResult| *r.yaw.last().unwrap();
        eprintln!(
            "yaw: acting {} wider {} drawn {} rad",
            last(&a),
            last(&b),
            last(&c)
        );
        assert!((last(&a) - last(&b)).abs() <= 1e-12 * last(&b).abs());
        assert!((last(&a) - last(&c)).abs() > 0.02 * last(&c).abs());
    }
}
