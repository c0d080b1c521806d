//! `campaign collect`: collecting reads every done point's responses again (reading twice is
//! harmless: the same files give the same numbers), appends them to the
//! design table (`results/table.csv`, the format `bumpsim doe fit` reads:
//! `name [unit]` headers, one row per point, run order) and fits the
//! regression with the very code of `doe fit`
//! ([`bumpsim_doe::table_fit::fit_table_weighted`]): `results/model.json`, the HTML
//! report `results/report/index.html` and `results/fit-command.txt`, the
//! `bumpsim doe fit` command that gives the same model from the table.
//! An identified parameter regressed with its standard errors in the table
//! (`NAME.se`, issue 39) is fitted as `doe fit --se NAME` does: weights
//! `1/(τ² + SEᵢ²)`, τ² by REML (`bumpsim_doe::weighted`), so its
//! coefficients' intervals include the identification's uncertainty.
//! Points that failed, are not done, or whose output is now unreadable are
//! left out of the table and listed; never filled with zeros.

use crate::error::{CampaignError, Result};
use crate::init::{self, SPEC_FILE};
use crate::readers;
use crate::run::spec_of;
use crate::spec::Spec;
use crate::state::{State, Status};
use bumpsim_doe::data::Data;
use bumpsim_doe::table_fit::{ResponseFit, StandardErrors, TableFitSpec, fit_table_weighted};
use bumpsim_io::output::Outputs;
use std::path::Path;

/// The collected table in the campaign folder.
pub const TABLE: &str = "results/table.csv";

/// What `collect` did.
#[derive(Debug, Clone)]
pub struct Collected {
    /// Rows in the table.
    pub rows: usize,
    /// Points left out, with why.
    pub missing: Vec<(usize, String)>,
    /// The regression's summary text (empty without responses to regress).
    pub fit_text: String,
    /// The `doe fit` command equal to the regression.
    pub fit_command: String,
}

/// Collects campaign folder `dir` into `dir/results`.
pub fn collect(dir: &Path) -> Result<Collected> {
    let spec = spec_of(dir)?;
    let state = State::read(dir)?;
    let (points, _) = init::points(&spec, &dir.join(SPEC_FILE))?;
    if points.len() != state.points.len() {
        return Err(CampaignError::State {
            path: dir.join(crate::state::STATE_FILE),
            message: format!(
                "{} points, but the design of {SPEC_FILE} has {}: the campaign file was edited; run `bumpsim campaign init` again",
                state.points.len(),
                points.len()
            ),
        });
    }
    let mut collected = Vec::new();
    let mut missing = Vec::new();
    for (p, values) in state.points.iter().zip(&points) {
        if p.status != Status::Done {
            missing.push((
                p.run,
                format!("{}{}", p.status.name(), reason_suffix(&p.reason)),
            ));
            continue;
        }
        match read_row(dir, &spec, p.run, &p.folder) {
            Ok((responses, errors)) => collected.push((p.run, values, responses, errors)),
            Err(e) => missing.push((p.run, e.to_string())),
        }
    }
    let rows = collected.len();
    let csv = table(&spec, &collected);
    if rows == 0 {
        return Err(CampaignError::Collect(format!(
            "{}: no point is done yet: nothing to collect (bumpsim campaign status {0})",
            dir.display()
        )));
    }
    let (fit_text, fit_command, files) = regression(&spec, &csv)?;
    write_results(dir, &csv, &files)?;
    Ok(Collected {
        rows,
        missing,
        fit_text,
        fit_command,
    })
}

fn reason_suffix(reason: &str) -> String {
    match reason.is_empty() {
        true => String::new(),
        false => format!(": {reason}"),
    }
}

/// A collected point: run, design values, responses and identified
/// parameters, their standard errors.
type Row<'a> = (usize, &'a init::PointValues, Vec<f64>, Vec<Option<f64>>);

/// The table: header and rows, then a column `NAME.se [unit]` for each
/// identified parameter whose standard error every row has.
fn table(spec: &Spec, rows: &[Row]) -> String {
    let columns = spec.identify.as_ref().map_or(Vec::new(), |i| i.columns());
    let kept: Vec<usize> = (0..columns.len())
        .filter(|&j| rows.iter().all(|r| r.3[j].is_some()))
        .collect();
    let mut csv = table_header(spec);
    csv.pop(); // its line break
    kept.iter()
        .for_each(|&j| csv += &format!(",{}.se [{}]", columns[j].0, columns[j].1));
    csv.push('\n');
    for (run, values, responses, errors) in rows {
        let mut all = responses.clone();
        all.extend(kept.iter().filter_map(|&j| errors[j]));
        csv += &table_row(*run, values, &all);
    }
    csv
}

/// The point's responses, then its identified parameters; their standard
/// errors.
fn read_row(
    dir: &Path,
    spec: &Spec,
    run: usize,
    folder: &str,
) -> Result<(Vec<f64>, Vec<Option<f64>>)> {
    let folder = dir.join(folder);
    let mut row = spec
        .responses
        .iter()
        .map(|r| {
            readers::read(&folder, r).map_err(|source| CampaignError::Output {
                run,
                response: r.name.clone(),
                source: Box::new(source),
            })
        })
        .collect::<Result<Vec<f64>>>()?;
    if let Some(identify) = &spec.identify {
        let parameters = crate::identify::identify_point(&folder, identify).map_err(|source| {
            CampaignError::Identification {
                run,
                source: Box::new(source),
            }
        })?;
        row.extend(parameters.0);
        return Ok((row, parameters.1));
    }
    Ok((row, Vec::new()))
}

/// `run,standard order,<factors and derived> [unit],<coded>,<responses> [unit]`.
fn table_header(spec: &Spec) -> String {
    let mut out = String::from("run,standard order");
    for (name, unit) in header_names(spec) {
        out += &match unit {
            Some(u) => format!(",{name} [{u}]"),
            None => format!(",{name}"),
        };
    }
    spec.design
        .factors
        .iter()
        .for_each(|f| out += &format!(",{} (coded)", f.name));
    for (name, unit) in spec.response_columns() {
        out += &match unit {
            Some(u) => format!(",{name} [{u}]"),
            None => format!(",{name}"),
        };
    }
    out + "\n"
}

/// Factor and derived columns with units, in the design table's order.
fn header_names(spec: &Spec) -> Vec<(String, Option<String>)> {
    let mut names: Vec<(String, Option<String>)> = spec
        .design
        .factors
        .iter()
        .map(|f| (f.name.clone(), f.unit.clone()))
        .collect();
    if let Ok(order) = spec.derived_order(Path::new(SPEC_FILE)) {
        names.extend(order.into_iter().map(|(n, _)| {
            let unit = spec.unit_of(&n);
            (n, unit)
        }));
    }
    names
}

fn table_row(run: usize, p: &init::PointValues, responses: &[f64]) -> String {
    let mut row = format!("{run},{}", p.standard);
    p.values.iter().for_each(|(_, v)| row += &format!(",{v}"));
    p.coded.iter().for_each(|z| row += &format!(",{z}"));
    responses.iter().for_each(|v| row += &format!(",{v}"));
    row + "\n"
}

/// The fit specification of a campaign: its factors at their design
/// levels, the regressed responses, its terms.
pub fn fit_spec(spec: &Spec) -> TableFitSpec {
    TableFitSpec {
        factors: spec.factor_names(),
        responses: spec.regressed(),
        low: spec.design.factors.iter().map(|f| f.low).collect(),
        high: spec.design.factors.iter().map(|f| f.high).collect(),
        interactions: spec.regress.interactions,
        squares: spec.regress.squares,
    }
}

/// The `bumpsim doe fit` command equal to the regression of the campaign
/// in folder `dir`, naming its table through `dir` (to run from the
/// current folder; `results/fit-command.txt` holds the one to run from
/// the campaign's folder).
pub fn fit_command_for(dir: &Path) -> Result<String> {
    let spec = spec_of(dir)?;
    let table = dir.join(TABLE);
    let data = Data::read(&table).map_err(|e| CampaignError::Collect(e.to_string()))?;
    let se = standard_errors(&spec, &data);
    Ok(fit_command(&fit_spec(&spec), &table, &se))
}

/// The regressed identified parameters whose standard errors the table
/// holds (`NAME.se`): they are fitted with them.
pub fn standard_errors(spec: &Spec, data: &Data) -> Vec<StandardErrors> {
    let identified = spec.identify.as_ref().map_or(Vec::new(), |i| i.columns());
    let weighted = |r: &String| {
        let column = format!("{r}.se");
        let known = identified.iter().any(|(n, _)| n == r);
        (known && data.column(&column).is_some()).then(|| StandardErrors {
            response: r.clone(),
            column,
        })
    };
    spec.regressed().iter().filter_map(weighted).collect()
}

/// The `bumpsim doe fit` command line equal to a regression of the table
/// `table` with standard errors `se` (quoted for a POSIX shell where it
/// needs to be).
pub fn fit_command(spec: &TableFitSpec, table: &Path, se: &[StandardErrors]) -> String {
    let join = |v: &[f64]| v.iter().map(f64::to_string).collect::<Vec<_>>().join(",");
    let mut command = format!(
        "bumpsim doe fit {} --factors {} --responses {} --low {} --high {}",
        shell_word(&table.display().to_string()),
        spec.factors.join(","),
        spec.responses.join(","),
        join(&spec.low),
        join(&spec.high)
    );
    if spec.interactions {
        command += " --interactions";
    }
    if spec.squares {
        command += " --squares";
    }
    for s in se {
        command += &format!(
            " --se {}",
            shell_word(&format!("{}={}", s.response, s.column))
        );
    }
    command
}

/// `word` as one word of a POSIX shell command: as it is, or in single
/// quotes when it holds white space, quotes or other special characters.
fn shell_word(word: &str) -> String {
    let plain = |c: char| c.is_ascii_alphanumeric() || "/._-+,:=@%".contains(c);
    match !word.is_empty() && word.chars().all(plain) {
        true => word.into(),
        false => format!("'{}'", word.replace('\'', r"'\''")),
    }
}

type Files = Vec<(String, String)>;

/// Fits the table: summary text, the equal `doe fit` command, and the
/// model JSON and report files.
fn regression(spec: &Spec, csv: &str) -> Result<(String, String, Files)> {
    let fit = fit_spec(spec);
    if fit.responses.is_empty() {
        let command = fit_command(&fit, Path::new(TABLE), &[]);
        return Ok((String::new(), command.clone(), vec![command_file(&command)]));
    }
    let data =
        Data::parse(csv, Path::new(TABLE)).map_err(|e| CampaignError::Collect(e.to_string()))?;
    let se = standard_errors(spec, &data);
    let command = fit_command(&fit, Path::new(TABLE), &se);
    let mut files = vec![command_file(&command)];
    let (model, fits) = fit_table_weighted(&data, &fit, &se)?;
    let json =
        serde_json::to_string_pretty(&model).map_err(|e| CampaignError::Collect(e.to_string()))?;
    files.push(("model.json".into(), json));
    let (text, report) = report(spec, &fits, &se)?;
    files.extend(report);
    Ok((text, command, files))
}

/// `results/fit-command.txt`.
fn command_file(command: &str) -> (String, String) {
    ("fit-command.txt".to_string(), format!("{command}\n"))
}

/// The HTML report of the regression (the `doe fit --report` page).
fn report(spec: &Spec, fits: &[ResponseFit], se: &[StandardErrors]) -> Result<(String, Files)> {
    let mut page =
        bumpsim_report::html::Html::new(&format!("bumpsim campaign '{}': regression", spec.name));
    let mut all = String::new();
    let mut files = Vec::new();
    for f in fits {
        let unit = f.unit.as_deref();
        let text = f.summary(se);
        all += &text;
        page.heading(&format!(
            "{}{}",
            f.name,
            unit.map_or(String::new(), |u| format!(" [{u}]"))
        ));
        page.preformatted(&text);
        let plots =
            bumpsim_report::doe::fit_plots(&f.name, unit.unwrap_or("-"), &f.fit, &f.observed)
                .map_err(|e| CampaignError::Report(e.to_string()))?;
        for (name, svg, caption) in plots {
            page.figure(&svg, &caption);
            files.push((format!("report/{name}"), svg));
        }
    }
    files.push(("report/index.html".into(), page.finish()));
    Ok((all, files))
}

/// Writes `results/` whole (staged, then moved into place).
fn write_results(dir: &Path, csv: &str, files: &Files) -> Result<()> {
    let mut guard = Outputs::new();
    guard.input(&dir.join("points"));
    guard.input(&dir.join(SPEC_FILE));
    let staged = guard.stage_folder(&dir.join("results"))?;
    staged.write("table.csv", csv.as_bytes())?;
    for (name, text) in files {
        staged.write(name, text.as_bytes())?;
    }
    staged.commit(&guard)?;
    Ok(())
}
