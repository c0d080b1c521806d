//! Processing steps on channels, composable into a pipeline (spec §4).
//!
//! Each [`Step`] maps a [`Channel`] to a new channel with the same
//! identity: filters ([`filter`](crate::filter)), bias removal (subtract
//! the mean over a pre-trigger interval, by default every sample before
//! t = 0), scaling and sign, trapezoidal integration and differentiation
//! ([`integrate`](crate::integrate), which also change the dimension:
//! acceleration ↔ velocity ↔ displacement, and the angular ones),
//! trimming, time shift, linear resampling, and force from a rigid mass
//! times its acceleration (`F = m a`, spec §4). [`combine`] forms the mean
//! or sum of channels (left and right side members; the cells of a
//! load-cell wall) on their common time base.
//!
//! Steps keep an ISO/TS 13499 code true to the data (see
//! [`Channel::filtered`]): CFC sets the filter-class letter and `Channel
//! frequency class`, integration and derivation the dimension letters
//! (`AC` → `VE` → `DS`), F = m a `FO`, and a negative scale notes the sign
//! change in `Comments`.
//!
//! [`Channel`]: bumpsim_core::channel::Channel
//! [`Channel::filtered`]: bumpsim_core::channel::Channel::filtered
//!
//! In TOML a pipeline is a list of one-key tables, e.g.
//! `steps = [{ cfc = 60 }, { bias = [-0.05, 0.0] }, { integrate = 15.86 }]`.
//!
//! ```
//! use bumpsim_core::prelude::*;
//! use bumpsim_signal::process::Step;
//! let a = UniformSeries::new(0.0, 0.001, vec![-9.81; 1001]).unwrap();
//! let ch = Channel::new("ACX", "decel", Dimension::Acceleration, a);
//! let v = Step::Integrate(5.0).apply(&ch).unwrap();
//! assert_eq!(v.dimension, Dimension::Velocity);
//! assert!((v.series.values()[1000] - (5.0 - 9.81)).abs() < 1e-9);
//! ```
//!
//! The parts: the steps (`steps`), several channels on one time base
//! (`time_base`) and [`ProcessError`] (`error`).

mod error;
mod steps;
mod time_base;

#[cfg(test)]
mod tests;

pub use error::ProcessError;
pub use steps::{ButterworthStep, Step, frequency_class, notes, run};
pub use time_base::{Combine, Resampling, align, combine, interpolate, resampling};
