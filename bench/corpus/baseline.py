"""The peer baseline of the shared corpus (BASELINE.md, baseline.tsv): measured earlier on a
machine like ours, shown in the report as a reference, never mixed with this run's numbers."""
import csv
import os
import re

BASELINE_TOOLS = {"tetrahedralize": ["ftetwild", "tetwild", "tetgen", "gmsh"], "meshrepair": ["meshfix"],
                  "simplify-in-envelope": []}
DISPLAY = {"ftetwild": "fTetWild", "tetwild": "TetWild", "tetgen": "TetGen", "gmsh": "gmsh", "meshfix": "MeshFix"}


def order(tool):
    """Position of a baseline tool in tables: BASELINE.md's order."""
    everything = [t for tools in BASELINE_TOOLS.values() for t in tools]
    return everything.index(tool) if tool in everything else len(everything)


def status_kind(text):
    """baseline.tsv status -> our failure kinds ('fail rc 134 (signal 6)' -> 'crash')."""
    text = (text or "").strip()
    if text == "ok" or text == "timeout":
        return text
    if "empty" in text:
        return "empty"
    if re.search(r"signal \d+", text):
        return "crash"
    return "error"


def _float(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return None


def load(corpus_dir, task):
    """Rows {model, tool, status, wall_s, user_s, peak_mb, out_tets, note} for the task's tools, or []."""
    path = os.path.join(corpus_dir or "", "baseline.tsv")
    wanted = BASELINE_TOOLS.get(task, [])
    if not corpus_dir or not wanted or not os.path.isfile(path):
        return []
    rows = []
    with open(path, newline="", encoding="utf-8") as f:
        for r in csv.DictReader(f, delimiter="\t"):
            if r.get("tool") not in wanted:
                continue
            rows.append({"model": r["model"], "tool": r["tool"], "status": status_kind(r.get("status")),
                         "raw_status": r.get("status"), "wall_s": _float(r.get("wall_s")),
                         "user_s": _float(r.get("user_s")), "peak_mb": _float(r.get("peak_rss_mb")),
                         "out_tets": _float(r.get("out_tets")), "timeout_s": _float(r.get("timeout_s"))})
    return rows


def source_files(corpus_dir):
    return [p for p in (os.path.join(corpus_dir or "", n) for n in ("BASELINE.md", "baseline.tsv")) if os.path.isfile(p)]
