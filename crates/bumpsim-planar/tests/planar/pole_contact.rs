//! A pole's contact on a finely divided bumper (w21, docs/planar.md "Pole
//! contact"): a strip narrow against the pole is crushed at its centre,
//! whose crush is the strip's mean to about w²/(24 r), so the peak force
//! of 40 strips lies within 2 % of that of 640, the foam taken as a
//! continuum (+1.2 % measured). The rule before w21 (every strip at its
//! point nearest the axis) put it 6.8 % above.

use bumpsim_core::model::MsdModel;
use bumpsim_impact::bumper::Bumper;
use bumpsim_planar::car::Layout;
use bumpsim_planar::{Face, PlanarCar, Settings, Striker, simulate};

/// Peak force, N, of a rigid 1200 kg car at 2 m/s into a 254 mm pole 0.1 m
/// left of its axis, its 1.6 m bumper a linear foam (4 MN/m across the
/// whole width) in `segments` strips.
fn peak_force(segments: usize) -> f64 {
    let body = MsdModel::new(vec![1200.0], vec![], vec![]).unwrap();
    let foam = Bumper::three_part(4e6, 1e9, 8e6).unwrap();
    let layout = Layout {
        segments,
        bumper_width: 1.6,
        ..Layout::default()
    };
    let car = PlanarCar::symmetric(&body, &foam, &layout).unwrap();
    let pole = Striker::barrier(Face::pole_of_diameter(0.254, 0.1), 2.0);
    simulate(&car, &pole, &Settings::default())
        .unwrap()
        .peak_force
}

#[test]
fn forty_strips_under_a_pole_push_as_the_continuum_does() {
    let (coarse, fine) = (peak_force(40), peak_force(640));
    let error = coarse / fine - 1.0;
    eprintln!("peak force: 40 strips {coarse:.1} N, 640 strips {fine:.1} N ({error:+.4})");
    assert!(error.abs() < 0.02, "{error}");
}
