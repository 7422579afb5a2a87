//! The settings a run took from the command line instead of the case file
//! (`asperity run` and `asperity check` overrides, applied by
//! `crate::app::driver::load_case`). A refusal of such a setting names the
//! option as given (`--increments 60000: …`), not a key the file may not
//! hold: every check places its key with [`Case::at`], which knows what the
//! command line replaced.

use super::Case;
use crate::input::mesh::blocks::BlockSpec;

/// What the command line replaced: for each case key, the option that set
/// it.
#[derive(Clone, Debug, Default)]
pub struct Overrides {
    /// (case key, option as given), e.g. (`[solver] increments`,
    /// `--increments 60000`), in the order applied.
    keys: Vec<(String, String)>,
    /// `--uniform`: the blocks as the case file grades them (to tell a
    /// refusal of the ungraded mesh from one of the case's own).
    pub(crate) graded_blocks: Option<Vec<BlockSpec>>,
}

impl Overrides {
    /// `option` (as given on the command line) set `key`: a case key as
    /// errors name it (`[solver] increments`), or a table (`[adapt]`) for
    /// every key in it.
    pub fn set(&mut self, key: impl Into<String>, option: impl Into<String>) {
        let key = key.into();
        self.keys.retain(|(k, _)| *k != key);
        self.keys.push((key, option.into()));
    }

    /// The option that set `key` (or the table holding it), if any.
    pub fn option(&self, key: &str) -> Option<&str> {
        self.keys
            .iter()
            .find(|(k, _)| {
                key == k
                    || key
                        .strip_prefix(k.as_str())
                        .is_some_and(|r| r.starts_with(' '))
            })
            .map(|(_, o)| o.as_str())
    }

    /// Did the command line replace anything?
    pub fn is_empty(&self) -> bool {
        self.keys.is_empty() && self.graded_blocks.is_none()
    }
}

impl Case {
    /// Where a refusal of `key` points: the option that set it on the
    /// command line (`--refine 40`), else `<case file>: <key>`.
    pub fn at(&self, key: &str) -> String {
        match self.overrides.option(key) {
            Some(option) => option.to_string(),
            None => format!("{}: {key}", self.source.display()),
        }
    }

    /// The option that set `key` on the command line, if one did.
    pub fn option(&self, key: &str) -> Option<&str> {
        self.overrides.option(key)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_key_and_the_keys_of_a_table_name_their_option() {
        let mut o = Overrides::default();
        o.set("[mesh] refine", "--refine 4");
        o.set("[adapt]", "--adapt 0.01");
        assert_eq!(o.option("[mesh] refine"), Some("--refine 4"));
        assert_eq!(o.option("[mesh] refine_region"), None);
        assert_eq!(o.option("[adapt] max_dofs"), Some("--adapt 0.01"));
        assert_eq!(o.option("[adapt]"), Some("--adapt 0.01"));
        assert_eq!(o.option("[solver] increments"), None);
        o.set("[mesh] refine", "--refine 5");
        assert_eq!(o.option("[mesh] refine"), Some("--refine 5"));
    }

    /// The record is no part of the effective case's key (the restart
    /// fingerprint): the effective values are.
    #[test]
    fn the_record_leaves_the_key_as_it_was() {
        let text = "[model]\nplane = \"strain\"\n[[mesh.block]]\nbody = \"a\"\nx = [0.0, 1.0]\nnx = [1]\ny = [0.0, 1.0]\nny = [1]\n[materials.a]\nyoung = 1.0\npoisson = 0.3\n";
        let mut case = Case::parse(text, "case.toml").unwrap();
        case.source = "case.toml".into();
        let plain = case.key();
        assert!(!plain.contains("overrides"), "{plain}");
        case.overrides.set("[mesh] refine", "--refine 2");
        case.overrides.graded_blocks = Some(case.mesh.block.clone());
        assert_eq!(case.key(), plain);
        assert_eq!(case.at("[mesh] refine"), "--refine 2");
        assert_eq!(case.at("[mesh] file"), "case.toml: [mesh] file");
    }
}
