//! Tests of the links: construction, curves, unloading rules, the
//! remembered unloading line.

use super::*;
use approx::assert_relative_eq;

#[test]
fn construction_names_the_bad_parameter() {
    let e = Curve::bilinear(1e6, -1.0, 0.1).unwrap_err();
    assert!(e.to_string().starts_with("yield_force = -1 N"), "{e}");
    let e = Curve::bilinear(1e6, 1e4, 1.5).unwrap_err();
    assert!(e.to_string().contains("hardening"), "{e}");
    assert!(Curve::linear(f64::NAN).is_err());
    assert!(Curve::progressive(1e6, 1e300, 1e200).is_err());
    let e = Link::new(Curve::linear(1.0).unwrap(), Unloading::Slope(0.0)).unwrap_err();
    assert!(e.to_string().starts_with("unloading = 0 N/m"), "{e}");
    let e = Curve::table(vec![[0.1, 10.0], [0.05, 20.0]]).unwrap_err();
    assert!(e.to_string().contains("point 2"), "{e}");
    assert!(Curve::table(vec![[0.1, 10.0], [0.2, -5.0]]).is_err());
    assert!(Curve::table(vec![[0.0, 0.0]]).is_err());
    assert!(Curve::table(vec![[0.1, 0.0], [0.2, 5.0]]).is_err());
}

#[test]
fn a_softening_fall_steeper_than_the_rise_needs_no_stiffer_unloading() {
    // rises at 1e6 N/m to 10 kN, falls at 1.8e6 N/m to 1 kN, rises at
    // 2e5 N/m: unloaded at 1.2e6 N/m, bumpsim's k_e is k_u at every
    // reached crush (secant and energy terms stay under the rise)
    let curve = Curve::table(vec![[0.01, 1e4], [0.015, 1e3], [0.03, 4e3]]).unwrap();
    assert!((curve.steepest_slope() - 1.8e6).abs() < 1.0);
    assert!((curve.steepest_rise() - 1e6).abs() < 1e-3);
    let link = Link::new(curve, Unloading::Slope(1.2e6)).unwrap();
    for reached in [0.005, 0.01, 0.012, 0.015, 0.02, 0.03, 0.1] {
        assert_eq!(link.replaced_unloading(reached), None, "at {reached} m");
    }
}

#[test]
fn a_replaced_unloading_slope_is_told_with_the_slope_used() {
    // elastic-perfectly-plastic, k = 1e6 N/m, F_y = 1e4 N: at 0.1 m the
    // secant is 1e5 N/m, the balance F²/(2 E_L) = 1e8 / (2 · 950) N/m
    let curve = Curve::bilinear(1e6, 1e4, 0.0).unwrap();
    let tiny = Link::new(curve.clone(), Unloading::Slope(1e-297)).unwrap();
    let (given, used) = tiny.replaced_unloading(0.1).unwrap();
    assert_eq!(given, 1e-297);
    assert_relative_eq!(used, 1e5, max_relative = 1e-12);
    let set = LinkState { reached: 0.1 }.plastic_set(&tiny);
    assert!(set.abs() < 1e-12, "{set}");
    // a slope steeper than the rule's is kept; before yield nothing is told
    let steep = Link::new(curve.clone(), Unloading::Slope(2e6)).unwrap();
    assert_eq!(steep.replaced_unloading(0.1), None);
    assert_eq!(tiny.replaced_unloading(0.005), None);
    let elastic = Link::new(curve, Unloading::Elastic).unwrap();
    assert_eq!(elastic.replaced_unloading(0.1), None);
}

#[test]
fn energies_are_the_integrals_of_the_curves() {
    let curves = [
        Curve::linear(2e5).unwrap(),
        Curve::progressive(2e5, 4e7, 0.3).unwrap(),
        Curve::bilinear(2e5, 1e4, 0.2).unwrap(),
        Curve::table(vec![[0.05, 1e4], [0.1, 1.2e4], [0.3, 5e4]]).unwrap(),
        Curve::table(vec![[0.05, 1e4], [0.1, 6e3], [0.2, 4e3]]).unwrap(),
    ];
    for curve in &curves {
        for d in [0.01, 0.07, 0.25, 0.5] {
            let n = 20_000;
            let h = d / n as f64;
            let simpson: f64 = (0..n)
                .map(|i| {
                    let a = i as f64 * h;
                    h / 6.0 * (curve.force(a) + 4.0 * curve.force(a + 0.5 * h) + curve.force(a + h))
                })
                .sum();
            assert_relative_eq!(curve.energy(d), simpson, max_relative = 1e-8);
        }
    }
}

/// Load, unload, reload past δ_max and unload again: the kept line
/// gives every force and the history bit for bit.
#[test]
fn the_remembered_force_is_the_force() {
    let table = Curve::table(vec![[0.05, 1e4], [0.1, 1.2e4], [0.3, 5e4]]).unwrap();
    for unloading in [Unloading::Slope(4e5), Unloading::Elastic] {
        let link = Link::new(table.clone(), unloading).unwrap();
        let (mut state, mut memory) = (LinkState::default(), Remembered::default());
        for d in [0.02, 0.12, 0.1, 0.05, 0.0, 0.08, 0.15, 0.2, 0.13, -0.01] {
            let force = link.force(d, &mut state);
            assert_eq!(
                link.remembered_force(d, &mut memory).to_bits(),
                force.to_bits()
            );
            assert_eq!(memory.state, state);
        }
    }
}

#[test]
fn a_cycle_dissipates_the_hysteresis_and_keeps_the_set() {
    let link = Link::new(
        Curve::bilinear(1e6, 5e4, 0.0).unwrap(),
        Unloading::Slope(1e6),
    )
    .unwrap();
    let mut s = LinkState::default();
    // load to 0.2 m (yield at 0.05 m), unload to zero force
    let mut work = 0.0;
    let mut last = (0.0, 0.0);
    for i in 1..=4000 {
        let d = if i <= 2000 {
            0.2 * i as f64 / 2000.0
        } else {
            0.2 - 0.05 * (i - 2000) as f64 / 2000.0
        };
        let f = link.force(d, &mut s);
        work += 0.5 * (f + last.1) * (d - last.0);
        last = (d, f);
    }
    assert_relative_eq!(last.1, 0.0, epsilon = 1e-6);
    assert_relative_eq!(s.plastic_set(&link), 0.15, max_relative = 1e-12);
    // perfectly plastic: F_y times the plastic set
    assert_relative_eq!(s.dissipated(&link), 5e4 * 0.15, max_relative = 1e-12);
    assert_relative_eq!(work, s.dissipated(&link), max_relative = 1e-6);
    assert_relative_eq!(link.stored(0.15, &s), 0.0, epsilon = 1e-9);
}

#[test]
fn a_linear_curve_stays_elastic_under_any_unloading_slope() {
    let link = Link::new(Curve::linear(1e5).unwrap(), Unloading::Slope(1e3)).unwrap();
    let mut s = LinkState::default();
    link.force(0.3, &mut s);
    assert_relative_eq!(link.force(0.1, &mut s), 1e4, max_relative = 1e-12);
    assert_relative_eq!(s.plastic_set(&link), 0.0, epsilon = 1e-15);
    assert_relative_eq!(s.dissipated(&link), 0.0, epsilon = 1e-9);
}

/// Below its elastic limit a link unloads elastically whatever its
/// unloading slope: a bilinear link loaded to δ < δ_y = F_y/k and an
/// unloading slope twice k gives back F = k δ to zero, with no set
/// and nothing dissipated (the law took a set δ/2 here before), and a
/// linear curve stays elastic under a steeper unloading slope too.
/// Past δ_y the set is the unloading line's.
#[test]
fn below_the_elastic_limit_a_link_unloads_elastically() {
    let (k, fy) = (1e6, 5e4);
    let link = Link::new(
        Curve::bilinear(k, fy, 0.1).unwrap(),
        Unloading::Slope(2.0 * k),
    )
    .unwrap();
    assert_relative_eq!(link.curve().elastic_limit(), 0.05, max_relative = 1e-15);
    let mut s = LinkState::default();
    assert_relative_eq!(link.force(0.02, &mut s), 2e4, max_relative = 1e-12);
    assert_relative_eq!(link.force(0.01, &mut s), 1e4, max_relative = 1e-12);
    assert_relative_eq!(link.force(0.0, &mut s), 0.0, epsilon = 1e-9);
    assert_relative_eq!(s.plastic_set(&link), 0.0, epsilon = 1e-15);
    assert_relative_eq!(s.dissipated(&link), 0.0, epsilon = 1e-12);
    assert_relative_eq!(link.stored(0.01, &s), 0.5 * k * 1e-4, max_relative = 1e-12);
    // at the elastic limit still elastic; past it the unloading line
    link.force(0.05, &mut s);
    assert_relative_eq!(s.plastic_set(&link), 0.0, epsilon = 1e-15);
    link.force(0.15, &mut s);
    let top = fy + 0.1 * k * 0.1;
    assert_relative_eq!(
        s.plastic_set(&link),
        0.15 - top / (2.0 * k),
        max_relative = 1e-12
    );
    let linear = Link::new(Curve::linear(k).unwrap(), Unloading::Slope(3.0 * k)).unwrap();
    let mut s = LinkState::default();
    linear.force(0.3, &mut s);
    assert_relative_eq!(linear.force(0.1, &mut s), 1e5, max_relative = 1e-12);
    assert_relative_eq!(s.plastic_set(&linear), 0.0, epsilon = 1e-15);
    assert_relative_eq!(s.dissipated(&linear), 0.0, epsilon = 1e-9);
}

#[test]
fn a_stiffening_curve_never_gives_back_more_than_it_took() {
    let link = Link::new(
        Curve::progressive(1e5, 1e8, 0.5).unwrap(),
        Unloading::Slope(1e4),
    )
    .unwrap();
    let mut s = LinkState::default();
    for d in [0.1, 0.2, 0.4] {
        link.force(d, &mut s);
        assert!(s.dissipated(&link) >= 0.0);
        assert!(s.plastic_set(&link) >= 0.0);
        assert!(link.stored(d, &s) <= link.curve().energy(d) * (1.0 + 1e-12));
    }
    let elastic = Link::new(link.curve().clone(), Unloading::Elastic).unwrap();
    let mut e = LinkState::default();
    assert_eq!(elastic.force(-0.1, &mut e), -elastic.force(0.1, &mut e));
}
