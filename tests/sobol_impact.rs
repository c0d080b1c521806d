//! Issue 39's Sobol' indices of an impact output: the peak force of a 1-D
//! pendulum impact on a 2-mass car behind a three-part bumper over six
//! parameters. The indices equal SALib's (its own sampling and analysis,
//! the impacts run here) within the bootstrap error. How long 6 parameters
//! × 10 000 base samples (80 000 impacts) take is measured by the criterion
//! bench `crates/bumpsim-impact/benches/sobol.rs` (a timed test failed
//! whenever the machine was busy).

use bumpsim::estimate::sobol::{Indices, Settings, indices};
use std::io::Write;
use std::process::{Command, Stdio};
use std::sync::Mutex;

#[path = "../crates/bumpsim-impact/benches/sobol/model.rs"]
mod model;
use model::{RANGES, inputs, peak_force};

/// The two tests run one after the other: each sweep has both cores.
static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

#[test]
fn six_parameters_times_ten_thousand_base_samples_rank_the_speed_first() {
    let _alone = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let s = indices(&inputs(), &peak_force, &Settings::new(10_000, 1)).unwrap();
    print(&s);
    assert_eq!(s.evaluations, 80_000);
    // the car's front mass hardly matters to the peak force, the speed does
    assert!(s.total[5] > 10.0 * s.total[0], "{s:?}");
}

fn print(s: &Indices) {
    for i in 0..s.names.len() {
        eprintln!(
            "{:<24} S {:.4} ± {:.4}  ST {:.4} ± {:.4}",
            s.names[i], s.first[i], s.first_conf[i], s.total[i], s.total_conf[i]
        );
    }
}

/// SALib samples (its Sobol' sequence, scrambled), the impacts run here
/// on its rows, SALib analyses.
const SALIB: &str = r#"
import sys, numpy as np
from SALib.sample import sobol as sample
from SALib.analyze import sobol
names = sys.argv[1].split(";")
bounds = [[float(a), float(b)] for a, b in (r.split(",") for r in sys.argv[2].split(";"))]
problem = {"num_vars": len(names), "names": names, "bounds": bounds}
X = sample.sample(problem, int(sys.argv[3]), calc_second_order=False, seed=5)
for row in X:
    sys.stdout.write(" ".join(repr(float(v)) for v in row) + "\n")
sys.stdout.write("\n"); sys.stdout.flush()
Y = np.array([float(sys.stdin.readline()) for _ in X])
r = sobol.analyze(problem, Y, calc_second_order=False, seed=5)
print(*r["S1"], *r["S1_conf"], *r["ST"], *r["ST_conf"])
"#;

#[test]
fn impact_indices_equal_salibs_within_the_bootstrap_error() {
    if !bumpsim_peers::python_available("SALib") {
        return;
    }
    let _alone = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let base = 2048;
    let names: Vec<&str> = RANGES.iter().map(|r| r.0).collect();
    let bounds: Vec<String> = RANGES.iter().map(|r| format!("{},{}", r.1, r.2)).collect();
    let mut child = Command::new("python3")
        .args([
            "-c",
            SALIB,
            &names.join(";"),
            &bounds.join(";"),
            &base.to_string(),
        ])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    let mut output = String::new();
    use std::io::Read;
    let mut stdout = child.stdout.take().unwrap();
    let mut reader = std::io::BufReader::new(&mut stdout);
    let mut rows = Vec::new();
    loop {
        let mut line = String::new();
        std::io::BufRead::read_line(&mut reader, &mut line).unwrap();
        if line.trim().is_empty() {
            break;
        }
        rows.push(
            line.split_whitespace()
                .map(|v| v.parse().unwrap())
                .collect::<Vec<f64>>(),
        );
    }
    let answers: Vec<String> = rows
        .iter()
        .map(|x| format!("{:e}", peak_force(x)))
        .collect();
    let mut stdin = child.stdin.take().unwrap();
    writeln!(stdin, "{}", answers.join("\n")).unwrap();
    drop(stdin);
    reader.read_to_string(&mut output).unwrap();
    assert!(child.wait().unwrap().success());
    let theirs: Vec<f64> = output
        .split_whitespace()
        .map(|v| v.parse().unwrap())
        .collect();
    let s = indices(&inputs(), &peak_force, &Settings::new(base, 2)).unwrap();
    print(&s);
    let d = RANGES.len();
    for i in 0..d {
        let (first, first_conf, total, total_conf) = (
            theirs[i],
            theirs[d + i],
            theirs[2 * d + i],
            theirs[3 * d + i],
        );
        eprintln!(
            "SALib {:<24} S {first:.4} ± {first_conf:.4}  ST {total:.4} ± {total_conf:.4}",
            s.names[i]
        );
        let error = |a: f64, b: f64| (a * a + b * b).sqrt();
        assert!(
            (s.first[i] - first).abs() < error(s.first_conf[i], first_conf),
            "S {i}"
        );
        assert!(
            (s.total[i] - total).abs() < error(s.total_conf[i], total_conf),
            "ST {i}"
        );
    }
}
