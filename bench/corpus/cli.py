"""Command line of bench/run_corpus.py."""
import argparse
import datetime
import json
import os
import shlex
import sys

from . import baseline, execute, machine, models, runner, tools
from . import report as report_mod
from .results import STATUSES, ResultStore, read_rows

BENCH_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
REPO_DIR = os.path.dirname(BENCH_DIR)
DEFAULT_CORPUS = os.path.normpath(os.path.join(REPO_DIR, "..", "shared", "corpus"))
DEFAULT_TIME_LIMIT = {"tetrahedralize": 600.0, "meshrepair": 300.0, "simplify-in-envelope": 600.0}


def parse_args(argv):
    p = argparse.ArgumentParser(
        prog="run_corpus.py",
        description="Run one of our tools and its peers over every model of a corpus folder, check every "
                    "output with mesh-check, and write results.jsonl, report.md and PNG plots. "
                    "Re-running the same command continues an interrupted run.")
    p.add_argument("--tool", choices=tools.TASKS, help="our tool to measure (its peers run on the same models)")
    p.add_argument("--corpus",
                   help="folder of models; MANIFEST.tsv if present, else every mesh file under it "
                        "(default: ../shared/corpus next to the repository)")
    p.add_argument("--out", help="output folder (default: bench/results/TOOL)")
    p.add_argument("--out-format", metavar="FMT[,FMT...]",
                   help="meshrepair: the format(s) our tool writes, each checked on the written file: "
                        f"{', '.join(tools.OUT_FORMATS)}, a comma list, or all ({','.join(tools.ALL_OUT_FORMATS)}); "
                        "one results row per format (tool meshrepair.FMT). Default glb. Peers write what they "
                        "always write")
    p.add_argument("--peers", help="comma-separated peers, or 'none' (default: tetrahedralize: tetgen,gmsh; "
                                   "meshrepair: admesh,meshlab; simplify-in-envelope: none). tetrahedralize "
                                   "also knows ftetwild (not by default: no Debian package; FloatTetwild_bin "
                                   "on PATH or --tool-path ftetwild=PATH)")
    p.add_argument("--no-ours", action="store_true", help="run the peers only")
    p.add_argument("--models", action="append", default=[], metavar="GLOB",
                   help="only models whose relative path or key matches (repeatable), e.g. 'thingi10k/*'")
    p.add_argument("-j", "--jobs", type=int, default=1, help="models in parallel (default 1)")
    p.add_argument("--time-limit", type=float, help="wall seconds per model and tool (default 600; meshrepair 300)")
    p.add_argument("--memory-limit", type=int, default=8192, help="MB of address space per tool run (default 8192)")
    p.add_argument("--check-time-limit", type=float, default=600.0, help="seconds for one mesh-check (default 600)")
    p.add_argument("-e", "--epsilon", type=float, default=1e-3, help="envelope, relative to the bbox diagonal")
    p.add_argument("--build-dir", default=os.environ.get("MR_BUILD_DIR", os.path.join(REPO_DIR, "build")),
                   help="CMake build folder with our tools (default: $MR_BUILD_DIR or build/)")
    p.add_argument("--tool-path", action="append", default=[], metavar="NAME=PATH",
                   help="use this executable for a tool or helper (e.g. tetgen=/opt/tetgen, mesh-check=...)")
    p.add_argument("--retry", default="", help="comma-separated statuses to run again, e.g. timeout,oom")
    p.add_argument("--report-only", action="store_true", help="rebuild report.md and plots from results.jsonl")
    args = p.parse_args(argv)
    if not args.tool and not args.report_only:
        p.error("--tool is required (unless --report-only)")
    bad = set(filter(None, args.retry.split(","))) - set(STATUSES)
    if bad:
        p.error(f"--retry: unknown status {', '.join(sorted(bad))}; known: {', '.join(STATUSES)}")
    try:
        args.out_formats = tools.parse_out_formats(args.out_format, args.tool) if args.tool else []
    except ValueError as e:
        p.error(str(e))
    _make_paths_absolute(args)
    return args


def _make_paths_absolute(args):
    """Every path argument made absolute against the current folder, before anything changes folder:
    the tools and mesh-check run inside their work folders."""
    args.build_dir = os.path.abspath(os.path.expanduser(args.build_dir))
    for name in ("out", "corpus"):
        value = getattr(args, name)
        if value:
            setattr(args, name, os.path.abspath(os.path.expanduser(value)))
    args.tool_path = [_absolute_override(pair) for pair in args.tool_path]


def _absolute_override(pair):
    name, sep, path = pair.partition("=")
    if not sep or not name or not path:
        raise SystemExit(f"--tool-path expects NAME=PATH, got {pair!r}")
    return f"{name}={os.path.abspath(os.path.expanduser(path))}"


def _overrides(pairs):
    """{name: absolute path} from NAME=PATH pairs (already absolute after parse_args)."""
    return dict(pair.partition("=")[::2] for pair in pairs)


def _select_tools(args, overrides):
    known = tools.all_tools()
    peers = tools.DEFAULT_PEERS[args.tool] if args.peers is None else [
        p for p in args.peers.split(",") if p and p != "none"]
    unknown = [p for p in peers if p not in known or known[p].ours]
    if unknown:
        raise SystemExit(f"unknown peer(s): {', '.join(unknown)}; known: "
                         f"{', '.join(n for n, t in known.items() if not t.ours)}")
    ours = [] if args.no_ours else _our_variants(known[args.tool], args.out_formats)
    selected = [tools.locate(t, args.build_dir, overrides) for t in ours + [known[n] for n in peers]]
    for t in selected:
        t.version = machine.package_version(t.name) if t.available and not t.ours else ""
    return selected


def _our_variants(tool, formats):
    """Our tool once per requested output format (or as it is when it has one fixed output)."""
    return [tools.with_out_format(tool, f) for f in formats] if formats else [tool]


def _tool_meta(t):
    return {"ours": t.ours, "task": t.task, "executable": t.executable, "unavailable": t.unavailable,
            "fair_config": t.fair_config, "version": t.version, "out_format": t.out_format}


def _load_meta(out_dir):
    try:
        with open(os.path.join(out_dir, "run.json"), encoding="utf-8") as f:
            return json.load(f)
    except (OSError, ValueError):
        return {}


def _save_meta(out_dir, meta):
    tmp = os.path.join(out_dir, "run.json.tmp")
    with open(tmp, "w", encoding="utf-8") as f:
        json.dump(meta, f, indent=2)
    os.replace(tmp, os.path.join(out_dir, "run.json"))


def _record_run(out_dir, args, argv, selected, corpus):
    meta = _load_meta(out_dir)
    if meta.get("task") not in (None, args.tool):
        raise SystemExit(f"{out_dir} holds a {meta['task']} run; choose another --out for {args.tool}")
    meta.update(task=args.tool, corpus=corpus)
    meta.setdefault("tools", {}).update({t.name: _tool_meta(t) for t in selected})
    order = meta.get("tool_order", [])
    meta["tool_order"] = order + [t.name for t in selected if t.name not in order]
    meta.setdefault("runs", []).append({
        "command": " ".join(shlex.quote(a) for a in [sys.argv[0]] + list(argv)),
        "cwd": os.getcwd(), "started": datetime.datetime.now().isoformat(timespec="seconds"),
        "machine": machine.describe(), "time_limit_s": args.time_limit, "memory_limit_mb": args.memory_limit,
        "check_time_limit_s": args.check_time_limit, "epsilon": args.epsilon, "jobs": args.jobs})
    _save_meta(out_dir, meta)
    return meta


def build_report(out_dir, corpus_override=None):
    meta = _load_meta(out_dir)
    rows = read_rows(os.path.join(out_dir, "results.jsonl"))
    if not meta and not rows:
        raise SystemExit(f"{out_dir} has no run.json nor results.jsonl")
    corpus = corpus_override or meta.get("corpus")
    ref = baseline.load(corpus, meta.get("task"))
    last = (meta.get("runs") or [{}])[-1]
    plot_names = []
    try:
        from . import plots  # needs matplotlib and numpy
        order = meta.get("tool_order") or sorted({r["tool"] for r in rows})
        plot_names = plots.make_all(rows, order, out_dir, last.get("time_limit_s") or 600,
                                    meta.get("task") == "tetrahedralize")
    except ImportError as e:
        print(f"warning: no plots ({e}); install python3-matplotlib", file=sys.stderr)
    return report_mod.write(out_dir, meta, rows, ref, plot_names)


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    args = parse_args(argv)
    out_dir = args.out or os.path.join(BENCH_DIR, "results", args.tool or "")
    if args.report_only:
        print(build_report(out_dir, args.corpus))
        return 0
    args.time_limit = args.time_limit or DEFAULT_TIME_LIMIT[args.tool]
    overrides = _overrides(args.tool_path)
    mesh_check = tools.helper(args.build_dir, "mesh-check", overrides)
    if not mesh_check:
        where = (f"no executable at {overrides['mesh-check']}" if "mesh-check" in overrides
                 else f"mesh-check is not built in {args.build_dir}")
        raise SystemExit(f"{where} (every output is checked with it): build it (ninja -C BUILD mesh-check) "
                         "or pass --build-dir / --tool-path mesh-check=PATH")
    corpus = args.corpus or DEFAULT_CORPUS
    chosen = models.select(models.discover(corpus), args.models)
    if not chosen:
        raise SystemExit(f"no models in {corpus}" + (f" matching {args.models}" if args.models else ""))
    os.makedirs(out_dir, exist_ok=True)
    selected = _select_tools(args, overrides)
    _record_run(out_dir, args, argv, selected, corpus)
    for t in selected:
        if not t.available:
            print(f"{t.name}: not available ({t.unavailable}); the others still run", flush=True)
    store = ResultStore(os.path.join(out_dir, "results.jsonl"))
    runnable = [t for t in selected if t.available]
    finished = store.finished(tuple(filter(None, args.retry.split(","))))
    total = sum((m.key, t.name) not in finished for m in chosen for t in runnable)
    print(f"{len(chosen)} models x {len(runnable)} tools: {total} runs to do, "
          f"{len(chosen) * len(runnable) - total} already in {store.path}", flush=True)
    ctx = runner.Context(task=args.tool, out_dir=out_dir, tools=runnable, mesh_check=mesh_check,
                         format_convert=tools.helper(args.build_dir, "format-convert", overrides),
                         limits=execute.Limits(args.time_limit, args.memory_limit),
                         check_limits=execute.Limits(args.check_time_limit, args.memory_limit),
                         epsilon=args.epsilon, store=store, finished=finished, total=total)
    try:
        runner.run_all(ctx, chosen, args.jobs)
    except KeyboardInterrupt:
        return 130
    print(build_report(out_dir))
    return 0
