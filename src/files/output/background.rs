//! The output writer's thread: the per-increment files (interface CSV, VTU,
//! `restart.bin`) are encoded and written here while the solver goes on with
//! the next increment.
//!
//! - **Order.** One thread takes the jobs in the order they were sent, so an
//!   increment's CSV and VTU are complete on disk before the `restart.bin`
//!   that lists them replaces the previous one (itself written to a
//!   temporary name and renamed): the checkpoint only ever references fully
//!   written files.
//! - **Bounded.** The queue holds [`QUEUE`] jobs: the solver runs at most
//!   about one increment ahead of the disk, and at most that many snapshots
//!   are held in memory besides the one being written.
//! - **Errors.** The first failed job is kept and every later one skipped;
//!   the solver's thread gets the error at its next send ([`Background::check`],
//!   at the next increment) or when it waits for the queue to drain
//!   ([`Background::drain`], at the end of the run; under MPI both results
//!   are agreed on by every rank in [`crate::solve`]).

use super::vtu::{Frame, Layout};
use crate::error::{Error, Result};
use crate::model::Model;
use crate::solve::Checkpoint;
use std::path::PathBuf;
use std::sync::mpsc::{sync_channel, Receiver, SyncSender};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;

/// Jobs waiting besides the one being written: an increment sends up to
/// three (CSV, VTU, checkpoint).
const QUEUE: usize = 3;

/// One file to write.
pub(crate) enum Job {
    /// Text, written as it is.
    Text { path: PathBuf, text: String },
    /// A VTU document.
    Vtu {
        path: PathBuf,
        layout: Arc<Layout>,
        frame: Box<Frame>,
    },
    /// `restart.bin`: written to `tmp`, then renamed to `path`.
    Checkpoint {
        tmp: PathBuf,
        path: PathBuf,
        fingerprint: u64,
        ck: Box<Checkpoint>,
        pvd: Vec<(f64, String)>,
    },
}

impl Job {
    fn run(self) -> Result<()> {
        match self {
            Job::Text { path, text } => {
                std::fs::write(&path, text).map_err(|e| Error::io(&path, e))
            }
            Job::Vtu {
                path,
                layout,
                frame,
            } => {
                let write = || -> std::io::Result<()> {
                    let mut w =
                        std::io::BufWriter::with_capacity(1 << 17, std::fs::File::create(&path)?);
                    layout.write(&mut w, &frame)?;
                    std::io::Write::flush(&mut w)
                };
                write().map_err(|e| Error::io(&path, e))
            }
            Job::Checkpoint {
                tmp,
                path,
                fingerprint,
                ck,
                pvd,
            } => {
                let write = || -> std::io::Result<()> {
                    let mut w = std::io::BufWriter::new(std::fs::File::create(&tmp)?);
                    crate::files::restart::write_to(&mut w, fingerprint, &ck, &pvd)?;
                    std::io::Write::flush(&mut w)
                };
                write().map_err(|e| Error::io(&tmp, e))?;
                std::fs::rename(&tmp, &path).map_err(|e| Error::io(&path, e))
            }
        }
    }
}

/// The writer thread and its queue.
pub(crate) struct Background {
    queue: Option<SyncSender<Job>>,
    thread: Option<JoinHandle<()>>,
    /// The first failure of a job, until the solver's side takes it.
    failed: Arc<Mutex<Option<Error>>>,
}

impl Background {
    pub fn start() -> Result<Background> {
        let (queue, jobs) = sync_channel(QUEUE);
        let failed = Arc::new(Mutex::new(None));
        let slot = Arc::clone(&failed);
        let thread = std::thread::Builder::new()
            .name("asperity-output".into())
            .spawn(move || work(&jobs, &slot))
            .map_err(|e| Error::Output(format!("cannot start the output writer thread: {e}")))?;
        Ok(Background {
            queue: Some(queue),
            thread: Some(thread),
            failed,
        })
    }

    /// The first failed write so far, if any (taken: reported once).
    pub fn check(&self) -> Result<()> {
        match self.failed.lock().map(|mut f| f.take()) {
            Ok(None) => Ok(()),
            Ok(Some(e)) => Err(e),
            Err(_) => Err(Error::Output("the output writer thread failed".into())),
        }
    }

    /// Queues a job (waits while the queue is full); first reports an earlier
    /// failure.
    pub(crate) fn send(&mut self, job: Job) -> Result<()> {
        self.check()?;
        let sent = self.queue.as_ref().map(|q| q.send(job).is_ok());
        if sent != Some(true) {
            // the thread is gone: it ended on a panic (or was drained)
            self.drain()?;
            return Err(Error::Output("the output writer thread has stopped".into()));
        }
        Ok(())
    }

    /// Waits until every queued job is written and ends the thread; the first
    /// failure, if any. Later jobs need a new [`Background`].
    pub fn drain(&mut self) -> Result<()> {
        self.queue = None;
        let panicked = self.thread.take().is_some_and(|t| t.join().is_err());
        self.check()?;
        if panicked {
            return Err(Error::Output("the output writer thread failed".into()));
        }
        Ok(())
    }
}

impl Drop for Background {
    /// Lets the thread finish what is queued (nothing is left writing into a
    /// folder about to be removed); its errors no longer matter.
    fn drop(&mut self) {
        self.queue = None;
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

fn work(jobs: &Receiver<Job>, failed: &Mutex<Option<Error>>) {
    let mut ok = true;
    for job in jobs {
        if !ok {
            continue;
        }
        if let Err(e) = job.run() {
            ok = false;
            if let Ok(mut f) = failed.lock() {
                f.get_or_insert(e);
            }
        }
    }
}

/// The model-dependent part of the output that stays the same for a whole
/// run, made once ([`Layout`]).
pub fn layout(model: &Model) -> Arc<Layout> {
    Arc::new(Layout::of(model, model.output.vtu_format))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn text(path: PathBuf, text: &str) -> Job {
        Job::Text {
            path,
            text: text.into(),
        }
    }

    #[test]
    fn jobs_run_in_order_and_the_first_failure_is_reported_once() {
        let dir = std::env::temp_dir().join(format!("asperity-background-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let mut bg = Background::start().unwrap();
        // the same file twice: the later job wins
        bg.send(text(dir.join("a.txt"), "1")).unwrap();
        bg.send(text(dir.join("a.txt"), "2")).unwrap();
        bg.send(text(dir.join("missing/b.txt"), "x")).unwrap();
        // the failure reaches the solver's side at a later send
        let t = std::time::Instant::now();
        let err = loop {
            match bg.send(text(dir.join("c.txt"), "after the failure")) {
                Err(e) => break e,
                Ok(()) => {
                    assert!(t.elapsed().as_secs() < 30, "the failure never surfaced");
                    std::thread::sleep(std::time::Duration::from_millis(1));
                }
            }
        };
        assert!(err.to_string().contains("missing/b.txt"), "{err}");
        // reported once; the jobs after it were skipped
        bg.drain().unwrap();
        assert_eq!(std::fs::read_to_string(dir.join("a.txt")).unwrap(), "2");
        assert!(!dir.join("c.txt").exists());
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_failure_of_the_last_job_is_reported_by_drain() {
        let mut bg = Background::start().unwrap();
        bg.send(text(PathBuf::from("/nonexistent-asperity/x.csv"), "x"))
            .unwrap();
        let err = bg.drain().unwrap_err();
        assert!(
            err.to_string().contains("/nonexistent-asperity/x.csv"),
            "{err}"
        );
        // the thread is gone: a later send is an error, not a hang
        assert!(bg.send(text(PathBuf::from("/tmp/never"), "x")).is_err());
    }
}
