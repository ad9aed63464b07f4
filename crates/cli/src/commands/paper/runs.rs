//! The commands the paper's record quotes, run as a reader runs them: this
//! very binary, once per command line, its JSON read from stdout. Each
//! line runs once however many claims read it; lines known in advance run
//! on several cores at once ([`Runs::prefetch`]).

use crate::failure::Failure;
use crate::output::note;
use serde_json::Value;
use std::collections::HashMap;
use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::sync::{Arc, Mutex, PoisonError};

/// The results of the command lines run so far, by line.
pub struct Runs {
    exe: PathBuf,
    jobs: usize,
    progress: bool,
    done: Mutex<HashMap<String, Arc<Value>>>,
}

impl Runs {
    /// Runs with this binary, `jobs` commands at a time.
    pub fn new(jobs: usize, progress: bool) -> Result<Self, Failure> {
        let exe = std::env::current_exe().map_err(|e| Failure {
            code: 1,
            message: format!("cannot find the gearshock binary to run: {e}"),
        })?;
        Ok(Runs {
            exe,
            jobs: jobs.max(1),
            progress,
            done: Mutex::default(),
        })
    }

    /// Runs every line not yet run, `jobs` at a time.
    pub fn prefetch(&self, lines: &[String]) -> Result<(), Failure> {
        let mut todo: Vec<&String> = lines.iter().filter(|l| self.cached(l).is_none()).collect();
        todo.sort();
        todo.dedup();
        let total = todo.len();
        let queue = Mutex::new(todo.into_iter());
        let failure: Mutex<Option<Failure>> = Mutex::default();
        std::thread::scope(|s| {
            for _ in 0..self.jobs.min(total) {
                s.spawn(|| loop {
                    if lock(&failure).is_some() {
                        return;
                    }
                    let Some(line) = lock(&queue).next() else {
                        return;
                    };
                    let start = std::time::Instant::now();
                    match self.run(line) {
                        Ok(v) => {
                            let n = {
                                let mut done = lock(&self.done);
                                done.insert(line.clone(), Arc::new(v));
                                done.len()
                            };
                            if self.progress {
                                note(&format!(
                                    "{n} commands run ({total} in this batch); {:.1} s: {line}",
                                    start.elapsed().as_secs_f64()
                                ));
                            }
                        }
                        Err(f) => {
                            lock(&failure).get_or_insert(f);
                            return;
                        }
                    }
                });
            }
        });
        match failure.into_inner().unwrap_or_else(PoisonError::into_inner) {
            Some(f) => Err(f),
            None => Ok(()),
        }
    }

    /// The JSON a command line prints, run now if not run before.
    pub fn get(&self, line: &str) -> Result<Arc<Value>, Failure> {
        if let Some(v) = self.cached(line) {
            return Ok(v);
        }
        let v = Arc::new(self.run(line)?);
        lock(&self.done).insert(line.to_string(), v.clone());
        Ok(v)
    }

    fn cached(&self, line: &str) -> Option<Arc<Value>> {
        lock(&self.done).get(line).cloned()
    }

    /// Runs `gearshock ARGS...` as written (words split at spaces).
    fn run(&self, line: &str) -> Result<Value, Failure> {
        let args: Vec<&str> = line.split_whitespace().skip(1).collect();
        let failed = |why: String| Failure {
            code: 1,
            message: format!("`{line}` {why}"),
        };
        let out = Command::new(&self.exe)
            .args(&args)
            .stdin(Stdio::null())
            .output()
            .map_err(|e| failed(format!("could not start: {e}")))?;
        if !out.status.success() {
            let err = String::from_utf8_lossy(&out.stderr);
            let last = err.lines().last().unwrap_or("").trim();
            return Err(failed(format!("failed: {last}")));
        }
        serde_json::from_slice(&out.stdout).map_err(|e| failed(format!("printed no JSON: {e}")))
    }
}

/// A lock that a panicked holder does not poison for the others (the
/// data are whole values, inserted at once).
fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    m.lock().unwrap_or_else(PoisonError::into_inner)
}
