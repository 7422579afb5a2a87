//! VTK XML unstructured grid (.vtu, ASCII) per increment and a .pvd series that
//! ParaView opens. Cells are VTK_QUADRATIC_QUAD (type 23), whose node order is
//! ours: corners counter-clockwise, then the midsides of edges 0-1, 1-2, 2-3, 3-0.

use crate::fem::q8;
use crate::material::VonMises;
use crate::model::Model;
use crate::solve::State;
use std::fmt::Write;

const VTK_QUADRATIC_QUAD: u8 = 23;

/// Nodal fields obtained by extrapolating Gauss point values to the nodes of each
/// element and averaging over the elements that share a node.
pub struct NodalFields {
    /// σxx, σyy, σxy, σzz (σ_rr, σ_zz, σ_rz, σ_θθ in axisymmetry)
    pub stress: Vec<[f64; 4]>,
    pub von_mises: Vec<f64>,
    pub peeq: Vec<f64>,
}

pub fn nodal_fields(model: &Model, state: &State) -> NodalFields {
    let nn = model.mesh.nodes.len();
    let ng = model.n_gauss();
    let mut acc = vec![[0.0f64; 6]; nn];
    let mut count = vec![0u32; nn];
    let mut vals = vec![0.0; ng];
    for (e, el) in model.mesh.elements.iter().enumerate() {
        let gp = &state.gauss[e * ng..(e + 1) * ng];
        #[allow(clippy::needless_range_loop)] // c numbers the field (σ components, Mises, PEEQ)
        for c in 0..6 {
            for (ip, g) in gp.iter().enumerate() {
                vals[ip] = match c {
                    0..=3 => g.stress[c],
                    4 => VonMises::equivalent_stress(&g.stress),
                    _ => g.peeq,
                };
            }
            let at_nodes = q8::extrapolate_to_nodes(&model.rule, &vals);
            for (a, &n) in el.nodes.iter().enumerate() {
                acc[n][c] += at_nodes[a];
            }
        }
        for &n in &el.nodes {
            count[n] += 1;
        }
    }
    let mut f = NodalFields {
        stress: Vec::with_capacity(nn),
        von_mises: Vec::with_capacity(nn),
        peeq: Vec::with_capacity(nn),
    };
    for (a, &c) in acc.iter().zip(&count) {
        let c = f64::from(c.max(1));
        f.stress.push([a[0] / c, a[1] / c, a[2] / c, a[3] / c]);
        f.von_mises.push(a[4] / c);
        f.peeq.push((a[5] / c).max(0.0));
    }
    f
}

/// Writes the VTU document for one state to `w` as it goes (the document of a
/// 1M-dof model is about 150 MB; it is never held in memory).
pub fn write_vtu(w: &mut dyn std::io::Write, model: &Model, state: &State) -> std::io::Result<()> {
    let mesh = &model.mesh;
    let nf = nodal_fields(model, state);
    let nn = mesh.nodes.len();
    let ne = mesh.elements.len();
    // interface tractions at the nodes of both sides
    let mut p_n = vec![0.0; nn];
    let mut p_t = vec![0.0; nn];
    let mut status = vec![-1i32; nn];
    let mut base = 0;
    for im in &model.interfaces {
        // shear tractions live at the spring points: one per pair when lumped
        let lumped = im.points.len() == im.pairs.len() && im.tangential.is_some();
        for (i, pr) in im.pairs.iter().enumerate() {
            let un = im.pair_approach_at(pr, &state.u, im.gap_at(state.time));
            let p = im.law.pressure(un).0;
            let t = if lumped {
                state.contact[base + i].p_t
            } else {
                0.0
            };
            for n in [pr.a, pr.b] {
                p_n[n] = p;
                p_t[n] = t;
                status[n] = i32::from(un > 0.0);
            }
        }
        base += im.points.len();
    }
    w.write_all(b"<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\">\n<UnstructuredGrid>\n")?;
    writeln!(w, "<Piece NumberOfPoints=\"{nn}\" NumberOfCells=\"{ne}\">")?;
    w.write_all(
        b"<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n",
    )?;
    for x in &mesh.nodes {
        writeln!(w, "{:e} {:e} 0", x[0], x[1])?;
    }
    w.write_all(b"</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n")?;
    for el in &mesh.elements {
        let n = &el.nodes;
        writeln!(
            w,
            "{} {} {} {} {} {} {} {}",
            n[0], n[1], n[2], n[3], n[4], n[5], n[6], n[7]
        )?;
    }
    w.write_all(b"</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n")?;
    for e in 0..ne {
        write!(w, "{} ", 8 * (e + 1))?;
    }
    w.write_all(b"\n</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n")?;
    for _ in 0..ne {
        write!(w, "{VTK_QUADRATIC_QUAD} ")?;
    }
    w.write_all(
        b"\n</DataArray>\n</Cells>\n<PointData Vectors=\"displacement\" Scalars=\"von_mises\">\n",
    )?;
    array(
        w,
        "displacement",
        3,
        (0..nn).flat_map(|i| [state.u[2 * i], state.u[2 * i + 1], 0.0]),
    )?;
    array(
        w,
        "stress",
        4,
        nf.stress.iter().flat_map(|v| v.iter().copied()),
    )?;
    if model.section.axisymmetric {
        // x = r, y = z: the fourth stress component is the hoop stress σ_θθ
        array(w, "hoop_stress", 1, nf.stress.iter().map(|v| v[3]))?;
    }
    array(w, "von_mises", 1, nf.von_mises.iter().copied())?;
    array(w, "peeq", 1, nf.peeq.iter().copied())?;
    array(w, "contact_pressure", 1, p_n.iter().copied())?;
    array(w, "contact_shear", 1, p_t.iter().copied())?;
    array(w, "contact_closed", 1, status.iter().map(|&v| f64::from(v)))?;
    w.write_all(b"</PointData>\n<CellData>\n")?;
    array(w, "body", 1, mesh.elements.iter().map(|e| e.body as f64))?;
    let ng = model.n_gauss();
    array(
        w,
        "max_peeq",
        1,
        (0..ne).map(|e| {
            state.gauss[e * ng..(e + 1) * ng]
                .iter()
                .fold(0.0f64, |a, g| a.max(g.peeq))
        }),
    )?;
    w.write_all(b"</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n")
}

fn array(
    w: &mut dyn std::io::Write,
    name: &str,
    comps: usize,
    vals: impl Iterator<Item = f64>,
) -> std::io::Result<()> {
    writeln!(
        w,
        "<DataArray type=\"Float64\" Name=\"{name}\" NumberOfComponents=\"{comps}\" format=\"ascii\">"
    )?;
    for (i, v) in vals.enumerate() {
        write!(w, "{v:e}")?;
        w.write_all(if (i + 1) % comps == 0 { b"\n" } else { b" " })?;
    }
    w.write_all(b"</DataArray>\n")
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
