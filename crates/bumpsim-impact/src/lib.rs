//! bumpsim-impact: concept studies without an FE code (papers A, B; spec §5–6).
//!
//! - [`bumper`]: three-part and tabulated bumper characteristics with elastic unloading;
//! - [`impact`]: impactor or barrier impacts on MSD cars by central differences;
//! - [`presets`]: named load cases with their sources;
//! - [`reduction`]: the reduced point mass of paper A and its sweeps;
//! - [`synth`]: synthetic pendulum test series with a measurement chain;
//! - [`text`]: summaries and CSV of results.

pub mod bumper;
pub mod impact;
pub mod presets;
pub mod reduction;
pub mod synth;
pub mod text;
