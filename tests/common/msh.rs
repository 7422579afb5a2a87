//! Gmsh 4.1 text of boxes of 20-node hexahedra stacked along y, for the
//! tests of interfaces on a mesh of volumes: each box a body (physical
//! volume) with its own nodes, so that two boxes touching along y = const
//! have distinct, coincident nodes there where their meshes agree.

/// One box: the body's name and its element boundaries along x, y and z
/// (each strictly increasing, at least two values).
pub struct Box3 {
    pub name: &'static str,
    pub axes: [Vec<f64>; 3],
}

/// The six sides of a box: (name suffix, axis, at the lower end?). The
/// names are those of an extruded block layout: `left` x min, `right` x
/// max, `bottom` y min, `top` y max, `zmin`, `zmax`.
pub const SIDES: [(&str, usize, bool); 6] = [
    ("left", 0, true),
    ("right", 0, false),
    ("bottom", 1, true),
    ("top", 1, false),
    ("zmin", 2, true),
    ("zmax", 2, false),
];

/// Gmsh's 20-node hexahedron: its corners and edge midpoints as offsets
/// (0, 1, 2) on the half-cell lattice, in Gmsh's node order (corners, then
/// the edges 0–1, 0–3, 0–4, 1–2, 1–5, 2–3, 2–6, 3–7, 4–5, 4–7, 5–6, 6–7).
fn h20_offsets() -> [[usize; 3]; 20] {
    let c = [
        [0, 0, 0],
        [2, 0, 0],
        [2, 2, 0],
        [0, 2, 0],
        [0, 0, 2],
        [2, 0, 2],
        [2, 2, 2],
        [0, 2, 2],
    ];
    let edges = [
        (0, 1),
        (0, 3),
        (0, 4),
        (1, 2),
        (1, 5),
        (2, 3),
        (2, 6),
        (3, 7),
        (4, 5),
        (4, 7),
        (5, 6),
        (6, 7),
    ];
    let mut out = [[0; 3]; 20];
    out[..8].copy_from_slice(&c);
    for (k, (p, q)) in edges.into_iter().enumerate() {
        out[8 + k] = std::array::from_fn(|a| (c[p][a] + c[q][a]) / 2);
    }
    out
}

/// The MSH 4.1 (ASCII) text of the boxes: physical volume `<name>` per box
/// (tags 1, 2, …), physical surfaces `<name>.<side>` ([`SIDES`]) of 8-node
/// quadrangles, one surface entity each; nodes numbered box by box, every
/// point of a box's half-cell lattice with at most one odd index a node.
pub fn boxes_msh(boxes: &[Box3]) -> String {
    let mut names = String::new();
    let mut entities = String::new();
    let mut nodes = String::new();
    let mut surfaces = String::new();
    let mut volumes = String::new();
    let (mut next_node, mut next_element) = (1usize, 1usize);
    let big = 1e3;
    for (b, bx) in boxes.iter().enumerate() {
        let m: [usize; 3] = std::array::from_fn(|a| 2 * (bx.axes[a].len() - 1) + 1);
        let coord = |a: usize, i: usize| -> f64 {
            let x = &bx.axes[a];
            if i % 2 == 0 {
                x[i / 2]
            } else {
                0.5 * (x[i / 2] + x[i / 2 + 1])
            }
        };
        // lattice point → node tag (0: no node)
        let mut tag = vec![0usize; m[0] * m[1] * m[2]];
        let at = |p: [usize; 3]| p[0] + m[0] * (p[1] + m[1] * p[2]);
        let mut block = String::new();
        let mut xyz = String::new();
        for k in 0..m[2] {
            for j in 0..m[1] {
                for i in 0..m[0] {
                    if (i % 2) + (j % 2) + (k % 2) > 1 {
                        continue;
                    }
                    tag[at([i, j, k])] = next_node;
                    block += &format!("{next_node}\n");
                    xyz += &format!("{} {} {}\n", coord(0, i), coord(1, j), coord(2, k));
                    next_node += 1;
                }
            }
        }
        let count = block.lines().count();
        nodes += &format!("3 {} 0 {count}\n{block}{xyz}", b + 1);
        let cells: [usize; 3] = std::array::from_fn(|a| bx.axes[a].len() - 1);
        let mut hexes = String::new();
        for k in 0..cells[2] {
            for j in 0..cells[1] {
                for i in 0..cells[0] {
                    let tags: Vec<String> = h20_offsets()
                        .iter()
                        .map(|o| tag[at([2 * i + o[0], 2 * j + o[1], 2 * k + o[2]])].to_string())
                        .collect();
                    hexes += &format!("{next_element} {}\n", tags.join(" "));
                    next_element += 1;
                }
            }
        }
        let n_hex = cells.iter().product::<usize>();
        volumes += &format!("3 {} 17 {n_hex}\n{hexes}", b + 1);
        names += &format!("3 {} \"{}\"\n", b + 1, bx.name);
        entities += &format!(
            "V {} -{big} -{big} -{big} {big} {big} {big} 1 {} 0\n",
            b + 1,
            b + 1
        );
        for (s, (side, axis, low)) in SIDES.iter().enumerate() {
            let id = 6 * b + s + 1;
            names += &format!("2 {id} \"{}.{side}\"\n", bx.name);
            let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
            let fixed = if *low { 0 } else { m[*axis] - 1 };
            let mut quads = String::new();
            for q in 0..cells[v] {
                for p in 0..cells[u] {
                    // corners and midsides in the (u, v) plane, counter-clockwise
                    let uv = [
                        [0, 0],
                        [2, 0],
                        [2, 2],
                        [0, 2],
                        [1, 0],
                        [2, 1],
                        [1, 2],
                        [0, 1],
                    ];
                    let tags: Vec<String> = uv
                        .iter()
                        .map(|o| {
                            let mut pt = [0; 3];
                            pt[*axis] = fixed;
                            pt[u] = 2 * p + o[0];
                            pt[v] = 2 * q + o[1];
                            tag[at(pt)].to_string()
                        })
                        .collect();
                    quads += &format!("{next_element} {}\n", tags.join(" "));
                    next_element += 1;
                }
            }
            surfaces += &format!("2 {id} 16 {}\n{quads}", cells[u] * cells[v]);
            entities += &format!("S {id} -{big} -{big} -{big} {big} {big} {big} 1 {id} 0\n");
        }
    }
    let n_phys = names.lines().count();
    let (n_surf, n_vol) = (6 * boxes.len(), boxes.len());
    // surfaces before volumes in $Entities
    let (s_lines, v_lines): (Vec<&str>, Vec<&str>) =
        entities.lines().partition(|l| l.starts_with('S'));
    let strip = |l: &&str| l[2..].to_string();
    let entities: Vec<String> = s_lines.iter().chain(&v_lines).map(strip).collect();
    let n_nodes = next_node - 1;
    let n_elements = next_element - 1;
    let n_blocks = boxes.len() * 7;
    format!(
        "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n{n_phys}\n{names}$EndPhysicalNames\n\
         $Entities\n0 0 {n_surf} {n_vol}\n{}\n$EndEntities\n\
         $Nodes\n{} {n_nodes} 1 {n_nodes}\n{nodes}$EndNodes\n\
         $Elements\n{n_blocks} {n_elements} 1 {n_elements}\n{surfaces}{volumes}$EndElements\n",
        entities.join("\n"),
        boxes.len()
    )
}

/// `n` equal cells from `a` to `b`: the n + 1 boundaries.
pub fn cells(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..=n).map(|i| a + (b - a) * i as f64 / n as f64).collect()
}
