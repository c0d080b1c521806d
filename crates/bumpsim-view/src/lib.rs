//! bumpsim-view: look at crash tests, models and verdicts in the browser.
//!
//! `bumpsim view PATH...` opens tests (ISO-MME folder, `.mme`, `.zip`;
//! NHTSA EV5; CSV) and bumpsim result JSONs in a local, read-only server
//! ([`server`]) or writes them as one self-contained page
//! ([`server::standalone`]). Everything the page shows is computed here,
//! by the library's own code: the readers (bumpsim-io), the processing
//! (bumpsim-signal: CFC, bias, scale, integration, derivative, sums and
//! means), the pulse metrics (bumpsim-verdict: peak, 3 ms clip, ΔV, OLC,
//! ASI), min/max decimation and cursor readouts ([`plot`]); the page's
//! script only draws (uPlot) and asks.
//!
//! - [`session`]: the opened inputs and the processed signals;
//! - [`query`]: a request's parameters, checked;
//! - [`plot`]: decimation, readouts, pulse metrics;
//! - [`decode`]: ISO/TS 13499 and NHTSA channel codes in words;
//! - [`results`]: result JSONs (fit %, ISO/TS 18571 ratings);
//! - [`curves`]: an identification's model against its study's tests;
//! - [`planar_view`]: a planar result's top view over time;
//! - [`api`]: the JSON answers; [`page`]: the page and its assets;
//! - [`server`]: the token-guarded server on 127.0.0.1;
//! - [`error`]: the error type, [`ViewError`].
//!
//! ```
//! use bumpsim_view::query::Query;
//! let q = Query::parse("sel=0:12&cfc=60&bias=1&t0=0&t1=0.005&px=800").unwrap();
//! assert_eq!(q.processing.steps().len(), 2);
//! assert!(Query::parse("t0=NaN&t1=1").is_err());
//! ```

pub mod api;
pub mod curves;
pub mod decode;
pub mod error;
pub mod page;
pub mod planar_view;
pub mod plot;
pub mod query;
pub mod results;
pub mod server;
pub mod session;

pub use error::ViewError;
pub use server::Viewer;
pub use session::Session;
