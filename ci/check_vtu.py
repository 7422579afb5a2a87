#!/usr/bin/env python3
"""Reads the VTU series of one `asperity run` with meshio, an independent reader,
and checks it. Usage: ci/check_vtu.py OUT_DIR [PROBE_X PROBE_Y]

Checks every file listed in OUT_DIR/results.pvd: it parses, holds only quad8
cells (VTK type 23) with eight valid point ids each, the expected point and cell
arrays with the right number of components, all finite. Prints one JSON object
on stdout with what it found (sizes, names, the displacement of the lower
body's point nearest to the probe, the peak contact pressure) for the caller to
compare with the run's own CSV and summary; exits 1 with a message on the
first failed check."""
import json
import math
import os
import sys
import xml.etree.ElementTree as ET

import meshio
import numpy as np

POINT_ARRAYS = {  # name: components (see src/files/output/vtu.rs)
    "displacement": 3,
    "stress": 4,
    "von_mises": 1,
    "peeq": 1,
    "contact_pressure": 1,
    "contact_shear": 1,
    "contact_closed": 1,
}
CELL_ARRAYS = {"body": 1, "max_peeq": 1}


def fail(msg):
    print(f"check_vtu: {msg}", file=sys.stderr)
    sys.exit(1)


def components(a):
    return 1 if a.ndim == 1 else a.shape[1]


def vtk_types(path):
    """The distinct cell type codes of the file, read from its XML directly: the
    text of an ASCII file's types array, or the block of a binary file's raw
    appended data its offset points at (UInt8 values after a byte count of the
    file's header_type)."""
    with open(path, "rb") as f:
        raw = f.read()
    at = raw.find(b"<AppendedData")
    if at < 0:
        root = ET.fromstring(raw)
    else:
        root = ET.fromstring(raw[:at] + b"</VTKFile>")
    for a in root.iter("DataArray"):
        if a.get("Name") != "types":
            continue
        if a.get("format") != "appended":
            return sorted({int(v) for v in a.text.split()})
        size = {"UInt32": 4, "UInt64": 8}.get(root.get("header_type", "UInt32"))
        if at < 0 or size is None or a.get("type") != "UInt8":
            fail(f"{path}: types array in an unexpected form")
        start = raw.index(b"_", at) + 1 + int(a.get("offset"))
        count = int.from_bytes(raw[start : start + size], "little")
        block = raw[start + size : start + size + count]
        if len(block) != count:
            fail(f"{path}: types block runs past the end of the file")
        return sorted(set(block))
    fail(f"{path}: no types array")


def main():
    out = sys.argv[1]
    probe = [float(v) for v in sys.argv[2:4]] or [0.0, 0.0]
    pvd = os.path.join(out, "results.pvd")
    entries = [
        (float(d.get("timestep")), d.get("file"))
        for d in ET.parse(pvd).getroot().iter("DataSet")
    ]
    if not entries:
        fail(f"{pvd} lists no data set")
    times = [t for t, _ in entries]
    if any(b <= a for a, b in zip(times, times[1:])):
        fail(f"{pvd}: time steps not increasing: {times}")
    report = {"files": len(entries), "timesteps": times}
    for t, rel in entries:
        path = os.path.join(out, rel)
        mesh = meshio.read(path)
        npts = len(mesh.points)
        if [c.type for c in mesh.cells] != ["quad8"]:
            fail(f"{path}: cell blocks {[c.type for c in mesh.cells]}, expected one quad8 block")
        cells = mesh.cells[0].data
        if cells.shape[1] != 8 or cells.min() < 0 or cells.max() >= npts:
            fail(f"{path}: bad connectivity, shape {cells.shape}")
        if not np.isfinite(mesh.points).all() or np.abs(mesh.points[:, 2]).max() != 0.0:
            fail(f"{path}: points not finite or not in the plane z = 0")
        for name, comps in POINT_ARRAYS.items():
            a = mesh.point_data.get(name)
            if a is None:
                fail(f"{path}: no point array {name} (has {sorted(mesh.point_data)})")
            if len(a) != npts or components(a) != comps:
                fail(f"{path}: point array {name} has shape {a.shape}, expected ({npts}, {comps})")
            if not np.isfinite(a).all():
                fail(f"{path}: point array {name} is not finite")
        for name, comps in CELL_ARRAYS.items():
            blocks = mesh.cell_data.get(name)
            if blocks is None:
                fail(f"{path}: no cell array {name} (has {sorted(mesh.cell_data)})")
            a = blocks[0]
            if len(a) != len(cells) or components(a) != comps:
                fail(f"{path}: cell array {name} has shape {a.shape}")
            if not np.isfinite(a).all():
                fail(f"{path}: cell array {name} is not finite")
        if (mesh.point_data["peeq"] < 0).any():
            fail(f"{path}: negative equivalent plastic strain")
    # the last file: what the caller compares with its own output
    pd = {k: np.asarray(v).reshape(len(v), -1) for k, v in mesh.point_data.items()}
    body = np.asarray(mesh.cell_data["body"][0]).ravel()
    lower = int(body.max())
    on_lower = np.zeros(npts, bool)
    on_lower[cells[body == lower].ravel()] = True
    iface = on_lower & (pd["contact_closed"][:, 0] >= 0)
    if not iface.any():
        fail(f"{path}: no interface point on the lower body")
    idx = np.flatnonzero(iface)
    d = np.hypot(mesh.points[idx, 0] - probe[0], mesh.points[idx, 1] - probe[1])
    p = int(idx[np.argmin(d)])
    u = pd["displacement"]
    report.update(
        points=npts,
        cells=len(cells),
        cell_type="quad8",
        vtk_types=vtk_types(path),
        point_arrays=sorted(mesh.point_data),
        cell_arrays=sorted(mesh.cell_data),
        probe_point=[float(v) for v in mesh.points[p, :2]],
        probe_uy=float(u[p, 1]),
        max_contact_pressure=float(pd["contact_pressure"].max()),
        max_von_mises=float(pd["von_mises"].max()),
        max_cell_peeq=float(mesh.cell_data["max_peeq"][0].max()),
        closed_points=int((pd["contact_closed"] > 0).sum()),
    )
    print(json.dumps(report))


if __name__ == "__main__":
    main()
