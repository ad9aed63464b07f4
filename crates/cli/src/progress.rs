//! Progress on stderr: a one-line bar when stderr is a terminal, or with
//! `--progress` one plain line per whole percent (for logs and cluster jobs,
//! where stderr is a file), or nothing.

use std::io::{IsTerminal, Write};

/// How progress is shown.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Mode {
    Off,
    Bar,
    Lines,
}

/// Progress of a job of `total` items.
pub struct Progress {
    total: usize,
    what: &'static str,
    mode: Mode,
    last_percent: Option<usize>,
}

impl Progress {
    /// A bar for `total` items when stderr is a terminal; with `lines`
    /// (`--progress`) plain lines whenever another percent is done, whatever
    /// stderr is.
    pub fn new(total: usize, what: &'static str, lines: bool) -> Self {
        let mode = if lines {
            Mode::Lines
        } else if std::io::stderr().is_terminal() {
            Mode::Bar
        } else {
            Mode::Off
        };
        Progress {
            total,
            what,
            mode,
            last_percent: None,
        }
    }

    /// Shows `done` of the total.
    pub fn update(&mut self, done: usize) {
        match self.mode {
            Mode::Off => {}
            Mode::Bar => {
                let width = 40;
                let filled = (done.min(self.total) * width)
                    .checked_div(self.total)
                    .unwrap_or(width);
                let mut err = std::io::stderr().lock();
                let _ = write!(
                    err,
                    "\r[{}{}] {done}/{} {}",
                    "#".repeat(filled),
                    " ".repeat(width - filled),
                    self.total,
                    self.what
                );
                let _ = err.flush();
            }
            Mode::Lines => {
                let percent = (done.min(self.total) * 100)
                    .checked_div(self.total)
                    .unwrap_or(100);
                if self.last_percent != Some(percent) {
                    self.last_percent = Some(percent);
                    let mut err = std::io::stderr().lock();
                    let _ = writeln!(
                        err,
                        "gearshock: progress {done}/{} {} ({percent} %)",
                        self.total, self.what
                    );
                    let _ = err.flush();
                }
            }
        }
    }

    /// Ends the line.
    pub fn finish(&mut self) {
        if self.mode == Mode::Bar {
            let _ = writeln!(std::io::stderr());
        }
    }
}
