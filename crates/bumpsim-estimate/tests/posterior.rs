//! Issue 39's posterior against analytic answers: a 2-parameter linear
//! model with Gaussian errors, whose posterior under a flat prior is a
//! Gaussian (σ known) or a Student t with n − 2 degrees of freedom (σ
//! integrated out under p(σ) ∝ 1/σ); the chain is the same on one thread
//! as on two, and a run too short says so.

use bumpsim_estimate::lm::LeastSquares;
use bumpsim_estimate::posterior::{Noise, Posterior, Settings, posterior};
use bumpsim_estimate::uncertainty::Parameter;
use nalgebra::{DMatrix, Matrix2, Vector2};
use statrs::distribution::{ContinuousCDF, Normal, StudentsT};

/// y = a + b x at 12 points with fixed "noise".
struct Line {
    x: Vec<f64>,
    y: Vec<f64>,
}

impl LeastSquares for Line {
    fn residual_count(&self) -> usize {
        self.x.len()
    }
    fn parameter_count(&self) -> usize {
        2
    }
    fn evaluate(&self, p: &[f64], r: &mut [f64], jac: Option<&mut DMatrix<f64>>) -> bool {
        for ((r, x), y) in r.iter_mut().zip(&self.x).zip(&self.y) {
            *r = p[0] + p[1] * x - y;
        }
        if let Some(j) = jac {
            for k in 0..self.x.len() {
                j[(k, 0)] = 1.0;
                j[(k, 1)] = self.x[k];
            }
        }
        true
    }
}

fn line() -> Line {
    let x: Vec<f64> = (0..12).map(|k| 0.25 * k as f64).collect();
    let noise = [
        0.3, -0.5, 0.1, 0.4, -0.2, -0.6, 0.5, 0.2, -0.3, 0.0, 0.6, -0.4,
    ];
    let y = x
        .iter()
        .zip(noise)
        .map(|(x, e)| 2.0 + 3.0 * x + e)
        .collect();
    Line { x, y }
}

/// The least-squares estimate, (XᵀX)⁻¹ and the objective at the estimate.
fn least_squares(l: &Line) -> (Vector2<f64>, Matrix2<f64>, f64) {
    let n = l.x.len() as f64;
    let (sx, sxx) = (
        l.x.iter().sum::<f64>(),
        l.x.iter().map(|x| x * x).sum::<f64>(),
    );
    let xtx = Matrix2::new(n, sx, sx, sxx);
    let xty = Vector2::new(
        l.y.iter().sum(),
        l.x.iter().zip(&l.y).map(|(x, y)| x * y).sum(),
    );
    let inverse = xtx.try_inverse().unwrap();
    let beta = inverse * xty;
    let objective =
        l.x.iter()
            .zip(&l.y)
            .map(|(x, y)| (beta[0] + beta[1] * x - y).powi(2))
            .sum();
    (beta, inverse, objective)
}

fn run(noise: Noise, walkers: usize, steps: usize) -> Posterior {
    let l = line();
    let (beta, _, _) = least_squares(&l);
    let parameters = [
        Parameter::with_symbol("a", "-").linear(1.0),
        Parameter::with_symbol("b", "-").linear(1.0),
    ];
    let mut settings = Settings::new(noise, 7);
    settings.ensemble.walkers = walkers;
    settings.ensemble.steps = steps;
    settings.ensemble.burn = steps / 10;
    let bounds = (vec![-1e3; 2], vec![1e3; 2]);
    posterior(
        &|| &l,
        &parameters,
        &[0, 1],
        beta.as_slice(),
        (&bounds.0, &bounds.1),
        &settings,
    )
    .unwrap()
}

/// Means within 2 % of the analytic standard deviation, 90 % interval ends
/// within 2 % of the analytic half-width.
fn compare(post: &Posterior, scale: [f64; 2], mean: Vector2<f64>, half: f64) {
    for i in 0..2 {
        let [low, high] = post.ci90[i].unwrap();
        let width = half * scale[i];
        eprintln!(
            "{}: mean {:.5} (analytic {:.5}), 90 % {low:.5} .. {high:.5} (analytic {:.5} .. {:.5})",
            post.names[i],
            post.mean[i],
            mean[i],
            mean[i] - width,
            mean[i] + width
        );
        assert!((post.mean[i] - mean[i]).abs() < 0.02 * scale[i], "mean {i}");
        assert!((low - (mean[i] - width)).abs() < 0.02 * width, "low {i}");
        assert!((high - (mean[i] + width)).abs() < 0.02 * width, "high {i}");
    }
    assert!(
        post.diagnostics.converged,
        "{:?}",
        post.diagnostics.warnings
    );
}

#[test]
fn a_linear_gaussian_posterior_is_the_analytic_one_within_two_percent() {
    let l = line();
    let (beta, inverse, objective) = least_squares(&l);
    // σ known: N(β̂, σ² (XᵀX)⁻¹)
    let sigma = 0.4;
    let post = run(Noise::Known(sigma), 64, 12_000);
    let sd = |i: usize| sigma * inverse[(i, i)].sqrt();
    let z = Normal::new(0.0, 1.0).unwrap().inverse_cdf(0.95);
    compare(&post, [sd(0), sd(1)], beta, z);
    // σ integrated out: Student t, ν = n − 2, scale s² (XᵀX)⁻¹
    let nu = (l.x.len() - 2) as f64;
    let s2 = objective / nu;
    let post = run(Noise::Effective(l.x.len() as f64), 64, 12_000);
    let scale = |i: usize| (s2 * inverse[(i, i)]).sqrt();
    let t = StudentsT::new(0.0, 1.0, nu).unwrap().inverse_cdf(0.95);
    compare(&post, [scale(0), scale(1)], beta, t);
    // the t's intervals are 10 % wider than the normal's: the test tells them apart
    assert!(t / z > 1.09);
}

#[test]
fn the_chain_is_the_same_on_any_number_of_threads_and_a_short_run_is_flagged() {
    let pool = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
    };
    let one = pool(1).install(|| run(Noise::Known(0.4), 8, 60));
    let two = pool(2).install(|| run(Noise::Known(0.4), 8, 60));
    assert_eq!(one, two);
    assert!(!one.diagnostics.converged);
    let warning = one.diagnostics.warnings.join("; ");
    assert!(
        warning.contains("has not converged") && warning.contains("run more steps"),
        "{warning}"
    );
}
