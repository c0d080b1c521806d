//! Stable-Rust fuzzing of the readers (proptest; no cargo fuzz, no nightly).
//!
//! Each target (CSV, EV5, ISO-MME, car/bumper/planar car TOML, study,
//! planar series and study,
//! model JSON, CalculiX results, the FE bumper mesh and its .dat, campaign file and state) mutates seed files (tests/fuzz/ and examples/identify/) with a
//! byte strategy (flips, inserts, deletes, truncation) and a structure
//! strategy (a line or number replaced by hostile values: NaN, inf, 1e308,
//! huge integers, empty), writes the result to a scratch file and runs the
//! reader: it must return Ok or an error, never panic. Each target runs for
//! `BUMPSIM_FUZZ_SECONDS` seconds (default 2, so `cargo test` stays quick;
//! scripts/test sets 30). The generator is seeded (`BUMPSIM_FUZZ_SEED`,
//! default below), so a run is reproducible: a longer run with the same seed
//! covers every case a shorter one tries; set another seed to explore.

use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed, TestCaseError, TestRunner};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use crate::util::root;

fn seed(path: &str) -> Vec<u8> {
    std::fs::read(root().join(path)).unwrap()
}

fn scratch(target: &str) -> PathBuf {
    crate::util::scratch(&format!("fuzz-{target}"))
}

fn seconds() -> u64 {
    std::env::var("BUMPSIM_FUZZ_SECONDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(2)
}

/// The generator seed: `BUMPSIM_FUZZ_SEED` or a fixed default.
fn rng_seed() -> u64 {
    std::env::var("BUMPSIM_FUZZ_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0x6275_6d70)
}

const HOSTILE: [&str; 12] = [
    "NaN",
    "inf",
    "-inf",
    "1e308",
    "-1e308",
    "1e-320",
    "0",
    "-0",
    "18446744073709551615",
    "-1",
    "",
    "99999999999999999999999",
];

/// One edit of a seed.
#[derive(Debug, Clone)]
enum Edit {
    Flip(usize, u8),
    Insert(usize, u8),
    Delete(usize, usize),
    Truncate(usize),
    /// Replace the n-th number-like token by a hostile value.
    Number(usize, usize),
    /// Duplicate line n.
    Repeat(usize),
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        (any::<usize>(), any::<u8>()).prop_map(|(i, b)| Edit::Flip(i, b)),
        (any::<usize>(), any::<u8>()).prop_map(|(i, b)| Edit::Insert(i, b)),
        (any::<usize>(), 1usize..64).prop_map(|(i, n)| Edit::Delete(i, n)),
        any::<usize>().prop_map(Edit::Truncate),
        (any::<usize>(), 0..HOSTILE.len()).prop_map(|(i, h)| Edit::Number(i, h)),
        (any::<usize>(), 0..HOSTILE.len()).prop_map(|(i, h)| Edit::Number(i, h)),
        any::<usize>().prop_map(Edit::Repeat),
    ]
}

fn apply(bytes: &mut Vec<u8>, edit: &Edit) {
    let len = bytes.len().max(1);
    match *edit {
        Edit::Flip(i, b) if !bytes.is_empty() => bytes[i % len] ^= b,
        Edit::Insert(i, b) => bytes.insert(i % (bytes.len() + 1), b),
        Edit::Delete(i, n) if !bytes.is_empty() => {
            let start = i % len;
            let end = (start + n).min(bytes.len());
            bytes.drain(start..end);
        }
        Edit::Truncate(i) => bytes.truncate(i % (bytes.len() + 1)),
        Edit::Number(i, h) => replace_number(bytes, i, HOSTILE[h]),
        Edit::Repeat(i) => {
            let text = String::from_utf8_lossy(bytes).into_owned();
            let lines: Vec<&str> = text.split_inclusive('\n').collect();
            if !lines.is_empty() {
                let k = i % lines.len();
                let mut out: Vec<&str> = lines.clone();
                out.insert(k, lines[k]);
                *bytes = out.concat().into_bytes();
            }
        }
        _ => {}
    }
}

fn replace_number(bytes: &mut Vec<u8>, which: usize, value: &str) {
    let is_num = |b: u8| b.is_ascii_digit() || b == b'.' || b == b'e' || b == b'E' || b == b'-';
    let mut spans = Vec::new();
    let mut k = 0;
    while k < bytes.len() {
        if bytes[k].is_ascii_digit() {
            let start = k;
            while k < bytes.len() && is_num(bytes[k]) {
                k += 1;
            }
            spans.push((start, k));
        } else {
            k += 1;
        }
    }
    if let Some(&(a, b)) = spans.get(which % spans.len().max(1)) {
        bytes.splice(a..b, value.bytes());
    }
}

fn mutated(seed: Vec<u8>) -> impl Strategy<Value = Vec<u8>> {
    proptest::collection::vec(edit(), 1..8).prop_map(move |edits| {
        let mut bytes = seed.clone();
        edits.iter().for_each(|e| apply(&mut bytes, e));
        bytes
    })
}

/// Runs `check` on mutations of `seed` for the fuzz time.
fn fuzz(name: &str, seed: Vec<u8>, check: impl Fn(&Path, &[u8])) {
    let dir = scratch(name);
    let deadline = Instant::now() + Duration::from_secs(seconds());
    let mut runner = TestRunner::new(Config {
        cases: 64,
        failure_persistence: None,
        rng_seed: RngSeed::Fixed(rng_seed()),
        ..Config::default()
    });
    let strategy = mutated(seed);
    let mut rounds = 0;
    while rounds == 0 || Instant::now() < deadline {
        rounds += 1;
        let result = runner.run(&strategy, |bytes| {
            check(&dir, &bytes);
            Ok::<(), TestCaseError>(())
        });
        if let Err(e) = result {
            panic!("fuzz target {name} (seed {}): {e}", rng_seed());
        }
    }
}

#[test]
fn fuzz_csv_table() {
    fuzz("csv", seed("tests/fuzz/table.csv"), |dir, bytes| {
        let path = dir.join("t.csv");
        std::fs::write(&path, bytes).unwrap();
        let _ = bumpsim_io::table::Table::read(&path);
        let _ = bumpsim_io::test_data::TestData::open(&path);
    });
}

#[test]
fn fuzz_car_and_bumper_toml() {
    fuzz("car", seed("tests/fuzz/car.toml"), |dir, bytes| {
        let text = String::from_utf8_lossy(bytes);
        let _ = bumpsim_io::car::Car::parse(&text, Path::new("car.toml"));
        let _ = bumpsim_io::car::Car::parse_json(&text, Path::new("car.json"));
        let path = dir.join("b.toml");
        std::fs::write(&path, bytes).unwrap();
        let _ = bumpsim_impact::bumper::Bumper::read(&path);
    });
    fuzz("bumper", seed("tests/fuzz/bumper.toml"), |dir, bytes| {
        let path = dir.join("b.toml");
        std::fs::write(&path, bytes).unwrap();
        if let Ok(b) = bumpsim_impact::bumper::Bumper::read(&path) {
            let _ = b.stiffest();
        }
    });
}

#[test]
fn fuzz_planar_car_toml() {
    use bumpsim_planar::{Face, PlanarCar, Settings, Side, Striker, simulate};
    // a fixed step keeps every case short; a diverging run must be an error
    let settings = Settings {
        step: Some(1e-5),
        duration: 0.01,
        ..Settings::default()
    };
    let face = Face::plane_in_degrees(10.0, 40.0, Side::Left);
    let check = |_: &Path, bytes: &[u8]| {
        let text = String::from_utf8_lossy(bytes);
        if let Ok(car) = PlanarCar::parse(&text, Path::new("planar.toml"))
            && let Ok(r) = simulate(&car, &Striker::barrier(face, 4.0), &settings)
        {
            assert!(r.peak_force.is_finite() && r.energy.initial.is_finite());
        }
    };
    fuzz("planar", seed("tests/fuzz/planar.toml"), check);
    // side members of nonlinear links ([[left.links]] tables, issue 46)
    fuzz("planar-links", seed("examples/planar/links.toml"), check);
}

/// A chain car of nonlinear links (issue 46: `[[links]]` and `[front]`
/// loading curves and tables, unloading rules): read, every link's force
/// and stored energy finite along its curve.
#[test]
fn fuzz_links_car_toml() {
    fuzz("links-car", seed("examples/links/car.toml"), |_, bytes| {
        let text = String::from_utf8_lossy(bytes);
        if let Ok(car) = bumpsim_io::link_car::LinkCar::parse(&text, Path::new("car.toml")) {
            let chain = &car.chain;
            for link in chain.links().iter().chain(chain.front()) {
                for d in [0.0, 1e-4, 0.02, 0.5, 3.0] {
                    let (force, energy) = (link.curve().force(d), link.curve().energy(d));
                    assert!(force.is_finite() && energy.is_finite(), "{link:?} at {d} m");
                }
            }
        }
    });
}

#[test]
fn fuzz_study_toml() {
    fuzz(
        "study",
        seed("examples/identify/study.toml"),
        |dir, bytes| {
            let path = dir.join("study.toml");
            std::fs::write(&path, bytes).unwrap();
            if let Ok(study) = bumpsim_ident::study::Study::read(&path) {
                for dof in study.dofs().into_iter().filter(|&d| d <= 3) {
                    let _ = study.settings(dof);
                }
            }
        },
    );
}

/// The chain study's issue-44 inputs: `[identification] objective`, a
/// case's `noise` and `bias`, `[priors]`; the priors applied to the
/// defaults of each model (their centres and spreads usable).
#[test]
fn fuzz_study_objective_and_priors() {
    let study = String::from_utf8(seed("examples/identify/study.toml")).unwrap();
    let case = "cfc = 180\noutput_dof = 1\n";
    assert!(study.contains(case));
    let seeded = format!(
        "[identification]\nobjective = \"acceleration\"\n{}\n[priors]\ntotal_mass = {{ spread = 0.02 }}\nm1 = \"none\"\nk2 = {{ value = \"600 N/mm\", spread = 0.3 }}\n",
        study.replacen(
            case,
            &format!("{case}noise = 0.002\nbias = [-0.01, 0.0]\n"),
            1
        )
    );
    fuzz("study-priors", seeded.into_bytes(), |dir, bytes| {
        let path = dir.join("study.toml");
        std::fs::write(&path, bytes).unwrap();
        let Ok(study) = bumpsim_ident::study::Study::read(&path) else {
            return;
        };
        for dof in study.dofs().into_iter().filter(|&d| d <= 3) {
            let Ok(settings) = study.settings(dof) else {
                continue;
            };
            let start = vec![100.0; bumpsim_core::model::parameter_count(dof)];
            let free: Vec<usize> = (0..start.len()).collect();
            if let Ok(priors) = bumpsim_ident::priors::priors(&settings, &start, &free) {
                for p in priors {
                    assert!(p.centre.is_finite() && p.centre > 0.0, "{p:?}");
                    assert!(p.spread.is_finite() && p.spread > 0.0, "{p:?}");
                }
            }
        }
    });
}

#[test]
fn fuzz_model_json() {
    fuzz("model", seed("tests/fuzz/model.json"), |_, bytes| {
        if let Ok(model) = serde_json::from_slice::<bumpsim_doe::model::ModelFile>(bytes) {
            let _ = model.predict(&[("A".into(), 0.5)]);
            if let Ok(map) = bumpsim_doe::reachable::LinearMap::from_model(&model, "y", "y") {
                let _ = map.boundary();
            }
        }
    });
}

#[test]
fn fuzz_isomme_channel_files() {
    let flat = root().join("examples/identify/FLAT");
    let mut chn = seed("examples/identify/FLAT/Channel/FLAT.chn");
    chn.extend(b"\r\n");
    for (part, name) in [
        (seed("examples/identify/FLAT/Channel/FLAT.001"), "FLAT.001"),
        (chn, "FLAT.chn"),
        (seed("examples/identify/FLAT/FLAT.mme"), "FLAT.mme"),
    ] {
        let name = name.to_string();
        let flat = flat.clone();
        fuzz(&format!("isomme-{name}"), part, move |dir, bytes| {
            let test = dir.join("FLAT");
            if !test.exists() {
                std::fs::create_dir_all(test.join("Channel")).unwrap();
                for f in [
                    "FLAT.mme",
                    "Channel/FLAT.chn",
                    "Channel/FLAT.001",
                    "Channel/FLAT.002",
                    "Channel/FLAT.003",
                ] {
                    std::fs::copy(flat.join(f), test.join(f)).unwrap();
                }
            }
            let target = if name.ends_with(".mme") {
                test.join(&name)
            } else {
                test.join("Channel").join(&name)
            };
            let original = std::fs::read(flat.join(target.strip_prefix(&test).unwrap())).unwrap();
            std::fs::write(&target, bytes).unwrap();
            let _ = bumpsim_io::test_data::TestData::open(&test);
            std::fs::write(&target, original).unwrap();
        });
    }
}

#[test]
fn fuzz_ev5() {
    fuzz("ev5", seed("tests/fuzz/test.ev5"), |dir, bytes| {
        let path = dir.join("t.EV5");
        std::fs::write(&path, bytes).unwrap();
        let _ = bumpsim_io::test_data::TestData::open(&path);
    });
}

#[test]
fn fuzz_calculix_dat() {
    let dir = scratch("calculix-setup");
    let model =
        bumpsim_core::model::MsdModel::new(vec![1.8, 74.8], vec![1.0e5], vec![4.75e5]).unwrap();
    let deck = bumpsim_export::calculix::calculix_deck(&model, &Default::default()).unwrap();
    let deck_path = dir.join("car.inp");
    std::fs::write(&deck_path, deck).unwrap();
    fuzz("calculix", seed("tests/fuzz/results.dat"), |_, bytes| {
        std::fs::write(deck_path.with_extension("dat"), bytes).unwrap();
        let _ = bumpsim_export::calculix::read_results(&deck_path);
    });
}

#[test]
fn fuzz_fe_bumper_mesh_and_dat() {
    use bumpsim_fe::{bumper::BumperMesh, deck, lsdyna};
    use bumpsim_impact::impact::Scenario;
    let car =
        bumpsim_core::model::MsdModel::new(vec![30.0, 1200.0], vec![8e3], vec![1.5e6]).unwrap();
    let scenario = Scenario::Impactor {
        mass: 900.0,
        speed: 2.0,
    };
    let run = deck::Run {
        increment: 1e-4,
        duration: 0.1,
    };
    let ls = lsdyna::LsDynaRun {
        units: Default::default(),
        duration: 0.1,
        output_interval: 1e-4,
    };
    fuzz(
        "fe-mesh",
        seed("examples/fe/bumper-plastic.toml"),
        |dir, bytes| {
            let path = dir.join("mesh.toml");
            std::fs::write(&path, bytes).unwrap();
            if let Ok(mesh) = BumperMesh::read(&path) {
                let _ = mesh.equivalent_bumper();
                if let Ok((text, _)) = deck::coupled_deck(&mesh, &car, scenario, &run) {
                    assert!(!text.contains("NaN") && !text.contains("inf"), "{text}");
                }
                let _ = lsdyna::lsdyna_deck(&mesh, &car, scenario, &ls);
            }
        },
    );
    fuzz("fe-dat", seed("tests/fuzz/fe.dat"), |_, bytes| {
        let _ = bumpsim_export::dat::parse(&String::from_utf8_lossy(bytes), Path::new("fe.dat"));
    });
}

#[test]
fn fuzz_campaign_file_and_state() {
    fuzz(
        "campaign-file",
        seed("examples/campaign/campaign.toml"),
        |path, bytes| {
            let _ = bumpsim_campaign::spec::Spec::parse(&String::from_utf8_lossy(bytes), path);
        },
    );
    let dir = scratch("campaign-state-setup");
    fuzz(
        "campaign-state",
        seed("tests/fuzz/campaign-state.toml"),
        |_, bytes| {
            std::fs::write(dir.join(bumpsim_campaign::state::STATE_FILE), bytes).unwrap();
            if let Ok(state) = bumpsim_campaign::state::State::read(&dir) {
                let _ = state.counts();
            }
        },
    );
}

#[test]
fn fuzz_planar_series_and_study() {
    use bumpsim_planar::series::make_series;
    use bumpsim_planar::study::PlanarStudy;
    let fuzz_dir = root().join("tests/fuzz");
    let series_dir = scratch("planar-series-files");
    std::fs::copy(fuzz_dir.join("planar.toml"), series_dir.join("planar.toml")).unwrap();
    fuzz(
        "planar-series",
        seed("tests/fuzz/planar-series.toml"),
        |_, bytes| {
            let path = series_dir.join("series.toml");
            std::fs::write(&path, bytes).unwrap();
            if let Ok(series) = make_series(&path) {
                for test in &series.tests {
                    let finite = test
                        .channels
                        .iter()
                        .all(|c| c.series.values().iter().all(|v| v.is_finite()));
                    assert!(finite, "test {} has non-finite samples", test.name);
                }
            }
        },
    );
    // the study of the seed series, over its own tests
    let tests = scratch("planar-study-tests");
    let series = make_series(&fuzz_dir.join("planar-series.toml")).unwrap();
    for t in &series.tests {
        let header =
            bumpsim_io::test_data::iso_header::test_header(&t.name, Some(t.striker.0), None);
        bumpsim_io::isomme::write(&tests.join(&t.name), &t.name, &header, &t.channels).unwrap();
    }
    std::fs::write(tests.join("start.toml"), &series.start).unwrap();
    // with issue 44's model settings and stated priors in the seed
    let seeded = series.study.replacen(
        "[model]\n",
        "[model]\ncornering = true\nrelaxation = false\nbumper = \"start\"\n",
        1,
    ) + "\n[priors]\nbody.yaw_inertia = { value = 2300.0, spread = 0.2 }\ntyres.mu_lateral = \"none\"\n";
    fuzz("planar-study", seeded.into_bytes(), |_, bytes| {
        let path = tests.join("study.toml");
        std::fs::write(&path, bytes).unwrap();
        if let Ok(study) = PlanarStudy::read(&path) {
            for case in study.cases.iter().chain(&study.validation) {
                assert!(
                    bumpsim_planar::drive::validate(&study.setup.template, &case.drive).is_ok(),
                    "{}",
                    case.name
                );
            }
            for p in &study.setup.priors {
                let usable = |v: Option<f64>| v.is_none_or(|v| v.is_finite() && v > 0.0);
                assert!(usable(p.value) && usable(p.spread), "{p:?}");
            }
        }
    });
}
