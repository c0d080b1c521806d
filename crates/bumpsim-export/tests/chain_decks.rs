//! The chain with nonlinear links exported (issue 46): the CalculiX deck
//! run in `ccx` against `Chain::run` into a barrier (peak link force and
//! residual crush within 2 %), an elastic-perfectly-plastic closed form,
//! and the LS-DYNA include parsed by ansys-dyna-core with every id defined.

use approx::assert_relative_eq;
use bumpsim_core::chain::{Chain, Drive};
use bumpsim_core::link::{Curve, Link, Unloading};
use bumpsim_core::series::UniformSeries;
use bumpsim_export::calculix::{CalculixOptions, read_results};
use bumpsim_export::chain::{lsdyna_chain_include, mapping};
use bumpsim_export::chain_calculix::{Barrier, calculix_chain_deck, read_link_forces};
use bumpsim_export::layout::{Axis, Layout, UnitSystem};
use bumpsim_export::lsdyna::LsDynaOptions;
use bumpsim_peers::peer_available;
use std::path::PathBuf;
use std::process::Command;

fn ccx_available() -> bool {
    peer_available("ccx (calculix-ccx)", "sh", &["-c", "command -v ccx"])
}

/// What the ccx run of a barrier deck shows of link 1.
struct Fe {
    peak_force: f64,
    max_crush: f64,
    residual: f64,
}

/// Writes the barrier deck of `chain` (units and axis given), runs ccx and
/// reads link 1's peak force, largest crush and plastic set (crush −
/// F / k_E on the unloading, which the elastic-plastic brick keeps
/// constant until it is pulled).
fn ccx_barrier(chain: &Chain, speed: f64, duration: f64, name: &str, layout: Layout) -> Fe {
    ccx_link(chain, speed, duration, name, layout, "link_1")
}

/// [`ccx_barrier`] for the link `which` (`link_1` or `front_link`).
fn ccx_link(
    chain: &Chain,
    speed: f64,
    duration: f64,
    name: &str,
    layout: Layout,
    which: &str,
) -> Fe {
    let options = CalculixOptions {
        layout,
        title: name.into(),
        id_offset: 100,
        ..Default::default()
    };
    let barrier = Barrier {
        speed,
        duration,
        increment: 1e-4,
        output_every: 1,
    };
    let deck = calculix_chain_deck(chain, &options, Some(&barrier)).unwrap();
    let path = run_ccx(name, &deck);
    let u = read_results(&path).unwrap();
    let f = read_link_forces(&path).unwrap();
    let force = &f.links.iter().find(|l| l.0 == which).expect(which).1;
    assert_eq!(force.len(), u.time.len());
    let crush: Vec<f64> = (0..u.time.len())
        .map(|k| match which {
            "front_link" => -u.displacement[0][k],
            _ => u.displacement[0][k] - u.displacement[1][k],
        })
        .collect();
    let top = (0..crush.len())
        .max_by(|a, b| crush[*a].total_cmp(&crush[*b]))
        .unwrap();
    let peak_force = force.iter().fold(0.0_f64, |m, v| m.max(*v));
    let link = match which {
        "front_link" => chain.front().unwrap(),
        _ => &chain.links()[0],
    };
    let k = bumpsim_export::chain::solver_unloading(link);
    // on the unloading, once the force is down to half its peak
    let after = (top..crush.len())
        .find(|&i| force[i] < 0.5 * peak_force)
        .expect("the link unloads within the run");
    Fe {
        peak_force,
        max_crush: crush[top],
        residual: crush[after] - force[after] / k,
    }
}

fn barrier_run(chain: &Chain, speed: f64, duration: f64) -> bumpsim_core::chain::ChainResponse {
    let samples = (duration / 1e-4).round() as usize + 1;
    chain
        .run(&Drive::Barrier {
            speed,
            step: 1e-4,
            samples,
        })
        .unwrap()
}

fn mm_layout() -> Layout {
    Layout {
        units: UnitSystem::MmSTonne,
        axis: Axis {
            component: 1,
            sign: -1.0,
        },
        origin: [1.0, 0.5, 0.0],
        spacing: 0.2,
    }
}

/// Writes `deck` as `chain.inp` in a fresh folder `name` of the target's
/// scratch space and runs it in ccx (one thread); fails unless it ends
/// cleanly; returns the deck's path.
fn run_ccx(name: &str, deck: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("chain-decks")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("chain.inp");
    std::fs::write(&path, deck).unwrap();
    let run = Command::new("ccx")
        .args(["-i", "chain"])
        .env("OMP_NUM_THREADS", "1")
        .current_dir(&dir)
        .output()
        .unwrap();
    let log = String::from_utf8_lossy(&run.stdout);
    assert!(run.status.success() && !log.contains("*ERROR"), "{log}");
    path
}

/// A mass M at V into the wall through an elastic-perfectly-plastic link:
/// crush `M V²/(2 F_y) + F_y/(2k)`, set `crush − F_y/k`, peak force F_y.
#[test]
fn an_elastic_perfectly_plastic_link_in_ccx_matches_the_closed_form_and_the_chain() {
    if !ccx_available() {
        return;
    }
    let (m, v, k, fy) = (1000.0, 10.0, 1e7, 1e5);
    let link = Link::new(Curve::bilinear(k, fy, 0.0).unwrap(), Unloading::Slope(k)).unwrap();
    assert!(mapping(&link).exact);
    let chain = Chain::new(vec![0.05, m], vec![0.0], vec![link]).unwrap();
    let fe = ccx_barrier(&chain, v, 0.16, "epp", Layout::default());
    let crush = m * v * v / (2.0 * fy) + fy / (2.0 * k);
    let set = crush - fy / k;
    eprintln!(
        "epp: ccx peak {} N, crush {} m, set {} m; closed form {fy} N, {crush} m, {set} m",
        fe.peak_force, fe.max_crush, fe.residual
    );
    assert_relative_eq!(fe.peak_force, fy, max_relative = 1e-3);
    assert_relative_eq!(fe.max_crush, crush, max_relative = 2e-3);
    assert_relative_eq!(fe.residual, set, max_relative = 2e-3);
    let r = barrier_run(&chain, v, 0.16);
    let bumpsim_peak = r.link_force[0].iter().fold(0.0_f64, |a, b| a.max(*b));
    assert_relative_eq!(bumpsim_peak, fe.peak_force, max_relative = 0.02);
    assert_relative_eq!(r.plastic_set[0], fe.residual, max_relative = 0.02);
}

/// Two masses with a hardening link into the wall behind a light m1, in
/// mm-s-t units along −y: ccx and `Chain::run` agree on the peak link force
/// and the residual crush within 2 %; and three masses with a tabulated
/// yielding link and a progressive elastic one behind it.
#[test]
fn a_yielding_chain_in_ccx_reproduces_the_impact_within_two_percent() {
    if !ccx_available() {
        return;
    }
    let link = Link::new(
        Curve::bilinear(2e6, 6e4, 0.1).unwrap(),
        Unloading::Slope(4e6),
    )
    .unwrap();
    let chain = Chain::new(vec![0.5, 1200.0], vec![0.0], vec![link]).unwrap();
    let (v, duration) = (8.0, 0.3);
    let fe = ccx_barrier(&chain, v, duration, "hardening", mm_layout());
    let r = barrier_run(&chain, v, duration);
    let peak = r.link_force[0].iter().fold(0.0_f64, |a, b| a.max(*b));
    eprintln!(
        "hardening: ccx peak {} N, crush {} m, set {} m; bumpsim {peak} N, {} m, {} m",
        fe.peak_force, fe.max_crush, fe.residual, r.reached[0], r.plastic_set[0]
    );
    assert_relative_eq!(fe.peak_force, peak, max_relative = 0.02);
    assert_relative_eq!(fe.max_crush, r.reached[0], max_relative = 0.02);
    assert_relative_eq!(fe.residual, r.plastic_set[0], max_relative = 0.02);

    let links = vec![
        Link::new(
            Curve::table(vec![[0.02, 4e4], [0.1, 6e4], [0.4, 1e5]]).unwrap(),
            Unloading::Slope(2e6),
        )
        .unwrap(),
        Link::new(
            Curve::progressive(5e5, 2e8, 0.3).unwrap(),
            Unloading::Elastic,
        )
        .unwrap(),
    ];
    let chain = Chain::new(vec![0.5, 60.0, 1100.0], vec![0.0, 2e3], links).unwrap();
    let (v, duration) = (9.0, 0.3);
    let fe = ccx_barrier(&chain, v, duration, "three", Layout::default());
    let r = barrier_run(&chain, v, duration);
    let peak = r.link_force[0].iter().fold(0.0_f64, |a, b| a.max(*b));
    eprintln!(
        "three masses: ccx peak {} N, crush {} m, set {} m; bumpsim {peak} N, {} m, {} m",
        fe.peak_force, fe.max_crush, fe.residual, r.reached[0], r.plastic_set[0]
    );
    assert_relative_eq!(fe.peak_force, peak, max_relative = 0.02);
    assert_relative_eq!(fe.residual, r.plastic_set[0], max_relative = 0.02);
}

/// A front link (the crush zone between the barrier and m1) ahead of a
/// yielding link: ccx and `Chain::run` agree on the front link's peak
/// force, largest crush and residual crush within 2 %.
#[test]
fn a_front_link_in_ccx_reproduces_the_impact_within_two_percent() {
    if !ccx_available() {
        return;
    }
    let yielding = |k: f64, fy: f64, r: f64| {
        Link::new(Curve::bilinear(k, fy, r).unwrap(), Unloading::Slope(k)).unwrap()
    };
    let front = yielding(3e6, 8e4, 0.05);
    let chain = Chain::new(
        vec![300.0, 1000.0],
        vec![0.0],
        vec![yielding(5e6, 1.2e5, 0.0)],
    )
    .unwrap()
    .with_front(front.clone());
    let (v, duration) = (10.0, 0.25);
    let fe = ccx_link(
        &chain,
        v,
        duration,
        "front",
        Layout::default(),
        "front_link",
    );
    let r = barrier_run(&chain, v, duration);
    let peak = r.force.iter().fold(0.0_f64, |a, b| a.max(-b));
    let mut state = bumpsim_core::link::LinkState::default();
    for x in &r.displacement[0] {
        front.force(*x, &mut state);
    }
    let (crush, set) = (state.reached, state.plastic_set(&front));
    eprintln!(
        "front: ccx peak {} N, crush {} m, set {} m; bumpsim {peak} N, {crush} m, {set} m",
        fe.peak_force, fe.max_crush, fe.residual
    );
    assert_relative_eq!(fe.peak_force, peak, max_relative = 0.02);
    assert_relative_eq!(fe.max_crush, crush, max_relative = 0.02);
    assert_relative_eq!(fe.residual, set, max_relative = 0.02);
    let dyna = lsdyna_chain_include(&chain, &LsDynaOptions::default()).unwrap();
    assert!(
        dyna.contains("$ front link: the barrier's fixed node 8"),
        "{dyna}"
    );
}

/// A softening table (the force falls after a fold buckles) maps to a
/// softening `*PLASTIC` table: ccx follows `Chain::run` within 2 %.
#[test]
fn a_softening_link_in_ccx_reproduces_the_impact_within_two_percent() {
    if !ccx_available() {
        return;
    }
    let table = Curve::table(vec![[0.02, 8e4], [0.08, 5e4], [0.3, 6e4]]).unwrap();
    let link = Link::new(table, Unloading::Slope(4e6)).unwrap();
    assert!(mapping(&link).exact);
    let chain = Chain::new(vec![0.5, 900.0], vec![0.0], vec![link]).unwrap();
    let (v, duration) = (7.0, 0.25);
    let fe = ccx_barrier(&chain, v, duration, "softening", Layout::default());
    let r = barrier_run(&chain, v, duration);
    let peak = r.link_force[0].iter().fold(0.0_f64, |a, b| a.max(*b));
    eprintln!(
        "softening: ccx peak {} N, crush {} m, set {} m; bumpsim {peak} N, {} m, {} m",
        fe.peak_force, fe.max_crush, fe.residual, r.reached[0], r.plastic_set[0]
    );
    assert_relative_eq!(fe.peak_force, peak, max_relative = 0.02);
    assert_relative_eq!(fe.max_crush, r.reached[0], max_relative = 0.02);
    assert_relative_eq!(fe.residual, r.plastic_set[0], max_relative = 0.02);
}

fn every_kind() -> Chain {
    let links = vec![
        Link::new(
            Curve::bilinear(2e6, 6e4, 0.1).unwrap(),
            Unloading::Slope(4e6),
        )
        .unwrap(),
        Link::new(
            Curve::progressive(5e5, 2e8, 0.3).unwrap(),
            Unloading::Elastic,
        )
        .unwrap(),
        Link::new(
            Curve::table(vec![[0.02, 4e4], [0.1, 6e4]]).unwrap(),
            Unloading::Slope(1e6),
        )
        .unwrap(),
        Link::linear(9e5).unwrap(),
    ];
    Chain::new(
        vec![2.0, 40.0, 300.0, 800.0, 500.0],
        vec![1e4, 0.0, 3e3, 2e3],
        links,
    )
    .unwrap()
}

#[test]
fn the_header_says_which_links_map_exactly() {
    let chain = every_kind();
    let deck = lsdyna_chain_include(&chain, &LsDynaOptions::default()).unwrap();
    let notes: Vec<&str> = deck.lines().filter(|l| l.starts_with("$ link ")).collect();
    assert_eq!(notes.len(), 4, "{notes:?}");
    assert!(notes[0].contains("exact in compression"), "{}", notes[0]);
    // the table's first slope 2e6 N/m is steeper than its unloading 1e6
    assert!(notes[2].contains("APPROXIMATE"), "{}", notes[2]);
    assert!(notes[3].contains("linear: exact"), "{}", notes[3]);
    let ccx = calculix_chain_deck(&chain, &CalculixOptions::default(), None).unwrap();
    assert_eq!(ccx.matches("*PLASTIC").count(), 2);
    assert_eq!(ccx.matches("TYPE=C3D8").count(), 2);
    assert_eq!(ccx.matches("NONLINEAR").count(), 1);
    let bad = Barrier {
        speed: -1.0,
        duration: 0.1,
        increment: 1e-4,
        output_every: 1,
    };
    assert!(calculix_chain_deck(&chain, &CalculixOptions::default(), Some(&bad)).is_err());
}

#[test]
fn the_lsdyna_include_parses_in_ansys_dyna_core_with_every_id_defined() {
    if !peer_available(
        "ansys-dyna-core",
        "python3",
        &["-c", "import ansys.dyna.core"],
    ) {
        return;
    }
    let force = UniformSeries::new(0.0, 1e-3, vec![0.0, -2e4, -5e4, -1e4, 0.0]).unwrap();
    let options = LsDynaOptions {
        layout: mm_layout(),
        id_offset: 7000,
        attach: vec![11, 12],
        initial_velocity: Some(-4.0),
        title: "nonlinear chain".into(),
        force: Some(force),
        output_interval: Some(1e-3),
        standalone: true,
    };
    let deck = lsdyna_chain_include(&every_kind(), &options).unwrap();
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("chain-decks");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("chain.k");
    std::fs::write(&path, &deck).unwrap();
    let script = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../tests/peers/dyna_deck.py");
    let args = [path.as_os_str(), "11".as_ref(), "12".as_ref()];
    let verdict: serde_json::Value =
        serde_json::from_slice(&bumpsim_peers::python(&script, &args)).unwrap();
    for empty in ["unprocessed", "errors", "undefined"] {
        assert_eq!(verdict[empty], serde_json::json!([]), "{empty}: {verdict}");
    }
    assert_eq!(verdict["strings"], 0, "raw keywords: {verdict}");
    let keywords = verdict["keywords"].to_string();
    for kind in [
        "MatSpringInelastic",
        "MatSpringNonlinearElastic",
        "MatSpringElastic",
        "MatDamperViscous",
        // the links act along the axis, not the nodes' line (a crush beyond
        // the spacing would turn them over): every element names it
        "DefineSdOrientation",
    ] {
        assert!(keywords.contains(kind), "{kind} missing: {keywords}");
    }
    // one, shared by the links (a front link brings its own); "undefined"
    // above is empty, so every element names a defined one
    assert_eq!(verdict["ids"]["orientation"].as_array().unwrap().len(), 1);
    // link 1's loading curve (id 7000 + 5 + 1): first quadrant, in mm and N
    let curve = verdict["curves"]["7006"].as_array().unwrap();
    let point = |i: usize| curve[i].as_array().unwrap().clone();
    assert_eq!(point(0), [serde_json::json!(0.0), serde_json::json!(0.0)]);
    assert_relative_eq!(point(1)[0].as_f64().unwrap(), 30.0, max_relative = 1e-6);
    assert_relative_eq!(point(1)[1].as_f64().unwrap(), 6e4, max_relative = 1e-6);
    let last = point(curve.len() - 1);
    assert_relative_eq!(last[0].as_f64().unwrap(), 1e4, max_relative = 1e-6);
    let f = 6e4 + 0.1 * 2e6 * (10.0 - 0.03);
    assert_relative_eq!(last[1].as_f64().unwrap(), f, max_relative = 1e-3);
}

/// Under a force history on m1 (the deck's `*CLOAD` path, mm-ms-kg units)
/// the CalculiX deck of a chain with a yielding, a progressive elastic and
/// a linear link follows `Chain::run` in the pendulum's frame: every
/// mass's displacement within 1 % of its peak.
#[test]
fn a_forced_chain_in_ccx_follows_chain_run() {
    if !ccx_available() {
        return;
    }
    let links = vec![
        Link::new(
            Curve::bilinear(4e6, 3e4, 0.05).unwrap(),
            Unloading::Slope(4e6),
        )
        .unwrap(),
        Link::new(
            Curve::progressive(1e6, 1e9, 0.2).unwrap(),
            Unloading::Elastic,
        )
        .unwrap(),
    ];
    let chain = Chain::new(vec![20.0, 150.0, 900.0], vec![500.0, 0.0], links).unwrap();
    let step = 2e-4;
    let force: Vec<f64> = (0..=500)
        .map(|k| {
            let t = k as f64 * step;
            if t < 0.04 {
                6e4 * (std::f64::consts::PI * t / 0.04).sin()
            } else {
                0.0
            }
        })
        .collect();
    let r = chain
        .run(&Drive::Force {
            force: &force,
            step,
            initial_velocity: 0.0,
            frame: bumpsim_core::chain::Frame::Rearward,
        })
        .unwrap();
    assert!(
        r.plastic_set[0] > 1e-3,
        "the link yields: {:?}",
        r.plastic_set
    );
    let options = CalculixOptions {
        layout: Layout {
            units: UnitSystem::MmMsKg,
            ..Default::default()
        },
        analysis: Some(bumpsim_export::calculix::Analysis {
            force: UniformSeries::new(0.0, step, force).unwrap(),
            increment: None,
            output_every: 1,
        }),
        ..Default::default()
    };
    let deck = calculix_chain_deck(&chain, &options, None).unwrap();
    let path = run_ccx("forced", &deck);
    let u = read_results(&path).unwrap();
    // ccx prints from the first increment on: its row k is sample k + 1
    assert_eq!(u.time.len() + 1, r.displacement[0].len());
    for (i, ours) in r.displacement.iter().enumerate() {
        let peak = ours.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let worst = u.displacement[i]
            .iter()
            .zip(&ours[1..])
            .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
        eprintln!("forced: m{} differs by {worst} m of {peak} m", i + 1);
        assert!(worst <= 0.01 * peak, "m{}: {worst} m of {peak} m", i + 1);
    }
}

/// A yielding front link, a second load path on m2 (a table, elastic
/// along it) after 150 mm and a rebound link on m3 (progressive, elastic)
/// after 100 mm: wall links both decks write exactly.
fn walled() -> Chain {
    walled_with(Unloading::Elastic)
}

/// [`walled`] with its path unloading by `unloading`.
fn walled_with(unloading: Unloading) -> Chain {
    let front = Link::new(
        Curve::bilinear(1.5e6, 8e4, 0.05).unwrap(),
        Unloading::Slope(2e6),
    )
    .unwrap();
    let links = vec![
        Link::new(
            Curve::progressive(5e5, 1e7, 0.3).unwrap(),
            Unloading::Elastic,
        )
        .unwrap(),
        Link::new(
            Curve::table(vec![[0.02, 6e4], [0.12, 1.1e5], [0.4, 1.4e5]]).unwrap(),
            Unloading::Slope(4e6),
        )
        .unwrap(),
    ];
    let path = Link::new(
        Curve::table(vec![[0.03, 6e4], [0.2, 1.2e5], [0.8, 1.5e5]]).unwrap(),
        unloading,
    )
    .unwrap();
    let rebound = Link::new(
        Curve::progressive(2e5, 5e6, 0.5).unwrap(),
        Unloading::Elastic,
    )
    .unwrap();
    Chain::new(vec![6.0, 180.0, 1250.0], vec![500.0, 2000.0], links)
        .unwrap()
        .with_front(front)
        .with_path(1, 0.15, path)
        .unwrap()
        .with_rebound(2, 0.1, rebound)
        .unwrap()
}

/// A link's largest compression, plastic set and force (never pulling)
/// along a crush history.
fn replay(link: &Link, crush: impl Iterator<Item = f64>) -> (f64, f64, Vec<f64>) {
    let mut state = bumpsim_core::link::LinkState::default();
    let force = crush.map(|c| link.force(c, &mut state).max(0.0)).collect();
    (state.reached, state.plastic_set(link), force)
}

/// The walled cars' barrier run: speed, m/s, and duration, s.
const WALLED_RUN: (f64, f64) = (40.0 / 3.6, 0.25);

/// `chain`'s CalculiX barrier deck (mm-s-t, 0.1 ms increments, the walled
/// run) and the path of its ccx results, run under `name`.
fn walled_in_ccx(chain: &Chain, title: &str, name: &str) -> (String, PathBuf) {
    let options = CalculixOptions {
        layout: mm_layout(),
        title: title.into(),
        id_offset: 100,
        ..Default::default()
    };
    let barrier = Barrier {
        speed: WALLED_RUN.0,
        duration: WALLED_RUN.1,
        increment: 1e-4,
        output_every: 1,
    };
    let deck = calculix_chain_deck(chain, &options, Some(&barrier)).unwrap();
    let path = run_ccx(name, &deck);
    (deck, path)
}

/// The wall links in ccx (mm-s-t along −y: the one-sided tables' signs
/// flip) against `Chain::run` into the barrier at 40 km/h: the peak
/// barrier force (the front brick's stress, and the wall springs' curves
/// on ccx's crush, which is what their tables carry), the front link's
/// largest compression and residual crush, and the path's and the rebound
/// link's largest compression, within 2 %. (A path that yields: the next
/// test.)
#[test]
fn wall_links_in_ccx_reproduce_the_impact_within_two_percent() {
    if !ccx_available() {
        return;
    }
    let chain = walled();
    let (_, path) = walled_in_ccx(&chain, "wall links", "walls");
    let (v, duration) = WALLED_RUN;
    let u = read_results(&path).unwrap();
    let f = read_link_forces(&path).unwrap();
    let front = f.links.iter().find(|l| l.0 == "front_link").unwrap();
    let front = &front.1;
    let (p, r) = (chain.path().unwrap(), chain.rebound().unwrap());
    let crush = |mass: usize, gap: f64| -> Vec<f64> {
        u.displacement[mass].iter().map(|x| -x - gap).collect()
    };
    let front_crush = crush(0, 0.0);
    let (path_crush, rebound_crush) = (crush(p.mass, p.gap), crush(r.mass, r.gap));
    let (_, _, second) = replay(&p.link, path_crush.iter().copied());
    let (_, _, rebound) = replay(&r.link, rebound_crush.iter().copied());
    let reach = |c: &[f64]| c.iter().fold(f64::MIN, |m, v| m.max(*v));
    let (path_reach, rebound_reach) = (reach(&path_crush), reach(&rebound_crush));
    let wall: Vec<f64> = (0..front.len())
        .map(|k| front[k] + second[k] + rebound[k])
        .collect();
    let peak = wall.iter().fold(0.0_f64, |m, v| m.max(*v));
    let k = bumpsim_export::chain::solver_unloading(chain.front().unwrap());
    let top = (0..front_crush.len())
        .max_by(|a, b| front_crush[*a].total_cmp(&front_crush[*b]))
        .unwrap();
    let front_peak = front.iter().fold(0.0_f64, |m, v| m.max(*v));
    let after = (top..front.len())
        .find(|&i| front[i] < 0.5 * front_peak)
        .expect("the front link unloads within the run");
    let front_set = front_crush[after] - front[after] / k;
    // ours
    let ours = barrier_run(&chain, v, duration);
    let our_peak = ours.force.iter().fold(0.0_f64, |m, v| m.max(-v));
    let x = &ours.displacement;
    let (our_front, our_front_set, _) = replay(chain.front().unwrap(), x[0].iter().copied());
    let our_path = reach(&x[p.mass]) - p.gap;
    let our_rebound = reach(&x[r.mass]) - r.gap;
    eprintln!(
        "walls: ccx peak {peak} N, front {} m set {front_set} m, path {path_reach} m, rebound {rebound_reach} m; bumpsim {our_peak} N, front {our_front} m set {our_front_set} m, path {our_path} m, rebound {our_rebound} m",
        reach(&front_crush)
    );
    assert!(our_path > 0.01 && our_rebound > 0.01, "both wall links act");
    assert_relative_eq!(peak, our_peak, max_relative = 0.02);
    assert_relative_eq!(reach(&front_crush), our_front, max_relative = 0.02);
    assert_relative_eq!(front_set, our_front_set, max_relative = 0.02);
    assert_relative_eq!(path_reach, our_path, max_relative = 0.02);
    assert_relative_eq!(rebound_reach, our_rebound, max_relative = 0.02);
}

/// The index of the largest value.
fn top(values: &[f64]) -> usize {
    (0..values.len())
        .max_by(|a, b| values[*a].total_cmp(&values[*b]))
        .unwrap()
}

/// A link's set on the unloading of a run: its crush less force over the
/// unloading slope `k`, once the force has fallen below half its peak.
fn set_of(crush: &[f64], force: &[f64], k: f64) -> f64 {
    let peak = force.iter().fold(0.0_f64, |m, v| m.max(*v));
    let after = (top(crush)..force.len())
        .find(|&i| force[i] < 0.5 * peak && force[i] > 0.0)
        .expect("the link unloads within the run");
    crush[after] - force[after] / k
}

/// The walled car with its path yielding (unloading at 5000 N/mm, above
/// its table's steepest slope 2000 N/mm: exact) in ccx against
/// `Chain::run` into the barrier at 40 km/h: the peak barrier force (the
/// front and path bricks' stresses, the rebound spring's curve on ccx's
/// crush), the path's largest crush and plastic set (ccx: crush less
/// force / k_u on the unloading; bumpsim: the link's set), the front link's
/// largest crush and set, within 2 %. (Before the path was a brick, its
/// spring unloaded along its curve: 508.0 kN against 469.5 kN.)
#[test]
fn a_yielding_wall_link_in_ccx_reproduces_the_impact_within_two_percent() {
    if !ccx_available() {
        return;
    }
    let chain = walled_with(Unloading::Slope(5e6));
    assert!(mapping(&chain.path().unwrap().link).exact);
    let (deck, path) = walled_in_ccx(&chain, "yielding wall link", "yielding-wall");
    assert!(!deck.contains("APPROXIMATE"), "{deck}");
    let (v, duration) = WALLED_RUN;
    let u = read_results(&path).unwrap();
    let f = read_link_forces(&path).unwrap();
    let force = |label: &str| &f.links.iter().find(|l| l.0 == label).expect(label).1;
    let (front, second) = (force("front_link"), force("second_load_path"));
    let (p, r) = (chain.path().unwrap(), chain.rebound().unwrap());
    let crush = |mass: usize, gap: f64| -> Vec<f64> {
        u.displacement[mass].iter().map(|x| -x - gap).collect()
    };
    let (front_crush, path_crush) = (crush(0, 0.0), crush(p.mass, p.gap));
    let (_, _, rebound) = replay(&r.link, crush(r.mass, r.gap).into_iter());
    let wall: Vec<f64> = (0..front.len())
        .map(|k| front[k] + second[k] + rebound[k])
        .collect();
    let peak = wall.iter().fold(0.0_f64, |m, v| m.max(*v));
    let k_front = bumpsim_export::chain::solver_unloading(chain.front().unwrap());
    let k_path = bumpsim_export::chain::solver_unloading(&p.link);
    let front_set = set_of(&front_crush, front, k_front);
    let path_set = set_of(&path_crush, second, k_path);
    let (front_reach, path_reach) = (front_crush[top(&front_crush)], path_crush[top(&path_crush)]);
    let ours = barrier_run(&chain, v, duration);
    let our_peak = ours.force.iter().fold(0.0_f64, |m, v| m.max(-v));
    let x = &ours.displacement;
    let (our_front, our_front_set, _) = replay(chain.front().unwrap(), x[0].iter().copied());
    let (our_path, our_path_set, _) = replay(&p.link, x[p.mass].iter().map(|x| x - p.gap));
    eprintln!(
        "yielding wall: ccx peak {peak} N, front {front_reach} m set {front_set} m, path {path_reach} m set {path_set} m; bumpsim {our_peak} N, front {our_front} m set {our_front_set} m, path {our_path} m set {our_path_set} m"
    );
    assert!(
        our_path_set > 0.01,
        "the path takes a set: {our_path_set} m"
    );
    assert_relative_eq!(peak, our_peak, max_relative = 0.02);
    assert_relative_eq!(path_reach, our_path, max_relative = 0.02);
    assert_relative_eq!(path_set, our_path_set, max_relative = 0.02);
    assert_relative_eq!(front_reach, our_front, max_relative = 0.02);
    assert_relative_eq!(front_set, our_front_set, max_relative = 0.02);
}
