//! The `.msh` 4.1 reader: file bytes to [`MshFile`], with every count checked
//! against the bytes left and every error naming the line or byte offset.

use crate::error::{Error, Result};
use std::collections::{BTreeMap, HashMap};

/// One block of elements of one type on one geometric entity.
#[derive(Clone, Debug, PartialEq)]
pub struct ElementBlock {
    pub(crate) dim: i32,
    pub entity: i32,
    pub(crate) etype: i32,
    /// Where the block header is (for errors).
    pub at: String,
    /// Element tags.
    pub(crate) tags: Vec<u64>,
    /// Node indices into [`MshFile::nodes`], `nodes_per_element` per element.
    pub(crate) conn: Vec<usize>,
}

/// The contents of a `.msh` file that asperity uses.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MshFile {
    /// The file's name, for errors.
    pub name: String,
    pub binary: bool,
    /// (dimension, physical tag) → name.
    pub(crate) physical_names: BTreeMap<(i32, i32), String>,
    /// (dimension, entity tag) → physical tags of that entity.
    pub(crate) entities: BTreeMap<(i32, i32), Vec<i32>>,
    /// Node tags in file order.
    pub(crate) node_tags: Vec<u64>,
    /// Node coordinates (x, y, z) in file order.
    pub nodes: Vec<[f64; 3]>,
    /// The first node off the plane z = 0: where it is, its tag and z (a
    /// plane mesh refuses it, [`super::build`]).
    pub(crate) off_plane: Option<(String, u64, f64)>,
    pub blocks: Vec<ElementBlock>,
}

/// Nodes per element of the element types asperity reads, with their names.
fn element_type(t: i32) -> Option<(usize, i32, &'static str)> {
    match t {
        15 => Some((1, 0, "1-node point")),
        8 => Some((3, 1, "3-node line")),
        16 => Some((8, 2, "8-node quadrangle")),
        9 => Some((6, 2, "6-node triangle")),
        17 => Some((20, 3, "20-node hexahedron")),
        11 => Some((10, 3, "10-node tetrahedron")),
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
        12 => "27-node hexahedron",
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
            let off = x[2].abs() > 1e-12 * x[0].abs().max(x[1].abs()).max(1.0);
            if off && msh.off_plane.is_none() {
                msh.off_plane = Some((c.place(at_x), tag, x[2]));
            }
            for _ in 0..extra {
                c.real("a parametric node coordinate")?;
            }
            msh.nodes.push(x);
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
                1..=5 => ": the mesh is first order; set Mesh.ElementOrder = 2 and Mesh.SecondOrderIncomplete = 1",
                10 => ": set Mesh.SecondOrderIncomplete = 1 for 8-node quadrangles",
                12 => ": set Mesh.SecondOrderIncomplete = 1 for 20-node hexahedra",
                _ => "",
            };
            return c.err(
                at,
                format!(
                    "element type {etype} ({}) not supported: asperity reads 8-node quadrangles (16), 6-node triangles (9) and 3-node lines (8), and in 3D 20-node hexahedra (17) and 10-node tetrahedra (11){hint}",
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
