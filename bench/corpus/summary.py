"""Numbers of the report, computed from results rows (pure functions, no I/O)."""
import math
import statistics

from .results import FAILURES

TIME_FLOOR_S = 0.01  # ratios of times below this measure process start-up, not the algorithm


def _num(value):
    if value == "inf":
        return math.inf
    return value if isinstance(value, (int, float)) and not isinstance(value, bool) else None


def median(values):
    values = [v for v in map(_num, values) if v is not None]
    return statistics.median(values) if values else None


def mean(values):
    values = [v for v in map(_num, values) if v is not None and math.isfinite(v)]
    return statistics.fmean(values) if values else None


def by_tool(rows):
    grouped = {}
    for r in rows:
        grouped.setdefault(r["tool"], []).append(r)
    return grouped


def success_line(rows):
    """One line of the success table for one tool's rows."""
    ok = [r for r in rows if r["status"] == "ok"]
    line = {"attempted": len(rows), "ok": len(ok)}
    line.update({kind: sum(r["status"] == kind for r in rows) for kind in FAILURES})
    line.update(median_wall=median(r.get("wall_s") for r in ok), mean_wall=mean(r.get("wall_s") for r in ok),
                median_cpu=median(r.get("cpu_s") for r in ok),
                peak_mb=max((r["peak_mb"] for r in ok if r.get("peak_mb") is not None), default=None),
                median_peak_mb=median(r.get("peak_mb") for r in ok))
    return line


def paired_ratios(rows_a, rows_b, time_key):
    """(median of per-model time ratios a/b, n) over the models both finished ok."""
    times_b = {r["model"]: r.get(time_key) for r in rows_b if r["status"] == "ok"}
    ratios = []
    for r in rows_a:
        tb = times_b.get(r["model"])
        ta = r.get(time_key)
        if r["status"] == "ok" and ta is not None and tb is not None:
            ratios.append(max(ta, TIME_FLOOR_S) / max(tb, TIME_FLOOR_S))
    return (statistics.median(ratios) if ratios else None), len(ratios)


def quality_line(rows):
    ok = [r for r in rows if r["status"] == "ok"]
    hausdorff = [r.get("hausdorff_rel") for r in ok]
    return {
        "n": len(ok),
        "worst_min_dihedral": min((r["min_dihedral_deg"] for r in ok if r.get("min_dihedral_deg") is not None),
                                  default=None),
        "median_min_dihedral": median(r.get("min_dihedral_deg") for r in ok),
        "median_avg_min_dihedral": median(r.get("avg_min_dihedral_deg") for r in ok),
        "median_max_amips": median(r.get("max_amips") for r in ok),
        "median_avg_amips": median(r.get("avg_amips") for r in ok),
        "median_min_radius_ratio": median(r.get("min_radius_ratio") for r in ok),
        "median_avg_radius_ratio": median(r.get("avg_radius_ratio") for r in ok),
        "watertight": sum(bool(r.get("watertight")) for r in ok),
        "within_envelope": sum(r.get("within_envelope") is True for r in ok),
        "distance_measured": sum(r.get("hausdorff_rel") is not None for r in ok),
        "median_hausdorff_rel": median(hausdorff),
        "max_hausdorff_rel": max((h for h in hausdorff if h is not None), default=None),
    }


def normalize_tag(tag):
    """'tiny(<100f)' -> 'tiny', 'format-edge:PLY tristrips' -> 'format-edge'."""
    return tag.split("(")[0].split(":")[0].strip()


def tag_success(rows, min_models=3):
    """[(tag, n_models, {tool: (ok, attempted)})], 'all' first, then tags by frequency."""
    models = {}
    for r in rows:
        models.setdefault(r["model"], {normalize_tag(t) for t in r.get("tags") or []})
    counts = {}
    for tags in models.values():
        for t in tags:
            counts[t] = counts.get(t, 0) + 1
    chosen = sorted((t for t, n in counts.items() if n >= min_models), key=lambda t: (-counts[t], t))
    table = [("all", len(models), _success_by_tool(rows, lambda r: True))]
    for tag in chosen:
        table.append((tag, counts[tag], _success_by_tool(rows, lambda r, t=tag: t in models[r["model"]])))
    return table


def _success_by_tool(rows, keep):
    result = {}
    for r in rows:
        if keep(r):
            ok, attempted = result.get(r["tool"], (0, 0))
            result[r["tool"]] = (ok + (r["status"] == "ok"), attempted + 1)
    return result


def baseline_line(rows):
    """Success line of a baseline tool (times: user seconds, as BASELINE.md advises)."""
    ok = [r for r in rows if r["status"] == "ok"]
    line = {"attempted": len(rows), "ok": len(ok)}
    line.update({kind: sum(r["status"] == kind for r in rows) for kind in FAILURES})
    line.update(median_wall=median(r["wall_s"] for r in ok), median_user=median(r["user_s"] for r in ok),
                peak_mb=max((r["peak_mb"] for r in ok if r["peak_mb"] is not None), default=None))
    return line
