//! Helpers shared by the integration tests.
#![allow(dead_code)]

pub mod corpus;
pub mod msh;

use asperity::input::case::Case;
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

/// Case text with `[solver] interface_loop` set (a `[solver]` table added
/// where the text has none); replaces a setting already there.
pub fn with_interface_loop(text: &str, on: bool) -> String {
    let kept: Vec<&str> = text
        .lines()
        .filter(|l| !l.trim_start().starts_with("interface_loop"))
        .collect();
    let text = kept.join("\n") + "\n";
    let key = format!("interface_loop = {on}\n");
    if text.starts_with("[solver]\n") {
        text.replacen("[solver]\n", &format!("[solver]\n{key}"), 1)
    } else if text.contains("\n[solver]\n") {
        text.replacen("\n[solver]\n", &format!("\n[solver]\n{key}"), 1)
    } else {
        format!("{text}\n[solver]\n{key}")
    }
}

/// Case text with its `[solver]` table replaced by one holding `body`
/// (TOML lines; the table must exist and not be the first line).
pub fn with_solver_table(text: &str, body: &str) -> String {
    let i = text.find("\n[solver]\n").expect("a [solver] table") + 1;
    let rest = &text[i + "[solver]\n".len()..];
    let end = rest
        .find("\n[")
        .map_or(text.len(), |j| i + "[solver]\n".len() + j + 1);
    format!("{}[solver]\n{body}\n{}", &text[..i], &text[end..])
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
    let sum = asperity::files::restart::fnv1a(&out);
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
        let sum = asperity::files::restart::fnv1a(&out);
        out.extend_from_slice(&sum.to_le_bytes());
        out
    }

    pub fn bytes(&self) -> Vec<u8> {
        self.bytes_with_count(self.sections.len() as u32)
    }
}

/// Starts the text of a case (see [`CaseText`]).
pub fn case() -> CaseText {
    CaseText::default()
}

/// Case text written in the order of the calls, for the TOML scaffolding the
/// tests repeat. A table method (`plane`, `block`, `material`, `law`, `ux`,
/// `pressure`, `solver`, ...) opens its table or array entry; a modifier
/// (`thickness`, `rx`, `plastic`, `weights`, `gap`, `history`, `x_range`,
/// `tolerances`, `with`, ...) adds a key to the table opened last; `raw`
/// adds text as it is. Values are written as `{:?}` writes them, which is
/// TOML for numbers (exactly: the shortest round trip), strings and arrays.
#[derive(Clone, Default)]
pub struct CaseText {
    text: String,
    no_vtu: bool,
}

impl CaseText {
    /// Adds `key = value` to the table opened last.
    pub fn with(mut self, key: &str, value: impl std::fmt::Debug) -> Self {
        self.text += &format!("{key} = {value:?}\n");
        self
    }

    /// Adds TOML text as it is (a line, tables), ending the line.
    pub fn raw(mut self, text: &str) -> Self {
        self.text += text;
        if !text.ends_with('\n') {
            self.text.push('\n');
        }
        self
    }

    /// `[model]` with `plane` = "stress", "strain" or "axisymmetric".
    pub fn plane(self, plane: &str) -> Self {
        self.raw("[model]").with("plane", plane)
    }

    /// Modifier of `plane`.
    pub fn thickness(self, t: f64) -> Self {
        self.with("thickness", t)
    }

    /// Modifier of `plane`: "full" or "reduced".
    pub fn integration(self, rule: &str) -> Self {
        self.with("integration", rule)
    }

    /// `[mesh]` with `refine`.
    pub fn refine(self, times: usize) -> Self {
        self.raw("[mesh]").with("refine", times)
    }

    /// A `[[mesh.block]]`: breakpoints and elements per segment in x and y.
    pub fn block(
        self,
        body: &str,
        x: impl AsRef<[f64]>,
        nx: impl AsRef<[usize]>,
        y: impl AsRef<[f64]>,
        ny: impl AsRef<[usize]>,
    ) -> Self {
        self.raw("[[mesh.block]]")
            .with("body", body)
            .with("x", x.as_ref())
            .with("nx", nx.as_ref())
            .with("y", y.as_ref())
            .with("ny", ny.as_ref())
    }

    /// Modifier of `block`: the grading of each x segment.
    pub fn rx(self, ratios: impl AsRef<[f64]>) -> Self {
        self.with("rx", ratios.as_ref())
    }

    /// Modifier of `block`: the grading of each y segment.
    pub fn ry(self, ratios: impl AsRef<[f64]>) -> Self {
        self.with("ry", ratios.as_ref())
    }

    /// A `[[mesh.interface]]` between the bottom of `upper` and the top of `lower`.
    pub fn interface(self, name: &str, upper: &str, lower: &str) -> Self {
        self.raw("[[mesh.interface]]")
            .with("name", name)
            .with("upper", upper)
            .with("lower", lower)
    }

    /// A `[[mesh.interface]]` between the right side of `left` and the left side of `right`.
    pub fn vertical_interface(self, name: &str, left: &str, right: &str) -> Self {
        self.raw("[[mesh.interface]]")
            .with("name", name)
            .with("left", left)
            .with("right", right)
    }

    /// `[materials.<body>]`, elastic.
    pub fn material(self, body: &str, young: f64, poisson: f64) -> Self {
        self.raw(&format!("[materials.{body}]"))
            .with("young", young)
            .with("poisson", poisson)
    }

    /// Modifier of `material`: von Mises plasticity with linear hardening.
    pub fn plastic(self, yield_stress: f64, hardening: f64) -> Self {
        self.with("yield_stress", yield_stress)
            .with("hardening", hardening)
    }

    /// `[interface.<name>]` with `law` ("power", "linear") and its c_n, m.
    pub fn law(self, name: &str, law: &str, c_n: f64, m: f64) -> Self {
        self.raw(&format!("[interface.{name}]"))
            .with("law", law)
            .with("c_n", c_n)
            .with("m", m)
    }

    /// Modifier of `law`: "lumped" or "consistent".
    pub fn weights(self, weights: &str) -> Self {
        self.with("weights", weights)
    }

    /// Modifier of `law`: the initial gap (negative: an interference).
    pub fn gap(self, gap: f64) -> Self {
        self.with("gap", gap)
    }

    /// `[interface.<name>.tangential]` with R, S, k_T^p/k_T^e and μ_m.
    pub fn tangential(self, name: &str, r: f64, s: f64, kp_ratio: f64, mu: f64) -> Self {
        self.raw(&format!("[interface.{name}.tangential]"))
            .with("r", r)
            .with("s", s)
            .with("kp_ratio", kp_ratio)
            .with("mu", mu)
    }

    /// `[history]`: named histories, each its points as TOML text.
    pub fn histories(self, histories: &[(&str, &str)]) -> Self {
        histories
            .iter()
            .fold(self.raw("[history]"), |case, (name, points)| {
                case.raw(&format!("{name} = {points}"))
            })
    }

    /// A `[[boundary]]` prescribing `ux` on a node set.
    pub fn ux(self, set: &str, ux: f64) -> Self {
        self.raw("[[boundary]]").with("set", set).with("ux", ux)
    }

    /// A `[[boundary]]` prescribing `uy` on a node set.
    pub fn uy(self, set: &str, uy: f64) -> Self {
        self.raw("[[boundary]]").with("set", set).with("uy", uy)
    }

    /// A `[[boundary]]` holding a node set in x and y.
    pub fn fixed(self, set: &str) -> Self {
        self.ux(set, 0.0).with("uy", 0.0)
    }

    /// A `[[load]]` pressing on an edge set (add a `shear` with `with`).
    pub fn pressure(self, edges: &str, pressure: f64) -> Self {
        self.raw("[[load]]")
            .with("edges", edges)
            .with("pressure", pressure)
    }

    /// A `[[load]]` shearing an edge set.
    pub fn shear(self, edges: &str, shear: f64) -> Self {
        self.raw("[[load]]")
            .with("edges", edges)
            .with("shear", shear)
    }

    /// Modifier of a boundary or load: it follows the named history.
    pub fn history(self, name: &str) -> Self {
        self.with("history", name)
    }

    /// Modifier of a boundary or load: only where x is in [from, to].
    pub fn x_range(self, from: f64, to: f64) -> Self {
        self.with("x_range", [from, to])
    }

    /// Modifier of a boundary or load: only where y is in [from, to].
    pub fn y_range(self, from: f64, to: f64) -> Self {
        self.with("y_range", [from, to])
    }

    /// `[solver]` with its keys as TOML text.
    pub fn solver(self, keys: &str) -> Self {
        self.raw("[solver]").raw(keys)
    }

    /// Modifier of `solver`: the residual and displacement tolerances.
    pub fn tolerances(self, residual: f64, displacement: f64) -> Self {
        self.with("residual_tolerance", residual)
            .with("displacement_tolerance", displacement)
    }

    /// Ends the case with `[output]` `vtu = false`.
    pub fn no_vtu(mut self) -> Self {
        self.no_vtu = true;
        self
    }

    /// The case text.
    pub fn build(self) -> String {
        let mut text = self.text;
        if self.no_vtu {
            text += "[output]\nvtu = false\n";
        }
        text
    }
}

/// The values of the named `<DataArray>` of a VTU file the program wrote, as
/// numbers, in either encoding: the text inside the tag (`ascii`), or the
/// raw appended block at the tag's offset (`binary`: after the `_` that opens
/// `<AppendedData encoding="raw">`, a UInt64 byte count, then the values,
/// little-endian; Float64, Int64 or UInt8). Every size is checked against
/// the file before it is read.
pub fn vtu_array(path: &std::path::Path, name: &str) -> Vec<f64> {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let appended = bytes
        .windows(13)
        .position(|w| w == b"<AppendedData")
        .unwrap_or(bytes.len());
    let xml = std::str::from_utf8(&bytes[..appended]).expect("the XML part is UTF-8");
    let tag = format!("Name=\"{name}\"");
    let start = xml
        .find(&tag)
        .map(|i| xml[..i].rfind('<').unwrap())
        .unwrap_or_else(|| panic!("{}: no array {name}", path.display()));
    let open = &xml[start..start + xml[start..].find('>').unwrap()];
    let attr = |key: &str| {
        let k = format!(" {key}=\"");
        open.find(&k).map(|i| {
            let v = &open[i + k.len()..];
            v[..v.find('"').unwrap()].to_string()
        })
    };
    match attr("format").as_deref() {
        Some("ascii") => {
            let body = &xml[start + open.len() + 1..];
            body[..body.find("</DataArray>").unwrap()]
                .split_whitespace()
                .map(|v| v.parse().unwrap())
                .collect()
        }
        Some("appended") => {
            assert!(
                xml.contains("header_type=\"UInt64\""),
                "UInt64 block headers"
            );
            assert!(xml.contains("byte_order=\"LittleEndian\""));
            let tail = &bytes[appended..];
            assert!(tail.starts_with(b"<AppendedData encoding=\"raw\">"));
            let underscore = appended + tail.iter().position(|&b| b == b'_').expect("the _ mark");
            let offset: usize = attr("offset").expect("an offset").parse().unwrap();
            let at = underscore + 1 + offset;
            assert!(at + 8 <= bytes.len(), "{name}: offset past the end");
            let count = u64::from_le_bytes(bytes[at..at + 8].try_into().unwrap()) as usize;
            assert!(count <= bytes.len() - at - 8, "{name}: block past the end");
            let block = &bytes[at + 8..at + 8 + count];
            match attr("type").as_deref() {
                Some("Float64") => block
                    .chunks_exact(8)
                    .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
                    .collect(),
                Some("Int64") => block
                    .chunks_exact(8)
                    .map(|c| i64::from_le_bytes(c.try_into().unwrap()) as f64)
                    .collect(),
                Some("UInt8") => block.iter().map(|&b| f64::from(b)).collect(),
                t => panic!("{name}: type {t:?}"),
            }
        }
        f => panic!("{}: {name} has format {f:?}", path.display()),
    }
}

pub const BAR_E: f64 = 200_000.0;
pub const BAR_L: f64 = 100.0;
pub const BAR_H: f64 = 10.0;
pub const BAR_T: f64 = 2.0;

/// A plane-stress bar [0, L] × [0, H], thickness T, held in x at both ends
/// (and in y at one corner), cut at x = 30 by section "bolt"; `section` and
/// `more` complete it.
pub fn pretension_bar(section: &str, more: &str) -> String {
    format!(
        r#"
[model]
plane = "stress"
thickness = {BAR_T}
[[mesh.block]]
body = "bar"
x = [0.0, 30.0, 60.0, {BAR_L}]
nx = [3, 3, 4]
y = [0.0, {BAR_H}]
ny = [2]
[materials.bar]
young = {BAR_E}
poisson = 0.3
[[boundary]]
set = "bar.left"
ux = 0.0
[[boundary]]
set = "bar.right"
ux = 0.0
[[boundary]]
set = "bar.left"
uy = 0.0
y_range = [0.0, 0.0]
[[pretension]]
name = "bolt"
body = "bar"
x = 30.0
{section}
{more}
[output]
vtu_every = 1000
"#
    )
}

/// Column `name` of a CSV file the program writes, as numbers (an empty
/// field is NaN).
pub fn csv_column(path: &std::path::Path, name: &str) -> Vec<f64> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path:?}: {e}"));
    let mut lines = text.lines();
    let head: Vec<&str> = lines.next().unwrap_or_default().split(',').collect();
    let k = head
        .iter()
        .position(|h| *h == name)
        .unwrap_or_else(|| panic!("no column {name} in {head:?}"));
    lines
        .map(|l| match l.split(',').nth(k) {
            Some("") => f64::NAN,
            Some(v) => v.parse().unwrap_or_else(|e| panic!("{name} = {v:?}: {e}")),
            None => panic!("{path:?}: a row without {name}: {l}"),
        })
        .collect()
}

/// `asperity run DIR --out OUT --quiet`, which must succeed.
pub fn run_ok(dir: &std::path::Path, out: &std::path::Path) {
    let (code, err) = run_asperity(&[
        "run",
        dir.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    assert_eq!(code, 0, "{}: {err}", dir.display());
}

/// Runs the built program: its exit code and its stderr.
pub fn run_asperity(args: &[&str]) -> (i32, String) {
    let (code, err, _) = run_asperity_out(args);
    (code, err)
}

/// [`run_asperity`] with stdout too: (exit code, stderr, stdout).
#[allow(dead_code)]
pub fn run_asperity_out(args: &[&str]) -> (i32, String, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_asperity"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into(),
        String::from_utf8_lossy(&out.stdout).into(),
    )
}

/// An observer that records nothing (runs whose result alone is checked).
pub struct Quiet;
impl asperity::solve::Observer for Quiet {
    fn increment(
        &mut self,
        _: &Model,
        _: &asperity::solve::State,
        _: &asperity::solve::Increment,
    ) -> asperity::Result<()> {
        Ok(())
    }
}

/// `asperity run CASE --out OUT --quiet EXTRA...`: exit code and stderr.
pub fn run_case(case: &std::path::Path, out: &std::path::Path, extra: &[&str]) -> (i32, String) {
    let (c, o) = (case.display().to_string(), out.display().to_string());
    let mut args = vec!["run", &c, "--out", &o, "--quiet"];
    args.extend_from_slice(extra);
    run_asperity(&args)
}

/// A file the run wrote into `dir`, whole.
pub fn read_out(dir: &std::path::Path, file: &str) -> String {
    std::fs::read_to_string(dir.join(file)).unwrap_or_else(|e| panic!("{file}: {e}"))
}
