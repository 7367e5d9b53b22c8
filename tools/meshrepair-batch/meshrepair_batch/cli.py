"""Options and main(): meshrepair-batch IN OUT_DIR [options] [-- TOOL OPTIONS]."""
import argparse
import os
import signal
import sys
import time

from . import inputs, progress, store

TOOLS = ("meshrepair", "tetrahedralize", "simplify-in-envelope", "hole-fill")
EXIT_OK, EXIT_SOME_FAILED, EXIT_USAGE = 0, 1, 2

DESCRIPTION = """Run one of the toolkit's tools over many models on Dask.

IN is a folder (searched recursively for mesh files), a glob (quote it) or a list file (one path a
line, relative to the list's folder; # comments). Each model runs as its own process of the tool,
under a time and a memory limit, writing OUT_DIR/<its path relative to IN, new extension>. One JSON
line per model goes to OUT_DIR/results.jsonl as it finishes, and a summary to OUT_DIR/summary.json.
Run the same command again to resume: models with a result are skipped (with --retry-failed, only
those that succeeded). Options after -- go to the tool.
Exit: 0 if every model succeeded, 1 if some failed, 2 on bad usage or input."""


def build_parser(default_tools_dir):
    p = argparse.ArgumentParser(prog="meshrepair-batch", description=DESCRIPTION,
                                formatter_class=argparse.RawDescriptionHelpFormatter,
                                usage="%(prog)s IN OUT_DIR [options] [-- TOOL OPTIONS]")
    p.add_argument("input", metavar="IN", help="folder, glob or list file of models")
    p.add_argument("out_dir", metavar="OUT_DIR", help="where outputs, results.jsonl and summary.json go")
    p.add_argument("--tool", choices=TOOLS, default="meshrepair", help="tool to run (default meshrepair)")
    p.add_argument("--to", metavar="EXT", help="output format/extension (default: the input's for surface "
                   "tools, msh for tetrahedralize)")
    p.add_argument("--tool-path", metavar="PATH", help="the tool's executable (default: TOOLS_DIR/TOOL/TOOL)")
    p.add_argument("--tools-dir", metavar="DIR", default=default_tools_dir,
                   help="build folder of the tools (default: %(default)s)")
    engine = p.add_argument_group("engine")
    engine.add_argument("--scheduler", metavar="ADDR", help="use this Dask scheduler (tcp://host:8786) instead "
                        "of a local cluster; workers must see the same paths")
    engine.add_argument("--scheduler-file", metavar="FILE", help="use the Dask scheduler this file describes")
    engine.add_argument("--workers", type=int, metavar="N", default=os.cpu_count() or 1,
                        help="local cluster: worker processes (default: one per core, %(default)s)")
    engine.add_argument("--tool-threads", type=int, metavar="N", default=1,
                        help="threads per tool run, passed as -j N (default 1: one model per core)")
    limits = p.add_argument_group("limits")
    limits.add_argument("--time-limit", type=float, metavar="S", default=600.0,
                        help="wall seconds per model; killed after (default %(default)g; 0: none)")
    limits.add_argument("--memory-limit", type=int, metavar="MB", default=8192,
                        help="address space per model run, MB (default %(default)s; 0: none)")
    p.add_argument("--retry-failed", action="store_true", help="run again models whose result is not ok")
    p.add_argument("--check", action="store_true", help="also run mesh-check on each output; a failed check "
                   "makes the status 'invalid'")
    p.add_argument("--mesh-check", metavar="PATH", help="mesh-check executable (default: TOOLS_DIR/mesh-check/mesh-check)")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress line and no summary on stderr")
    return p


def split_tool_options(argv):
    """(batch argv, tool options): everything after the first -- goes to the tool."""
    if "--" in argv:
        i = argv.index("--")
        return argv[:i], argv[i + 1:]
    return argv, []


def tool_command(tool_path, model, opts, tool_options, stats_path):
    """The tool's argv for one model."""
    command = [tool_path, model.path, model.output] + list(tool_options) + ["--stats", stats_path]
    if not any(o in ("-j", "--threads") or o.startswith("--threads=") for o in tool_options):
        command += ["-j", str(opts.tool_threads)]
    return command


def make_task(model, opts, tool_path, tool_options, check_path):
    """Everything a worker needs to run one model (plain data: it is sent to the worker)."""
    logs = os.path.join(os.path.abspath(opts.out_dir), "logs", *model.key.split("/"))
    stats = logs + ".stats.json"
    check = None
    if check_path:
        check = [check_path, model.output, "-q", "-j", str(opts.tool_threads)]
    return {"input": model.path, "key": model.key, "input_bytes": model.size, "tool": opts.tool,
            "output": model.output, "stats": stats, "stdout_log": logs + ".stdout.txt",
            "stderr_log": logs + ".stderr.txt", "time_limit_s": opts.time_limit, "memory_limit_mb": opts.memory_limit,
            "command": tool_command(tool_path, model, opts, tool_options, stats), "check_command": check}


def resolve_executable(explicit, tools_dir, name):
    """Absolute path of a tool; UsageError when it is not an executable file."""
    path = os.path.abspath(explicit or os.path.join(tools_dir, name, name))
    if not (os.path.isfile(path) and os.access(path, os.X_OK)):
        hint = "" if explicit else " (build it, or pass --tools-dir or --tool-path)"
        raise inputs.InputError(f"{name}: no executable at {path}{hint}")
    return path


def validate(opts):
    """InputError on option values that cannot work."""
    if opts.workers < 1:
        raise inputs.InputError("--workers must be at least 1")
    if opts.tool_threads < 1:
        raise inputs.InputError("--tool-threads must be at least 1")
    if opts.time_limit < 0 or opts.memory_limit < 0:
        raise inputs.InputError("--time-limit and --memory-limit must be >= 0")
    if opts.scheduler and opts.scheduler_file:
        raise inputs.InputError("give --scheduler or --scheduler-file, not both")
    if opts.scheduler_file and not os.path.isfile(opts.scheduler_file):
        raise inputs.InputError(f"--scheduler-file {opts.scheduler_file}: no such file")
    if os.path.exists(opts.out_dir) and not os.path.isdir(opts.out_dir):
        raise inputs.InputError(f"OUT_DIR {opts.out_dir} exists and is not a folder")
    opts.to = inputs.check_extension(opts.tool, opts.to)


def prepare(argv, default_tools_dir):
    """(opts, models, tasks to run, store): parses, finds the models and what is left to do."""
    batch_argv, tool_options = split_tool_options(argv)
    opts = build_parser(default_tools_dir).parse_args(batch_argv)
    validate(opts)
    tool_path = resolve_executable(opts.tool_path, opts.tools_dir, opts.tool)
    check_path = resolve_executable(opts.mesh_check, opts.tools_dir, "mesh-check") if opts.check else None
    models = inputs.plan_outputs(inputs.discover(opts.input, opts.out_dir), opts.out_dir, opts.tool, opts.to)
    try:
        results = store.ResultStore(opts.out_dir)
    except store.Busy as e:
        raise inputs.InputError(str(e)) from e
    tasks = [make_task(m, opts, tool_path, tool_options, check_path) for m in models
             if not results.should_skip((m.path, opts.tool), opts.retry_failed)]
    return opts, models, tasks, results


def main(argv=None, default_tools_dir="build/tools"):
    """Runs the batch; returns the exit code."""
    argv = sys.argv[1:] if argv is None else argv
    try:
        opts, models, tasks, results = prepare(argv, default_tools_dir)
    except inputs.InputError as e:
        print(f"meshrepair-batch: error: {e}", file=sys.stderr)
        return EXIT_USAGE
    signal.signal(signal.SIGTERM, _terminate)
    start = time.monotonic()
    run_rows, workers = [], None
    bar = progress.Progress(len(tasks), len(models) - len(tasks), enabled=not opts.quiet and bool(tasks))
    try:
        if tasks:
            workers = _run(opts, tasks, results, bar, run_rows)
    except KeyboardInterrupt:
        print(f"\nmeshrepair-batch: interrupted; {len(run_rows)} new results kept in {results.path}; "
              "run the same command to resume", file=sys.stderr)
        return 130
    finally:
        results.close()
    rows = [results.latest[(m.path, opts.tool)] for m in models if (m.path, opts.tool) in results.latest]
    summary = store.summarize(rows, run_rows, len(models) - len(tasks), time.monotonic() - start, workers)
    summary.update(tool=opts.tool, input=opts.input, out_dir=os.path.abspath(opts.out_dir))
    store.write_summary(opts.out_dir, summary)
    if not opts.quiet:
        print(store.format_summary(summary), file=sys.stderr)
    return EXIT_OK if summary["ok"] == len(models) else EXIT_SOME_FAILED


def _run(opts, tasks, results, bar, run_rows):
    """Starts or joins the Dask cluster and stores each result as it arrives (also in run_rows);
    returns the number of workers."""
    from . import engine

    def on_result(row):
        results.append(row)
        run_rows.append(row)
        bar.update(row)

    client, close = engine.open_client(opts.scheduler, opts.scheduler_file, opts.workers)
    try:
        workers = engine.worker_count(client)
        if not opts.quiet:
            where = opts.scheduler or opts.scheduler_file or "a local cluster"
            print(f"meshrepair-batch: {len(tasks)} models to run with {opts.tool} on {where} "
                  f"({workers} worker{'' if workers == 1 else 's'})", file=sys.stderr)
            if workers == 0:
                print("meshrepair-batch: the scheduler has no workers yet; tasks wait until one joins",
                      file=sys.stderr)
        with bar:
            engine.run_tasks(client, tasks, on_result)
    finally:
        close()
    return workers


def _terminate(signum, frame):
    raise KeyboardInterrupt()
