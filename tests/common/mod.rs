//! Helpers shared by the integration tests.
#![allow(dead_code)]

use asperity::case::Case;
use asperity::model::Model;
use std::path::PathBuf;

/// A fresh, empty scratch folder under the target directory.
pub fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Builds a model from case text.
pub fn model(text: &str) -> Model {
    let case = Case::parse(text, "test.toml").unwrap_or_else(|e| panic!("{e}"));
    Model::build(case).unwrap_or_else(|e| panic!("{e}"))
}

/// Writes a case folder and returns the path of its case.toml.
pub fn case_dir(name: &str, text: &str) -> PathBuf {
    let dir = scratch(name);
    let p = dir.join("case.toml");
    std::fs::write(&p, text).unwrap();
    p
}

/// The project root (for cases/).
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Relative difference |a − b| / max(|a|, |b|, tiny).
pub fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / a.abs().max(b.abs()).max(1e-300)
}

/// A restart file without the named sections, as an earlier build wrote it
/// (checksum recomputed); every name must be a section of the file.
pub fn strip_restart_sections(bytes: &[u8], names: &[&str]) -> Vec<u8> {
    let body = &bytes[..bytes.len() - 8];
    let n = u32::from_le_bytes(body[24..28].try_into().unwrap());
    let mut at = 28;
    let mut kept = Vec::new();
    let mut count = 0u32;
    for _ in 0..n {
        let start = at;
        let len = u16::from_le_bytes(body[at..at + 2].try_into().unwrap()) as usize;
        let name = std::str::from_utf8(&body[at + 2..at + 2 + len])
            .unwrap()
            .to_string();
        let kind = body[at + 2 + len];
        let cnt =
            u64::from_le_bytes(body[at + 3 + len..at + 11 + len].try_into().unwrap()) as usize;
        at += 11 + len + cnt * if kind <= 2 { 8 } else { 1 };
        if !names.contains(&name.as_str()) {
            kept.extend_from_slice(&body[start..at]);
            count += 1;
        }
    }
    assert_eq!(at, body.len());
    assert_eq!(
        count as usize + names.len(),
        n as usize,
        "the file had every section of {names:?}"
    );
    let mut out = body[..24].to_vec();
    out.extend_from_slice(&count.to_le_bytes());
    out.extend_from_slice(&kept);
    let sum = asperity::restart::fnv1a(&out);
    out.extend_from_slice(&sum.to_le_bytes());
    out
}

/// One section of a restart file: name, kind, element count, payload.
#[derive(Clone)]
pub struct Section {
    pub name: String,
    pub kind: u8,
    pub count: u64,
    pub data: Vec<u8>,
}

/// A restart file taken apart into its sections, to change some and write
/// it back with a recomputed checksum, as anyone can (the format is public,
/// docs/running.md).
#[derive(Clone)]
pub struct Forge {
    /// Magic, version, reserved and fingerprint.
    pub head: Vec<u8>,
    pub sections: Vec<Section>,
}

impl Forge {
    pub fn parse(bytes: &[u8]) -> Forge {
        let body = &bytes[..bytes.len() - 8];
        let n = u32::from_le_bytes(body[24..28].try_into().unwrap());
        let mut at = 28;
        let mut sections = Vec::new();
        for _ in 0..n {
            let len = u16::from_le_bytes(body[at..at + 2].try_into().unwrap()) as usize;
            let name = String::from_utf8(body[at + 2..at + 2 + len].to_vec()).unwrap();
            let kind = body[at + 2 + len];
            let count = u64::from_le_bytes(body[at + 3 + len..at + 11 + len].try_into().unwrap());
            at += 11 + len;
            let size = count as usize * if kind <= 2 { 8 } else { 1 };
            sections.push(Section {
                name,
                kind,
                count,
                data: body[at..at + size].to_vec(),
            });
            at += size;
        }
        assert_eq!(at, body.len());
        Forge {
            head: body[..24].to_vec(),
            sections,
        }
    }

    pub fn get(&mut self, name: &str) -> &mut Section {
        self.sections
            .iter_mut()
            .find(|s| s.name == name)
            .unwrap_or_else(|| panic!("no section {name}"))
    }

    pub fn f64s(&mut self, name: &str) -> Vec<f64> {
        self.get(name)
            .data
            .chunks_exact(8)
            .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
            .collect()
    }

    pub fn u64s(&mut self, name: &str) -> Vec<u64> {
        self.get(name)
            .data
            .chunks_exact(8)
            .map(|c| u64::from_le_bytes(c.try_into().unwrap()))
            .collect()
    }

    pub fn text(&mut self, name: &str) -> String {
        String::from_utf8(self.get(name).data.clone()).unwrap()
    }

    pub fn set_f64s(&mut self, name: &str, v: &[f64]) {
        let s = self.get(name);
        s.count = v.len() as u64;
        s.data = v.iter().flat_map(|x| x.to_le_bytes()).collect();
    }

    pub fn set_u64s(&mut self, name: &str, v: &[u64]) {
        let s = self.get(name);
        s.count = v.len() as u64;
        s.data = v.iter().flat_map(|x| x.to_le_bytes()).collect();
    }

    pub fn set_bytes(&mut self, name: &str, v: &[u8]) {
        let s = self.get(name);
        s.count = v.len() as u64;
        s.data = v.to_vec();
    }

    /// The file, with this section count in the header.
    pub fn bytes_with_count(&self, n: u32) -> Vec<u8> {
        let mut out = self.head.clone();
        out.extend_from_slice(&n.to_le_bytes());
        for s in &self.sections {
            out.extend_from_slice(&(s.name.len() as u16).to_le_bytes());
            out.extend_from_slice(s.name.as_bytes());
            out.push(s.kind);
            out.extend_from_slice(&s.count.to_le_bytes());
            out.extend_from_slice(&s.data);
        }
        let sum = asperity::restart::fnv1a(&out);
        out.extend_from_slice(&sum.to_le_bytes());
        out
    }

    pub fn bytes(&self) -> Vec<u8> {
        self.bytes_with_count(self.sections.len() as u32)
    }
}
