//! Moved: `bumpsim export planar` is now `crate::export::planar`, a
//! submodule only `export` calls (issue 31: no module circle). This file
//! stays empty until `mod export_planar;` leaves main.rs.
