//! The state a planar car carries through a step besides its coordinates:
//! the bumper segments' contact (see `dynamics`) and the side members'
//! nonlinear links (issue 46 item 2, [`bumpsim_core::link`]).
//!
//! A nonlinear link's crush is the side member's compression
//! `δ = −(u_front − u_back)`; its force `F = L(δ)` (compression positive)
//! follows its loading curve while δ passes its largest value so far and
//! its unloading rule below it, so each link remembers δ_max
//! ([`LinkState`]). The histories are updated once per step, after the
//! positions move and before the accelerations there ([`Model::hold`]),
//! as the 1-D chain does ([`bumpsim_core::chain`]); the energy balance
//! counts each link's elastic energy in `springs` and its plastic work
//! `W_p = E_L(δ_max) − F_max²/(2 k_e)` in `plastic`.

use super::{Contact, Model};
use crate::car::PlanarCar;
use crate::result::Bottomed;
use crate::striker::Placed;
use bumpsim_core::link::LinkState;
use bumpsim_impact::bumper::{Bumper, BumperState};

impl Model {
    /// Updates each nonlinear link's force and history at positions `q`
    /// (linear links need neither).
    pub fn hold(&self, q: &[f64], c: &mut Contact) {
        if c.links.len() != self.links.len() {
            c.links = vec![LinkState::default(); self.links.len()];
            c.link_force = vec![0.0; self.links.len()];
        }
        for (k, l) in self.links.iter().enumerate() {
            if let Some(law) = &l.law {
                c.link_force[k] = law.force(-l.stretch(q), &mut c.links[k]);
            }
        }
    }

    /// The plastic work of the nonlinear links so far, J.
    pub fn plastic_work(&self, c: &Contact) -> f64 {
        self.links
            .iter()
            .zip(&c.links)
            .filter_map(|(l, s)| l.law.as_ref().map(|law| s.dissipated(law)))
            .sum()
    }

    /// Each link's plastic set and largest compression, m (empty when
    /// every link is linear).
    pub fn link_sets(&self, c: &Contact) -> (Vec<f64>, Vec<f64>) {
        if self.links.iter().all(|l| l.law.is_none()) || c.links.len() != self.links.len() {
            return (Vec::new(), Vec::new());
        }
        self.links
            .iter()
            .zip(&c.links)
            .map(|(l, s)| match &l.law {
                Some(law) => (s.plastic_set(law), s.reached),
                None => (0.0, 0.0),
            })
            .unzip()
    }
}

impl Contact {
    /// The first segment whose own crush (without the absorber's) has
    /// passed the depth of `car`'s block, if any, as bottomed at `time` (s).
    pub fn bottomed(&self, car: &PlanarCar, time: f64) -> Option<Bottomed> {
        let block = car.beam().block?;
        let segment =
            (0..self.crush.len()).find(|&j| self.crush[j] - self.absorber[j] > block.depth)?;
        let centre = car.segment_centre(segment);
        Some(Bottomed {
            time,
            segment,
            centre,
        })
    }

    /// [`Contact::new`] with the segments' histories `damage` left by
    /// earlier impacts (empty: undamaged).
    pub fn damaged(segments: usize, damage: &[BumperState]) -> Contact {
        let mut c = Contact::new(segments);
        if damage.len() == segments {
            c.states.copy_from_slice(damage);
        }
        c
    }

    pub fn new(segments: usize) -> Contact {
        Contact {
            states: vec![BumperState::default(); segments],
            penetration: vec![0.0; segments],
            crush: vec![0.0; segments],
            force: vec![0.0; segments],
            total: vec![0.0; segments],
            direction: vec![[0.0; 2]; segments],
            point: vec![[0.0; 2]; segments],
            covered: vec![true; segments],
            switched: vec![false; segments],
            blocked: vec![false; segments],
            deflection: vec![0.0; segments],
            rest: vec![0.0; segments],
            engaged: vec![false; segments],
            patches: [0.0; 4],
            absorber: vec![0.0; segments],
            absorbed: vec![BumperState::default(); segments],
            links: Vec::new(),
            link_force: Vec::new(),
        }
    }
}

/// The absorber strips of a barrier face, one per segment (none for other
/// faces). `striker::place` has checked the absorber, so its
/// characteristic exists.
pub(super) fn absorbers(car: &PlanarCar, face: &Placed) -> Vec<Bumper> {
    match face {
        Placed::Barrier {
            absorber: Some(absorber),
            ..
        } => absorber
            .characteristic(car.segment_width())
            .map(|strip| vec![strip; car.beam().segments.len()])
            .unwrap_or_default(),
        _ => Vec::new(),
    }
}
