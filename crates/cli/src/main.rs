//! `gearshock`: the native command line of the gearshock solver, for batch
//! sweeps on a workstation or a cluster and for checking results.
//!
//! JSON goes to stdout (or CSV with `--format csv`), a progress bar to stderr
//! when stderr is a terminal (plain progress lines with `--progress`). Bad
//! input exits with code 2 and one line that names the offending flag, key
//! or value; a solver failure exits with 1. Every option is checked before
//! any work starts, input files are read through a size limit, and each
//! command's total work and memory are capped ([`budget`]).

mod bench;
mod csv;
mod figure;
mod presets;
mod progress;

use clap::{Args, Parser, Subcommand, ValueEnum};
use serde_json::Value;
use solver::hbm::{FrfContinuation, FrfSpec, Method};
use solver::keys;
use solver::lyapunov::{largest_exponent, LyapunovOptions};
use solver::map::{MapSpec, RegimeMap};
use solver::parametric::Parametric;
use solver::params::{ModelKind, ModelParams};
use solver::steady::{steady_state, Model, SteadyOptions};
use solver::sweep::{canonical_order, BifurcationSweep, Direction, Directions, SweepSpec};
use solver::SolverError;
use std::io::Read;
use std::io::Write;
use std::process::ExitCode;

/// Vibration and tooth impacts of a compound planetary gear set with backlash.
#[derive(Debug, Parser)]
#[command(name = "gearshock", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
enum Format {
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
enum ModelArg {
    Ravigneaux,
    GearPair,
}

/// Parameter selection shared by every subcommand.
#[derive(Debug, Args)]
struct ParamArgs {
    /// Built-in model.
    #[arg(long, value_enum)]
    model: Option<ModelArg>,
    /// A JSON file with a flat object of parameter keys (see `gearshock keys`).
    #[arg(long, value_name = "FILE.json")]
    params: Option<std::path::PathBuf>,
    /// Set one parameter, e.g. `--set backlash_um=200` (repeatable).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
    /// Output format (jsonl streams sweeps point by point).
    #[arg(long, value_enum, default_value = "json")]
    format: Format,
    /// Print progress lines on stderr even when it is not a terminal (logs,
    /// cluster jobs): one line per whole percent.
    #[arg(long)]
    progress: bool,
}

/// Options of a steady-state run.
#[derive(Debug, Args)]
struct RunArgs {
    /// Maximum transient mesh periods (the transient ends early once the
    /// Poincaré samples have settled, unless --full-transient).
    #[arg(long, default_value_t = 300)]
    transient_periods: u32,
    /// Recorded mesh periods.
    #[arg(long, default_value_t = 100)]
    record_periods: u32,
    /// Always integrate every transient period.
    #[arg(long)]
    full_transient: bool,
    /// Relative tolerance of the integrator.
    #[arg(long, default_value_t = solver::steady::DEFAULT_RTOL, allow_hyphen_values = true)]
    rtol: f64,
    /// Absolute tolerance as a mesh deflection (m).
    #[arg(long, default_value_t = solver::steady::DEFAULT_ATOL_M, allow_hyphen_values = true)]
    atol: f64,
}

impl RunArgs {
    fn apply(&self, opts: &mut SteadyOptions) {
        opts.transient_periods = self.transient_periods;
        opts.record_periods = self.record_periods;
        opts.early_settle = !self.full_transient;
        opts.rtol = self.rtol;
        opts.atol_m = self.atol;
    }
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Print the full parameter set (defaults plus --params/--set) as JSON.
    #[command(allow_negative_numbers = true)]
    Params {
        #[command(flatten)]
        p: ParamArgs,
    },
    /// List every parameter key with unit, range and meaning.
    #[command(allow_negative_numbers = true)]
    Keys {
        /// Print a Markdown table (as in the README).
        #[arg(long)]
        markdown: bool,
    },
    /// Static equilibrium, mesh forces and natural modes.
    #[command(allow_negative_numbers = true)]
    Modes {
        #[command(flatten)]
        p: ParamArgs,
    },
    /// Steady-state response at one dimensionless mesh frequency.
    #[command(allow_negative_numbers = true)]
    Simulate {
        #[command(flatten)]
        p: ParamArgs,
        /// Dimensionless mesh frequency Omega = omega / omega_ref.
        #[arg(long, allow_hyphen_values = true)]
        omega: f64,
        #[command(flatten)]
        run: RunArgs,
        /// Mesh to report (e.g. s1a1, s2b2, a1b1, rb3; pg for the gear pair).
        #[arg(long)]
        mesh: Option<String>,
        /// Highest harmonic order in the spectrum.
        #[arg(long, default_value_t = 8.0, allow_hyphen_values = true)]
        max_order: f64,
    },
    /// Bifurcation diagram: Poincaré samples over a sweep of Omega.
    #[command(allow_negative_numbers = true)]
    Bifurcation {
        #[command(flatten)]
        p: ParamArgs,
        /// First Omega.
        #[arg(long, allow_hyphen_values = true)]
        omega_from: f64,
        /// Last Omega.
        #[arg(long, allow_hyphen_values = true)]
        omega_to: f64,
        /// Number of Omega points.
        #[arg(long, default_value_t = 200)]
        points: u32,
        /// Sweep direction: up, down or both (up then down).
        #[arg(long, default_value = "up")]
        direction: String,
        #[command(flatten)]
        run: RunArgs,
        /// Mesh to report, or `all`.
        #[arg(long)]
        mesh: Option<String>,
        /// Number of interleaved continuation chains (see the README).
        #[arg(long)]
        chains: Option<u32>,
        /// Compute only shard i of n (every n-th point from i; implies --chains n).
        #[arg(long, value_name = "i/n")]
        shard: Option<String>,
    },
    /// Frequency response by harmonic balance with arclength continuation.
    #[command(allow_negative_numbers = true)]
    Frf {
        #[command(flatten)]
        p: ParamArgs,
        /// First Omega.
        #[arg(long, allow_hyphen_values = true)]
        omega_from: f64,
        /// Last Omega.
        #[arg(long, allow_hyphen_values = true)]
        omega_to: f64,
        /// Nominal points: the largest continuation step is range / points.
        #[arg(long, default_value_t = 400)]
        points: u32,
        /// Harmonics H (1 ..= 40).
        #[arg(long, default_value_t = 7)]
        harmonics: usize,
        /// aft (time grid, any H), exact (closed-form integration between the
        /// contact switches, any H) or describing-function (the seed's Eqs. 9-13, H = 1).
        #[arg(long, default_value = "exact")]
        method: String,
        /// Continue up from --omega-from or down from --omega-to.
        #[arg(long, default_value = "up")]
        direction: String,
        /// AFT time-grid size (default: max(64 H, 256) rounded up to a power of two).
        #[arg(long)]
        grid: Option<usize>,
        /// Skip the Floquet stability of each point.
        #[arg(long)]
        no_stability: bool,
        /// Mesh to report, or `all`.
        #[arg(long)]
        mesh: Option<String>,
    },
    /// Impact-regime map over Omega (columns) and a parameter (rows).
    #[command(allow_negative_numbers = true)]
    Map {
        #[command(flatten)]
        p: ParamArgs,
        /// First Omega.
        #[arg(long, allow_hyphen_values = true)]
        omega_from: f64,
        /// Last Omega.
        #[arg(long, allow_hyphen_values = true)]
        omega_to: f64,
        /// Number of Omega columns.
        #[arg(long, default_value_t = 100)]
        omega_points: u32,
        /// The row parameter: any numeric key (e.g. backlash_um, te_um).
        #[arg(long, default_value = "backlash_um")]
        key: String,
        /// First value of the row parameter.
        #[arg(long, allow_hyphen_values = true)]
        value_from: f64,
        /// Last value of the row parameter.
        #[arg(long, allow_hyphen_values = true)]
        value_to: f64,
        /// Number of rows.
        #[arg(long, default_value_t = 40)]
        value_points: u32,
        #[command(flatten)]
        run: RunArgs,
        /// Mesh whose regime is mapped (default: the worst over all meshes).
        #[arg(long)]
        mesh: Option<String>,
        /// Compute only shard i of n (rows i, i + n, ...).
        #[arg(long, value_name = "i/n")]
        shard: Option<String>,
    },
    /// Largest Lyapunov exponent of the Poincaré map over a sweep of Omega.
    #[command(allow_negative_numbers = true)]
    Lyapunov {
        #[command(flatten)]
        p: ParamArgs,
        /// First Omega.
        #[arg(long, allow_hyphen_values = true)]
        omega_from: f64,
        /// Last Omega.
        #[arg(long, allow_hyphen_values = true)]
        omega_to: f64,
        /// Number of Omega points.
        #[arg(long, default_value_t = 50)]
        points: u32,
        /// Transient mesh periods before measuring.
        #[arg(long, default_value_t = 300)]
        transient_periods: u32,
        /// Mesh periods averaged.
        #[arg(long, default_value_t = 200)]
        periods: u32,
    },
    /// Parametric instability over Omega: the Floquet spectral radius of the
    /// linear system with every tooth pair in contact (above 1, motion large
    /// against the backlash grows without bound).
    #[command(allow_negative_numbers = true)]
    Instability {
        #[command(flatten)]
        p: ParamArgs,
        /// First Omega.
        #[arg(long, allow_hyphen_values = true)]
        omega_from: f64,
        /// Last Omega.
        #[arg(long, allow_hyphen_values = true)]
        omega_to: f64,
        /// Number of Omega points.
        #[arg(long, default_value_t = 200)]
        points: u32,
    },
    /// Join the JSON outputs of all shards of one sweep.
    #[command(allow_negative_numbers = true)]
    Merge {
        /// Shard outputs (JSON files).
        files: Vec<std::path::PathBuf>,
        /// Directory for a figure's files (shards of `gearshock figure ID
        /// --shard i/n` only).
        #[arg(long, value_name = "DIR")]
        out: Option<std::path::PathBuf>,
    },
    /// Print every preset (the paper's figures as settings) as JSON.
    Presets,
    /// Compute every panel of one of the paper's figures: SVG, JSON, CSV per panel.
    Figure {
        #[command(flatten)]
        args: figure::FigureArgs,
    },
    /// Measure the solver's speed (medians over repeats).
    #[command(allow_negative_numbers = true)]
    Bench {
        /// Repeats per figure.
        #[arg(long, default_value_t = 5)]
        repeats: u32,
        /// Fewer points and periods (for smoke tests).
        #[arg(long)]
        quick: bool,
    },
}

/// A failure and its exit code.
struct Failure {
    code: u8,
    message: String,
}

/// The solver's option names that are this program's flags (`--NAME`).
const FLAGS: &[&str] = &[
    "omega",
    "omega-from",
    "omega-to",
    "points",
    "omega-points",
    "value-points",
    "transient-periods",
    "record-periods",
    "periods",
    "rtol",
    "atol",
    "chains",
    "shard",
    "harmonics",
    "grid",
];

impl From<SolverError> for Failure {
    fn from(e: SolverError) -> Self {
        // An option the user typed is named as typed: `--omega -1`.
        if let SolverError::BadOption {
            option,
            value,
            allowed,
        } = &e
        {
            if FLAGS.contains(&option.as_str()) {
                return usage(format!(
                    "--{option} {value} is out of range: allowed {allowed}"
                ));
            }
        }
        let code = match e {
            SolverError::StepSizeTooSmall { .. }
            | SolverError::NonFinite { .. }
            | SolverError::Diverged { .. }
            | SolverError::TooManySteps { .. }
            | SolverError::NotConverged { .. }
            | SolverError::ContinuationStalled { .. }
            | SolverError::Singular { .. } => 1,
            _ => 2,
        };
        Failure {
            code,
            message: e.to_string(),
        }
    }
}

/// `points` equally spaced Omegas from `omega_from` to `omega_to` (both
/// included, each in the solver's range 0.01 ..= 20), or a usage failure
/// naming the bad option and its range.
fn omega_grid(
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
            "--points {points}: allowed 2 ..= {max_points}"
        )));
    }
    Ok((0..points)
        .map(|i| omega_from + (omega_to - omega_from) * f64::from(i) / f64::from(points - 1))
        .collect())
}

fn usage(message: impl Into<String>) -> Failure {
    Failure {
        code: 2,
        message: message.into(),
    }
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            use clap::error::ErrorKind;
            if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) {
                print!("{e}");
                return ExitCode::SUCCESS;
            }
            // One line: clap's message up to its usage block, joined.
            let text = e.render().to_string();
            let message: Vec<&str> = text
                .lines()
                .take_while(|l| !l.starts_with("Usage:") && !l.starts_with("For more information"))
                .map(str::trim)
                .filter(|l| !l.is_empty() && !l.starts_with("tip:"))
                .collect();
            let line = message.join(" ");
            eprintln!("gearshock: {}", line.trim_start_matches("error: "));
            return ExitCode::from(2);
        }
    };
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(f) => {
            eprintln!("gearshock: {}", f.message);
            ExitCode::from(f.code)
        }
    }
}

/// Largest `--params` file (bytes): a parameter set is a few kB.
const MAX_PARAMS_BYTES: u64 = 1 << 20;
/// Largest shard file `merge` reads (bytes).
const MAX_SHARD_BYTES: u64 = 256 << 20;
/// Largest total of the files `merge` reads (bytes): parsed JSON takes
/// several times its text in memory.
const MAX_MERGE_BYTES: u64 = 1 << 30;

/// A reader that fails once more than its limit has been read, so that no
/// input (`/dev/zero`, a forged file) can grow memory without bound.
struct Limited<R> {
    inner: R,
    left: u64,
}

impl<R: Read> Read for Limited<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        // Read one byte past the limit to tell "exactly the limit" from "more".
        let want = buf
            .len()
            .min(usize::try_from(self.left.saturating_add(1)).unwrap_or(usize::MAX));
        let n = self.inner.read(&mut buf[..want])?;
        if n as u64 > self.left {
            return Err(std::io::Error::other("over the size limit"));
        }
        self.left -= n as u64;
        Ok(n)
    }
}

/// Describes a size in words (e.g. "1 MiB").
fn bytes_text(n: u64) -> String {
    if n >= 1 << 30 && n.is_multiple_of(1 << 30) {
        format!("{} GiB", n >> 30)
    } else if n >= 1 << 20 && n.is_multiple_of(1 << 20) {
        format!("{} MiB", n >> 20)
    } else {
        format!("{n} bytes")
    }
}

/// Reads and parses a JSON file of at most `limit` bytes, returning the
/// value and the bytes read; the failure names `what` (the flag or
/// command), the file and `limit_text` (what the limit is).
fn read_json(
    path: &std::path::Path,
    limit: u64,
    what: &str,
    limit_text: &str,
) -> Result<(Value, u64), Failure> {
    let shown = path.display();
    let too_large = || usage(format!("{what} {shown}: larger than {limit_text}"));
    let file = std::fs::File::open(path).map_err(|e| usage(format!("{what} {shown}: {e}")))?;
    if file
        .metadata()
        .is_ok_and(|m| m.is_file() && m.len() > limit)
    {
        return Err(too_large());
    }
    let mut reader = Limited {
        inner: std::io::BufReader::new(file),
        left: limit,
    };
    let value = serde_json::from_reader(&mut reader).map_err(|e| {
        if e.is_io() && e.to_string().contains("over the size limit") {
            too_large()
        } else if e.is_io() {
            usage(format!("{what} {shown}: {e}"))
        } else {
            usage(format!("{what} {shown}: not JSON: {e}"))
        }
    })?;
    Ok((value, limit - reader.left))
}

fn model_kind(m: ModelArg) -> ModelKind {
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
fn load_params(p: &ParamArgs) -> Result<ModelParams, Failure> {
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
    Ok(params)
}

/// Caps on the work and memory of one command (one shard of a sharded
/// run), as `map` caps its cells: each option has its own range, and these
/// bound their product, so no combination runs for days or fills memory
/// before writing anything.
mod budget {
    /// Most mesh periods one command integrates (some hours on one core at
    /// the 20-70 us a period takes; split larger runs with `--shard`).
    pub const MAX_PERIODS: u64 = 100_000_000;
    /// Most Poincaré samples (points x directions x meshes x recorded
    /// periods) one bifurcation command keeps for its output (some hundred
    /// MB once written as JSON).
    pub const MAX_SAMPLES: u64 = 2_000_000;
    /// Most `--points x (2 --harmonics + 1)^3` of one frequency response: a
    /// Newton step solves a dense system of (2 H + 1) unknowns per
    /// coordinate, so its work grows like the cube; this allows every point
    /// count up to H = 27 and some hours at H = 40.
    pub const MAX_FRF_WORK: u64 = 2_000_000_000;
}

/// Checks `periods` (the product `formula` of the options) against
/// [`budget::MAX_PERIODS`]; `split` says how to split a larger run.
fn check_work(periods: u64, formula: &str, split: &str) -> Result<(), Failure> {
    if periods > budget::MAX_PERIODS {
        return Err(usage(format!(
            "{formula} = {periods} mesh periods is more than the {} one command may integrate: \
             use fewer points or periods, or {split}",
            budget::MAX_PERIODS
        )));
    }
    Ok(())
}

fn mesh_index(model: &Model, name: Option<&str>) -> Result<usize, Failure> {
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

fn parse_shard(s: &str) -> Result<(u32, u32), Failure> {
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

/// Writes a result as JSON, or as the CSV `csv` makes of that JSON.
fn output(format: Format, value: &Value, csv: fn(&Value) -> String) -> Result<(), Failure> {
    match format {
        Format::Json => emit(value),
        Format::Jsonl => {
            emit_line(value);
            Ok(())
        }
        Format::Csv => {
            emit_text(&csv(value));
            Ok(())
        }
    }
}

fn emit(value: &Value) -> Result<(), Failure> {
    let text = serde_json::to_string_pretty(value).map_err(|e| Failure {
        code: 1,
        message: format!("cannot write JSON: {e}"),
    })?;
    let mut out = std::io::stdout().lock();
    // A closed pipe (e.g. `| head`) is not an error worth reporting.
    let _ = writeln!(out, "{text}");
    Ok(())
}

/// Writes one JSON line and flushes it, so a reader (or a killed job's
/// log) has every line written so far.
fn emit_line(value: &Value) {
    let mut out = std::io::stdout().lock();
    let _ = writeln!(out, "{value}");
    let _ = out.flush();
}

/// Streams a sweep as JSON lines when the format asks for it: the header
/// at once, then [`Stream::item`] per result, then [`Stream::finish`].
struct Stream {
    on: bool,
    items: usize,
}

impl Stream {
    fn new(format: Format, header: impl FnOnce() -> Value) -> Self {
        let on = format == Format::Jsonl;
        if on {
            emit_line(&header());
        }
        Stream { on, items: 0 }
    }

    /// Writes `value` if streaming; returns whether it did.
    fn item(&mut self, value: impl FnOnce() -> Value) -> bool {
        if self.on {
            emit_line(&value());
            self.items += 1;
        }
        self.on
    }

    /// The closing line, so a reader knows the stream is whole.
    fn finish(self, what: &str) {
        if self.on {
            emit_line(&serde_json::json!({ "complete": true, what: self.items }));
        }
    }
}

fn emit_text(text: &str) {
    let mut out = std::io::stdout().lock();
    let _ = out.write_all(text.as_bytes());
}

fn run(cli: Cli) -> Result<(), Failure> {
    match cli.command {
        Command::Params { p } => {
            let params = load_params(&p)?;
            // Building checks cross-field rules (tooth counts, torque balance).
            Model::new(&params)?;
            match p.format {
                Format::Json => emit(&Value::Object(keys::to_json(&params))),
                Format::Jsonl => {
                    emit_line(&Value::Object(keys::to_json(&params)));
                    Ok(())
                }
                Format::Csv => {
                    emit_text(&csv::params(&params));
                    Ok(())
                }
            }
        }
        Command::Keys { markdown } => {
            emit_text(&if markdown {
                csv::keys_markdown()
            } else {
                csv::keys_text()
            });
            Ok(())
        }
        Command::Modes { p } => {
            let params = load_params(&p)?;
            let model = Model::new(&params)?;
            match p.format {
                Format::Json | Format::Jsonl => {
                    output(p.format, &report::modes_json(&model), |_| String::new())
                }
                Format::Csv => {
                    emit_text(&csv::modes(&model));
                    Ok(())
                }
            }
        }
        Command::Simulate {
            p,
            omega,
            run,
            mesh,
            max_order,
        } => {
            let params = load_params(&p)?;
            let model = Model::new(&params)?;
            let j = mesh_index(&model, mesh.as_deref())?;
            let mut opts = SteadyOptions::new(omega);
            run.apply(&mut opts);
            opts.history_meshes = vec![j];
            if !(max_order.is_finite() && max_order > 0.0) {
                return Err(usage(format!(
                    "--max-order {max_order}: must be a positive number"
                )));
            }
            opts.validate()?;
            let ss = steady_state(&model, &opts, None)?;
            match p.format {
                Format::Json | Format::Jsonl => output(
                    p.format,
                    &report::simulate_json(&model, &ss, j, max_order),
                    |_| String::new(),
                ),
                Format::Csv => {
                    emit_text(&csv::history(&ss, j));
                    Ok(())
                }
            }
        }
        Command::Bifurcation {
            p,
            omega_from,
            omega_to,
            points,
            direction,
            run,
            mesh,
            chains,
            shard,
        } => {
            let params = load_params(&p)?;
            let model = Model::new(&params)?;
            let mut spec = SweepSpec::new(omega_from, omega_to, points);
            run.apply(&mut spec.steady);
            spec.directions = Directions::from_name(&direction).ok_or_else(|| {
                usage(format!(
                    "--direction {}: allowed up, down, both",
                    keys::truncate(&direction, 20)
                ))
            })?;
            spec.meshes = match mesh.as_deref() {
                Some("all") => (0..model.system.meshes.len()).collect(),
                other => vec![mesh_index(&model, other)?],
            };
            if let Some(s) = &shard {
                let (i, n) = parse_shard(s)?;
                if let Some(c) = chains {
                    if c != n {
                        return Err(usage(format!(
                            "--shard {s} needs --chains {n} (got --chains {c})"
                        )));
                    }
                }
                spec.chains = n;
                spec.shard = Some(i);
            } else if let Some(c) = chains {
                spec.chains = c;
            }
            let mut sweep = BifurcationSweep::new(model.clone(), spec.clone())?;
            let total = sweep.total() as u64;
            let (transient, record) = (
                u64::from(run.transient_periods),
                u64::from(run.record_periods),
            );
            check_work(
                total * (transient + record),
                &format!(
                    "{total} points (--points over --direction and --shard) x (--transient-periods {transient} + --record-periods {record})"
                ),
                "split the sweep with --shard i/n",
            )?;
            let samples = total * spec.meshes.len() as u64 * record;
            // Streamed points are not kept, so only the work is capped then.
            if samples > budget::MAX_SAMPLES && p.format != Format::Jsonl {
                return Err(usage(format!(
                    "{total} points x {} meshes (--mesh) x --record-periods {record} = {samples} Poincaré samples \
                     is more than the {} one command may keep: use fewer points, meshes or recorded periods, \
                     stream them with --format jsonl, or split the sweep with --shard i/n",
                    spec.meshes.len(),
                    budget::MAX_SAMPLES
                )));
            }
            let mut bar = progress::Progress::new(sweep.total(), "points", p.progress);
            let mut stream = Stream::new(p.format, || {
                serde_json::json!({
                    "model": model.system.model.name(),
                    "params": Value::Object(keys::to_json(&params)),
                    "spec": report::sweep_spec_json(&model, &spec),
                })
            });
            let mut pts = Vec::new();
            while !sweep.is_finished() {
                for pt in sweep.advance(1) {
                    if !stream.item(|| report::sweep_point_json(&model, &pt)) {
                        pts.push(pt);
                    }
                }
                bar.update(sweep.done());
            }
            bar.finish();
            if p.format == Format::Jsonl {
                stream.finish("points");
                return Ok(());
            }
            canonical_order(&mut pts);
            let value = report::sweep_json(&model, &params, &spec, &pts);
            output(p.format, &value, csv::sweep)
        }
        Command::Frf {
            p,
            omega_from,
            omega_to,
            points,
            harmonics,
            method,
            direction,
            grid,
            no_stability,
            mesh,
        } => {
            let params = load_params(&p)?;
            let model = Model::new(&params)?;
            let mut spec = FrfSpec::new(omega_from, omega_to, points);
            spec.harmonics = harmonics;
            spec.method = Method::from_name(&method).ok_or_else(|| {
                usage(format!(
                    "--method {}: allowed aft, exact, describing-function",
                    keys::truncate(&method, 30)
                ))
            })?;
            spec.direction = Direction::from_name(&direction).ok_or_else(|| {
                usage(format!(
                    "--direction {}: allowed up, down",
                    keys::truncate(&direction, 20)
                ))
            })?;
            spec.grid = grid;
            spec.stability = !no_stability;
            let meshes: Vec<usize> = match mesh.as_deref() {
                Some("all") => (0..model.system.meshes.len()).collect(),
                other => vec![mesh_index(&model, other)?],
            };
            // Larger H is refused by the solver's own check, naming it.
            if harmonics <= 40 {
                let work = u64::from(points) * (2 * harmonics as u64 + 1).pow(3);
                if work > budget::MAX_FRF_WORK {
                    return Err(usage(format!(
                        "--points {points} x (2 x --harmonics {harmonics} + 1)^3 = {work} is more than the {} \
                         one frequency response may take: use fewer points or harmonics",
                        budget::MAX_FRF_WORK
                    )));
                }
            }
            let mut c = FrfContinuation::new(&model, spec)?;
            let mut bar = progress::Progress::new(1000, "per mille of the range", p.progress);
            let mut branch = Vec::new();
            let mut failure = None;
            while !c.is_finished() {
                match c.advance(16) {
                    Ok(pts) => branch.extend(pts),
                    Err(e) => {
                        failure = Some(e);
                        break;
                    }
                }
                bar.update((c.progress() * 1000.0) as usize);
            }
            bar.finish();
            let value = report::frf_json(&model, &params, &c, &branch, &meshes, failure.as_ref());
            output(p.format, &value, csv::frf)?;
            // Restarts and left-out gaps are in the JSON; say them here too.
            for n in c.notes() {
                eprintln!("gearshock: note: {n}");
            }
            if failure.is_none() && c.left_at_start() {
                eprintln!(
                    "gearshock: note: the branch turned back at a fold and left the range at its start; \
                     continue from the other end with --direction {} to see the rest",
                    if c.spec().direction == Direction::Up { "down" } else { "up" }
                );
            }
            match failure {
                // The partial branch is written (marked `complete: false`),
                // and the failure is reported with exit code 1.
                Some(e) => Err(Failure {
                    code: 1,
                    message: format!("{e} (the branch up to there was written, marked incomplete)"),
                }),
                None => Ok(()),
            }
        }
        Command::Map {
            p,
            omega_from,
            omega_to,
            omega_points,
            key,
            value_from,
            value_to,
            value_points,
            run,
            mesh,
            shard,
        } => {
            let params = load_params(&p)?;
            let model = Model::new(&params)?;
            // `+ 0.0` turns a typed -0 into 0, so the echoed spec reads 0.
            let mut spec = MapSpec::new(
                (omega_from, omega_to, omega_points),
                &key,
                (value_from + 0.0, value_to + 0.0, value_points),
            );
            run.apply(&mut spec.steady);
            spec.mesh = match mesh.as_deref() {
                None | Some("worst") => None,
                other => Some(mesh_index(&model, other)?),
            };
            if let Some(s) = &shard {
                spec.shard = Some(parse_shard(s)?);
            }
            let mut map = RegimeMap::new(&params, spec.clone())?;
            let total = map.total() as u64;
            check_work(
                total * (u64::from(run.transient_periods) + u64::from(run.record_periods)),
                &format!(
                    "{total} cells (--omega-points x --value-points over --shard) x (--transient-periods {} + --record-periods {})",
                    run.transient_periods, run.record_periods
                ),
                "split the map with --shard i/n",
            )?;
            let mut bar = progress::Progress::new(map.total(), "cells", p.progress);
            let mut stream = Stream::new(p.format, || {
                serde_json::json!({
                    "model": model.system.model.name(),
                    "params": Value::Object(keys::to_json(&params)),
                    "spec": report::map_spec_json(&model, &spec),
                })
            });
            let mut cells = Vec::new();
            while !map.is_finished() {
                for cell in map.advance(1) {
                    if !stream.item(|| report::map_cell_json(&cell)) {
                        cells.push(cell);
                    }
                }
                bar.update(map.done());
            }
            bar.finish();
            if p.format == Format::Jsonl {
                stream.finish("cells");
                return Ok(());
            }
            let value = report::map_json(&model, &params, &spec, &cells);
            output(p.format, &value, csv::map)
        }
        Command::Lyapunov {
            p,
            omega_from,
            omega_to,
            points,
            transient_periods,
            periods,
        } => {
            let params = load_params(&p)?;
            let model = Model::new(&params)?;
            let omegas = omega_grid(omega_from, omega_to, points, 10_000)?;
            let mut opts = LyapunovOptions::new(omega_from);
            opts.transient_periods = transient_periods;
            opts.periods = periods;
            // Every option checked before the first point is computed.
            opts.validate()?;
            // The transient once, then two trajectories over the periods.
            check_work(
                u64::from(points) * (u64::from(transient_periods) + 2 * u64::from(periods)),
                &format!(
                    "--points {points} x (--transient-periods {transient_periods} + 2 x --periods {periods})"
                ),
                "split the Omega range over several runs",
            )?;
            let mut bar = progress::Progress::new(omegas.len(), "points", p.progress);
            let mut stream = Stream::new(p.format, || {
                serde_json::json!({
                    "model": model.system.model.name(),
                    "params": Value::Object(keys::to_json(&params)),
                    "spec": report::lyapunov_spec_json(&opts),
                })
            });
            let mut out = Vec::new();
            let mut state: Option<Vec<f64>> = None;
            for (i, omega) in omegas.into_iter().enumerate() {
                opts.omega = omega;
                let l = largest_exponent(&model, &opts, state.as_deref())?;
                state = Some(l.end_state.clone());
                if !stream.item(|| report::lyapunov_point_json(&l)) {
                    out.push(l);
                }
                bar.update(i + 1);
            }
            bar.finish();
            if p.format == Format::Jsonl {
                stream.finish("points");
                return Ok(());
            }
            let value = report::lyapunov_json(&model, &params, &opts, &out);
            output(p.format, &value, csv::lyapunov)
        }
        Command::Instability {
            p,
            omega_from,
            omega_to,
            points,
        } => {
            let params = load_params(&p)?;
            let model = Model::new(&params)?;
            let omegas = omega_grid(omega_from, omega_to, points, 100_000)?;
            let engaged = Parametric::new(&model)?;
            let mut bar = progress::Progress::new(omegas.len(), "points", p.progress);
            let mut stream = Stream::new(p.format, || {
                serde_json::json!({
                    "model": model.system.model.name(),
                    "params": Value::Object(keys::to_json(&params)),
                })
            });
            let mut out = Vec::new();
            for (i, omega) in omegas.into_iter().enumerate() {
                let point = engaged.at(omega)?;
                if !stream.item(|| report::instability_point_json(&point)) {
                    out.push(point);
                }
                bar.update(i + 1);
            }
            bar.finish();
            let bands = report::instability_bands(&out);
            let text: Vec<String> = bands
                .iter()
                .map(|(a, b)| format!("Omega {a:.4} to {b:.4}"))
                .collect();
            eprintln!(
                "gearshock: unstable bands of the engaged system: {}",
                if text.is_empty() {
                    "none in the scanned range".to_string()
                } else {
                    text.join(", ")
                }
            );
            if p.format == Format::Jsonl {
                stream.finish("points");
                return Ok(());
            }
            let value = report::instability_json(&model, &params, &out);
            output(p.format, &value, csv::instability)
        }
        Command::Merge { files, out } => {
            if files.is_empty() {
                return Err(usage("merge: give the shard JSON files to join"));
            }
            if files.len() as u64 > report::MAX_SHARDS {
                return Err(usage(format!(
                    "merge: {} files given: allowed at most {} shards",
                    files.len(),
                    report::MAX_SHARDS
                )));
            }
            let mut shards = Vec::new();
            let mut left = MAX_MERGE_BYTES;
            for f in &files {
                let (limit, limit_text) = if left < MAX_SHARD_BYTES {
                    (
                        left,
                        format!(
                            "what is left of the {} allowed for all files together",
                            bytes_text(MAX_MERGE_BYTES)
                        ),
                    )
                } else {
                    (
                        MAX_SHARD_BYTES,
                        format!("the {} allowed per file", bytes_text(MAX_SHARD_BYTES)),
                    )
                };
                let (v, read) = read_json(f, limit, "merge:", &limit_text)?;
                left -= read;
                shards.push(v);
            }
            // Messages name each shard by its file.
            let names: Vec<String> = files.iter().map(|f| f.display().to_string()).collect();
            if shards
                .first()
                .is_some_and(|v| v.get("figure_shard").is_some())
            {
                emit(&figure::shard::merge(&shards, &names, out.as_deref())?)
            } else if out.is_some() {
                Err(usage(
                    "merge --out: only figure shards (gearshock figure ID --shard i/n) write files",
                ))
            } else if shards.first().is_some_and(|v| v.get("cells").is_some()) {
                emit(&report::merge_map_files(&shards, &names)?)
            } else {
                emit(&report::merge_sweep_files(&shards, &names)?)
            }
        }
        Command::Presets => emit(&presets::all_json()),
        Command::Figure { args } => emit(&figure::run(&args)?),
        Command::Bench { repeats, quick } => {
            if repeats == 0 || repeats > 100 {
                return Err(usage(format!("--repeats {repeats}: allowed 1 ..= 100")));
            }
            emit(&bench::run(repeats, quick)?)
        }
    }
}
