//! Experimental designs in coded units (spec §7, thesis ch. 3.5).
//!
//! Coded units: `z = (X − X_centre) / (X_high − X_centre)`, so the low and
//! high levels are −1 and +1. Designs:
//! - two-level full factorial 2^k (standard order, first factor fastest) with
//!   centre points;
//! - fractional factorial 2^(k−p) from generators such as `D=AB`, `E=-AC`;
//!   its resolution is computed from the defining relation (the shortest
//!   word among all products of the generator words), not assumed;
//! - central composite: face-centred (α = 1) or circumscribed
//!   (α = (2^k)^(1/4), rotatable);
//! - Latin hypercube and uniform random samples on [−1, 1]^k from a seed.
//!
//! ```
//! use bumpsim_doe::design::{fractional_factorial, resolution};
//! let d = fractional_factorial(&["A", "B", "C", "D=AB", "E=AC", "F=BC", "G=ABC"]).unwrap();
//! assert_eq!(d.runs.len(), 8);
//! assert_eq!(resolution(&["D=AB", "E=AC", "F=BC", "G=ABC"]).unwrap(), 3);
//! ```

use crate::model::Factor;
use rand_chacha::ChaCha8Rng;
use rand_core::{Rng, SeedableRng};
use std::str::FromStr;

/// Why a design cannot be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum DesignError {
    /// A generator is malformed.
    #[error("generator '{generator}': {reason}")]
    Generator {
        /// The generator text.
        generator: String,
        /// What is wrong.
        reason: String,
    },
    /// A size is out of range.
    #[error("design: {0}")]
    Size(String),
    /// More centre points than [`MAX_CENTRE`].
    #[error("{centre} centre points: at most {MAX_CENTRE} (limit MAX_CENTRE)")]
    Centre {
        /// The centre points asked for.
        centre: usize,
    },
}

/// A design: factor names and runs in coded units.
#[derive(Debug, Clone, PartialEq)]
pub struct Design {
    /// Factor names.
    pub factors: Vec<String>,
    /// Runs, one row of coded levels per run.
    pub runs: Vec<Vec<f64>>,
}

/// Most centre points of a design (each is a run): docs/limits.md.
pub const MAX_CENTRE: usize = 1_000_000;

/// Refuses more centre points than [`MAX_CENTRE`] (each is a row held in
/// memory).
fn check_centre(centre: usize) -> Result<(), DesignError> {
    if centre > MAX_CENTRE {
        return Err(DesignError::Centre { centre });
    }
    Ok(())
}

/// Full factorial 2^k in standard order (first factor alternates fastest),
/// then `centre` centre points.
pub fn full_factorial(factors: &[&str], centre: usize) -> Result<Design, DesignError> {
    let k = factors.len();
    if k == 0 || k > 20 {
        return Err(DesignError::Size(format!("{k} factors: expected 1 to 20")));
    }
    check_centre(centre)?;
    distinct_names(factors)?;
    let mut runs: Vec<Vec<f64>> = (0..1usize << k)
        .map(|r| {
            (0..k)
                .map(|j| if r >> j & 1 == 1 { 1.0 } else { -1.0 })
                .collect()
        })
        .collect();
    runs.extend((0..centre).map(|_| vec![0.0; k]));
    Ok(Design {
        factors: factors.iter().map(|s| s.to_string()).collect(),
        runs,
    })
}

/// A generator `D=AB` (or `D=-AB`): the new factor, its sign and the base letters.
fn parse_generator(text: &str, base: &[String]) -> Result<(String, f64, Vec<usize>), DesignError> {
    let error = |reason: &str| DesignError::Generator {
        generator: text.into(),
        reason: reason.into(),
    };
    let (name, word) = text
        .split_once('=')
        .ok_or_else(|| error("expected NEW=WORD, e.g. D=AB"))?;
    if name.trim().is_empty() {
        return Err(error("no name before '=': expected NEW=WORD, e.g. D=AB"));
    }
    if base.iter().any(|b| b == name.trim()) {
        return Err(error(
            "it generates a base factor: name a factor of its own",
        ));
    }
    let word = word.trim();
    let (sign, word) = match word.strip_prefix('-') {
        Some(rest) => (-1.0, rest),
        None => (1.0, word.trim_start_matches('+')),
    };
    let letters = word
        .chars()
        .map(|c| {
            base.iter()
                .position(|b| b == &c.to_string())
                .ok_or_else(|| error(&format!("'{c}' is not a base factor ({})", base.join(", "))))
        })
        .collect::<Result<Vec<_>, _>>()?;
    if letters.len() < 2 {
        return Err(error("the word needs at least two base factors"));
    }
    Ok((name.trim().to_string(), sign, letters))
}

/// Fractional factorial from base factor names and generators, e.g.
/// `["A", "B", "C", "D=AB"]`: a full factorial in the base factors, the
/// generated columns as signed products.
pub fn fractional_factorial(columns: &[&str]) -> Result<Design, DesignError> {
    let base: Vec<String> = columns
        .iter()
        .filter(|c| !c.contains('='))
        .map(|c| c.trim().to_string())
        .collect();
    let names: Vec<&str> = base.iter().map(String::as_str).collect();
    let full = full_factorial(&names, 0)?;
    let generators = columns
        .iter()
        .filter(|c| c.contains('='))
        .map(|g| parse_generator(g, &base))
        .collect::<Result<Vec<_>, _>>()?;
    for (k, (name, _, _)) in generators.iter().enumerate() {
        if let Some(j) = generators[..k].iter().position(|g| &g.0 == name) {
            let texts: Vec<&&str> = columns.iter().filter(|c| c.contains('=')).collect();
            return Err(DesignError::Generator {
                generator: texts[k].to_string(),
                reason: format!(
                    "factor '{name}' is generated again (first by '{}'): give each generated factor one generator",
                    texts[j]
                ),
            });
        }
    }
    let mut factors = base.clone();
    factors.extend(generators.iter().map(|g| g.0.clone()));
    distinct_names(&factors.iter().map(String::as_str).collect::<Vec<_>>())?;
    let runs =
        full.runs
            .iter()
            .map(|r| {
                let mut row = r.clone();
                row.extend(generators.iter().map(|(_, sign, letters)| {
                    sign * letters.iter().map(|&l| r[l]).product::<f64>()
                }));
                row
            })
            .collect();
    Ok(Design { factors, runs })
}

/// The resolution of the fraction defined by `generators` (`D=AB`, ...):
/// the shortest word in the defining relation, built from every product of
/// the generator words `I = D·AB = ...`. Base factors are the letters
/// appearing on the right-hand sides.
pub fn resolution(generators: &[&str]) -> Result<usize, DesignError> {
    let mut letters: Vec<String> = Vec::new();
    for g in generators {
        let (name, word) = g.split_once('=').ok_or_else(|| DesignError::Generator {
            generator: g.to_string(),
            reason: "expected NEW=WORD".into(),
        })?;
        for c in word
            .trim()
            .trim_start_matches(['-', '+'])
            .chars()
            .map(|c| c.to_string())
            .chain(std::iter::once(name.trim().to_string()))
        {
            if !letters.contains(&c) {
                letters.push(c);
            }
        }
    }
    let words: Vec<u64> = generators
        .iter()
        .map(|g| {
            let (name, word) = g.split_once('=').unwrap_or((g, ""));
            let mut bits = 1u64 << letters.iter().position(|l| l == name.trim()).unwrap_or(0);
            for c in word.trim().trim_start_matches(['-', '+']).chars() {
                bits ^= 1u64
                    << letters
                        .iter()
                        .position(|l| *l == c.to_string())
                        .unwrap_or(0);
            }
            bits
        })
        .collect();
    if words.is_empty() {
        return Err(DesignError::Size(
            "a full factorial has no defining relation (resolution is unlimited)".into(),
        ));
    }
    let shortest = (1u64..1 << words.len())
        .map(|subset| {
            words
                .iter()
                .enumerate()
                .filter(|(i, _)| subset >> i & 1 == 1)
                .fold(0u64, |acc, (_, w)| acc ^ w)
                .count_ones() as usize
        })
        .min()
        .unwrap_or(0);
    Ok(shortest)
}

/// Central composite design: the 2^k factorial, 2k axial points at ±α,
/// and `centre` centre points. `face_centred` uses α = 1; otherwise the
/// circumscribed, rotatable α = (2^k)^(1/4).
pub fn central_composite(
    factors: &[&str],
    centre: usize,
    face_centred: bool,
) -> Result<Design, DesignError> {
    check_centre(centre)?;
    let mut design = full_factorial(factors, 0)?;
    let k = factors.len();
    let alpha = if face_centred {
        1.0
    } else {
        ((1u64 << k) as f64).powf(0.25)
    };
    for j in 0..k {
        for sign in [-1.0, 1.0] {
            let mut row = vec![0.0; k];
            row[j] = sign * alpha;
            design.runs.push(row);
        }
    }
    design.runs.extend((0..centre).map(|_| vec![0.0; k]));
    Ok(design)
}

fn unit(rng: &mut ChaCha8Rng) -> f64 {
    (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64
}

/// Latin hypercube of `n` runs on [−1, 1]^k: each factor's range is cut
/// into n equal strata, one run in each, strata shuffled per factor.
#[allow(clippy::needless_range_loop)] // runs[i][j]: run i, factor j
pub fn latin_hypercube(factors: &[&str], n: usize, seed: u64) -> Design {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let k = factors.len();
    let mut runs = vec![vec![0.0; k]; n];
    for j in 0..k {
        let mut strata: Vec<usize> = (0..n).collect();
        for i in (1..n).rev() {
            strata.swap(i, (unit(&mut rng) * (i + 1) as f64) as usize);
        }
        for (i, &s) in strata.iter().enumerate() {
            runs[i][j] = -1.0 + 2.0 * (s as f64 + unit(&mut rng)) / n as f64;
        }
    }
    Design {
        factors: factors.iter().map(|s| s.to_string()).collect(),
        runs,
    }
}

/// `n` uniform random runs on [−1, 1]^k.
pub fn uniform(factors: &[&str], n: usize, seed: u64) -> Design {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let runs = (0..n)
        .map(|_| {
            factors
                .iter()
                .map(|_| -1.0 + 2.0 * unit(&mut rng))
                .collect()
        })
        .collect();
    Design {
        factors: factors.iter().map(|s| s.to_string()).collect(),
        runs,
    }
}

/// A random run order (Fisher–Yates from the seed), as indices.
pub fn run_order(n: usize, seed: u64) -> Vec<usize> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut order: Vec<usize> = (0..n).collect();
    for i in (1..n).rev() {
        order.swap(i, (unit(&mut rng) * (i + 1) as f64) as usize);
    }
    order
}

/// The kinds of design [`make`] builds, by their command-line names.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DesignKind {
    /// `full`: two-level full factorial.
    Full,
    /// `fractional`: 2^(k−p) from generators.
    Fractional,
    /// `ccf`: face-centred central composite.
    CompositeFaceCentred,
    /// `ccc`: circumscribed (rotatable) central composite.
    CompositeCircumscribed,
    /// `lhs`: Latin hypercube.
    LatinHypercube,
    /// `uniform`: uniform random runs.
    Uniform,
}

/// A design name that is none of the kinds.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("design '{0}': expected full, fractional, ccf, ccc, lhs or uniform")]
pub struct DesignKindError(pub String);

impl FromStr for DesignKind {
    type Err = DesignKindError;

    fn from_str(text: &str) -> Result<DesignKind, DesignKindError> {
        Ok(match text {
            "full" => DesignKind::Full,
            "fractional" => DesignKind::Fractional,
            "ccf" => DesignKind::CompositeFaceCentred,
            "ccc" => DesignKind::CompositeCircumscribed,
            "lhs" => DesignKind::LatinHypercube,
            "uniform" => DesignKind::Uniform,
            other => return Err(DesignKindError(other.into())),
        })
    }
}

/// What a design needs besides its kind and factors.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct DesignOptions {
    /// Generators of a fraction (`D=AB`), naming factors by name.
    pub generators: Vec<String>,
    /// Centre points (factorial and composite designs).
    pub centre: usize,
    /// Runs of a Latin hypercube or uniform design.
    pub runs: usize,
    /// Seed of the random designs and of the run order.
    pub seed: u64,
}

/// Builds a design of `kind` over `names`; a fraction also returns its
/// resolution. The generated factors of a fraction keep their place
/// after the base factors.
///
/// ```
/// use bumpsim_doe::design::{DesignKind, DesignOptions, make};
/// let options = DesignOptions { generators: vec!["C=AB".into()], ..Default::default() };
/// let (d, resolution) = make(DesignKind::Fractional, &["A", "B", "C"], &options).unwrap();
/// assert_eq!((d.runs.len(), resolution), (4, Some(3)));
/// ```
pub fn make(
    kind: DesignKind,
    names: &[&str],
    options: &DesignOptions,
) -> Result<(Design, Option<usize>), DesignError> {
    let (centre, runs, seed) = (options.centre, options.runs, options.seed);
    check_options(kind, names, options)?;
    Ok(match kind {
        DesignKind::Full => (full_factorial(names, centre)?, None),
        DesignKind::Fractional => {
            let (design, resolution) = fraction(names, &options.generators)?;
            (design, Some(resolution))
        }
        DesignKind::CompositeFaceCentred => (central_composite(names, centre, true)?, None),
        DesignKind::CompositeCircumscribed => (central_composite(names, centre, false)?, None),
        DesignKind::LatinHypercube => (latin_hypercube(names, runs, seed), None),
        DesignKind::Uniform => (uniform(names, runs, seed), None),
    })
}

/// Refuses options the kind would ignore (generators outside a fraction,
/// no generators for one, centre points of a random design, no runs for
/// one), and factor names given twice.
fn check_options(
    kind: DesignKind,
    names: &[&str],
    options: &DesignOptions,
) -> Result<(), DesignError> {
    let random = matches!(kind, DesignKind::LatinHypercube | DesignKind::Uniform);
    let size = |why: &str| Err(DesignError::Size(why.into()));
    match kind {
        DesignKind::Fractional if options.generators.is_empty() => {
            size("a fraction needs generators (e.g. D=AB)")
        }
        DesignKind::Fractional => Ok(()),
        _ if !options.generators.is_empty() => {
            size("generators make a fractional design only: leave them out or make it 'fractional'")
        }
        _ if random && options.centre > 0 => {
            size("centre points belong to factorial and composite designs, not to lhs or uniform")
        }
        _ if random && options.runs == 0 => size("an lhs or uniform design needs at least one run"),
        _ => Ok(()),
    }?;
    distinct_names(names)
}

/// Refuses a factor name that is empty or given twice.
fn distinct_names(names: &[&str]) -> Result<(), DesignError> {
    for (i, name) in names.iter().enumerate() {
        if name.trim().is_empty() {
            return Err(DesignError::Size(format!(
                "factor {}: an empty name",
                i + 1
            )));
        }
        if names[..i].iter().any(|n| n.trim() == name.trim()) {
            return Err(DesignError::Size(format!("factor '{name}' is given twice")));
        }
    }
    Ok(())
}

/// The fraction whose generated factors are given by `generators`, and its
/// resolution.
fn fraction(names: &[&str], generators: &[String]) -> Result<(Design, usize), DesignError> {
    if let Some(g) = generators.iter().find(|g| {
        let name = g.split_once('=').map_or("", |(n, _)| n.trim());
        !names.iter().any(|n| n.trim() == name)
    }) {
        return Err(DesignError::Generator {
            generator: g.clone(),
            reason: format!(
                "it generates no factor of the design ({})",
                names.join(", ")
            ),
        });
    }
    let generated = |n: &&str| {
        generators.iter().any(|g| {
            g.split_once('=')
                .is_some_and(|(name, _)| name.trim() == n.trim())
        })
    };
    let mut columns: Vec<&str> = names.iter().copied().filter(|n| !generated(n)).collect();
    columns.extend(generators.iter().map(String::as_str));
    let words: Vec<&str> = generators.iter().map(String::as_str).collect();
    Ok((fractional_factorial(&columns)?, resolution(&words)?))
}

impl Design {
    /// The design as CSV: run number, standard order, the physical levels
    /// (from `factors` by name; a factor not found stays coded) and the
    /// coded levels, one row per run in `order` (indices into the runs).
    pub fn to_csv(&self, factors: &[Factor], order: &[usize]) -> String {
        let by_name = |n: &String| factors.iter().find(|f| &f.name == n);
        let mut csv = String::from("run,standard order");
        self.factors.iter().for_each(|f| csv += &format!(",{f}"));
        self.factors
            .iter()
            .for_each(|f| csv += &format!(",{f} (coded)"));
        csv.push('\n');
        for (run, &i) in order.iter().enumerate() {
            let row = &self.runs[i];
            csv += &format!("{},{}", run + 1, i + 1);
            for (f, z) in self.factors.iter().zip(row) {
                csv += &format!(",{}", by_name(f).map_or(*z, |f| f.physical(*z)));
            }
            row.iter().for_each(|z| csv += &format!(",{z}"));
            csv.push('\n');
        }
        csv
    }

    /// Refuses a run whose physical level of a factor (from `factors` by
    /// name) is not a finite number: a composite design's axial points lie
    /// beyond the factor's range, and `A:1e308:1.7e308` wrote `inf`.
    pub fn check_levels(&self, factors: &[Factor]) -> Result<(), DesignError> {
        for row in &self.runs {
            for (name, z) in self.factors.iter().zip(row) {
                let Some(factor) = factors.iter().find(|f| &f.name == name) else {
                    continue;
                };
                let level = factor.physical(*z);
                if !level.is_finite() {
                    return Err(DesignError::Size(format!(
                        "factor '{name}': the level at coded {z:.4} is {level}, not a finite number: give a range of smaller numbers"
                    )));
                }
            }
        }
        Ok(())
    }

    /// The run order: random from `seed` when `randomise`, else standard.
    pub fn order(&self, randomise: bool, seed: u64) -> Vec<usize> {
        match randomise {
            true => run_order(self.runs.len(), seed),
            false => (0..self.runs.len()).collect(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn resolutions_of_known_fractions() {
        assert_eq!(resolution(&["D=ABC"]).unwrap(), 4);
        assert_eq!(resolution(&["E=ABCD"]).unwrap(), 5);
        assert_eq!(resolution(&["D=AB", "E=AC"]).unwrap(), 3);
        assert_eq!(resolution(&["E=ABC", "F=BCD"]).unwrap(), 4);
        assert!(resolution(&[]).is_err());
    }

    #[test]
    fn composite_designs_refuse_too_many_centre_points() {
        for face_centred in [true, false] {
            let err = central_composite(&["A"], MAX_CENTRE + 1, face_centred).unwrap_err();
            assert_eq!(
                err,
                DesignError::Centre {
                    centre: MAX_CENTRE + 1
                }
            );
        }
        assert!(central_composite(&["A"], 2, true).is_ok());
    }

    #[test]
    fn composite_and_space_filling() {
        let ccd = central_composite(&["A", "B"], 3, false).unwrap();
        assert_eq!(ccd.runs.len(), 4 + 4 + 3);
        assert!((ccd.runs[4][0] + 2f64.sqrt()).abs() < 1e-12);
        let lhs = latin_hypercube(&["A", "B"], 10, 3);
        for j in 0..2 {
            let mut strata: Vec<usize> = lhs
                .runs
                .iter()
                .map(|r| ((r[j] + 1.0) / 2.0 * 10.0) as usize)
                .collect();
            strata.sort();
            assert_eq!(strata, (0..10).collect::<Vec<_>>(), "one run per stratum");
        }
        assert_eq!(latin_hypercube(&["A"], 5, 9), latin_hypercube(&["A"], 5, 9));
        assert!(fractional_factorial(&["A", "B", "C=AX"]).is_err());
    }
}
