//! A side chain of the planar car file: `masses`, `dampers` and either
//! `springs` (linear) or one `[[left.links]]` / `[[right.links]]` table per
//! mass, in the 1-D links car's form ([`bumpsim_io::link_car`],
//! docs/formats.md): `curve` (linear, progressive, bilinear, table) with its
//! keys and `unloading` ("elastic" or a slope). Errors name the file, the
//! side, the link and the key (`car.toml: left: link 2: yield_force: ...`).

use super::ChainFile;
use crate::car::{PlanarError, SideChain};
use std::path::Path;

/// The side chain `side` (`left`, `right`) of a file; `error` names the file.
pub(super) fn side_chain(
    side: &str,
    c: ChainFile,
    error: &dyn Fn(String) -> PlanarError,
) -> Result<SideChain, PlanarError> {
    if c.links.is_empty() {
        return Ok(SideChain {
            masses: c.masses,
            dampers: c.dampers,
            springs: c.springs,
            links: Vec::new(),
        });
    }
    if !c.springs.is_empty() {
        return Err(error(format!(
            "{side}.springs: a side chain with [[{side}.links]] gives every spring there (each link's curve), not in springs"
        )));
    }
    let most = bumpsim_core::model::MAX_DOF;
    if c.links.len() > most {
        return Err(error(format!(
            "{side}.links: {} links: at most {most} a side (MAX_DOF, docs/limits.md)",
            c.links.len()
        )));
    }
    let links = c
        .links
        .iter()
        .enumerate()
        .map(|(j, v)| bumpsim_io::link_car::link(Path::new(side), format!("link {}", j + 1), v))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| error(e.to_string()))?;
    Ok(SideChain::linked(c.masses, c.dampers, links))
}

/// The `[side]` table of `chain` (SI), which [`side_chain`] reads back.
pub(super) fn side_toml(side: &str, chain: &SideChain) -> String {
    let head = format!(
        "\n[{side}]\nmasses = {:?}    # kg\ndampers = {:?}    # N·s/m\n",
        chain.masses, chain.dampers
    );
    if chain.links.is_empty() {
        return head + &format!("springs = {:?}    # N/m\n", chain.springs);
    }
    let links: Vec<String> = chain
        .links
        .iter()
        .map(|l| format!("  {},\n", bumpsim_io::link_car::link_toml(l)))
        .collect();
    head + &format!(
        "links = [    # front to back, SI (docs/formats.md)\n{}]\n",
        links.concat()
    )
}
