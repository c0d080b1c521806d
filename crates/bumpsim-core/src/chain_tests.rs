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

/// The chain of the sensitivity test from its 13 values `[m1 m2 m3 c1 c2
/// k1 Fy1 r1 ku1 k2 k3 δlim2 ku2]` (ku: the unloading slope) on any [`Real`]: link 1 yielding with
/// hardening, link 2 progressive, both unloading along a slope.
fn sensitivity_values<T: Real>(chain: &Chain, theta: &[T]) -> ChainValues<T> {
    ChainValues {
        masses: theta[..3].to_vec(),
        dampers: theta[3..5].to_vec(),
        links: vec![
            chain.links()[0].with_parameters(&theta[5..9]),
            chain.links()[1].with_parameters(&theta[9..13]),
        ],
        front: None,
        path: None,
        rebound: None,
        path_gap: None,
        rebound_gap: None,
    }
}

/// Through the history (link 1 yields, both links unload along their
/// slopes and keep a set, link 2 stiffens), the dual numbers give the
/// derivatives of the discrete motion: on `f64` the motion is the run's bit
/// for bit, and each seeded log parameter's column of m3's displacement
/// (and m1's) matches the central difference of the same run (the chain's
/// step held, relative step 1e-5) to 1e-7 of the column's largest value
/// at every sample (measured: 6e-9 at worst, the difference's own
/// truncation and rounding). A difference across a branch switch of the
/// history (a step that turns from loading to unloading as the parameter
/// moves) would differ by the jump of the derivative there; here none of
/// the 800 samples does.
#[test]
fn dual_numbers_give_the_chain_s_derivatives_through_its_history() {
    use crate::dual::Dual;
    let base = [
        50.0, 300.0, 1000.0, 500.0, 2000.0, 2e6, 4e4, 0.1, 6e6, 5e5, 1e8, 0.3, 2e6,
    ];
    let links = vec![
        Link::new(
            Curve::bilinear(2e6, 4e4, 0.1).unwrap(),
            Unloading::Slope(6e6),
        )
        .unwrap(),
        Link::new(
            Curve::progressive(5e5, 1e8, 0.3).unwrap(),
            Unloading::Slope(2e6),
        )
        .unwrap(),
    ];
    let chain = Chain::new(base[..3].to_vec(), base[3..5].to_vec(), links).unwrap();
    let force: Vec<f64> = (0..800)
        .map(|k| match k < 250 {
            true => 8e4 * (std::f64::consts::PI * k as f64 / 250.0).sin(),
            false => 0.0,
        })
        .collect();
    let drive = Drive::Force {
        force: &force,
        step: 1e-4,
        initial_velocity: 0.0,
        frame: Frame::Rearward,
    };
    let run = chain.run(&drive).unwrap();
    assert!(
        run.plastic_set.iter().all(|s| *s > 1e-3),
        "{:?}",
        run.plastic_set
    );
    let motion = chain.motion(&drive, &chain.values::<f64>()).unwrap();
    assert_eq!(motion.displacement, run.displacement);
    assert_eq!(motion.force, run.force);
    let seeded = [0, 1, 3, 5, 6, 7, 10, 12];
    let theta: Vec<Dual<8>> = base
        .iter()
        .enumerate()
        .map(|(i, v)| match seeded.iter().position(|s| *s == i) {
            Some(d) => Dual::seeded(*v, d, *v),
            None => Dual::constant(*v),
        })
        .collect();
    let dual = chain
        .motion(&drive, &sensitivity_values(&chain, &theta))
        .unwrap();
    let h = 1e-5;
    for (d, &i) in seeded.iter().enumerate() {
        let shifted = |by: f64| {
            let mut theta = base.to_vec();
            theta[i] *= by.exp();
            let values = sensitivity_values(&chain, &theta);
            chain.motion(&drive, &values).unwrap().displacement
        };
        let (up, down) = (shifted(h), shifted(-h));
        for mass in [0, 2] {
            let central: Vec<f64> = (0..force.len())
                .map(|k| (up[mass][k] - down[mass][k]) / (2.0 * h))
                .collect();
            let scale = central.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            let worst = (0..force.len())
                .map(|k| (dual.displacement[mass][k].tangent[d] - central[k]).abs())
                .fold(0.0_f64, f64::max);
            assert!(
                scale > 0.0 && worst <= 1e-7 * scale,
                "parameter {i}, mass {}: worst {worst:.3e} of {scale:.3e}",
                mass + 1
            );
        }
    }
}

/// Into the wall (the barrier objective's drive): a 2-mass car behind a
/// tabulated front crush zone and a second load path from m2 after a gap,
/// each force seeded (the table's forces, the path's yield force, the
/// link's stiffness, m1). The wall force and m2's displacement on dual
/// numbers match central differences of the same runs (the chain's step
/// held, relative step 1e-5) to 1e-7 of each column's largest value
/// (measured: 9e-9 at worst).
#[test]
fn dual_numbers_give_the_wall_force_s_derivatives_into_the_barrier() {
    use crate::dual::Dual;
    let front = Link::new(
        Curve::table(vec![[0.05, 8e4], [0.2, 1.2e5], [0.6, 1.5e5]]).unwrap(),
        Unloading::Slope(5e6),
    )
    .unwrap();
    let link = Link::new(
        Curve::bilinear(3e6, 1e5, 0.1).unwrap(),
        Unloading::Slope(9e6),
    )
    .unwrap();
    let path = epp(4e6, 6e4);
    let chain = Chain::new(vec![200.0, 1300.0], vec![3000.0], vec![link])
        .unwrap()
        .with_front(front)
        .with_path(1, 0.25, path)
        .unwrap();
    let drive = Drive::Barrier {
        speed: 15.0,
        step: 1e-4,
        samples: 1200,
    };
    let run = chain.run(&drive).unwrap();
    let motion = chain.motion(&drive, &chain.values::<f64>()).unwrap();
    assert_eq!(motion.force, run.force);
    assert!(run.reached[0] > 0.1, "the link yields: {:?}", run.reached);
    // [m1, F1, F2, F3 of the front, k1, Fy of the path]
    let base = [200.0, 8e4, 1.2e5, 1.5e5, 3e6, 6e4];
    let values = |theta: &[Dual<6>]| {
        let mut v = chain.values::<Dual<6>>();
        v.masses[0] = theta[0];
        let c = |x: f64| Dual::constant(x);
        let front = chain.front().unwrap();
        v.front = Some(front.with_parameters(&[theta[1], theta[2], theta[3], c(5e6)]));
        v.links[0] = chain.links()[0].with_parameters(&[theta[4], c(1e5), c(0.1), c(9e6)]);
        let path = &chain.path().unwrap().link;
        v.path = Some(path.with_parameters(&[c(4e6), theta[5], c(0.0), c(4e6)]));
        v
    };
    let seeded: Vec<Dual<6>> = (0..6).map(|i| Dual::seeded(base[i], i, base[i])).collect();
    let dual = chain.motion(&drive, &values(&seeded)).unwrap();
    let h = 1e-5;
    for i in 0..6 {
        let shifted = |by: f64| {
            let theta: Vec<Dual<6>> = (0..6)
                .map(|k| Dual::constant(base[k] * if k == i { by.exp() } else { 1.0 }))
                .collect();
            let m = chain.motion(&drive, &values(&theta)).unwrap();
            (m.force, m.displacement[1].clone())
        };
        let (up, down) = (shifted(h), shifted(-h));
        let series = [
            (&up.0, &down.0, &dual.force),
            (&up.1, &down.1, &dual.displacement[1]),
        ];
        for (which, (u, d, exact)) in series.into_iter().enumerate() {
            let central: Vec<f64> = (0..u.len())
                .map(|k| (u[k].real - d[k].real) / (2.0 * h))
                .collect();
            let scale = central.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            let worst = (0..u.len())
                .map(|k| (exact[k].tangent[i] - central[k]).abs())
                .fold(0.0_f64, f64::max);
            assert!(
                scale > 0.0 && worst <= 1e-7 * scale,
                "parameter {i}, series {which}: worst {worst:.3e} of {scale:.3e}"
            );
        }
    }
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
