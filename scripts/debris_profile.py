#!/usr/bin/env python3
"""How the debris is spread across the impact axis as it arrives at a depth: the mass per unit
area of chosen bodies' points within a slab of z, in rings about the axis, at every snapshot.

  debris_profile.py RUN --bodies projectile,panel.front --z "-33.5 mm,-36 mm"
                    [--bin "0.5 mm"] [--radius "4 mm"] [--axis "0 mm,0 mm"]
                    [--quantity areal_mass|velocity_z]

A point counts where it is at the snapshot (failed or not), if its z lies in the slab (the two
--z bounds in either order) and its distance from the axis (parallel to z through --axis) lies
in a ring of width --bin out to --radius (a whole number of rings, default 8). --quantity
areal_mass (default): the points' mass over the ring's area, kg/m^2. A model cut by symmetry planes through the axis (a
`symmetry` boundary of the run's scene.resolved.toml on x = axis X or y = axis Y) holds half or
a quarter of each ring, and the area is that part's. velocity_z: the median z-velocity of the
ring's points, m/s (NaN when it holds none). Output: CSV on standard output, one row per
snapshot (time in s, then one value per ring, its column named after the ring in mm); on
standard error the share of each ring the model holds.
"""
import argparse
import pathlib
import sys
import tomllib

import h5py
import numpy as np

from failure_history import body_index, snapshot_paths
from hvi_units import length, lengths  # lengths with units, "0.5 mm", read by hvi


def held_share(run, axis):
    """The share of a ring about the axis the model holds: 1/2 per symmetry plane through it."""
    path = run / "scene.resolved.toml"
    planes = set()
    for b in tomllib.loads(path.read_text()).get("boundary", []):
        if b.get("type") != "symmetry" or str(b.get("face", ""))[:1] not in ("x", "y"):
            continue
        if "position" not in b:
            raise ValueError(f"{path}: a symmetry boundary on face {b['face']} has no position")
        d = "xy".index(b["face"][0])
        if abs(b["position"] - axis[d]) < 1e-12:
            planes.add(d)
    return 0.5 ** len(planes)


def profile(run, bodies, z_range, axis, width, radius, quantity="areal_mass"):
    run = pathlib.Path(run)
    snapshots = snapshot_paths(run)
    chosen = [body_index(run, name, "--bodies") for name in bodies]
    share = held_share(run, axis)
    n = int(round(radius / width))
    if n < 1 or abs(n * width - radius) > 1e-9 * radius:
        raise ValueError(f"--radius {radius * 1e3:g} mm is not a whole number of {width * 1e3:g} mm rings")
    edges = width * np.arange(n + 1)
    area = share * np.pi * (edges[1:] ** 2 - edges[:-1] ** 2)
    names = [f"r_{edges[i] * 1e3:g}_{edges[i + 1] * 1e3:g}_mm" for i in range(n)]
    z_low, z_high = min(z_range), max(z_range)
    rows = []
    for path in snapshots:
        with h5py.File(path, "r") as f:
            time = float(f.attrs["time"])
            x = f["position"][:]
            mine = np.isin(f["body"][:], chosen) & (x[:, 2] >= z_low) & (x[:, 2] <= z_high)
            r = np.hypot(x[mine, 0] - axis[0], x[mine, 1] - axis[1])
            ring = np.floor(r / width).astype(int)
            inside = ring < n
            if quantity == "areal_mass":
                mass = f["mass"][:][mine][inside]
                rows.append((time, np.bincount(ring[inside], weights=mass, minlength=n) / area))
                continue
            vz = f["velocity"][:][mine][inside, 2]
            ring = ring[inside]
            rows.append((time, np.array([np.median(vz[ring == i]) if np.any(ring == i) else np.nan
                                         for i in range(n)])))
    return names, share, rows


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("run", help="run directory (hvi run --out)")
    parser.add_argument("--bodies", required=True, help="body names as in run.json, comma-separated")
    parser.add_argument("--z", required=True, help='the slab\'s two z bounds "Z1,Z2", e.g. "-33.5 mm,-36 mm"')
    parser.add_argument("--bin", default="0.5 mm", help='ring width (default "0.5 mm")')
    parser.add_argument("--radius", help="outer radius of the rings (default: 8 rings)")
    parser.add_argument("--axis", default="0 mm,0 mm", help='impact axis "X,Y" (default "0 mm,0 mm")')
    parser.add_argument("--quantity", default="areal_mass", choices=["areal_mass", "velocity_z"],
                        help="mass per ring area, kg/m^2 (default), or the median z-velocity, m/s")
    args = parser.parse_args(argv)
    try:
        width = length(args.bin, "--bin")
        radius = length(args.radius, "--radius") if args.radius else 8 * width
        if not (width > 0 and radius > 0):
            raise ValueError("--bin and --radius must be positive")
        axis = lengths("--axis", args.axis, "X,Y")
        z_range = lengths("--z", args.z, "Z1,Z2")
        names, share, rows = profile(args.run, args.bodies.split(","), z_range, axis, width, radius,
                                     args.quantity)
    except (OSError, KeyError, ValueError, tomllib.TOMLDecodeError) as e:
        print(f"debris_profile.py: {e}", file=sys.stderr)
        return 2
    print(",".join(["time_s"] + names))
    for t, values in rows:
        print(",".join([f"{t:.9g}"] + [f"{v:.6g}" for v in values]))
    print(f"the model holds {share:g} of each ring (symmetry planes through the axis)", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
