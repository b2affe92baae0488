#!/usr/bin/env python3
"""Where and when a body failed, read from a run's snapshots: the fraction of its points failed,
or the median of a field over its intact points, grouped by where each point started, at every
snapshot time.

  failure_history.py RUN --body NAME [--by radius|layer|height|wall] [--bin "0.5 mm"] [--radius "4 mm"]
                         [--axis "X,Y"]
                         [--quantity failed|outward|velocity_z|volume_ratio|pressure|principal|plastic_strain]

Each of the body's points is followed by id from the first snapshot and put in a group. In a
growing hybrid (snapshots with `reference_position`) the body gains points as the zone takes the
far field over: every point any snapshot holds is followed, grouped by its undeformed position X,
and counts from the first snapshot that holds it (before, it was far field: not failed, not in a
median). The groups:
  --by radius (default): by its distance from the impact axis (parallel to z through --axis,
    default "0 mm,0 mm") in bins of --bin, out to --radius (default 8 bins);
  --by layer: by the z it started at (one column per point layer of a facesheet, top first),
    counting only points that started within --radius of the axis;
  --by height: by the z it started at in bins of --bin from the body's top down (a core's walls
    along the impact axis), counting only points that started within --radius of the axis;
  --by wall: by its distance in plan from the nearest honeycomb wall's mid-surface (the run's
    [[panel]]: its cell diameter, rotation and pattern origin), in bins of --bin, counting only
    points that started within --radius of the axis: whether a facesheet fails along the walls'
    footprint, wherever the walls stand on the grid.
--quantity failed (default): the fraction of the group's points failed: a point counts as
failed at a snapshot if its `failed` field is non-zero there (failed or eroded) or if it is no
longer in the model (it left the grid). Any other quantity is the median over the group's intact
points (NaN when none is left): outward, how far a point has moved away from the axis since the
first snapshot (m); velocity_z (m/s); volume_ratio V/V0; pressure (Pa, compression positive);
principal, the largest principal Cauchy stress (Pa, tension positive); plastic_strain, the
equivalent plastic strain of Johnson-Cook strength (a taken-over point starts from the far
field's). Output: CSV on standard
output, one row per snapshot (time in s, then one value per group, its column named after the
group in mm); on standard error how many points each group holds.
"""
import argparse
import json
import pathlib
import sys
import tomllib

import h5py
import numpy as np

from hvi_units import length, lengths  # lengths with units, "0.5 mm", read by hvi


def body_index(run, name, option="--body"):
    bodies = json.loads((run / "run.json").read_text())["bodies"]
    if name not in bodies:
        raise ValueError(f"{option} '{name}': the run's bodies are {', '.join(bodies)}")
    return bodies.index(name)


def snapshot_paths(run):
    """A run's particle snapshots in time order; none is an error."""
    snapshots = sorted((run / "snapshots").glob("particles_*.h5"))
    if not snapshots:
        raise ValueError(f"{run}/snapshots: no particle snapshots")
    return snapshots


def wall_distance(xy, panel):
    """In-plane distance of each point (x, y) from the nearest wall mid-surface of a [[panel]] of
    the resolved scene (geometry/honeycomb.hpp: centres (n D/2, m sqrt(3) D/2), n + m even, in the
    pattern frame turned by `rotation`; the walls D/2 from each centre, normals at 0, 60, 120 deg)."""
    D, theta = panel["cell_diameter"], panel["rotation"]
    c, s = np.cos(theta), np.sin(theta)
    feature = {"cell-center": (0.0, 0.0), "vertex": (0.0, D / np.sqrt(3)), "wall": (D / 2, 0.0)}
    fx, fy = feature[panel["origin_at"]]
    ox = panel["pattern_origin"][0] - (c * fx - s * fy)
    oy = panel["pattern_origin"][1] - (s * fx + c * fy)
    dx, dy = xy[:, 0] - ox, xy[:, 1] - oy
    qx, qy = c * dx + s * dy, -s * dx + c * dy  # the pattern frame
    row = np.sqrt(3) * D / 2
    # The cell holding the point is the candidate centre of least hexagonal extent from it.
    extent = np.full(len(xy), np.inf)
    m0, n0 = np.round(qy / row), np.round(qx / (D / 2))
    for m in (m0 - 1, m0, m0 + 1):
        for n in (n0 - 1, n0, n0 + 1):
            ux, uy = qx - n * D / 2, qy - m * row
            e = np.max([np.abs(ux * np.cos(a) + uy * np.sin(a)) for a in (0, np.pi / 3, 2 * np.pi / 3)], axis=0)
            extent = np.where((n + m) % 2 == 0, np.minimum(extent, e), extent)
    return D / 2 - extent


def run_panel(run):
    """The run's one [[panel]] from its resolved scene."""
    scene = tomllib.loads((pathlib.Path(run) / "scene.resolved.toml").read_text())
    panels = scene.get("panel", [])
    if len(panels) != 1:
        raise ValueError(f"{run}: --by wall needs a run with one [[panel]], this one has {len(panels)}")
    return panels[0]


def groups(x0, by, axis, width, radius, panel=None):
    """Each point's group index (-1: in none) and the groups' column names."""
    r = np.hypot(x0[:, 0] - axis[0], x0[:, 1] - axis[1])
    if by == "wall":
        d = wall_distance(x0[:, :2], panel)
        n = int(np.ceil(0.5 * panel["cell_diameter"] / width))
        index = np.minimum(np.floor(d / width).astype(int), n - 1)
        index[r >= radius] = -1
        names = [f"w_{i * width * 1e3:g}_{(i + 1) * width * 1e3:g}_mm" for i in range(n)]
        return index, names
    if by == "radius":
        n = int(round(radius / width))
        index = np.floor(r / width).astype(int)
        index[(index >= n) | (r >= radius)] = -1
        names = [f"r_{i * width * 1e3:g}_{(i + 1) * width * 1e3:g}_mm" for i in range(n)]
        return index, names
    if by == "height":
        top = x0[:, 2].max()
        depth = top - x0[:, 2]
        n = int(np.floor(depth.max() / width)) + 1
        index = np.minimum(np.floor(depth / width).astype(int), n - 1)
        index[r >= radius] = -1
        names = [f"z_{(top - i * width) * 1e3:.4g}_{(top - (i + 1) * width) * 1e3:.4g}_mm" for i in range(n)]
        return index, names
    # Layers: the distinct starting z (to 1 nm), top first.
    z = np.round(x0[:, 2], 9)
    levels = np.unique(z)[::-1]
    index = np.searchsorted(-levels, -z)
    index[r >= radius] = -1
    return index, [f"z_{level * 1e3:g}_mm" for level in levels]


def largest_principal(stress):
    """The largest eigenvalue of each Cauchy stress, stored as xx xy xz yy yz zz."""
    m = np.empty((len(stress), 3, 3))
    for k, (i, j) in enumerate([(0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)]):
        m[:, i, j] = m[:, j, i] = stress[:, k]
    return np.linalg.eigvalsh(m)[:, -1]


def field(f, now, quantity, axis):
    """The per-point value of a median quantity for the body's points in a snapshot."""
    if quantity == "outward":
        x = f["position"][:][now]
        return np.hypot(x[:, 0] - axis[0], x[:, 1] - axis[1])  # r0 is subtracted by the caller
    if quantity == "velocity_z":
        return f["velocity"][:][now][:, 2]
    if quantity == "principal":
        return largest_principal(f["stress"][:][now])
    return f[quantity][:][now]


def undeformed_positions(snapshots, b):
    """The ids (sorted) of body b's points and where each started. Without `reference_position`,
    the first snapshot's points at their positions there; with it (a growing hybrid), every point
    of every snapshot at its X."""
    with h5py.File(snapshots[0], "r") as f:
        if "reference_position" not in f:
            mine = f["body"][:] == b
            ids, x0 = f["id"][:][mine], f["position"][:][mine]
            order = np.argsort(ids)
            return ids[order], x0[order]
    ids, x0 = [], []
    for path in snapshots:
        with h5py.File(path, "r") as f:
            mine = f["body"][:] == b
            ids.append(f["id"][:][mine])
            x0.append(f["reference_position"][:][mine])
    ids, x0 = np.concatenate(ids), np.concatenate(x0)
    ids, first = np.unique(ids, return_index=True)  # sorted, each point once
    return ids, x0[first]


def history(run, body, by, axis, width, radius, quantity="failed"):
    run = pathlib.Path(run)
    snapshots = snapshot_paths(run)
    b = body_index(run, body)
    ids, x0 = undeformed_positions(snapshots, b)
    if ids.size == 0:
        raise ValueError(f"{snapshots[0]}: body '{body}' has no points")
    index, names = groups(x0, by, axis, width, radius, run_panel(run) if by == "wall" else None)
    r0 = np.hypot(x0[:, 0] - axis[0], x0[:, 1] - axis[1])
    counts = np.bincount(index[index >= 0], minlength=len(names))
    born = np.zeros(ids.size, dtype=bool)  # held by this or an earlier snapshot
    rows = []
    for path in snapshots:
        with h5py.File(path, "r") as f:
            time = float(f.attrs["time"])
            now = f["body"][:] == b
            now_ids, failed = f["id"][:][now], f["failed"][:][now] > 0
            values = None if quantity == "failed" else field(f, now, quantity, axis)[~failed]
        held = np.minimum(np.searchsorted(ids, now_ids), ids.size - 1)
        born[held[ids[held] == now_ids]] = True
        # Intact points still in the model; every other point of the body born so far counts as failed.
        intact_ids = now_ids[~failed]
        where = np.minimum(np.searchsorted(ids, intact_ids), ids.size - 1)
        if np.any(ids[where] != intact_ids):
            raise ValueError(f"{path}: body '{body}' has points the first snapshot does not "
                             "(a growing zone's run made before its snapshots carried reference_position)")
        if quantity == "failed":
            intact = np.zeros(ids.size, dtype=bool)
            intact[where] = True
            lost = born & (~intact) & (index >= 0)
            rows.append((time, np.bincount(index[lost], minlength=len(names)) / np.maximum(counts, 1)))
            continue
        if quantity == "outward":
            values = values - r0[where]
        group = index[where]
        rows.append((time, np.array([np.median(values[group == g]) if np.any(group == g) else np.nan
                                     for g in range(len(names))])))
    return names, counts, rows


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("run", help="run directory (hvi run --out)")
    parser.add_argument("--body", required=True, help="body name as in run.json, e.g. panel.rear")
    parser.add_argument("--by", default="radius", choices=["radius", "layer", "height", "wall"],
                        help="group by (default radius)")
    parser.add_argument("--bin", default="0.5 mm", help='radial or height bin width (default "0.5 mm")')
    parser.add_argument("--quantity", default="failed",
                        choices=["failed", "outward", "velocity_z", "volume_ratio", "pressure", "principal",
                                 "plastic_strain"],
                        help="fraction failed (default) or the median of a field over intact points")
    parser.add_argument("--radius", help="outer radius of the groups (default: 8 bins)")
    parser.add_argument("--axis", default="0 mm,0 mm", help='impact axis "X,Y" (default "0 mm,0 mm")')
    args = parser.parse_args(argv)
    try:
        width = length(args.bin, "--bin")
        radius = length(args.radius, "--radius") if args.radius else 8 * width
        axis = lengths("--axis", args.axis, "X,Y")
        if not (width > 0 and radius > 0):
            raise ValueError("--bin and --radius must be positive")
        names, counts, rows = history(args.run, args.body, args.by, axis, width, radius,
                                      args.quantity)
    except (OSError, KeyError, ValueError) as e:
        print(f"failure_history.py: {e}", file=sys.stderr)
        return 2
    print(",".join(["time_s"] + names))
    for t, fraction in rows:
        print(",".join([f"{t:.9g}"] + [f"{v:.4f}" if args.quantity == "failed" else f"{v:.6g}" for v in fraction]))
    print("points per group: " + ", ".join(f"{n} {c}" for n, c in zip(names, counts)), file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
