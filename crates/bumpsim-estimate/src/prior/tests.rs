//! The prior module's tests: the gradient against differences, the
//! information, the lines.

use super::*;
use approx::assert_relative_eq;

/// Two residuals on three parameters: r = [p0 − 1, p1 + p2 − 2].
struct Linear;
impl LeastSquares for Linear {
    fn residual_count(&self) -> usize {
        2
    }
    fn parameter_count(&self) -> usize {
        3
    }
    fn evaluate(&self, p: &[f64], r: &mut [f64], j: Option<&mut DMatrix<f64>>) -> bool {
        r[0] = p[0] - 1.0;
        r[1] = p[1] + p[2] - 2.0;
        if let Some(j) = j {
            j.fill(0.0);
            j[(0, 0)] = 1.0;
            j[(1, 1)] = 1.0;
            j[(1, 2)] = 1.0;
        }
        true
    }
}

#[test]
fn the_jacobian_and_the_normal_equations_agree_with_differences() {
    let prior = Prior::sum("total", vec![0, 2], 5.0, 0.1).unwrap();
    let single = Prior::single("one", 1, 2.0, 0.3).unwrap();
    let problem = Priored::new(Linear, vec![prior, single], 0.5).unwrap();
    let p = [0.3, -0.2, 1.1];
    let mut r = vec![0.0; 4];
    let mut jac = DMatrix::zeros(4, 3);
    assert!(problem.evaluate(&p, &mut r, Some(&mut jac)));
    // the sum prior's residual: 0.5 (ln(e^0.3 + e^1.1) − ln 5)/0.1
    let v = (0.3f64.exp() + 1.1f64.exp()).ln();
    assert_relative_eq!(r[2], 5.0 * (v - 5f64.ln()), epsilon = 1e-12);
    for j in 0..3 {
        let mut q = p;
        q[j] += 1e-7;
        let mut rq = vec![0.0; 4];
        problem.evaluate(&q, &mut rq, None);
        for i in 0..4 {
            assert_relative_eq!((rq[i] - r[i]) / 1e-7, jac[(i, j)], epsilon = 1e-5);
        }
    }
    let (mut jtj, mut g) = (DMatrix::zeros(3, 3), DVector::zeros(3));
    let mut r2 = vec![0.0; 4];
    assert!(problem.normal(&p, &mut r2, &mut jtj, &mut g));
    assert_relative_eq!(jtj, jac.transpose() * &jac, epsilon = 1e-12);
    assert_relative_eq!(
        g,
        jac.transpose() * DVector::from_column_slice(&r),
        epsilon = 1e-12
    );
}

#[test]
fn a_ratio_priors_gradient_information_and_line_are_its_difference_of_logs() {
    let ratio = Prior::ratio("left/right.k", 1, 2, 1.0, 0.2)
        .unwrap()
        .from_source("mirror images");
    let problem = Priored::new(Linear, vec![ratio.clone()], 0.5).unwrap();
    let p = [0.3, -0.2, 1.1];
    let mut r = vec![0.0; 3];
    let mut jac = DMatrix::zeros(3, 3);
    assert!(problem.evaluate(&p, &mut r, Some(&mut jac)));
    // 0.5 (ln(θ1/θ2) − ln 1)/0.2 = 2.5 (−0.2 − 1.1)
    assert_relative_eq!(r[2], 2.5 * (-1.3), epsilon = 1e-12);
    for j in 0..3 {
        let mut q = p;
        q[j] += 1e-7;
        let mut rq = vec![0.0; 3];
        problem.evaluate(&q, &mut rq, None);
        assert_relative_eq!((rq[2] - r[2]) / 1e-7, jac[(2, j)], epsilon = 1e-5);
    }
    assert_relative_eq!(jac[(2, 1)], 2.5, epsilon = 1e-12);
    assert_relative_eq!(jac[(2, 2)], -2.5, epsilon = 1e-12);
    let (mut jtj, mut g) = (DMatrix::zeros(3, 3), DVector::zeros(3));
    assert!(problem.normal(&p, &mut [0.0; 3], &mut jtj, &mut g));
    assert_relative_eq!(jtj, jac.transpose() * &jac, epsilon = 1e-12);
    // its information is (e1 − e2)(e1 − e2)ᵀ/s²: none on the level
    let info = information(std::slice::from_ref(&ratio), &p);
    assert_relative_eq!(info[(1, 1)], 25.0, epsilon = 1e-12);
    assert_relative_eq!(info[(1, 2)], -25.0, epsilon = 1e-12);
    assert_relative_eq!((&info * DVector::from_element(3, 1.0)).norm(), 0.0);
    // the estimate is the ratio; z its log over the spread
    let out = moved(std::slice::from_ref(&ratio), &p);
    assert_relative_eq!(out[0].estimate, (-1.3f64).exp(), epsilon = 1e-12);
    assert_relative_eq!(out[0].z, -6.5, epsilon = 1e-12);
    let line = text(&out, &|_, v| format!("{v} N/m"));
    assert!(
        line.contains("prior left/right.k: left/right ratio 1.000 ± 0.200 (ln) (mirror images) -> 0.273 (moved -6.50 sd): the data disagree"),
        "{line}"
    );
    // not a prior on one parameter's level
    assert!(prior_only(&[ratio], &[Some(1.0), Some(1.0), Some(1.0)]).is_empty());
    assert!(Prior::ratio("same", 1, 1, 1.0, 0.2).is_err());
    let far = Prior::ratio("far", 0, 7, 1.0, 0.2).unwrap();
    assert!(Priored::new(Linear, vec![far], 1.0).is_err());
}

#[test]
fn hostile_priors_are_refused_by_name() {
    let e = |r: Result<Prior, PriorError>| r.unwrap_err().to_string();
    assert!(e(Prior::single("m", 0, f64::NAN, 0.1)).contains("prior 'm': centre"));
    assert!(e(Prior::single("m", 0, -3.0, 0.1)).contains("centre"));
    assert!(e(Prior::single("m", 0, 3.0, -0.1)).contains("prior 'm': spread"));
    assert!(e(Prior::single("m", 0, 3.0, f64::INFINITY)).contains("spread"));
    // issue 44's hostile pass: a centre beyond the search's range ran to
    // exit 0 at the bounds, a spread of 1e-300 overflowed every start
    assert!(e(Prior::single("m", 0, 1e300, 0.1)).contains("from 1e-12 to 1e15"));
    assert!(e(Prior::single("m", 0, 1e-300, 0.1)).contains("centre"));
    assert!(e(Prior::single("m", 0, 3.0, 1e-300)).contains("from 1e-6 to 100"));
    assert!(e(Prior::single("m", 0, 3.0, 1e300)).contains("spread"));
    let far = Prior::single("far", 7, 1.0, 0.1).unwrap();
    let Err(err) = Priored::new(Linear, vec![far], 1.0) else {
        panic!("an index beyond the problem is refused")
    };
    assert!(err.to_string().contains("prior 'far'"), "{err}");
    assert!(Priored::new(Linear, vec![], f64::NAN).is_err());
}

#[test]
fn moved_counts_prior_standard_deviations_and_warns_beyond_two() {
    let prior = Prior::single("I", 0, 100.0, 0.1)
        .unwrap()
        .from_source("geometry");
    let out = moved(&[prior], &[(100f64 * 1.5).ln()]);
    assert_relative_eq!(out[0].z, 1.5f64.ln() / 0.1, epsilon = 1e-12);
    assert_relative_eq!(out[0].estimate, 150.0, epsilon = 1e-9);
    assert_eq!(warnings(&out).len(), 1);
    let line = text(&out, &|_, v| format!("{v:.0} kg·m²"));
    assert!(
        line.contains("100 kg·m²") && line.contains("(geometry)") && line.contains("+4.05 sd"),
        "{line}"
    );
}

#[test]
fn a_parameter_the_data_hardly_inform_is_named() {
    let priors = [
        Prior::single("a", 0, 1.0, 0.2).unwrap(),
        Prior::single("b", 1, 1.0, 0.2).unwrap(),
        Prior::sum("ab", vec![0, 1], 2.0, 0.2).unwrap(),
    ];
    let found = prior_only(&priors, &[Some(0.19), Some(0.05)]);
    assert_eq!(found.len(), 1);
    assert_eq!((found[0].0, found[0].1.name.as_str()), (0, "a"));
    assert!(prior_only(&priors, &[None, None]).is_empty());
}

#[test]
fn the_priors_information_narrows_the_datas_covariance() {
    use crate::uncertainty::{Correlation, Uncertainty};
    // two parameters, data sd 0.2 and 0.4 of ln θ, correlated 0.5
    let u = Uncertainty {
        names: vec!["a".into(), "b".into()],
        standard_errors: vec![Some(0.2 * 2.0), Some(0.4 * 3.0)],
        ci95: vec![
            Some([2.0 * (-0.392f64).exp(), 2.0 * 0.392f64.exp()]),
            Some([3.0 * (-0.784f64).exp(), 3.0 * 0.784f64.exp()]),
        ],
        at_bound: vec![false; 2],
        fixed: vec![false; 2],
        correlation: vec![vec![Some(1.0), Some(0.5)], vec![Some(0.5), Some(1.0)]],
        residual_std: 1.0,
        degrees_of_freedom: 100,
        singular_values: vec![],
        condition: 1.0,
        scales: vec![],
        determined: vec![Some(true); 2],
        weakest_direction: vec![],
        error_model: Correlation::RandomWalk,
        residual_correlation: 0.0,
        inflation: 1.0,
        warnings: vec![],
    };
    let theta = [2.0, 3.0];
    let p = [2f64.ln(), 3f64.ln()];
    let prior = Prior::single("b", 1, 3.0, 0.3).unwrap();
    let out = with_priors(u, &[prior], &theta, &[0, 1], &p);
    let c: DMatrix<f64> = DMatrix::from_row_slice(2, 2, &[0.04, 0.04, 0.04, 0.16]);
    let expected: DMatrix<f64> = (c.try_inverse().unwrap()
        + DMatrix::from_row_slice(2, 2, &[0.0, 0.0, 0.0, 1.0 / 0.09]))
    .try_inverse()
    .unwrap();
    assert_relative_eq!(
        out.standard_errors[1].unwrap(),
        3.0 * expected[(1, 1)].sqrt(),
        epsilon = 1e-12
    );
    assert_relative_eq!(
        out.standard_errors[0].unwrap(),
        2.0 * expected[(0, 0)].sqrt(),
        epsilon = 1e-12
    );
    let [low, high] = out.ci95[1].unwrap();
    assert_relative_eq!(
        (high / 3.0).ln(),
        1.96 * expected[(1, 1)].sqrt(),
        epsilon = 1e-9
    );
    assert_relative_eq!(low * high, 9.0, epsilon = 1e-9);
}

#[test]
fn noise_is_the_inflated_residual_deviation() {
    assert_relative_eq!(noise(8.0, 10, 2, 1.0), 1.0);
    assert_relative_eq!(noise(8.0, 10, 2, 4.0), 2.0);
    assert!(noise(0.0, 10, 2, 1.0) > 0.0);
}

#[test]
fn a_tight_spread_prints_its_digits() {
    // issue 44's hostile pass: a spread of 1e-6 printed "± 0.000"
    assert_eq!(spread_text(1e-6), "1.00e-6");
    assert_eq!(spread_text(0.005), "0.00500");
    // the recorded outputs' spreads print as before
    assert_eq!(spread_text(0.01), "0.010");
    assert_eq!(spread_text(1.1513), "1.151");
    let moved = Moved {
        name: "m".into(),
        centre: 2.0,
        spread: 1e-6,
        source: String::new(),
        ratio: false,
        estimate: 2.0,
        z: 0.0,
    };
    let line = text(&[moved], &|_, v| format!("{v} kg"));
    assert!(line.contains("± 1.00e-6 (ln)"), "{line}");
}
