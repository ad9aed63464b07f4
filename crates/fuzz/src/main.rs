//! `gearshock-fuzz`: the long run of the fuzz harness (see the crate docs),
//! e.g. `cargo run --release -p fuzz -- --inputs 1000000` for a million
//! inputs per target. Prints each target's inputs, failures and rate; exits
//! 1 if any input panicked or broke an invariant.

use std::process::ExitCode;
use std::time::Instant;

fn main() -> ExitCode {
    let mut inputs: u64 = 1_000_000;
    let mut seed: u64 = 1;
    let mut only: Option<String> = None;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let value = args.next();
        let parsed = value.as_deref().and_then(|v| v.parse::<u64>().ok());
        match (a.as_str(), parsed) {
            ("--inputs", Some(n)) => inputs = n,
            ("--seed", Some(s)) => seed = s,
            ("--target", _) if value.is_some() => only = value,
            _ => {
                eprintln!(
                    "usage: gearshock-fuzz [--inputs N (per target, default 1000000)] [--seed S] [--target {}]",
                    fuzz::TARGETS.join("|")
                );
                return ExitCode::from(2);
            }
        }
    }
    // Panics are caught and counted; the default hook would print each one.
    std::panic::set_hook(Box::new(|_| {}));
    let mut failed = false;
    let t_all = Instant::now();
    for &target in fuzz::TARGETS {
        if only.as_deref().is_some_and(|o| o != target) {
            continue;
        }
        let t0 = Instant::now();
        let report = fuzz::run(target, seed, inputs);
        let s = t0.elapsed().as_secs_f64();
        println!(
            "{target}: {} inputs, {} failures, {s:.1} s ({:.0} inputs/s)",
            report.inputs,
            report.failures.len(),
            report.inputs as f64 / s.max(1e-9)
        );
        for f in report.failures.iter().take(5) {
            println!("  failure: {f}");
        }
        failed |= !report.failures.is_empty();
    }
    println!("total {:.1} s", t_all.elapsed().as_secs_f64());
    if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}
