//! Meshes read from Gmsh `.msh` files, format version 4.1, ASCII or binary.
//!
//! Physical surfaces become bodies (named by their physical names), physical
//! curves become node sets and edge sets of the same name, and each
//! `[[mesh.interface]]` pairs the nodes of an upper body's curve with the
//! coincident nodes of a lower body's curve. Bodies must be meshed with 8-node
//! quads (element type 16) and curves with 3-node lines (type 8): in Gmsh,
//! `Mesh.ElementOrder = 2; Mesh.SecondOrderIncomplete = 1;` and recombined
//! surfaces. See `docs/gmsh.md`.
//!
//! The reader never panics: every count is checked against the bytes left in
//! the file before anything is allocated, arithmetic is checked, and every
//! error is one line naming the file and the line (ASCII) or byte offset
//! (binary data) where the problem is.

use super::{ContactEdge, Element, Interface, Mesh};
use crate::error::{Error, Result};
use crate::mesh::blocks::InterfaceSpec;
use std::collections::{BTreeMap, HashMap};
use std::path::Path;

/// One block of elements of one type on one geometric entity.
#[derive(Clone, Debug, PartialEq)]
pub struct ElementBlock {
    pub dim: i32,
    pub entity: i32,
    pub etype: i32,
    /// Where the block header is (for errors).
    pub at: String,
    /// Element tags.
    pub tags: Vec<u64>,
    /// Node indices into [`MshFile::nodes`], `nodes_per_element` per element.
    pub conn: Vec<usize>,
}

/// The contents of a `.msh` file that asperity uses.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MshFile {
    /// The file's name, for errors.
    pub name: String,
    pub binary: bool,
    /// (dimension, physical tag) → name.
    pub physical_names: BTreeMap<(i32, i32), String>,
    /// (dimension, entity tag) → physical tags of that entity.
    pub entities: BTreeMap<(i32, i32), Vec<i32>>,
    /// Node tags in file order.
    pub node_tags: Vec<u64>,
    /// Node coordinates (x, y) in file order.
    pub nodes: Vec<[f64; 2]>,
    pub blocks: Vec<ElementBlock>,
}

/// Nodes per element of the element types asperity reads, with their names.
fn element_type(t: i32) -> Option<(usize, i32, &'static str)> {
    match t {
        15 => Some((1, 0, "1-node point")),
        8 => Some((3, 1, "3-node line")),
        16 => Some((8, 2, "8-node quadrangle")),
        _ => None,
    }
}

fn element_type_name(t: i32) -> &'static str {
    match t {
        1 => "2-node line",
        2 => "3-node triangle",
        3 => "4-node quadrangle",
        4 => "4-node tetrahedron",
        5 => "8-node hexahedron",
        6 => "6-node prism",
        7 => "5-node pyramid",
        9 => "6-node triangle",
        10 => "9-node quadrangle",
        11 => "10-node tetrahedron",
        17 => "20-node hexahedron",
        _ => "unknown type",
    }
}

const SECTIONS_WE_READ: [&str; 5] = [
    "MeshFormat",
    "PhysicalNames",
    "Entities",
    "Nodes",
    "Elements",
];

/// A cursor over the file's bytes. In ASCII mode numbers are whitespace
/// separated tokens; in binary mode (inside the binary sections of a binary
/// file) ints are 4 bytes, size_t 8 bytes and doubles 8 bytes, little-endian.
struct Cursor<'a> {
    b: &'a [u8],
    pos: usize,
    name: &'a str,
    binary: bool,
}

impl<'a> Cursor<'a> {
    fn place(&self, at: usize) -> String {
        if self.binary {
            format!("{} (byte {at})", self.name)
        } else {
            let at = at.min(self.b.len());
            let line = self.b[..at].iter().filter(|&&c| c == b'\n').count() + 1;
            format!("{}:{line}", self.name)
        }
    }

    fn err<T>(&self, at: usize, message: impl Into<String>) -> Result<T> {
        Err(Error::Mesh {
            place: self.place(at),
            message: message.into(),
        })
    }

    fn left(&self) -> usize {
        self.b.len().saturating_sub(self.pos)
    }

    fn skip_ws(&mut self) {
        while self.pos < self.b.len() && self.b[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
    }

    /// The next whitespace-separated token and where it starts.
    fn token(&mut self, what: &str) -> Result<(usize, &'a [u8])> {
        self.skip_ws();
        if self.pos >= self.b.len() {
            return self.err(
                self.pos,
                format!("unexpected end of file, expected {what} (truncated file?)"),
            );
        }
        let start = self.pos;
        while self.pos < self.b.len() && !self.b[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
        Ok((start, &self.b[start..self.pos]))
    }

    fn parse_tok<T: std::str::FromStr>(&mut self, what: &str, kind: &str) -> Result<(usize, T)> {
        let (at, tok) = self.token(what)?;
        match std::str::from_utf8(tok)
            .ok()
            .and_then(|s| s.parse::<T>().ok())
        {
            Some(v) => Ok((at, v)),
            None => self.err(
                at,
                format!("expected {what} ({kind}), found \"{}\"", shown(tok)),
            ),
        }
    }

    fn bytes(&mut self, n: usize, what: &str) -> Result<&'a [u8]> {
        if self.left() < n {
            return self.err(
                self.pos,
                format!("unexpected end of file in {what} (truncated file?)"),
            );
        }
        let s = &self.b[self.pos..self.pos + n];
        self.pos += n;
        Ok(s)
    }

    /// An `int` field.
    fn int(&mut self, what: &str) -> Result<(usize, i32)> {
        if self.binary {
            let at = self.pos;
            let s = self.bytes(4, what)?;
            Ok((at, i32::from_le_bytes([s[0], s[1], s[2], s[3]])))
        } else {
            self.parse_tok(what, "an integer")
        }
    }

    /// A `size_t` field.
    fn size(&mut self, what: &str) -> Result<(usize, u64)> {
        if self.binary {
            let at = self.pos;
            let s = self.bytes(8, what)?;
            let mut a = [0u8; 8];
            a.copy_from_slice(s);
            Ok((at, u64::from_le_bytes(a)))
        } else {
            self.parse_tok(what, "a non-negative integer")
        }
    }

    /// A `double` field.
    fn real(&mut self, what: &str) -> Result<(usize, f64)> {
        if self.binary {
            let at = self.pos;
            let s = self.bytes(8, what)?;
            let mut a = [0u8; 8];
            a.copy_from_slice(s);
            Ok((at, f64::from_le_bytes(a)))
        } else {
            self.parse_tok(what, "a number")
        }
    }

    /// A count that must fit in what is left of the file, `min_bytes` per item.
    fn count(&mut self, what: &str, min_bytes: usize) -> Result<usize> {
        let (at, n) = self.size(what)?;
        let fits = usize::try_from(n)
            .ok()
            .filter(|&n| n.checked_mul(min_bytes).is_some_and(|b| b <= self.left()));
        match fits {
            Some(n) => Ok(n),
            None => self.err(
                at,
                format!(
                    "bad count: {what} = {n} is more than the {} bytes left in the file can hold (truncated file?)",
                    self.left()
                ),
            ),
        }
    }

    /// Bytes per item for count checks: `ints`, `sizes`, `reals` fields.
    fn item_bytes(&self, ints: usize, sizes: usize, reals: usize) -> usize {
        if self.binary {
            4 * ints + 8 * sizes + 8 * reals
        } else {
            2 * (ints + sizes + reals) // at least one digit and one separator each
        }
    }

    /// After a section header in a binary file: the end of the header line.
    fn end_of_header_line(&mut self, section: &str) -> Result<()> {
        while self.pos < self.b.len() && (self.b[self.pos] == b' ' || self.b[self.pos] == b'\r') {
            self.pos += 1;
        }
        if self.pos < self.b.len() && self.b[self.pos] == b'\n' {
            self.pos += 1;
            Ok(())
        } else {
            self.err(self.pos, format!("expected a line end after ${section}"))
        }
    }

    /// Expects the `$End…` line of a section.
    fn end_section(&mut self, section: &str) -> Result<()> {
        self.binary = false;
        let want = format!("$End{section}");
        let (at, tok) = self.token(&want)?;
        if tok != want.as_bytes() {
            return self.err(
                at,
                format!(
                    "expected {want}, found \"{}\" (bad counts in ${section}?)",
                    shown(tok)
                ),
            );
        }
        Ok(())
    }
}

/// A token for an error message: printable, at most 24 characters.
fn shown(tok: &[u8]) -> String {
    let s: String = String::from_utf8_lossy(tok)
        .chars()
        .map(|c| if c.is_control() { '?' } else { c })
        .take(24)
        .collect();
    if tok.len() > 24 {
        format!("{s}…")
    } else {
        s
    }
}

/// Parses the bytes of a `.msh` 4.1 file (ASCII or binary); `name` names the
/// file in errors.
pub fn parse_msh(bytes: &[u8], name: &str) -> Result<MshFile> {
    let mut c = Cursor {
        b: bytes,
        pos: 0,
        name,
        binary: false,
    };
    let mut msh = MshFile {
        name: name.to_string(),
        ..MshFile::default()
    };
    let mut seen: Vec<String> = Vec::new();
    let mut tag_index: HashMap<u64, usize> = HashMap::new();
    loop {
        c.skip_ws();
        if c.pos >= bytes.len() {
            break;
        }
        let (at, tok) = c.token("a section header")?;
        if seen.is_empty() && tok != b"$MeshFormat" {
            return c.err(at, "not a Gmsh mesh file: it must start with $MeshFormat");
        }
        let Some(section) = tok.strip_prefix(b"$") else {
            return c.err(
                at,
                format!(
                    "expected a section header such as $Nodes, found \"{}\"",
                    shown(tok)
                ),
            );
        };
        let section = String::from_utf8_lossy(section).into_owned();
        if SECTIONS_WE_READ.contains(&section.as_str()) && seen.contains(&section) {
            return c.err(at, format!("section ${section} appears twice"));
        }
        let binary_section =
            msh.binary && matches!(section.as_str(), "Entities" | "Nodes" | "Elements");
        if binary_section {
            c.end_of_header_line(&section)?;
            c.binary = true;
        }
        match section.as_str() {
            "MeshFormat" => mesh_format(&mut c, &mut msh)?,
            "PhysicalNames" => physical_names(&mut c, &mut msh)?,
            "Entities" => entities(&mut c, &mut msh)?,
            "Nodes" => nodes(&mut c, &mut msh, &mut tag_index)?,
            "Elements" => elements(&mut c, &mut msh, &tag_index)?,
            "PartitionedEntities" => {
                return c.err(
                    at,
                    "partitioned meshes are not supported (save the mesh unpartitioned)",
                )
            }
            s if s.starts_with("End") => {
                return c.err(at, format!("${section} without its section"))
            }
            _ => {
                // skip an unknown section: find its end line
                let end = format!("$End{section}");
                let from = c.pos;
                let found = bytes[from..]
                    .windows(end.len())
                    .position(|w| w == end.as_bytes());
                match found {
                    Some(i) => c.pos = from + i + end.len(),
                    None => {
                        return c.err(
                            at,
                            format!("section ${section} has no {end} (truncated file?)"),
                        )
                    }
                }
            }
        }
        if !binary_section {
            c.binary = false;
        }
        seen.push(section);
    }
    for s in SECTIONS_WE_READ {
        if !seen.iter().any(|x| x == s) {
            let what = if seen.is_empty() {
                "empty file: not a Gmsh mesh".to_string()
            } else {
                format!("missing section ${s} (truncated file?)")
            };
            return Err(Error::Mesh {
                place: name.to_string(),
                message: what,
            });
        }
    }
    Ok(msh)
}

fn mesh_format(c: &mut Cursor, msh: &mut MshFile) -> Result<()> {
    let (at, version) = c.token("the MSH version")?;
    if version != b"4.1" {
        return c.err(
            at,
            format!(
                "MSH format version {} is not supported: asperity reads version 4.1 (Gmsh: Mesh.MshFileVersion = 4.1)",
                shown(version)
            ),
        );
    }
    let (at, file_type) = c.int("the file type (0 ASCII, 1 binary)")?;
    if !(file_type == 0 || file_type == 1) {
        return c.err(
            at,
            format!("file type {file_type} must be 0 (ASCII) or 1 (binary)"),
        );
    }
    let (at, data_size) = c.int("the data size")?;
    if data_size != 8 {
        return c.err(
            at,
            format!("data size {data_size} is not supported (size_t must be 8 bytes)"),
        );
    }
    msh.binary = file_type == 1;
    if msh.binary {
        c.end_of_header_line("MeshFormat")?;
        let at = c.pos;
        c.binary = true;
        let (_, one) = c.int("the endianness check")?;
        c.binary = false;
        if one != 1 {
            let msg = if one.swap_bytes() == 1 {
                "the binary mesh is big-endian; asperity reads little-endian files only".to_string()
            } else {
                format!("the endianness check reads {one}, expected 1 (corrupt binary header)")
            };
            return Err(Error::Mesh {
                place: format!("{} (byte {at})", c.name),
                message: msg,
            });
        }
    }
    c.end_section("MeshFormat")
}

fn physical_names(c: &mut Cursor, msh: &mut MshFile) -> Result<()> {
    c.binary = false;
    let n = c.count("the number of physical names", 8)?;
    for _ in 0..n {
        let (_, dim) = c.int("a physical dimension")?;
        let (at, tag) = c.int("a physical tag")?;
        if !(0..=3).contains(&dim) {
            return c.err(at, format!("physical dimension {dim} must be 0 to 3"));
        }
        c.skip_ws();
        let at = c.pos;
        if c.pos >= c.b.len() || c.b[c.pos] != b'"' {
            return c.err(at, "expected a quoted physical name");
        }
        let rest = &c.b[c.pos + 1..];
        let Some(len) = rest.iter().position(|&b| b == b'"' || b == b'\n') else {
            return c.err(
                at,
                "the physical name has no closing quote (truncated file?)",
            );
        };
        if rest[len] != b'"' {
            return c.err(at, "the physical name has no closing quote on its line");
        }
        let Ok(name) = std::str::from_utf8(&rest[..len]) else {
            return c.err(at, "the physical name is not valid UTF-8");
        };
        if name.is_empty() {
            return c.err(at, "empty physical name");
        }
        if msh
            .physical_names
            .iter()
            .any(|(&(d, _), m)| m == name && (d == dim || (d >= 1 && dim >= 1)))
        {
            return c.err(
                at,
                format!("physical name \"{name}\" is used twice (names must be unique)"),
            );
        }
        if msh
            .physical_names
            .insert((dim, tag), name.to_string())
            .is_some()
        {
            return c.err(
                at,
                format!("physical tag {tag} of dimension {dim} is named twice"),
            );
        }
        c.pos += 1 + len + 1;
    }
    c.end_section("PhysicalNames")
}

fn entities(c: &mut Cursor, msh: &mut MshFile) -> Result<()> {
    let mut counts = [0usize; 4];
    let names = ["points", "curves", "surfaces", "volumes"];
    for (k, n) in counts.iter_mut().enumerate() {
        let per = c.item_bytes(1, 1, 3);
        *n = c.count(&format!("the number of {}", names[k]), per)?;
    }
    for (dim, &n) in counts.iter().enumerate() {
        for _ in 0..n {
            let (at, tag) = c.int("an entity tag")?;
            let coords = if dim == 0 { 3 } else { 6 };
            for _ in 0..coords {
                c.real("an entity bounding box coordinate")?;
            }
            let per = c.item_bytes(1, 0, 0);
            let np = c.count("the number of physical tags", per)?;
            let mut phys = Vec::with_capacity(np);
            for _ in 0..np {
                phys.push(c.int("a physical tag")?.1);
            }
            if dim > 0 {
                let nb = c.count("the number of bounding entities", per)?;
                for _ in 0..nb {
                    c.int("a bounding entity tag")?;
                }
            }
            if msh.entities.insert((dim as i32, tag), phys).is_some() {
                return c.err(
                    at,
                    format!("entity {tag} of dimension {dim} is listed twice"),
                );
            }
        }
    }
    c.end_section("Entities")
}

fn nodes(c: &mut Cursor, msh: &mut MshFile, tag_index: &mut HashMap<u64, usize>) -> Result<()> {
    let per_block = c.item_bytes(3, 1, 0);
    let nblocks = c.count("the number of node blocks", per_block)?;
    let per_node = c.item_bytes(0, 1, 3);
    let (at_total, _) = (c.pos, ());
    let total = c.count("the number of nodes", per_node)?;
    c.size("the minimum node tag")?;
    c.size("the maximum node tag")?;
    msh.nodes.reserve(total);
    msh.node_tags.reserve(total);
    tag_index.reserve(total);
    let mut read = 0usize;
    for _ in 0..nblocks {
        let (_, dim) = c.int("an entity dimension")?;
        let (_, _entity) = c.int("an entity tag")?;
        let (at, parametric) = c.int("the parametric flag")?;
        if !(0..=3).contains(&dim) || !(parametric == 0 || parametric == 1) {
            return c.err(
                at,
                format!("bad node block header: dimension {dim}, parametric flag {parametric}"),
            );
        }
        let extra = if parametric == 1 { dim as usize } else { 0 };
        let per = c.item_bytes(0, 1, 3 + extra);
        let n = c.count("the number of nodes in the block", per)?;
        read = read.saturating_add(n);
        if read > total {
            return c.err(
                at,
                format!("bad counts: the node blocks hold more than the {total} nodes announced"),
            );
        }
        let first = msh.node_tags.len();
        for _ in 0..n {
            let (at, tag) = c.size("a node tag")?;
            if tag == 0 {
                return c.err(at, "node tag 0 (tags start at 1)");
            }
            if tag_index.insert(tag, msh.node_tags.len()).is_some() {
                return c.err(at, format!("node tag {tag} appears twice"));
            }
            msh.node_tags.push(tag);
        }
        for k in 0..n {
            let tag = msh.node_tags[first + k];
            let mut x = [0.0; 3];
            let mut at_x = c.pos;
            for (i, xi) in x.iter_mut().enumerate() {
                let (at, v) = c.real("a node coordinate")?;
                if i == 0 {
                    at_x = at;
                }
                if !v.is_finite() {
                    return c.err(
                        at,
                        format!(
                            "node {tag}: coordinate {} is {v}, not a finite number",
                            ["x", "y", "z"][i]
                        ),
                    );
                }
                *xi = v;
            }
            if x[2].abs() > 1e-12 * x[0].abs().max(x[1].abs()).max(1.0) {
                return c.err(
                    at_x,
                    format!(
                        "node {tag} has z = {}: asperity is 2D, the mesh must lie in the plane z = 0",
                        x[2]
                    ),
                );
            }
            for _ in 0..extra {
                c.real("a parametric node coordinate")?;
            }
            msh.nodes.push([x[0], x[1]]);
        }
    }
    if read != total {
        return c.err(
            at_total,
            format!("bad counts: $Nodes announces {total} nodes but its blocks hold {read}"),
        );
    }
    c.end_section("Nodes")
}

fn elements(c: &mut Cursor, msh: &mut MshFile, tag_index: &HashMap<u64, usize>) -> Result<()> {
    let per_block = c.item_bytes(3, 1, 0);
    let nblocks = c.count("the number of element blocks", per_block)?;
    let at_total = c.pos;
    let total = c.count("the number of elements", c.item_bytes(0, 2, 0))?;
    c.size("the minimum element tag")?;
    c.size("the maximum element tag")?;
    let mut read = 0usize;
    for _ in 0..nblocks {
        let (at_block, dim) = c.int("an entity dimension")?;
        let (_, entity) = c.int("an entity tag")?;
        let (at, etype) = c.int("an element type")?;
        let Some((nn, tdim, _)) = element_type(etype) else {
            let hint = match etype {
                1..=3 => ": the mesh is first order; set Mesh.ElementOrder = 2 and Mesh.SecondOrderIncomplete = 1",
                9 => ": mesh the surfaces with quadrangles (Recombine Surface, or Mesh.RecombineAll = 1)",
                10 => ": set Mesh.SecondOrderIncomplete = 1 for 8-node quadrangles",
                _ => "",
            };
            return c.err(
                at,
                format!(
                    "element type {etype} ({}) not supported: asperity reads 8-node quadrangles (16) and 3-node lines (8){hint}",
                    element_type_name(etype)
                ),
            );
        };
        if dim != tdim {
            return c.err(
                at,
                format!("element type {etype} in an entity of dimension {dim} (expected {tdim})"),
            );
        }
        let per = c.item_bytes(0, 1 + nn, 0);
        let n = c.count("the number of elements in the block", per)?;
        read = read.saturating_add(n);
        if read > total {
            return c.err(
                at,
                format!(
                    "bad counts: the element blocks hold more than the {total} elements announced"
                ),
            );
        }
        let mut block = ElementBlock {
            dim,
            entity,
            etype,
            at: c.place(at_block),
            tags: Vec::with_capacity(n),
            conn: Vec::with_capacity(n * nn),
        };
        for _ in 0..n {
            let (_, tag) = c.size("an element tag")?;
            block.tags.push(tag);
            for _ in 0..nn {
                let (at, node) = c.size("a node tag")?;
                match tag_index.get(&node) {
                    Some(&i) => block.conn.push(i),
                    None => {
                        return c.err(
                            at,
                            format!("element {tag} refers to unknown node tag {node} (not in $Nodes, or $Nodes comes after $Elements)"),
                        )
                    }
                }
            }
        }
        msh.blocks.push(block);
    }
    if read != total {
        return c.err(
            at_total,
            format!("bad counts: $Elements announces {total} elements but its blocks hold {read}"),
        );
    }
    c.end_section("Elements")
}

/// Reads a `.msh` file and builds the mesh: bodies from physical surfaces,
/// node and edge sets from physical curves, and the interfaces.
/// `place` names the case (for errors about its keys).
pub fn read(path: &Path, interfaces: &[InterfaceSpec], place: &str) -> Result<Mesh> {
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    let msh = parse_msh(&bytes, &path.display().to_string())?;
    build_mesh(&msh, interfaces, place)
}

fn mesh_err<T>(place: &str, message: impl Into<String>) -> Result<T> {
    Err(Error::Mesh {
        place: place.to_string(),
        message: message.into(),
    })
}

/// Builds the mesh from a parsed file.
pub fn build_mesh(msh: &MshFile, interfaces: &[InterfaceSpec], place: &str) -> Result<Mesh> {
    let file = msh.name.as_str();
    // physical surfaces → bodies, in order of their tags
    let mut block_body: Vec<Option<usize>> = vec![None; msh.blocks.len()];
    let mut body_tags: Vec<i32> = Vec::new();
    for (k, b) in msh.blocks.iter().enumerate() {
        if b.dim != 2 || b.tags.is_empty() {
            continue;
        }
        let Some(phys) = msh.entities.get(&(2, b.entity)) else {
            return mesh_err(
                &b.at,
                format!("surface entity {} is not listed in $Entities", b.entity),
            );
        };
        match phys.as_slice() {
            [] => {
                return mesh_err(
                    &b.at,
                    format!("surface entity {} has elements but is in no physical surface (every body must be a named physical surface)", b.entity),
                )
            }
            [t] => {
                if !msh.physical_names.contains_key(&(2, *t)) {
                    return mesh_err(
                        file,
                        format!("physical surface {t} has no name in $PhysicalNames (bodies are named by their physical names)"),
                    );
                }
                if !body_tags.contains(t) {
                    body_tags.push(*t);
                }
                block_body[k] = Some(*t as usize); // replaced by the body index below
            }
            more => {
                return mesh_err(
                    &b.at,
                    format!("surface entity {} is in physical surfaces {more:?}; it must belong to exactly one (one body)", b.entity),
                )
            }
        }
    }
    if body_tags.is_empty() {
        return mesh_err(
            file,
            "no 8-node quadrangles in any physical surface: the mesh has no body",
        );
    }
    body_tags.sort_unstable();
    for (k, b) in msh.blocks.iter().enumerate() {
        if let Some(t) = block_body[k] {
            let tag = t as i32;
            block_body[k] = body_tags.iter().position(|&x| x == tag);
            let _ = b;
        }
    }
    let mut mesh = Mesh {
        bodies: body_tags
            .iter()
            .map(|t| msh.physical_names[&(2, *t)].clone())
            .collect(),
        ..Mesh::default()
    };
    // nodes used by body elements, numbered in file order
    let mut new_id = vec![usize::MAX; msh.nodes.len()];
    for (k, b) in msh.blocks.iter().enumerate() {
        if block_body[k].is_some() {
            for &n in &b.conn {
                new_id[n] = 0;
            }
        }
    }
    let mut tag_of = Vec::new();
    for (i, id) in new_id.iter_mut().enumerate() {
        if *id == 0 {
            *id = mesh.nodes.len();
            mesh.nodes.push(msh.nodes[i]);
            tag_of.push(msh.node_tags[i]);
        }
    }
    // elements, counter-clockwise
    for (k, b) in msh.blocks.iter().enumerate() {
        let Some(body) = block_body[k] else { continue };
        for conn in b.conn.chunks_exact(8) {
            let mut n: [usize; 8] = std::array::from_fn(|a| new_id[conn[a]]);
            let x: [[f64; 2]; 4] = std::array::from_fn(|a| mesh.nodes[n[a]]);
            let area2: f64 = (0..4)
                .map(|a| {
                    let (p, q) = (x[a], x[(a + 1) % 4]);
                    p[0] * q[1] - q[0] * p[1]
                })
                .sum();
            if area2 < 0.0 {
                // clockwise: walk the corners the other way round
                n = [n[0], n[3], n[2], n[1], n[7], n[6], n[5], n[4]];
            }
            mesh.elements.push(Element { nodes: n, body });
        }
    }
    let mut node_body = vec![usize::MAX; mesh.nodes.len()];
    for el in &mesh.elements {
        for &n in &el.nodes {
            if node_body[n] != usize::MAX && node_body[n] != el.body {
                return mesh_err(
                    file,
                    format!(
                        "node {} at ({}, {}) belongs to both bodies \"{}\" and \"{}\": bodies in contact need their own nodes along the interface (Gmsh: separate points and curves there, Geometry.AutoCoherence = 0)",
                        tag_of[n], mesh.nodes[n][0], mesh.nodes[n][1], mesh.bodies[node_body[n]], mesh.bodies[el.body]
                    ),
                );
            }
            node_body[n] = el.body;
        }
    }
    for (b, name) in mesh.bodies.iter().enumerate() {
        let mut set: Vec<usize> = mesh
            .elements
            .iter()
            .filter(|e| e.body == b)
            .flat_map(|e| e.nodes)
            .collect();
        set.sort_unstable();
        set.dedup();
        mesh.node_sets.insert(format!("{name}.all"), set);
    }
    // element edges: sorted corner pair → (element, local edge)
    let mut edge_of: HashMap<(usize, usize), (usize, usize)> = HashMap::new();
    for (e, el) in mesh.elements.iter().enumerate() {
        for i in 0..4 {
            let (p, q) = (el.nodes[i], el.nodes[(i + 1) % 4]);
            edge_of.entry((p.min(q), p.max(q))).or_insert((e, i));
        }
    }
    // physical curves → node sets and edge sets (edges walked with the body on the left)
    let mut curve_body: BTreeMap<String, usize> = BTreeMap::new();
    for b in msh.blocks.iter().filter(|b| b.dim == 1) {
        let Some(phys) = msh.entities.get(&(1, b.entity)) else {
            return mesh_err(
                &b.at,
                format!("curve entity {} is not listed in $Entities", b.entity),
            );
        };
        for t in phys {
            let Some(name) = msh.physical_names.get(&(1, *t)) else {
                return mesh_err(
                    file,
                    format!("physical curve {t} has no name in $PhysicalNames (node sets are named by physical names)"),
                );
            };
            if mesh.bodies.iter().any(|b| format!("{b}.all") == *name) {
                return mesh_err(
                    file,
                    format!("physical curve \"{name}\" has the name of a body's own node set"),
                );
            }
            let mut edges = Vec::new();
            let mut nodes = Vec::new();
            for (k, conn) in b.conn.chunks_exact(3).enumerate() {
                let ids: [usize; 3] = std::array::from_fn(|a| new_id[conn[a]]);
                if let Some(a) = ids.iter().position(|&i| i == usize::MAX) {
                    return mesh_err(
                        &b.at,
                        format!(
                            "line element {} of physical curve \"{name}\": node {} is on no body element",
                            b.tags[k], msh.node_tags[conn[a]]
                        ),
                    );
                }
                let [p, q, mid] = ids;
                let edge = edge_of.get(&(p.min(q), p.max(q))).and_then(|&(e, i)| {
                    let el = &mesh.elements[e];
                    (el.nodes[4 + i] == mid)
                        .then(|| ([el.nodes[i], mid, el.nodes[(i + 1) % 4]], el.body))
                });
                let Some((edge, body)) = edge else {
                    return mesh_err(
                        &b.at,
                        format!(
                            "line element {} of physical curve \"{name}\" is not an edge of any quadrangle",
                            b.tags[k]
                        ),
                    );
                };
                if *curve_body.entry(name.clone()).or_insert(body) != body {
                    return mesh_err(
                        file,
                        format!(
                            "physical curve \"{name}\" lies on two bodies; a set must be on one"
                        ),
                    );
                }
                edges.push(edge);
                nodes.extend(edge);
            }
            let set = mesh.node_sets.entry(name.clone()).or_default();
            set.extend(nodes);
            set.sort_unstable();
            set.dedup();
            mesh.edge_sets
                .entry(name.clone())
                .or_default()
                .extend(edges);
        }
    }
    for spec in interfaces {
        let iface = pair_curves(msh, &mesh, &curve_body, &tag_of, spec, place)?;
        mesh.interfaces.push(iface);
    }
    Ok(mesh)
}

fn pair_curves(
    msh: &MshFile,
    mesh: &Mesh,
    curve_body: &BTreeMap<String, usize>,
    tag_of: &[u64],
    spec: &InterfaceSpec,
    place: &str,
) -> Result<Interface> {
    let at = format!("{place}: [[mesh.interface]] \"{}\"", spec.name);
    let bad = |m: String| Error::input(&at, m);
    let (Some(upper), Some(lower)) = (&spec.upper_curve, &spec.lower_curve) else {
        return Err(bad(
            "a mesh read from a file needs upper_curve and lower_curve (physical curve names)"
                .into(),
        ));
    };
    let curve = |name: &str| -> Result<usize> {
        if let Some(&b) = curve_body.get(name) {
            return Ok(b);
        }
        if let Some((&(d, _), _)) = msh.physical_names.iter().find(|(_, n)| *n == name) {
            let what = [
                "a physical point",
                "a physical curve",
                "a physical surface",
                "a physical volume",
            ][d.clamp(0, 3) as usize];
            return Err(bad(format!(
                "\"{name}\" is {what} (dimension {d}) in {}, not a physical curve of 3-node lines",
                msh.name
            )));
        }
        Err(bad(format!(
            "physical curve \"{name}\" not found in {} (physical curves: {})",
            msh.name,
            curve_body.keys().cloned().collect::<Vec<_>>().join(", ")
        )))
    };
    let (ua, lb) = (curve(upper)?, curve(lower)?);
    for (given, body, side) in [(&spec.upper, ua, "upper"), (&spec.lower, lb, "lower")] {
        if let Some(g) = given {
            if *g != mesh.bodies[body] {
                return Err(bad(format!(
                    "{side} = \"{g}\" but {side}_curve lies on body \"{}\"",
                    mesh.bodies[body]
                )));
            }
        }
    }
    if ua == lb {
        return Err(bad(format!(
            "upper_curve \"{upper}\" and lower_curve \"{lower}\" are on the same body \"{}\"",
            mesh.bodies[ua]
        )));
    }
    let a_edges = &mesh.edge_sets[upper];
    let b_edges = &mesh.edge_sets[lower];
    let h = a_edges
        .iter()
        .chain(b_edges)
        .map(|e| {
            let (p, q) = (mesh.nodes[e[0]], mesh.nodes[e[2]]);
            (p[0] - q[0]).hypot(p[1] - q[1])
        })
        .fold(f64::INFINITY, f64::min);
    let tol = 1e-9 * h;
    let b_nodes = &mesh.node_sets[lower];
    let a_nodes = &mesh.node_sets[upper];
    let near = |x: [f64; 2], set: &[usize]| {
        set.iter()
            .copied()
            .find(|&m| (mesh.nodes[m][0] - x[0]).hypot(mesh.nodes[m][1] - x[1]) <= tol)
    };
    let unpaired = |n: usize, on: &str, other: &str| -> Result<Interface> {
        let x = mesh.nodes[n];
        Err(bad(format!(
            "node {} at ({}, {}) of curve \"{on}\" in {} has no partner on curve \"{other}\" within {tol:.1e} mm (the two sides must have coincident nodes)",
            tag_of[n], x[0], x[1], msh.name
        )))
    };
    let mut edges = Vec::with_capacity(a_edges.len());
    for e in a_edges {
        let mut b = [0; 3];
        for i in 0..3 {
            match near(mesh.nodes[e[i]], b_nodes) {
                Some(m) => b[i] = m,
                None => return unpaired(e[i], upper, lower),
            }
        }
        edges.push(ContactEdge { a: *e, b });
    }
    // nodes of the lower curve within the extent of the upper one must be paired too
    let (lo, hi) = a_nodes.iter().fold(
        ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
        |(lo, hi), &n| {
            let x = mesh.nodes[n];
            (
                [lo[0].min(x[0]), lo[1].min(x[1])],
                [hi[0].max(x[0]), hi[1].max(x[1])],
            )
        },
    );
    for &n in b_nodes {
        let x = mesh.nodes[n];
        let inside = (0..2).all(|k| x[k] >= lo[k] - tol && x[k] <= hi[k] + tol);
        if inside && near(x, a_nodes).is_none() {
            return unpaired(n, lower, upper);
        }
    }
    Ok(Interface {
        name: spec.name.clone(),
        body_a: ua,
        body_b: lb,
        edges,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const TINY: &str = include_str!("../../tests/data/tiny.msh");
    const TINY_BIN: &[u8] = include_bytes!("../../tests/data/tiny-bin.msh");

    fn contact() -> InterfaceSpec {
        InterfaceSpec {
            name: "contact".into(),
            upper: None,
            lower: None,
            upper_curve: Some("punch.bottom".into()),
            lower_curve: Some("foundation.top".into()),
        }
    }

    fn build(text: &str) -> Result<Mesh> {
        let msh = parse_msh(text.as_bytes(), "t.msh")?;
        build_mesh(&msh, &[contact()], "case.toml")
    }

    /// The error text of a file that must be rejected; checks it is one line.
    fn err(bytes: &[u8]) -> String {
        let r = parse_msh(bytes, "t.msh").and_then(|m| build_mesh(&m, &[contact()], "case.toml"));
        let e = r.expect_err("must be rejected").to_string();
        assert!(!e.contains('\n'), "{e}");
        e
    }

    #[test]
    fn tiny_mesh_ascii_and_binary() {
        let a = parse_msh(TINY.as_bytes(), "tiny.msh").unwrap();
        let b = parse_msh(TINY_BIN, "tiny-bin.msh").unwrap();
        assert!(!a.binary && b.binary);
        assert_eq!(a.nodes.len(), 21);
        assert_eq!(a.node_tags, b.node_tags);
        assert_eq!(a.physical_names, b.physical_names);
        assert_eq!(a.entities, b.entities);
        assert_eq!(a.physical_names[&(2, 1)], "punch");
        let m = build(TINY).unwrap();
        m.validate().unwrap();
        assert_eq!(m.bodies, ["punch", "foundation"]);
        assert_eq!(m.elements.len(), 3);
        assert_eq!(m.nodes.len(), 21);
        assert_eq!(m.node_sets["punch.bottom"].len(), 3);
        assert_eq!(m.node_sets["foundation.top"].len(), 5);
        assert_eq!(m.node_sets["punch.all"].len(), 8);
        let iface = &m.interfaces[0];
        assert_eq!((iface.body_a, iface.body_b, iface.edges.len()), (0, 1, 1));
        let e = &iface.edges[0];
        for i in 0..3 {
            assert_ne!(e.a[i], e.b[i]);
            assert_eq!(m.nodes[e.a[i]], m.nodes[e.b[i]]);
        }
        // along +x: the lower body on the right of the walk
        assert!(m.nodes[e.a[0]][0] < m.nodes[e.a[2]][0]);
        // the top edge of the punch walked with the punch on its left: −x
        let top = m.edge_sets["punch.top"][0];
        assert!(m.nodes[top[0]][0] > m.nodes[top[2]][0]);
        // loads on the foundation's two top curves: one edge set of two edges
        assert_eq!(m.edge_sets["foundation.top"].len(), 2);
    }

    #[test]
    fn clockwise_quads_are_turned_counter_clockwise() {
        let ccw = build(TINY).unwrap();
        let text = TINY.replace("11 1 2 3 4 11 12 13 14 ", "11 1 4 3 2 14 13 12 11 ");
        assert_ne!(text, TINY);
        let turned = build(&text).unwrap();
        turned.validate().unwrap();
        assert_eq!(turned.elements[0].nodes, ccw.elements[0].nodes);
    }

    #[test]
    fn unknown_sections_are_skipped() {
        let text = TINY.replace(
            "$Entities",
            "$Comments\nanything $Nodes 1 2 3\n$EndComments\n$Entities",
        );
        build(&text).unwrap();
    }

    #[test]
    fn header_errors() {
        assert!(err(b"").contains("empty file"));
        let e = err(TINY.replace("4.1 0 8", "2.2 0 8").as_bytes());
        assert!(
            e.starts_with("mesh t.msh:2: MSH format version 2.2 is not supported"),
            "{e}"
        );
        assert!(err(TINY.replace("4.1 0 8", "4.1 0 4").as_bytes()).contains("data size 4"));
        assert!(err(b"hello").contains("must start with $MeshFormat"));
        let e = err(TINY.replace("PhysicalNames", "PhysicalNamez").as_bytes());
        assert!(e.contains("t.msh: missing section $PhysicalNames"), "{e}");
        let mut big = TINY_BIN.to_vec();
        let at = big.windows(8).position(|w| w == b"4.1 1 8\n").unwrap() + 8;
        big[at..at + 4].copy_from_slice(&1i32.to_be_bytes());
        let e = err(&big);
        assert!(
            e.contains("big-endian") && e.contains(&format!("(byte {at})")),
            "{e}"
        );
    }

    #[test]
    fn truncation_anywhere_is_an_error_not_a_panic() {
        for cut in 0..TINY.len() {
            let r = parse_msh(&TINY.as_bytes()[..cut], "t.msh");
            if let Err(e) = r {
                assert!(!e.to_string().contains('\n'));
            } else {
                // only a cut in the trailing whitespace may pass
                assert!(TINY[cut..].trim().is_empty(), "cut at {cut} passed");
            }
        }
        for cut in 0..TINY_BIN.len() {
            if let Ok(m) = parse_msh(&TINY_BIN[..cut], "t.msh") {
                assert_eq!(m.nodes.len(), 21, "cut at {cut} passed");
            }
        }
        let e = err(&TINY_BIN[..TINY_BIN.len() / 2]);
        assert!(e.contains("(byte ") && e.contains("truncated file"), "{e}");
    }

    #[test]
    fn node_errors() {
        let e = err(TINY.replace("\n20 20 0\n", "\n20 20 0.5\n").as_bytes());
        let line = TINY[..TINY.find("\n20 20 0\n").unwrap() + 1]
            .lines()
            .count()
            + 1;
        assert!(
            e.contains("node 3 has z = 0.5") && e.contains(&format!("t.msh:{line}:")),
            "{e}"
        );
        let e = err(TINY.replace("\n20 20 0\n", "\nnan 20 0\n").as_bytes());
        assert!(
            e.contains("node 3: coordinate x is NaN, not a finite number"),
            "{e}"
        );
        let e = err(TINY.replace("\n20 20 0\n", "\n20 inf 0\n").as_bytes());
        assert!(e.contains("coordinate y is inf"), "{e}");
        let e = err(TINY.replace("24 21 1 21", "24 22 1 22").as_bytes());
        assert!(
            e.contains("bad counts: $Nodes announces 22 nodes but its blocks hold 21"),
            "{e}"
        );
        let e = err(TINY
            .replace("24 21 1 21", "24 99999999999999 1 21")
            .as_bytes());
        assert!(
            e.contains("bad count: the number of nodes = 99999999999999"),
            "{e}"
        );
        let e = err(TINY.replace("0 2 0 1\n2\n", "0 2 0 1\n1\n").as_bytes());
        assert!(e.contains("node tag 1 appears twice"), "{e}");
        let e = err(TINY
            .replace("11 1 2 3 4 11 12 13 14 ", "11 1 2 3 4 11 12 13 99 ")
            .as_bytes());
        assert!(
            e.contains("element 11 refers to unknown node tag 99"),
            "{e}"
        );
        let e = err(TINY
            .replace("garbage", "")
            .replace("0 1 0 1\n1\n0 0 0", "0 1 0 1\n1\n0 zero 0")
            .as_bytes());
        assert!(
            e.contains("expected a node coordinate (a number), found \"zero\""),
            "{e}"
        );
    }

    #[test]
    fn element_and_physical_errors() {
        let e = err(TINY.replace("\n2 1 16 1\n", "\n2 1 9 1\n").as_bytes());
        assert!(
            e.contains("element type 9 (6-node triangle) not supported"),
            "{e}"
        );
        let line = TINY[..TINY.find("\n2 1 16 1\n").unwrap() + 1]
            .lines()
            .count()
            + 1;
        assert!(e.contains(&format!("t.msh:{line}:")), "{e}");
        let e = err(TINY.replace("\n2 1 16 1\n", "\n2 1 3 1\n").as_bytes());
        assert!(
            e.contains("element type 3 (4-node quadrangle)") && e.contains("ElementOrder"),
            "{e}"
        );
        let e = err(TINY.replace("\n2 1 16 1\n", "\n1 1 16 1\n").as_bytes());
        assert!(
            e.contains("in an entity of dimension 1 (expected 2)"),
            "{e}"
        );
        let e = err(TINY
            .replace("2 1 \"punch\"", "2 1 \"punch.top\"")
            .as_bytes());
        assert!(e.contains("\"punch.top\" is used twice"), "{e}");
        let e = err(TINY.replace("13 13 1 13", "13 14 1 14").as_bytes());
        assert!(e.contains("bad counts: $Elements announces 14"), "{e}");
        // a surface in no physical group
        let text = TINY.replace(
            "1 0 0 0 20 20 0 1 1 4 1 2 -3 -4",
            "1 0 0 0 20 20 0 0 4 1 2 -3 -4",
        );
        assert!(err(text.as_bytes())
            .contains("surface entity 1 has elements but is in no physical surface"));
        // the case names a group the file does not have, or one of the wrong dimension
        let msh = parse_msh(TINY.as_bytes(), "t.msh").unwrap();
        let mut spec = contact();
        spec.upper_curve = Some("punch.base".into());
        let e = build_mesh(&msh, &[spec], "case.toml")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("physical curve \"punch.base\" not found in t.msh"),
            "{e}"
        );
        let mut spec = contact();
        spec.lower_curve = Some("foundation".into());
        let e = build_mesh(&msh, &[spec], "case.toml")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("\"foundation\" is a physical surface (dimension 2)"),
            "{e}"
        );
        let mut spec = contact();
        spec.upper = Some("foundation".into());
        let e = build_mesh(&msh, &[spec], "case.toml")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("upper = \"foundation\" but upper_curve lies on body \"punch\""),
            "{e}"
        );
    }

    #[test]
    fn bodies_sharing_nodes_are_rejected() {
        // the foundation's first element takes the punch's corner node 1 instead of its own 10
        let text = TINY.replace("12 5 6 9 10 15 21 18 20 ", "12 5 6 9 1 15 21 18 20 ");
        let e = err(text.as_bytes());
        assert!(
            e.contains("node 1 at (0, 0) belongs to both bodies \"punch\" and \"foundation\""),
            "{e}"
        );
    }

    #[test]
    fn unpaired_interface_node_names_tag_and_coordinates() {
        // move the punch's bottom midside node (tag 11) off its partner (tag 18)
        let text = TINY.replacen("11\n9.9999999999716 0 0", "11\n9.5 0 0", 1);
        let e = err(text.as_bytes());
        assert!(
            e.contains("node 11 at (9.5, 0) of curve \"punch.bottom\"") && e.contains("no partner"),
            "{e}"
        );
    }
}
