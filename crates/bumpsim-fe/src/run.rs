//! Running the coupled deck in CalculiX and reading it back as an impact.
//!
//! Duration and increment: `bumpsim impact` with the mesh's equivalent
//! characteristic estimates the contact end t_c; the FE run lasts 1.3 t_c
//! in 1500 fixed increments unless given.
//!
//! Results, in `bumpsim impact`'s conventions (displacements along the
//! direction of travel; compression ≥ 0):
//! - contact force F = Σ_i k_node · max(0, u_striker − u_beam,i) over the
//!   beam nodes (the contact springs' own law), reported raw and filtered
//!   with SAE J211 CFC 60 (the class of barrier load cells); the peak force
//!   is the filtered one, as a test laboratory would report it;
//! - compression: striker to m1 (barrier: m1's travel; pendulum: pendulum
//!   minus m1); remaining compression: the crush of the bumper (m1's travel
//!   minus the beam's mean travel) at the end;
//! - energy: E(t) = kinetic energy of car and pendulum + car springs + car
//!   dampers' dissipation (trapezoidal rule over the printed velocities) +
//!   internal (elastic and plastic) and kinetic energy of beam and boxes +
//!   the contact springs' energy; the balance error is
//!   |E(end) − E(first print)| / E(first print).

use crate::FeError;
use crate::bumper::BumperMesh;
use crate::deck::{CONTACT_SPAN, Layout, Run, coupled_deck};
use bumpsim_core::model::MsdModel;
use bumpsim_export::dat::{Block, Blocks, history, parse};
use bumpsim_impact::impact::{EnergyBalance, ImpactResult, Options, Scenario, simulate};
use bumpsim_signal::filter::{Cfc, CfcStandard};
use std::path::{Path, PathBuf};

/// Settings of one coupled run.
#[derive(Debug, Clone, PartialEq)]
pub struct FeRun {
    /// The bumper.
    pub mesh: BumperMesh,
    /// The car.
    pub car: MsdModel,
    /// Barrier or pendulum.
    pub scenario: Scenario,
    /// Fixed time increment, s (default: duration / 1500).
    pub increment: Option<f64>,
    /// Simulated time, s (default: 1.3 × the estimated contact end).
    pub duration: Option<f64>,
    /// Folder for the deck and the solver's files (created; kept).
    pub work: PathBuf,
    /// The CalculiX command.
    pub solver: String,
}

impl FeRun {
    /// Settings with the defaults (`ccx` from PATH).
    pub fn new(mesh: BumperMesh, car: MsdModel, scenario: Scenario, work: PathBuf) -> FeRun {
        FeRun {
            mesh,
            car,
            scenario,
            increment: None,
            duration: None,
            work,
            solver: "ccx".into(),
        }
    }
}

/// The result of a coupled run.
#[derive(Debug, Clone, PartialEq)]
pub struct FeResult {
    /// The run as an impact (force CFC 60-filtered).
    pub impact: ImpactResult,
    /// Peak of the unfiltered contact force, N.
    pub raw_peak_force: f64,
    /// Internal energy of beam and crash boxes at the end (plastic work and
    /// what stays elastic), J.
    pub bumper_internal_energy: f64,
    /// `bumpsim impact` with the mesh's equivalent characteristic (none
    /// when it failed and the duration was given).
    pub equivalent: Option<ImpactResult>,
    /// The deck that ran.
    pub deck: PathBuf,
    /// Time increment, s.
    pub increment: f64,
    /// Lateral crash-box positions after snapping to the mesh, m.
    pub crash_box_y: [f64; 2],
}

/// Most increments of one run.
pub const MAX_INCREMENTS: f64 = 1e6;

/// Writes the deck, runs CalculiX and reads the results, in `settings.work`.
pub fn run(settings: &FeRun) -> Result<FeResult, FeError> {
    run_in(settings, &settings.work)
}

/// [`run`] with the deck and CalculiX's files written in `folder`, a
/// staging folder the caller moves to `settings.work` once the whole command
/// has succeeded (so a failed or interrupted run leaves the work folder as
/// it was); the result names the files as they will be in `settings.work`.
pub fn run_in(settings: &FeRun, folder: &Path) -> Result<FeResult, FeError> {
    check_scenario(settings.scenario)?;
    // the estimate may fail (a car too stiff for impact's explicit steps):
    // then the user's --duration runs without it
    let equivalent = equivalent(&settings.mesh, &settings.car, settings.scenario);
    let duration = match (settings.duration, &equivalent) {
        (Some(duration), _) => duration,
        (None, Ok(e)) => 1.3 * e.contact_time,
        (None, Err(e)) => return Err(e.clone()),
    };
    let increment = settings.increment.unwrap_or(duration / 1500.0);
    check_run(duration, increment, "increment")?;
    check_work(&settings.work)?;
    check_work(folder)?;
    let run = Run {
        increment,
        duration,
    };
    let (text, layout) = coupled_deck(&settings.mesh, &settings.car, settings.scenario, &run)?;
    let deck = folder.join("bumper.inp");
    // whole or not at all (temp file + rename), never onto an input
    bumpsim_io::output::write_file(&deck, text.as_bytes()).map_err(|e| FeError::File {
        path: deck.display().to_string(),
        message: format!("cannot write: {e}"),
    })?;
    solve(&settings.solver, folder, folder == settings.work)?;
    // errors name the results as the work folder would hold them
    let dat = settings.work.join("bumper.dat");
    let text =
        bumpsim_core::files::read_text(&folder.join("bumper.dat")).map_err(|e| FeError::File {
            path: dat.display().to_string(),
            message: format!("cannot read: {e}"),
        })?;
    let blocks = parse(&text, &dat)?;
    let read = Reader {
        blocks: &blocks,
        path: &dat,
        layout: &layout,
        settings,
    };
    let (impact, raw_peak_force, bumper_internal_energy) = read.impact(increment)?;
    Ok(FeResult {
        impact,
        raw_peak_force,
        bumper_internal_energy,
        equivalent: equivalent.ok(),
        deck: settings.work.join("bumper.inp"),
        increment,
        crash_box_y: layout.crash_box_y,
    })
}

/// `bumpsim impact` with the mesh's equivalent characteristic: the
/// estimate of the contact end that sizes a run (1.3 × it).
pub fn equivalent(
    mesh: &BumperMesh,
    car: &MsdModel,
    scenario: Scenario,
) -> Result<ImpactResult, FeError> {
    let bumper = mesh.equivalent_bumper()?;
    simulate(car, &bumper, scenario, &Options::default())
        .map_err(|e| FeError::Estimate(e.to_string()))
}

/// A closing speed and a pendulum mass that are positive and finite (also
/// when the estimate, which checks them too, is skipped).
pub(crate) fn check_scenario(scenario: Scenario) -> Result<(), FeError> {
    let (speed, mass) = match scenario {
        Scenario::Barrier { speed } => (speed, 1.0),
        Scenario::Impactor { mass, speed } => (speed, mass),
    };
    for (name, value) in [("speed (m/s)", speed), ("pendulum mass (kg)", mass)] {
        if !(value.is_finite() && value > 0.0) {
            return Err(FeError::Parameter {
                name: name.into(),
                value,
                expected: "positive and finite".into(),
            });
        }
    }
    scenario.check().map_err(FeError::Scenario)
}

/// The longest simulated time of a coupled run or deck, s: a low-speed
/// impact is over within a second (and 1e308 s overflowed the deck's units).
pub const MAX_DURATION: f64 = 100.0;

/// The shortest simulated time of a coupled run or deck, s: a low-speed
/// impact lasts tens of milliseconds, and 1e-308 s gave a deck ending at
/// a subnormal time.
pub const MIN_DURATION: f64 = 1e-6;

/// A duration from [`MIN_DURATION`] to [`MAX_DURATION`], and an `increment` (the run's, or a
/// deck's output interval) of at most the duration and at most
/// [`MAX_INCREMENTS`] of them.
pub(crate) fn check_run(duration: f64, increment: f64, what: &str) -> Result<(), FeError> {
    let bad = |name: &str, value: f64, expected: &str| FeError::Parameter {
        name: name.into(),
        value,
        expected: expected.into(),
    };
    if !(duration.is_finite() && duration > 0.0) {
        return Err(bad("duration (s)", duration, "positive and finite"));
    }
    if !(MIN_DURATION..=MAX_DURATION).contains(&duration) {
        return Err(bad(
            "duration (s)",
            duration,
            "from 1e-6 s (MIN_DURATION) to 100 s (MAX_DURATION)",
        ));
    }
    if !(increment.is_finite() && increment > 0.0) {
        return Err(bad(
            &format!("{what} (s)"),
            increment,
            "positive and finite",
        ));
    }
    if increment > duration {
        return Err(bad(
            &format!("{what} (s)"),
            increment,
            "at most the duration",
        ));
    }
    let count = duration / increment;
    if count > MAX_INCREMENTS {
        return Err(bad(
            &format!("{what}s (duration / {what})"),
            count,
            "at most 1e6",
        ));
    }
    Ok(())
}

/// How many of the solver's last output lines a failure quotes.
const LOG_TAIL: usize = 12;

/// Whether a file is one the run writes into its work folder (the deck,
/// CalculiX's `bumper.*` files, its log and `spooles.out`).
fn ours(name: &str) -> bool {
    name.starts_with("bumper.") || name == "ccx.log" || name == "spooles.out"
}

/// Whether `path` names one of the files a run writes into `work` (an
/// output given there would meet the run's own file only after the run).
///
/// ```
/// use bumpsim_fe::run::in_work;
/// use std::path::Path;
/// assert!(in_work(Path::new("w"), Path::new("w/bumper.dat")));
/// assert!(!in_work(Path::new("w"), Path::new("w/fe.json")));
/// assert!(!in_work(Path::new("w"), Path::new("bumper.dat")));
/// ```
pub fn in_work(work: &Path, path: &Path) -> bool {
    let folder = |p: &Path| match p.as_os_str().is_empty() {
        true => std::path::absolute("."),
        false => std::path::absolute(p),
    };
    let same = match (path.parent().map(folder), folder(work)) {
        (Some(Ok(a)), Ok(b)) => a == b,
        _ => false,
    };
    same && path.file_name().is_some_and(|n| ours(&n.to_string_lossy()))
}

/// Refuses a work folder holding anything but a previous run's files: the
/// run overwrites those, and must never overwrite the user's (an input
/// bumper or car file among them).
fn check_work(work: &Path) -> Result<(), FeError> {
    let entries = match std::fs::read_dir(work) {
        Ok(entries) => entries,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(()),
        Err(e) => {
            return Err(FeError::File {
                path: work.display().to_string(),
                message: format!("cannot use as the work folder: {e}"),
            });
        }
    };
    let foreign = entries
        .filter_map(Result::ok)
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .find(|name| !ours(name) || name.ends_with(".toml"));
    match foreign {
        None => Ok(()),
        Some(name) => Err(FeError::File {
            path: work.display().to_string(),
            message: format!(
                "holds '{name}', which is not a file of a previous run: choose an empty or new --work folder"
            ),
        }),
    }
}

/// Runs `solver -i bumper` in `work` (one thread unless OMP_NUM_THREADS is
/// set), its output in `ccx.log`. A failure quotes the log's last lines,
/// and names the log where it is `kept` (a staging folder is removed).
fn solve(solver: &str, work: &Path, kept: bool) -> Result<(), FeError> {
    let log = work.join("ccx.log");
    let fail = |message: String| FeError::Solver {
        solver: solver.into(),
        message,
    };
    let out = std::fs::File::create(&log)
        .map_err(|e| fail(format!("cannot write {}: {e}", log.display())))?;
    let err = out.try_clone().map_err(|e| fail(e.to_string()))?;
    let mut command = std::process::Command::new(solver);
    // CalculiX's OpenMP threads only spin on a model this small
    if std::env::var_os("OMP_NUM_THREADS").is_none() {
        command.env("OMP_NUM_THREADS", "1");
    }
    let status = command
        .args(["-i", "bumper"])
        .current_dir(work)
        .stdout(out)
        .stderr(err)
        .status()
        .map_err(|e| {
            fail(format!(
                "cannot start ({e}); install CalculiX (Debian: calculix-ccx)"
            ))
        })?;
    let text = std::fs::read_to_string(&log).unwrap_or_default();
    let error = text.lines().find(|l| l.contains("*ERROR")).map(str::trim);
    let lines: Vec<&str> = text.lines().collect();
    let tail = lines[lines.len().saturating_sub(LOG_TAIL)..].join("\n    ");
    let see = match kept {
        true => format!("see {}", log.display()),
        false => "the work folder is left as it was".into(),
    };
    match (status.success(), error) {
        (true, None) => Ok(()),
        (_, e) => Err(fail(format!(
            "the run failed ({}); {see}; the end of its output:\n    {tail}",
            e.unwrap_or("non-zero exit"),
        ))),
    }
}

struct Reader<'a> {
    blocks: &'a Blocks,
    path: &'a Path,
    layout: &'a Layout,
    settings: &'a FeRun,
}

/// The blocks of one (quantity, set), or an error naming what is missing.
fn series<'a>(
    blocks: &'a Blocks,
    quantity: &str,
    set: &str,
    path: &Path,
) -> Result<&'a [Block], FeError> {
    history(blocks, quantity, set).ok_or_else(|| FeError::File {
        path: path.display().to_string(),
        message: format!("no '{quantity}' blocks for set {set} (did the run end early?)"),
    })
}

/// Node values along x: per node (outer) and time (inner).
fn along_x(blocks: &[Block], nodes: &[u64], path: &Path) -> Result<Vec<Vec<f64>>, FeError> {
    nodes
        .iter()
        .map(|&n| {
            blocks
                .iter()
                .map(|b| {
                    b.rows
                        .iter()
                        .find(|r| r.id == Some(n))
                        .and_then(|r| r.values.first().copied())
                        .ok_or_else(|| FeError::File {
                            path: path.display().to_string(),
                            message: format!("node {n} missing at time {} s", b.time),
                        })
                })
                .collect()
        })
        .collect()
}

/// Linear interpolation of (t, y) at `at` (t increasing, clamped at the ends).
fn interpolate(t: &[f64], y: &[f64], at: f64) -> f64 {
    let i = t.partition_point(|&x| x <= at).clamp(1, t.len() - 1);
    let w = ((at - t[i - 1]) / (t[i] - t[i - 1])).clamp(0.0, 1.0);
    y[i - 1] + w * (y[i] - y[i - 1])
}

/// SAE J211 CFC 60 of a signal at the solver's (possibly cut-back) times:
/// resampled to the nominal increment, filtered, and read back at `time`.
fn cfc60(time: &[f64], force: &[f64], increment: f64) -> Result<Vec<f64>, FeError> {
    if time.len() < 2 {
        return Ok(force.to_vec());
    }
    let (t0, t1) = (time[0], time[time.len() - 1]);
    let n = ((t1 - t0) / increment).round() as usize + 1;
    let grid: Vec<f64> = (0..n).map(|k| t0 + k as f64 * increment).collect();
    let uniform: Vec<f64> = grid.iter().map(|&t| interpolate(time, force, t)).collect();
    let filtered = Cfc::new(60.0, CfcStandard::SaeJ211)
        .and_then(|c| c.filter(&uniform, increment))
        .map_err(|e| FeError::Estimate(format!("CFC 60 of the contact force: {e}")))?;
    Ok(time
        .iter()
        .map(|&t| interpolate(&grid, &filtered, t))
        .collect())
}

impl Reader<'_> {
    fn nodes(&self, quantity: &str, set: &str, nodes: &[u64]) -> Result<Vec<Vec<f64>>, FeError> {
        along_x(
            series(self.blocks, quantity, set, self.path)?,
            nodes,
            self.path,
        )
    }

    fn total(&self, quantity: &str, set: &str, len: usize) -> Result<Vec<f64>, FeError> {
        let blocks = series(self.blocks, quantity, set, self.path)?;
        let values: Vec<f64> = blocks
            .iter()
            .filter_map(|b| b.rows.first()?.values.first().copied())
            .collect();
        match values.len() == len {
            true => Ok(values),
            false => Err(FeError::File {
                path: self.path.display().to_string(),
                message: format!(
                    "{quantity} for {set}: {} values for {len} times (truncated?)",
                    values.len()
                ),
            }),
        }
    }

    fn impact(&self, increment: f64) -> Result<(ImpactResult, f64, f64), FeError> {
        let l = self.layout;
        let car_blocks = series(self.blocks, "displacements", "BUMPSIM_NALL", self.path)?;
        let time: Vec<f64> = car_blocks.iter().map(|b| b.time).collect();
        let n = time.len();
        let x = self.nodes("displacements", "BUMPSIM_NALL", &l.car)?;
        let v = self.nodes("velocities", "BUMPSIM_NALL", &l.car)?;
        let beam = self.nodes("displacements", "FE_BEAM", &l.beam)?;
        let (px, pv) = match l.pendulum {
            Some(p) => (
                Some(self.nodes("displacements", "FE_PENDULUM", &[p])?.remove(0)),
                Some(self.nodes("velocities", "FE_PENDULUM", &[p])?.remove(0)),
            ),
            None => (None, None),
        };
        if [&beam[0], px.as_ref().unwrap_or(&beam[0])]
            .iter()
            .any(|h| h.len() != n)
        {
            return Err(FeError::File {
                path: self.path.display().to_string(),
                message: "the beam or pendulum histories do not match the car's times (truncated?)"
                    .into(),
            });
        }
        let striker = |k: usize| px.as_ref().map_or(0.0, |p| p[k]);
        let force: Vec<f64> = (0..n)
            .map(|k| {
                beam.iter()
                    .map(|u| (striker(k) - u[k]).max(0.0))
                    .sum::<f64>()
                    * l.contact_node
            })
            .collect();
        let sign = if px.is_some() { 1.0 } else { -1.0 };
        let travel = |h: &[f64]| h.iter().map(|u| sign * u).collect::<Vec<f64>>();
        let mut bodies = Vec::new();
        let mut displacements = Vec::new();
        let mut velocities = Vec::new();
        if let (Some(p), Some(pv)) = (&px, &pv) {
            bodies.push("impactor".to_string());
            displacements.push(travel(p));
            velocities.push(travel(pv));
        }
        for (i, (xi, vi)) in x.iter().zip(&v).enumerate() {
            bodies.push(format!("m{}", i + 1));
            displacements.push(travel(xi));
            velocities.push(travel(vi));
        }
        // barrier: m1's travel −u_1; pendulum: u_p − u_1
        let compression: Vec<f64> = (0..n).map(|k| striker(k) - x[0][k]).collect();
        let filtered = cfc60(&time, &force, increment)?;
        let (energy, internal) = self.energy(&x, &v, pv.as_deref(), &time)?;
        let crush_end = {
            let last = n - 1;
            let beam_mean = beam.iter().map(|u| u[last]).sum::<f64>() / beam.len() as f64;
            beam_mean - x[0][last]
        };
        let contact: Vec<usize> = (0..n).filter(|&k| force[k] > 0.0).collect();
        let at = |k: Option<&usize>| k.map_or(0.0, |&k| time[k]);
        let result = ImpactResult {
            bodies,
            contact_start: at(contact.first()),
            contact_time: at(contact.last()),
            max_compression: compression.iter().copied().fold(0.0, f64::max),
            remaining_compression: crush_end,
            peak_force: filtered.iter().copied().fold(0.0, f64::max),
            absorbed_energy: internal,
            energy,
            step: increment,
            time,
            force: filtered,
            compression,
            displacements,
            velocities,
        };
        Ok((result, force.iter().copied().fold(0.0, f64::max), internal))
    }

    fn energy(
        &self,
        x: &[Vec<f64>],
        v: &[Vec<f64>],
        pendulum: Option<&[f64]>,
        time: &[f64],
    ) -> Result<(EnergyBalance, f64), FeError> {
        let n = time.len();
        let car = &self.settings.car;
        let masses = car.masses();
        let pendulum_mass = match self.settings.scenario {
            Scenario::Impactor { mass, .. } => mass,
            Scenario::Barrier { .. } => 0.0,
        };
        let kinetic = |k: usize| {
            let car: f64 = masses
                .iter()
                .zip(v)
                .map(|(m, vi)| 0.5 * m * vi[k] * vi[k])
                .sum();
            car + pendulum.map_or(0.0, |p| 0.5 * pendulum_mass * p[k] * p[k])
        };
        let links = |k: usize, f: &dyn Fn(f64, f64, usize) -> f64| -> f64 {
            (0..car.springs().len())
                .map(|j| f(x[j][k] - x[j + 1][k], v[j][k] - v[j + 1][k], j))
                .sum()
        };
        let springs = |k: usize| links(k, &|dx, _, j| 0.5 * car.springs()[j] * dx * dx);
        let power = |k: usize| links(k, &|_, dv, j| car.dampers()[j] * dv * dv);
        let mut dampers = vec![0.0; n];
        for k in 1..n {
            dampers[k] = dampers[k - 1] + 0.5 * (power(k) + power(k - 1)) * (time[k] - time[k - 1]);
        }
        let total = |q: &str, set: &str| self.total(q, set, n);
        let internal: Vec<f64> = total("total internal energy", "FE_EBEAM")?
            .iter()
            .zip(total("total internal energy", "FE_EBOX")?)
            .map(|(a, b)| a + b)
            .collect();
        let offset = 0.5
            * self.layout.contact_node
            * CONTACT_SPAN
            * CONTACT_SPAN
            * self.layout.beam.len() as f64;
        let contact: Vec<f64> = total("total internal energy", "FE_ECONTACT")?
            .iter()
            .map(|e| e - offset)
            .collect();
        let moving: Vec<f64> = total("total kinetic energy", "FE_EBEAM")?
            .iter()
            .zip(total("total kinetic energy", "FE_EBOX")?)
            .map(|(a, b)| a + b)
            .collect();
        let sum =
            |k: usize| kinetic(k) + springs(k) + dampers[k] + internal[k] + contact[k] + moving[k];
        let (first, last) = (sum(0), sum(n - 1));
        let balance = EnergyBalance {
            initial: first,
            kinetic: kinetic(n - 1) + moving[n - 1],
            springs: springs(n - 1),
            dampers: dampers[n - 1],
            bumper: internal[n - 1] + contact[n - 1],
            relative_error: ((last - first) / first).abs(),
        };
        Ok((balance, internal[n - 1]))
    }
}
