#!/usr/bin/python3
"""Hole filling: our hole-fill against CGAL (hole_fill_peer_cgal) and admesh, on the open models.

    bench/hole_fill_bench.py --out /tmp/hf_bench [--models 'thingi10k/*'] [--time-limit 120]

Every model of the corpus manifest with closed == 0 (or those matching --models)
is filled by each tool, one run at a time, under a time limit; wall seconds and
peak memory are measured. Each output, and each tool's input, is judged by
mesh-check: boundary edges left, self-intersecting pairs added (output minus the
file the tool read), watertight. For ours, the input faces missing from the
output (as position triples, up to rotation of the corners) are counted too.
admesh reads STL only: it gets the model converted by format-convert (float32),
and its added intersections are counted against that STL.

Writes OUT/results.jsonl (one line per model and tool; rows already there are
skipped on a second run) and OUT/report.md (a table per tool and a summary).
"""
import argparse
import csv
import fnmatch
import json
import os
import signal
import statistics
import subprocess
import sys
import tempfile
import time

TOOLS = ("ours", "cgal", "admesh")


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    p.add_argument("--build-dir", default=os.path.join(repo, "build"), help="the configured build folder (default: build)")
    p.add_argument("--corpus", default="/work/shared/corpus", help="folder with MANIFEST.tsv")
    p.add_argument("--out", required=True, help="folder for results.jsonl, report.md and the outputs")
    p.add_argument("--models", help="fnmatch pattern on the manifest's file column (default: every open model)")
    p.add_argument("--time-limit", type=float, default=120, help="seconds per tool run (default 120)")
    p.add_argument("--check-time-limit", type=float, default=900, help="seconds per mesh-check run (default 900)")
    args = p.parse_args()
    for name in ("build_dir", "corpus", "out"):
        setattr(args, name, os.path.abspath(getattr(args, name)))
    return args


def select_models(corpus, pattern):
    with open(os.path.join(corpus, "MANIFEST.tsv"), newline="") as f:
        rows = list(csv.DictReader(f, delimiter="\t"))
    if pattern:
        return [r["file"] for r in rows if fnmatch.fnmatch(r["file"], pattern)]
    return [r["file"] for r in rows if r["closed"].strip() == "0"]


def run(cmd, limit):
    """Runs cmd under /usr/bin/time; returns status, exit code, wall s, peak MB, stdout, stderr."""
    with tempfile.NamedTemporaryFile(suffix=".time", delete=False) as t:
        time_file = t.name
    start = time.monotonic()
    proc = subprocess.Popen(["/usr/bin/time", "-f", "%M", "-o", time_file] + cmd, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, errors="replace", start_new_session=True)
    try:
        out, err = proc.communicate(timeout=limit)
        status = "ok" if proc.returncode == 0 else "error"
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        out, err = proc.communicate()
        status = "timeout"
    wall = time.monotonic() - start
    peak_mb = None
    try:
        with open(time_file) as f:
            peak_mb = int(f.read().split()[-1]) / 1024
    except (OSError, ValueError, IndexError):
        pass
    os.unlink(time_file)
    return {"status": status, "exit_code": proc.returncode if status != "timeout" else None,
            "wall_s": round(wall, 3), "peak_mb": None if peak_mb is None else round(peak_mb, 1),
            "stdout": out, "stderr": err}


def mesh_check(tools, path, limit):
    """The "surface" part of mesh-check's report, or None with the reason."""
    try:
        r = subprocess.run([tools["mesh-check"], path, "-j", "1"], capture_output=True, text=True, timeout=limit)
        return json.loads(r.stdout)["surface"], None
    except subprocess.TimeoutExpired:
        return None, "mesh-check timeout"
    except (ValueError, KeyError):
        return None, "mesh-check: " + (r.stderr.strip().splitlines() or ["exit %d" % r.returncode])[-1]


def read_obj(path):
    """Positions and triangles (as position triples) of an OBJ file; polygons are fanned."""
    positions, faces = [], []
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                x, y, z = line.split()[1:4]
                positions.append((float(x), float(y), float(z)))
            elif line.startswith("f "):
                ids = [int(c.split("/")[0]) for c in line.split()[1:]]
                ids = [i - 1 if i > 0 else len(positions) + i for i in ids]
                for k in range(1, len(ids) - 1):
                    faces.append((positions[ids[0]], positions[ids[k]], positions[ids[k + 1]]))
    return faces


def face_key(face):
    """The corners rotated so that the smallest position comes first (orientation kept)."""
    k = face.index(min(face))
    return face[k:] + face[:k]


def input_faces_changed(input_obj, output_obj):
    """How many input faces (counted with multiplicity) are not in the output."""
    counts = {}
    for face in read_obj(input_obj):
        key = face_key(face)
        counts[key] = counts.get(key, 0) + 1
    for face in read_obj(output_obj):
        key = face_key(face)
        if counts.get(key, 0) > 0:
            counts[key] -= 1
    return sum(counts.values())


class Model:
    """One corpus model: its work folder and, made once on demand, its conversions and checks."""

    def __init__(self, args, tools, file):
        self.args, self.tools, self.file = args, tools, file
        self.path = os.path.join(args.corpus, file)
        self.dir = os.path.join(args.out, "work", file.replace("/", "__"))
        os.makedirs(self.dir, exist_ok=True)
        self._converted, self._checks = {}, {}

    def converted(self, ext):
        """The model written by format-convert as IN.ext, or None when that fails."""
        if ext not in self._converted:
            path = os.path.join(self.dir, "input." + ext)
            r = subprocess.run([self.tools["format-convert"], self.path, path, "-q"], capture_output=True)
            self._converted[ext] = path if r.returncode == 0 and os.path.exists(path) else None
        return self._converted[ext]

    def check(self, path):
        if path not in self._checks:
            self._checks[path] = mesh_check(self.tools, path, self.args.check_time_limit)
        return self._checks[path]


def run_tool(model, tool, limit):
    tools, d = model.tools, model.dir
    row = {"model": model.file, "tool": tool, "time_limit": limit}
    source = model.path
    if tool == "ours":
        out, stats = os.path.join(d, "ours.obj"), os.path.join(d, "ours_stats.json")
        cmd = [tools["hole-fill"], source, out, "--stats", stats, "-j", "1"]
    elif tool == "cgal":
        out = os.path.join(d, "cgal.obj")
        cmd = [tools["hole_fill_peer_cgal"], source, out]
    else:
        out = os.path.join(d, "admesh.stl")
        source = model.converted("stl")
        if source is None:
            row.update(status="error", detail="format-convert to STL failed")
            return row
        cmd = [tools["admesh"], "--fill-holes", "--write-binary-stl=" + out, source]
    for stale in [out] + ([stats] if tool == "ours" else []):
        if os.path.exists(stale):
            os.unlink(stale)

    r = run(cmd, limit)
    row.update({k: r[k] for k in ("status", "exit_code", "wall_s", "peak_mb")})
    if r["status"] == "error":
        row["detail"] = (r["stderr"].strip().splitlines() or [""])[-1][:300]
    if tool == "ours" and os.path.exists(stats):
        with open(stats) as f:
            s = json.load(f)
        row.update(holes=s.get("holes_found"), filled=s.get("holes_filled"), failed=s.get("holes_failed"),
                   patch_faces=s.get("patch_faces"), tool_watertight=s.get("watertight"))
    if tool == "cgal" and r["status"] == "ok":
        try:
            s = json.loads(r["stdout"].strip().splitlines()[-1])
            row.update(holes=s["holes"], filled=s["filled"], fill_s=s["seconds"])
        except (ValueError, KeyError, IndexError):
            pass
    if r["status"] == "timeout" or not os.path.exists(out):
        return row

    before, why = model.check(source)
    after, why_out = model.check(out)
    row["output_written"] = True
    if before is not None:
        row.update(input_faces=before["faces"], input_boundary_edges=before["boundary_edges"],
                   input_selfint=before["self_intersecting_pairs"])
    else:
        row["check_detail"] = "input: " + why
    if after is None:
        row["check_detail"] = "output: " + why_out
        return row
    row.update(faces=after["faces"], boundary_edges=after["boundary_edges"],
               nonmanifold_edges=after["nonmanifold_edges"], nonmanifold_vertices=after["nonmanifold_vertices"],
               selfint=after["self_intersecting_pairs"], watertight=bool(after["watertight"]))
    if before is not None:
        row["selfint_added"] = after["self_intersecting_pairs"] - before["self_intersecting_pairs"]
    if tool == "ours":
        input_obj = model.converted("obj")
        if input_obj is not None:
            row["input_faces_changed"] = input_faces_changed(input_obj, out)
    return row


def fmt(v, digits=2):
    if v is None:
        return "–"
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, float):
        return f"{v:.{digits}f}"
    return str(v)


def status_text(row):
    if row["status"] == "error":
        code = row.get("exit_code")
        return "error" + (f" ({code})" if code is not None else "")
    return row["status"]


def write_report(path, rows, time_limit):
    lines = ["# Hole filling: hole-fill vs CGAL vs admesh", "",
             "Judged by mesh-check on each written file. *self-int added*: self-intersecting pairs of the "
             "output minus those of the file the tool read (admesh: the model converted to float32 STL). "
             "A run that exits non-zero but writes a file is still judged. "
             f"Time limit {time_limit:g} s a run; in the median, a timeout counts as the limit.", ""]
    by_tool = {t: [r for r in rows if r["tool"] == t] for t in TOOLS}

    lines += ["## Summary", "",
              "| tool | models | exit 0 | holes closed fully (0 boundary edges) | no self-intersection added "
              "| watertight | input faces kept | median wall s |", "|---|---|---|---|---|---|---|---|"]
    for tool, rs in by_tool.items():
        if not rs:
            continue
        walls = [r["wall_s"] if r["status"] != "timeout" else r.get("time_limit", time_limit)
                 for r in rs if r.get("wall_s") is not None]
        kept = sum(1 for r in rs if r.get("input_faces_changed") == 0) if tool == "ours" else None
        lines.append("| {} | {} | {} | {} | {} | {} | {} | {} |".format(
            tool, len(rs), sum(r["status"] == "ok" for r in rs),
            sum(r.get("boundary_edges") == 0 for r in rs),
            sum(r.get("selfint_added") is not None and r["selfint_added"] <= 0 for r in rs),
            sum(r.get("watertight") is True for r in rs),
            "–" if kept is None else kept,
            fmt(statistics.median(walls), 3) if walls else "–"))
    lines.append("")

    for tool, rs in by_tool.items():
        if not rs:
            continue
        extra = {"ours": ["holes filled/found", "input faces changed"], "cgal": ["holes faired/found"],
                 "admesh": []}[tool]
        head = ["model", "input faces", "input boundary edges", "status", "wall s", "peak MB",
                "boundary edges left", "self-int added", "watertight"] + extra
        lines += [f"## {tool}", "", "| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
        for r in sorted(rs, key=lambda r: r["model"]):
            cells = [r["model"], fmt(r.get("input_faces")), fmt(r.get("input_boundary_edges")), status_text(r),
                     fmt(r.get("wall_s"), 3), fmt(r.get("peak_mb"), 1), fmt(r.get("boundary_edges")),
                     fmt(r.get("selfint_added")), fmt(r.get("watertight"))]
            if tool in ("ours", "cgal"):
                cells.append("–" if r.get("holes") is None else f"{r.get('filled')}/{r['holes']}")
            if tool == "ours":
                cells.append(fmt(r.get("input_faces_changed")))
            lines.append("| " + " | ".join(cells) + " |")
        notes = [r for r in rs if r.get("detail") or r.get("check_detail")]
        if notes:
            lines.append("")
            for r in notes:
                lines.append(f"- {r['model']}: " + "; ".join(x for x in (r.get("detail"), r.get("check_detail")) if x))
        lines.append("")
    with open(path, "w") as f:
        f.write("\n".join(lines))


def main():
    args = parse_args()
    tools = {"hole-fill": os.path.join(args.build_dir, "tools/hole-fill/hole-fill"),
             "hole_fill_peer_cgal": os.path.join(args.build_dir, "bench/hole_fill_peer_cgal"),
             "format-convert": os.path.join(args.build_dir, "tools/format-convert/format-convert"),
             "mesh-check": os.path.join(args.build_dir, "tools/mesh-check/mesh-check"),
             "admesh": "admesh"}
    missing = [p for n, p in tools.items() if n != "admesh" and not os.access(p, os.X_OK)]
    if missing:
        sys.exit("missing (build them first): " + ", ".join(missing))
    os.makedirs(args.out, exist_ok=True)
    results = os.path.join(args.out, "results.jsonl")
    rows = []
    if os.path.exists(results):
        with open(results) as f:
            rows = [json.loads(line) for line in f if line.strip()]
    done = {(r["model"], r["tool"]) for r in rows}

    models = select_models(args.corpus, args.models)
    if not models:
        sys.exit("no model selected")
    for i, file in enumerate(models, 1):
        model = Model(args, tools, file)
        for tool in TOOLS:
            if (file, tool) in done:
                continue
            row = run_tool(model, tool, args.time_limit)
            rows.append(row)
            with open(results, "a") as f:
                f.write(json.dumps(row) + "\n")
            print(f"[{i}/{len(models)}] {file} {tool}: {status_text(row)} {fmt(row.get('wall_s'), 3)} s, "
                  f"boundary edges left {fmt(row.get('boundary_edges'))}, "
                  f"self-int added {fmt(row.get('selfint_added'))}", flush=True)
    write_report(os.path.join(args.out, "report.md"), rows, args.time_limit)
    print("wrote", os.path.join(args.out, "report.md"))


if __name__ == "__main__":
    main()
