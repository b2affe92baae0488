#!/usr/bin/env python3
"""A displacement probe read after the run, from its snapshots: for a point the scene did not
name as a [[measure]], or a probe added to the scene after the run.

  probe_history.py RUN --point "X,Y,Z" [--axis x|y|z]      (e.g. --point "0 mm,20 mm,-15.2 mm")

It reads the point as hvi's `kind = "displacement"` measure does (cases/run/probes.hpp), in the
undeformed configuration:
  - in a hybrid's far field (the point outside `[far_field.zone]` in plane): the nearest far-field
    node, u = its displacement, from RUN/far_field.pvd and its VTU files;
  - with a zone that grows (`[far_field.zone.grow]`), from the first snapshot whose far field no
    longer holds that node (the zone took its cells): the points of the nearest point's body
    whose undeformed positions X (the snapshots' `reference_position`) lie within one grid cell
    of the point, u = mean (x_p - X_p);
  - otherwise the particles of the nearest particle's body within one grid cell of the point in
    the first snapshot, followed by id: u = mean (x_p - x_p^0) over those still in the model.
So on a run's own probe point it gives the run's probes.csv values at the snapshot times (after
a take-over to within the far field's displacement gradient over a cell: the run's probe goes on
from its node's reading, the script from the points' own X).
Output: CSV on standard output (time in s, the displacement component in m, one row per
snapshot); on standard error what it read and the value of largest magnitude.
"""
import argparse
import base64
import pathlib
import re
import struct
import sys
import tomllib
import xml.etree.ElementTree as ET
import zlib

import h5py
import numpy as np

UNITS = {"m": 1.0, "mm": 1e-3, "um": 1e-6}


def length(text):
    """A length with a unit ("20 mm", "-15.2mm", "0.02 m"); a bare number is metres."""
    m = re.fullmatch(r"\s*([-+0-9.eE]+)\s*([a-z]*)\s*", text)
    if not m or m.group(2) not in UNITS | {"": 1.0}:
        raise ValueError(f"'{text}' is not a length (a number with m, mm or um)")
    return float(m.group(1)) * UNITS.get(m.group(2), 1.0)


def lengths(option, text, names):
    """An option's comma-separated lengths, one per name of `names` ("X,Y,Z")."""
    parts = text.split(",")
    count = len(names.split(","))
    if len(parts) != count:
        raise ValueError(f"{option} '{text}': expected {['one', 'two', 'three'][count - 1]} lengths {names}")
    return [length(p) for p in parts]


def vtu_arrays(path):
    """The DataArrays of a VTU file written by deal.II (binary, zlib-compressed or not, or ascii),
    by Name (the unnamed point coordinates as 'points')."""
    text = pathlib.Path(path).read_text()
    compressed = "vtkZLibDataCompressor" in text
    header_type = re.search(r'header_type="(\w+)"', text)
    word = "<Q" if header_type and header_type.group(1) == "UInt64" else "<I"
    size = struct.calcsize(word)
    types = {"Float32": np.float32, "Float64": np.float64, "Int32": np.int32, "Int64": np.int64, "UInt8": np.uint8}
    arrays = {}
    for m in re.finditer(r"<DataArray([^>]*)>(.*?)</DataArray>", text, re.S):
        attrs, body = m.group(1), m.group(2).strip()
        name = re.search(r'Name="([^"]*)"', attrs)
        name = name.group(1) if name else "points"
        dtype = types[re.search(r'type="(\w+)"', attrs).group(1)]
        components = re.search(r'NumberOfComponents="(\d+)"', attrs)
        components = int(components.group(1)) if components else 1
        form = re.search(r'format="(\w+)"', attrs).group(1)
        if form == "ascii":
            data = np.array(body.split(), dtype=dtype)
        elif form == "binary" and compressed:
            # header: blocks, block size, last block size, then each block's compressed size
            blocks = struct.unpack(word, base64.b64decode(body[: 4 * ((size + 2) // 3)])[:size])[0]
            header_chars = 4 * (((3 + blocks) * size + 2) // 3)
            header = struct.unpack(f"{word[0]}{3 + blocks}{word[1]}", base64.b64decode(body[:header_chars])[: (3 + blocks) * size])
            payload, raw, offset = base64.b64decode(body[header_chars:]), b"", 0
            for n in header[3:]:
                raw += zlib.decompress(payload[offset : offset + n])
                offset += n
            data = np.frombuffer(raw, dtype=dtype)
        elif form == "binary":
            raw = base64.b64decode(body)
            data = np.frombuffer(raw[size:], dtype=dtype)
        else:
            raise ValueError(f"{path}: DataArray format '{form}' is not read")
        arrays[name] = data.reshape(-1, components) if components > 1 else data
    return arrays


def far_field_history(run, point, axis):
    collection = ET.parse(run / "far_field.pvd").getroot()
    rows, node = [], None
    for dataset in collection.iter("DataSet"):
        a = vtu_arrays(run / dataset.get("file"))
        if node is None:
            node = int(np.argmin(np.linalg.norm(a["points"] - point, axis=1)))
            where = a["points"][node]
        rows.append((float(dataset.get("timestep")), float(a["displacement"][node, axis])))
    return rows, f"the far-field node at {where[0]:.6g}, {where[1]:.6g}, {where[2]:.6g} m"


def particle_history(run, point, axis, cell):
    snapshots = sorted((run / "snapshots").glob("particles_*.h5"))
    if not snapshots:
        raise ValueError(f"{run}/snapshots: no particle snapshots")
    with h5py.File(snapshots[0], "r") as f:
        x0, ids, body = f["position"][:], f["id"][:], f["body"][:]
    r2 = np.sum((x0 - point) ** 2, axis=1)
    nearest = int(np.argmin(r2))
    chosen = (body == body[nearest]) & (r2 <= max(cell * cell, r2[nearest]))
    reference = dict(zip(ids[chosen].tolist(), x0[chosen, axis].tolist()))
    rows = []
    for path in snapshots:
        with h5py.File(path, "r") as f:
            ids_now = f["id"][:]
            now = np.isin(ids_now, list(reference))
            z = f["position"][:, axis][now]
            z0 = np.array([reference[i] for i in ids_now[now].tolist()])
            rows.append((float(f.attrs["time"]), float(np.mean(z - z0)) if z.size else float("nan")))
    return rows, f"{int(chosen.sum())} particles of body {int(body[nearest])} within {cell:g} m"


def snapshot_times(run):
    """The particle snapshots in time order, as (time, path)."""
    snapshots = sorted((run / "snapshots").glob("particles_*.h5"))
    if not snapshots:
        raise ValueError(f"{run}/snapshots: no particle snapshots")
    times = []
    for path in snapshots:
        with h5py.File(path, "r") as f:
            times.append((float(f.attrs["time"]), path))
    return times


def grown_zone_history(run, point, axis, cell):
    """The far-field node's reading while the far field holds it, then the points that took it
    over, by their undeformed positions."""
    collection = ET.parse(run / "far_field.pvd").getroot()
    datasets = [(float(d.get("timestep")), d.get("file")) for d in collection.iter("DataSet")]
    snapshots = snapshot_times(run)
    node, rows, taken, described = None, [], None, ""
    for time, file in datasets:
        a = vtu_arrays(run / file)
        if node is None:
            node = a["points"][int(np.argmin(np.linalg.norm(a["points"] - point, axis=1)))].astype(float)
            described = f"the far-field node at {node[0]:.6g}, {node[1]:.6g}, {node[2]:.6g} m"
        # The VTU lists each cell's nodes (in float32): the node is there while a cell of it is.
        distance = np.linalg.norm(a["points"] - node, axis=1)
        if taken is None and distance.min() <= 1e-3 * cell:
            rows.append((time, float(a["displacement"][int(np.argmin(distance)), axis])))
            continue
        if taken is None:
            taken = time
        path = min(snapshots, key=lambda s: abs(s[0] - time))[1]
        with h5py.File(path, "r") as f:
            if "reference_position" not in f:
                raise ValueError(f"the zone took the far-field node at {node} by t = {time:g} s, and {path.name} holds "
                                 "no reference_position (a run made before hvi wrote it): read the run's probes.csv")
            X, x, body = f["reference_position"][:], f["position"][:], f["body"][:]
        r2 = np.sum((X - point) ** 2, axis=1)
        nearest = int(np.argmin(r2))
        chosen = (body == body[nearest]) & (r2 <= max(cell * cell, r2[nearest]))
        rows.append((time, float(np.mean(x[chosen, axis] - X[chosen, axis]))))
        described_points = f"{int(chosen.sum())} points of body {int(body[nearest])} within {cell:g} m by their undeformed positions"
    if taken is not None:
        described += f", then (from t = {taken:g} s, the zone grown over it) {described_points}"
    return rows, described


def history(run, point, axis):
    run = pathlib.Path(run)
    scene = tomllib.loads((run / "scene.resolved.toml").read_text())
    zone = scene.get("far_field", {}).get("zone")
    cell = float(scene["grid"]["cell_size"])
    if zone is not None and not (zone["lower"][0] <= point[0] <= zone["upper"][0] and zone["lower"][1] <= point[1] <= zone["upper"][1]):
        if "grow" in zone:
            return grown_zone_history(run, point, axis, cell)
        return far_field_history(run, point, axis)
    return particle_history(run, point, axis, cell)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("run", help="run directory (hvi run --out)")
    parser.add_argument("--point", required=True, help='undeformed position "X,Y,Z" with units, e.g. "0 mm,20 mm,-15.2 mm"')
    parser.add_argument("--axis", default="z", choices=["x", "y", "z"], help="displacement component (default z)")
    args = parser.parse_args(argv)
    try:
        point = np.array(lengths("--point", args.point, "X,Y,Z"))
        rows, what = history(args.run, point, "xyz".index(args.axis))
    except (OSError, KeyError, ValueError) as e:
        print(f"probe_history.py: {e}", file=sys.stderr)
        return 2
    print(f"time_s,displacement_{args.axis}_m")
    for t, u in rows:
        print(f"{t:.9g},{u:.9g}")
    t_peak, u_peak = max(rows, key=lambda r: abs(r[1]) if np.isfinite(r[1]) else -1.0)
    print(f"read {what}; largest |u| {u_peak:.6g} m at {t_peak:.6g} s", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
