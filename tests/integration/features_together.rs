//! docs/features-together.md's table of feature pairs is checked against the
//! project (issue 46): every refused pair names folders of the bad-input
//! corpus (which `bad_inputs` runs, each refused with its message) and says
//! why in one of four words; every supported pair names a test file and a
//! function in it that runs the pair. A row whose folder, file or function is
//! gone (renamed, or the refusal lifted and its folder removed) fails here.

use crate::common;

/// The answers a row may give, and the reasons a refusal may have.
const REASONS: [&str; 4] = ["physics", "mathematics", "no effect", "not built"];

/// The table's rows after its marker: (feature, with, answer, evidence).
fn rows() -> Vec<[String; 4]> {
    let doc = std::fs::read_to_string(common::root().join("docs/features-together.md")).unwrap();
    let mut lines = doc
        .lines()
        .skip_while(|l| !l.starts_with("<!-- features-together:"));
    assert!(lines.next().is_some(), "no table marker");
    let header = lines.next().unwrap();
    assert_eq!(header, "| feature | with | answer | why | shown by |");
    lines
        .skip(1)
        .take_while(|l| l.starts_with('|'))
        .map(|l| {
            // no cell holds a '|' of its own
            let cells: Vec<String> = l
                .trim()
                .trim_matches('|')
                .split('|')
                .map(|c| c.trim().to_string())
                .collect();
            assert_eq!(cells.len(), 5, "a row of five cells: {l}");
            [
                cells[0].clone(),
                cells[1].clone(),
                cells[2].clone(),
                cells[4].clone(),
            ]
        })
        .collect()
}

/// The backticked words of a cell, in order.
fn quoted(cell: &str) -> Vec<&str> {
    cell.split('`').skip(1).step_by(2).collect()
}

#[test]
fn every_pair_of_the_features_table_is_tied_to_its_refusal_or_its_test() {
    let root = common::root();
    let rows = rows();
    assert!(rows.len() >= 40, "{} rows", rows.len());
    let mut refused = 0;
    for [feature, with, answer, evidence] in &rows {
        let row = format!("{feature} | {with}");
        let mut folders = 0;
        let mut functions = 0;
        let mut file: Option<String> = None;
        for word in quoted(evidence) {
            if word.contains('/') {
                let path = root.join(word);
                assert!(path.exists(), "{row}: {word} does not exist");
                if word.starts_with("tests/bad_inputs/") {
                    let expect = std::fs::read_to_string(path.join("expect.txt"))
                        .unwrap_or_else(|e| panic!("{row}: {word}/expect.txt: {e}"));
                    assert!(!expect.trim().is_empty(), "{row}: {word} expects nothing");
                    folders += 1;
                    file = None;
                } else {
                    file = Some(std::fs::read_to_string(&path).unwrap());
                }
            } else {
                let text = file
                    .as_ref()
                    .unwrap_or_else(|| panic!("{row}: `{word}` follows no file"));
                assert!(
                    text.contains(&format!("fn {word}(")),
                    "{row}: no fn {word} in the file before it"
                );
                functions += 1;
            }
        }
        if let Some(why) = answer.strip_prefix("refused: ") {
            refused += 1;
            assert!(
                REASONS.iter().any(|r| why.starts_with(r)),
                "{row}: \"{answer}\" gives none of the reasons {REASONS:?}"
            );
            assert!(folders > 0, "{row}: a refusal names no bad-input folder");
        } else {
            assert!(
                answer.starts_with("supported"),
                "{row}: \"{answer}\" is neither supported nor refused"
            );
            assert!(functions > 0, "{row}: a supported pair names no test");
        }
    }
    assert!(refused >= 30, "{refused} refused rows");
}
