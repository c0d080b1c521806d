//! The reachable region of two responses of a linear stage-1 model
//! (paper C, spec §7).
//!
//! With main-effect models `y = c + Σ_j g_j t_j` of two responses in m coded
//! factors `t ∈ [−1, 1]^m` (plate thicknesses ±20 %), the reachable set of
//! `(y1, y2)` is a zonotope: the sum of the segments `[−g_j, g_j]`. Its exact
//! boundary is a convex polygon of 2m vertices (generators sorted by angle,
//! walked once forwards and once backwards). The thesis sampled it with
//! 50,000 random thickness sets; both are given. For a corner of a requested
//! cell, the thickness set of least norm that reaches it is found with the
//! bounds enforced (components that leave [−1, 1] are fixed at the bound and
//! the rest re-solved), and its residual is reported; a corner outside the
//! region is said to be unreachable.

use crate::model::{ModelFile, Response};
use crate::regression::Term;
use nalgebra::{DMatrix, DVector};
use rand_chacha::ChaCha8Rng;
use rand_core::{Rng, SeedableRng};
use serde::Serialize;

/// A linear map from coded factors to two responses.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LinearMap {
    /// The response names.
    pub names: [String; 2],
    /// The value at the centre (all factors 0).
    pub centre: [f64; 2],
    /// One generator per factor: the change of both responses per coded unit.
    pub generators: Vec<[f64; 2]>,
}

/// Why the region cannot be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("reachable region: {0}")]
pub struct ReachError(pub String);

fn main_effects(r: &Response, factors: &[String]) -> Result<(f64, Vec<f64>), ReachError> {
    let mut centre = 0.0;
    let mut g = vec![0.0; factors.len()];
    for (name, c) in &r.coefficients {
        match Term::parse(name, factors) {
            Some(Term::Intercept) => centre = *c,
            Some(Term::Main(i)) => g[i] = *c,
            _ => {
                return Err(ReachError(format!(
                    "response '{}' has term '{name}': the region needs a main-effect (linear) model",
                    r.name
                )));
            }
        }
    }
    Ok((centre, g))
}

/// The largest `|intercept| + Σ|main effect|` of a response the region
/// takes: its square stays a number (the region's corner tests and
/// distances multiply two responses), as in `doe fit`, whose sums of
/// squares must be numbers.
pub const MAX_REACH: f64 = 1e150;

/// Refuses a response whose coefficients reach beyond [`MAX_REACH`],
/// naming its largest coefficient.
fn check_reach(r: &Response) -> Result<(), ReachError> {
    let reach: f64 = r.coefficients.values().map(|c| c.abs()).sum();
    if reach <= MAX_REACH {
        return Ok(());
    }
    let (term, c) = r
        .coefficients
        .iter()
        .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
        .map_or(("", 0.0), |(t, c)| (t.as_str(), *c));
    Err(ReachError(format!(
        "response '{}': coefficient of '{term}' = {}: expected |intercept| + Σ|main effects| ≤ {} (the region multiplies two responses): rescale it (other units)",
        r.name,
        bumpsim_core::units::short(c),
        bumpsim_core::units::short(MAX_REACH)
    )))
}

impl LinearMap {
    /// The map of responses `x` and `y` of a model file.
    ///
    /// Refused: `x` equal to `y` (a response against itself is a line, not
    /// a region), and a response whose intercept and main effects reach
    /// beyond [`MAX_REACH`] (the region's areas and corner distances square
    /// them).
    pub fn from_model(model: &ModelFile, x: &str, y: &str) -> Result<LinearMap, ReachError> {
        model.validate().map_err(|e| ReachError(e.to_string()))?;
        if x == y {
            return Err(ReachError(format!(
                "--x and --y both name '{x}': expected two different responses"
            )));
        }
        let factors: Vec<String> = model.factors.iter().map(|f| f.name.clone()).collect();
        let find = |n: &str| {
            model
                .responses
                .iter()
                .find(|r| r.name == n)
                .ok_or_else(|| ReachError(format!("no response '{n}' in the model")))
        };
        let (cx, gx) = main_effects(find(x)?, &factors)?;
        let (cy, gy) = main_effects(find(y)?, &factors)?;
        check_reach(find(x)?)?;
        check_reach(find(y)?)?;
        Ok(LinearMap {
            names: [x.into(), y.into()],
            centre: [cx, cy],
            generators: gx.into_iter().zip(gy).map(|(a, b)| [a, b]).collect(),
        })
    }

    /// The responses at coded factors `t`.
    pub fn at(&self, t: &[f64]) -> [f64; 2] {
        let mut p = self.centre;
        for (g, ti) in self.generators.iter().zip(t) {
            p[0] += g[0] * ti;
            p[1] += g[1] * ti;
        }
        p
    }

    /// `n` random factor sets in [−1, 1]^m mapped to the plane.
    pub fn samples(&self, n: usize, seed: u64) -> Vec<[f64; 2]> {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let m = self.generators.len();
        (0..n)
            .map(|_| {
                let t: Vec<f64> = (0..m)
                    .map(|_| -1.0 + 2.0 * ((rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64))
                    .collect();
                self.at(&t)
            })
            .collect()
    }

    /// The exact boundary, counter-clockwise.
    pub fn boundary(&self) -> Vec<[f64; 2]> {
        let mut g: Vec<[f64; 2]> = self
            .generators
            .iter()
            .filter(|g| g[0] != 0.0 || g[1] != 0.0)
            .map(|&[a, b]| {
                if b < 0.0 || (b == 0.0 && a < 0.0) {
                    [-a, -b]
                } else {
                    [a, b]
                }
            })
            .collect();
        g.sort_by(|a, b| a[1].atan2(a[0]).total_cmp(&b[1].atan2(b[0])));
        let mut p = [
            self.centre[0] - g.iter().map(|v| v[0]).sum::<f64>(),
            self.centre[1] - g.iter().map(|v| v[1]).sum::<f64>(),
        ];
        let mut polygon = vec![p];
        for sign in [2.0, -2.0] {
            for v in &g {
                p = [p[0] + sign * v[0], p[1] + sign * v[1]];
                polygon.push(p);
            }
        }
        polygon.pop();
        polygon
    }

    /// The factor set of least norm within [−1, 1] that reaches `target`,
    /// and the distance left.
    pub fn solve(&self, target: [f64; 2]) -> (Vec<f64>, f64) {
        let m = self.generators.len();
        let mut t = vec![0.0; m];
        let mut fixed = vec![false; m];
        for _ in 0..=m {
            let free: Vec<usize> = (0..m).filter(|&j| !fixed[j]).collect();
            if free.is_empty() {
                break;
            }
            let rest = self.at(&(0..m)
                .map(|j| if fixed[j] { t[j] } else { 0.0 })
                .collect::<Vec<_>>());
            let r = DVector::from_vec(vec![target[0] - rest[0], target[1] - rest[1]]);
            let b = DMatrix::from_fn(2, free.len(), |i, c| self.generators[free[c]][i]);
            let solution = b
                .clone()
                .pseudo_inverse(1e-12)
                .map(|p| p * &r)
                .unwrap_or_else(|_| DVector::zeros(free.len()));
            for (c, &j) in free.iter().enumerate() {
                t[j] = solution[c];
            }
            let outside: Vec<usize> = free.iter().copied().filter(|&j| t[j].abs() > 1.0).collect();
            if outside.is_empty() {
                break;
            }
            for j in outside {
                t[j] = t[j].clamp(-1.0, 1.0);
                fixed[j] = true;
            }
        }
        let p = self.at(&t);
        (
            t,
            ((p[0] - target[0]).powi(2) + (p[1] - target[1]).powi(2)).sqrt(),
        )
    }
}

/// Whether `point` lies inside a counter-clockwise convex polygon.
pub fn contains(polygon: &[[f64; 2]], point: [f64; 2]) -> bool {
    let n = polygon.len();
    (0..n).all(|i| {
        let (a, b) = (polygon[i], polygon[(i + 1) % n]);
        (b[0] - a[0]) * (point[1] - a[1]) - (b[1] - a[1]) * (point[0] - a[0])
            >= -1e-9 * (1.0 + a[0].abs() + a[1].abs()).powi(2)
    })
}

/// One corner of a cell.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Corner {
    /// The target (x, y).
    pub target: [f64; 2],
    /// Whether it lies in the reachable region.
    pub reachable: bool,
    /// The coded factor set found.
    pub factors: Vec<f64>,
    /// Distance between the target and what the factor set reaches.
    pub residual: f64,
}

/// The four corners of the cell `[x0, x1] × [y0, y1]` (finite, x0 ≤ x1,
/// y0 ≤ y1).
pub fn cell(map: &LinearMap, x: [f64; 2], y: [f64; 2]) -> Result<Vec<Corner>, ReachError> {
    let finite = x.iter().chain(&y).all(|v| v.is_finite());
    if !(finite && x[0] <= x[1] && y[0] <= y[1]) {
        return Err(ReachError(format!(
            "cell {}..{} × {}..{}: expected finite bounds X0 ≤ X1, Y0 ≤ Y1",
            x[0], x[1], y[0], y[1]
        )));
    }
    let polygon = map.boundary();
    let corners = [[x[0], y[0]], [x[1], y[0]], [x[1], y[1]], [x[0], y[1]]]
        .into_iter()
        .map(|target| {
            let (factors, residual) = map.solve(target);
            let scale = 1e-9 * (1.0 + target[0].abs() + target[1].abs());
            Corner {
                target,
                reachable: contains(&polygon, target) && residual <= scale,
                factors,
                residual,
            }
        })
        .collect();
    Ok(corners)
}
