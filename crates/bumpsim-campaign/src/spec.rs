//! The campaign file (`CAMPAIGN.toml`, docs/campaign.md): the design, the
//! deck template, derived quantities, the solver command, the responses to
//! read back per point, the regression and the executor settings. Parsed
//! with serde (unknown keys refused) and validated before anything is
//! written or submitted.

use crate::error::{CampaignError, Result, read_error};
use crate::expr::Expr;
use crate::response::ResponseSpec;
use bumpsim_doe::model::Factor;
use bumpsim_doe::{DesignKind, DesignOptions};
use bumpsim_io::table::split_header;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The plain-name rule of factors, derived quantities and responses (the
/// expressions' identifiers).
pub use crate::expr::is_name;

/// Most points a campaign may have (docs/limits.md).
pub const MAX_POINTS: usize = 100_000;
/// Retries of a task at most (`[executor] retries`).
pub const MAX_RETRIES: u32 = 100;

/// A parsed, validated campaign file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Spec {
    /// Campaign name (job names, reports).
    pub name: String,
    /// The design: any kind `bumpsim doe design` makes.
    pub design: DesignSpec,
    /// Derived quantities: name = expression over factors and other derived
    /// ones, with an optional unit at the end (`"2 * t_rail [m]"`).
    #[serde(default)]
    pub derived: BTreeMap<String, String>,
    /// The deck template and the files copied beside it.
    pub template: TemplateSpec,
    /// The solver command.
    pub solver: SolverSpec,
    /// What to read back per point.
    #[serde(default, rename = "response")]
    pub responses: Vec<ResponseSpec>,
    /// Per-point identification from a study template.
    #[serde(default)]
    pub identify: Option<crate::identify::IdentifySpec>,
    /// The regression of the collected table.
    #[serde(default)]
    pub regress: RegressSpec,
    /// Where and how the points run.
    #[serde(default)]
    pub executor: ExecutorSpec,
}

/// The design of a campaign.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DesignSpec {
    /// full | fractional | ccf | ccc | lhs | uniform.
    pub kind: String,
    /// The factors with their physical ranges (SI recommended).
    pub factors: Vec<Factor>,
    /// Generators of a fraction (`D=AB`).
    #[serde(default)]
    pub generators: Vec<String>,
    /// Centre points.
    #[serde(default)]
    pub centre: usize,
    /// Runs of an lhs or uniform design.
    #[serde(default = "default_runs")]
    pub runs: usize,
    /// Seed of random designs and of the run order.
    #[serde(default = "default_seed")]
    pub seed: u64,
    /// Randomise the run order.
    #[serde(default)]
    pub randomise: bool,
}

fn default_runs() -> usize {
    20
}

fn default_seed() -> u64 {
    1
}

/// The deck template.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TemplateSpec {
    /// The template file (relative to the campaign file): any text with
    /// `{{name}}` placeholders.
    pub file: PathBuf,
    /// The rendered deck's file name in each point folder (default: the
    /// template's file name).
    #[serde(default)]
    pub deck: Option<String>,
    /// Files copied unchanged into each point folder (relative to the campaign file).
    #[serde(default)]
    pub files: Vec<PathBuf>,
    /// For LS-DYNA `*PARAMETER` users: also write this include in each point
    /// folder, one `R name value` card per factor and derived quantity.
    #[serde(default)]
    pub lsdyna_parameters: Option<String>,
}

/// The solver command, run in the point folder.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolverSpec {
    /// Program and arguments (`["ccx", "-i", "deck"]`): a program name
    /// on PATH or an absolute path (it runs in each point folder).
    pub command: Vec<String>,
}

/// The regression of the collected table (`doe fit`).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RegressSpec {
    /// Responses to regress (default: all).
    #[serde(default)]
    pub responses: Vec<String>,
    /// Two-factor interactions.
    #[serde(default)]
    pub interactions: bool,
    /// Squares.
    #[serde(default)]
    pub squares: bool,
}

/// Executor settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExecutorSpec {
    /// `local` (default) or `slurm`.
    #[serde(default = "default_kind")]
    pub kind: String,
    /// Local process slots.
    #[serde(default = "default_slots")]
    pub slots: usize,
    /// Retries of a failed, timed-out, pre-empted or lost task.
    #[serde(default = "default_retries")]
    pub retries: u32,
    /// Seconds between status polls of Slurm.
    #[serde(default = "default_poll")]
    pub poll_seconds: f64,
    /// Time limit per task, in Slurm's form (`HH:MM:SS`, ...), for both
    /// executors: the local one kills a task's process group at it, Slurm
    /// gets it as `--time` unless `[executor.slurm] time` says otherwise.
    #[serde(default)]
    pub time: Option<String>,
    /// Slurm settings.
    #[serde(default)]
    pub slurm: SlurmSpec,
}

fn default_kind() -> String {
    "local".into()
}

fn default_slots() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

fn default_retries() -> u32 {
    2
}

fn default_poll() -> f64 {
    2.0
}

impl Default for ExecutorSpec {
    fn default() -> Self {
        ExecutorSpec {
            kind: default_kind(),
            slots: default_slots(),
            retries: default_retries(),
            poll_seconds: default_poll(),
            time: None,
            slurm: SlurmSpec::default(),
        }
    }
}

/// Per-task resources and site settings of the Slurm array.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SlurmSpec {
    /// `--partition`.
    #[serde(default)]
    pub partition: Option<String>,
    /// `--account`.
    #[serde(default)]
    pub account: Option<String>,
    /// `--time` per task (`HH:MM:SS`).
    #[serde(default)]
    pub time: Option<String>,
    /// `--cpus-per-task`.
    #[serde(default)]
    pub cpus_per_task: Option<u32>,
    /// `--mem` per task (`4G`).
    #[serde(default)]
    pub mem: Option<String>,
    /// The array's `%` limit: tasks running at once (default: no limit).
    #[serde(default)]
    pub max_concurrent: Option<usize>,
    /// Tasks of the campaign queued or running at once; the controller
    /// submits more as they end (default 10 000, at most half the
    /// cluster's `MaxJobCount`).
    #[serde(default)]
    pub max_queued: Option<usize>,
    /// `module load` lines of the job script.
    #[serde(default)]
    pub modules: Vec<String>,
    /// Shell lines run before the solver (environment setup).
    #[serde(default)]
    pub setup: Vec<String>,
    /// Further `sbatch` options, verbatim (`--qos=normal`).
    #[serde(default)]
    pub options: Vec<String>,
}

impl Spec {
    /// Reads and validates a campaign file.
    pub fn read(path: &Path) -> Result<Spec> {
        let text = std::fs::read_to_string(path).map_err(|e| read_error(path, e))?;
        Spec::parse(&text, path)
    }

    /// Parses and validates campaign text; `path` is used in messages.
    ///
    /// ```
    /// use bumpsim_campaign::spec::Spec;
    /// let text = r#"
    /// name = "c"
    /// [design]
    /// kind = "full"
    /// factors = [{ name = "t_rail", low = 1.5e-3, high = 2.5e-3, unit = "m" }]
    /// [derived]
    /// t_mm = "t_rail * 1000"
    /// [template]
    /// file = "bumper.k.tmpl"
    /// [solver]
    /// command = ["lsdyna", "i=bumper.k"]
    /// "#;
    /// let spec = Spec::parse(text, "c.toml".as_ref()).unwrap();
    /// assert_eq!(spec.deck_name(), "bumper.k.tmpl");
    /// let bad = Spec::parse(&text.replace("t_rail * 1000", "t_beam * 1000"), "c.toml".as_ref());
    /// assert!(bad.unwrap_err().to_string().contains("unknown name 't_beam'"));
    /// ```
    pub fn parse(text: &str, path: &Path) -> Result<Spec> {
        let spec: Spec = toml::from_str(text).map_err(|e| CampaignError::Toml {
            path: path.into(),
            message: e.to_string(),
        })?;
        spec.validate(path)?;
        Ok(spec)
    }

    fn invalid(path: &Path, key: &str, message: String) -> CampaignError {
        CampaignError::Invalid {
            path: path.into(),
            key: key.into(),
            message,
        }
    }

    fn validate(&self, path: &Path) -> Result<()> {
        self.validate_size(path)?;
        for f in &self.design.factors {
            Factor::new(&f.name, f.low, f.high, None)
                .map_err(|e| Spec::invalid(path, "design.factors", e.to_string()))?;
            if !is_name(&f.name) {
                let message = format!("'{}': names are letters, digits and _", f.name);
                return Err(Spec::invalid(path, "design.factors", message));
            }
        }
        self.derived_order(path)?;
        match self.solver.command.first() {
            None => return Err(Spec::invalid(path, "solver.command", "is empty".into())),
            // the solver runs in each point folder: a relative path would mean another file there
            Some(p) if p.contains('/') && !p.starts_with('/') => {
                let message = format!("'{p}': give an absolute path or a program name on PATH");
                return Err(Spec::invalid(path, "solver.command", message));
            }
            Some(_) => {}
        }
        self.validate_point_files(path)?;
        self.validate_responses(path)?;
        self.validate_executor(path)
    }

    /// The files of each point folder (name, the key that names it), in
    /// the order of [`crate::init::input_files`]: the rendered deck, the
    /// copied files, the LS-DYNA parameter include, the rendered study.
    pub fn point_files(&self) -> Vec<(String, String)> {
        let deck_key = match self.template.deck {
            Some(_) => "template.deck",
            None => "template.file",
        };
        let mut files = vec![(self.deck_name(), deck_key.to_string())];
        for (i, f) in self.template.files.iter().enumerate() {
            if let Some(name) = f.file_name() {
                let key = format!("template.files[{}]", i + 1);
                files.push((name.to_string_lossy().into_owned(), key));
            }
        }
        if let Some(name) = &self.template.lsdyna_parameters {
            files.push((name.clone(), "template.lsdyna_parameters".into()));
        }
        if self.identify.is_some() {
            let name = crate::identify::STUDY_FILE.to_string();
            files.push((name, "identify (its rendered study)".into()));
        }
        files
    }

    /// A file name that is not plain (a path, `..`) is refused; two files of
    /// one name in a point folder (a file listed twice, a deck named like a
    /// copied file) would be written twice: refused.
    fn validate_point_files(&self, path: &Path) -> Result<()> {
        let files = self.point_files();
        for (i, (name, key)) in files.iter().enumerate() {
            // the staging refuses it too, but without the file and key
            bumpsim_io::output::plain_name(name)
                .map_err(|e| Spec::invalid(path, key, e.to_string()))?;
            if let Some((_, first)) = files[..i].iter().find(|(n, _)| n == name) {
                let message = format!(
                    "'{name}' is also the file of {first}: each file of a point folder needs a name of its own"
                );
                return Err(Spec::invalid(path, key, message));
            }
        }
        Ok(())
    }

    /// Refuses designs beyond [`MAX_POINTS`] before any is made: the runs
    /// of a space-filling design, 2^k of a factorial (k ≤ 16), centre points.
    fn validate_size(&self, path: &Path) -> Result<()> {
        let kind = self.design_kind(path)?;
        let d = &self.design;
        let random = matches!(kind, DesignKind::LatinHypercube | DesignKind::Uniform);
        let too_many = match random {
            true => d.runs == 0 || d.runs > MAX_POINTS,
            false => d.factors.len() > 16 || d.centre > MAX_POINTS,
        };
        if too_many || d.factors.is_empty() {
            let message = format!(
                "1 to {MAX_POINTS} points (runs of lhs/uniform; at most 16 factors in a factorial or composite design; at least one factor) (docs/limits.md)"
            );
            return Err(Spec::invalid(path, "design", message));
        }
        Ok(())
    }

    /// The design kind, checked.
    pub fn design_kind(&self, path: &Path) -> Result<DesignKind> {
        self.design
            .kind
            .parse()
            .map_err(|e: bumpsim_doe::design::DesignKindError| {
                Spec::invalid(path, "design.kind", e.to_string())
            })
    }

    /// The options `bumpsim_doe::design::make` needs.
    pub fn design_options(&self) -> DesignOptions {
        DesignOptions {
            generators: self.design.generators.clone(),
            centre: self.design.centre,
            runs: self.design.runs,
            seed: self.design.seed,
        }
    }

    /// The derived quantities in an order where each uses only factors and
    /// earlier ones; an unknown name or a cycle is an error naming the key.
    pub fn derived_order(&self, path: &Path) -> Result<Vec<(String, Expr)>> {
        let mut known: Vec<String> = self.design.factors.iter().map(|f| f.name.clone()).collect();
        let mut todo = Vec::new();
        for (name, text) in &self.derived {
            let key = format!("derived.{name}");
            // "expression [unit]": the unit is for the table header
            let text = split_header(text).map_or(text.as_str(), |(expression, _)| expression);
            let expr = Expr::parse(text).map_err(|e| Spec::invalid(path, &key, e.to_string()))?;
            if known.contains(name) || !is_name(name) {
                let message = format!("'{name}' is a factor already or not a plain name");
                return Err(Spec::invalid(path, &key, message));
            }
            todo.push((name.clone(), expr));
        }
        let mut ordered = Vec::new();
        while !todo.is_empty() {
            let ready = todo
                .iter()
                .position(|(_, e)| e.names().iter().all(|n| known.iter().any(|k| k == n)));
            let Some(i) = ready else {
                return Err(self.unresolved(path, &todo, &known));
            };
            let (name, expr) = todo.remove(i);
            known.push(name.clone());
            ordered.push((name, expr));
        }
        Ok(ordered)
    }

    fn unresolved(&self, path: &Path, todo: &[(String, Expr)], known: &[String]) -> CampaignError {
        let pending: Vec<&str> = todo.iter().map(|(n, _)| n.as_str()).collect();
        let (name, expr) = &todo[0];
        let missing = expr
            .names()
            .into_iter()
            .find(|n| !known.iter().any(|k| k == n) && !pending.contains(n));
        let message = match missing {
            Some(unknown) => format!(
                "unknown name '{unknown}' (factors: {})",
                self.factor_names().join(", ")
            ),
            None => format!(
                "the derived quantities {} depend on each other",
                pending.join(", ")
            ),
        };
        Spec::invalid(path, &format!("derived.{name}"), message)
    }

    /// The unit of a factor or derived quantity, if given.
    pub fn unit_of(&self, name: &str) -> Option<String> {
        match self.design.factors.iter().find(|f| f.name == name) {
            Some(f) => f.unit.clone(),
            None => self
                .derived
                .get(name)
                .and_then(|t| split_header(t))
                .map(|(_, unit)| unit.to_string()),
        }
    }

    /// The factor names, in design order.
    pub fn factor_names(&self) -> Vec<String> {
        self.design.factors.iter().map(|f| f.name.clone()).collect()
    }

    /// The rendered deck's file name in a point folder.
    pub fn deck_name(&self) -> String {
        self.template.deck.clone().unwrap_or_else(|| {
            self.template
                .file
                .file_name()
                .map_or("deck".into(), |n| n.to_string_lossy().into_owned())
        })
    }

    /// The response columns of the collected table: the `[[response]]`s,
    /// then the identified parameters.
    pub fn response_columns(&self) -> Vec<(String, Option<String>)> {
        let mut columns: Vec<(String, Option<String>)> = self
            .responses
            .iter()
            .map(|r| (r.name.clone(), r.unit.clone()))
            .collect();
        if let Some(identify) = &self.identify {
            columns.extend(
                identify
                    .columns()
                    .into_iter()
                    .map(|(n, u)| (n, Some(u.to_string()))),
            );
        }
        columns
    }

    /// The responses to regress (default: every response column).
    pub fn regressed(&self) -> Vec<String> {
        match self.regress.responses.is_empty() {
            true => self
                .response_columns()
                .into_iter()
                .map(|(n, _)| n)
                .collect(),
            false => self.regress.responses.clone(),
        }
    }

    fn validate_responses(&self, path: &Path) -> Result<()> {
        for (i, r) in self.responses.iter().enumerate() {
            let key = format!("response[{}] '{}'", i + 1, r.name);
            r.check().map_err(|source| CampaignError::Response {
                path: path.into(),
                key: key.clone(),
                source,
            })?;
            if self.responses[..i].iter().any(|o| o.name == r.name) {
                return Err(Spec::invalid(
                    path,
                    &key,
                    "a second response of this name".into(),
                ));
            }
            self.validate_response_name(path, &key, &r.name)?;
        }
        let columns: Vec<String> = self
            .response_columns()
            .into_iter()
            .map(|(n, _)| n)
            .collect();
        for (i, name) in self.regress.responses.iter().enumerate() {
            if self.regress.responses[..i].contains(name) {
                let message = format!("'{name}' is listed twice: list each response once");
                return Err(Spec::invalid(path, "regress.responses", message));
            }
            if !columns.contains(name) {
                let message = format!("'{name}' is not a response column ({})", columns.join(", "));
                return Err(Spec::invalid(path, "regress.responses", message));
            }
        }
        self.validate_identify(path, &columns)
    }

    /// A response's column must not take the name of a factor or derived
    /// quantity: the table would hold two columns of one name.
    fn validate_response_name(&self, path: &Path, key: &str, name: &str) -> Result<()> {
        let other = match self.design.factors.iter().any(|f| f.name == name) {
            true => Some(("factor", "design.factors")),
            false => (self.derived.contains_key(name)).then_some(("derived quantity", "derived")),
        };
        match other {
            Some((what, table)) => {
                let message = format!(
                    "named like the {what} '{name}' ({table}): the table would have two columns '{name}'; rename the response or the {what}"
                );
                Err(Spec::invalid(path, key, message))
            }
            None => Ok(()),
        }
    }

    fn validate_identify(&self, path: &Path, columns: &[String]) -> Result<()> {
        let Some(identify) = &self.identify else {
            return Ok(());
        };
        let most = bumpsim_ident::settings::MAX_DOF;
        if identify.dof == 0 || identify.dof > most {
            return Err(Spec::invalid(
                path,
                "identify.dof",
                format!("expected 1 to {most} (the identification's limit, docs/limits.md)"),
            ));
        }
        let mut names = self.factor_names();
        names.extend(self.derived.keys().cloned());
        for (i, name) in columns.iter().enumerate() {
            if names.contains(name) || columns[..i].contains(name) {
                let message = format!(
                    "column '{name}' twice: rename the factor, derived quantity or response (identified parameters are m1.., c1.., k1..)"
                );
                return Err(Spec::invalid(path, "identify", message));
            }
        }
        Ok(())
    }

    fn validate_executor(&self, path: &Path) -> Result<()> {
        let e = &self.executor;
        if e.kind != "local" && e.kind != "slurm" {
            let message = format!("'{}': expected local or slurm", e.kind);
            return Err(Spec::invalid(path, "executor.kind", message));
        }
        if e.slots == 0 || e.slots > 1024 {
            return Err(Spec::invalid(
                path,
                "executor.slots",
                "expected 1 to 1024".into(),
            ));
        }
        if e.retries > MAX_RETRIES {
            let message = format!("{}: at most {MAX_RETRIES} (docs/limits.md)", e.retries);
            return Err(Spec::invalid(path, "executor.retries", message));
        }
        if !(e.poll_seconds.is_finite() && (0.01..=3600.0).contains(&e.poll_seconds)) {
            let message = "expected 0.01 to 3600 s".into();
            return Err(Spec::invalid(path, "executor.poll_seconds", message));
        }
        for (key, value) in [
            ("executor.slurm.max_concurrent", e.slurm.max_concurrent),
            ("executor.slurm.max_queued", e.slurm.max_queued),
        ] {
            if value == Some(0) {
                return Err(Spec::invalid(path, key, "expected at least 1".into()));
            }
        }
        for (key, value) in [
            ("executor.time", &e.time),
            ("executor.slurm.time", &e.slurm.time),
        ] {
            if let Some(text) = value.as_ref().filter(|t| time_limit(t).is_none()) {
                let message = format!(
                    "'{text}': expected a Slurm time above zero: MINUTES, MM:SS, HH:MM:SS, D-HH, D-HH:MM or D-HH:MM:SS"
                );
                return Err(Spec::invalid(path, key, message));
            }
        }
        Ok(())
    }
}

impl ExecutorSpec {
    /// The local executor's time limit per task: `time`, else Slurm's
    /// `time` (the same campaign file limits a task alike on both).
    pub fn local_time(&self) -> Option<(String, std::time::Duration)> {
        let text = self.time.as_ref().or(self.slurm.time.as_ref())?;
        time_limit(text).map(|limit| (text.clone(), limit))
    }

    /// Slurm's `--time`: `[executor.slurm] time`, else `time`.
    pub fn slurm_time(&self) -> Option<&String> {
        self.slurm.time.as_ref().or(self.time.as_ref())
    }
}

/// A time limit in Slurm's forms (`sbatch --time`): MINUTES, MM:SS,
/// HH:MM:SS, D-HH, D-HH:MM, D-HH:MM:SS; `None` if it is none of them or zero.
///
/// ```
/// use bumpsim_campaign::spec::time_limit;
/// use std::time::Duration;
/// assert_eq!(time_limit("02:00:00"), Some(Duration::from_secs(7200)));
/// assert_eq!(time_limit("1-12"), Some(Duration::from_secs(129_600)));
/// assert_eq!(time_limit("0:02"), Some(Duration::from_secs(2)));
/// assert_eq!(time_limit("2h"), None);
/// ```
pub fn time_limit(text: &str) -> Option<std::time::Duration> {
    let (days, rest) = match text.split_once('-') {
        Some((d, rest)) => (Some(d.parse::<u64>().ok()?), rest),
        None => (None, text),
    };
    let parts: Vec<u64> = rest
        .split(':')
        .map(|p| p.parse().ok())
        .collect::<Option<_>>()?;
    let seconds = match (days, parts.as_slice()) {
        (None, [m]) => m.checked_mul(60)?,
        (None, [m, s]) => m.checked_mul(60)?.checked_add(*s)?,
        (None, [h, m, s]) => hms(*h, *m, *s)?,
        (Some(d), [h]) => hms(d.checked_mul(24)?.checked_add(*h)?, 0, 0)?,
        (Some(d), [h, m]) => hms(d.checked_mul(24)?.checked_add(*h)?, *m, 0)?,
        (Some(d), [h, m, s]) => hms(d.checked_mul(24)?.checked_add(*h)?, *m, *s)?,
        _ => return None,
    };
    (seconds > 0).then(|| std::time::Duration::from_secs(seconds))
}

fn hms(h: u64, m: u64, s: u64) -> Option<u64> {
    h.checked_mul(3600)?
        .checked_add(m.checked_mul(60)?)?
        .checked_add(s)
}

/// Finds `program` as the solver or scheduler runs it: a path with a `/`
/// as given (relative to `dir`), else the first executable on PATH.
pub fn find_program(program: &str, dir: &Path) -> Option<PathBuf> {
    use std::os::unix::fs::PermissionsExt;
    let executable = |p: &Path| {
        std::fs::metadata(p).is_ok_and(|m| m.is_file() && m.permissions().mode() & 0o111 != 0)
    };
    if program.contains('/') {
        let path = dir.join(program);
        return executable(&path).then_some(path);
    }
    let paths = std::env::var_os("PATH")?;
    std::env::split_paths(&paths)
        .map(|d| d.join(program))
        .find(|p| executable(p))
}

#[cfg(test)]
mod tests;
