//! The options shared by the subcommands (the parameter set, the output
//! format, a steady run's periods and tolerances) and their checks: the
//! parameter set built from `--model`, `--params` and `--set`, Omega grids,
//! mesh names and shards.

use crate::failure::{usage, Failure};
use crate::input::{bytes_text, read_json, MAX_PARAMS_BYTES};
use clap::{Args, ValueEnum};
use serde_json::Value;
use solver::iso6336::IsoInputs;
use solver::keys;
use solver::params::{ModelKind, ModelParams};
use solver::steady::{Model, SteadyOptions};

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// One JSON document, written at the end.
    Json,
    /// CSV tables.
    Csv,
    /// JSON lines, streamed: for bifurcation, map, lyapunov and
    /// instability a header line (model, params, spec), then one line per
    /// point or cell as soon as it is computed, then `{"complete": true,
    /// ...}`; for the other commands the JSON document on one line.
    Jsonl,
}

#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum ModelArg {
    Ravigneaux,
    GearPair,
}

/// Parameter selection shared by every subcommand.
#[derive(Debug, Args)]
pub struct ParamArgs {
    /// Built-in model.
    #[arg(long, value_enum)]
    pub model: Option<ModelArg>,
    /// A JSON file with a flat object of parameter keys (see `gearshock keys`).
    #[arg(long, value_name = "FILE.json")]
    pub params: Option<std::path::PathBuf>,
    /// Set one parameter, e.g. `--set backlash_um=200` (repeatable).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// A table of TE against mesh-cycle fraction, roll angle or time (CSV,
    /// units in the header) fitted to a mesh kind's TE, e.g. `--te-file
    /// s1a=te.csv` (`pair=te.csv` on the gear pair; repeatable). The fit
    /// replaces that kind's TE mean and harmonics, after --params and --set.
    #[arg(long = "te-file", value_name = "KIND=FILE")]
    pub te_file: Vec<String>,
    /// Harmonics of the mesh frequency fitted to each --te-file table.
    #[arg(long, default_value_t = solver::params::TE_HARMONICS, value_name = "N")]
    pub te_harmonics: usize,
    /// Output format (jsonl streams sweeps point by point).
    #[arg(long, value_enum, default_value = "json")]
    pub format: Format,
    /// Print progress lines on stderr even when it is not a terminal (logs,
    /// cluster jobs): one line per whole percent.
    #[arg(long)]
    pub progress: bool,
}

/// The Omega range of a sweep, given as Omega or as the input member's
/// speed in rpm (either end either way).
#[derive(Debug, Args)]
pub struct OmegaRange {
    /// First Omega.
    #[arg(long, allow_hyphen_values = true, value_parser = crate::flags::finite,
          required_unless_present = "rpm_from", conflicts_with = "rpm_from")]
    omega_from: Option<f64>,
    /// Last Omega.
    #[arg(long, allow_hyphen_values = true, value_parser = crate::flags::finite,
          required_unless_present = "rpm_to", conflicts_with = "rpm_to")]
    omega_to: Option<f64>,
    /// First input speed in rpm (of the small sun s1, or of the pinion),
    /// instead of --omega-from.
    #[arg(long, allow_hyphen_values = true, value_parser = crate::flags::finite)]
    rpm_from: Option<f64>,
    /// Last input speed in rpm, instead of --omega-to.
    #[arg(long, allow_hyphen_values = true, value_parser = crate::flags::finite)]
    rpm_to: Option<f64>,
}

impl OmegaRange {
    /// The range in Omega on `model`: speeds given in rpm are converted
    /// (`solver::campbell::omega_at`) and the conversion said on stderr,
    /// so that a range refused later in Omega can be read back in rpm.
    pub fn omegas(&self, model: &Model) -> Result<(f64, f64), Failure> {
        let end = |omega: Option<f64>, rpm: Option<f64>, flag: &str| -> Result<f64, Failure> {
            match (omega, rpm) {
                (Some(o), _) => Ok(o),
                (None, Some(r)) if r > 0.0 => {
                    let o = solver::campbell::omega_at(model, r);
                    crate::output::note(&format!("note: {flag} {r} is Omega {o:.6}"));
                    Ok(o)
                }
                (None, Some(r)) => Err(usage(format!(
                    "{flag} {r} is out of range: allowed above 0 rpm"
                ))),
                // clap requires one of the two.
                (None, None) => Err(usage(format!("{flag} is missing"))),
            }
        };
        Ok((
            end(self.omega_from, self.rpm_from, "--rpm-from")?,
            end(self.omega_to, self.rpm_to, "--rpm-to")?,
        ))
    }
}

/// An Omega range and its number of points (200 by default: a
/// bifurcation sweep, an instability scan).
#[derive(Debug, Args)]
pub struct OmegaPoints {
    #[command(flatten)]
    pub range: OmegaRange,
    /// Number of Omega points.
    #[arg(long, default_value_t = 200)]
    pub points: u32,
}

/// The key varied against Omega and its range (the map's rows, the
/// boundaries' second axis).
#[derive(Debug, Args)]
pub struct KeyRange {
    /// The key varied against Omega: any numeric key for a map (e.g.
    /// backlash_um, te_um); for boundaries one that leaves the natural
    /// modes unchanged (backlash_um, te_um, damping_ratio,
    /// stiffness_variation, a torque, a per-mesh backlash or TE key).
    #[arg(long, default_value = "backlash_um")]
    pub key: String,
    /// First value of the key.
    #[arg(long, allow_hyphen_values = true, value_parser = crate::flags::finite)]
    pub value_from: f64,
    /// Last value of the key.
    #[arg(long, allow_hyphen_values = true, value_parser = crate::flags::finite)]
    pub value_to: f64,
}

/// Options of a steady-state run.
#[derive(Debug, Args)]
pub struct RunArgs {
    /// Maximum transient mesh periods (the transient ends early once the
    /// Poincaré samples have settled, unless --full-transient).
    #[arg(long, default_value_t = 300)]
    pub transient_periods: u32,
    /// Recorded mesh periods.
    #[arg(long, default_value_t = 100)]
    pub record_periods: u32,
    /// Always integrate every transient period (no early end, no shooting).
    #[arg(long)]
    pub full_transient: bool,
    /// Do not look for a periodic orbit by shooting during the transient:
    /// integrate only (with the early-settle test, without the Lyapunov
    /// probe).
    #[arg(long)]
    pub no_shooting: bool,
    /// Relative tolerance of the integrator.
    #[arg(long, default_value_t = solver::steady::DEFAULT_RTOL, allow_hyphen_values = true, value_parser = crate::flags::finite)]
    pub rtol: f64,
    /// Absolute tolerance as a mesh deflection (m).
    #[arg(long, default_value_t = solver::steady::DEFAULT_ATOL_M, allow_hyphen_values = true, value_parser = crate::flags::finite)]
    pub atol: f64,
}

impl RunArgs {
    pub fn apply(&self, opts: &mut SteadyOptions) {
        opts.transient_periods = self.transient_periods;
        opts.record_periods = self.record_periods;
        opts.early_settle = !self.full_transient;
        opts.shooting = !(self.full_transient || self.no_shooting);
        opts.rtol = self.rtol;
        opts.atol_m = self.atol;
    }
}

impl ParamArgs {
    /// The parameter set ([`load_params`]) and its model.
    pub fn load(&self) -> Result<(ModelParams, Model), Failure> {
        let params = load_params(self)?;
        let model = Model::new(&params)?;
        Ok((params, model))
    }
}

/// The header line of a streamed sweep: the model, its parameters and
/// (where the sweep has one) its spec.
pub fn stream_header(model: &Model, params: &ModelParams, spec: Option<Value>) -> Value {
    let mut header = serde_json::json!({
        "model": model.system.model.name(),
        "params": Value::Object(keys::to_json(params)),
    });
    if let Some(spec) = spec {
        header["spec"] = spec;
    }
    header
}

pub fn model_kind(m: ModelArg) -> ModelKind {
    match m {
        ModelArg::Ravigneaux => ModelKind::Ravigneaux,
        ModelArg::GearPair => ModelKind::GearPair,
    }
}

/// Builds the parameter set. The model is settled first, whichever of
/// `--model`, `--set model=...` and the file's `model` names it (they must
/// agree), because choosing a model resets every parameter to its
/// defaults: applied in the order given, `--set backlash_um=50 --set
/// model=gear-pair` would silently drop the backlash. Then the file's keys,
/// then the `--set`s in order.
pub fn load_params(p: &ParamArgs) -> Result<ModelParams, Failure> {
    let mut chosen: Option<(String, ModelKind)> = p
        .model
        .map(|m| (format!("--model {}", model_kind(m).name()), model_kind(m)));
    let mut sets = Vec::new();
    for assignment in &p.set {
        let Some((name, text)) = assignment.split_once('=') else {
            return Err(usage(format!(
                "--set {}: not of the form KEY=VALUE",
                keys::truncate(assignment, 60)
            )));
        };
        if name.trim() != "model" {
            sets.push(assignment);
            continue;
        }
        keys::parse_value("model", text).map_err(|e| usage(format!("--set {e}")))?;
        let kind = ModelKind::from_name(text.trim()).unwrap_or(ModelParams::default().kind());
        let this = format!("--set model={}", kind.name());
        if let Some((before, k)) = &chosen {
            if *k != kind {
                return Err(usage(format!(
                    "{this} contradicts {before}: give one model"
                )));
            }
        }
        chosen = Some((this, kind));
    }
    let file = match &p.params {
        Some(path) => {
            let shown = path.display();
            let limit = format!(
                "the {} allowed for a parameter file",
                bytes_text(MAX_PARAMS_BYTES)
            );
            match read_json(path, MAX_PARAMS_BYTES, "--params", &limit)?.0 {
                Value::Object(map) => Some((shown.to_string(), map)),
                _ => {
                    return Err(usage(format!(
                        "--params {shown}: the file must hold one flat JSON object of KEY: VALUE"
                    )))
                }
            }
        }
        None => None,
    };
    let file_kind = match &file {
        Some((shown, map)) => match map.get("model") {
            Some(Value::String(m)) => {
                keys::parse_value("model", m)
                    .map_err(|e| usage(format!("--params {shown}: {e}")))?;
                ModelKind::from_name(m.trim())
            }
            _ => None,
        },
        None => None,
    };
    if let (Some((shown, _)), Some(fk), Some((given, k))) = (&file, file_kind, &chosen) {
        if fk != *k {
            return Err(usage(format!(
                "--params {shown} is a {} parameter set but {given} was given: its settings would be dropped",
                fk.name()
            )));
        }
    }
    let kind = chosen
        .map(|(_, k)| k)
        .or(file_kind)
        .unwrap_or(ModelParams::default().kind());
    let mut params = ModelParams::defaults(kind);
    if let Some((shown, map)) = &file {
        keys::apply_json(&mut params, map).map_err(|e| usage(format!("--params {shown}: {e}")))?;
    }
    for assignment in sets {
        keys::set_assignment(&mut params, assignment).map_err(|e| usage(format!("--set {e}")))?;
    }
    for given in &p.te_file {
        apply_te_file(&mut params, given, p.te_harmonics)?;
    }
    Ok(params)
}

/// Fits one `--te-file KIND=FILE` table (`solver::te_file`) and sets the
/// kind's TE keys to the fit, its residual said on stderr.
fn apply_te_file(params: &mut ModelParams, given: &str, harmonics: usize) -> Result<(), Failure> {
    use solver::te_file::{self, MAX_TE_FILE_BYTES};
    let max = solver::params::TE_HARMONICS;
    if !(1..=max).contains(&harmonics) {
        return Err(usage(format!(
            "--te-harmonics {harmonics} is out of range: allowed 1 ..= {max}"
        )));
    }
    let kinds = te_file::kinds(params);
    let (kind, path) = given
        .split_once('=')
        .filter(|(k, _)| kinds.contains(k))
        .ok_or_else(|| {
            usage(format!(
                "--te-file {}: not of the form KIND=FILE with KIND one of {}",
                keys::truncate(given, 60),
                kinds.join(", ")
            ))
        })?;
    let what = format!("--te-file {kind}=");
    let limit = format!(
        "the {} allowed for a TE file",
        bytes_text(MAX_TE_FILE_BYTES)
    );
    let mut file = crate::input::LimitedFile::open(
        std::path::Path::new(path),
        MAX_TE_FILE_BYTES,
        &what,
        &limit,
    )?;
    let mut text = String::new();
    std::io::Read::read_to_string(file.reader(), &mut text).map_err(|e| {
        if e.to_string().contains("over the size limit") {
            usage(format!("{what}{path}: larger than {limit}"))
        } else {
            usage(format!("{what}{path}: {e}"))
        }
    })?;
    let refused = |e: solver::error::SolverError| usage(format!("{what}{path}: {e}"));
    let table = te_file::parse(&text).map_err(refused)?;
    let fit = te_file::fit_into(params, kind, &table, harmonics).map_err(refused)?;
    crate::output::note(&format!(
        "{what}{path}: {harmonics} harmonics fitted to {} points over {:.3} mesh periods; \
         RMS residual {:.3e} µm against an RMS TE of {:.3e} µm; coefficients rounded to {} decimals of a µm",
        fit.points, fit.periods, fit.rms_residual_um, fit.rms_um, fit.decimals
    ));
    Ok(())
}

/// `points` equally spaced Omegas from `omega_from` to `omega_to` (both
/// included, each in the solver's range 0.01 ..= 20), or a usage failure
/// naming the bad option and its range.
pub fn omega_grid(
    omega_from: f64,
    omega_to: f64,
    points: u32,
    max_points: u32,
) -> Result<Vec<f64>, Failure> {
    for (flag, v) in [("--omega-from", omega_from), ("--omega-to", omega_to)] {
        if !(v.is_finite() && (0.01..=20.0).contains(&v)) {
            return Err(usage(format!(
                "{flag} {v} is out of range: allowed 0.01 ..= 20"
            )));
        }
    }
    if omega_to.partial_cmp(&omega_from) != Some(std::cmp::Ordering::Greater) {
        return Err(usage(format!(
            "--omega-to {omega_to}: must exceed --omega-from {omega_from}"
        )));
    }
    if !(2..=max_points).contains(&points) {
        return Err(usage(format!(
            "--points {points} is out of range: allowed 2 ..= {max_points}"
        )));
    }
    Ok((0..points)
        .map(|i| omega_from + (omega_to - omega_from) * f64::from(i) / f64::from(points - 1))
        .collect())
}

pub fn mesh_index(model: &Model, name: Option<&str>) -> Result<usize, Failure> {
    match name {
        None => Ok(0),
        Some(n) => model.system.mesh_index(n).ok_or_else(|| {
            let names: Vec<&str> = model
                .system
                .meshes
                .iter()
                .map(|m| m.name.as_str())
                .collect();
            usage(format!(
                "--mesh {}: no such mesh; this model has {}",
                keys::truncate(n, 40),
                names.join(", ")
            ))
        }),
    }
}

pub fn parse_shard(s: &str) -> Result<(u32, u32), Failure> {
    s.split_once('/')
        .and_then(|(i, n)| Some((i.parse::<u32>().ok()?, n.parse::<u32>().ok()?)))
        .filter(|&(i, n)| i < n)
        .ok_or_else(|| {
            usage(format!(
                "--shard {}: expected i/n with i < n, e.g. 0/4",
                keys::truncate(s, 20)
            ))
        })
}

/// The meshes named by `--mesh`: `all`, one by name, or the first.
pub fn meshes(model: &Model, name: Option<&str>) -> Result<Vec<usize>, Failure> {
    Ok(match name {
        Some("all") => (0..model.system.meshes.len()).collect(),
        other => vec![mesh_index(model, other)?],
    })
}

/// The inputs of ISO 6336-1's dynamic factor K_v (method B) that the model
/// lacks; the model gives the geometry, stiffness, load and inertias.
#[derive(Debug, Args)]
pub struct IsoArgs {
    /// Accuracy grade by ISO 1328-1 (1 to 11) for K_v.
    #[arg(long, default_value_t = IsoInputs::default().accuracy_grade, allow_hyphen_values = true, value_parser = crate::flags::finite)]
    pub accuracy_grade: f64,
    /// Face width in mm for K_v (the model's mesh stiffness over it is the
    /// standard's c_gamma_alpha: 1e9 N/m over 50 mm is 20 N/(mm um)).
    #[arg(long, default_value_t = IsoInputs::default().face_width_mm, allow_hyphen_values = true, value_parser = crate::flags::finite)]
    pub face_width_mm: f64,
    /// Application factor K_A for K_v's line load.
    #[arg(long, default_value_t = IsoInputs::default().application_factor, allow_hyphen_values = true, value_parser = crate::flags::finite)]
    pub application_factor: f64,
    /// Tip relief C_a in um for K_v (default: the standard's running-in
    /// amount C_ay of case-hardened steel, 2.0 um).
    #[arg(long, allow_hyphen_values = true, value_parser = crate::flags::finite)]
    pub tip_relief_um: Option<f64>,
}

impl IsoArgs {
    /// The solver's inputs, checked (a refusal names the flag's value).
    pub fn inputs(&self) -> Result<IsoInputs, Failure> {
        let inputs = IsoInputs {
            accuracy_grade: self.accuracy_grade,
            face_width_mm: self.face_width_mm,
            application_factor: self.application_factor,
            tip_relief_um: self.tip_relief_um,
            ..IsoInputs::default()
        };
        inputs.validate()?;
        Ok(inputs)
    }
}
