"""PNG plots of a run (matplotlib, Agg backend). Each function returns the file name it wrote, or None."""
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)
import numpy as np  # noqa: E402
from matplotlib.ticker import MaxNLocator  # noqa: E402

from . import summary  # noqa: E402

COLORS = {"tetrahedralize": "#d62728", "meshrepair": "#d62728", "simplify-in-envelope": "#d62728",
          "meshrepair.glb": "#d62728", "meshrepair.stl": "#8b0000", "meshrepair.obj": "#e377c2",
          "meshrepair.drc": "#17becf",
          "tetgen": "#1f77b4", "gmsh": "#2ca02c", "ftetwild": "#9467bd", "admesh": "#ff7f0e", "meshlab": "#9467bd"}
FALLBACK = ["#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"]
TIME_FLOOR_S = 1e-3  # log axes cannot show 0 s


def color(tool, order):
    return COLORS.get(tool) or FALLBACK[order.index(tool) % len(FALLBACK)]


def _save(fig, out_dir, name):
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, name), dpi=110)
    plt.close(fig)
    return name


def _scatter_by_size(ax, rows, order, field, floor):
    """Each tool's runs as (input faces, field) points, o = valid, x = failed; False if none."""
    plotted = False
    for tool in order:
        mine = [r for r in rows if r["tool"] == tool and r.get("input_faces") and r.get(field) is not None]
        for ok, marker in ((True, "o"), (False, "x")):
            pts = [(r["input_faces"], max(r[field], floor)) for r in mine if (r["status"] == "ok") == ok]
            if pts:
                x, y = zip(*pts)
                label = f"{tool} ({'ok' if ok else 'failed'}, {len(pts)})"
                style = dict(facecolors=color(tool, order)) if ok else {}
                ax.scatter(x, y, marker=marker, s=36 if ok else 30, color=color(tool, order), alpha=0.8,
                           label=label, **style)
                plotted = True
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("input faces")
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    return plotted


def time_vs_size(rows, order, out_dir, time_limit):
    fig, ax = plt.subplots(figsize=(8, 5))
    if not _scatter_by_size(ax, rows, order, "cpu_s", TIME_FLOOR_S):
        plt.close(fig)
        return None
    ax.axhline(time_limit, color="grey", linestyle="--", linewidth=1)
    ax.text(ax.get_xlim()[1], time_limit, f"time limit {time_limit:g} s (wall) ", va="bottom", ha="right",
            color="grey", fontsize=8)
    ax.set_ylabel("CPU time, user + sys [s]")
    ax.set_title("Time against input size (o = valid output, x = failed)")
    return _save(fig, out_dir, "time_vs_size.png")


def memory_vs_size(rows, order, out_dir):
    fig, ax = plt.subplots(figsize=(8, 5))
    if not _scatter_by_size(ax, rows, order, "peak_mb", 1.0):
        plt.close(fig)
        return None
    ax.set_ylabel("peak resident memory [MB]")
    ax.set_title("Memory against input size (o = valid output, x = failed)")
    return _save(fig, out_dir, "memory_vs_size.png")


def _histograms(rows, order, out_dir, name, panels, title):
    """panels: [(field, x label, log bins?)]; overlaid step histograms, one colour per tool."""
    ok = [r for r in rows if r["status"] == "ok"]
    if not any(r.get(f) is not None for r in ok for f, _, _ in panels):
        return None
    fig, axes = plt.subplots(1, len(panels), figsize=(5.2 * len(panels), 4.2))
    for ax, (field, label, log) in zip(np.atleast_1d(axes), panels):
        _histogram_panel(ax, ok, order, field, label, log)
    fig.suptitle(title)
    return _save(fig, out_dir, name)


def _histogram_panel(ax, ok, order, field, label, log):
    values = {t: [summary._num(r.get(field)) for r in ok if r["tool"] == t and r.get(field) is not None]
              for t in order}
    finite = [v for vs in values.values() for v in vs if v is not None and math.isfinite(v)]
    if not finite:
        ax.text(0.5, 0.5, "no data", ha="center", transform=ax.transAxes)
        return
    lo, hi = min(finite), max(finite)
    if log:
        lo = max(lo, 1e-12)
        bins = np.geomspace(lo, max(hi, lo * 1.01), 25)
        ax.set_xscale("log")
    else:
        bins = np.linspace(lo, max(hi, lo + 1e-9), 25)
    for tool in order:
        vs = [v for v in values[tool] if v is not None]
        unbounded = sum(not math.isfinite(v) for v in vs)
        vs = [v for v in vs if math.isfinite(v)]
        if vs:
            extra = f", {unbounded} inf" if unbounded else ""
            ax.hist(np.clip(vs, bins[0], bins[-1]), bins=bins, histtype="step", linewidth=2,
                    color=color(tool, order), label=f"{tool} (n={len(vs)}{extra})")
    ax.set_xlabel(label)
    ax.set_ylabel("models")
    ax.yaxis.set_major_locator(MaxNLocator(integer=True))
    ax.legend(fontsize=8, loc="best")
    ax.grid(True, alpha=0.3)


def dihedral(rows, order, out_dir):
    return _histograms(rows, order, out_dir, "dihedral.png",
                       [("min_dihedral_deg", "smallest dihedral angle of the mesh [deg]", False),
                        ("avg_min_dihedral_deg", "mean over tets of their smallest dihedral angle [deg]", False)],
                       "Dihedral angles of valid tet meshes (higher is better)")


def amips(rows, order, out_dir):
    return _histograms(rows, order, out_dir, "amips.png",
                       [("max_amips", "worst tet AMIPS energy (log)", True),
                        ("avg_amips", "mean tet AMIPS energy (log)", True)],
                       "AMIPS energy of valid tet meshes (3 = regular tet; lower is better)")


def distance(rows, order, out_dir):
    return _histograms(rows, order, out_dir, "distance.png",
                       [("hausdorff_rel", "Hausdorff distance / input bbox diagonal (log)", True)],
                       "Distance between output and input (sampled, both ways)")


def success_by_tag(rows, order, out_dir):
    table = summary.tag_success(rows)
    if len(table) <= 1 and not table[0][2]:
        return None
    tools = [t for t in order if any(t in per for _, _, per in table)]
    height = 0.8 / max(1, len(tools))
    fig, ax = plt.subplots(figsize=(9, 1.2 + 0.22 * len(table) * max(2, len(tools))))
    y = np.arange(len(table))
    for i, tool in enumerate(tools):
        counts = [per.get(tool, (0, 0)) for _, _, per in table]
        rates = [100.0 * ok / n if n else 0.0 for ok, n in counts]
        pos = y + (i - (len(tools) - 1) / 2) * height
        ax.barh(pos, rates, height=height * 0.95, color=color(tool, order), label=tool)
        for p, rate, (ok, n) in zip(pos, rates, counts):
            if n:
                ax.text(rate + 1, p, f"{ok}/{n}", va="center", fontsize=7)
    ax.set_yticks(y, [f"{tag} ({n})" for tag, n, _ in table])
    ax.invert_yaxis()
    ax.set_xlim(0, 112)
    ax.set_xlabel("valid outputs [% of the models with the tag]")
    ax.set_title("Success by defect category (manifest tags; a model has several)")
    ax.legend(fontsize=8, loc="lower right")
    ax.grid(True, axis="x", alpha=0.3)
    return _save(fig, out_dir, "success_by_tag.png")


def make_all(rows, order, out_dir, time_limit, volume):
    names = [time_vs_size(rows, order, out_dir, time_limit), memory_vs_size(rows, order, out_dir),
             success_by_tag(rows, order, out_dir)]
    if volume:
        names += [dihedral(rows, order, out_dir), amips(rows, order, out_dir)]
    names.append(distance(rows, order, out_dir))
    return [n for n in names if n]
