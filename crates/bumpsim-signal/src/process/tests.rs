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
    let one = Step::Trim([0.1, 0.1]).apply(&c).unwrap_err().to_string();
    assert!(one.contains("keeps one sample"), "{one}");
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

/// A window of three values ran as its first two (hostile pass of issue
/// 34): a trim or bias window is exactly two times.
#[test]
fn a_window_of_another_count_is_refused() {
    #[derive(Debug, serde::Deserialize)]
    struct Pipeline {
        #[allow(dead_code)]
        steps: Vec<Step>,
    }
    for text in [
        "steps = [{ trim = [0.0, 0.3, 0.5] }]",
        "steps = [{ bias = [0.0] }]",
    ] {
        let error = toml::from_str::<Pipeline>(text).unwrap_err().to_string();
        assert!(error.contains("exactly 2 numbers"), "{text}: {error}");
    }
    let fine: Pipeline = toml::from_str("steps = [{ trim = [0.0, 0.3] }]").unwrap();
    assert_eq!(fine.steps, [Step::Trim([0.0, 0.3])]);
}

fn coded(code: &str, fine: &str) -> Channel {
    let series = UniformSeries::new(0.0, 1e-4, vec![0.0, 1.0, 2.0, 1.0]).unwrap();
    let mut c = Channel::new(code, "cell", Dimension::Force, series);
    c.set_meta("Comments", fine);
    c
}

#[test]
fn a_sum_says_it_is_one_and_codes_the_common_fields_with_su() {
    let cells = [
        coded("B0LOMA010100FOXP", "cell 1"),
        coded("B0LOMA010200FOXP", "cell 2"),
        coded("B0LOMA020100FOXP", "cell 3"),
    ];
    let sum = combine(&cells, Combine::Sum, "B0LOMA*").unwrap();
    assert_eq!(sum.name, "sum of 3 channels B0LOMA*");
    assert_eq!(sum.meta("Channel code"), Some("B0LOMASU0000FOXP"));
    assert_eq!(
        bumpsim_io::test_data::iso_header::iso_code(&sum),
        "B0LOMASU0000FOXP"
    );
    assert!(
        sum.meta("Comments")
            .unwrap()
            .starts_with("sum of 3 channels: B0LOMA010100FOXP")
    );
    let sides = [
        coded("10SIMELE0000ACXP", "left"),
        coded("10SIMERI0000ACXP", "right"),
    ];
    let mean = combine(&sides, Combine::Mean, "sides").unwrap();
    assert_eq!(mean.meta("Channel code"), Some("10SIMEAV0000ACXP"));
}

#[test]
fn a_finer_cfc_after_a_coarser_one_keeps_the_coarser_label_and_says_so() {
    let values: Vec<f64> = (0..400).map(|k| (k as f64 * 0.05).sin()).collect();
    let raw = Channel::new(
        "10SIMELE0000ACXP",
        "x",
        Dimension::Acceleration,
        UniformSeries::new(0.0, 1e-4, values).unwrap(),
    );
    let cfc60 = Step::Cfc(60.0).apply(&raw).unwrap();
    assert_eq!(cfc60.code, "10SIMELE0000ACXD");
    let again = Step::Cfc(1000.0).apply(&cfc60).unwrap();
    assert_eq!(again.code, "10SIMELE0000ACXD");
    assert_eq!(again.meta("Channel frequency class"), Some("60"));
    let said = notes(&[Step::Cfc(1000.0)], &cfc60);
    assert_eq!(said.len(), 1);
    assert!(said[0].contains("CFC 1000 after CFC 60"), "{said:?}");
    assert!(notes(&[Step::Cfc(60.0), Step::Cfc(180.0)], &raw)[0].contains("CFC 180 after CFC 60"));
    assert!(notes(&[Step::Cfc(180.0), Step::Cfc(60.0)], &raw).is_empty());
}

#[test]
fn a_bias_records_its_offset_interval() {
    let c = channel(-0.2, vec![1.0, 1.0, 3.0, 5.0], Dimension::Acceleration);
    let b = Step::PretriggerBias(true).apply(&c).unwrap();
    assert_eq!(b.meta("Start offset interval"), Some("-2e-1"));
    assert_eq!(b.meta("End offset interval"), Some("0e0"));
    let w = Step::Bias([-0.2, -0.1]).apply(&c).unwrap();
    assert_eq!(w.meta("End offset interval"), Some("-1e-1"));
}
