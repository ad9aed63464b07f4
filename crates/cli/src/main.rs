//! `gearshock`: the native command line of the gearshock solver, for batch
//! sweeps on a workstation or a cluster and for checking results.
//!
//! JSON goes to stdout (or CSV with `--format csv`), a progress bar to stderr
//! when stderr is a terminal (plain progress lines with `--progress`). Bad
//! input exits with code 2 and one line that names the offending flag, key
//! or value; a solver failure exits with 1; a failed write (a full disk,
//! `> /dev/full`) exits with 3 naming stdout or the file, a closed stdout
//! (`>&-`) with 3 before any work, and a closed pipe with 3 and no word
//! ([`output`]). Every option is checked before
//! any work starts, input files are read through a size limit, and each
//! command's total work and memory are capped ([`budget`]).
//!
//! Rooms: [`commands`] holds one module per subcommand (its options and its
//! run); [`sweep`] is the one loop every sweep runs (progress, streaming);
//! [`output`] writes stdout; [`args`] holds the options the subcommands
//! share and their checks; [`input`] reads files through a size limit
//! ([`shards`] streams a shard file's items one at a time);
//! [`budget`] caps each command's work; [`failure`] maps errors to exit codes;
//! [`flags`] words clap's refusals (the flag, its value, its real range);
//! [`reference`] renders this command line's reference, `docs/cli.md`.

mod args;
mod budget;
mod commands;
mod csv;
mod failure;
mod flags;
mod input;
mod output;
mod progress;
mod reference;
mod shards;
mod sweep;

use clap::{CommandFactory, FromArgMatches};
use std::process::ExitCode;

/// Vibration and tooth impacts of a compound planetary gear set with backlash.
#[derive(Debug, clap::Parser)]
#[command(name = "gearshock", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: commands::Command,
}

fn main() -> ExitCode {
    let argv: Vec<String> = std::env::args_os()
        .map(|a| a.to_string_lossy().into_owned())
        .collect();
    let parsed = flags::hyphen_values(Cli::command())
        .try_get_matches_from(&argv)
        .and_then(|m| Cli::from_arg_matches(&m));
    let cli = match parsed {
        Ok(cli) => cli,
        Err(e) => {
            use clap::error::ErrorKind;
            if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) {
                return match output::check_stdout()
                    .and_then(|()| output::stdout(e.to_string().as_bytes()))
                {
                    Ok(()) => ExitCode::SUCCESS,
                    Err(f) => exit(&f),
                };
            }
            output::note(&flags::message(&e, &argv));
            return ExitCode::from(2);
        }
    };
    match output::check_stdout().and_then(|()| commands::run(cli.command)) {
        Ok(()) => ExitCode::SUCCESS,
        Err(f) => exit(&f),
    }
}

/// Says why (unless the failure is a closed pipe's, which wants no word)
/// and exits with the failure's code.
fn exit(f: &failure::Failure) -> ExitCode {
    if !f.message.is_empty() {
        output::note(&f.message);
    }
    ExitCode::from(f.code)
}
