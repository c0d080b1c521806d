//! Issue 44: do the planar identification's 95 % intervals cover an
//! independent generator's truth as often as they say? The series of
//! tests/peers/planar_independent.py (another model family: progressive
//! side-member springs on guides, a rigid beam on foam strips, Magic-Formula
//! tyres with transient slip, RK4; two sill and two side-member
//! accelerometers; trained on a flat pendulum, a centred pole and a 10°
//! wall with four load cells) are written under `--seeds`: each seed a car
//! of its own (body mass ±5 %, yaw inertia ±15 %, grip ±15 %, side members
//! ±15–20 %, log-normal) under noise of its own, so the model family's
//! offset differs between seeds as it does between real cars. Each series
//! is identified as its study says (stated priors, staged search) with
//! [`STARTS`] starts instead of 16, **and the tyres' law estimated** (C_α
//! and σ, `cornering = relaxation = true`) **under a stated prior on σ**
//! ([`relaxation_prior`]): the study's choice for a car whose tyres nobody
//! measured, made explicit here (the default turns them on only with a
//! yaw-rate sensor, docs/planar.md "Defaults chosen by evidence"; these
//! series carry sills and side members); why below.
//!
//! The generator's car is not bumpsim's, so only the parameters with a
//! one-to-one meaning are compared: the total mass (the body and both
//! chains' masses against the body and the side members; its interval from
//! the estimates' covariance, `Var ln M = Σ w_i w_j Cov(ln θ_i, ln θ_j)`,
//! `w_i = θ_i/M`), the yaw inertia (the body's about its CG in both: each
//! model adds its chain or side-member masses at their positions) and the
//! lateral grip as a sliding tyre's friction coefficient. The chains'
//! links are another family's (a linear spring against a progressive one):
//! they have no truth to cover.
//!
//! **The grip's truth is the generator's sliding level**, `μ sin(C π/2)`
//! (0.891 μ at its shape C = 1.3), not its Magic Formula's peak μ.
//! bumpsim's μ_y is the friction coefficient of a sliding tyre: its
//! rolling law `F_y = −μ_y N tanh(C_α α/(μ_y N))` rises to μ_y N and stays
//! there, and its sliding law is Coulomb's `μ_y N`; it has no peak above
//! its sliding level. The generator's `F_y = −μ N sin(C atan(B α'))` peaks
//! at μN and falls to `μ N sin(C π/2)` as the tyre slides sideways
//! (`α' → ∞`). The quantity both models have is the sliding level; the
//! peak is the generator's alone. (The measurement below gives both.)
//!
//! Error model (bumpsim_planar::identify::CORRELATION): each sensor weighed
//! by its pre-trigger noise, σ² τ with τ the residuals' integrated
//! autocorrelation time (the 1-D chain's estimator), the priors at their
//! stated spreads (`bumpsim_estimate::information`).
//!
//! Measured (2026-11-29, release build, seeds 0–49, grip against the
//! peak): 120 of 150 intervals cover the truth (80 %): the total mass 48
//! of 50 (RMS z 0.83), the yaw inertia 32 of 50 (1.91), the grip 40 of 50
//! (1.55). τ 30–127 (the own generator's 72–148).
//!
//! Measured again (2026-11-29, debug build, seeds 0–19, the 20 the loaded
//! machine wrote in time; ~40 s an identification):
//!
//! | | covered | RMS z | median θ̂/θ |
//! |---|---|---|---|
//! | total mass | 20 of 20 | 0.70 | 1.000 |
//! | yaw inertia | 12 of 20 | 1.83 | 0.970 (0.90–1.08) |
//! | grip, against the sliding level | 17 of 20 | 1.21 | 0.912 (0.68–1.26) |
//!
//! 49 of 60 (81.7 %), below 85 %. On seeds 0–6 and 10–16 the grip against
//! its peak covered 11 of 14 (RMS z 1.58, median 0.813), against the
//! sliding level 13 of 14 (1.01). **The yaw inertia's intervals are too
//! narrow**: its estimates scatter by about 4.5 % (ln) around 3 % low with
//! a standard error of 1–2 %, a model-family offset (the generator's tyres
//! relax over 0.55 m with C_α 75 kN/rad; the study keeps bumpsim's default
//! 0.4 m and the start's 60 kN/rad, neither estimated, `cornering = false`)
//! that no error model of the residuals reaches: at the optimum the
//! residuals are orthogonal to the Jacobian, so the part of the misfit that
//! moved the estimate is the part they no longer show.
//!
//! Tried and not adopted: a Huber–White sandwich with each residual
//! series' own Bartlett window (Newey–West; `P Jᵀ Ω̂ J P` with `Ω̂` from each
//! series' residuals and the priors at σ² τ) instead of one pooled σ² τ.
//! On seeds 0–4 and 10–14 it gave the yaw inertia RMS z 1.45 / 2.44
//! (pooled 1.39 / 2.08) and the grip 1.86 / 1.54 (2.02 / 1.43): no wider
//! where it matters (commit "estimate::robust", reverted). What is left: a
//! model-error term for the yaw inertia (e.g. the spread of the estimates
//! over leave-one-case-out refits), or the tyres' relaxation and C_α
//! estimated, which the study's defaults decide. A first look at the
//! latter (`cornering = true`, `relaxation = true`, 4 starts, seeds 0, 1,
//! 7, 9, 12, 13, 14, 16, 19, most of them misses above): the grip covers
//! 9 of 9 (|z| ≤ 1.07), the yaw inertia 7 of 9 (z −2.01 to 1.42), but on
//! seeds 1 and 9 it lands 19–20 % high with z 6.7 and 7.4 (another basin
//! or a bound, not looked into).
//!
//! **Seeds 1 and 9: a bound, not a basin** (debug build, 16 starts,
//! `coverage::measured`, 2026-11-29). With C_α and σ estimated and no
//! prior on σ, σ runs to its 2 m upper bound on both (the search's 0.01–2 m), 16 of
//! 16 starts there (the staged search funnels them), and I_z rises with it
//! along a valley the data hardly see; pinned at its truth (a prior of
//! spread 0.005), the search ends at σ 0.47 m and a *lower* data objective:
//!
//! | seed | free: I_z/truth, σ, F | I_z pinned: σ, F | the yaw prior's centre a b M / truth |
//! |---|---|---|---|
//! | 1 | 1.189, 2.00 m, 9.482e-4 m² | 0.47 m, 9.459e-4 m² | 1.25 (2.2 of its sd) |
//! | 9 | 1.199, 2.00 m, 5.741e-4 m² | 0.47 m, 5.402e-4 m² | 1.43 (3.5 of its sd) |
//!
//! What the search minimises adds the priors, and the yaw inertia's (a b M,
//! spread 0.10) lies far above these two cars' truths, so the valley's far
//! end wins. Not a second optimum of the data and not a missed basin (16
//! starts find the same point): the intervals then hold σ at its bound and
//! leave out the I_z–σ trade (SE 2 % on a 19 % error). A stated prior on σ
//! (bumpsim's 0.4 m, about a passenger tyre's radius; 0.2–0.8 m as ±2 sd,
//! read as the cornering stiffness's range is) keeps σ off the bound and
//! puts the trade into the intervals: seeds 1 and 9 at 1.095 (z 1.83) and
//! 1.132 (z 2.88), σ 0.48 and 0.53 m (truth 0.55), 4 starts.
//!
//! The generator draws I_z with a log-sd of 0.15 around 2050 kg·m²,
//! independent of the mass: dynamic indices of about 0.70–1.30 at ±2 sd,
//! wider than the prior's stated 0.8–1.2 (Milliken). A Bayesian interval
//! covers at its rate over cars drawn from its prior; a car far outside it
//! (seed 9, index ≈ 0.70) is pulled towards a b M, which is the prior
//! saying what it was told. Neither changed here.
//!
//! **Measured with the tyres estimated and the σ prior** (2026-11-29, debug
//! build, 4 starts, ~40-90 s an identification on a machine at load 20;
//! the seeds the generator wrote in time):
//!
//! | | covered | RMS z | median θ̂/θ |
//! |---|---|---|---|
//! | total mass | 18 of 18 | 0.76 | 1.000 (1.00–1.00) |
//! | yaw inertia | 16 of 18 | 1.28 | 0.972 (0.88–1.13) |
//! | grip, against the sliding level | 18 of 18 | 0.92 | 0.931 (0.75–1.26) |
//!
//! Seeds 0–15, 25 and 26: 52 of 54 (96.3 %), inside 85–99 % but on 18
//! cars, not 50 (the generator wrote ~1 series in 4 min under that load;
//! `BUMPSIM_COVERAGE_DIR=<folder> BUMPSIM_COVERAGE_FIRST=k
//! BUMPSIM_COVERAGE_SERIES=n` runs the seeds a folder holds). The misses
//! are the yaw inertia of seed 9 (1.132, z 2.88), the car far below its
//! prior (above), and of seed 14 (0.875, z −1.99). Against the fixed tyres
//! on seeds 0–19 (49 of 60): the yaw inertia's median ratio stays 0.97
//! (0.970 then), its standard errors are 4–6 % instead of 1–2 %, σ and C_α
//! now in its covariance; no model-error term
//! was added (none is needed at this count, and one would push the share
//! above 99 %). On seeds 0–4 and 9 σ ends 0.39–0.53 m (truth 0.55) and C_α
//! 0.43–0.85 of the truth, both flagged "not determined by the data: its
//! interval is mostly its prior's": the data do not pin the tyres, and the
//! yaw inertia's interval now says what that costs it.
//!
//! **All 50 seeds** (2026-11-29, release build, 4 starts, the same study:
//! tyres estimated, the σ prior; 14 s for the 50 identifications, seeds
//! 0–49 of `planar_independent.py --seeds`, run in chunks and then whole,
//! the same figures):
//!
//! | | covered | RMS z | median θ̂/θ (range) |
//! |---|---|---|---|
//! | total mass | 48 of 50 | 0.85 | 1.000 (1.00–1.00) |
//! | yaw inertia | 44 of 50 | 1.28 | 0.981 (0.80–1.18) |
//! | grip, against the sliding level | 49 of 50 | 0.93 | 0.973 (0.71–1.54) |
//!
//! **141 of 150 (94.0 %), inside 85–99 %.** Among the 18 seeds above the
//! release build misses the same two (seeds 9 and 14, same z). The misses
//! (θ̂/θ, z):
//!
//! - total mass: seed 39 (1.001, 1.97), seed 43 (0.998, −2.11), both just
//!   outside, at 0.1–0.2 % of the mass;
//! - yaw inertia: seed 9 (1.132, 2.88), 14 (0.875, −1.99), 22 (1.123,
//!   2.30), 32 (1.164, 2.48), 38 (1.183, 3.19), 41 (0.803, −3.03);
//! - grip: seed 41 (1.539, 2.73).
//!
//! The yaw inertia's misses are the cars outside its prior: the
//! generator's dynamic index `I_z/(a b M)` is 0.70, 1.21, 0.75, 0.75,
//! 0.71 and 1.42 on those six seeds (seed 14's at the edge). Of the 43
//! cars with an index inside the prior's stated 0.8–1.2, none misses (RMS
//! z 0.89, |z| ≤ 1.90); of the 7 outside it, 6 do (seed 2, at 0.79, has
//! z 1.73). Over all 50, the yaw inertia's z correlates with ln index at
//! −0.98: the estimate is pulled towards `a b M` (see above). Seed
//! 41 (index 1.42, peak μ 0.68, the third lowest of 50) misses the grip
//! as well, 1.539 beside a yaw inertia of 0.803 (not looked into). Runs:
//! `.runs/seeds-*.txt` and `.runs/all-0-49.txt` in worktree h6 (not
//! committed).

use bumpsim_planar::identify::{PlanarIdentification, identify};
use bumpsim_planar::study::PlanarStudy;
use std::path::{Path, PathBuf};

/// Seeds of the full count.
const SERIES: usize = 50;

/// Starts per identification (the study's 16 reduced).
const STARTS: usize = 4;

/// The series of seeds `first .. first + count` (None without numpy).
fn series(first: usize, count: usize) -> Option<PathBuf> {
    if !bumpsim_peers::python_available("numpy") {
        return None;
    }
    // a folder per seed range: two ranges in one folder would flip its
    // stamp and rewrite it under the other test's reads
    let out =
        Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("planar-coverage-{first}-{count}"));
    let script =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/peers/planar_independent.py");
    let seeds = format!("{first}:{count}");
    let marker = format!("seeds-{first}-{count}.txt");
    bumpsim_peers::generated(&script, &out, &["--seeds", &seeds], &marker);
    Some(out)
}

/// One compared quantity of one series: the estimate, its 95 % interval
/// and the truth.
#[derive(Debug, Clone, Copy)]
struct Covered {
    value: f64,
    interval: Option<[f64; 2]>,
    truth: f64,
}

impl Covered {
    fn covers(&self) -> bool {
        self.interval
            .is_some_and(|[a, b]| a <= self.truth && self.truth <= b)
    }

    /// `ln(θ̂/θ)` over the interval's half width in standard errors.
    fn z(&self) -> Option<f64> {
        let [a, b] = self.interval?;
        let se = (b / a).ln() / (2.0 * 1.96);
        Some((self.value / self.truth).ln() / se)
    }
}

/// The total mass's estimate and 95 % interval (see the module).
fn total_mass(r: &PlanarIdentification) -> (f64, Option<[f64; 2]>) {
    let masses: Vec<usize> = (0..r.parameters.len())
        .filter(|&i| r.parameters[i].unit == "kg")
        .collect();
    let total: f64 = masses.iter().map(|&i| r.parameters[i].value).sum();
    let mut variance = 0.0;
    for &i in &masses {
        for &j in &masses {
            let (ei, ej) = (&r.parameters[i], &r.parameters[j]);
            let (Some(si), Some(sj)) = (ei.standard_error, ej.standard_error) else {
                return (total, None);
            };
            let Some(rho) = r.uncertainty.correlation[i][j] else {
                return (total, None);
            };
            // SE(θ) = θ SE(ln θ): w_i SE(ln θ_i) = SE(θ_i)/M
            variance += rho * si * sj / (total * total);
        }
    }
    let half = 1.96 * variance.sqrt();
    (total, Some([total * (-half).exp(), total * half.exp()]))
}

/// A stated prior on the tyres' relaxation length σ: bumpsim's default
/// 0.4 m (about a passenger tyre's radius), 0.2–0.8 m as ±2 standard
/// deviations of ln σ (the cornering stiffness's range is read the same
/// way). See the module: without it σ runs to its 2 m bound on some seeds.
fn relaxation_prior() -> bumpsim_estimate::stated::PriorSetting {
    bumpsim_estimate::stated::PriorSetting {
        name: "tyres.relaxation_length".into(),
        removed: false,
        value: Some(bumpsim_planar::car::RELAXATION_LENGTH),
        spread: Some(4f64.ln() / 4.0),
    }
}

/// The compared quantities of the series in `dir` (total mass, yaw
/// inertia, grip), identified as its study says with [`STARTS`] starts.
fn compared(dir: &Path) -> [Covered; 3] {
    let sheet: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("series.json")).unwrap()).unwrap();
    let mut study = PlanarStudy::read(&dir.join("study.toml")).unwrap();
    study.setup.starts = STARTS;
    study.setup.cornering = true;
    study.setup.relaxation = true;
    study.setup.priors.push(relaxation_prior());
    let r = identify(&study.cases, &study.setup, &|| {}).unwrap();
    let named = |name: &str, truth: f64| {
        let p = r.parameters.iter().find(|p| p.name == name).unwrap();
        Covered {
            value: p.value,
            interval: p.ci95,
            truth,
        }
    };
    let truth = |key: &str| sheet[key].as_f64().unwrap();
    // the sliding level of the Magic Formula (see the module)
    let shape = sheet["car"]["tyres"]["shape"].as_f64().unwrap();
    let sliding = truth("mu") * (shape * std::f64::consts::FRAC_PI_2).sin();
    let (value, interval) = total_mass(&r);
    eprintln!(
        "  objective {:.4e} m², variance inflation {:.1}, prior noise {:.3e} m",
        r.objective, r.inflation, r.prior_noise
    );
    [
        Covered {
            value,
            interval,
            truth: truth("total_mass"),
        },
        named("body.yaw_inertia", truth("yaw_inertia")),
        named("tyres.mu_lateral", sliding),
    ]
}

/// The coverage of seeds `first .. first + count`, printed per quantity
/// with its RMS z: (covered, compared).
fn coverage(first: usize, count: usize) -> Option<(usize, usize)> {
    let dir = match std::env::var("BUMPSIM_COVERAGE_DIR") {
        Ok(d) => PathBuf::from(d),
        Err(_) => series(first, count)?,
    };
    let names = ["total mass", "yaw inertia", "lateral grip"];
    let clock = std::time::Instant::now();
    let mut all: Vec<[Covered; 3]> = Vec::new();
    for k in first..first + count {
        let one = compared(&dir.join(format!("seed-{k}")));
        let ratio = one.map(|c| c.value / c.truth);
        let z = one.map(|c| c.z());
        eprintln!("seed {k}: estimate/truth {ratio:.3?}, z {z:.2?}");
        all.push(one);
    }
    for (q, name) in names.iter().enumerate() {
        let covered = all.iter().filter(|c| c[q].covers()).count();
        let z: Vec<f64> = all.iter().filter_map(|c| c[q].z()).collect();
        let rms = (z.iter().map(|z| z * z).sum::<f64>() / z.len().max(1) as f64).sqrt();
        eprintln!(
            "{name}: {covered} of {count} intervals cover the truth; RMS z {rms:.2} (1 for honest intervals)"
        );
    }
    let covered = all.iter().flatten().filter(|c| c.covers()).count();
    eprintln!(
        "{covered} of {} intervals cover the truth in {:.0} s",
        3 * count,
        clock.elapsed().as_secs_f64()
    );
    Some((covered, 3 * count))
}

/// The full count: 50 series (`BUMPSIM_COVERAGE_SERIES` fewer, from seed
/// `BUMPSIM_COVERAGE_FIRST`); 85–99 % of the intervals cover the truth.
#[test]
#[ignore = "issue 44: with the tyres estimated under a σ prior, 141 of 150 on seeds 0-49 (94.0 %, release, 14 s; mass 48/50, RMS z 0.85; yaw inertia 44/50, 1.28; grip 49/50, 0.93); the fixed tyres gave 49 of 60 on seeds 0-19: see the module; writing 50 series takes 20-60 min of Python"]
fn the_intervals_cover_an_independent_generators_truth() {
    let var = |name: &str, default: usize| {
        std::env::var(name)
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(default)
    };
    let (first, count) = (
        var("BUMPSIM_COVERAGE_FIRST", 0),
        var("BUMPSIM_COVERAGE_SERIES", SERIES),
    );
    let Some((covered, total)) = coverage(first, count) else {
        return;
    };
    let share = covered as f64 / total as f64;
    assert!((0.85..=0.99).contains(&share), "{covered} of {total}");
}

/// The measurement behind the module's tyre question (ignored; release):
/// each seed of `BUMPSIM_COVERAGE_SEEDS` (comma-separated, default
/// `1,9,0,7`) of the series in `BUMPSIM_COVERAGE_DIR` (default: written
/// under the target's tmp folder) identified with `BUMPSIM_COVERAGE_STARTS`
/// starts (default [`STARTS`]), the tyres' C_α and σ estimated unless
/// `BUMPSIM_COVERAGE_TYRES=0`, and with `BUMPSIM_COVERAGE_PIN=1` the yaw
/// inertia pinned at its truth by a prior of spread 0.005: printed, each
/// estimate against the truth, the data objective, the priored total
/// `F + s² Σ z²` (the search's objective) and the starts at the best.
#[test]
#[ignore = "a measurement: minutes per seed"]
fn measured() {
    let var = |name: &str| std::env::var(name).ok();
    let seeds: Vec<usize> = var("BUMPSIM_COVERAGE_SEEDS")
        .unwrap_or("1,9,0,7".into())
        .split(',')
        .filter_map(|s| s.trim().parse().ok())
        .collect();
    let starts = var("BUMPSIM_COVERAGE_STARTS").and_then(|s| s.parse().ok());
    let tyres = var("BUMPSIM_COVERAGE_TYRES").is_none_or(|v| v != "0");
    let pin = var("BUMPSIM_COVERAGE_PIN").is_some_and(|v| v == "1");
    let sigma = var("BUMPSIM_COVERAGE_SIGMA").is_some_and(|v| v == "1");
    let dir = match var("BUMPSIM_COVERAGE_DIR") {
        Some(d) => PathBuf::from(d),
        None => {
            let last = seeds.iter().max().copied().unwrap_or(0);
            let Some(d) = series(0, last + 1) else {
                return;
            };
            d
        }
    };
    for k in seeds {
        let here = dir.join(format!("seed-{k}"));
        let sheet: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(here.join("series.json")).unwrap())
                .unwrap();
        let mut study = PlanarStudy::read(&here.join("study.toml")).unwrap();
        study.setup.starts = starts.unwrap_or(STARTS);
        study.setup.cornering = tyres;
        study.setup.relaxation = tyres;
        let truth_iz = sheet["yaw_inertia"].as_f64().unwrap();
        if sigma {
            study.setup.priors.push(relaxation_prior());
        }
        if pin {
            study
                .setup
                .priors
                .push(bumpsim_estimate::stated::PriorSetting {
                    name: "body.yaw_inertia".into(),
                    removed: false,
                    value: Some(truth_iz),
                    spread: Some(0.005),
                });
        }
        let clock = std::time::Instant::now();
        let r = identify(&study.cases, &study.setup, &|| {}).unwrap();
        let shape = sheet["car"]["tyres"]["shape"].as_f64().unwrap();
        let mu = sheet["mu"].as_f64().unwrap() * (shape * std::f64::consts::FRAC_PI_2).sin();
        let tyre = &sheet["car"]["tyres"];
        let truths = [
            ("body.yaw_inertia", truth_iz),
            ("tyres.mu_lateral", mu),
            (
                "tyres.cornering_stiffness",
                tyre["cornering_stiffness"].as_f64().unwrap(),
            ),
            (
                "tyres.relaxation_length",
                tyre["relaxation_length"].as_f64().unwrap(),
            ),
        ];
        let priored: f64 = r.objective
            + r.prior_noise * r.prior_noise * r.priors.iter().map(|m| m.z * m.z).sum::<f64>();
        eprintln!(
            "seed {k} ({} starts, tyres {tyres}, σ prior {sigma}, pin {pin}, {:.0} s): F {:.5e} m², priored {:.5e} m², s {:.3e} m, τ {:.1}, best {}/{} ({} alone)",
            study.setup.starts,
            clock.elapsed().as_secs_f64(),
            r.objective,
            priored,
            r.prior_noise,
            r.inflation,
            r.starts.reached_best,
            r.starts.total,
            r.starts.reached_best_alone
        );
        for (name, truth) in truths {
            if let Some(p) = r.parameters.iter().find(|p| p.name == name) {
                let z = Covered {
                    value: p.value,
                    interval: p.ci95,
                    truth,
                }
                .z();
                eprintln!(
                    "  {name}: {:.4e} (truth {truth:.4e}, ratio {:.3}, 95 % {:?}, z {z:.2?})",
                    p.value,
                    p.value / truth,
                    p.ci95
                );
            }
        }
        for m in &r.priors {
            eprintln!("  prior {}: z {:.2}", m.name, m.z);
        }
        for w in &r.warnings {
            eprintln!("  warning: {w}");
        }
    }
}
