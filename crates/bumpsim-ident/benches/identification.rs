//! Criterion benchmarks of identification: one Jacobian evaluation (the
//! state-space recursion, as the statistics take it), the normal equations
//! and the residuals (the modal form, as LM takes them), a single
//! start and the 32-start 3-DOF identification on three 500-sample load
//! cases, and the issue-19 DOF table (1..5 DOF, 32 starts each, continuation
//! from each model to the next) on those cases and on the bundled
//! three-test example. Figures: docs/benchmarks.md.

use bumpsim_core::model::MsdModel;
use bumpsim_estimate::lm::{Damping, LeastSquares};
use bumpsim_ident::case::{LoadCase, Objective};
use bumpsim_ident::estimate::{Settings, identify};
use bumpsim_ident::study::Study;
use criterion::{Criterion, criterion_group, criterion_main};
use nalgebra::DMatrix;
use std::hint::black_box;

const STEP: f64 = 2e-4;

/// Three pendulum-like cases of 500 samples (0.1 s at 5 kHz) made with the
/// exact zoh simulation of a known 3-DOF car, with a little deterministic noise.
fn cases() -> Vec<LoadCase> {
    let truth = MsdModel::new(
        vec![30.0, 250.0, 1170.0],
        vec![8e3, 2.5e4],
        vec![1.5e6, 6e5],
    )
    .unwrap();
    [(4.5e4, 0.06, 1.0), (3.5e4, 0.07, 1.5), (2.5e4, 0.085, 2.0)]
        .iter()
        .enumerate()
        .map(|(l, &(peak, duration, shape))| {
            let force: Vec<f64> = (0..500)
                .map(|k| {
                    let t = k as f64 * STEP;
                    if t < duration {
                        peak * (std::f64::consts::PI * t / duration).sin().powf(shape)
                    } else {
                        0.0
                    }
                })
                .collect();
            let mut c = LoadCase {
                name: format!("case {l}"),
                start: 0.0,
                step: STEP,
                force,
                measured: vec![0.0; 500],
                output_dof: 1,
                initial_velocity: 0.0,
                window: (0, 499),
                compare: Default::default(),
            };
            c.measured = c
                .simulate(&truth)
                .unwrap()
                .iter()
                .enumerate()
                .map(|(k, x)| x + 5e-5 * ((k * 7 + l) as f64).sin())
                .collect();
            c
        })
        .collect()
}

fn benches(c: &mut Criterion) {
    let cases = cases();
    let objective = Objective::new(&cases, 3, &[None; 7]);
    let p: Vec<f64> = [30.0f64, 250.0, 1170.0, 8e3, 2.5e4, 1.5e6, 6e5]
        .iter()
        .map(|v| v.ln())
        .collect();
    let mut r = vec![0.0; objective.residual_count()];
    let mut jac = DMatrix::zeros(objective.residual_count(), 7);
    c.bench_function("jacobian 3-DOF, 3 x 500 samples", |b| {
        b.iter(|| objective.evaluate(black_box(&p), &mut r, Some(&mut jac)))
    });
    // what LM takes per iteration: residuals and JᵀJ, Jᵀr (the modal form);
    // two points in turn, so that each call makes its modal form (the
    // objective keeps the last point's)
    let (mut jtj, mut g) = (DMatrix::zeros(7, 7), nalgebra::DVector::zeros(7));
    let q: Vec<f64> = p.iter().map(|v| v + 1e-3).collect();
    let mut turn = false;
    c.bench_function("normal equations 3-DOF, 3 x 500 samples", |b| {
        b.iter(|| {
            turn = !turn;
            let point = if turn { &p } else { &q };
            objective.normal(black_box(point), &mut r, &mut jtj, &mut g)
        })
    });
    c.bench_function("residuals 3-DOF, 3 x 500 samples", |b| {
        b.iter(|| {
            turn = !turn;
            let point = if turn { &p } else { &q };
            objective.evaluate(black_box(point), &mut r, None)
        })
    });
    let mut group = c.benchmark_group("identify 3-DOF, 3 x 500 samples");
    group.sample_size(10);
    for starts in [1, 32] {
        let settings = Settings::new(3, starts);
        group.bench_function(format!("{starts} starts"), |b| {
            b.iter(|| identify(black_box(&cases), &settings, &|| {}).unwrap())
        });
    }
    group.finish();
    let study = Study::read(std::path::Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/identify/study.toml"
    )))
    .unwrap();
    let bundled = study.load(5).unwrap().cases;
    let mut group = c.benchmark_group("DOF table 1..5, 32 starts each");
    group.sample_size(10);
    group.bench_function("synthetic, 3 x 500 samples", |b| {
        b.iter(|| table(&|_| black_box(&cases).clone()))
    });
    group.bench_function("bundled example, 3 tests", |b| {
        b.iter(|| table(&|dof| study.retarget(black_box(&bundled), dof)))
    });
    // the same table with LM's trust-region damping (not yet the default),
    // for a relative figure on the same load (issue 44 item 6)
    group.bench_function("synthetic, 3 x 500 samples, trust region", |b| {
        b.iter(|| table_with(&|_| black_box(&cases).clone(), Damping::TrustRegion))
    });
    group.finish();
}

/// The DOF table as `bumpsim identify --dof 1..5 --starts 32` runs it: each
/// model continued from the one before.
fn table(cases_for: &dyn Fn(usize) -> Vec<LoadCase>) -> f64 {
    table_with(cases_for, Damping::default())
}

/// [`table`] with LM's `damping`.
fn table_with(cases_for: &dyn Fn(usize) -> Vec<LoadCase>, damping: Damping) -> f64 {
    bumpsim_ident::dofs::table(&[1, 2, 3, 4, 5], &|dof| {
        let mut settings = Settings::new(dof, 32);
        settings.solver.damping = damping;
        (cases_for(dof), settings)
    })
    .iter()
    .map(|r| r.as_ref().unwrap().objective)
    .sum()
}

criterion_group!(identification, benches);
criterion_main!(identification);
