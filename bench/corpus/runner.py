"""Running every selected tool on every model: prepare the input, run under limits, check, record."""
import datetime
import json
import os
import shutil
import sys
import threading
from concurrent.futures import FIRST_COMPLETED, ThreadPoolExecutor, wait
from dataclasses import dataclass, field

from . import check, execute
from .results import ROW_KEYS, ResultStore

OOM_PATTERNS = ("bad_alloc", "out of memory", "cannot allocate memory", "memoryerror")


@dataclass
class Context:
    task: str
    out_dir: str
    tools: list  # available tools to run, ours first
    mesh_check: str
    format_convert: str | None
    limits: execute.Limits
    check_limits: execute.Limits
    epsilon: float
    store: ResultStore
    finished: set
    total: int
    stop: threading.Event = field(default_factory=threading.Event)
    done: int = 0
    lock: threading.Lock = field(default_factory=threading.Lock)


def classify(outcome, stderr_path, memory_mb):
    """Failure kind of a finished child, or None if it exited 0."""
    if outcome.timed_out:
        return "timeout"
    if outcome.returncode == 0:
        return None
    log = execute.tail(stderr_path, 2000).lower()
    near_limit = memory_mb > 0 and outcome.peak_mb >= 0.9 * memory_mb
    if any(p in log for p in OOM_PATTERNS) or near_limit or outcome.signal == 9:
        return "oom"  # SIGKILL not sent by us on timeout: the kernel's OOM killer
    return "crash" if outcome.signal is not None else "error"


def prepare_input(ctx, tool, model, workdir):
    """(path the tool reads, note): the original, or a conversion made by format-convert (untimed)."""
    if tool.input_ext is None or os.path.splitext(model.path)[1].lower() in tool.native_exts:
        return model.path, ""
    target = os.path.join(workdir, "in" + tool.input_ext)
    note = "format-convert not built"
    if ctx.format_convert:
        outcome = execute.run_limited([ctx.format_convert, model.path, target], workdir, ctx.check_limits,
                                      os.path.join(workdir, "convert"), ctx.stop)
        if outcome.returncode == 0 and os.path.exists(target):
            return tool.final_input(target, workdir), ""
        note = "format-convert failed: " + execute.tail(outcome.stderr_path, 200)
    if model.path.lower().endswith(tool.input_ext):
        shutil.copyfile(model.path, target)  # a copy: finish_input may edit it
        return tool.final_input(target, workdir), note + "; the tool got the original file"
    return None, note


def _load_tool_stats(workdir):
    try:
        with open(os.path.join(workdir, "stats.json"), encoding="utf-8") as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def run_tool(ctx, model, tool, input_faces, reference):
    """Runs one tool on one model and returns its results row."""
    workdir = os.path.join(ctx.out_dir, "models", model.key, tool.name)
    shutil.rmtree(workdir, ignore_errors=True)
    os.makedirs(workdir)
    row = dict.fromkeys(ROW_KEYS + check.CHECK_FIELDS)
    row.update(model=model.key, file=model.relpath, tags=list(model.tags), input_faces=input_faces,
               input_bytes=model.bytes, tool=tool.name, ours=tool.ours, task=tool.task, out_format=tool.out_format,
               time_limit_s=ctx.limits.time_s, memory_limit_mb=ctx.limits.memory_mb, epsilon=ctx.epsilon)
    path, note = prepare_input(ctx, tool, model, workdir)
    if path is None:
        row.update(status="no-input", note=note)
        return _finish(row)
    outcome = execute.run_limited(tool.command(path, workdir, ctx.epsilon), workdir, ctx.limits,
                                  os.path.join(workdir, "tool"), ctx.stop)
    stderr = outcome.stderr_path
    row.update(returncode=outcome.returncode, signal=outcome.signal, wall_s=round(outcome.wall_s, 4),
               cpu_s=round(outcome.cpu_s, 4), user_s=round(outcome.user_s, 4), sys_s=round(outcome.sys_s, 4),
               peak_mb=round(outcome.peak_mb, 1), tool_stats=_load_tool_stats(workdir) if tool.ours else None)
    status = classify(outcome, stderr, ctx.limits.memory_mb)
    if status is not None:
        row.update(status=status, note=_failure_note(status, outcome, stderr, ctx.limits))
        return _finish(row)
    output = tool.output(workdir)
    if not output or os.path.getsize(output) == 0:
        row.update(status="empty", note="exit 0 but no output file" if not output else "exit 0, output file empty")
        return _finish(row)
    row.update(output=os.path.relpath(output, ctx.out_dir), output_bytes=os.path.getsize(output))
    status, why, fields = check.check_output(ctx, tool, output, reference, workdir, ctx.stop,
                                             input_closed=check.input_is_closed(model.tags))
    row.update(fields)
    row.update(status=status, note="; ".join(n for n in (why, note) if n))
    return _finish(row)


def _failure_note(status, outcome, stderr, limits):
    if status == "timeout":
        return f"killed after {limits.time_s:g} s"
    head = f"signal {outcome.signal}" if outcome.signal is not None else f"exit {outcome.returncode}"
    return f"{head}: {execute.log_summary([stderr, outcome.stdout_path])}"


def _finish(row):
    row["finished_at"] = datetime.datetime.now().isoformat(timespec="seconds")
    return row


def _input_info(ctx, model):
    """{'faces', 'readable', 'note'} of a model's input, measured once (cached in input.json)."""
    model_dir = os.path.join(ctx.out_dir, "models", model.key)
    cache = os.path.join(model_dir, "input.json")
    try:
        with open(cache, encoding="utf-8") as f:
            return json.load(f)
    except (OSError, ValueError):
        pass
    os.makedirs(model_dir, exist_ok=True)
    faces, note = check.measure_input(ctx, model, model_dir, ctx.stop)
    info = {"faces": faces, "readable": faces is not None, "note": note}
    with open(cache, "w", encoding="utf-8") as f:
        json.dump(info, f)
    return info


def run_model(ctx, model):
    pending = [t for t in ctx.tools if (model.key, t.name) not in ctx.finished]
    if not pending:
        return
    info = _input_info(ctx, model)
    faces = model.faces if model.faces is not None else info["faces"]
    reference = model.path if info["readable"] else None
    for tool in pending:
        row = run_tool(ctx, model, tool, faces, reference)
        if reference is None:
            row["note"] = "; ".join(n for n in (row.get("note"), "no distances: our readers reject the input") if n)
        ctx.store.append(row)
        _progress(ctx, row)


def _progress(ctx, row):
    with ctx.lock:
        ctx.done += 1
        wall = f"{row['wall_s']:8.2f} s" if row.get("wall_s") is not None else " " * 10
        peak = f"{row['peak_mb']:7.0f} MB" if row.get("peak_mb") is not None else " " * 10
        note = f"  {row['note'][:70]}" if row.get("note") and row["status"] != "ok" else ""
        print(f"[{ctx.done:>4}/{ctx.total}] {row['model'][:40]:<40} {row['tool']:<15} {row['status']:<9}"
              f"{wall} {peak}{note}", flush=True)


def run_all(ctx, models, jobs):
    """Runs the models, `jobs` at a time; largest first so that parallel jobs finish together."""
    order = sorted(models, key=lambda m: -m.bytes)
    with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        futures = {pool.submit(run_model, ctx, m): m for m in order}
        try:
            pending = set(futures)
            while pending:
                finished, pending = wait(pending, timeout=0.5, return_when=FIRST_COMPLETED)
                for f in finished:
                    _report_exception(f, futures[f])
        except KeyboardInterrupt:
            ctx.stop.set()
            for f in futures:
                f.cancel()
            print("interrupted: finished pairs are in results.jsonl; run the same command to continue",
                  file=sys.stderr)
            raise


def _report_exception(future, model):
    error = future.exception()
    if error is not None and not isinstance(error, execute.Interrupted):
        print(f"error: runner failed on {model.relpath}: {error!r}", file=sys.stderr)
