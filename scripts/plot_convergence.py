#!/usr/bin/env python3
"""Plots a convergence study (hvi convergence): relative error against wall time, one panel per
quantity, log-log. Usage: scripts/plot_convergence.py DIR  (reads DIR/convergence.csv, writes
DIR/convergence.png)."""
import csv
import math
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

out = pathlib.Path(sys.argv[1])
rows = list(csv.DictReader(open(out / "convergence.csv")))
quantities = sorted({r["quantity"] for r in rows})
fig, axes = plt.subplots(1, len(quantities), figsize=(4.2 * len(quantities), 3.6), squeeze=False)
for ax, q in zip(axes[0], quantities):
    by_ppc = {}
    for r in rows:
        if r["quantity"] != q:
            continue
        err = float(r["relative_error"])
        if not math.isfinite(err) or err == 0.0:
            continue
        by_ppc.setdefault(r["particles_per_cell"], []).append((float(r["wall_seconds"]), abs(err), r["level"]))
    for ppc, pts in sorted(by_ppc.items()):
        pts.sort()
        ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", label=f"ppc {ppc}" if ppc != "0" else "scene ppc")
        for t, e, label in pts:
            ax.annotate(label, (t, e), fontsize=7, xytext=(3, 3), textcoords="offset points")
    ax.set_title(q)
    ax.set_xlabel("wall time (s)")
    ax.set_ylabel("|relative error|")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
fig.tight_layout()
fig.savefig(out / "convergence.png", dpi=120)
