//! Progress and log lines of `asperity run` on stderr (rank 0 only under MPI).
//!
//! Two formats: `text` (one readable line per event) and `json` (one JSON
//! object per line; the fields are documented in `docs/running.md`). `quiet`
//! silences the progress events (start, increment, cutback, finish); a stop
//! and an error are always reported.

use serde_json::{json, Value};
use std::time::Instant;

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum LogFormat {
    #[default]
    Text,
    Json,
}

/// Emits the events of one run.
#[derive(Clone, Debug)]
pub struct Log {
    pub format: LogFormat,
    pub quiet: bool,
    started: Instant,
    /// Load factor at the start of this process (after a restart: the restored one).
    lambda_start: f64,
    /// Last load factor of the schedule.
    lambda_end: f64,
}

impl Log {
    pub fn new(format: LogFormat, quiet: bool) -> Log {
        Log {
            format,
            quiet,
            started: Instant::now(),
            lambda_start: 0.0,
            lambda_end: 1.0,
        }
    }

    /// Seconds since the log was created.
    pub fn elapsed(&self) -> f64 {
        self.started.elapsed().as_secs_f64()
    }

    /// Sets the load-factor range this process covers (for the ETA).
    pub fn range(&mut self, from: f64, to: f64) {
        self.lambda_start = from;
        self.lambda_end = to;
    }

    /// Estimated remaining seconds from the load-factor progress of this process.
    pub fn eta(&self, lambda: f64) -> Option<f64> {
        let done = lambda - self.lambda_start;
        let left = self.lambda_end - lambda;
        (done > 0.0).then(|| (self.elapsed() * left.max(0.0) / done).max(0.0))
    }

    fn emit(&self, event: &str, mut fields: Value, text: impl FnOnce() -> String) {
        match self.format {
            LogFormat::Text => eprintln!("{}", text()),
            LogFormat::Json => {
                let mut obj = serde_json::Map::new();
                obj.insert("event".into(), json!(event));
                obj.insert("time_s".into(), json!(round3(self.elapsed())));
                if let Value::Object(m) = fields.take() {
                    obj.extend(m);
                }
                eprintln!("{}", Value::Object(obj));
            }
        }
    }

    /// A progress event (silenced by `quiet`).
    pub fn progress(&self, event: &str, fields: Value, text: impl FnOnce() -> String) {
        if !self.quiet {
            self.emit(event, fields, text);
        }
    }

    /// A stop or error event (always printed).
    pub fn always(&self, event: &str, fields: Value, text: impl FnOnce() -> String) {
        self.emit(event, fields, text);
    }
}

/// Seconds rounded to milliseconds (JSON lines stay short).
pub(crate) fn round3(x: f64) -> f64 {
    (x * 1000.0).round() / 1000.0
}
