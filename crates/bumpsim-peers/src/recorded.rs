//! Recorded outputs: a regression check that a refactoring leaves results
//! as they were (issue 31: impact and planar outputs within 1e-9 of peak of
//! the previous commit's).
//!
//! A [`Recording`] collects named histories (decimated: every n-th sample
//! and the last, with the sample count; [`Recording::every`]) and
//! scalars. [`Recording::check`] compares it with a file written by an
//! earlier commit: histories must have the same count and every kept
//! sample within [`TOLERANCE`] of the channel's recorded peak; scalars
//! within [`TOLERANCE`] of their recorded magnitude. With the environment
//! variable [`RECORD`] set, it writes the file instead (once, on the commit
//! whose outputs are the reference). The file is plain text, one channel a
//! line, each number in Rust's shortest round-trip form (read back exact).
//!
//! ```
//! use bumpsim_peers::recorded::Recording;
//! let mut r = Recording::default();
//! r.history("x", &[0.0, 1.0, 2.0]);
//! r.scalar("peak", 2.0);
//! let text = r.to_text();
//! assert_eq!(Recording::parse(&text).unwrap().to_text(), text);
//! assert!(r.differences(&r).is_empty());
//! ```

use std::path::Path;

/// The environment variable that makes [`Recording::check`] write the file.
pub const RECORD: &str = "BUMPSIM_RECORD";

/// Largest difference allowed, relative to the channel's recorded peak.
pub const TOLERANCE: f64 = 1e-9;

/// A line of a recording that is not `name<TAB>count<TAB>values` (1-based).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BadLine(pub usize);

impl std::fmt::Display for BadLine {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "line {}: expected name, sample count and values", self.0)
    }
}

impl std::error::Error for BadLine {}

/// Named channels: `(name, sample count, kept values)`; a scalar has count 0.
#[derive(Debug, Clone, PartialEq)]
pub struct Recording {
    channels: Vec<(String, usize, Vec<f64>)>,
    every: usize,
}

impl Default for Recording {
    fn default() -> Self {
        Recording::every(7)
    }
}

impl Recording {
    /// An empty recording that keeps every `n`-th sample of a history (and
    /// its last); the default keeps every 7th.
    pub fn every(n: usize) -> Recording {
        Recording {
            channels: Vec::new(),
            every: n.max(1),
        }
    }

    /// Adds a history (decimated).
    pub fn history(&mut self, name: &str, values: &[f64]) {
        let mut kept: Vec<f64> = values.iter().step_by(self.every).copied().collect();
        if values.len() > 1 && !(values.len() - 1).is_multiple_of(self.every) {
            kept.extend(values.last());
        }
        self.channels.push((name.into(), values.len(), kept));
    }

    /// Adds a scalar.
    pub fn scalar(&mut self, name: &str, value: f64) {
        self.channels.push((name.into(), 0, vec![value]));
    }

    /// The file's text.
    pub fn to_text(&self) -> String {
        let line = |(name, count, values): &(String, usize, Vec<f64>)| {
            let numbers: Vec<String> = values.iter().map(|v| format!("{v:e}")).collect();
            format!("{name}\t{count}\t{}\n", numbers.join(" "))
        };
        self.channels.iter().map(line).collect()
    }

    /// Reads a file's text; the error names the first line that is not a channel.
    pub fn parse(text: &str) -> Result<Recording, BadLine> {
        let mut channels = Vec::new();
        for (n, line) in text.lines().enumerate() {
            let mut parts = line.split('\t');
            let bad = BadLine(n + 1);
            let (Some(name), Some(count), Some(values)) =
                (parts.next(), parts.next(), parts.next())
            else {
                return Err(bad);
            };
            let count = count.parse().map_err(|_| bad)?;
            let values = values
                .split(' ')
                .map(str::parse)
                .collect::<Result<Vec<f64>, _>>()
                .map_err(|_| bad)?;
            channels.push((name.to_string(), count, values));
        }
        Ok(Recording { channels, every: 1 })
    }

    /// What differs from `reference` beyond [`TOLERANCE`], a line each.
    pub fn differences(&self, reference: &Recording) -> Vec<String> {
        let mut out = Vec::new();
        if self.channels.len() != reference.channels.len() {
            out.push(format!(
                "{} channels, recorded {}",
                self.channels.len(),
                reference.channels.len()
            ));
        }
        for ((name, count, values), (r_name, r_count, r_values)) in
            self.channels.iter().zip(&reference.channels)
        {
            if name != r_name || count != r_count || values.len() != r_values.len() {
                out.push(format!(
                    "{name} ({count} samples): recorded {r_name} ({r_count})"
                ));
                continue;
            }
            let peak = r_values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let worst = values
                .iter()
                .zip(r_values)
                .map(|(a, b)| (a - b).abs())
                .fold(
                    0.0f64,
                    |m, d| if d.is_nan() { f64::INFINITY } else { m.max(d) },
                );
            if worst > TOLERANCE * peak {
                out.push(format!("{name}: differs by {worst:e}, peak {peak:e}"));
            }
        }
        out
    }

    /// Compares with the recording at `path`, panicking with every
    /// difference; writes it instead when [`RECORD`] is set.
    pub fn check(&self, path: &Path) {
        if std::env::var_os(RECORD).is_some() {
            std::fs::write(path, self.to_text()).expect("write the recording");
            eprintln!("recorded {}", path.display());
            return;
        }
        let text = std::fs::read_to_string(path)
            .unwrap_or_else(|e| panic!("{}: {e} (record it with {RECORD}=1)", path.display()));
        let reference =
            Recording::parse(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let differences = self.differences(&reference);
        assert!(
            differences.is_empty(),
            "{} differs from the recorded outputs:\n{}",
            path.display(),
            differences.join("\n")
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_change_beyond_the_tolerance_is_found_and_one_within_is_not() {
        let mut a = Recording::default();
        a.history("x", &[0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0]);
        a.scalar("s", 3.0);
        let mut within = Recording::default();
        within.history("x", &[0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0 + 1e-10]);
        within.scalar("s", 3.0);
        assert!(within.differences(&a).is_empty());
        let mut beyond = Recording::default();
        beyond.history(
            "x",
            &[0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0 + 1.0, 8.0 + 1e-7],
        );
        beyond.scalar("s", f64::NAN);
        let found = beyond.differences(&a);
        assert_eq!(found.len(), 2, "{found:?}");
        let mut shorter = Recording::default();
        shorter.history("x", &[0.0, 1.0]);
        shorter.scalar("s", 3.0);
        assert_eq!(shorter.differences(&a).len(), 1);
    }
}
