//! A one-line progress bar on stderr, shown only when stderr is a terminal.

use std::io::{IsTerminal, Write};

/// Progress of a job of `total` items.
pub struct Progress {
    total: usize,
    what: &'static str,
    enabled: bool,
}

impl Progress {
    /// A bar for `total` items, silent unless stderr is a terminal.
    pub fn new(total: usize, what: &'static str) -> Self {
        Progress {
            total,
            what,
            enabled: std::io::stderr().is_terminal(),
        }
    }

    /// Shows `done` of the total.
    pub fn update(&mut self, done: usize) {
        if !self.enabled {
            return;
        }
        let width = 40;
        let filled = (done * width).checked_div(self.total).unwrap_or(width);
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

    /// Ends the line.
    pub fn finish(&mut self) {
        if self.enabled {
            let _ = writeln!(std::io::stderr());
        }
    }
}
