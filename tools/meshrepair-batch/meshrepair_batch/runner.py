"""Running one model: the tool as a child process under a time and memory limit, measured.

This module runs on Dask workers, which may be processes started by hand on other machines: it
imports only the standard library, and the engine ships it to workers by value (cloudpickle), so a
worker needs no copy of this package, only the tool binaries and the files at the same paths.

Launch chain: `prlimit --as=BYTES -- /usr/bin/time -o FILE -f FMT -- TOOL IN OUT ... --stats S -j N`
in a new session (its own process group):
- prlimit sets RLIMIT_AS right before exec: safe in a threaded worker, unlike preexec_fn (used only
  when prlimit is missing);
- GNU time reports the tool's own peak RSS. Measured from the worker, ru_maxrss would include the
  worker's RSS, which Linux carries over into a forked child's high-water mark;
- the time limit is a timer here: it kills the tool (then the whole group) with SIGKILL;
- `timeout --foreground -s KILL LIMIT+30` right before the tool is a backstop: a tool whose batch or
  worker was killed (SIGKILL, Ctrl-C closing the local cluster) still ends at its time limit
  instead of running on as an orphan.
"""
import datetime
import json
import os
import re
import resource
import shutil
import signal
import socket
import subprocess
import threading
import time

GNU_TIME = "/usr/bin/time"
TIME_FORMAT = "%e %U %S %M %x"
GRACE_S = 5.0  # after killing the tool on timeout, time for GNU time to report and exit
BACKSTOP_S = 30.0  # coreutils timeout kills the tool this long after the limit if nobody else did
STDERR_TAIL_LINES = 8
STDERR_TAIL_CHARS = 1500
MEMORY_PATTERNS = ("bad_alloc", "out of memory", "cannot allocate memory", "memoryerror")


def run_model(task):
    """Runs task's tool on one model and returns its result row (a JSON-able dict). Never raises
    for the tool's own failures: a crash, a timeout or a missing binary are statuses."""
    started = _now()
    for path in (task["output"], task["stats"], task["stderr_log"]):
        os.makedirs(os.path.dirname(path), exist_ok=True)
    _remove(task["stats"])
    outcome = run_limited(task["command"], task["time_limit_s"], task["memory_limit_mb"],
                          task["stdout_log"], task["stderr_log"])
    status = classify(outcome, task)
    row = {
        "input": task["input"], "key": task["key"], "tool": task["tool"], "output": task["output"],
        "status": status, "exit_code": outcome["returncode"], "signal": outcome["signal"],
        "wall_s": round(outcome["wall_s"], 3), "cpu_s": round(outcome["cpu_s"], 3),
        "peak_rss_mb": None if outcome["peak_mb"] is None else round(outcome["peak_mb"], 1),
        "time_limit_s": task["time_limit_s"], "memory_limit_mb": task["memory_limit_mb"],
        "stats": _load_json(task["stats"]), "stderr_tail": tail(task["stderr_log"]),
        "command": task["command"], "started_at": started,
    }
    if status == "ok" and task.get("check_command"):
        row.update(check_output(task))
        if row["check"] != "passed":
            row["status"] = "invalid"
    row.update(where_am_i())
    row["finished_at"] = _now()
    return row


def classify(outcome, task):
    """ok, failed, timeout, memory or crashed, from how the child ended and what it left."""
    if outcome["timed_out"]:
        return "timeout"
    if outcome["returncode"] == 0:
        output = task["output"]
        return "ok" if os.path.isfile(output) and os.path.getsize(output) > 0 else "failed"
    log = tail(task["stderr_log"], lines=40, chars=4000).lower()
    limit = task["memory_limit_mb"]
    near_limit = limit > 0 and outcome["peak_mb"] is not None and outcome["peak_mb"] >= 0.9 * limit
    if any(p in log for p in MEMORY_PATTERNS) or near_limit or outcome["signal"] == signal.SIGKILL:
        return "memory"  # a SIGKILL we did not send: the kernel's OOM killer
    if outcome["signal"] is not None:
        return "crashed"
    return "failed"


def run_limited(command, time_limit_s, memory_mb, stdout_path, stderr_path):
    """Runs command to completion or timeout; returns returncode, signal, timed_out, wall_s, cpu_s,
    peak_mb (None when unknown)."""
    rusage_path = stderr_path + ".rusage"
    _remove(rusage_path)
    argv, preexec = wrap(command, time_limit_s, memory_mb, rusage_path)
    with open(stdout_path, "wb") as out, open(stderr_path, "wb") as err:
        start = time.monotonic()
        try:
            proc = subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=out, stderr=err,
                                    start_new_session=True, preexec_fn=preexec)
        except OSError as e:
            err.write(f"cannot start {command[0]}: {e}\n".encode())
            return dict(returncode=127, signal=None, timed_out=False, wall_s=0.0, cpu_s=0.0, peak_mb=None)
        timed_out = threading.Event()
        timer = threading.Timer(time_limit_s, _on_timeout, (proc.pid, timed_out)) if time_limit_s > 0 else None
        if timer:
            timer.daemon = True
            timer.start()
        _, status, usage = os.wait4(proc.pid, 0)
        wall = time.monotonic() - start
        if timer:
            timer.cancel()
        proc.returncode = status  # reaped here: keep Popen from waiting again
        kill_group(proc.pid)  # stragglers the tool left behind
    sig = os.WTERMSIG(status) if os.WIFSIGNALED(status) else None
    code = os.WEXITSTATUS(status) if os.WIFEXITED(status) else None
    peak = None if GNU_TIME in argv else usage.ru_maxrss / 1024.0  # see the module docstring
    reported = read_gnu_time(rusage_path)
    if reported:
        code, sig, peak = reported
    _remove(rusage_path)
    return dict(returncode=code, signal=sig, timed_out=timed_out.is_set(), wall_s=wall,
                cpu_s=usage.ru_utime + usage.ru_stime, peak_mb=peak)


def wrap(command, time_limit_s, memory_mb, rusage_path):
    """(argv, preexec_fn): command behind timeout, GNU time and prlimit when they exist."""
    argv = list(command)
    backstop = shutil.which("timeout")
    if time_limit_s > 0 and backstop:
        argv = [backstop, "--foreground", "-s", "KILL", f"{time_limit_s + BACKSTOP_S:g}"] + argv
    if os.access(GNU_TIME, os.X_OK):
        argv = [GNU_TIME, "-o", rusage_path, "-f", TIME_FORMAT, "--"] + argv
    if memory_mb <= 0:
        return argv, None
    limit = memory_mb * 1024 * 1024
    prlimit = shutil.which("prlimit")
    if prlimit:
        return [prlimit, f"--as={limit}", "--"] + argv, None
    return argv, lambda: resource.setrlimit(resource.RLIMIT_AS, (limit, limit))


def _on_timeout(pid, flag):
    """Kills the tool first, the innermost process of the chain: timeout (if any) reaps it and dies
    of the same signal, and GNU time still reports the tool's usage. Then the whole group."""
    flag.set()
    leaves = [p for p in _descendants(pid) if not _children(p)]
    for leaf in leaves:
        kill_pid(leaf)
    deadline = time.monotonic() + (GRACE_S if leaves else 0.0)
    while time.monotonic() < deadline and _alive(pid):
        time.sleep(0.05)
    kill_group(pid)


def _descendants(pid):
    """Pids below pid in the process tree (from /proc)."""
    found, todo = [], [pid]
    while todo:
        children = _children(todo.pop())
        found += children
        todo += children
    return found


def _children(pid):
    """Pids of pid's children (from /proc), or [] when the kernel does not list them."""
    try:
        with open(f"/proc/{pid}/task/{pid}/children", encoding="ascii") as f:
            return [int(p) for p in f.read().split()]
    except (OSError, ValueError):
        return []


def _alive(pid):
    try:
        with open(f"/proc/{pid}/stat", encoding="ascii", errors="replace") as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except (OSError, IndexError):
        return False


def kill_pid(pid):
    """SIGKILL to one process, if it still exists (shared with bench/corpus/execute.py)."""
    try:
        os.kill(pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass


def kill_group(pgid):
    """SIGKILL to a process group, if it still exists (shared with bench/corpus/execute.py)."""
    try:
        os.killpg(pgid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass


def read_gnu_time(path):
    """(returncode, signal, peak_mb) of the tool as GNU time saw it, or None."""
    try:
        with open(path, encoding="utf-8", errors="replace") as f:
            text = f.read()
    except OSError:
        return None
    numbers = re.search(r"^([\d.]+) ([\d.]+) ([\d.]+) (\d+) (\d+)\s*$", text, re.M)
    if not numbers:
        return None
    killed = re.search(r"terminated by signal (\d+)", text)
    sig = int(killed.group(1)) if killed else None
    return (None if sig else int(numbers.group(5))), sig, int(numbers.group(4)) / 1024.0


def check_output(task):
    """check (passed, failed or error) and check_report from mesh-check on the written output."""
    report_path = task["stats"] + ".check.json"
    _remove(report_path)
    command = task["check_command"] + ["--json", report_path]
    try:
        done = subprocess.run(command, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                              stderr=subprocess.PIPE, timeout=max(task["time_limit_s"], 60), check=False)
        verdict = {0: "passed", 1: "failed"}.get(done.returncode, "error")
    except (OSError, subprocess.TimeoutExpired) as e:
        verdict = f"error: {e}"
    return {"check": verdict, "check_report": _load_json(report_path)}


def where_am_i():
    """The Dask worker's address (None outside a worker), host name and worker pid."""
    address = None
    try:
        from distributed import get_worker  # present on every Dask worker
        address = get_worker().address
    except (ImportError, ValueError):
        pass
    return {"worker": address, "host": socket.gethostname(), "worker_pid": os.getpid()}


def tail(path, lines=STDERR_TAIL_LINES, chars=STDERR_TAIL_CHARS):
    """The last lines of a log, joined with newlines, at most chars long."""
    try:
        with open(path, "rb") as f:
            f.seek(max(0, os.path.getsize(path) - 4 * chars))
            text = f.read().decode("utf-8", "replace")
    except OSError:
        return ""
    kept = [ln.rstrip() for ln in text.splitlines() if ln.strip()]
    return "\n".join(kept[-lines:])[-chars:]


def _load_json(path):
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def _remove(path):
    try:
        os.remove(path)
    except FileNotFoundError:
        pass


def _now():
    return datetime.datetime.now().astimezone().isoformat(timespec="seconds")
