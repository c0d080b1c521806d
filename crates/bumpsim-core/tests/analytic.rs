//! Simulation checked against analytic solutions, conservation laws and an
//! independent fine-step Runge–Kutta reference.

use approx::assert_relative_eq;
use bumpsim_core::modal::ModalForm;
use bumpsim_core::prelude::*;
use bumpsim_core::state_space::{StateSpace, elastic_modes};
use proptest::prelude::*;

fn thesis_model() -> MsdModel {
    MsdModel::new(
        vec![1.8, 74.8, 1670.0],
        vec![6.46e6, 1.97e5],
        vec![4.75e5, 5.0e5],
    )
    .unwrap()
}

/// A pendulum-like half-sine pulse, 40 kN for 60 ms, then zero; 10 kHz.
fn half_sine(samples: usize) -> UniformSeries {
    let values = (0..samples)
        .map(|i| {
            let t = i as f64 * 1e-4;
            if t < 0.06 {
                4e4 * (std::f64::consts::PI * t / 0.06).sin()
            } else {
                0.0
            }
        })
        .collect();
    UniformSeries::new(0.0, 1e-4, values).unwrap()
}

/// Deterministic rough force (a linear congruential sequence), N.
fn rough_force(samples: usize, step: f64) -> UniformSeries {
    let mut state: u64 = 12345;
    let values = (0..samples)
        .map(|_| {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((state >> 11) as f64 / (1u64 << 53) as f64 - 0.3) * 2e4
        })
        .collect();
    UniformSeries::new(0.0, step, values).unwrap()
}

#[test]
fn free_mass_under_constant_force_is_exact_with_zoh_and_foh() {
    let (mass, force) = (1450.0, 2.5e4);
    let car = MsdModel::new(vec![mass], vec![], vec![]).unwrap();
    let series = UniformSeries::new(0.0, 1e-4, vec![force; 1001]).unwrap();
    for method in [Method::Zoh, Method::Foh] {
        let r = simulate(&car, &series, method, &InitialState::Rest).unwrap();
        for k in [1, 10, 500, 1000] {
            let t = r.time[k];
            assert_relative_eq!(
                r.displacement[0][k],
                force * t * t / (2.0 * mass),
                max_relative = 1e-12
            );
            assert_relative_eq!(r.velocity[0][k], force * t / mass, max_relative = 1e-12);
            assert_relative_eq!(r.acceleration[0][k], force / mass, max_relative = 1e-12);
        }
    }
}

#[test]
fn foh_is_exact_for_a_force_ramp() {
    // f = a t on a free mass: x = a t³ / 6m
    let (mass, slope) = (2.0, 300.0);
    let car = MsdModel::new(vec![mass], vec![], vec![]).unwrap();
    let series = UniformSeries::new(
        0.0,
        1e-3,
        (0..101).map(|i| slope * i as f64 * 1e-3).collect(),
    )
    .unwrap();
    let r = simulate(&car, &series, Method::Foh, &InitialState::Rest).unwrap();
    let t = r.time[100];
    assert_relative_eq!(
        r.displacement[0][100],
        slope * t.powi(3) / (6.0 * mass),
        max_relative = 1e-11
    );
    // zoh holds each sample: its error is first order in T, visibly larger
    let z = simulate(&car, &series, Method::Zoh, &InitialState::Rest).unwrap();
    assert!((z.displacement[0][100] / r.displacement[0][100] - 1.0).abs() > 1e-3);
}

#[test]
fn two_dof_free_vibration_has_the_analytic_frequency() {
    let (m1, m2, k): (f64, f64, f64) = (650.0, 400.0, 4e6);
    let omega = (k * (1.0 / m1 + 1.0 / m2)).sqrt();
    let car = MsdModel::new(vec![m1, m2], vec![0.0], vec![k]).unwrap();
    let u0 = 1e-3;
    let series = UniformSeries::new(0.0, 1e-4, vec![0.0; 5001]).unwrap();
    let r = simulate(
        &car,
        &series,
        Method::Zoh,
        &InitialState::State(vec![u0, 0.0, 0.0, 0.0]),
    )
    .unwrap();
    for k in 0..series.len() {
        let u = r.displacement[0][k] - r.displacement[1][k];
        assert_relative_eq!(u, u0 * (omega * r.time[k]).cos(), epsilon = 1e-12);
    }
    // frequency from the up-crossings of the relative displacement, independent of the formula above
    let u: Vec<f64> = (0..series.len())
        .map(|k| r.displacement[0][k] - r.displacement[1][k])
        .collect();
    let crossings: Vec<f64> = (1..u.len())
        .filter(|&k| u[k - 1] < 0.0 && u[k] >= 0.0)
        .map(|k| r.time[k - 1] + 1e-4 * u[k - 1] / (u[k - 1] - u[k]))
        .collect();
    let period = (crossings.last().unwrap() - crossings[0]) / (crossings.len() - 1) as f64;
    assert_relative_eq!(std::f64::consts::TAU / period, omega, max_relative = 1e-5);
    let mode = elastic_modes(&car).unwrap()[0];
    assert_relative_eq!(mode.natural_frequency(), omega, max_relative = 1e-10);
}

#[test]
fn momentum_equals_impulse() {
    let car = MsdModel::new(vec![150.0, 500.0, 800.0], vec![1e2, 2e5], vec![5e5, 5e5]).unwrap();
    let force = rough_force(2000, 1e-4);
    for method in [Method::Zoh, Method::Foh] {
        let r = simulate(&car, &force, method, &InitialState::UniformVelocity(1.5)).unwrap();
        assert!(
            r.momentum_error() < 1e-9,
            "{method}: {}",
            r.momentum_error()
        );
    }
}

#[test]
fn energy_balances_with_exact_holds() {
    let car = MsdModel::new(vec![150.0, 500.0, 800.0], vec![1e2, 2e5], vec![5e5, 5e5]).unwrap();
    let force = rough_force(2000, 1e-4);
    for method in [Method::Zoh, Method::Foh] {
        let r = simulate(&car, &force, method, &InitialState::Rest).unwrap();
        assert!(
            r.energy.relative_error() < 1e-6,
            "{method}: {}",
            r.energy.relative_error()
        );
        assert!(r.energy.dissipated.last().unwrap() > &0.0);
    }
}

#[test]
fn thesis_model_runs_with_zoh_and_is_refused_by_taylor1() {
    let car = thesis_model();
    let force = half_sine(1500);
    let r = simulate(&car, &force, Method::Zoh, &InitialState::Rest).unwrap();
    assert!(r.displacement.iter().flatten().all(|v| v.is_finite()));
    assert!(r.momentum_error() < 1e-9, "{}", r.momentum_error());
    assert!(
        r.energy.relative_error() < 1e-6,
        "{}",
        r.energy.relative_error()
    );
    let refused = simulate(&car, &force, Method::Taylor1, &InitialState::Rest).unwrap_err();
    let message = refused.to_string();
    assert!(
        message.contains("unstable") && message.contains("largest stable step"),
        "{message}"
    );
}

#[test]
fn taylor1_with_substeps_approaches_zoh() {
    let car = thesis_model();
    let force = half_sine(1500);
    let exact = simulate(&car, &force, Method::Zoh, &InitialState::Rest).unwrap();
    let sim = Simulator::with_substeps(&car, Method::Taylor1, 1e-4, Substeps::Auto).unwrap();
    let euler = sim.run(&force, &InitialState::Rest).unwrap();
    let peak = exact.peak_displacement(0).1.abs();
    let worst = exact.displacement[0]
        .iter()
        .zip(&euler.displacement[0])
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(
        worst < 1e-3 * peak,
        "taylor1 with {} sub-steps off by {worst} m",
        sim.discrete().substeps()
    );
}

/// Classical RK4 on X' = A X + B f with f held over each sample, `sub` steps per sample.
fn rk4_reference(car: &MsdModel, force: &UniformSeries, sub: usize) -> Vec<Vec<f64>> {
    let ss = StateSpace::from_model(car);
    let (a, b) = (ss.a(), ss.b());
    let h = force.step() / sub as f64;
    let mut x = nalgebra::DVector::zeros(ss.order());
    let mut out = vec![x.as_slice().to_vec()];
    for &f in &force.values()[..force.len() - 1] {
        let rate = |x: &nalgebra::DVector<f64>| a * x + b * f;
        for _ in 0..sub {
            let k1 = rate(&x);
            let k2 = rate(&(&x + &k1 * (h / 2.0)));
            let k3 = rate(&(&x + &k2 * (h / 2.0)));
            let k4 = rate(&(&x + &k3 * h));
            x += (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (h / 6.0);
        }
        out.push(x.as_slice().to_vec());
    }
    out
}

fn stable_model() -> impl Strategy<Value = MsdModel> {
    (1usize..=5).prop_flat_map(|n| {
        (
            proptest::collection::vec(1.0f64..3.3, n),
            proptest::collection::vec(0.0f64..4.0, n - 1),
            proptest::collection::vec(4.0f64..7.0, n - 1),
        )
            .prop_map(|(m, c, k)| {
                let pow = |v: Vec<f64>| v.into_iter().map(|e| 10f64.powf(e)).collect::<Vec<_>>();
                MsdModel::new(pow(m), pow(c), pow(k)).unwrap()
            })
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]
    #[test]
    fn zoh_agrees_with_fine_step_runge_kutta(car in stable_model(), seed in 0u64..1000) {
        let step = 1e-4;
        let fastest = elastic_modes(&car).unwrap().last().map_or(0.0, |m| m.natural_frequency());
        let sub = ((step * fastest / 0.05).ceil() as usize).max(4);
        prop_assume!(sub <= 2000);
        let mut force = rough_force(60 + seed as usize % 40, step).values().to_vec();
        force.rotate_left(seed as usize % 50);
        let force = UniformSeries::new(0.0, step, force).unwrap();
        let r = simulate(&car, &force, Method::Zoh, &InitialState::Rest).unwrap();
        let reference = rk4_reference(&car, &force, sub);
        let n = car.dof();
        for i in 0..n {
            let scale = reference.iter().fold(1e-300_f64, |s, x| s.max(x[i].abs()));
            for (k, x) in reference.iter().enumerate() {
                prop_assert!((r.displacement[i][k] - x[i]).abs() <= 1e-6 * scale,
                    "x{} at sample {k}: zoh {} vs rk4 {}", i + 1, r.displacement[i][k], x[i]);
            }
        }
    }
}

/// Issue 12: exactly one function in the workspace computes the zoh (and foh)
/// Φ/Γ. Any Φ/Γ needs a matrix exponential; this scans every library and
/// binary source that uses nalgebra, and every file of core's modal form
/// (tests excluded), for `.exp()` calls and names the function each is in.
/// Allowed: `exponential::hold_exponential` (Φ, Γ and their sensitivities),
/// `energy::step_integral` (the energy integrals W of one step, which never
/// yield Φ or Γ), the scalar `f64::exp` of the confidence intervals in
/// `stats::intervals` (the body of `stats::uncertainty`), the scalar `f64::exp`
/// of a log-scale parameter (`uncertainty::theta`), and the modal form of the same zoh
/// (`sweep::slot_constants`, `sweep::phi1`: `e^(λT)` and `φ1(λT)` of the
/// eigenvalues, tested equal to `hold_exponential`'s responses in
/// `modal::tests`). A new matrix exponential anywhere fails here.
#[test]
fn exactly_one_function_computes_the_hold_discretisation() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut found = Vec::new();
    let crates = std::fs::read_dir(root.join("crates")).unwrap();
    let mut files = Vec::new();
    for krate in crates {
        collect_rust_files(&krate.unwrap().path().join("src"), &mut files);
    }
    for file in files {
        let text = std::fs::read_to_string(&file).unwrap();
        // a module's tests in their own file (`#[cfg(test)] mod tests;`)
        // are not its code
        if file.file_name().is_some_and(|n| n == "tests.rs") {
            continue;
        }
        let modal = file.components().any(|c| c.as_os_str() == "modal");
        if !(modal || text.contains("nalgebra") || text.contains("DMatrix")) {
            continue;
        }
        let code = text.split("#[cfg(test)]").next().unwrap_or("");
        let mut function = String::from("<top>");
        for line in code.lines() {
            if let Some(rest) = line.trim_start().split("fn ").nth(1)
                && line.contains("fn ")
                && !line.trim_start().starts_with("//")
            {
                function = rest
                    .split(|c: char| !(c.is_alphanumeric() || c == '_'))
                    .next()
                    .unwrap_or("")
                    .to_string();
            }
            if line.contains(".exp()") && !line.trim_start().starts_with("//") {
                let name = file.file_stem().unwrap().to_string_lossy().to_string();
                found.push(format!("{name}::{function}"));
            }
        }
    }
    found.sort();
    found.dedup();
    // besides the hold discretisation: scalar `f64::exp` of log-scale
    // parameters (a band's car `bands::car`, the nonlinear links' one
    // `objective::fill` for both their objectives (the links' Jacobian is
    // exact now, by dual numbers), a prior's
    // estimate `prior::moved`) and the log-sum-exp of a prior on a sum of
    // parameters (`prior::log_sum`), and a prior's interval on the parameter
    // scale (`prior::with_priors`), and the fitted bumper's log-scale
    // factors (`bumper_fit::{fit_bumper, with_law}`)
    let allowed = [
        "bands::car",
        "bumper_fit::fit_bumper",
        "bumper_fit::with_law",
        "energy::step_integral",
        "exponential::hold_exponential",
        "objective::fill",
        "prior::log_sum",
        "prior::moved",
        "prior::with_priors",
        "propagator::phi1",
        "propagator::slot_constants",
        "uncertainty::intervals",
        "uncertainty::theta",
    ];
    assert_eq!(found, allowed, "matrix exponentials found in {found:?}");
}

fn collect_rust_files(dir: &std::path::Path, out: &mut Vec<std::path::PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries {
        let path = entry.unwrap().path();
        if path.is_dir() {
            collect_rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

use bumpsim_peers::python_available;

/// Both evaluations of the zoh-sampled model, the modal form
/// (`ModalForm::simulate`) and the state-space recursion
/// (`DiscreteModel::output`), against the exact zoh response computed in
/// 50-digit arithmetic by mpmath (tests/peers/mpmath_zoh.py: `expm` of the
/// augmented matrix, then the recursion). Models: a moderate car, a far
/// mass behind a 1 N/m link (its output is the small difference of the
/// rigid and elastic parts), two stiff chains (springs up to 6.6e8 N/m on
/// kilogram masses, where the state space loses digits) and a chain 1 %
/// above critical damping (two nearly equal real eigenvalues). Whenever the
/// modal form accepts a model (it estimates its own error, budget
/// `OUTPUT_PRECISION` = 1e-11) its output must agree with the reference to
/// 1e-10 of the peak; the state space to 1e-9. Both errors are printed.
#[test]
fn modal_and_state_space_zoh_match_50_digit_arithmetic() {
    if !python_available("mpmath") {
        return;
    }
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let script = root.join("tests/peers/mpmath_zoh.py");
    let (step, samples) = (2e-4, 300);
    let force: Vec<f64> = (0..samples)
        .map(|k| 4e4 * (0.012 * k as f64).sin().max(0.0))
        .collect();
    // 1 % above critical damping of the relative motion: c = 1.01 · 2 √(k μ)
    let (m1, m2, k): (f64, f64, f64) = (30.0, 1170.0, 1.5e6);
    let critical = 1.01 * 2.0 * (k * m1 * m2 / (m1 + m2)).sqrt();
    // (name, masses, dampers, springs, output mass, initial velocity)
    let cases = [
        (
            "car",
            vec![30.0, 250.0, 1170.0],
            vec![8e3, 2.5e4],
            vec![1.5e6, 6e5],
            0,
            1.3,
        ),
        (
            "weakly linked far mass",
            vec![30.0, 250.0, 1170.0, 80.0],
            vec![8e3, 2.5e4, 0.5],
            vec![1.5e6, 6e5, 1.0],
            3,
            0.0,
        ),
        (
            "stiff light chain",
            vec![1.5, 3.2, 9.0, 5.5],
            vec![20.0, 150.0, 40.0],
            vec![2e8, 4.5e7, 8e6],
            0,
            1.3,
        ),
        (
            "stiff heavy-ended chain",
            vec![1320.88, 1.2427, 2.770, 3302.1],
            vec![1.0, 61501.8, 1.0],
            vec![6.5627e8, 1.0146e6, 3.0265e8],
            0,
            0.0,
        ),
        (
            "1 % above critical damping",
            vec![m1, m2],
            vec![critical],
            vec![k],
            0,
            1.3,
        ),
    ];
    let mut refused = Vec::new();
    for (index, (name, masses, dampers, springs, output, v0)) in cases.into_iter().enumerate() {
        let car = MsdModel::new(masses.clone(), dampers.clone(), springs.clone()).unwrap();
        let n = car.dof();
        let d = DiscreteModel::new(&car, Method::Zoh, step).unwrap();
        let (mut state_space, mut work) = (vec![0.0; samples], vec![0.0; d.work_len()]);
        let initial: Vec<f64> = (0..2 * n).map(|i| if i < n { 0.0 } else { v0 }).collect();
        d.output(&initial, &force, output, &mut state_space, None, &mut work)
            .unwrap();
        let mut modal = vec![0.0; samples];
        let modal = match ModalForm::new(&car, output, false)
            .and_then(|form| form.simulate(step, v0, &force, &mut modal))
        {
            Ok(()) => Ok(modal),
            Err(e) => {
                refused.push(name);
                Err(e.to_string())
            }
        };
        let case = serde_json::json!({
            "name": name,
            "masses": masses,
            "dampers": dampers,
            "springs": springs,
            "step": step,
            "initial_velocity": v0,
            "force": force,
            "output": output,
            "state_space": state_space,
            "modal": modal.as_ref().ok(),
            "modal_refusal": modal.as_ref().err(),
        });
        let file = std::env::temp_dir().join(format!(
            "bumpsim-mpmath-zoh-{}-{index}-{}.json",
            std::process::id(),
            std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .map_or(0, |t| t.as_nanos())
        ));
        std::fs::write(&file, serde_json::to_string(&case).unwrap()).unwrap();
        let out = std::process::Command::new("python3")
            .arg(&script)
            .arg(&file)
            .current_dir(&root)
            .output();
        std::fs::remove_file(&file).unwrap();
        let out = out.unwrap();
        let (stdout, stderr) = (
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr),
        );
        print!("{stdout}");
        assert!(
            out.status.success(),
            "{name}: bumpsim's zoh differs from the 50-digit reference\n{stdout}{stderr}"
        );
    }
    println!("modal form refused: {refused:?}");
}
