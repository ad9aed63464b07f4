//! The subcommands, one module each: its options (a clap `Args` struct) and
//! its `run`. The sweeps share [`crate::sweep::run`]; every command writes
//! through [`crate::output`].

mod bench;
mod bifurcation;
mod boundaries;
mod campbell;
mod figure;
mod frf;
mod instability;
mod keys;
mod lyapunov;
mod map;
mod merge;
mod modes;
mod paper;
mod params;
mod presets;
mod sharing;
mod simulate;

use crate::args::ParamArgs;
use crate::failure::Failure;
use clap::Subcommand;

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Print the full parameter set (defaults plus --params/--set) as JSON.
    #[command(allow_negative_numbers = true)]
    Params {
        #[command(flatten)]
        p: ParamArgs,
    },
    /// List every parameter key with unit, range and meaning.
    #[command(allow_negative_numbers = true)]
    Keys(keys::KeysArgs),
    /// Static equilibrium, mesh forces and natural modes.
    #[command(allow_negative_numbers = true)]
    Modes {
        #[command(flatten)]
        p: ParamArgs,
    },
    /// Steady-state response at one dimensionless mesh frequency.
    #[command(allow_negative_numbers = true)]
    Simulate(simulate::SimulateArgs),
    /// Bifurcation diagram: Poincaré samples over a sweep of Omega.
    #[command(allow_negative_numbers = true)]
    Bifurcation(bifurcation::BifurcationArgs),
    /// Frequency response: the periodic branch in Omega by harmonic balance
    /// or shooting, with arclength continuation.
    #[command(allow_negative_numbers = true)]
    Frf(frf::FrfArgs),
    /// Impact-regime map over Omega (columns) and a parameter (rows).
    #[command(allow_negative_numbers = true)]
    Map(map::MapArgs),
    /// The map's boundaries traced as curves in Omega and one key: folds
    /// (the jump), contact changes, cusps.
    #[command(allow_negative_numbers = true)]
    Boundaries(boundaries::BoundariesArgs),
    /// Campbell diagram: the natural frequencies against input speed (rpm),
    /// the mesh orders, and their crossings (critical speeds) with each
    /// mode's excitation by the planets' phasing.
    #[command(allow_negative_numbers = true)]
    Campbell(campbell::CampbellArgs),
    /// How the planets share the load over a sweep of speed: each planet's
    /// largest mesh force and the load-sharing factor (largest over mean)
    /// per mesh kind, in-phase against sequential phasing.
    #[command(allow_negative_numbers = true)]
    Sharing(sharing::SharingArgs),
    /// Largest Lyapunov exponent of the Poincaré map over a sweep of Omega.
    #[command(allow_negative_numbers = true)]
    Lyapunov(lyapunov::LyapunovArgs),
    /// Parametric instability over Omega: the Floquet spectral radius of the
    /// linear system with every tooth pair in contact (above 1, motion large
    /// against the backlash grows without bound).
    #[command(allow_negative_numbers = true)]
    Instability(instability::InstabilityArgs),
    /// Join the JSON outputs of all shards of one bifurcation, map or figure
    /// run.
    #[command(allow_negative_numbers = true)]
    Merge(merge::MergeArgs),
    /// Print every preset (the paper's figures as settings) as JSON.
    Presets,
    /// Compute every panel of one of the paper's figures: SVG, JSON, CSV per panel.
    Figure {
        #[command(flatten)]
        args: figure::FigureArgs,
    },
    /// Measure the solver's speed (medians over repeats).
    #[command(allow_negative_numbers = true)]
    Bench(bench::BenchArgs),
    /// Print this command line's reference in Markdown (docs/cli.md).
    #[command(hide = true)]
    HelpMarkdown,
    /// The paper's claims checked: run the commands docs/paper.md quotes
    /// and print their record, or render docs/paper.md and the page's
    /// claims from it (--root).
    Paper(paper::PaperArgs),
}

/// Runs one subcommand.
pub fn run(command: Command) -> Result<(), Failure> {
    match command {
        Command::Params { p } => params::run(&p),
        Command::Keys(a) => keys::run(&a),
        Command::Modes { p } => modes::run(&p),
        Command::Simulate(a) => simulate::run(&a),
        Command::Bifurcation(a) => bifurcation::run(&a),
        Command::Frf(a) => frf::run(&a),
        Command::Map(a) => map::run(&a),
        Command::Boundaries(a) => boundaries::run(&a),
        Command::Campbell(a) => campbell::run(&a),
        Command::Sharing(a) => sharing::run(&a),
        Command::Lyapunov(a) => lyapunov::run(&a),
        Command::Instability(a) => instability::run(&a),
        Command::Merge(a) => merge::run(&a),
        Command::Presets => presets::run(),
        Command::Figure { args } => crate::output::emit(&figure::run(&args)?),
        Command::Bench(a) => bench::run_command(&a),
        Command::HelpMarkdown => crate::output::emit_text(&crate::reference::markdown()),
        Command::Paper(a) => paper::run(&a),
    }
}
