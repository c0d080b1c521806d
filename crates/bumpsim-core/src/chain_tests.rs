//! Tests of the chain with nonlinear links: closed forms, the exact linear
//! chain, the energy balance, hostile drives.

use super::*;
use crate::discrete::Method;
use crate::link::{Curve, Unloading};
use crate::model::MsdModel;
use crate::series::UniformSeries;
use crate::simulate::{InitialState, simulate};
use approx::assert_relative_eq;

fn epp(k: f64, fy: f64) -> Link {
    Link::new(Curve::bilinear(k, fy, 0.0).unwrap(), Unloading::Slope(k)).unwrap()
}

/// A mass M at V into a wall through an elastic-perfectly-plastic link
/// (k, F_y): crush `M V²/(2 F_y) + F_y/(2k)`, plastic set `crush − F_y/k`,
/// dissipated `F_y · set`, rebound `F_y / √(k M)`.
#[test]
fn an_elastic_perfectly_plastic_mass_into_a_wall_matches_the_closed_form() {
    let (m, v, k, fy) = (1000.0, 10.0, 1e7, 1e5);
    let chain = Chain::new(vec![0.01, m], vec![0.0], vec![epp(k, fy)]).unwrap();
    let r = chain
        .run(&Drive::Barrier {
            speed: v,
            step: 1e-4,
            samples: 3000,
        })
        .unwrap();
    let crush = m * v * v / (2.0 * fy) + fy / (2.0 * k);
    assert_relative_eq!(r.max_deformation(0), crush, max_relative = 1e-3);
    let set = crush - fy / k;
    assert_relative_eq!(r.plastic_set[0], set, max_relative = 1e-3);
    let plastic = *r.plastic.last().unwrap();
    assert_relative_eq!(plastic, fy * set, max_relative = 1e-3);
    let rebound = r.velocity[1].iter().fold(0.0_f64, |a, b| a.min(*b));
    assert_relative_eq!(-rebound, fy / (k * m).sqrt(), max_relative = 0.02);
    assert!(r.energy_error() < 1e-3, "{}", r.energy_error());
}

/// The same closed form through a front link on one mass, exactly the
/// single mass of the classic problem.
#[test]
fn one_mass_through_a_front_link_matches_the_closed_form() {
    let (m, v, k, fy) = (1000.0, 10.0, 1e7, 1e5);
    let chain = Chain::new(vec![m], vec![], vec![])
        .unwrap()
        .with_front(epp(k, fy));
    let r = chain
        .run(&Drive::Barrier {
            speed: v,
            step: 1e-4,
            samples: 3000,
        })
        .unwrap();
    let crush = m * v * v / (2.0 * fy) + fy / (2.0 * k);
    let last = r.velocity[0].len() - 1;
    assert_relative_eq!(
        r.displacement[0].iter().fold(0.0_f64, |a, b| a.max(*b)),
        crush,
        max_relative = 1e-3
    );
    assert_relative_eq!(
        -r.velocity[0][last],
        fy / (k * m).sqrt(),
        max_relative = 1e-3
    );
    assert_relative_eq!(
        *r.plastic.last().unwrap(),
        fy * (crush - fy / k),
        max_relative = 1e-3
    );
    assert_relative_eq!(
        r.force.iter().fold(0.0_f64, |a, b| a.min(*b)),
        -fy,
        max_relative = 1e-9
    );
    assert!(r.energy_error() < 1e-3, "{}", r.energy_error());
}

/// Linear links give the linear chain's exact (foh) response to O(T²).
#[test]
fn linear_links_follow_the_exact_linear_chain() {
    let (masses, dampers, springs) = (vec![20.0, 300.0, 900.0], vec![800.0, 2e3], vec![4e5, 9e5]);
    let model = MsdModel::new(masses.clone(), dampers.clone(), springs.clone()).unwrap();
    let links = springs.iter().map(|k| Link::linear(*k).unwrap()).collect();
    let chain = Chain::new(masses, dampers, links).unwrap();
    let force: Vec<f64> = (0..600)
        .map(|k| -2e4 * (k as f64 * 0.01).sin().max(0.0))
        .collect();
    let series = UniformSeries::new(0.0, 1e-4, force.clone()).unwrap();
    let exact = simulate(
        &model,
        &series,
        Method::Foh,
        &InitialState::UniformVelocity(3.0),
    )
    .unwrap();
    let r = chain
        .run(&Drive::Force {
            force: &force,
            step: 1e-4,
            initial_velocity: 3.0,
            frame: Frame::Rearward,
        })
        .unwrap();
    let scale = exact.displacement[2]
        .iter()
        .fold(0.0_f64, |a, b| a.max(b.abs()));
    for (a, b) in r.displacement[2].iter().zip(&exact.displacement[2]) {
        assert!((a - b).abs() < 1e-4 * scale, "{a} {b}");
    }
    assert!(r.energy_error() < 1e-3, "{}", r.energy_error());
}

/// The balance closes with the plastic and viscous work in a
/// three-mass chain of yielding and stiffening links.
#[test]
fn the_energy_balance_closes_with_the_dissipated_work() {
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
    let chain = Chain::new(vec![10.0, 400.0, 1200.0], vec![500.0, 3e3], links).unwrap();
    let r = chain
        .run(&Drive::Barrier {
            speed: 15.0,
            step: 1e-4,
            samples: 2000,
        })
        .unwrap();
    assert!(r.plastic.last().unwrap() > &0.0 && r.viscous.last().unwrap() > &0.0);
    assert!(r.energy_error() < 2e-3, "{}", r.energy_error());
    assert!(r.plastic_set.iter().all(|s| *s >= 0.0));
}

#[test]
fn hostile_drives_are_refused() {
    let chain = Chain::new(vec![1.0, 2.0], vec![0.0], vec![Link::linear(1e3).unwrap()]).unwrap();
    let bad = [
        Drive::Barrier {
            speed: f64::NAN,
            step: 1e-3,
            samples: 10,
        },
        Drive::Barrier {
            speed: 1.0,
            step: 0.0,
            samples: 10,
        },
        Drive::Barrier {
            speed: 1.0,
            step: 1e-3,
            samples: 1,
        },
        Drive::Force {
            force: &[0.0, 1.0],
            step: -1.0,
            initial_velocity: 0.0,
            frame: Frame::Forward,
        },
    ];
    for drive in bad {
        assert!(
            matches!(chain.run(&drive), Err(ChainError::Drive { .. })),
            "{drive:?}"
        );
    }
    let stiff = Chain::new(
        vec![1e-9, 2.0],
        vec![0.0],
        vec![Link::linear(1e12).unwrap()],
    )
    .unwrap();
    let long = Drive::Barrier {
        speed: 1.0,
        step: 1.0,
        samples: 10,
    };
    assert!(matches!(
        stiff.run(&long),
        Err(ChainError::TooManySteps { .. })
    ));
    assert!(Chain::new(vec![1.0, -2.0], vec![0.0], vec![Link::linear(1.0).unwrap()]).is_err());
    assert!(Chain::new(vec![1.0, 2.0], vec![], vec![Link::linear(1.0).unwrap()]).is_err());
}

/// A second load path after a gap (Kamal's engine meeting the wall): one
/// mass M at V through a front link (k, F_1) and a path (k, F_2) that
/// touches after the gap g. Past both yields the work done is
/// `F_1 (c − F_1/2k) + F_2 (c − g − F_2/2k) = M V²/2`, which gives the
/// crush c; the wall force is −(F_1 + F_2) at it, and the balance closes.
#[test]
fn a_second_path_after_a_gap_adds_its_force_and_its_work() {
    let (m, v, k, f1, f2, gap) = (1000.0, 10.0, 1e7, 1e5, 5e4, 0.1);
    let chain = Chain::new(vec![m], vec![], vec![])
        .unwrap()
        .with_front(epp(k, f1))
        .with_path(0, gap, epp(k, f2))
        .unwrap();
    let r = chain
        .run(&Drive::Barrier {
            speed: v,
            step: 1e-4,
            samples: 3000,
        })
        .unwrap();
    let (d1, d2) = (f1 / (2.0 * k), f2 / (2.0 * k));
    let crush = (0.5 * m * v * v + f1 * d1 + f2 * (gap + d2)) / (f1 + f2);
    let reached = r.displacement[0].iter().fold(0.0_f64, |a, b| a.max(*b));
    assert_relative_eq!(reached, crush, max_relative = 1e-3);
    let peak = r.force.iter().fold(0.0_f64, |a, b| a.min(*b));
    assert_relative_eq!(peak, -(f1 + f2), max_relative = 1e-9);
    // before the gap closes only the front pushes
    let early = r.displacement[0].iter().position(|x| *x > 0.05).unwrap();
    assert_relative_eq!(r.force[early], -f1, max_relative = 1e-9);
    assert!(r.energy_error() < 1e-3, "{}", r.energy_error());
    let bad = Chain::new(vec![m], vec![], vec![]).unwrap();
    assert!(bad.clone().with_path(1, 0.0, epp(k, f2)).is_err());
    assert!(bad.with_path(0, -0.1, epp(k, f2)).is_err());
}

/// A rebound link is a third wall link in parallel: with the front link
/// (k, F_1), a path (k, F_2) after the gap g and a rebound link (k, F_3)
/// on the same mass from its first touch, past every yield the work done is
/// `F_1 (c − F_1/2k) + F_2 (c − g − F_2/2k) + F_3 (c − F_3/2k) = M V²/2`;
/// the wall force is −(F_1 + F_2 + F_3) at the crush c; the balance closes;
/// and the mass rebounds off the three unloading slopes at the end.
#[test]
fn a_rebound_link_adds_a_third_force_and_its_work() {
    let (m, v, k, f1, f2, f3, gap) = (1000.0, 10.0, 1e7, 1e5, 5e4, 3e4, 0.1);
    let chain = Chain::new(vec![m], vec![], vec![])
        .unwrap()
        .with_front(epp(k, f1))
        .with_path(0, gap, epp(k, f2))
        .unwrap()
        .with_rebound(0, 0.0, epp(k, f3))
        .unwrap();
    assert!(chain.rebound().is_some());
    let r = chain
        .run(&Drive::Barrier {
            speed: v,
            step: 1e-4,
            samples: 3000,
        })
        .unwrap();
    let (d1, d2, d3) = (f1 / (2.0 * k), f2 / (2.0 * k), f3 / (2.0 * k));
    let crush = (0.5 * m * v * v + f1 * d1 + f2 * (gap + d2) + f3 * d3) / (f1 + f2 + f3);
    let reached = r.displacement[0].iter().fold(0.0_f64, |a, b| a.max(*b));
    assert_relative_eq!(reached, crush, max_relative = 1e-3);
    let peak = r.force.iter().fold(0.0_f64, |a, b| a.min(*b));
    assert_relative_eq!(peak, -(f1 + f2 + f3), max_relative = 1e-9);
    let early = r.displacement[0].iter().position(|x| *x > 0.05).unwrap();
    assert_relative_eq!(r.force[early], -(f1 + f3), max_relative = 1e-9);
    assert!(r.energy_error() < 1e-3, "{}", r.energy_error());
    let bad = Chain::new(vec![m], vec![], vec![]).unwrap();
    assert!(bad.clone().with_rebound(1, 0.0, epp(k, f3)).is_err());
    assert!(bad.with_rebound(0, f64::NAN, epp(k, f3)).is_err());
}
