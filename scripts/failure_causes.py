#!/usr/bin/env python3
"""What a body's points were doing just before they failed, read from a run's snapshots: for the
points intact at one snapshot and failed (or gone) at the next, their state at the first of the
two, one row per snapshot interval.

  failure_causes.py RUN --body panel.rear [--cell "0.2 mm"]

Columns: time (s) of the interval's end; failed, how many of the body's points failed in it;
damaged, the share of them whose Johnson-Cook damage had reached 0.5 (ductile failure on its way)
against those failed with little damage (spall, erosion, or a jump within one interval);
plastic_strain, pressure (Pa, compression positive), principal (the largest principal stress, Pa,
tension positive) and volume_ratio, medians over them; foreign, the share of them with a point
of another body within one grid cell (the debris sharing their nodes' velocity: without
[contact] it moves them as one); relative_speed, the median speed of that nearest foreign point
relative to the failing point (m/s). CSV on standard output."""
import argparse
import pathlib
import sys
import tomllib

import h5py
import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from failure_history import body_index, largest_principal, snapshot_paths  # noqa: E402


def scene(run):
    with open(run / "scene.resolved.toml", "rb") as f:
        return tomllib.load(f)


def read(path):
    with h5py.File(path) as f:
        d = {k: f[k][:] for k in ("id", "body", "failed", "position", "velocity", "damage",
                                  "plastic_strain", "pressure", "stress", "volume_ratio") if k in f}
        d["time"] = float(f.attrs["time"])
    d["id"] = d["id"].ravel()
    d["body"] = d["body"].ravel()
    return d


def nearest_foreign(x, v, others_x, others_v, cell):
    """For each row of x: whether a foreign point lies within `cell`, and its relative speed."""
    near = np.zeros(len(x), bool)
    speed = np.full(len(x), np.nan)
    for k in range(len(x)):
        d2 = np.sum((others_x - x[k]) ** 2, axis=1)
        if len(d2) == 0:
            continue
        j = np.argmin(d2)
        if d2[j] <= cell * cell:
            near[k] = True
            speed[k] = np.linalg.norm(others_v[j] - v[k])
    return near, speed


def median(a):
    a = a[np.isfinite(a)]
    return f"{np.median(a):.6g}" if len(a) else ""


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("run", type=pathlib.Path)
    p.add_argument("--body", required=True)
    p.add_argument("--cell", default="", help="grid cell (default: the scene's), e.g. '0.2 mm'")
    a = p.parse_args()
    body = body_index(a.run, a.body)
    cell = float(a.cell.split()[0]) * 1e-3 if a.cell else scene(a.run)["grid"]["cell_size"]
    print("time,failed,damaged,plastic_strain,pressure,principal,volume_ratio,foreign,relative_speed")
    paths = snapshot_paths(a.run)
    before = read(paths[0])
    for path in paths[1:]:
        now = read(path)
        mine = (before["body"] == body) & (before["failed"].ravel() == 0)
        failed_now = set(now["id"][(now["body"] == body) & (now["failed"].ravel() != 0)])
        gone = set(before["id"][mine]) - set(now["id"])
        ids = before["id"]
        hit = mine & np.array([i in failed_now or i in gone for i in ids])
        n = int(hit.sum())
        row = [f"{now['time']:.6g}", str(n)]
        if n:
            x, v = before["position"][hit], before["velocity"][hit]
            z0, z1 = x[:, 2].min() - cell, x[:, 2].max() + cell
            other = (before["body"] != body) & (before["position"][:, 2] > z0) & (before["position"][:, 2] < z1)
            near, speed = nearest_foreign(x, v, before["position"][other], before["velocity"][other], cell)
            damage = before["damage"].ravel()[hit] if "damage" in before else np.zeros(n)
            row += [f"{np.mean(damage >= 0.5):.3f}", median(before["plastic_strain"].ravel()[hit]),
                    median(before["pressure"].ravel()[hit]), median(largest_principal(before["stress"][hit])),
                    median(before["volume_ratio"].ravel()[hit]), f"{np.mean(near):.3f}", median(speed)]
        else:
            row += [""] * 7
        print(",".join(row))
        before = now


if __name__ == "__main__":
    main()
