//! The chain's mechanism for [`crate::leapfrog`], written once over any
//! [`Real`]: on `f64` it is [`super::Chain::run`], on
//! [`crate::dual::Dual`] numbers ([`super::Chain::motion`]) the same steps
//! carry the exact derivatives of the discrete motion with respect to the
//! values seeded in [`ChainValues`] (the forward sensitivity equations of
//! the leapfrog with the links' history: every step's branch — loading,
//! unloading, a plastic set reached — is the one the values take, and its
//! derivative is carried through the history `δ_max`). The equations are
//! those of [`super`]; every product keeps the `f64` run's operands in
//! their order, so a run on `f64` is bit for bit the same. Nothing is
//! allocated after the start: the records are reserved for every sample.
//! Each link's unloading line is kept while its δ_max stays
//! ([`Remembered`]): a run into the barrier unloads over most of its
//! samples.

use super::{Chain, ChainResponse};
use crate::dual::Real;
use crate::leapfrog::{Control, Leapfrog, Mechanism, Stepped};
use crate::link::{Link, Remembered};

/// A chain's values on the numbers `T`, in the chain's shape: what a run
/// on dual numbers differentiates ([`Chain::values`] gives them as
/// constants; seed the ones to differentiate by).
#[derive(Debug, Clone, PartialEq)]
pub struct ChainValues<T> {
    /// Masses, kg.
    pub masses: Vec<T>,
    /// Dampers, N·s/m.
    pub dampers: Vec<T>,
    /// Links ([`Link::with_parameters`]).
    pub links: Vec<Link<T>>,
    /// The front link, when the chain has one.
    pub front: Option<Link<T>>,
    /// The second load path's link, when the chain has one.
    pub path: Option<Link<T>>,
    /// The rebound link, when the chain has one.
    pub rebound: Option<Link<T>>,
    /// The second load path's gap, m (None: the chain's own,
    /// [`super::WallPath::gap`]).
    pub path_gap: Option<T>,
    /// The rebound link's gap, m (None: the chain's own).
    pub rebound_gap: Option<T>,
}

/// The motion of a run on the numbers `T` ([`Chain::motion`]): what the
/// objectives compare, at every sample.
#[derive(Debug, Clone, PartialEq)]
pub struct Motion<T> {
    /// Displacements, m; outer index = mass.
    pub displacement: Vec<Vec<T>>,
    /// The force on m1 (given, or the wall's), N.
    pub force: Vec<T>,
    /// Each link's plastic set at the end of the run, m
    /// ([`crate::link::LinkState::plastic_set`], as [`ChainResponse::plastic_set`]).
    pub plastic_set: Vec<T>,
}

/// What a run records.
pub(super) enum Out<T> {
    /// Every history and the energy balance ([`ChainResponse`], values).
    Full(Box<ChainResponse>),
    /// Displacements and the force on m1, on `T`.
    Motion(Motion<T>),
}

impl<T> Out<T> {
    /// The records of a chain of `n` masses for `samples` samples.
    pub(super) fn new(full: bool, n: usize, samples: usize, striker: bool) -> Out<T> {
        if !full {
            return Out::Motion(Motion {
                displacement: series(n, samples),
                force: Vec::with_capacity(samples),
                plastic_set: Vec::with_capacity(n - 1),
            });
        }
        let l = n - 1;
        Out::Full(Box::new(ChainResponse {
            step: 0.0,
            force: Vec::with_capacity(samples),
            displacement: series(n, samples),
            velocity: series(n, samples),
            link_force: series(l, samples),
            kinetic: Vec::with_capacity(samples),
            stored: Vec::with_capacity(samples),
            viscous: Vec::with_capacity(samples),
            plastic: Vec::with_capacity(samples),
            work: Vec::with_capacity(samples),
            plastic_set: vec![],
            reached: vec![],
            striker_displacement: Vec::with_capacity(samples * striker as usize),
            striker_velocity: Vec::with_capacity(samples * striker as usize),
        }))
    }
}

/// `count` series, each reserved for `samples` values.
fn series<U>(count: usize, samples: usize) -> Vec<Vec<U>> {
    (0..count).map(|_| Vec::with_capacity(samples)).collect()
}

/// The mechanism of one run: forces, histories and records.
pub(super) struct Mover<'a, T> {
    chain: &'a Chain,
    values: &'a ChainValues<T>,
    force: &'a [f64],
    every: usize,
    wall: Option<(f64, f64)>,
    sign: f64,
    striker: Option<f64>,
    front: Remembered<T>,
    front_force: T,
    path: Remembered<T>,
    path_force: T,
    rebound: Remembered<T>,
    rebound_force: T,
    states: Vec<Remembered<T>>,
    springs: Vec<T>,
    applied: usize,
    viscous: T,
    work: T,
    pub(super) out: Out<T>,
}

/// How a run is driven: the force samples, the sample's integration
/// steps, the wall's penalty and the frame's sign.
pub(super) struct Driven<'a> {
    pub(super) force: &'a [f64],
    pub(super) every: usize,
    pub(super) wall: Option<(f64, f64)>,
    pub(super) sign: f64,
    /// The striker's mass, kg ([`super::Drive::Striker`]; its state is
    /// the last of the integrated ones).
    pub(super) striker: Option<f64>,
}

impl<'a, T: Real> Mover<'a, T> {
    pub(super) fn new(
        chain: &'a Chain,
        values: &'a ChainValues<T>,
        driven: Driven<'a>,
        out: Out<T>,
    ) -> Mover<'a, T> {
        let (n, l) = (chain.dof(), chain.dof() - 1);
        let zero = T::constant(0.0);
        let mut m = Mover {
            chain,
            values,
            force: driven.force,
            every: driven.every,
            wall: driven.wall,
            sign: driven.sign,
            striker: driven.striker,
            front: Remembered::default(),
            front_force: zero,
            path: Remembered::default(),
            path_force: zero,
            rebound: Remembered::default(),
            rebound_force: zero,
            states: vec![Remembered::default(); l],
            springs: vec![zero; l],
            applied: 0,
            viscous: zero,
            work: zero,
            out,
        };
        let states = n + m.striker.is_some() as usize;
        m.moved(&vec![zero; states], &vec![zero; states], usize::MAX);
        m
    }

    /// Mass `i`'s travel into the wall, `x_i` (a rigid wall at 0) or
    /// `x_i − x_s` (the striker's face at `x_s`); the same of velocities.
    fn wall_travel(&self, x: &[T], i: usize) -> T {
        match self.striker {
            None => x[i],
            Some(_) => x[i] - x[self.chain.dof()],
        }
    }

    /// The force on m1 at integration step `k` (foh between samples), or
    /// the wall's at m1's travel `x1` into it and its rate `v1`.
    fn external(&self, k: usize, x1: T, v1: T) -> T {
        if self.wall.is_some() && self.values.front.is_some() {
            return -self.front_force;
        }
        if let Some((kw, cw)) = self.wall {
            return if x1.value() > 0.0 {
                -(x1 * kw + v1 * cw).max_constant(0.0)
            } else {
                T::constant(0.0)
            };
        }
        let sample = k / self.every;
        let frac = (k % self.every) as f64 / self.every as f64;
        T::constant(match (self.force.get(sample), self.force.get(sample + 1)) {
            (Some(a), Some(b)) => a + (b - a) * frac,
            (Some(a), None) => *a,
            _ => 0.0,
        })
    }

    /// The records, each link's plastic set and reached compression
    /// filled in a full run.
    pub(super) fn finish(self, interval: f64) -> Out<T> {
        let mut out = self.out;
        let sets = self
            .states
            .iter()
            .zip(&self.values.links)
            .map(|(s, l)| s.state.plastic_set(l));
        match &mut out {
            Out::Full(o) => {
                o.step = interval;
                o.plastic_set = sets.map(|s| s.value()).collect();
                o.reached = self
                    .states
                    .iter()
                    .map(|s| s.state.reached.value())
                    .collect();
            }
            Out::Motion(o) => o.plastic_set = sets.collect(),
        }
        out
    }

    /// The energy records of a full run at positions `q`, velocities `v`.
    fn energies(&self, q: &[T], v: &[T]) -> [f64; 3] {
        let (mut stored, mut plastic) = (0.0, 0.0);
        let values = self.values;
        for (j, link) in values.links.iter().enumerate() {
            stored += link
                .stored((q[j] - q[j + 1]) * self.sign, &self.states[j].state)
                .value();
            plastic += self.states[j].state.dissipated(link).value();
        }
        if let (Some(front), Some(_)) = (&values.front, self.wall) {
            if self.front_force.value() > 0.0 {
                stored += front
                    .stored(self.wall_travel(q, 0), &self.front.state)
                    .value();
            }
            plastic += self.front.state.dissipated(front).value();
        }
        if let (Some(path), Some(wall), Some(_)) = (&values.path, &self.chain.path, self.wall) {
            if self.path_force.value() > 0.0 {
                let crush = self.wall_travel(q, wall.mass) - wall.gap;
                stored += path.stored(crush, &self.path.state).value();
            }
            plastic += self.path.state.dissipated(path).value();
        }
        if let (Some(rebound), Some(wall), Some(_)) =
            (&values.rebound, &self.chain.rebound, self.wall)
        {
            if self.rebound_force.value() > 0.0 {
                let crush = self.wall_travel(q, wall.mass) - wall.gap;
                stored += rebound.stored(crush, &self.rebound.state).value();
            }
            plastic += self.rebound.state.dissipated(rebound).value();
        }
        let mut kinetic: f64 = values
            .masses
            .iter()
            .zip(v)
            .map(|(m, w)| 0.5 * m.value() * w.value() * w.value())
            .sum();
        if let Some(mass) = self.striker {
            let w = v[self.chain.dof()].value();
            kinetic += 0.5 * mass * w * w;
        }
        [kinetic, stored, plastic]
    }
}

impl<T: Real> Mechanism<T> for Mover<'_, T> {
    type Error = usize;

    fn moved(&mut self, q: &[T], _v: &[T], k: usize) {
        for (j, link) in self.values.links.iter().enumerate() {
            let crush = (q[j] - q[j + 1]) * self.sign;
            self.springs[j] = link.remembered_force(crush, &mut self.states[j]) * self.sign;
        }
        if let (Some(front), Some(_)) = (&self.values.front, self.wall) {
            let crush = self.wall_travel(q, 0);
            self.front_force = front
                .remembered_force(crush, &mut self.front)
                .max_constant(0.0);
        }
        if let (Some(path), Some(wall), Some(_)) = (&self.values.path, &self.chain.path, self.wall)
        {
            let gap = self.values.path_gap.unwrap_or(T::constant(wall.gap));
            let crush = self.wall_travel(q, wall.mass) - gap;
            self.path_force = path
                .remembered_force(crush, &mut self.path)
                .max_constant(0.0);
        }
        if let (Some(rebound), Some(wall), Some(_)) =
            (&self.values.rebound, &self.chain.rebound, self.wall)
        {
            let gap = self.values.rebound_gap.unwrap_or(T::constant(wall.gap));
            let crush = self.wall_travel(q, wall.mass) - gap;
            self.rebound_force = rebound
                .remembered_force(crush, &mut self.rebound)
                .max_constant(0.0);
        }
        self.applied = k.wrapping_add(1);
    }

    fn accelerations(&mut self, q: &[T], v: &[T], a: &mut [T]) {
        let k = self.applied;
        let f = self.external(k, self.wall_travel(q, 0), self.wall_travel(v, 0));
        let (c, masses) = (&self.values.dampers, &self.values.masses);
        let path = self.chain.path.as_ref().map(|p| p.mass);
        let rebound = self.chain.rebound.as_ref().map(|p| p.mass);
        let n = self.chain.dof();
        if let Some(mass) = self.striker {
            // the striker takes the reaction of every wall link
            let on_car = f - self.path_force - self.rebound_force;
            a[n] = -on_car / T::constant(mass);
        }
        for (i, ai) in a[..n].iter_mut().enumerate() {
            let mut sum = if i == 0 { f } else { T::constant(0.0) };
            if i + 1 < n {
                sum -= self.springs[i] + c[i] * (v[i] - v[i + 1]);
            }
            if i > 0 {
                sum += self.springs[i - 1] + c[i - 1] * (v[i - 1] - v[i]);
            }
            if path == Some(i) {
                sum -= self.path_force;
            }
            if rebound == Some(i) {
                sum -= self.rebound_force;
            }
            *ai = sum / masses[i];
        }
    }

    fn stepped(&mut self, s: &Stepped<'_, T>) {
        if matches!(self.out, Out::Motion(_)) {
            return;
        }
        let c = &self.values.dampers;
        let k = if s.half { 0 } else { self.applied };
        let f = self.external(k, self.wall_travel(s.q, 0), self.wall_travel(s.before, 0));
        if self.values.front.is_none() || self.wall.is_none() {
            // on m1's travel into the wall (the striker takes −f)
            self.work += f * s.length * self.wall_travel(s.mean, 0);
        }
        for (j, cj) in c.iter().enumerate() {
            let rate = s.before[j] - s.before[j + 1];
            self.viscous += *cj * s.length * rate * (s.mean[j] - s.mean[j + 1]);
        }
    }

    fn record(&mut self, k: usize, state: &Leapfrog<T>) -> Result<Control, usize> {
        let (q, v) = (state.q(), state.velocities());
        if q.iter().chain(v).any(|x| !x.value().is_finite()) {
            return Err(k / self.every);
        }
        let (x1, v1) = (self.wall_travel(q, 0), self.wall_travel(v, 0));
        let wall = self.external(k, x1, v1) - self.path_force - self.rebound_force;
        let energies = match self.out {
            Out::Full(_) => self.energies(q, v),
            Out::Motion(_) => [0.0; 3],
        };
        match &mut self.out {
            Out::Motion(o) => {
                o.force.push(wall);
                for (x, series) in q.iter().zip(&mut o.displacement) {
                    series.push(*x);
                }
            }
            Out::Full(o) => {
                o.force.push(wall.value());
                for (i, (x, w)) in q.iter().zip(v).take(self.chain.dof()).enumerate() {
                    o.displacement[i].push(x.value());
                    o.velocity[i].push(w.value());
                }
                for (j, spring) in self.springs.iter().enumerate() {
                    o.link_force[j].push((*spring * self.sign).value());
                }
                let [kinetic, stored, plastic] = energies;
                if self.striker.is_some() {
                    let s = self.chain.dof();
                    o.striker_displacement.push(q[s].value());
                    o.striker_velocity.push(v[s].value());
                }
                o.kinetic.push(kinetic);
                o.stored.push(stored);
                o.plastic.push(plastic);
                o.viscous.push(self.viscous.value());
                o.work.push(self.work.value());
            }
        }
        Ok(Control::Continue)
    }
}
