"""report.md: the success table first, then ratios, quality, plots, the baseline reference and details."""
import math
import os

from . import baseline as baseline_mod
from . import summary
from .results import FAILURES

KIND_HEADERS = {"crash": "crash", "error": "error", "timeout": "timeout", "oom": "oom", "empty": "empty",
                "invalid": "invalid", "unchecked": "unchecked", "no-input": "no input"}


def fmt(value, digits=2):
    value = summary._num(value)
    if value is None:
        return "—"
    if isinstance(value, float) and math.isinf(value):
        return "inf"
    if isinstance(value, int):
        return str(value)
    if value != 0 and (abs(value) >= 1e5 or abs(value) < 10 ** -digits):
        return f"{value:.{digits}g}" if abs(value) >= 1e5 else f"{value:.1e}"
    return f"{value:.{digits}f}"


def _table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(lines)


def _label(tool, meta):
    return f"**{tool}** (ours)" if meta.get("ours") else tool


def _out_format(tool, meta, rows):
    """Format of the file a tool wrote: from the run's metadata, else from its rows (older runs: '—')."""
    written = meta.get("out_format") or next((r.get("out_format") for r in rows if r.get("out_format")), None)
    return written or "—"


def _pct(ok, n):
    return f"{ok}/{n} ({100.0 * ok / n:.0f}%)" if n else "0/0"


def headline(order, grouped, tools_meta):
    parts = []
    for tool in order:
        meta = tools_meta.get(tool, {})
        rows = grouped.get(tool, [])
        if rows:
            parts.append(f"{_label(tool, meta)} {_pct(sum(r['status'] == 'ok' for r in rows), len(rows))} valid")
        elif meta.get("unavailable"):
            parts.append(f"{_label(tool, meta)} not available ({meta['unavailable']})")
    return "; ".join(parts)


def success_section(order, grouped, tools_meta):
    lines = {t: summary.success_line(grouped[t]) for t in order if t in grouped}
    kinds = [k for k in FAILURES if any(line[k] for line in lines.values())]
    header = ["tool", "output checked", "valid / attempted"] + [KIND_HEADERS[k] for k in kinds] + [
        "median wall s", "mean wall s", "median CPU s", "median peak MB", "max peak MB"]
    rows = []
    for tool in order:
        meta = tools_meta.get(tool, {})
        written = _out_format(tool, meta, grouped.get(tool, []))
        if tool in lines:
            s = lines[tool]
            rows.append([_label(tool, meta), written, _pct(s["ok"], s["attempted"])] + [s[k] for k in kinds] +
                        [fmt(s["median_wall"]), fmt(s["mean_wall"]), fmt(s["median_cpu"]),
                         fmt(s["median_peak_mb"], 0), fmt(s["peak_mb"], 0)])
        elif meta.get("unavailable"):
            rows.append([_label(tool, meta), written, f"not available: {meta['unavailable']}"] +
                        [""] * (len(header) - 3))
    missing = [KIND_HEADERS[k] for k in FAILURES if k not in kinds]
    text = ["## Success (every output checked by our mesh-check)", "",
            _table(header, rows), "",
            "Times and memory are over the valid outputs only. Wall and CPU (user + sys of the tool's own process) "
            "seconds; peak MB = peak resident memory (ru_maxrss). Output checked: the format of the file the "
            "tool wrote, which mesh-check read (`meshrepair.FMT` = meshrepair asked for that format)."]
    if missing:
        text.append(f"No run ended as: {', '.join(missing)}.")
    return "\n".join(text)


def ratio_section(order, grouped):
    measured = [t for t in order if t in grouped]
    if len(measured) < 2:
        return ""
    rows = []
    for a in measured:
        cells = []
        for b in measured:
            if a == b:
                cells.append("·")
                continue
            cpu, n = summary.paired_ratios(grouped[a], grouped[b], "cpu_s")
            wall, _ = summary.paired_ratios(grouped[a], grouped[b], "wall_s")
            cells.append(f"{fmt(cpu)}× cpu, {fmt(wall)}× wall (n={n})" if n else "no common success")
        rows.append([a] + cells)
    return "\n".join([
        "## Time ratios on the models both tools succeed on", "",
        "Cell = median over those models of (row tool's time / column tool's time); below 1: the row tool is "
        f"faster. n = number of models. Times under {summary.TIME_FLOOR_S} s count as {summary.TIME_FLOOR_S} s.",
        "", _table(["row / column"] + measured, rows)])


def quality_section(order, grouped, volume, epsilon):
    measured = [t for t in order if t in grouped]
    if not measured:
        return ""
    q = {t: summary.quality_line(grouped[t]) for t in measured}
    dist = ["within envelope", "median Hausdorff / diag", "max Hausdorff / diag"]
    if volume:
        header = ["tool", "valid", "worst min dihedral °", "median min dihedral °", "median mean min dihedral °",
                  "median max AMIPS", "median mean AMIPS", "median min radius ratio", "median mean radius ratio",
                  "watertight boundary"] + dist
        rows = [[t, q[t]["n"], fmt(q[t]["worst_min_dihedral"]), fmt(q[t]["median_min_dihedral"]),
                 fmt(q[t]["median_avg_min_dihedral"]), fmt(q[t]["median_max_amips"]), fmt(q[t]["median_avg_amips"]),
                 fmt(q[t]["median_min_radius_ratio"], 3), fmt(q[t]["median_avg_radius_ratio"], 3),
                 f"{q[t]['watertight']}/{q[t]['n']}"] + _distance_cells(q[t]) for t in measured]
    else:
        header = ["tool", "valid", "watertight"] + dist
        rows = [[t, q[t]["n"], f"{q[t]['watertight']}/{q[t]['n']}"] + _distance_cells(q[t]) for t in measured]
    notes = [f"Per model, over valid outputs. Envelope: sampled distance from the output to the input <= "
             f"{epsilon:g} × the input's bbox diagonal. Hausdorff = max of both one-sided sampled distances."]
    if volume:
        notes.append("Radius ratio = 3 × inradius / circumradius (1 = regular tet); mesh-check does not report it "
                     "yet, so the runner computes it from the output converted to Medit (empty when that fails "
                     "or the mesh has more than 5M tets). Watertight boundary: closed, manifold, outward, no "
                     "self-intersection (exact).")
    return "\n".join(["## Output quality", "", _table(header, rows), "", " ".join(notes)])



def _defects_local(stats):
    """Whether meshrepair found the input's defects local (--stats "defects_cut"."local"); None when not reported."""
    return ((stats or {}).get("defects_cut") or {}).get("local")


def _kept_median_phrase(shares, what):
    return f"{100 * summary.median(shares):.1f}% over {len(shares)} {what}" if shares else f"no {what}"


def kept_input_section(order, grouped):
    """meshrepair: how much of each output is input triangles kept as they were (--stats "provenance")."""
    rows, shares, by_locality = [], [], {True: [], False: []}
    for tool in order:
        for r in sorted(grouped.get(tool, []), key=lambda r: r["model"]):
            p = (r.get("tool_stats") or {}).get("provenance")
            if r["status"] != "ok" or not p:
                continue
            shares.append(p["kept_area_share"])
            local = _defects_local(r["tool_stats"])
            if local is not None:
                by_locality[local].append(p["kept_area_share"])
            rows.append([f"`{r['model']}`", tool, (r["tool_stats"] or {}).get("path", ""), fmt(r.get("input_faces")),
                         {True: "yes", False: "no", None: "–"}[local],
                         fmt(p["input_triangles_kept"]), f"{100 * p['kept_area_share']:.1f}%",
                         fmt(p["recut_faces"]), fmt(p["filled_faces"])])
    if not rows:
        return ""
    return "\n".join([
        "## Input kept", "",
        f"Share of the output's area on input triangles kept as they were (corners bit for bit on the output "
        f"grid): median {_kept_median_phrase(shares, 'outputs')}; "
        f"{_kept_median_phrase(by_locality[True], 'inputs whose defects are local')}, "
        f"{_kept_median_phrase(by_locality[False], 'others')}. Defects local: the faces that are defects "
        "(degenerate, meeting another improperly, on an edge of other than two faces or of two disagreeing "
        "ones) are at most a tenth of the faces, or the only defects are holes. Recut: output faces within "
        "epsilon of an input triangle; filled: farther from every input triangle (holes, gaps).", "",
        _table(["model", "tool", "path", "input faces", "defects local", "input faces kept", "kept area",
                "recut faces", "filled faces"], rows)])


def _distance_cells(q):
    return [f"{q['within_envelope']}/{q['distance_measured']}", fmt(q["median_hausdorff_rel"], 5),
            fmt(q["max_hausdorff_rel"], 5)]


def baseline_section(baseline_rows, run_models, grouped, corpus_dir):
    if not baseline_rows:
        return ""
    keys = set(run_models)
    rows_by_tool = {}
    for r in sorted(baseline_rows, key=lambda r: baseline_mod.order(r["tool"])):
        if r["model"] in keys:
            rows_by_tool.setdefault(r["tool"], []).append(r)
    table = []
    for tool, rows in rows_by_tool.items():
        s = summary.baseline_line(rows)
        kinds = ", ".join(f"{s[k]} {k}" for k in FAILURES if s[k])
        table.append([baseline_mod.DISPLAY.get(tool, tool), _pct(s["ok"], s["attempted"]), kinds or "—",
                      fmt(s["median_wall"]), fmt(s["median_user"]), fmt(s["peak_mb"], 0)])
    text = ["## Reference: BASELINE.md — NOT measured in this run", "",
            f"From `{os.path.join(corpus_dir, 'baseline.tsv')}`: measured earlier on a 2-core machine like this "
            "one, with the commands listed in BASELINE.md; restricted to the models of this run (matched by "
            "model key). Its 'ok' means exit 0 with non-empty output, not a mesh-check verdict. Compare user "
            "seconds, not wall.", "",
            _table(["tool (baseline)", "ok / attempted", "failures", "median wall s", "median user s",
                    "max peak MB"], table)]
    text += _agreement(rows_by_tool, grouped) + _cross_run_ratios(rows_by_tool, grouped)
    return "\n".join(text)


def _agreement(rows_by_tool, grouped):
    lines = []
    for tool, rows in rows_by_tool.items():
        if tool not in grouped:
            continue
        ours = {r["model"]: r["status"] for r in grouped[tool]}
        both = [(r["model"], r["status"], ours[r["model"]]) for r in rows if r["model"] in ours]
        differ = [f"`{m}` (baseline {b}, now {n})" for m, b, n in both if (b == "ok") != (n == "ok")]
        lines.append(f"- {tool}: same ok / not-ok verdict as the baseline on {len(both) - len(differ)} of "
                     f"{len(both)} models" + (f"; differs on {', '.join(differ)}" if differ else ""))
    return (["", "This run against the baseline, for the tools in both:"] + lines) if lines else []


def _cross_run_ratios(rows_by_tool, grouped):
    lines = []
    for tool, rows in grouped.items():
        if not rows or not rows[0].get("ours"):
            continue
        for ref, ref_rows in rows_by_tool.items():
            ratio, n = summary.paired_ratios(rows, [dict(r, cpu_s=r["user_s"]) for r in ref_rows], "cpu_s")
            if n:
                lines.append(f"- {tool} CPU s / {baseline_mod.DISPLAY.get(ref, ref)} user s (cross-run): "
                             f"median {fmt(ratio)}× over {n} models both succeed on")
    return (["", "Ours against the baseline (different runs, so only indicative):"] + lines) if lines else []


def per_model_section(order, grouped, baseline_rows):
    by_model = {}
    for tool, rows in grouped.items():
        for r in rows:
            by_model.setdefault(r["model"], {"row": r})[tool] = r
    ref = {}
    for r in sorted(baseline_rows, key=lambda r: baseline_mod.order(r["tool"])):
        if r["model"] in by_model:
            ref.setdefault(r["tool"], {})[r["model"]] = r
    tools = [t for t in order if t in grouped]
    header = ["model", "faces", "tags"] + tools + [f"{baseline_mod.DISPLAY.get(t, t)} (baseline)" for t in ref]
    rows = []
    for model in sorted(by_model):
        first = by_model[model]["row"]
        tags = ", ".join(dict.fromkeys(summary.normalize_tag(t) for t in first.get("tags") or []))
        cells = [_cell(by_model[model].get(t), "cpu_s") for t in tools]
        cells += [_cell(ref[t].get(model), "user_s") for t in ref]
        rows.append([f"`{model}`", fmt(first.get("input_faces")), tags] + cells)
    return "\n".join(["## Per model", "", "Status and CPU seconds (baseline: user seconds).", "",
                      _table(header, rows)])


def _cell(row, time_key):
    if row is None:
        return ""
    t = row.get(time_key)
    return f"{row['status']} {fmt(t)}s" if row["status"] == "ok" and t is not None else row["status"]


def failure_notes(order, grouped):
    rows = [[f"`{r['model']}`", t, r["status"], (r.get("note") or "").replace("|", "/")[:160]]
            for t in order for r in sorted(grouped.get(t, []), key=lambda r: r["model"]) if r["status"] != "ok"]
    if not rows:
        return ""
    return "\n".join(["<details><summary>Failure notes (" + str(len(rows)) + ")</summary>", "",
                      _table(["model", "tool", "status", "note (end of stderr, or the check that failed)"], rows),
                      "", "</details>"])


def run_section(meta, n_models):
    runs = meta.get("runs", [])
    last = runs[-1] if runs else {}
    m = last.get("machine", {})
    lines = ["## Run", ""]
    lines += [f"- Command{'s' if len(runs) > 1 else ''} (results of all of them are merged; a resumed run "
              "skips what is done):"]
    lines += [f"  - `{r['command']}` ({r['started']})" for r in runs]
    lines += [f"- Corpus: `{meta.get('corpus')}`, {n_models} models in the results",
              f"- Machine: {m.get('cpu_model')}, {m.get('cores')} cores ({m.get('usable_cores')} usable), "
              f"{m.get('memory_gib')} GiB memory, {m.get('os')}, kernel {m.get('kernel')}; load average at start "
              f"{', '.join(map(str, m.get('load_at_start', [])))}",
              f"- Limits per model and tool: {fmt(last.get('time_limit_s'), 0)} s wall (the whole process group is "
              f"killed), {fmt(last.get('memory_limit_mb'), 0)} MB address space (RLIMIT_AS); mesh-check: "
              f"{fmt(last.get('check_time_limit_s'), 0)} s; epsilon {last.get('epsilon')} of the input's bbox "
              f"diagonal; {last.get('jobs')} model(s) in parallel"]
    return "\n".join(lines)


def config_section(order, tools_meta):
    lines = ["## Tools and their configuration", ""]
    for tool in order:
        meta = tools_meta.get(tool, {})
        where = f"`{meta['executable']}`" if meta.get("executable") else f"not available: {meta.get('unavailable')}"
        version = f", version {meta['version']}" if meta.get("version") else ""
        lines.append(f"- **{tool}**{' (ours)' if meta.get('ours') else ''}: {meta.get('fair_config')} — {where}"
                     f"{version}")
    lines += ["", "Every tool runs through the same harness: same input model, same limits, one thread "
              "(ours with `-j 1`, gmsh with `-nt 1`, fTetWild with `--max-threads 1`, OMP_NUM_THREADS=1 for "
              "all), its own process group, CPU time and peak memory from the kernel's rusage of the tool's "
              "process. Input conversion for peers is done before the clock starts."]
    return "\n".join(lines)


DEFINITIONS = """## Definitions

- **valid**: exit 0 and an output that our `mesh-check` accepts. Tet meshes: at least one tet, no inverted
  or degenerate tet (exact orientation on the stored coordinates), closed boundary, boundary within the
  envelope of the input (sampled distance <= epsilon × bbox diagonal). Repaired surfaces:
  watertight (closed, manifold, consistently oriented outward, no degenerate face, no self-intersection).
  Simplified surfaces: non-empty and within the envelope.
- **crash**: killed by a signal (segfault, abort). **error**: non-zero exit. **timeout**: still running
  at the time limit (process group killed). **oom**: failed while near the memory limit, or with an
  allocation failure in its stderr, or killed by the kernel. **empty**: exit 0 but no output, an empty
  file, or 0 tets/faces. **invalid**: output that mesh-check rejects or cannot read. **unchecked**:
  mesh-check itself did not finish. **no input**: the input could not be converted to the peer's format.
- Results: `results.jsonl` (one line per model and tool), outputs and logs in `models/<model>/<tool>/`."""


def write(out_dir, meta, rows, baseline_rows, plot_names):
    """Writes out_dir/report.md and returns its path."""
    tools_meta = meta.get("tools", {})
    order = [t for t in meta.get("tool_order", []) if t in tools_meta or any(r["tool"] == t for r in rows)]
    order += sorted({r["tool"] for r in rows} - set(order))
    grouped = summary.by_tool(rows)
    volume = meta.get("task") == "tetrahedralize"
    models = sorted({r["model"] for r in rows})
    parts = [f"# Corpus run: {meta.get('task')}", "", headline(order, grouped, tools_meta), "",
             success_section(order, grouped, tools_meta),
             ratio_section(order, grouped),
             quality_section(order, grouped, volume, (meta.get("runs") or [{}])[-1].get("epsilon", 1e-3)),
             "" if volume else kept_input_section(order, grouped),
             "## Plots\n\n" + "\n\n".join(f"![{n}]({n})" for n in plot_names) if plot_names
             else "## Plots\n\nNo plots (matplotlib missing or nothing to plot).",
             baseline_section(baseline_rows, models, grouped, meta.get("corpus", "")),
             run_section(meta, len(models)),
             config_section(order, tools_meta),
             per_model_section(order, grouped, [r for r in baseline_rows]),
             failure_notes(order, grouped),
             DEFINITIONS]
    path = os.path.join(out_dir, "report.md")
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n\n".join(p for p in parts if p) + "\n")
    return path
