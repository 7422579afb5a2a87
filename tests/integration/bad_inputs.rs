//! The bad-input corpus: every folder `tests/bad_inputs/NN-name/` holds a case
//! that `asperity` must reject, and `expect.txt`, a piece of text the error
//! message must contain. The case is stored as patches (`case.toml.patch`: a base
//! case of `tests/bad_inputs/base/` and what to change, see
//! `tests/bad_inputs/README.md`) or, when it cannot be one, as raw files; each
//! folder is assembled into a scratch folder of the same name under
//! `CARGO_TARGET_TMPDIR/bad_inputs/NN-name/`, and that is what runs. A patch
//! that does not apply fails the test naming its folder and line.
//!
//! For each folder, in order, `asperity run <case> --out <scratch>/out --quiet`
//! must exit with code 2, print exactly one line on stderr, starting `error: `
//! and containing the expected text, never mention a panic, and leave neither the
//! output folder nor a `.partial` folder behind. `asperity check <case>` must
//! then either accept the case (the failure is one of solving, not of the input)
//! or fail with the very same line. Failures are collected and reported together.
//! A folder whose bad input is a run option rather than the case holds a valid
//! case and `args.txt` (more `run` arguments, one a line) and/or `env.txt`
//! (`NAME=value` lines for the run's environment); `check` must accept its case,
//! and, when the arguments are all overrides of the case (which `check` takes
//! too, [`RUN_ONLY`] none of them), refuse it with them with the run's very line.
//! See docs/reliability.md.

use crate::common::corpus;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// A run longer than this is a failure (the corpus must fail fast).
const TIME_LIMIT: Duration = Duration::from_secs(60);

struct Outcome {
    code: Option<i32>,
    stdout: String,
    stderr: String,
    seconds: f64,
}

/// Environment variables a folder's `env.txt` may set: removed from every run,
/// so that the corpus does not depend on the caller's environment.
const OPTION_VARS: [&str; 1] = ["ASPERITY_THREADS"];

/// The options of `run` that `check` does not take (the others override the
/// case, and `check` takes them as `run` does).
const RUN_ONLY: [&str; 10] = [
    "--out",
    "--quiet",
    "--log-format",
    "--restart",
    "--stop-after",
    "--threads",
    "--backend",
    "--inject-fault",
    "--nonlinear",
    "--memory",
];

/// Runs the binary with a time limit and extra environment variables; a
/// process that overruns is killed.
fn asperity(args: &[&std::ffi::OsStr], env: &[(String, String)]) -> Outcome {
    let started = Instant::now();
    let dir = std::env::temp_dir();
    let tag = format!(
        "asperity-bad-inputs-{}-{}",
        std::process::id(),
        started.elapsed().as_nanos()
    );
    // stdout and stderr go to files: no pipe can fill up while we poll
    let (out_path, err_path) = (
        dir.join(format!("{tag}.out")),
        dir.join(format!("{tag}.err")),
    );
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_asperity"));
    for v in OPTION_VARS {
        cmd.env_remove(v);
    }
    let mut child = cmd
        .args(args)
        .envs(env.iter().map(|(k, v)| (k, v)))
        .stdin(Stdio::null())
        .stdout(std::fs::File::create(&out_path).unwrap())
        .stderr(std::fs::File::create(&err_path).unwrap())
        .spawn()
        .expect("cannot start asperity");
    let code = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status.code();
        }
        if started.elapsed() > TIME_LIMIT {
            let _ = child.kill();
            let _ = child.wait();
            break None;
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    let read = |p: &Path| {
        let s = String::from_utf8_lossy(&std::fs::read(p).unwrap_or_default()).into_owned();
        let _ = std::fs::remove_file(p);
        s
    };
    Outcome {
        code,
        stdout: read(&out_path),
        stderr: read(&err_path),
        seconds: started.elapsed().as_secs_f64(),
    }
}

/// Problems with one outcome: exit code, the single error line, panics.
fn judge(what: &str, o: &Outcome, expect: &str, problems: &mut Vec<String>) {
    if o.code.is_none() {
        problems.push(format!(
            "{what}: killed after {:.0} s (or ended by a signal)",
            o.seconds
        ));
    } else if o.code != Some(2) {
        problems.push(format!("{what}: exit code {:?}, expected 2", o.code));
    }
    for (stream, text) in [("stdout", &o.stdout), ("stderr", &o.stderr)] {
        if text.contains("panicked") || text.contains("RUST_BACKTRACE") {
            problems.push(format!("{what}: panic on {stream}: {text:?}"));
        }
    }
    let lines: Vec<&str> = o.stderr.lines().collect();
    if lines.len() != 1 {
        problems.push(format!(
            "{what}: {} lines on stderr, expected exactly one: {:?}",
            lines.len(),
            o.stderr
        ));
    }
    let first = lines.first().copied().unwrap_or("");
    if !first.starts_with("error: ") {
        problems.push(format!(
            "{what}: stderr does not start with `error: `: {first:?}"
        ));
    }
    if !first.contains(expect) {
        problems.push(format!("{what}: expected text {expect:?} not in {first:?}"));
    }
}

#[test]
fn every_bad_input_is_rejected_with_one_clear_line() {
    let scratch = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bad_inputs");
    let _ = std::fs::remove_dir_all(&scratch);
    let mut failures: Vec<String> = Vec::new();
    let mut checked_only = 0;
    let all = corpus::folders();
    assert!(all.len() >= 60, "only {} corpus folders", all.len());
    for source in &all {
        let name = source.file_name().unwrap().to_string_lossy().into_owned();
        let mut problems = Vec::new();
        let expect = match std::fs::read_to_string(source.join("expect.txt")) {
            Ok(s) if !s.trim().is_empty() => s.trim_end_matches(['\n', '\r']).to_string(),
            _ => {
                failures.push(format!("{name}: no expect.txt (or it is empty)"));
                continue;
            }
        };
        // a scratch folder of its own: the assembled case, named like the
        // corpus folder, and `out`, which must not exist afterwards, nor any
        // `.out.partial-*` beside it
        let parent = scratch.join(&name);
        std::fs::create_dir_all(&parent).unwrap();
        let folder = parent.join(&name);
        if let Err(e) = corpus::assemble(source, &folder) {
            failures.push(format!("{name}: the case does not assemble: {e}"));
            continue;
        }
        let folder = &folder;
        let out = parent.join("out");
        let lines = |file: &str| -> Vec<String> {
            std::fs::read_to_string(source.join(file))
                .map(|s| s.lines().map(str::to_string).collect())
                .unwrap_or_default()
        };
        let extra = lines("args.txt");
        let mut env = Vec::new();
        for line in lines("env.txt") {
            match line.split_once('=') {
                Some((k, v)) if OPTION_VARS.contains(&k) => env.push((k.into(), v.into())),
                _ => failures.push(format!(
                    "{name}: env.txt: {line:?} is not NAME=value of {OPTION_VARS:?}"
                )),
            }
        }
        let options = !extra.is_empty() || !env.is_empty();
        let mut args: Vec<&std::ffi::OsStr> = vec![
            "run".as_ref(),
            folder.as_os_str(),
            "--out".as_ref(),
            out.as_os_str(),
            "--quiet".as_ref(),
        ];
        args.extend(extra.iter().map(std::ffi::OsStr::new));
        let run = asperity(&args, &env);
        judge("run", &run, &expect, &mut problems);
        if out.exists() {
            problems.push(format!("run: output folder {} left behind", out.display()));
        }
        let leftovers: Vec<String> = std::fs::read_dir(&parent)
            .unwrap()
            .filter_map(|e| e.ok())
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .filter(|n| n.contains("partial"))
            .collect();
        if !leftovers.is_empty() {
            problems.push(format!("run: partial output left: {leftovers:?}"));
        }
        // `check` validates without solving: it fails with the same line, or it
        // accepts a case whose trouble only shows when solving
        let check = asperity(&["check".as_ref(), folder.as_os_str()], &[]);
        let overrides_only = options
            && env.is_empty()
            && !extra
                .iter()
                .any(|a| RUN_ONLY.iter().any(|o| a.split('=').next() == Some(*o)));
        if overrides_only {
            // `check` with the same overrides: the run's very line
            let mut args: Vec<&std::ffi::OsStr> = vec!["check".as_ref(), folder.as_os_str()];
            args.extend(extra.iter().map(std::ffi::OsStr::new));
            let with = asperity(&args, &[]);
            judge("check with the overrides", &with, &expect, &mut problems);
            if with.stderr != run.stderr {
                problems.push(format!(
                    "check with the overrides and run disagree: {:?} vs {:?}",
                    with.stderr, run.stderr
                ));
            }
        }
        match check.code {
            // the case is valid: the run's options are what is wrong
            _ if options => {
                checked_only += 1;
                if check.code != Some(0) {
                    problems.push(format!(
                        "check rejected the case of a folder whose run options are the bad input: {:?}",
                        check.stderr
                    ));
                }
            }
            Some(0) => {
                checked_only += 1;
                let solving = ["did not converge", "linear solver"];
                if !solving.iter().any(|s| run.stderr.contains(s)) {
                    problems.push(format!(
                        "check accepted the case but run failed with an input error: {:?}",
                        run.stderr
                    ));
                }
            }
            _ => {
                judge("check", &check, &expect, &mut problems);
                if check.stderr != run.stderr {
                    problems.push(format!(
                        "check and run disagree: {:?} vs {:?}",
                        check.stderr, run.stderr
                    ));
                }
            }
        }
        println!(
            "{name}: {:.2} s  {}",
            run.seconds,
            run.stderr.lines().next().unwrap_or("")
        );
        failures.extend(problems.into_iter().map(|p| format!("{name}: {p}")));
    }
    println!(
        "{} cases, {} rejected by `check` too, {} only when solving",
        all.len(),
        all.len() - checked_only,
        checked_only
    );
    assert!(
        failures.is_empty(),
        "{} problem(s) in the bad-input corpus:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// Every corpus folder assembles (each patch applies to its base), without
/// running anything: a fast first check of the corpus files. Every base is
/// used by some patch, and no folder is left without an input.
#[test]
fn every_corpus_folder_assembles_and_every_base_is_used() {
    let scratch = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bad_inputs_assembled");
    let _ = std::fs::remove_dir_all(&scratch);
    let mut failures = Vec::new();
    let mut used = std::collections::BTreeSet::new();
    let all = corpus::folders();
    assert!(all.len() >= 60, "only {} corpus folders", all.len());
    for source in &all {
        let name = source.file_name().unwrap().to_string_lossy().into_owned();
        match corpus::assemble(source, &scratch.join(&name)) {
            Ok(bases) => used.extend(bases),
            Err(e) => failures.push(format!("{name}: {e}")),
        }
    }
    let bases: Vec<String> = std::fs::read_dir(corpus::base_dir())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert!(
        !bases.is_empty(),
        "no base in {}",
        corpus::base_dir().display()
    );
    for b in &bases {
        if !used.contains(b) {
            failures.push(format!("base/{b}: no patch uses it"));
        }
    }
    println!(
        "{} folders assembled from {} bases into {}",
        all.len(),
        bases.len(),
        scratch.display()
    );
    assert!(
        failures.is_empty(),
        "{} corpus folder(s) do not assemble:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// The patch format, directive by directive, on a small base: what each one
/// makes, byte for byte, and that a malformed patch is refused naming its line
/// (an unknown directive, key, table or base, a table that needs its number, a
/// base line already gone, a truncation that is not last).
#[test]
fn patches_make_what_the_format_says_and_refuse_what_it_does_not() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bad_inputs_patch_format");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("b.toml"),
        "name = \"b\"\n\n[model]\nplane = \"stress\"\n\n[[load]]\nset = \"a\"\n\n[[load]]\nset = \"b\"\n\n[solver]\nincrements = 4\n",
    )
    .unwrap();
    let make =
        |patch: &str| corpus::apply_patch(patch, &dir).map(|(_, b)| String::from_utf8(b).unwrap());
    let cases = [
        (
            "base b.toml\nset [model] plane = \"strain\"\nadd [model] thickness = 2.0\n",
            "name = \"b\"\n\n[model]\nplane = \"strain\"\nthickness = 2.0\n\n[[load]]\nset = \"a\"\n\n[[load]]\nset = \"b\"\n\n[solver]\nincrements = 4\n",
        ),
        (
            "base b.toml\n# a comment\nadd-first colour = \"red\"\nadd-first [[load]]#2 x = 1\ndelete [[load]]#1 set\n",
            "colour = \"red\"\nname = \"b\"\n\n[model]\nplane = \"stress\"\n\n[[load]]\n\n[[load]]\nx = 1\nset = \"b\"\n\n[solver]\nincrements = 4\n",
        ),
        (
            "base b.toml\ndelete [[load]]#2\nbefore [solver] [output]\nbefore [solver] vtu = false\nbefore [solver]\nappend max_cutbacks = 2\n",
            "name = \"b\"\n\n[model]\nplane = \"stress\"\n\n[[load]]\nset = \"a\"\n\n[output]\nvtu = false\n\n[solver]\nincrements = 4\nmax_cutbacks = 2\n",
        ),
        (
            "base b.toml\nreplace 1 # the first line\ninsert 4 thickness = 1.0\nremove 5-10\nappend\ntruncate 43\n",
            "# the first line\n\n[model]\nthickness = 1.0\np",
        ),
        (
            "base b.toml\nremove 2\nreplace 3\ninsert 13 x\n",
            "name = \"b\"\n\nplane = \"stress\"\n\n[[load]]\nset = \"a\"\n\n[[load]]\nset = \"b\"\n\n[solver]\nx\nincrements = 4\n",
        ),
    ];
    for (patch, want) in cases {
        match make(patch) {
            Ok(got) => assert_eq!(got, want, "{patch}"),
            Err(e) => panic!("{patch}: {e}"),
        }
    }
    let refused = [
        (
            "base b.toml\nset [model] plane = 1\nfrobnicate x\n",
            "line 3: \"frobnicate x\": unknown directive \"frobnicate\"",
        ),
        (
            "base b.toml\nset [model] young = 1.0\n",
            "line 2: \"set [model] young = 1.0\": no line of key young in [model]",
        ),
        ("base b.toml\nset [mesh] refine = 2\n", "no table [mesh]"),
        (
            "base b.toml\nadd [[load]] x = 1\n",
            "2 tables [[load]]: say which with [[load]]#N",
        ),
        (
            "base b.toml\nadd [[load]]#3 x = 1\n",
            "no table [[load]]#3 (there are 2)",
        ),
        (
            "base b.toml\nset [solver] no key here\n",
            "not a `key = value` line",
        ),
        (
            "base c.toml\nset [model] plane = 1\n",
            "line 1: unknown base \"c.toml\"",
        ),
        ("base ../b.toml\n", "is not a file name"),
        (
            "set [model] plane = 1\n",
            "line 1: \"set [model] plane = 1\": the first line must be `base NAME`",
        ),
        ("", "empty patch"),
        (
            "base b.toml\nremove 3\nreplace 3 x\n",
            "line 3: \"replace 3 x\": line 3 of the base is not there",
        ),
        (
            "base b.toml\nreplace 14 x\n",
            "line 14 of the base is not there",
        ),
        ("base b.toml\nremove 5-4\n", "bad line range"),
        (
            "base b.toml\ntruncate 10\nappend x\n",
            "truncate must be the last directive",
        ),
        ("base b.toml\ntruncate 1000\n", "past the end"),
        ("base b.toml\nbefore x = 1\n", "before needs a table"),
        ("base b.toml\ndelete\n", "delete needs a key or a table"),
    ];
    for (patch, needle) in refused {
        match make(patch) {
            Ok(got) => panic!("{patch:?} was accepted, made {got:?}"),
            Err(e) => assert!(
                e.contains(needle),
                "{patch:?}: {e:?} does not say {needle:?}"
            ),
        }
    }
    // a folder with a patch that does not apply, or with nothing to run, does
    // not assemble, and says which file and line
    let folder = dir.join("99-broken");
    std::fs::create_dir_all(&folder).unwrap();
    std::fs::write(folder.join("expect.txt"), "x\n").unwrap();
    let e = corpus::assemble(&folder, &dir.join("out-empty")).unwrap_err();
    assert!(e.contains("no input"), "{e}");
    std::fs::write(
        folder.join("case.toml.patch"),
        "base punch.toml\nset [model] colour = 1\n",
    )
    .unwrap();
    let e = corpus::assemble(&folder, &dir.join("out-patch")).unwrap_err();
    assert!(
        e.starts_with("case.toml.patch: line 2: ")
            && e.contains("no line of key colour in [model]"),
        "{e}"
    );
}

/// Every base case is valid (`asperity check` accepts it), so that a corpus
/// case is a valid case with what its patch changes. A base that reads
/// `mesh.msh` names the mesh base it goes with (`tiny.msh`), which is put
/// beside it.
#[test]
fn every_base_case_is_valid() {
    let scratch = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bad_inputs_bases");
    let _ = std::fs::remove_dir_all(&scratch);
    let mut names: Vec<String> = std::fs::read_dir(corpus::base_dir())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    let meshes: Vec<&String> = names.iter().filter(|n| n.ends_with(".msh")).collect();
    let mut failures = Vec::new();
    let mut checked = 0;
    for name in names.iter().filter(|n| n.ends_with(".toml")) {
        let text = std::fs::read_to_string(corpus::base_dir().join(name)).unwrap();
        let dir = scratch.join(name.trim_end_matches(".toml"));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("case.toml"), &text).unwrap();
        let named: Vec<&&String> = meshes
            .iter()
            .filter(|m| text.contains(m.as_str()))
            .collect();
        match named.as_slice() {
            [] if text.contains("\"mesh.msh\"") => {
                failures.push(format!(
                    "base/{name}: reads mesh.msh but names no mesh base"
                ));
                continue;
            }
            [] => {}
            [m] => {
                std::fs::copy(corpus::base_dir().join(m.as_str()), dir.join("mesh.msh")).unwrap();
            }
            more => {
                failures.push(format!("base/{name}: names several mesh bases {more:?}"));
                continue;
            }
        }
        let o = asperity(&["check".as_ref(), dir.as_os_str()], &[]);
        checked += 1;
        if o.code != Some(0) {
            failures.push(format!(
                "base/{name}: `asperity check` exit code {:?}: {}",
                o.code,
                o.stderr.trim()
            ));
        }
    }
    assert!(checked >= 10, "only {checked} base cases");
    assert!(
        failures.is_empty(),
        "{} base case(s) not valid:\n{}",
        failures.len(),
        failures.join("\n")
    );
}
