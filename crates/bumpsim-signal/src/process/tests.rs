//! The steps, their TOML spelling, and channels put on one time base.

use super::*;
use approx::assert_relative_eq;
use bumpsim_core::channel::Channel;
use bumpsim_core::series::UniformSeries;
use bumpsim_core::units::Dimension;

fn channel(start: f64, values: Vec<f64>, dimension: Dimension) -> Channel {
    Channel::new(
        "X",
        "x",
        dimension,
        UniformSeries::new(start, 0.1, values).unwrap(),
    )
}

#[test]
fn bias_trim_shift_and_mass() {
    let c = channel(-0.2, vec![1.0, 1.0, 3.0, 5.0], Dimension::Acceleration);
    let b = Step::PretriggerBias(true).apply(&c).unwrap();
    assert_relative_eq!(b.series.values()[3], 4.0);
    let t = Step::Trim([0.0, 0.1]).apply(&c).unwrap();
    assert_eq!(t.series.values(), &[3.0, 5.0]);
    let s = Step::Shift(0.2).apply(&c).unwrap();
    assert_relative_eq!(s.series.start(), 0.0);
    let f = Step::Mass(2.0).apply(&c).unwrap();
    assert_eq!(f.dimension, Dimension::Force);
    assert!(Step::Mass(2.0).apply(&f).is_err());
    assert!(Step::Bias([5.0, 6.0]).apply(&c).is_err());
    assert!(Step::Trim([5.0, 6.0]).apply(&c).is_err());
    assert!(Step::Integrate(0.0).apply(&f).is_err());
}

#[test]
fn resampling_names_interpolated_and_trimmed_channels() {
    let a = channel(0.0, vec![1.0, 2.0, 3.0], Dimension::Force);
    assert_eq!(resampling(&[a.clone(), a.clone()]), None);
    // half a step later: the common base starts at 0.05 s, ends at 0.15 s
    let mut b = channel(0.05, vec![1.0, 2.0, 3.0], Dimension::Force);
    b.code = "Y\u{1b}[31m".into();
    let r = resampling(&[a.clone(), b.clone()]).unwrap();
    assert_eq!(r.interpolated.len(), 1);
    assert_eq!(r.interpolated[0].0, 0);
    approx::assert_relative_eq!(r.span[0], 0.05, max_relative = 1e-12);
    approx::assert_relative_eq!(r.span[1], 0.15, max_relative = 1e-12);
    assert_eq!(r.trimmed, [(0, 2), (1, 1)]);
    // the common base is what align and combine use
    let (times, _) = align(&[a, b]).unwrap();
    assert_eq!(times.len(), 2);
    let text = r.to_string();
    assert_eq!(
        text,
        r"X and Y\u001B[31m put on one time base, every 100.0 ms from 50.00 ms to 150.0 ms; X (every 100.0 ms) interpolated linearly; X: 2 samples outside that span left out; Y\u001B[31m: 1 sample outside that span left out"
    );
}

#[test]
fn many_resampled_channels_are_named_in_groups() {
    let at = |code: &str, start: f64| {
        let mut c = channel(start, vec![1.0; 5], Dimension::Force);
        c.code = code.into();
        c
    };
    let five = [
        at("A", 0.0),
        at("B", 0.05),
        at("C", 0.05),
        at("D", 0.05),
        at("E", 0.0),
    ];
    let text = resampling(&five).unwrap().to_string();
    assert_eq!(
        text,
        "5 channels put on one time base, every 100.0 ms from 50.00 ms to 350.0 ms; A, E (every 100.0 ms) interpolated linearly; A, E: 2 samples each outside that span left out; B, C, D: 1 sample each outside that span left out"
    );
}

#[test]
fn combine_mean_and_sum_on_the_overlap() {
    let a = channel(0.0, vec![1.0, 2.0, 3.0], Dimension::Force);
    let b = channel(0.1, vec![10.0, 20.0, 30.0], Dimension::Force);
    let sum = combine(&[a.clone(), b.clone()], Combine::Sum, "A+B").unwrap();
    assert_eq!(sum.series.values(), &[12.0, 23.0]);
    let mean = combine(&[a.clone(), b], Combine::Mean, "m").unwrap();
    assert_relative_eq!(mean.series.values()[0], 6.0);
    let c = channel(0.0, vec![1.0], Dimension::Length);
    assert!(combine(&[a, c], Combine::Sum, "bad").is_err());
    assert!(combine(&[], Combine::Sum, "none").is_err());
}

#[test]
fn resample_interpolates_linearly() {
    let a = channel(0.0, vec![0.0, 1.0, 2.0], Dimension::Length);
    let r = Step::Resample(0.05).apply(&a).unwrap();
    assert_eq!(r.series.len(), 5);
    assert_relative_eq!(r.series.values()[3], 1.5, max_relative = 1e-12);
}

#[test]
fn steps_parse_from_toml_like_json() {
    let steps: Vec<Step> = serde_json::from_str(
        r#"[{"cfc": 60}, {"bias": [-0.05, 0.0]}, {"butterworth": {"order": 4, "cutoff": 300}}]"#,
    )
    .unwrap();
    assert_eq!(steps[0], Step::Cfc(60.0));
    assert!(matches!(
        steps[2],
        Step::Butterworth(ButterworthStep {
            zero_phase: true,
            ..
        })
    ));
}
