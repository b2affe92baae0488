#!/ usr / bin / env python3
"""Plots a ballistic-limit search (hvi ballistic-limit): hvi's critical diameter at each speed with
its bracket (the largest diameter stopped, the smallest that perforated), every trial, the SRL
ballistic limit equation's curve for the same panel and the database's experiments on it (P filled,
NP open). Usage: scripts/plot_ballistic_limit.py DIR (reads DIR/ballistic_limit.csv, trials.csv,
srl.csv, experiments.csv; writes DIR/ballistic_limit.png)."""
import csv
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def rows(path):
    return list(csv.DictReader(open(path))) if path.exists() else []


def number(text):
    try:
        return float(text)
    except ValueError:
        return float("nan")


out = pathlib.Path(sys.argv[1])
limits = rows(out / "ballistic_limit.csv")
if limits and "speed_km_s" not in limits[0]:
    sys.exit("plot_ballistic_limit.py: a --vary velocity search has no diameter curve to plot")
fig, ax = plt.subplots(figsize=(6.4, 4.4))
srl = rows(out / "srl.csv")
if srl:
    ax.plot([number(r["speed_km_s"]) for r in srl], [number(r["critical_diameter_mm"]) for r in srl],
            "-", color="0.45", label="SRL equation")
for outcome, style in (("P", dict(marker="x", color="tab:red")), ("NP", dict(marker="+", color="tab:green"))):
    t = [r for r in rows(out / "trials.csv") if r["outcome"] == outcome]
    if not t:
        continue
    ax.plot([number(r["speed_km_s"]) for r in t], [number(r["diameter_mm"]) for r in t], ls="none",
            ms=6, label=f"hvi trial, {outcome}", **style)
v = [number(r["speed_km_s"]) for r in limits]
d = [number(r["critical_diameter_mm"]) for r in limits]
lo = [number(r["critical_diameter_mm"]) - number(r["stopped_mm"]) for r in limits]
hi = [number(r["perforated_mm"]) - number(r["critical_diameter_mm"]) for r in limits]
ax.errorbar(v, d, yerr=[lo, hi], fmt="o-", color="tab:blue", capsize=3, label="hvi ballistic limit")
for outcome, face in (("P", "black"), ("NP", "none")):
    e = [r for r in rows(out / "experiments.csv") if r["outcome"] == outcome]
    if not e:
        continue
    ax.plot([number(r["speed_km_s"]) for r in e], [number(r["diameter_mm"]) for r in e], "s", ms=6,
            mfc=face, mec="black", ls="none", label=f"experiment, {outcome}")
ax.set_xlabel("impact speed (km/s)")
ax.set_ylabel("projectile diameter (mm)")
ax.set_title("ballistic limit: perforating above the curve")
ax.grid(True, alpha=0.3)
ax.legend(fontsize=7)
fig.tight_layout()
fig.savefig(out / "ballistic_limit.png", dpi=120)
