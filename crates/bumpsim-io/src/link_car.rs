//! Car files of a chain with nonlinear links ([`bumpsim_core::chain`],
//! [`bumpsim_core::link`]; issue 46): the linear car file's `masses` and
//! `dampers`, and instead of `springs` one `[[links]]` table per link j
//! (between mass j and j+1), optionally a `[front]` link (the crush zone
//! between the barrier and m1). docs/formats.md has the full form.
//!
//! Each link gives its loading curve `F_L(δ)` (δ > 0 in compression):
//!
//! | `curve` | keys | curve |
//! |---|---|---|
//! | `linear` | `stiffness` | `k δ` |
//! | `progressive` | `stiffness`, `limit`, `limit_force` | `k δ + k3 δ³` to δ_lim, `k3 = (F_lim − k δ_lim)/δ_lim³` |
//! | `bilinear` | `stiffness`, `yield_force`, `hardening` (0..=1, default 0) | `k δ` to F_y, then slope `r k` |
//! | `table` | `points = [[δ, F], ...]` | piecewise linear from (0, 0) |
//!
//! and `unloading = "elastic"` (default: back along the curve) or an
//! unloading slope (`"2000 N/mm"`). Quantities are numbers in SI or text
//! with a unit (`"1500 N/mm"`, `"80 kN"`, `"200 mm"`), converted to SI on
//! reading. Unknown keys are errors; every error names the file, the link
//! (`link 2`, `front link`) and the key.
//!
//! ```
//! use bumpsim_io::link_car::LinkCar;
//! let text = "masses = [2.0, 900.0]\ndampers = [0.0]\n[[links]]\ncurve = \"bilinear\"\n\
//!             stiffness = \"1000 N/mm\"\nyield_force = \"50 kN\"\nunloading = \"2000 N/mm\"\n";
//! let car = LinkCar::parse(text, "car.toml".as_ref()).unwrap();
//! assert_eq!(car.chain.dof(), 2);
//! let bad = text.replace("50 kN", "-50 kN");
//! let err = LinkCar::parse(&bad, "car.toml".as_ref()).unwrap_err().to_string();
//! assert!(err.starts_with("car.toml: link 1: yield_force"), "{err}");
//! ```

use crate::car::CarError;
pub use crate::car::has_links;
use bumpsim_core::chain::Chain;
use bumpsim_core::link::{Curve, Link, Unloading};
use bumpsim_core::units::{Dimension, parse_quantity};
use std::path::Path;
use toml::{Table, Value};

/// A car whose links are nonlinear.
#[derive(Debug, Clone, PartialEq)]
pub struct LinkCar {
    /// Optional name from the file.
    pub name: Option<String>,
    /// The validated chain (with its front link, if the file has one).
    pub chain: Chain,
}

/// Where an error is: the link's name and the key.
struct At<'a> {
    path: &'a Path,
    link: String,
}

impl At<'_> {
    fn error(&self, key: &str, reason: impl Into<String>) -> CarError {
        CarError::LinkKey {
            path: self.path.into(),
            link: self.link.clone(),
            key: key.into(),
            reason: reason.into(),
        }
    }

    /// A quantity: a finite number (SI) or text with a unit of `dimension`.
    fn quantity(&self, table: &Table, key: &str, dimension: Dimension) -> Result<f64, CarError> {
        let value = table.get(key).ok_or_else(|| self.error(key, "missing"))?;
        self.value(value, key, dimension)
    }

    fn value(&self, value: &Value, key: &str, dimension: Dimension) -> Result<f64, CarError> {
        let number = match value {
            Value::Float(v) => *v,
            Value::Integer(v) => *v as f64,
            Value::String(s) => {
                return parse_quantity(s, dimension).map_err(|e| self.error(key, e.to_string()));
            }
            other => {
                return Err(self.error(
                    key,
                    format!("{other}: expected a number or text with a unit"),
                ));
            }
        };
        match number.is_finite() {
            true => Ok(number),
            false => Err(self.error(key, format!("{number} is not a finite number"))),
        }
    }
}

fn unit_of(value: &Value) -> Option<String> {
    value.as_str().map(str::to_string)
}

/// The keys each curve allows (besides `curve` and `unloading`).
fn allowed(curve: &str) -> Option<&'static [&'static str]> {
    Some(match curve {
        "linear" => &["stiffness"],
        "progressive" => &["stiffness", "limit", "limit_force"],
        "bilinear" => &["stiffness", "yield_force", "hardening"],
        "table" => &["points"],
        _ => return None,
    })
}

fn curve(at: &At<'_>, table: &Table) -> Result<Curve, CarError> {
    let name = table
        .get("curve")
        .and_then(Value::as_str)
        .ok_or_else(|| at.error("curve", "missing: linear, progressive, bilinear or table"))?;
    let keys = allowed(name).ok_or_else(|| {
        at.error(
            "curve",
            format!("{name:?} is not a curve (linear, progressive, bilinear, table)"),
        )
    })?;
    if let Some(key) = table
        .keys()
        .find(|k| !keys.contains(&k.as_str()) && !["curve", "unloading"].contains(&k.as_str()))
    {
        return Err(at.error(
            key,
            format!(
                "unknown key for curve = {name:?} (allowed: {})",
                keys.join(", ")
            ),
        ));
    }
    let link = |source| CarError::Link {
        path: at.path.into(),
        link: at.link.clone(),
        source,
    };
    let k = || at.quantity(table, "stiffness", Dimension::Stiffness);
    match name {
        "linear" => Curve::linear(k()?).map_err(link),
        "progressive" => {
            let (k, limit) = (k()?, at.quantity(table, "limit", Dimension::Length)?);
            let top = at.quantity(table, "limit_force", Dimension::Force)?;
            // a negative limit was refused as a limit_force below a
            // negative product (the wrong key; round 5's hostile pass)
            if limit.is_nan() || limit <= 0.0 {
                let given = bumpsim_core::units::short(limit);
                return Err(at.error("limit", format!("{given} m: must be positive")));
            }
            if top.is_nan() || top < k * limit {
                return Err(at.error(
                    "limit_force",
                    format!(
                        "{top} N: must be at least stiffness × limit = {} N",
                        k * limit
                    ),
                ));
            }
            Curve::progressive(k, (top - k * limit) / limit.powi(3), limit).map_err(link)
        }
        "bilinear" => {
            let hardening = match table.get("hardening") {
                None => 0.0,
                Some(v) => at.value(v, "hardening", Dimension::Dimensionless)?,
            };
            let yield_force = at.quantity(table, "yield_force", Dimension::Force)?;
            Curve::bilinear(k()?, yield_force, hardening).map_err(link)
        }
        _ => Curve::table(points(at, table)?).map_err(link),
    }
}

fn points(at: &At<'_>, table: &Table) -> Result<Vec<[f64; 2]>, CarError> {
    let list = table
        .get("points")
        .and_then(Value::as_array)
        .ok_or_else(|| at.error("points", "missing: a list of [deformation, force] pairs"))?;
    // refused before a million pairs are converted (seconds) only to be refused
    let most = bumpsim_core::link::MAX_TABLE_POINTS;
    if list.len() > most {
        let count = list.len();
        return Err(at.error("points", format!("{count} points: at most {most}")));
    }
    let mut out = Vec::with_capacity(list.len());
    for (i, point) in list.iter().enumerate() {
        let key = format!("points[{}]", i + 1);
        let pair = match point.as_array().map(Vec::as_slice) {
            Some([d, f]) => [
                at.value(d, &key, Dimension::Length)?,
                at.value(f, &key, Dimension::Force)?,
            ],
            _ => return Err(at.error(&key, "expected a pair [deformation, force]")),
        };
        if let Some(before) = out
            .last()
            .map(|p: &[f64; 2]| p[0])
            .filter(|d| pair[0] <= *d)
        {
            return Err(at.error(
                &key,
                format!("deformation {} m after {before} m: must increase", pair[0]),
            ));
        }
        if pair[0] < 0.0 || pair[1] < 0.0 {
            return Err(at.error(&key, "deformation and force must not be negative"));
        }
        out.push(pair);
    }
    Ok(out)
}

fn unloading(at: &At<'_>, table: &Table) -> Result<Unloading, CarError> {
    match table.get("unloading") {
        None => Ok(Unloading::Elastic),
        Some(v) if unit_of(v).as_deref() == Some("elastic") => Ok(Unloading::Elastic),
        Some(v) => Ok(Unloading::Slope(at.value(
            v,
            "unloading",
            Dimension::Stiffness,
        )?)),
    }
}

/// One link's table (a `[[links]]` entry, a `[front]` table, or a planar
/// side member's `[[left.links]]`): errors name `path`, the link `name`
/// (`link 2`, `left link 1`) and the key.
pub fn link(path: &Path, name: String, value: &Value) -> Result<Link, CarError> {
    let at = At { path, link: name };
    let table = value.as_table().ok_or_else(|| {
        at.error(
            "",
            "expected a table of keys (curve = ..., stiffness = ...)",
        )
    })?;
    let curve = curve(&at, table)?;
    let unloading = unloading(&at, table)?;
    Link::new(curve, unloading).map_err(|source| CarError::Link {
        path: path.into(),
        link: at.link.clone(),
        source,
    })
}

/// `link` as a TOML inline table in SI that [`link`] reads back (a
/// progressive curve through its `limit_force`, so its cubic term comes
/// back to rounding).
pub fn link_toml(link: &Link) -> String {
    let curve = match link.curve() {
        Curve::Linear { stiffness } => format!("curve = \"linear\", stiffness = {stiffness:?}"),
        Curve::Progressive {
            stiffness, limit, ..
        } => format!(
            "curve = \"progressive\", stiffness = {stiffness:?}, limit = {limit:?}, limit_force = {:?}",
            link.curve().force(*limit)
        ),
        Curve::Bilinear {
            stiffness,
            yield_force,
            hardening,
        } => format!(
            "curve = \"bilinear\", stiffness = {stiffness:?}, yield_force = {yield_force:?}, hardening = {hardening:?}"
        ),
        Curve::Table { points } => {
            let points: Vec<String> = points
                .iter()
                .map(|p| format!("[{:?}, {:?}]", p[0], p[1]))
                .collect();
            format!("curve = \"table\", points = [{}]", points.join(", "))
        }
    };
    match link.unloading() {
        Unloading::Elastic => format!("{{ {curve}, unloading = \"elastic\" }}"),
        Unloading::Slope(k) => format!("{{ {curve}, unloading = {k:?} }}"),
    }
}

/// A list of quantities (`masses`, `dampers`).
fn list(path: &Path, table: &Table, key: &str, dimension: Dimension) -> Result<Vec<f64>, CarError> {
    let at = At {
        path,
        link: "car".into(),
    };
    match table.get(key) {
        None if key == "dampers" => Ok(Vec::new()),
        None => Err(at.error(key, "missing")),
        Some(Value::Array(values)) => values
            .iter()
            .enumerate()
            .map(|(i, v)| at.value(v, &format!("{key}[{}]", i + 1), dimension))
            .collect(),
        Some(other) => Err(at.error(key, format!("{other}: expected a list"))),
    }
}

impl LinkCar {
    /// Parses car TOML with nonlinear links; `path` is used in messages.
    pub fn parse(text: &str, path: &Path) -> Result<LinkCar, CarError> {
        let table: Table = toml::from_str(text).map_err(|e| CarError::Syntax {
            path: path.into(),
            message: crate::toml_message(text, &e),
        })?;
        Self::from_table(&table, path)
    }

    /// The car of a parsed file.
    pub fn from_table(table: &Table, path: &Path) -> Result<LinkCar, CarError> {
        let at = At {
            path,
            link: "car".into(),
        };
        // the verdict's limits ([damageability], lengths in its
        // length_unit) are read by `verdict`, docs/verdict.md
        let known = [
            "kind",
            "name",
            "masses",
            "dampers",
            "links",
            "front",
            "damageability",
            "length_unit",
            "path",
            "rebound",
        ];
        if let Some(key) = table.keys().find(|k| !known.contains(&k.as_str())) {
            let hint = if key == "springs" {
                " (a car with [[links]] gives every spring there)"
            } else {
                ""
            };
            return Err(at.error(key, format!("unknown key{hint}")));
        }
        let kinds = [Some("links"), Some("chain")];
        if let Some(kind) = table.get("kind").filter(|k| !kinds.contains(&k.as_str())) {
            return Err(at.error(
                "kind",
                format!("{kind}: a car with links is kind = \"links\" (or \"chain\", as before)"),
            ));
        }
        let name = match table.get("name") {
            None => None,
            Some(Value::String(s)) => Some(s.clone()),
            Some(other) => return Err(at.error("name", format!("{other}: expected text"))),
        };
        let masses = list(path, table, "masses", Dimension::Mass)?;
        let dampers = list(path, table, "dampers", Dimension::Damping)?;
        let links = match table.get("links") {
            None => Vec::new(),
            Some(Value::Array(items)) => items
                .iter()
                .enumerate()
                .map(|(j, v)| link(path, format!("link {}", j + 1), v))
                .collect::<Result<_, _>>()?,
            Some(_) => return Err(at.error("links", "expected [[links]] tables")),
        };
        let chain = Chain::new(masses, dampers, links).map_err(|source| CarError::Model {
            path: path.into(),
            source,
        })?;
        let mut chain = match table.get("front") {
            None => chain,
            Some(v) => chain.with_front(link(path, "front link".into(), v)?),
        };
        let model = |source| CarError::Model {
            path: path.into(),
            source,
        };
        if let Some(v) = table.get("path") {
            let (mass, gap, link) = wall_link(path, "second load path", v, chain.dof())?;
            chain = chain.with_path(mass, gap, link).map_err(model)?;
        }
        if let Some(v) = table.get("rebound") {
            let (mass, gap, link) = wall_link(path, "rebound link", v, chain.dof())?;
            chain = chain.with_rebound(mass, gap, link).map_err(model)?;
        }
        Ok(LinkCar { name, chain })
    }

    /// The car as a car file (`kind = "links"`, SI) that
    /// [`LinkCar::parse`] reads back to the same chain (numbers written
    /// in full precision).
    pub fn to_toml(&self) -> String {
        let c = &self.chain;
        let list = |v: &[f64]| {
            let items: Vec<String> = v.iter().map(|x| format!("{x:?}")).collect();
            format!("[{}]", items.join(", "))
        };
        let mut out = String::from("kind = \"links\"\n");
        if let Some(name) = &self.name {
            out += &format!("name = {}\n", Value::String(name.clone()));
        }
        out += &format!("masses = {}  # kg\n", list(c.masses()));
        out += &format!("dampers = {}  # N·s/m\n", list(c.dampers()));
        let entry = |link: &Link| {
            let inline = link_toml(link);
            inline[1..inline.len() - 1].trim().to_string()
        };
        for l in c.links() {
            out += &format!("\n[[links]]\n{}\n", keys(&entry(l)));
        }
        if let Some(front) = c.front() {
            out += &format!("\n[front]\n{}\n", keys(&entry(front)));
        }
        let walls = [("path", c.path()), ("rebound", c.rebound())];
        for (name, wall) in walls {
            if let Some(w) = wall {
                out += &format!(
                    "\n[{name}]\nmass = {}\ngap = {:?}  # m\n{}\n",
                    w.mass + 1,
                    w.gap,
                    keys(&entry(&w.link))
                );
            }
        }
        out
    }
}

/// An inline table's `a = 1, b = [..]` as one key per line (commas inside
/// brackets kept).
fn keys(inline: &str) -> String {
    let mut out = String::new();
    let mut depth = 0_i32;
    for ch in inline.chars() {
        match ch {
            '[' => depth += 1,
            ']' => depth -= 1,
            _ => {}
        }
        match (ch, depth) {
            (',', 0) => out.push('\n'),
            _ => out.push(ch),
        }
    }
    out.lines().map(str::trim).collect::<Vec<_>>().join("\n")
}

/// A wall link's table (`[path]`, `[rebound]`): `mass` (1-based, of a
/// chain of `dof`), `gap` (m, default 0) and the link's keys.
fn wall_link(
    path: &Path,
    name: &str,
    value: &Value,
    dof: usize,
) -> Result<(usize, f64, Link), CarError> {
    let at = At {
        path,
        link: name.into(),
    };
    let mut table = value
        .as_table()
        .cloned()
        .ok_or_else(|| at.error("", "expected a table (mass = ..., gap = ..., curve = ...)"))?;
    let mass = match table.remove("mass") {
        Some(Value::Integer(m)) if (1..=dof as i64).contains(&m) => m as usize - 1,
        Some(other) => {
            return Err(at.error(
                "mass",
                format!("{other}: expected the number of a mass of the chain, 1 to {dof}"),
            ));
        }
        None => return Err(at.error("mass", format!("missing: the mass it pushes, 1 to {dof}"))),
    };
    let gap = match table.remove("gap") {
        None => 0.0,
        Some(v) => at.value(&v, "gap", Dimension::Length)?,
    };
    if gap < 0.0 {
        return Err(at.error("gap", format!("{gap} m: must not be negative")));
    }
    let link = link(path, name.into(), &Value::Table(table))?;
    Ok((mass, gap, link))
}

/// A car file of the chain in either form.
#[derive(Debug, Clone, PartialEq)]
pub enum ChainCar {
    /// Linear springs (`springs = [...]`), read by [`crate::car::Car`].
    Linear(crate::car::Car),
    /// Nonlinear links (`[[links]]`, `[front]`).
    Links(LinkCar),
}

impl ChainCar {
    /// The car's name, if the file gives one.
    pub fn name(&self) -> Option<&str> {
        match self {
            ChainCar::Linear(car) => car.name.as_deref(),
            ChainCar::Links(car) => car.name.as_deref(),
        }
    }

    /// Reads a car file (or, for `.json`, an identification result) in
    /// either form: a TOML file with `[[links]]` or `[front]` as
    /// [`LinkCar`], everything else exactly as [`crate::car::Car::read_model_file`].
    pub fn read(path: &Path) -> Result<ChainCar, CarError> {
        let json = path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("json"));
        if json {
            return Ok(ChainCar::Linear(crate::car::Car::read_model_file(path)?));
        }
        let text = bumpsim_core::files::read_car_text(path)?;
        match toml::from_str::<Table>(&text) {
            Ok(table) if has_links(&table) => {
                Ok(ChainCar::Links(LinkCar::from_table(&table, path)?))
            }
            _ => Ok(ChainCar::Linear(crate::car::Car::parse(&text, path)?)),
        }
    }
}

#[cfg(test)]
#[path = "link_car_tests.rs"]
mod tests;
