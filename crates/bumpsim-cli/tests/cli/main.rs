//! Runs the real `bumpsim` binary on the bundled example and on malformed
//! inputs written here, and checks exit codes and messages.
//!
//! One test binary (ripgrep's layout): one module per command (`campaign`:
//! local and real-Slurm campaigns), plus
//! `docs` (the runnable blocks of README.md and docs/*.md), `reports` (four
//! HTML reports read in Chromium),
//! `planar` (the planar car), `formats` (ISO-MME and EV5 through the commands, pyisomme), `robustness`
//! (hostile inputs, kills mid-write) and `fuzz` (the readers under mutated
//! inputs; `BUMPSIM_FUZZ_SECONDS` per target).

mod campaign;
mod docs;
mod doe;
mod export;
mod fe;
mod formats;
mod formats_letter;
mod fuzz;
mod identify;
mod identify_links;
mod impact;
mod impact_links;
mod issue48;
mod links_series;
mod planar;
mod planar_coverage;
mod planar_identify;
mod presets;
mod recorded;
mod reports;
mod reports_answer;
mod robustness;
mod signal;
mod simulate;
mod util;
mod verdict;
mod view;
