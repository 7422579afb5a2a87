//! Memory bandwidth of this machine for one core and for two at once: the
//! ceiling of a two-rank speed-up for code that streams memory, as the sparse
//! matrix-vector products of the Krylov solves do (docs/performance.md, "Two
//! cores, one memory bus").
//!
//! `cargo bench --bench bandwidth` prints, for two kernels over arrays far
//! larger than the caches, the median bandwidth of one thread, of two threads
//! running the same kernel on their own arrays at the same time (summed), and
//! their ratio. One- and two-thread trials alternate, so that a shared host's
//! drift reaches both alike; the ratio is the median over adjacent pairs, with
//! its range. Compute-bound work on the same cores is timed alongside, to show
//! that the cores themselves are independent.
//!
//! * `read`: a sum over one array (what a sparse product does to the matrix);
//! * `triad`: `a = b + s c` (STREAM's triad: two reads, one write).

use std::hint::black_box;
use std::sync::Barrier;
use std::time::Instant;

/// Doubles per array: 160 MB, five times a 32 MB last-level cache.
const LEN: usize = 20_000_000;
/// Passes over the arrays per trial.
const PASSES: usize = 10;
/// Trials per measurement; the median is reported.
const TRIALS: usize = 9;

#[derive(Clone, Copy)]
enum Kernel {
    Read,
    Triad,
    Compute,
}

impl Kernel {
    fn name(self) -> &'static str {
        match self {
            Kernel::Read => "read",
            Kernel::Triad => "triad",
            Kernel::Compute => "compute",
        }
    }

    /// What one element and pass counts for in the reported rate: bytes moved
    /// (read, triad) or flops (compute: one update of two flops).
    fn work(self) -> f64 {
        match self {
            Kernel::Read => 8.0,
            Kernel::Triad => 24.0,
            Kernel::Compute => 2.0,
        }
    }
}

struct Arrays {
    a: Vec<f64>,
    b: Vec<f64>,
    c: Vec<f64>,
}

impl Arrays {
    fn new() -> Self {
        Arrays {
            a: vec![0.0; LEN],
            b: (0..LEN).map(|i| (i % 7) as f64).collect(),
            c: (0..LEN).map(|i| (i % 5) as f64).collect(),
        }
    }

    /// One trial: seconds for PASSES passes.
    fn run(&mut self, kernel: Kernel) -> f64 {
        let t = Instant::now();
        match kernel {
            Kernel::Read => {
                for _ in 0..PASSES {
                    // eight partial sums, so that the adds do not wait on each other
                    let mut s = [0.0f64; 8];
                    for chunk in black_box(&self.b).chunks_exact(8) {
                        for (acc, v) in s.iter_mut().zip(chunk) {
                            *acc += v;
                        }
                    }
                    black_box(s);
                }
            }
            Kernel::Triad => {
                for p in 0..PASSES {
                    let s = black_box(1.0 + p as f64);
                    for ((a, b), c) in self.a.iter_mut().zip(&self.b).zip(&self.c) {
                        *a = b + s * c;
                    }
                    black_box(&mut self.a);
                }
            }
            Kernel::Compute => {
                // eight independent chains held in registers, 2 flops per update
                let mut x = [1.0f64; 8];
                let (a, b) = (black_box(0.999_999_9), black_box(1e-7));
                for _ in 0..PASSES * LEN / 8 / 64 {
                    for _ in 0..64 {
                        for v in x.iter_mut() {
                            *v = *v * a + b;
                        }
                    }
                    black_box(&mut x);
                }
            }
        }
        t.elapsed().as_secs_f64()
    }
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// One trial of `kernel` on the first `threads` of `arrays`, each thread on its
/// own arrays, started together: the rate (GB/s, or Gflop/s for compute)
/// summed over the threads.
fn trial(arrays: &mut [Arrays], threads: usize, kernel: Kernel) -> f64 {
    let barrier = Barrier::new(threads);
    std::thread::scope(|scope| {
        let handles: Vec<_> = arrays[..threads]
            .iter_mut()
            .map(|a| {
                let barrier = &barrier;
                scope.spawn(move || {
                    barrier.wait();
                    a.run(kernel)
                })
            })
            .collect();
        handles
            .into_iter()
            .map(|h| kernel.work() * (PASSES * LEN) as f64 / h.join().expect("trial") / 1e9)
            .sum()
    })
}

fn main() {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    println!(
        "cores available: {cores}; arrays of {} MB; one- and two-thread trials alternate, \
         medians of {TRIALS}",
        LEN * 8 / 1_000_000
    );
    println!();
    println!(
        "| kernel | 1 thread | 2 threads (sum) | ratio (median of trial pairs) | ratio range |"
    );
    println!("|---|---:|---:|---:|---:|");
    let mut arrays = [Arrays::new(), Arrays::new()];
    for kernel in [Kernel::Read, Kernel::Triad, Kernel::Compute] {
        trial(&mut arrays, 2, kernel); // first touch, warm-up
        let (mut one, mut two, mut ratio) = (Vec::new(), Vec::new(), Vec::new());
        for _ in 0..TRIALS {
            // adjacent trials see the same state of a shared host
            let a = trial(&mut arrays, 1, kernel);
            let b = trial(&mut arrays, 2, kernel);
            one.push(a);
            two.push(b);
            ratio.push(b / a);
        }
        let unit = if matches!(kernel, Kernel::Compute) {
            "Gflop/s"
        } else {
            "GB/s"
        };
        let lo = ratio.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = ratio.iter().copied().fold(0.0, f64::max);
        println!(
            "| {} | {:.1} {unit} | {:.1} {unit} | {:.2} | {lo:.2}-{hi:.2} |",
            kernel.name(),
            median(one),
            median(two),
            median(ratio)
        );
    }
}
