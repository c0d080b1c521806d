//! Issue 39's Sobol' indices: the sequence is scipy's, and the indices of
//! the Ishigami function equal its analytic ones and SALib's within the
//! bootstrap error.

use bumpsim_estimate::sobol::{Indices, Input, Settings, indices, sequence};
use std::f64::consts::PI;
use std::process::Command;

/// Runs a Python snippet and parses its whitespace-separated numbers.
fn python(code: &str) -> Vec<f64> {
    let run = Command::new("python3").args(["-c", code]).output().unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    String::from_utf8_lossy(&run.stdout)
        .split_whitespace()
        .map(|v| v.parse().unwrap())
        .collect()
}

#[test]
fn the_sequence_is_scipys_unscrambled_sobol_sequence() {
    if !bumpsim_peers::python_available("scipy") {
        return;
    }
    let theirs = python(
        "from scipy.stats import qmc\n\
         import warnings; warnings.simplefilter('ignore')\n\
         for p in qmc.Sobol(24, scramble=False).random(1024): print(*p)",
    );
    let ours: Vec<f64> = sequence(24, 1024).unwrap().concat();
    assert_eq!(ours.len(), theirs.len());
    for (k, (a, b)) in ours.iter().zip(&theirs).enumerate() {
        assert!(
            (a - b).abs() < 1e-12,
            "point {}, dimension {}: {a} vs {b}",
            k / 24,
            k % 24
        );
    }
    assert!(sequence(25, 4).is_none());
}

/// `sin x1 + 7 sin² x2 + 0.1 x3⁴ sin x1` on `[−π, π]³`.
fn ishigami(x: &[f64]) -> f64 {
    x[0].sin() + 7.0 * x[1].sin().powi(2) + 0.1 * x[2].powi(4) * x[0].sin()
}

fn ishigami_indices() -> Indices {
    let inputs: Vec<Input> = ["x1", "x2", "x3"]
        .iter()
        .map(|n| Input::uniform(*n, -PI, PI))
        .collect();
    indices(&inputs, &ishigami, &Settings::new(8192, 3)).unwrap()
}

#[test]
fn ishigami_indices_are_the_analytic_ones_within_the_bootstrap_error() {
    // Sobol' & Levitan (1999); a = 7, b = 0.1
    let (a, b) = (7.0f64, 0.1f64);
    let v1 = 0.5 * (1.0 + b * PI.powi(4) / 5.0).powi(2);
    let v2 = a * a / 8.0;
    let v13 = b * b * PI.powi(8) * 8.0 / 225.0;
    let v = v1 + v2 + v13;
    let first = [v1 / v, v2 / v, 0.0];
    let total = [(v1 + v13) / v, v2 / v, v13 / v];
    let s = ishigami_indices();
    assert_eq!(s.evaluations, 8192 * 5);
    assert!((s.variance - v).abs() < 0.01 * v, "{} vs {v}", s.variance);
    for i in 0..3 {
        eprintln!(
            "{}: S {:.4} ± {:.4} (analytic {:.4}), ST {:.4} ± {:.4} (analytic {:.4})",
            s.names[i],
            s.first[i],
            s.first_conf[i],
            first[i],
            s.total[i],
            s.total_conf[i],
            total[i]
        );
        assert!((s.first[i] - first[i]).abs() < s.first_conf[i], "S {i}");
        assert!((s.total[i] - total[i]).abs() < s.total_conf[i], "ST {i}");
        assert!(s.first_conf[i] < 0.05 && s.total_conf[i] < 0.05);
    }
}

#[test]
fn ishigami_indices_equal_salibs_within_the_bootstrap_error() {
    if !bumpsim_peers::python_available("SALib") {
        return;
    }
    let theirs = python(
        "import numpy as np\n\
         from SALib.sample import sobol as sample\n\
         from SALib.analyze import sobol\n\
         from SALib.test_functions import Ishigami\n\
         problem = {'num_vars': 3, 'names': ['x1', 'x2', 'x3'], 'bounds': [[-np.pi, np.pi]] * 3}\n\
         X = sample.sample(problem, 8192, calc_second_order=False, seed=11)\n\
         r = sobol.analyze(problem, Ishigami.evaluate(X), calc_second_order=False, seed=11)\n\
         print(*r['S1'], *r['S1_conf'], *r['ST'], *r['ST_conf'])",
    );
    let s = ishigami_indices();
    for i in 0..3 {
        let (first, first_conf, total, total_conf) =
            (theirs[i], theirs[3 + i], theirs[6 + i], theirs[9 + i]);
        eprintln!(
            "{}: S {:.4} vs SALib {first:.4} ± {first_conf:.4}; ST {:.4} vs {total:.4} ± {total_conf:.4}",
            s.names[i], s.first[i], s.total[i]
        );
        let error = |a: f64, b: f64| (a * a + b * b).sqrt();
        assert!((s.first[i] - first).abs() < error(s.first_conf[i], first_conf));
        assert!((s.total[i] - total).abs() < error(s.total_conf[i], total_conf));
    }
}

#[test]
fn bad_inputs_are_errors_naming_them() {
    let f = |x: &[f64]| x[0];
    let settings = Settings::new(64, 1);
    let flat = [Input::uniform("k1", 2.0, 2.0)];
    let error = indices(&flat, &f, &settings).unwrap_err().to_string();
    assert!(error.contains("'k1'"), "{error}");
    assert!(indices(&[], &f, &settings).is_err());
    let many: Vec<Input> = (0..13)
        .map(|i| Input::uniform(format!("x{i}"), 0.0, 1.0))
        .collect();
    assert!(indices(&many, &f, &settings).is_err());
    let nan = |x: &[f64]| if x[0] > 0.5 { f64::NAN } else { x[0] };
    let error = indices(&[Input::uniform("x", 0.0, 1.0)], &nan, &settings).unwrap_err();
    assert!(error.to_string().contains("NaN"), "{error}");
    let constant = |_: &[f64]| 3.0;
    let error = indices(&[Input::uniform("x", 0.0, 1.0)], &constant, &settings).unwrap_err();
    assert!(error.to_string().contains("same"), "{error}");
    // a posterior's draws: the quantile function of the marginal
    let draws = Input::draws("m1", (0..1000).map(|k| k as f64).collect());
    let s = indices(
        &[draws, Input::uniform("x", 0.0, 1.0)],
        &|x: &[f64]| x[0],
        &Settings::new(4096, 1),
    )
    .unwrap();
    assert!(
        (s.first[0] - 1.0).abs() < s.first_conf[0] && s.total[1] == 0.0,
        "{s:?}"
    );
}
