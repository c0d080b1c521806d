//! Tests of a striker into the chain ([`Drive::Striker`]) against the
//! closed forms of a two-body impact, the barrier run as the striker's
//! mass grows, and the energy and momentum balances of a yielding chain.

use super::*;
use crate::link::{Curve, LinkState, Unloading};
use approx::assert_relative_eq;

fn struck(chain: &Chain, mass: f64, speed: f64, step: f64, samples: usize) -> ChainResponse {
    chain
        .run(&Drive::Striker {
            mass,
            speed,
            step,
            samples,
        })
        .unwrap()
}

/// The last sample the striker pushes, s.
fn contact_time(r: &ChainResponse) -> f64 {
    let last = r.force.iter().rposition(|f| *f != 0.0).unwrap();
    (last + 1) as f64 * r.step
}

fn last(v: &[f64]) -> f64 {
    *v.last().unwrap()
}

/// A linear elastic front link (k) between a striker M at V and one mass
/// m at rest: the two-body elastic impact. After separation the striker
/// moves at `(M − m)/(M + m) V` and the car at `2M/(M + m) V` (momentum
/// and energy), the contact lasts half a period `π √(μ/k)` of the reduced
/// mass `μ = M m/(M + m)`, and the peak force is `V √(k μ)`.
#[test]
fn an_elastic_front_link_is_the_two_body_elastic_impact() {
    let (big, m, k, v) = (1500.0, 1000.0, 1e6, 2.0);
    let chain = Chain::new(vec![m], vec![], vec![])
        .unwrap()
        .with_front(Link::linear(k).unwrap());
    let r = struck(&chain, big, v, 1e-5, 12_000);
    let mu = big * m / (big + m);
    let (striker, car) = (-last(&r.striker_velocity), -last(&r.velocity[0]));
    // the leapfrog's O((ωT)²) with ωT = 4e-4, and the contact's end
    // within one sample of 1e-5 s
    assert_relative_eq!(striker, (big - m) / (big + m) * v, max_relative = 1e-3);
    assert_relative_eq!(car, 2.0 * big / (big + m) * v, max_relative = 1e-4);
    let period = std::f64::consts::PI * (mu / k).sqrt();
    assert_relative_eq!(contact_time(&r), period, max_relative = 2e-4);
    let peak = r.force.iter().fold(0.0_f64, |a, f| a.max(-f));
    assert_relative_eq!(peak, v * (k * mu).sqrt(), max_relative = 1e-4);
    // elastic: nothing dissipated, nothing kept, the car's force never pulls
    assert!(r.force.iter().all(|f| *f <= 0.0));
    assert_eq!(last(&r.plastic), 0.0);
    assert!(r.energy_error() < 1e-4, "{}", r.energy_error());
}

/// A yielding front link (k, F_y, no hardening) unloading along a slope
/// k_u ≫ k: the perfectly plastic impact as k_u grows. It gives back
/// only `E_r = F_y²/(2 k_u)`, so after separation the bodies leave the
/// common velocity `M V/(M + m)` at the relative speed `√(2 E_r/μ)`, and
/// the plastic work is `½ μ V² − E_r`; the front link's plastic set stays.
#[test]
fn a_yielding_front_link_leaves_the_common_velocity_and_dissipates_half_mu_v_squared() {
    let (big, m, v) = (1500.0, 1000.0, 4.0);
    let (k, fy, ku) = (5e6, 5e4, 5e8);
    let link = Link::new(Curve::bilinear(k, fy, 0.0).unwrap(), Unloading::Slope(ku)).unwrap();
    let chain = Chain::new(vec![m], vec![], vec![])
        .unwrap()
        .with_front(link.clone());
    let r = struck(&chain, big, v, 1e-5, 20_000);
    let mu = big * m / (big + m);
    let common = big * v / (big + m);
    let given_back = fy * fy / (2.0 * ku);
    let apart = (2.0 * given_back / mu).sqrt();
    let (striker, car) = (-last(&r.striker_velocity), -last(&r.velocity[0]));
    assert!(r.force[r.force.len() - 100..].iter().all(|f| *f == 0.0));
    assert_relative_eq!(striker, common - m / (big + m) * apart, max_relative = 1e-3);
    assert_relative_eq!(car, common + big / (big + m) * apart, max_relative = 1e-3);
    assert!(
        (car - striker - apart).abs() < 0.02 * apart,
        "{car} {striker}"
    );
    let plastic = last(&r.plastic);
    assert_relative_eq!(plastic, 0.5 * mu * v * v - given_back, max_relative = 1e-3);
    // the dissipated energy is ½ μ V² to within E_r / (½ μ V²) = 0.5 %
    assert_relative_eq!(plastic, 0.5 * mu * v * v, max_relative = 6e-3);
    // the set is the crush less F_y/k_u, and stays after the separation
    let crush = r.displacement[0]
        .iter()
        .zip(&r.striker_displacement)
        .fold(0.0_f64, |a, (x1, xs)| a.max(x1 - xs));
    let set = LinkState { reached: crush }.plastic_set(&link);
    assert_relative_eq!(set, crush - fy / ku, max_relative = 1e-9);
    let gap = last(&r.displacement[0]) - last(&r.striker_displacement);
    assert!(
        gap < set,
        "separated: {gap} m apart against a set of {set} m"
    );
    assert!(r.energy_error() < 1e-3, "{}", r.energy_error());
}

/// A striker into a chain of yielding and stiffening links with dampers,
/// through a front link or the penalty contact: the balance `E_kin(0) =
/// E_kin + E_stored + W_viscous + W_plastic + W_contact` closes to 1e-3
/// and the momentum `M V` is conserved.
#[test]
fn the_balance_closes_and_momentum_is_kept_in_a_yielding_chain() {
    let links = vec![
        Link::new(
            Curve::bilinear(2e6, 4e4, 0.1).unwrap(),
            Unloading::Slope(4e6),
        )
        .unwrap(),
        Link::new(
            Curve::progressive(1e6, 5e7, 0.3).unwrap(),
            Unloading::Slope(3e6),
        )
        .unwrap(),
    ];
    let chain = Chain::new(vec![10.0, 300.0, 1100.0], vec![500.0, 3e3], links).unwrap();
    let front = Link::new(
        Curve::bilinear(3e6, 6e4, 0.05).unwrap(),
        Unloading::Slope(5e6),
    )
    .unwrap();
    let (big, v) = (1400.0, 8.0 / 3.6 * 2.0);
    for chain in [chain.clone().with_front(front), chain] {
        let r = struck(&chain, big, v, 1e-4, 4000);
        assert!(last(&r.plastic) > 0.0 && last(&r.viscous) > 0.0);
        assert!(r.energy_error() < 1e-3, "{}", r.energy_error());
        assert_relative_eq!(r.kinetic[0], 0.5 * big * v * v, max_relative = 1e-12);
        let momentum: f64 = chain
            .masses()
            .iter()
            .zip(&r.velocity)
            .map(|(m, w)| m * last(w))
            .sum::<f64>()
            + big * last(&r.striker_velocity);
        assert_relative_eq!(momentum, -big * v, max_relative = 1e-9);
        assert!(r.plastic_set.iter().all(|s| *s >= 0.0));
    }
}

/// As the striker's mass grows the run becomes the barrier run seen from
/// the wall: the car's travel relative to the striker and the force follow
/// [`Drive::Barrier`]'s.
#[test]
fn a_very_heavy_striker_is_the_rigid_barrier() {
    let front = Link::new(
        Curve::bilinear(2e6, 5e4, 0.05).unwrap(),
        Unloading::Slope(4e6),
    )
    .unwrap();
    let chain = Chain::new(
        vec![20.0, 900.0],
        vec![1e3],
        vec![Link::linear(3e6).unwrap()],
    )
    .unwrap()
    .with_front(front);
    let (v, samples) = (3.0, 2000);
    let wall = chain
        .run(&Drive::Barrier {
            speed: v,
            step: 1e-4,
            samples,
        })
        .unwrap();
    let r = struck(&chain, 1e7, v, 1e-4, samples);
    let peak = wall.force.iter().fold(0.0_f64, |a, f| a.max(f.abs()));
    let travel = wall.displacement[1]
        .iter()
        .fold(0.0_f64, |a, x| a.max(x.abs()));
    // the striker's own deceleration, impulse/M ≈ 5e-4 m/s, shifts it by
    // about 1e-4 m over the run: 1e-3 of the travel and of the peak force
    for k in 0..samples {
        // the car's travel into the striker is the barrier run's travel
        let relative = r.displacement[1][k] - r.striker_displacement[k];
        let x = wall.displacement[1][k];
        assert!((relative - x).abs() < 1e-3 * travel, "{k}: {relative} {x}");
        assert!((r.force[k] - wall.force[k]).abs() < 1e-3 * peak, "{k}");
    }
}

#[test]
fn a_bad_striker_mass_is_refused_by_name() {
    let chain = Chain::new(vec![1.0, 2.0], vec![0.0], vec![Link::linear(1e3).unwrap()]).unwrap();
    for mass in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let e = chain
            .run(&Drive::Striker {
                mass,
                speed: 1.0,
                step: 1e-3,
                samples: 10,
            })
            .unwrap_err();
        assert!(e.to_string().starts_with("mass = "), "{e}");
    }
}

/// The motion on `f64` is the full run's, the striker's state included
/// in the integration (not in the motion's displacements, the car's).
#[test]
fn the_motion_of_a_struck_chain_is_the_runs() {
    let chain = Chain::new(
        vec![5.0, 800.0],
        vec![200.0],
        vec![Link::linear(2e6).unwrap()],
    )
    .unwrap()
    .with_front(
        Link::new(
            Curve::bilinear(1e6, 3e4, 0.0).unwrap(),
            Unloading::Slope(2e6),
        )
        .unwrap(),
    );
    let drive = Drive::Striker {
        mass: 1200.0,
        speed: 2.5,
        step: 1e-4,
        samples: 1500,
    };
    let r = chain.run(&drive).unwrap();
    let m = chain.motion(&drive, &chain.values::<f64>()).unwrap();
    assert_eq!(m.displacement.len(), 2);
    assert_eq!(m.displacement, r.displacement);
    assert_eq!(m.force, r.force);
}
