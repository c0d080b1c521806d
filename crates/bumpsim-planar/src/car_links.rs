//! Nonlinear links in the side members (issue 46 item 2): a side chain's
//! link j may be any [`bumpsim_core::link::Link`] — a loading curve `F_L(δ)`
//! (linear, progressive, bilinear yielding with hardening, tabulated) and an
//! unloading rule (elastic along the curve, or an elastic slope from the
//! reached crush with a plastic set) — the one law the 1-D
//! [`bumpsim_core::chain`] runs. The link's crush is the compression of
//! the side member, `δ = −(u_front − u_back)` (u along body x, the back the
//! next mass or the body), its force `F = L(δ)` pushes the two apart.
//!
//! A chain with links keeps `springs` as their initial slopes (what the
//! reports, bounds and linear readers see); [`SideChain::linked`] sets them,
//! and [`PlanarCar::new`] refuses a chain where they differ.

use super::{Layout, PlanarCar, PlanarError, SideChain, parameter, require};
use bumpsim_core::chain::Chain;
use bumpsim_core::link::{Curve, Link, Unloading};
use bumpsim_impact::bumper::Bumper;

impl SideChain {
    /// A chain whose links are `links` (one per mass, link j behind mass
    /// j): `springs` are their initial slopes. Checked by [`PlanarCar::new`].
    pub fn linked(masses: Vec<f64>, dampers: Vec<f64>, links: Vec<Link>) -> SideChain {
        SideChain {
            springs: links.iter().map(|l| l.curve().initial_slope()).collect(),
            masses,
            dampers,
            links,
        }
    }

    /// Whether every link is linear (no `links` given).
    pub fn is_linear(&self) -> bool {
        self.links.is_empty()
    }

    /// Link `j` (0-based) as a [`Link`]: the nonlinear one, or the linear
    /// elastic spring `springs[j]`; `None` past the chain or for a spring
    /// that is no valid stiffness.
    pub fn link(&self, j: usize) -> Option<Link> {
        match self.links.get(j) {
            Some(link) => Some(link.clone()),
            None if self.links.is_empty() => Link::linear(*self.springs.get(j)?).ok(),
            None => None,
        }
    }

    /// The same chain with every force (masses kept) scaled by `factor`
    /// (> 0): dampers, springs and links (a half car's side of a 1-D chain).
    pub fn scaled(&self, factor: f64) -> Result<SideChain, PlanarError> {
        require(
            "factor",
            factor,
            "1",
            "must be positive and finite",
            factor > 0.0,
        )?;
        let links = self
            .links
            .iter()
            .enumerate()
            .map(|(j, l)| {
                scaled(l, factor).map_err(|e| {
                    parameter(&format!("links[{}]", j + 1), factor, "1", &e.to_string())
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let mut chain = SideChain {
            masses: self.masses.clone(),
            dampers: self.dampers.iter().map(|c| c * factor).collect(),
            springs: self.springs.iter().map(|k| k * factor).collect(),
            links: Vec::new(),
        };
        if !links.is_empty() {
            chain = SideChain::linked(chain.masses, chain.dampers, links);
        }
        Ok(chain)
    }
}

/// `link` with its forces (and so its slopes) scaled by `factor`.
pub fn scaled(link: &Link, factor: f64) -> Result<Link, bumpsim_core::link::LinkError> {
    let curve = match link.curve() {
        Curve::Linear { stiffness } => Curve::linear(stiffness * factor)?,
        Curve::Progressive {
            stiffness,
            cubic,
            limit,
        } => Curve::progressive(stiffness * factor, cubic * factor, *limit)?,
        Curve::Bilinear {
            stiffness,
            yield_force,
            hardening,
        } => Curve::bilinear(stiffness * factor, yield_force * factor, *hardening)?,
        Curve::Table { points } => {
            Curve::table(points.iter().map(|p| [p[0], p[1] * factor]).collect())?
        }
    };
    let unloading = match link.unloading() {
        Unloading::Elastic => Unloading::Elastic,
        Unloading::Slope(k) => Unloading::Slope(k * factor),
    };
    Link::new(curve, unloading)
}

/// The links of `chain` (side `side`): none, or one per mass whose initial
/// slope is the chain's spring.
pub(super) fn check(side: &str, chain: &SideChain) -> Result<(), PlanarError> {
    let n = chain.masses.len();
    if chain.links.is_empty() {
        return Ok(());
    }
    require(
        &format!("{side}.links"),
        chain.links.len() as f64,
        "links",
        &format!("one per mass ({n}) or none (linear springs)"),
        chain.links.len() == n,
    )?;
    for (j, (link, &k)) in chain.links.iter().zip(&chain.springs).enumerate() {
        let slope = link.curve().initial_slope();
        require(
            &format!("{side}.links[{}]", j + 1),
            slope,
            "N/m",
            &format!(
                "the link's initial slope must equal {side}.springs[{}] = {k:?} N/m (SideChain::linked sets them)",
                j + 1
            ),
            slope == k && link.steepest_slope().is_finite(),
        )?;
    }
    Ok(())
}

/// Serialises a chain's links as their descriptions (JSON outputs).
pub(super) fn described<S: serde::Serializer>(links: &[Link], s: S) -> Result<S::Ok, S::Error> {
    s.collect_seq(links.iter().map(describe))
}

/// A link in words with SI values: `bilinear: stiffness 1e6 N/m, ...`.
pub fn describe(link: &Link) -> String {
    let curve = match link.curve() {
        Curve::Linear { stiffness } => format!("linear: stiffness {stiffness:e} N/m"),
        Curve::Progressive {
            stiffness,
            cubic,
            limit,
        } => format!(
            "progressive: stiffness {stiffness:e} N/m, cubic {cubic:e} N/m^3, limit {limit:e} m"
        ),
        Curve::Bilinear {
            stiffness,
            yield_force,
            hardening,
        } => format!(
            "bilinear: stiffness {stiffness:e} N/m, yield_force {yield_force:e} N, hardening {hardening}"
        ),
        Curve::Table { points } => format!("table: {} points", points.len()),
    };
    match link.unloading() {
        Unloading::Elastic => format!("{curve}; unloading elastic"),
        Unloading::Slope(k) => format!("{curve}; unloading {k:e} N/m"),
    }
}

/// The most a step load's force is amplified in a hardening link: a load
/// F applied at once to a spring `F_L = k3 δ³` peaks where
/// `k3 δ⁴/4 = F δ`, at `F_L = 4 F` (a linear spring's: `2 F`).
pub const DYNAMIC_FACTOR: f64 = 4.0;

/// The crush at which `curve` carries `force` (N), when that is below its
/// progressive limit; `None` for any other curve or a force beyond the limit.
fn reach(curve: &Curve, force: f64) -> Option<f64> {
    let Curve::Progressive { limit, .. } = *curve else {
        return None;
    };
    if !(force > 0.0 && force < curve.force(limit)) {
        return None;
    }
    // bisection: the loading curve rises monotonically from 0
    let (mut low, mut high) = (0.0, limit);
    for _ in 0..64 {
        let mid = 0.5 * (low + high);
        match curve.force(mid) < force {
            true => low = mid,
            false => high = mid,
        }
    }
    Some(high)
}

/// `link` with its progressive limit lowered to the crush at which it
/// carries `force` (N), where that is below the limit; else `link`.
fn within(link: &Link, force: f64) -> Result<Link, PlanarError> {
    let Curve::Progressive {
        stiffness, cubic, ..
    } = *link.curve()
    else {
        return Ok(link.clone());
    };
    let Some(crush) = reach(link.curve(), force) else {
        return Ok(link.clone());
    };
    Curve::progressive(stiffness, cubic, crush)
        .and_then(|c| Link::new(c, link.unloading()))
        .map_err(|e| parameter("limit", crush, "m", &e.to_string()))
}

impl PlanarCar {
    /// The car as loads of at most `force` in all (N) can load its side
    /// members, for the critical step of a replay under such loads
    /// ([`crate::drive::substeps`]): each progressive link's limit lowered
    /// to the crush at which it carries `DYNAMIC_FACTOR` (4) × `force`,
    /// where that is below its limit (past the limit the curve continues
    /// along its tangent, so the link's steepest slope becomes the one the
    /// loads can reach). Not a car to run: the links' curves beyond that
    /// crush differ. (A progressive link's limit, 0.3 m by default, is
    /// far past the crush of a low-speed test: its slope there, 109 times
    /// the initial one at the identification's default start, made the
    /// replays of issue 46's progressive series take five integration
    /// steps per 0.3 ms sample; at the loads' reach they take one or two.)
    pub fn within_force(&self, force: f64) -> Result<PlanarCar, PlanarError> {
        let side = |chain: &SideChain| -> Result<SideChain, PlanarError> {
            if chain.links.is_empty() {
                return Ok(chain.clone());
            }
            let links = chain
                .links
                .iter()
                .map(|l| within(l, DYNAMIC_FACTOR * force))
                .collect::<Result<Vec<_>, _>>()?;
            Ok(SideChain::linked(
                chain.masses.clone(),
                chain.dampers.clone(),
                links,
            ))
        };
        let (left, right) = (side(self.left())?, side(self.right())?);
        PlanarCar::new(self.body, left, right, self.beam.clone(), self.tyres)
            .and_then(|c| c.with_crash_boxes(self.crash_boxes()))
            .and_then(|c| c.with_effective_width(self.effective_width))
    }

    /// The symmetric planar car of a 1-D chain with nonlinear links
    /// ([`bumpsim_core::chain::Chain`], no front link): as
    /// [`PlanarCar::symmetric`], the last mass the body and the other
    /// masses, dampers and links halved onto each side (a link's forces
    /// halved), so a full-width flat impact reduces to the 1-D chain.
    pub fn symmetric_links(
        chain: &Chain,
        bumper: &Bumper,
        layout: &Layout,
    ) -> Result<PlanarCar, PlanarError> {
        if chain.front().is_some() {
            return Err(parameter(
                "front",
                1.0,
                "link",
                "a planar car's bumper is its crush zone ahead of mass 1: give the chain without a front link",
            ));
        }
        let n = chain.dof();
        let springs: Vec<f64> = chain
            .links()
            .iter()
            .map(|l| l.curve().initial_slope())
            .collect();
        let linear = bumpsim_core::model::MsdModel::new(
            chain.masses().to_vec(),
            chain.dampers().to_vec(),
            springs,
        )
        .map_err(|e| parameter("chain", n as f64, "masses", &e.to_string()))?;
        let car = PlanarCar::symmetric(&linear, bumper, layout)?;
        let side = SideChain::linked(
            car.left.masses.clone(),
            chain.dampers().to_vec(),
            chain.links().to_vec(),
        )
        .scaled(0.5)?;
        PlanarCar::new(car.body, side.clone(), side, car.beam, car.tyres)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A car of one progressive link a side, `F = k δ + k3 δ³` up to 0.3 m.
    fn progressive() -> PlanarCar {
        let (k, k3) = (1.5e6, 6e8);
        let link = Link::new(Curve::progressive(k, k3, 0.3).unwrap(), Unloading::Elastic).unwrap();
        let chain = Chain::new(vec![8.0, 1200.0], vec![1500.0], vec![link]).unwrap();
        let bumper = Bumper::three_part(3e6, 1e12, 3e6).unwrap();
        PlanarCar::symmetric_links(&chain, &bumper, &Layout::default()).unwrap()
    }

    #[test]
    fn a_force_bounds_the_progressive_links_slope_and_so_the_replay_step() {
        let car = progressive();
        let force = 6e4;
        let within = car.within_force(force).unwrap();
        for (link, original) in within.left().links.iter().zip(&car.left().links) {
            let Curve::Progressive { limit, .. } = *link.curve() else {
                panic!("a progressive link: {link:?}")
            };
            // the limit now carries four times the force (the half car's link)
            let carried = original.curve().force(limit);
            assert!(
                (carried - DYNAMIC_FACTOR * force).abs() < 1e-6 * carried,
                "{carried} N at {limit} m"
            );
            assert!(limit < 0.3 && link.steepest_slope() < original.steepest_slope());
        }
        let step = 3e-4;
        let fewer = crate::drive::substeps(&within, step, 0.25).unwrap();
        let limit = crate::drive::substeps(&car, step, 0.25).unwrap();
        assert!(fewer < limit, "{fewer} against {limit} steps per sample");
        // a force beyond the limit's, or none, leaves the car as it is
        assert_eq!(car.within_force(1e12).unwrap(), car);
        assert_eq!(car.within_force(0.0).unwrap(), car);
    }
}
