//! VTK XML unstructured grid (.vtu) per increment and a .pvd series that
//! ParaView opens. Cells are VTK_QUADRATIC_QUAD (type 23) and
//! VTK_QUADRATIC_TRIANGLE (type 22) (`Family::vtk_cell`), whose node order
//! is ours: corners counter-clockwise, then the midsides of edges 0-1, 1-2,
//! 2-3, 3-0 (2-0 for the triangle).
//!
//! Writing is split in two so that the expensive part can run beside the
//! solver: `Frame::of` takes what one state shows (nodal averages, contact
//! values) into owned arrays, quickly, on the solver's thread; `Layout`
//! (made once per model: the mesh, and everything of the document that does
//! not change between increments, already encoded) and `Layout::write` turn
//! a frame into the document, on the writer's thread
//! (`super::background`). Two encodings ([`VtuFormat`]): `binary`, raw
//! appended data (the arrays' little-endian bytes after the XML, each block
//! preceded by its byte count as a UInt64), and `ascii`, every number as text.

use crate::input::case::VtuFormat;
use crate::model::Model;
use crate::physics::element::family::{Family, GaussRule, MAX_NODES};
use crate::physics::material::VonMises;
use crate::solve::State;
use std::fmt::Write;
use std::io::Write as _;

/// Nodal fields obtained by extrapolating Gauss point values to the nodes of each
/// element and averaging over the elements that share a node.
pub(crate) struct NodalFields {
    /// σxx, σyy, σxy, σzz (σ_rr, σ_zz, σ_rz, σ_θθ in axisymmetry)
    pub stress: Vec<[f64; 4]>,
    pub von_mises: Vec<f64>,
    pub peeq: Vec<f64>,
    /// σ_rθ, σ_zθ (a model with twist), σ_xz, σ_yz (3D); empty otherwise.
    pub twist_shear: Vec<[f64; 2]>,
}

/// The extrapolation of [`q8::extrapolate_to_nodes`] as a matrix, row by
/// node: `w[a][k]` is node a's value for Gauss point k at 1 and the others
/// at 0. Σ_k w[a][k] v_k, summed in k's order from 0, is bit for bit what
/// `extrapolate_to_nodes` returns (it sums the same products, weight times
/// value, in the same order; the unit values only add exact zeros), without
/// its Lagrange products for every element and field.
fn extrapolation_weights(family: Family, rule: &GaussRule) -> Vec<[f64; MAX_NODES]> {
    let ng = rule.points.len();
    (0..ng)
        .map(|k| {
            let mut unit = vec![0.0; ng];
            unit[k] = 1.0;
            family.extrapolate_to_nodes(rule, &unit)
        })
        .collect()
}

/// Each family's extrapolation weights at the model's rules, in
/// [`Family::index`] order (row k: each node's share of point k).
fn all_weights(model: &Model) -> Vec<Vec<Vec<f64>>> {
    let rows = |w: Vec<&[f64]>| w.into_iter().map(<[f64]>::to_vec).collect::<Vec<_>>();
    let mut out: Vec<Vec<Vec<f64>>> = Family::ALL
        .iter()
        .map(|&f| {
            let w = extrapolation_weights(f, model.rule_of(f));
            rows(w.iter().map(|r| &r[..]).collect())
        })
        .collect();
    for f in Family::SOLID {
        let solid = f.solid().expect("a solid family");
        let w = solid.extrapolation(model.rule3(solid));
        out.push(rows(w.iter().map(|r| &r[..]).collect()));
    }
    out
}

pub(crate) fn nodal_fields(model: &Model, state: &State) -> NodalFields {
    let nn = model.mesh.nodes.len();
    let weights = all_weights(model);
    // the fields at every Gauss point (σ components, a slot not extrapolated,
    // PEEQ), then with twist σ_rθ and σ_zθ, in 3D σ_xz and σ_yz
    let fields = if model.node_dofs().six_components() {
        8
    } else {
        6
    };
    let mut acc = vec![[0.0f64; 8]; nn];
    let mut count = vec![0u32; nn];
    let mut vals = [[0.0f64; 8]; crate::physics::element::solid3::MAX_POINTS3];
    for (e, el) in model.mesh.elements.iter().enumerate() {
        let gp = state.gauss.range(model.points(e));
        let w = &weights[el.family.index()];
        for (v, g) in vals.iter_mut().zip(gp) {
            *v = [
                g.stress[0],
                g.stress[1],
                g.stress[2],
                g.stress[3],
                0.0,
                g.peeq,
                g.stress[4],
                g.stress[5],
            ];
        }
        for (a, &n) in el.nodes().iter().enumerate() {
            for c in 0..fields {
                let mut at_node = 0.0;
                for (wk, v) in w.iter().zip(&vals) {
                    at_node += wk[a] * v[c];
                }
                acc[n][c] += at_node;
            }
            count[n] += 1;
        }
    }
    let mut f = NodalFields {
        stress: Vec::with_capacity(nn),
        von_mises: Vec::with_capacity(nn),
        peeq: Vec::with_capacity(nn),
        twist_shear: Vec::new(),
    };
    for (a, &c) in acc.iter().zip(&count) {
        let c = f64::from(c.max(1));
        let s = a.map(|v| v / c);
        f.stress.push([s[0], s[1], s[2], s[3]]);
        // of the nodal stress itself: never negative, and what its components
        // say (the extrapolated Gauss values of √(3 J₂) overshoot below zero
        // beside a load's edge)
        let shear = if fields == 8 { [s[6], s[7]] } else { [0.0; 2] };
        f.von_mises.push(VonMises::equivalent_stress(&[
            s[0], s[1], s[2], s[3], shear[0], shear[1],
        ]));
        f.peeq.push(s[5].max(0.0));
        if fields == 8 {
            f.twist_shear.push(shear);
        }
    }
    f
}

/// What one state shows, as owned arrays (node by node, or cell by cell):
/// the per-increment part of a VTU document.
#[derive(Default)]
pub(crate) struct Frame {
    /// u_x, u_y, 0 per node (u_r, u_z, u_θ with twist; u_x, u_y, u_z in 3D).
    displacement: Vec<f64>,
    /// Four components per node; in 3D six, in ParaView's order of a
    /// symmetric tensor: xx, yy, zz, xy, yz, xz.
    stress: Vec<f64>,
    /// σ_rθ, σ_zθ per node (twist only; empty without).
    twist_shear: Vec<f64>,
    von_mises: Vec<f64>,
    peeq: Vec<f64>,
    contact_pressure: Vec<f64>,
    contact_shear: Vec<f64>,
    /// 1 closed, 0 open, −1 not on an interface.
    contact_closed: Vec<f64>,
    /// With twist: the circumferential shear p_Tθ of the interface (empty
    /// without twist).
    contact_hoop_shear: Vec<f64>,
    /// Per cell.
    max_peeq: Vec<f64>,
    /// Per cell: η_e² of the error estimate (N·mm, [`crate::measure::estimate`]).
    error_estimate: Vec<f64>,
    /// Per cell: η_e² / η².
    error_share: Vec<f64>,
}

impl Frame {
    /// The frame of a state whose error estimate is `estimate`.
    pub fn with(
        model: &Model,
        state: &State,
        estimate: Option<&crate::measure::estimate::Estimate>,
    ) -> Frame {
        let mesh = &model.mesh;
        let nn = mesh.nodes.len();
        let ne = mesh.elements.len();
        let nf = nodal_fields(model, state);
        // interface tractions at the nodes of both sides
        let mut p_n = vec![0.0; nn];
        let mut p_t = vec![0.0; nn];
        let twist = model.node_dofs().twist();
        let solid = mesh.dim() == 3;
        let mut p_h = if twist { vec![0.0; nn] } else { Vec::new() };
        let mut status = vec![-1.0; nn];
        let mut base = 0;
        for im in &model.interfaces {
            // shear tractions live at the spring points: one per pair when lumped
            let lumped = im.points.len() == im.pairs.len() && im.tangential.is_some();
            for (i, pr) in im.pairs.iter().enumerate() {
                let un = im.pair_approach_at(pr, &state.u, im.gap_at(state.time));
                let p = im.law.pressure(un).0;
                let (t, h) = if lumped {
                    (state.contact[base + i].p_t, state.contact[base + i].p_h)
                } else {
                    (0.0, 0.0)
                };
                for n in [pr.a, pr.b] {
                    p_n[n] = p;
                    p_t[n] = t;
                    if twist {
                        p_h[n] = h;
                    }
                    status[n] = f64::from(i32::from(un > 0.0));
                }
            }
            base += im.points.len();
        }
        Frame {
            displacement: (0..nn)
                .flat_map(|i| {
                    let nd = model.node_dofs();
                    let third = if nd.per_node() == 3 {
                        state.u[nd.dof(i, 2)]
                    } else {
                        0.0
                    };
                    [state.u[nd.dof(i, 0)], state.u[nd.dof(i, 1)], third]
                })
                .collect(),
            stress: if solid {
                nf.stress
                    .iter()
                    .zip(&nf.twist_shear)
                    .flat_map(|(s, t)| [s[0], s[1], s[3], s[2], t[1], t[0]])
                    .collect()
            } else {
                nf.stress.iter().flat_map(|v| v.iter().copied()).collect()
            },
            twist_shear: if twist {
                nf.twist_shear
                    .iter()
                    .flat_map(|v| v.iter().copied())
                    .collect()
            } else {
                Vec::new()
            },
            von_mises: nf.von_mises,
            peeq: nf.peeq,
            contact_pressure: p_n,
            contact_shear: p_t,
            contact_closed: status,
            contact_hoop_shear: p_h,
            max_peeq: (0..ne)
                .map(|e| {
                    state
                        .gauss
                        .range(model.points(e))
                        .iter()
                        .fold(0.0f64, |a, g| a.max(g.peeq))
                })
                .collect(),
            error_estimate: estimate.map_or(Vec::new(), |e| e.element.clone()),
            error_share: estimate.map_or(Vec::new(), |e| e.shares()),
        }
    }

    /// The cell arrays after `body`, in document order.
    fn cell_arrays(&self) -> Vec<(&'static str, Values<'_>)> {
        vec![
            ("max_peeq", Values::All(&self.max_peeq)),
            ("error_estimate", Values::All(&self.error_estimate)),
            ("error_share", Values::All(&self.error_share)),
        ]
    }

    /// The point arrays in document order: name, components, values. The
    /// hoop stress (axisymmetry) is the fourth stress component again.
    /// With twist, `twist_shear` (σ_rθ, σ_zθ) follows, and
    /// `contact_hoop_shear` (p_Tθ) ends the list.
    fn point_arrays(
        &self,
        hoop: bool,
        twist: bool,
        solid: bool,
    ) -> Vec<(&'static str, usize, Values<'_>)> {
        let mut v = vec![
            ("displacement", 3, Values::All(&self.displacement)),
            (
                "stress",
                if solid { 6 } else { 4 },
                Values::All(&self.stress),
            ),
        ];
        if hoop {
            v.push(("hoop_stress", 1, Values::Every4th(&self.stress)));
        }
        if twist {
            v.push(("twist_shear", 2, Values::All(&self.twist_shear)));
        }
        v.extend([
            ("von_mises", 1, Values::All(&self.von_mises)),
            ("peeq", 1, Values::All(&self.peeq)),
            ("contact_pressure", 1, Values::All(&self.contact_pressure)),
            ("contact_shear", 1, Values::All(&self.contact_shear)),
            ("contact_closed", 1, Values::All(&self.contact_closed)),
        ]);
        if twist {
            v.push((
                "contact_hoop_shear",
                1,
                Values::All(&self.contact_hoop_shear),
            ));
        }
        v
    }
}

/// The values of one array: a whole vector, or its every fourth (from the
/// fourth on: σ_θθ of the stress).
#[derive(Clone, Copy)]
enum Values<'a> {
    All(&'a [f64]),
    Every4th(&'a [f64]),
}

impl Values<'_> {
    fn len(self) -> usize {
        match self {
            Values::All(v) => v.len(),
            Values::Every4th(v) => v.len() / 4,
        }
    }
    fn for_each(self, mut f: impl FnMut(f64)) {
        match self {
            Values::All(v) => v.iter().for_each(|&x| f(x)),
            Values::Every4th(v) => v.chunks_exact(4).for_each(|c| f(c[3])),
        }
    }
}

/// Everything of a model's VTU documents that does not change between
/// increments, encoded once: the XML before and after the per-increment
/// arrays and the mesh's own arrays (points, cells, `body`).
pub(crate) struct Layout {
    format: VtuFormat,
    hoop: bool,
    /// The model has twist: the `twist_shear` array is written.
    twist: bool,
    /// A 3D model: six stress components.
    solid: bool,
    /// From the XML declaration to where the first per-increment array goes.
    head: Vec<u8>,
    /// ascii: `</PointData>` and the `body` array;
    /// binary: the end of the XML and the appended mesh blocks.
    middle: Vec<u8>,
    /// binary: the `body` block (it follows the point data blocks).
    body: Vec<u8>,
}

/// What both encodings write of the mesh: counts, node coordinates,
/// connectivity ends, element bodies and the point arrays' names.
struct MeshArrays<'m> {
    mesh: &'m crate::input::mesh::Mesh,
    nn: usize,
    ne: usize,
    /// Each cell's end in the connectivity (VTK's offsets).
    ends: Vec<usize>,
    /// The connectivity's length.
    connectivity: usize,
    /// x, y, z per node.
    points: Vec<f64>,
    /// A 3D model.
    solid: bool,
    /// The body of each cell.
    body: Vec<f64>,
    /// The point arrays with their components (the values are each frame's).
    names: Vec<(&'static str, usize)>,
}

impl Layout {
    pub fn of(model: &Model, format: VtuFormat) -> Layout {
        let mesh = &model.mesh;
        let hoop = model.section.axisymmetric;
        let twist = model.node_dofs().twist();
        let solid = mesh.dim() == 3;
        let ends: Vec<usize> = mesh
            .elements
            .iter()
            .scan(0, |at, el| {
                *at += el.nodes().len();
                Some(*at)
            })
            .collect();
        let m = MeshArrays {
            mesh,
            nn: mesh.nodes.len(),
            ne: mesh.elements.len(),
            connectivity: ends.last().copied().unwrap_or(0),
            ends,
            points: mesh.nodes.iter().flat_map(|x| *x).collect(),
            solid,
            body: mesh.elements.iter().map(|e| e.body as f64).collect(),
            names: Frame::default()
                .point_arrays(hoop, twist, solid)
                .iter()
                .map(|&(n, c, _)| (n, c))
                .collect(),
        };
        let (head, middle, body) = match format {
            VtuFormat::Ascii => Self::ascii(&m),
            VtuFormat::Binary => Self::binary(&m),
        };
        Layout {
            format,
            hoop,
            twist,
            solid,
            head,
            middle,
            body,
        }
    }

    /// The ASCII document's head (up to the point data) and its middle
    /// (from the point data to the cell data's `body`); no body block.
    fn ascii(m: &MeshArrays<'_>) -> (Vec<u8>, Vec<u8>, Vec<u8>) {
        let MeshArrays {
            mesh,
            nn,
            ne,
            ends,
            body,
            solid,
            ..
        } = m;
        let (nn, ne) = (*nn, *ne);
        let mut head = Vec::new();
        let mut middle = Vec::new();
        let h = &mut head;
        h.extend_from_slice(b"<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\">\n<UnstructuredGrid>\n");
        let _ = writeln!(h, "<Piece NumberOfPoints=\"{nn}\" NumberOfCells=\"{ne}\">");
        h.extend_from_slice(
            b"<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n",
        );
        for x in &mesh.nodes {
            if *solid {
                let _ = writeln!(h, "{:e} {:e} {:e}", x[0], x[1], x[2]);
            } else {
                let _ = writeln!(h, "{:e} {:e} 0", x[0], x[1]);
            }
        }
        h.extend_from_slice(b"</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
        for el in &mesh.elements {
            let n: Vec<String> = el.nodes().iter().map(|n| n.to_string()).collect();
            let _ = writeln!(h, "{}", n.join(" "));
        }
        h.extend_from_slice(
            b"</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n",
        );
        for end in ends.iter() {
            let _ = write!(h, "{end} ");
        }
        h.extend_from_slice(
            b"\n</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n",
        );
        for el in &mesh.elements {
            let _ = write!(h, "{} ", el.family.vtk_cell());
        }
        h.extend_from_slice(b"\n</DataArray>\n</Cells>\n<PointData Vectors=\"displacement\" Scalars=\"von_mises\">\n");
        middle.extend_from_slice(b"</PointData>\n<CellData>\n");
        let _ = ascii_array(&mut middle, "body", 1, Values::All(body));
        (head, middle, Vec::new())
    }

    /// The binary document's head (the XML and the mesh blocks), its middle
    /// (its end) and the `body` block, which follows the point data blocks.
    fn binary(m: &MeshArrays<'_>) -> (Vec<u8>, Vec<u8>, Vec<u8>) {
        let MeshArrays {
            mesh,
            nn,
            ne,
            ends,
            connectivity,
            points,
            body,
            names,
            ..
        } = m;
        let (nn, ne, connectivity) = (*nn, *ne, *connectivity);
        let empty = Frame::default();
        let mut head = Vec::new();
        let mut middle = Vec::new();
        let mut body_block = Vec::new();
        // every block: its byte count (UInt64), then its bytes
        let f64s = |n: usize| 8 + 8 * n as u64;
        let mut offset = 0u64;
        let mut next = |bytes: u64| {
            let at = offset;
            offset += bytes;
            at
        };
        let h = &mut head;
        h.extend_from_slice(b"<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<UnstructuredGrid>\n");
        let _ = writeln!(h, "<Piece NumberOfPoints=\"{nn}\" NumberOfCells=\"{ne}\">");
        let _ = writeln!(
        h,
        "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"appended\" offset=\"{}\"/>\n</Points>\n<Cells>",
        next(f64s(3 * nn))
    );
        let _ = writeln!(
            h,
            "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"appended\" offset=\"{}\"/>",
            next(f64s(connectivity))
        );
        let _ = writeln!(
            h,
            "<DataArray type=\"Int64\" Name=\"offsets\" format=\"appended\" offset=\"{}\"/>",
            next(f64s(ne))
        );
        let _ = writeln!(
        h,
        "<DataArray type=\"UInt8\" Name=\"types\" format=\"appended\" offset=\"{}\"/>\n</Cells>",
        next(8 + ne as u64)
    );
        h.extend_from_slice(b"<PointData Vectors=\"displacement\" Scalars=\"von_mises\">\n");
        for &(name, comps) in names.iter() {
            let _ = writeln!(
            h,
            "<DataArray type=\"Float64\" Name=\"{name}\" NumberOfComponents=\"{comps}\" format=\"appended\" offset=\"{}\"/>",
            next(f64s(comps * nn))
        );
        }
        h.extend_from_slice(b"</PointData>\n<CellData>\n");
        let cells = std::iter::once("body").chain(empty.cell_arrays().into_iter().map(|a| a.0));
        for name in cells {
            let _ = writeln!(
            h,
            "<DataArray type=\"Float64\" Name=\"{name}\" NumberOfComponents=\"1\" format=\"appended\" offset=\"{}\"/>",
            next(f64s(ne))
        );
        }
        h.extend_from_slice(
            b"</CellData>\n</Piece>\n</UnstructuredGrid>\n<AppendedData encoding=\"raw\">\n_",
        );
        // the mesh blocks follow the XML directly
        raw_f64(h, Values::All(points));
        raw_len(h, 8 * connectivity);
        for el in &mesh.elements {
            for &n in el.nodes().iter() {
                h.extend_from_slice(&(n as i64).to_le_bytes());
            }
        }
        raw_len(h, 8 * ne);
        for &end in ends.iter() {
            h.extend_from_slice(&(end as i64).to_le_bytes());
        }
        raw_len(h, ne);
        h.extend(mesh.elements.iter().map(|el| el.family.vtk_cell()));
        raw_f64(&mut body_block, Values::All(body));
        middle.extend_from_slice(b"\n</AppendedData>\n</VTKFile>\n");
        (head, middle, body_block)
    }

    /// Writes the document of one frame to `w` (the document of a 1M-dof
    /// model is about 150 MB in ASCII; it is never held in memory whole).
    pub fn write(&self, w: &mut dyn std::io::Write, frame: &Frame) -> std::io::Result<()> {
        let mut buf = Vec::with_capacity(1 << 16);
        w.write_all(&self.head)?;
        match self.format {
            VtuFormat::Ascii => {
                for (name, comps, vals) in frame.point_arrays(self.hoop, self.twist, self.solid) {
                    ascii_tag(&mut buf, name, comps);
                    ascii_values(w, &mut buf, comps, vals)?;
                }
                w.write_all(&self.middle)?;
                for (name, vals) in frame.cell_arrays() {
                    ascii_tag(&mut buf, name, 1);
                    ascii_values(w, &mut buf, 1, vals)?;
                }
                w.write_all(b"</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n")
            }
            VtuFormat::Binary => {
                for (_, _, vals) in frame.point_arrays(self.hoop, self.twist, self.solid) {
                    raw_f64(&mut buf, vals);
                    w.write_all(&buf)?;
                    buf.clear();
                }
                w.write_all(&self.body)?;
                for (_, vals) in frame.cell_arrays() {
                    raw_f64(&mut buf, vals);
                    w.write_all(&buf)?;
                    buf.clear();
                }
                w.write_all(&self.middle)
            }
        }
    }
}

fn ascii_tag(buf: &mut Vec<u8>, name: &str, comps: usize) {
    let _ = writeln!(
        buf,
        "<DataArray type=\"Float64\" Name=\"{name}\" NumberOfComponents=\"{comps}\" format=\"ascii\">"
    );
}

/// The values as text (`{:e}`, `comps` to a line) and the closing tag,
/// flushed to `w` every 64 KB through `buf`, which it leaves empty.
fn ascii_values(
    w: &mut dyn std::io::Write,
    buf: &mut Vec<u8>,
    comps: usize,
    vals: Values,
) -> std::io::Result<()> {
    let mut i = 0;
    let mut result = Ok(());
    vals.for_each(|v| {
        let _ = write!(buf, "{v:e}");
        i += 1;
        buf.push(if i % comps == 0 { b'\n' } else { b' ' });
        if buf.len() >= 1 << 16 && result.is_ok() {
            result = w.write_all(buf);
            buf.clear();
        }
    });
    result?;
    buf.extend_from_slice(b"</DataArray>\n");
    w.write_all(buf)?;
    buf.clear();
    Ok(())
}

fn ascii_array(
    w: &mut dyn std::io::Write,
    name: &str,
    comps: usize,
    vals: Values,
) -> std::io::Result<()> {
    let mut buf = Vec::new();
    ascii_tag(&mut buf, name, comps);
    ascii_values(w, &mut buf, comps, vals)
}

/// A block's header: its byte count, UInt64 little-endian.
fn raw_len(buf: &mut Vec<u8>, bytes: usize) {
    buf.extend_from_slice(&(bytes as u64).to_le_bytes());
}

/// One block of Float64 values: header and little-endian bytes.
fn raw_f64(buf: &mut Vec<u8>, vals: Values) {
    raw_len(buf, 8 * vals.len());
    buf.reserve(8 * vals.len());
    vals.for_each(|v| buf.extend_from_slice(&v.to_le_bytes()));
}

/// The .pvd collection listing (time = load factor, file name).
pub fn pvd(entries: &[(f64, String)]) -> String {
    let mut s = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\">\n<Collection>\n",
    );
    for (t, f) in entries {
        let _ = writeln!(s, "<DataSet timestep=\"{t}\" part=\"0\" file=\"{f}\"/>");
    }
    s.push_str("</Collection>\n</VTKFile>\n");
    s
}
