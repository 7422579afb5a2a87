//! Every subcommand's `--help` explains every argument and option: no entry
//! without a description.

use std::process::Command;

fn help(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_asperity"))
        .args(args)
        .arg("--help")
        .env("COLUMNS", "200")
        .output()
        .unwrap();
    assert!(out.status.success(), "{args:?} --help failed");
    String::from_utf8(out.stdout).unwrap()
}

/// The entries of the Arguments/Options sections without a description.
fn undocumented(text: &str) -> Vec<String> {
    let mut missing = Vec::new();
    let mut in_section = false;
    let lines: Vec<&str> = text.lines().collect();
    for (i, line) in lines.iter().enumerate() {
        if line.ends_with(':') && !line.starts_with(' ') {
            in_section = matches!(*line, "Arguments:" | "Options:" | "Commands:");
            continue;
        }
        let t = line.trim_start();
        if !in_section || t.is_empty() {
            continue;
        }
        let indent = line.len() - t.len();
        let is_entry =
            t.starts_with('-') || t.starts_with('<') || t.starts_with('[') || indent == 2;
        if !is_entry || indent > 6 {
            continue;
        }
        // "entry   description" on one line, or the description on the next,
        // deeper-indented line
        let rest = t.split("  ").skip(1).map(str::trim).find(|s| !s.is_empty());
        let same_line = rest.is_some_and(|r| !r.starts_with('['));
        let next_line = lines
            .get(i + 1)
            .is_some_and(|n| n.len() - n.trim_start().len() >= indent + 2 && !n.trim().is_empty());
        if !same_line && !next_line {
            missing.push(t.to_string());
        }
    }
    missing
}

#[test]
fn every_option_of_every_subcommand_is_explained() {
    let mut all = Vec::new();
    for cmd in [
        vec![],
        vec!["run"],
        vec!["check"],
        vec!["figures"],
        vec!["report"],
        vec!["study"],
        vec!["study", "refine"],
        vec!["study", "stability"],
    ] {
        let text = help(&cmd);
        for m in undocumented(&text) {
            all.push(format!("asperity {} --help: {m}", cmd.join(" ")));
        }
    }
    assert!(all.is_empty(), "undocumented:\n{}", all.join("\n"));
}

#[test]
fn the_checker_sees_a_missing_description() {
    let text = "Usage: x\n\nArguments:\n  <CASE>  \n\nOptions:\n      --out <OUT>          [default: a]\n  -h, --help  Print help\n";
    assert_eq!(undocumented(text).len(), 2, "{:?}", undocumented(text));
}
