#!/usr/bin/env python3
"""The report of a study (hvi report DIR): a Markdown file with PNG figures, from DIR/sweep.csv (hvi
sweep) and each run's snapshots and measurements.

  report.py DIR [--reference REF_DIR]

Figures: top views of both facesheets of each run (intact material; paper Fig. 13), the core's
damage seen from the side (Fig. 11), D_f and D_r against impact energy (Fig. 15), the channel
taper against impact energy (Fig. 16), and D_f and D_r against time for runs with a hole history
(hvi measure RUN --snapshot all). Tables: every run; against Table 2 (Turner's experiments and the
paper's MPM) for runs named case1..case7; against Table 5 (the paper's D_f) for runs named
m<mass>g_v<speed>, marking front holes still growing; whether each hole history has settled.
REF_DIR holds turner_validation.csv and front_holes.csv (cases/paper/reference).
"""
import argparse
import csv
import json
import math
import pathlib
import re
import subprocess
import sys
import tempfile
import tomllib

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

MM = 1e-3


def number(text):
    try:
        v = float(text)
        return v if math.isfinite(v) else None
    except (TypeError, ValueError):
        return None


def csv_rows(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def load_runs(out):
    """One dict per run: the sweep.csv row, or a single run directory's measurements."""
    sweep = out / "sweep.csv"
    if (out / "ballistic_limit.csv").exists():  # hvi ballistic-limit: its trials
        sweep = out / "trials" / "sweep.csv"
    if sweep.exists():
        rows = csv_rows(sweep)
        for r in rows:
            r["dir"] = sweep.parent / r["run"]
        return rows
    if (out / "measurements.csv").exists():  # a single run
        row = csv_rows(out / "measurements.csv")[0]
        row["dir"] = out
        summary = json.loads((out / "summary.json").read_text()) if (out / "summary.json").exists() else {}
        row["status"] = summary.get("status", "")
        row["wall_seconds"] = str(summary.get("wall_seconds_total", summary.get("wall_seconds", "")))
        row["particles"] = str(summary.get("particles", ""))
        row["energy_balance"] = str(summary.get("energy_balance", ""))
        return [row]
    sys.exit(f"report.py: {out} has neither sweep.csv (hvi sweep) nor measurements.csv (hvi measure)")


def projectile_mass(run_dir, d_p):
    """m_p = rho pi d^3 / 6 with the density of the projectile's material in the resolved scene."""
    scene = tomllib.loads((run_dir / "scene.resolved.toml").read_text())
    bodies = {b["name"]: b for b in scene.get("body", [])}
    materials = {m["name"]: m for m in scene.get("material", [])}
    if "projectile" not in bodies:
        return None
    rho = materials[bodies["projectile"]["material"]].get("density")
    return rho * math.pi * d_p**3 / 6 if rho else None


def last_snapshot(run_dir):
    files = sorted((run_dir / "snapshots").glob("particles_*.h5"))
    return files[-1] if files else None


def read_pgm(path):
    """A binary PGM (P5, 8 bits) as a 2D array, its first row the image's top."""
    data = path.read_bytes()
    fields, pos = [], 0
    while len(fields) < 4:
        while data[pos:pos + 1].isspace():
            pos += 1
        end = pos
        while not data[end:end + 1].isspace():
            end += 1
        fields.append(data[pos:end])
        pos = end
    nx, ny = int(fields[1]), int(fields[2])
    return np.frombuffer(data[pos + 1:pos + 1 + nx * ny], dtype=np.uint8).reshape(ny, nx)


def top_views(run_dir, hvi, scratch):
    """hvi measure's own top views of the run's facesheets (mirrored across its symmetry planes as
    the measurement is), and the measurement, written into `scratch`; None if it fails."""
    done = subprocess.run([hvi, "measure", str(run_dir), "--images", "--out", str(scratch)],
                          capture_output=True, text=True)
    if done.returncode != 0 or not (scratch / "measurements.json").exists():
        return None
    return json.loads((scratch / "measurements.json").read_text())


def draw_top_view(ax, part, meas, scratch):
    """One facesheet's top view as hvi measure rasters it: material black, the hole grey."""
    sheet = meas.get(part, {})
    view = sheet.get("top_view")
    if not view or not (scratch / view["file"]).exists():
        ax.set_visible(False)
        return
    x0, y0, px = view["x0"] / MM, view["y0"] / MM, view["pixel"] / MM
    ax.imshow(read_pgm(scratch / view["file"]), cmap="gray", vmin=0, vmax=255, interpolation="nearest",
              extent=(x0, x0 + view["nx"] * px, y0, y0 + view["ny"] * px))
    title = f"{part} facesheet (intact)"
    if sheet.get("perforated"):
        title += f": D = {sheet.get('D', 0) / MM:.2f} mm, e = {sheet.get('eccentricity', 0):.3f}"
    else:
        title += ": not perforated"
    ax.set_title(title, fontsize=9)
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")


def figure_run(run, figures, hvi):
    """Top views of the facesheets and the core's damage seen from the side, for one run."""
    d = run["dir"]
    snap = last_snapshot(d)
    info_file = d / "run.json"
    if snap is None or not info_file.exists():
        return None
    bodies = json.loads(info_file.read_text()).get("bodies", [])
    with tempfile.TemporaryDirectory() as tmp:
        scratch = pathlib.Path(tmp)
        meas = top_views(d, hvi, scratch) or {}
        fig, axes = plt.subplots(1, 3, figsize=(14, 4.6))
        for ax, part in zip(axes[:2], ("front", "rear")):
            draw_top_view(ax, part, meas, scratch)
    with h5py.File(snap, "r") as f:
        pos = f["position"][()]
        body = f["body"][()]
        failed = f["failed"][()] if "failed" in f else np.zeros(len(body), dtype=np.int8)
        damage = f["damage"][()] if "damage" in f else failed.astype(float)
    index = {name: k for k, name in enumerate(bodies)}
    ax = axes[2]
    if "panel.core" in index:
        core = np.flatnonzero(body == index["panel.core"])
        core = core[np.argsort(damage[core], kind="stable")]  # the damaged walls drawn last, on top
        sc = ax.scatter(pos[core, 0] / MM, pos[core, 2] / MM, s=0.3, c=np.clip(damage[core], 0, 1), cmap="gray_r",
                        vmin=0, vmax=1, linewidths=0, rasterized=True)
        fig.colorbar(sc, ax=ax, label="damage (1: failed)")
        ax.set_title("core seen along y: damage of the walls", fontsize=9)
        ax.set_aspect("equal")
        ax.set_xlabel("x (mm)")
        ax.set_ylabel("z (mm)")
    else:
        ax.set_visible(False)
    fig.suptitle(f"{run['run']} at t = {meas.get('time', 0) * 1e6:.2f} us", fontsize=10)
    fig.tight_layout()
    png = figures / f"{run['run']}.png"
    fig.savefig(png, dpi=90)
    plt.close(fig)
    return png


def failed_zone_diameter(run, which="rear"):
    """Diagnostic, not the paper's measure: twice the largest radius about the impact axis out to
    which at least half of the sheet's particles (in 0.25 mm rings) have failed. A coarse run can
    end with the failed disc still in place; the paper's measure (intact material) then sees only
    the part already cleared."""
    d = run["dir"]
    snap = last_snapshot(d)
    if snap is None or not (d / "run.json").exists() or not (d / "measurements.json").exists():
        return None
    bodies = json.loads((d / "run.json").read_text()).get("bodies", [])
    meas = json.loads((d / "measurements.json").read_text())
    name = meas.get(which, {}).get("body", f"panel.{which}")
    if name not in bodies:
        return None
    with h5py.File(snap, "r") as f:
        if "failed" not in f:
            return None
        sel = f["body"][()] == bodies.index(name)
        pos = f["position"][()][sel]
        failed = f["failed"][()][sel] > 0
    x0, y0 = meas.get("axis", [0.0, 0.0])
    r = np.hypot(pos[:, 0] - x0, pos[:, 1] - y0)
    ring = 0.25 * MM
    radius = 0.0
    for k in range(int(r.max() / ring) + 1 if len(r) else 0):
        inside = (r >= k * ring) & (r < (k + 1) * ring)
        if inside.sum() == 0:
            radius = (k + 1) * ring  # nothing left there: torn away
            continue
        if failed[inside].mean() < 0.5:
            break
        radius = (k + 1) * ring
    return 2 * radius


def fmt_mm(v):
    return f"{v / MM:.2f}" if v is not None else "—"


def fmt_ratio(text):
    v = number(text)
    return f"{v:.3f}" if v else "—"


def perforated(run, which):
    text = run.get(f"{which}_perforated", "")
    return None if text == "" else text.lower() in ("true", "1", "1.0")


def runs_table(runs):
    lines = ["| run | status | particles | wall (s) | front | D_f (mm) | e_f | rear | D_r (mm) | e_r | taper | energy |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in runs:
        def cell(which):
            p = perforated(r, which)
            return "—" if p is None else ("perforated" if p else "NP")
        eb = number(r.get("energy_balance"))
        wall = number(r.get("wall_seconds"))
        lines.append("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |".format(
            r["run"], r.get("status", ""), r.get("particles", ""), f"{wall:.0f}" if wall is not None else "—",
            cell("front"), fmt_mm(number(r.get("D_f"))), fmt_ratio(r.get("e_f")), cell("rear"), fmt_mm(number(r.get("D_r"))),
            fmt_ratio(r.get("e_r")), f"{number(r.get('taper')):.3f}" if number(r.get("taper")) is not None else "—",
            f"{100 * eb:+.2f}%" if eb is not None else "—"))
    return "\n".join(lines)


def table2(runs, ref_dir):
    """Against Table 2: perforation of the rear sheet and D_r, for runs named case1..case7."""
    by_case = {int(m.group(1)): r for r in runs if (m := re.fullmatch(r"case(\d+)", r["run"]))}
    if not by_case:
        return None
    ref = {int(row["case"]): row for row in csv_rows(ref_dir / "turner_validation.csv")}
    lines = ["| case | Turner | d_p (mm) | v_p (m/s) | D_r exp. (mm) | D_r paper MPM (mm) | D_r hvi (mm) | hvi vs exp. | outcome | failed-zone D (mm) |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    correct, errors, paper_errors, done = 0, [], [], 0
    for case in sorted(ref):
        row, r = ref[case], by_case.get(case)
        exp_np = row["D_r_exp_mm"] == "NP"
        hvi_p = perforated(r, "rear") if r and r.get("status") == "finished" else None
        d_hvi = number(r.get("D_r")) if r else None
        cells = [str(case), row["ref_case"], row["d_p_mm"], row["v_p_m_s"], row["D_r_exp_mm"], row["D_r_paper_mpm_mm"]]
        if hvi_p is None:
            cells += ["not run", "—", "—", "—"]
        else:
            done += 1
            match = hvi_p == (not exp_np)
            correct += match
            cells.append(f"{d_hvi / MM:.2f}" if hvi_p and d_hvi else "NP")
            if hvi_p and not exp_np and d_hvi:
                err = d_hvi / MM / float(row["D_r_exp_mm"]) - 1
                errors.append(abs(err))
                cells.append(f"{100 * err:+.0f}%")
            else:
                cells.append("—")
            cells.append("correct" if match else "wrong")
            zone = failed_zone_diameter(r)
            cells.append(f"{zone / MM:.2f}" if zone else "—")
        if row["D_r_paper_mpm_mm"] != "NP" and not exp_np:
            paper_errors.append(abs(float(row["D_r_paper_mpm_mm"]) / float(row["D_r_exp_mm"]) - 1))
        lines.append("| " + " | ".join(cells) + " |")
    lines.append("")
    lines.append(f"Perforation of the rear sheet classified correctly: **{correct} of {done}** runs "
                 f"(the paper: 5 of 7). Mean |D_r error| against experiment over the shots both perforated: "
                 + (f"**{100 * np.mean(errors):.0f}%** ({len(errors)} shots)" if errors else "—")
                 + f" (the paper: {100 * np.mean(paper_errors):.0f}% over {len(paper_errors)}). The last column is a "
                 "diagnostic, not the paper's measure: the diameter of the disc of the rear sheet in which at least half "
                 "the material has failed (in 0.25 mm rings), cleared away or not.")
    return "\n".join(lines)


def table5(runs, ref_dir):
    """Against Table 5: D_f for runs named m<mass>g_v<speed>, and for each label of runs named
    m<mass>g_v<speed>_<label> (one variant of the study each, such as a cell size:
    study/front_hole_fine.toml's m10g_v2200_h0141) a table of its own."""
    variants = {}
    for r in runs:
        m = re.fullmatch(r"m(\d+)g_v(\d+)(?:_(\w+))?", r["run"])
        if m and number(r.get("D_f")) is not None:
            found = variants.setdefault(m.group(3) or "", {})
            found[(int(m.group(1)), int(m.group(2)))] = (number(r["D_f"]) / MM, growing_front_hole(r))
    if not variants:
        return None
    ref = csv_rows(ref_dir / "front_holes.csv")
    parts = []
    for label in sorted(variants):
        if label:
            parts += [f"Runs `m<g>g_v<m/s>_{label}`:", ""]
        parts += [table5_variant(variants[label], ref), ""]
    return "\n".join(parts[:-1])


def table5_variant(found, ref):
    """One Table 5 comparison: found[(mass in g, speed in m/s)] = (D_f in mm, whether it still grows)."""
    speeds = [int(k[1:]) for k in ref[0] if k.startswith("v")]
    lines = ["| m_p (g) | " + " | ".join(f"{v} m/s: paper / hvi" for v in speeds) + " |",
             "|---|" + "---|" * len(speeds)]
    within, count, errs, growing = 0, 0, [], 0
    for row in ref:
        mass = int(row["m_p_g"])
        cells = [str(mass)]
        for v in speeds:
            paper = float(row[f"v{v}"])
            if (mass, v) not in found:
                cells.append(f"{paper:.2f} / —")
                continue
            hvi, grows = found[(mass, v)]
            growing += grows
            err = hvi / paper - 1
            errs.append(err)
            count += 1
            within += abs(err) <= 0.05
            cells.append(f"{paper:.2f} / {hvi:.2f} ({100 * err:+.0f}%{', growing' if grows else ''})")
        lines.append("| " + " | ".join(cells) + " |")
    lines.append("")
    lines.append(f"D_f within 5% of the paper's: **{within} of {count}** runs; mean error {100 * np.mean(errs):+.1f}%, "
                 f"mean |error| {100 * np.mean(np.abs(errs)):.1f}%.")
    if growing:
        lines.append(f"{growing} of these front holes {'still grows' if growing == 1 else 'still grow'} at the end of "
                     f"{'its' if growing == 1 else 'their'} run (more than "
                     f"{100 * SETTLED:.0f}% over its last fifth; Hole histories below).")
    return "\n".join(lines)


def energy_figures(runs, figures):
    pts = []
    for r in runs:
        d_p, v_p = number(r.get("d_p")), number(r.get("v_p"))
        if d_p is None or v_p is None or r.get("status") != "finished":
            continue
        m = projectile_mass(r["dir"], d_p)
        if m is None:
            continue
        pts.append((0.5 * m * v_p**2, d_p, number(r.get("D_f")), number(r.get("D_r")), number(r.get("taper"))))
    if len(pts) < 2:
        return []
    sizes = sorted({p[1] for p in pts})

    def against_energy(ax, column, scale, ylabel):
        """One line per projectile size: column `column` of pts (divided by `scale`) against energy."""
        for d in sizes:
            sel = sorted((p[0], p[column]) for p in pts if p[1] == d and p[column] is not None)
            if sel:
                ax.plot([e / 1e3 for e, _ in sel], [v / scale for _, v in sel], "o-", label=f"d_p = {d / MM:.2f} mm")
        ax.set_xscale("log")
        ax.set_xlabel("impact energy (kJ)")
        ax.set_ylabel(ylabel)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)

    def save(fig, png, title):
        fig.tight_layout()
        fig.savefig(figures / png, dpi=90)
        plt.close(fig)
        made.append((title, png))

    made = []
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    against_energy(axes[0], 2, MM, "D_f (mm)")
    against_energy(axes[1], 3, MM, "D_r (mm)")
    save(fig, "holes_vs_energy.png", "Hole diameters against impact energy (paper Fig. 15)")
    if any(p[4] is not None for p in pts):
        fig, ax = plt.subplots(figsize=(5.5, 4))
        against_energy(ax, 4, 1.0, "taper t = (D_r - D_f) / S")
        save(fig, "taper_vs_energy.png", "Channel taper against impact energy (paper Fig. 16)")
    return made


SETTLED = 0.02  # largest |change| of a hole's diameter over the last fifth of a run for it to count as final
FRONT, REAR = 1, 2  # columns of a hole history


def hole_history(run_dir):
    """(t, D_f, D_r) per snapshot, in time order; None for NP. From RUN/measurements_history.csv
    (hvi measure --snapshot all) or RUN/holes_history.csv (the run's own, with a holes measure's
    history = true), whichever has more rows: a run that kept only its newest snapshots has its
    whole history in the second only."""
    best = None
    for name in ("measurements_history.csv", "holes_history.csv"):
        path = run_dir / name
        if not path.exists():
            continue
        rows = [(number(r.get("time")), number(r.get("D_f")), number(r.get("D_r"))) for r in csv_rows(path)]
        rows = sorted((t, f, r) for t, f, r in rows if t is not None)
        if best is None or len(rows) > len(best):
            best = rows
    return best


def settling(h, column):
    """Whether one hole of a history has settled: its diameter at the end against the diameter at
    80% of the end time (the last snapshot at or before it). Returns (opened at, D there, D at the
    end, change, verdict, settled) with None where the sheet was not perforated."""
    t_end = h[-1][0]
    opened = next((row[0] for row in h if row[column] is not None), None)
    before = [row[column] for row in h if row[0] <= 0.8 * t_end + 1e-15]
    early, late = before[-1] if before else None, h[-1][column]
    if late is None:
        return opened, early, late, None, "NP at the end", False
    if early is None:
        return opened, early, late, None, f"no (> {100 * SETTLED:.0f}%)", False
    c = late / early - 1
    return opened, early, late, c, "yes" if abs(c) <= SETTLED else f"no (> {100 * SETTLED:.0f}%)", abs(c) <= SETTLED


def growing_front_hole(run):
    """True when the run has a hole history whose front hole has not settled by its end."""
    h = hole_history(run["dir"])
    return bool(h) and h[-1][FRONT] is not None and not settling(h, FRONT)[5]


def history_section(runs, figures):
    """Each hole against time for every run with a history, and whether it has settled: its
    diameter at the end against the diameter at 80% of the end time."""
    histories = [(r["run"], h) for r in runs if (h := hole_history(r["dir"]))]
    if not histories:
        return None
    lines = []
    for column, sheet, symbol in ((FRONT, "front", "D_f"), (REAR, "rear", "D_r")):
        lines += [f"| run | {sheet} opens at (us) | {symbol} at 0.8 t_end (mm) | {symbol} at t_end (mm) | change | settled |",
                  "|---|---|---|---|---|---|"]
        fig, ax = plt.subplots(figsize=(6.5, 4))
        for name, h in histories:
            opened, early, late, c, verdict, _ = settling(h, column)
            change = "—" if late is None else "opened late" if early is None else f"{100 * c:+.1f}%"
            lines.append(f"| {name} | {'NP' if opened is None else f'{opened / 1e-6:.1f}'} | {fmt_mm(early)} | "
                         f"{fmt_mm(late)} | {change} | {verdict} |")
            pts = [(row[0], row[column]) for row in h if row[column] is not None]
            if pts:
                ax.plot([t / 1e-6 for t, _ in pts], [d / MM for _, d in pts], "o-", ms=3, label=name)
        ax.set_xlabel("t (us)")
        ax.set_ylabel(f"{symbol} (mm)")
        ax.grid(True, alpha=0.3)
        if ax.lines:
            ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(figures / f"{sheet}_hole_history.png", dpi=90)
        plt.close(fig)
        lines += ["", f"![{sheet} hole against time](report/{sheet}_hole_history.png)", ""]
    lines += [f"A hole counts as settled when its diameter changed by at most {100 * SETTLED:.0f}% over the last "
              "fifth of the run."]
    return "\n".join(lines)


def markdown_table(rows, columns):
    """A Markdown table of `columns` (CSV column, heading) from CSV rows."""
    lines = ["| " + " | ".join(h for _, h in columns) + " |", "|" + "---|" * len(columns)]
    lines += ["| " + " | ".join(r.get(c, "") for c, _ in columns) + " |" for r in rows]
    return "\n".join(lines)


def limit_sections(out):
    """hvi ballistic-limit's curve and hvi validate's shots, when the directory holds them."""
    md = []
    if (out / "ballistic_limit.csv").exists():
        rows = csv_rows(out / "ballistic_limit.csv")
        md += ["## Ballistic limit (hvi ballistic-limit)", "",
               markdown_table(rows, [("speed_km_s", "v (km/s)"), ("critical_diameter_mm", "d_c (mm)"),
                                     ("stopped_mm", "largest NP (mm)"), ("perforated_mm", "smallest P (mm)"),
                                     ("trials", "trials"), ("wall_seconds", "wall (s)"), ("status", "status"),
                                     ("srl_critical_diameter_mm", "SRL d_c (mm)")]), ""]
        if (out / "ballistic_limit.png").exists():
            md += ["![ballistic limit](ballistic_limit.png)", ""]
    if (out / "validate.csv").exists():
        rows = csv_rows(out / "validate.csv")
        right = sum(r["right"] == "1" for r in rows)
        run = sum(r["right"] != "" for r in rows)
        srl = sum(r["srl"] == r["observed"] for r in rows)
        md += ["## Against the experiments (hvi validate)", "",
               f"hvi: {right} of {run} outcomes right; SRL equation: {srl} of {len(rows)}.", "",
               markdown_table(rows, [("run", "shot"), ("d_p_mm", "d_p (mm)"), ("v_km_s", "v (km/s)"),
                                     ("observed", "experiment"), ("srl", "SRL"), ("hvi", "hvi"),
                                     ("hvi_D_r_mm", "hvi D_r (mm)")]), ""]
    return md


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("dir", type=pathlib.Path)
    parser.add_argument("--reference", type=pathlib.Path,
                        default=pathlib.Path(__file__).resolve().parent.parent / "cases" / "paper" / "reference")
    parser.add_argument("--no-run-figures", action="store_true", help="skip the per-run top views (large runs)")
    parser.add_argument("--hvi", default=str(pathlib.Path(__file__).resolve().parent.parent / "build" / "hvi"),
                        help="the hvi program, whose measure draws the top views")
    args = parser.parse_args()
    out = args.dir
    runs = load_runs(out)
    figures = out / "report"
    figures.mkdir(exist_ok=True)
    md = [f"# hvi report: {out}", "", f"{len(runs)} runs.", ""] + limit_sections(out)
    md += ["## Runs", "", runs_table(runs), ""]
    t2 = table2(runs, args.reference)
    if t2:
        md += ["## Against Table 2 (Turner's experiments, the paper's MPM)", "", t2, ""]
    t5 = table5(runs, args.reference)
    if t5:
        md += ["## Against Table 5 (the paper's D_f)", "", t5, ""]
    hist = history_section(runs, figures)
    if hist:
        md += ["## Hole histories (hvi measure RUN --snapshot all)", "", hist, ""]
    for title, png in energy_figures(runs, figures):
        md += [f"## {title}", "", f"![{title}](report/{png})", ""]
    if not args.no_run_figures:
        md += ["## Top views and core damage (paper Figs. 11, 13)", ""]
        for r in runs:
            if r.get("status") == "finished":
                png = figure_run(r, figures, args.hvi)
                if png:
                    md += [f"### {r['run']}", "", f"![{r['run']}](report/{png.name})", ""]
    (out / "report.md").write_text("\n".join(md) + "\n")
    print(f"report: {out / 'report.md'} (figures in {figures})")


if __name__ == "__main__":
    main()
