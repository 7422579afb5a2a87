//! Our own VTU files read back, as [`crate::files::output::vtu`] writes them:
//! the mesh (points, cells of the four families, each cell's body) and which
//! nodes lie on an interface (`contact_closed` ≥ 0), in either encoding
//! (raw appended blocks, each a UInt64 byte count and little-endian values;
//! or ASCII). Every size is checked against the file before it is used: a
//! forged count allocates nothing.

use crate::error::{Error, Result};
use crate::physics::element::family::Family;

/// The undeformed mesh of a VTU file.
pub(super) struct Grid {
    /// x, y, z per node (z = 0 in a plane model).
    pub points: Vec<[f64; 3]>,
    /// Each cell's family and its nodes' range in `connectivity`.
    pub cells: Vec<(Family, std::ops::Range<usize>)>,
    pub connectivity: Vec<usize>,
    /// Each cell's body (mesh order; 0 where the file has no `body`).
    pub body: Vec<usize>,
    /// Per node: on an interface (false where the file does not say).
    pub on_interface: Vec<bool>,
}

impl Grid {
    /// The nodes of cell `c`.
    pub fn nodes(&self, c: usize) -> &[usize] {
        &self.connectivity[self.cells[c].1.clone()]
    }

    /// A 3D mesh (hexahedra, tetrahedra).
    pub fn solid(&self) -> bool {
        self.cells.iter().any(|(f, _)| f.dim() == 3)
    }
}

/// One `<DataArray>` of the document: its attributes, and for ASCII its text.
struct Array<'a> {
    /// Where its tag starts in the XML.
    at: usize,
    attrs: Vec<(&'a str, &'a str)>,
    text: &'a str,
}

impl Array<'_> {
    fn attr(&self, key: &str) -> Option<&str> {
        self.attrs.iter().find(|a| a.0 == key).map(|a| a.1)
    }
}

/// The document as the reader sees it: its XML, its arrays and the appended
/// data (after the `_`), if any.
struct Document<'a> {
    place: &'a str,
    xml: &'a str,
    arrays: Vec<Array<'a>>,
    appended: Option<&'a [u8]>,
}

/// Reads the VTU bytes of `place` (a file of the folder, for messages).
pub(super) fn parse(place: &str, bytes: &[u8]) -> Result<Grid> {
    let doc = Document::of(place, bytes)?;
    let piece = tag_attrs(doc.xml, "<Piece").ok_or_else(|| doc.bad("no <Piece>"))?;
    let count = |key: &str| -> Result<usize> {
        let v = piece.iter().find(|a| a.0 == key).map(|a| a.1);
        v.and_then(|v| v.parse().ok())
            .ok_or_else(|| doc.bad(&format!("<Piece> has no {key}")))
    };
    let (nn, ne) = (count("NumberOfPoints")?, count("NumberOfCells")?);
    let points_at = doc
        .xml
        .find("<Points>")
        .ok_or_else(|| doc.bad("no <Points>"))?;
    let points = doc.arrays.iter().find(|a| a.at > points_at);
    let points = doc.values(
        points.ok_or_else(|| doc.bad("no point coordinates"))?,
        3 * nn,
    )?;
    let named = |name: &str| doc.arrays.iter().find(|a| a.attr("Name") == Some(name));
    let need = |name: &str| named(name).ok_or_else(|| doc.bad(&format!("no {name} array")));
    let offsets = doc.indices(need("offsets")?, ne, usize::MAX)?;
    let types = doc.values(need("types")?, ne)?;
    let cells = cells_of(&doc, &offsets, &types)?;
    let connectivity = doc.indices(
        need("connectivity")?,
        offsets.last().copied().unwrap_or(0),
        nn,
    )?;
    let body = match named("body") {
        Some(a) => doc.indices(a, ne, usize::MAX)?,
        None => vec![0; ne],
    };
    let on_interface = match named("contact_closed") {
        Some(a) => doc.values(a, nn)?.iter().map(|&v| v >= 0.0).collect(),
        None => vec![false; nn],
    };
    Ok(Grid {
        points: points.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect(),
        cells,
        connectivity,
        body,
        on_interface,
    })
}

/// Each cell's family (from its VTK type) and node range (from the
/// offsets): its node count must be its family's.
fn cells_of(
    doc: &Document,
    offsets: &[usize],
    types: &[f64],
) -> Result<Vec<(Family, std::ops::Range<usize>)>> {
    let families = [Family::Q8, Family::T6, Family::H20, Family::T10];
    let mut start = 0;
    let mut cells = Vec::with_capacity(offsets.len());
    for (c, (&end, &t)) in offsets.iter().zip(types).enumerate() {
        let family = families
            .into_iter()
            .find(|f| f64::from(f.vtk_cell()) == t)
            .ok_or_else(|| {
                doc.bad(&format!(
                    "cell {c}: type {t} is not one this program writes"
                ))
            })?;
        if end < start || end - start != family.nodes() {
            return Err(doc.bad(&format!(
                "cell {c}: {} nodes for a {}",
                end.saturating_sub(start),
                family.name()
            )));
        }
        cells.push((family, start..end));
        start = end;
    }
    Ok(cells)
}

impl<'a> Document<'a> {
    fn of(place: &'a str, bytes: &'a [u8]) -> Result<Document<'a>> {
        let bad = |m: &str| Error::input(place, format!("not a VTU file of this program: {m}"));
        let marker = b"<AppendedData";
        let split = bytes.windows(marker.len()).position(|w| w == marker);
        let (head, appended) = match split {
            Some(at) => {
                let rest = &bytes[at..];
                let data = rest
                    .iter()
                    .position(|&b| b == b'_')
                    .ok_or_else(|| bad("no `_` before the appended data"))?;
                (&bytes[..at], Some(&rest[data + 1..]))
            }
            None => (bytes, None),
        };
        let xml = std::str::from_utf8(head).map_err(|_| bad("its XML is not UTF-8"))?;
        if !xml.contains("<VTKFile type=\"UnstructuredGrid\"") {
            return Err(bad("no <VTKFile type=\"UnstructuredGrid\">"));
        }
        let mut arrays = Vec::new();
        let mut from = 0;
        while let Some(i) = xml[from..].find("<DataArray") {
            let at = from + i;
            let end = at
                + xml[at..]
                    .find('>')
                    .ok_or_else(|| bad("a <DataArray> tag is not closed"))?;
            let tag = &xml[at..end];
            let text = if tag.ends_with('/') {
                ""
            } else {
                let close = xml[end..]
                    .find("</DataArray>")
                    .ok_or_else(|| bad("a <DataArray> is not closed"))?;
                &xml[end + 1..end + close]
            };
            arrays.push(Array {
                at,
                attrs: attrs(tag),
                text,
            });
            from = end;
        }
        Ok(Document {
            place,
            xml,
            arrays,
            appended,
        })
    }

    fn bad(&self, m: &str) -> Error {
        Error::input(self.place, format!("not a VTU file of this program: {m}"))
    }

    /// The values of `a`, exactly `len` of them, as numbers.
    fn values(&self, a: &Array, len: usize) -> Result<Vec<f64>> {
        let name = a.attr("Name").unwrap_or("points");
        let values = match a.attr("format") {
            Some("appended") => self.block(a, name)?,
            Some("ascii") => a
                .text
                .split_ascii_whitespace()
                .map(|w| w.parse::<f64>())
                .collect::<std::result::Result<Vec<f64>, _>>()
                .map_err(|_| self.bad(&format!("{name}: a value is not a number")))?,
            _ => return Err(self.bad(&format!("{name}: neither appended nor ascii"))),
        };
        if values.len() != len {
            return Err(self.bad(&format!("{name} has {} values, not {len}", values.len())));
        }
        Ok(values)
    }

    /// The values of `a` as whole numbers, each below `bound`.
    fn indices(&self, a: &Array, len: usize, bound: usize) -> Result<Vec<usize>> {
        let name = a.attr("Name").unwrap_or("");
        self.values(a, len)?
            .into_iter()
            .map(|v| {
                let ok = v >= 0.0 && v.fract() == 0.0 && v < bound as f64 && v < 2f64.powi(53);
                ok.then_some(v as usize)
                    .ok_or_else(|| self.bad(&format!("{name}: {v} is not an index here")))
            })
            .collect()
    }

    /// The appended block of `a`: its UInt64 byte count, then the values.
    fn block(&self, a: &Array, name: &str) -> Result<Vec<f64>> {
        let bad = |m: &str| self.bad(&format!("{name}: {m}"));
        let data = self
            .appended
            .ok_or_else(|| bad("appended, but no appended data"))?;
        let offset: usize = a
            .attr("offset")
            .and_then(|o| o.parse().ok())
            .ok_or_else(|| bad("no offset"))?;
        let head = data
            .get(offset..offset.saturating_add(8))
            .ok_or_else(|| bad("offset beyond the file"))?;
        let n = u64::from_le_bytes(head.try_into().unwrap_or([0; 8]));
        let start = offset + 8;
        let body = usize::try_from(n)
            .ok()
            .and_then(|n| data.get(start..start.checked_add(n)?))
            .ok_or_else(|| bad("its block runs beyond the file"))?;
        let (size, read): (usize, fn(&[u8]) -> f64) = match a.attr("type") {
            Some("Float64") => (8, |b| f64::from_le_bytes(b.try_into().unwrap_or([0; 8]))),
            Some("Int64") => (8, |b| {
                i64::from_le_bytes(b.try_into().unwrap_or([0; 8])) as f64
            }),
            Some("UInt8") => (1, |b| f64::from(b[0])),
            _ => return Err(bad("a type this program does not write")),
        };
        if body.len() % size != 0 {
            return Err(bad("its byte count is not a whole number of values"));
        }
        Ok(body.chunks_exact(size).map(read).collect())
    }
}

/// The attributes of the first tag of `xml` that starts with `open`.
fn tag_attrs<'a>(xml: &'a str, open: &str) -> Option<Vec<(&'a str, &'a str)>> {
    let at = xml.find(open)?;
    let end = at + xml[at..].find('>')?;
    Some(attrs(&xml[at..end]))
}

/// `key="value"` pairs of a tag's text.
fn attrs(tag: &str) -> Vec<(&str, &str)> {
    let mut out = Vec::new();
    let mut rest = tag;
    while let Some(eq) = rest.find("=\"") {
        let key = rest[..eq].rsplit(char::is_whitespace).next().unwrap_or("");
        let value_from = &rest[eq + 2..];
        let Some(close) = value_from.find('"') else {
            break;
        };
        out.push((key, &value_from[..close]));
        rest = &value_from[close + 1..];
    }
    out
}
