//! An error on one rank ends every rank with one message, exit code 2 and no
//! output.

use crate::common;
use crate::support::*;

#[test]
fn a_bad_case_ends_every_rank_with_one_message() {
    let text =
        include_str!("../../cases/punch-plane-stress/case.toml").replace("m = 0.5", "m = 1.5");
    let case = common::case_dir("parallel-bad", &text);
    let (code, err) = mpirun(2, &["run", case.to_str().unwrap(), "--quiet"]);
    assert_eq!(code, 2, "{err}");
    assert_eq!(err.matches("error:").count(), 1, "{err}");
    assert!(err.contains("m = 1.5 must be in (0, 1]"), "{err}");
}

#[test]
fn a_fault_on_rank_1_ends_every_rank_with_its_message_and_no_output() {
    let root = common::scratch("parallel-fault");
    let case = common::root().join("cases/punch-plane-stress");
    let t = std::time::Instant::now();
    let err = fails_cleanly_on_two_ranks(&root, &case, &["--inject-fault", "1:30"]);
    assert!(err.contains("rank 1: fault injected on rank 1"), "{err}");
    assert!(t.elapsed().as_secs() < 30, "took {:?}", t.elapsed());
}

/// A load that cannot converge, solved by SNES on 2 ranks: exit code 2, one
/// message, no output folder.
#[test]
fn a_load_snes_cannot_converge_ends_every_rank_cleanly() {
    let root = common::scratch("parallel-snes-fail");
    let case = common::corpus::bad_input("85-cannot-converge");
    let err = fails_cleanly_on_two_ranks(&root, &case, &[]);
    assert!(err.contains("did not converge"), "{err}");
}

/// The whole-model checks run on every rank (each builds the model from the
/// same file): a case valid key by key but wrong as a whole (two interfaces
/// over the same node pairs; a mesh reaching x < 0 with symmetric_half) ends
/// both ranks with exit code 2 and one message, no output.
#[test]
fn a_model_wrong_as_a_whole_is_refused_once_on_two_ranks() {
    for (name, needle) in [
        ("101-interface-pairs-twice", "both pair the nodes at"),
        ("107-symmetric-half-negative-x", "lies at x < 0"),
        (
            "241-matching-and-nonmatching-same-sides",
            "both use the edge",
        ),
        (
            "250-force-on-prescribed-dof",
            "is prescribed by a [[boundary]]",
        ),
        ("244-history-never-used", "is never used"),
        ("340-arc-apex-off-block", "center"),
    ] {
        let root = common::scratch(&format!("parallel-whole-{name}"));
        let case = common::corpus::bad_input(name);
        let err = fails_cleanly_on_two_ranks(&root, &case, &[]);
        assert!(err.contains(needle), "{name}: {err}");
    }
}

/// `--backend serial` under `mpirun -n 2` would run two independent serial
/// solves into one folder: both ranks exit 2, one message, nothing written.
#[test]
fn the_serial_backend_under_mpirun_is_refused() {
    let root = common::scratch("parallel-serial-backend");
    let case = common::root().join("cases/punch-plane-stress");
    let err = fails_cleanly_on_two_ranks(&root, &case, &["--backend", "serial"]);
    assert!(
        err.contains("the serial backend under an MPI launcher with 2 processes"),
        "{err}"
    );
}

/// A MUMPS factorization that cannot get its memory ends the run at once with
/// one `memory:` line, on both nonlinear paths: no cutbacks (a smaller step
/// needs the same factor). MUMPS's work space is starved with ICNTL(14) = −99
/// (INFOG(1) = −9, which PETSc reports as PC_FACTOR_OUTMEMORY).
#[test]
fn a_factorization_out_of_memory_ends_the_run_without_cutbacks() {
    let case = common::root().join("cases/punch-plane-stress");
    for nl in ["snes", "builtin"] {
        let root = common::scratch(&format!("parallel-oom-{nl}"));
        let err = fails_cleanly_on_two_ranks(
            &root,
            &case,
            &["--nonlinear", nl, "--", "-mat_mumps_icntl_14", "-99"],
        );
        assert!(
            err.contains("memory: the direct factorization (MUMPS) could not allocate"),
            "{nl}: {err}"
        );
        assert!(!err.contains("cutback"), "{nl}: {err}");
    }
}

/// A forged restart folder (a VTU name that leaves the folder) is refused by
/// every rank alike, before anything is written: one message, exit 2, and
/// the file the name points at is untouched.
#[test]
fn a_forged_restart_folder_is_refused_on_two_ranks() {
    let root = common::scratch("parallel-forged-restart");
    let case = common::root().join("cases/punch-plane-stress");
    let first = root.join("first");
    let (code, err) = mpirun(
        2,
        &[
            "run",
            case.to_str().unwrap(),
            "--quiet",
            "--stop-after",
            "3",
            "--out",
            first.to_str().unwrap(),
        ],
    );
    assert!(
        code != 2 && first.join("restart.bin").is_file(),
        "{code}: {err}"
    );
    let victim = root.join("victim.txt");
    std::fs::write(&victim, "keep me").unwrap();
    let mut forge = common::Forge::parse(&std::fs::read(first.join("restart.bin")).unwrap());
    let names = forge.text("pvd_file");
    let first_name = names
        .lines()
        .next()
        .expect("a VTU file was written")
        .to_string();
    let forged = names.replacen(&first_name, "../victim.txt", 1);
    forge.set_bytes("pvd_file", forged.as_bytes());
    std::fs::write(first.join("restart.bin"), forge.bytes()).unwrap();
    let err = fails_cleanly_on_two_ranks(&root, &case, &["--restart", first.to_str().unwrap()]);
    assert!(err.contains("restart.bin"), "{err}");
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "keep me");
}

/// A write of rank 0's output thread that fails in the middle of a 2-rank
/// run (its `vtu` folder replaced by a file once increment 3 is on disk):
/// every rank ends at the next increment with one message, exit code 2, no
/// hang, and no output left behind.
#[test]
fn a_failed_write_on_rank_0_ends_every_rank_cleanly() {
    use std::time::{Duration, Instant};
    let root = common::scratch("parallel-write-fails");
    let out = root.join("out");
    let err_file = root.join("stderr.txt");
    let mut child = std::process::Command::new("mpirun")
        .args(["-n", "2"])
        .arg(env!("CARGO_BIN_EXE_asperity"))
        .arg("run")
        .arg(common::root().join("cases/punch-plane-stress"))
        .args(["--refine", "2", "--increments", "80", "--quiet", "--out"])
        .arg(&out)
        .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
        .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
        .env("OMPI_MCA_rmaps_base_oversubscribe", "1")
        .env("OMPI_MCA_mpi_yield_when_idle", "1")
        .env("OMPI_MCA_hwloc_base_binding_policy", "none")
        .stdout(std::process::Stdio::null())
        .stderr(std::fs::File::create(&err_file).unwrap())
        .spawn()
        .expect("mpirun is on PATH");
    let started = Instant::now();
    let partial = loop {
        let found = std::fs::read_dir(&root)
            .unwrap()
            .filter_map(|e| e.ok())
            .map(|e| e.path())
            .find(|p| {
                p.file_name()
                    .is_some_and(|n| n.to_string_lossy().starts_with(".out.partial-"))
                    && p.join("interface/0004.csv").exists()
            });
        if let Some(p) = found {
            break p;
        }
        assert!(
            child.try_wait().unwrap().is_none(),
            "the run ended before increment 4: {}",
            std::fs::read_to_string(&err_file).unwrap_or_default()
        );
        assert!(started.elapsed() < Duration::from_secs(120));
        std::thread::sleep(Duration::from_millis(2));
    };
    std::fs::rename(partial.join("vtu"), root.join("vtu-moved")).unwrap();
    std::fs::write(partial.join("vtu"), b"not a folder").unwrap();
    let t = Instant::now();
    let code = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s.code().unwrap_or(-1);
        }
        if t.elapsed() > Duration::from_secs(120) {
            let _ = child.kill();
            panic!("the ranks hang after a failed write");
        }
        std::thread::sleep(Duration::from_millis(10));
    };
    let err = std::fs::read_to_string(&err_file).unwrap();
    assert_eq!(code, 2, "{err}");
    assert_eq!(err.matches("error:").count(), 1, "{err}");
    assert!(err.contains("vtu/0"), "{err}");
    assert!(!err.contains("panick"), "{err}");
    assert!(!out.exists(), "output left behind");
    assert!(!partial.exists(), "partial output left behind");
}
