"""Running one child process under a time and memory limit, measuring its own resource use.

The child runs in a new session (its own process group) so that a timeout kills it and everything
it started. Launch chain: `prlimit --as=BYTES -- /usr/bin/time -o FILE -- TOOL ...`:
- prlimit sets RLIMIT_AS right before its exec (thread-safe, unlike preexec_fn);
- GNU time forks the tool from a ~2 MB process and reports the tool's own peak RSS. Measured from
  here, ru_maxrss would include this Python process's RSS, which the kernel carries over into a
  forked child's high-water mark.
Wall time is measured here; CPU time (user + sys) comes from os.wait4's rusage (which includes the
reaped tool), peak memory from GNU time's %M (or from wait4 when GNU time is missing).
"""
import os
import pathlib
import re
import shutil
import signal
import sys
import threading
import time
import subprocess
from dataclasses import dataclass

# One reading of GNU time's report and one way to kill, shared with meshrepair-batch (its runner imports only the
# standard library).
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "tools" / "meshrepair-batch"))
from meshrepair_batch.runner import TIME_FORMAT, kill_group, kill_pid, read_gnu_time  # noqa: E402

GNU_TIME = "/usr/bin/time" if os.access("/usr/bin/time", os.X_OK) else None
GRACE_S = 5.0  # after killing the tool on timeout, time for GNU time to report and exit


class Interrupted(Exception):
    """The run was asked to stop (Ctrl-C, SIGTERM) while a child was running."""


@dataclass
class Limits:
    time_s: float
    memory_mb: int


@dataclass
class Outcome:
    returncode: int | None  # None when killed by a signal
    signal: int | None
    timed_out: bool
    wall_s: float
    user_s: float
    sys_s: float
    peak_mb: float
    stdout_path: str = ""
    stderr_path: str = ""

    @property
    def cpu_s(self):
        return self.user_s + self.sys_s


def _wrap(command, limits, rusage_path):
    wrapped = list(command)
    if GNU_TIME:
        wrapped = [GNU_TIME, "-o", rusage_path, "-f", TIME_FORMAT, "--"] + wrapped
    if limits.memory_mb > 0 and shutil.which("prlimit"):
        wrapped = [shutil.which("prlimit"), f"--as={limits.memory_mb * 1024 * 1024}", "--"] + wrapped
    return wrapped


def _group_members(pgid, except_pid):
    """Pids of the process group other than except_pid (from /proc)."""
    members = []
    for entry in os.listdir("/proc"):
        if not entry.isdigit() or int(entry) == except_pid:
            continue
        try:
            with open(f"/proc/{entry}/stat", encoding="utf-8", errors="replace") as f:
                fields = f.read().rsplit(")", 1)[1].split()
        except (OSError, IndexError):
            continue
        if len(fields) > 2 and int(fields[2]) == pgid:
            members.append(int(entry))
    return members


def _wait(pid, deadline, stop):
    """(pid, status, rusage) once the child exits, or None at the deadline or on stop."""
    pause = 0.002
    while True:
        result = os.wait4(pid, os.WNOHANG)
        if result[0]:
            return result
        if stop.is_set() or time.monotonic() > deadline:
            return None
        time.sleep(pause)
        pause = min(pause * 1.5, 0.05)


def run_limited(command, cwd, limits, log_base, stop=None, env=None):
    """Runs command to completion, timeout or stop, logging to log_base.{stdout,stderr}.txt.

    Never raises for the child's own failures; raises Interrupted when stop is set."""
    stop = stop or threading.Event()
    env = dict(os.environ if env is None else env)
    env.setdefault("OMP_NUM_THREADS", "1")
    out_path, err_path, rusage_path = (f"{log_base}.{s}.txt" for s in ("stdout", "stderr", "rusage"))
    with open(out_path, "wb") as out, open(err_path, "wb") as err:
        start = time.monotonic()
        try:
            proc = subprocess.Popen(_wrap(command, limits, rusage_path), cwd=cwd, stdin=subprocess.DEVNULL,
                                    stdout=out, stderr=err, env=env, start_new_session=True)
        except OSError as e:
            err.write(f"cannot start {command[0]}: {e}\n".encode())
            return Outcome(127, None, False, 0.0, 0.0, 0.0, 0.0, out_path, err_path)
        result = _wait(proc.pid, start + limits.time_s, stop)
        timed_out = result is None and not stop.is_set()
        wall = time.monotonic() - start
        if result is None:
            # Kill the tool first so that GNU time still reports its usage, then everything.
            for pid in _group_members(proc.pid, proc.pid) if GNU_TIME else [proc.pid]:
                kill_pid(pid)
            result = _wait(proc.pid, time.monotonic() + GRACE_S, threading.Event())
            if result is None:
                kill_group(proc.pid)
                result = os.wait4(proc.pid, 0)
        _, status, usage = result
        proc.returncode = status  # reaped here: keep Popen from waiting again
        kill_group(proc.pid)  # stragglers the tool left behind
    if stop.is_set():
        raise Interrupted()
    sig = os.WTERMSIG(status) if os.WIFSIGNALED(status) else None
    code = os.WEXITSTATUS(status) if os.WIFEXITED(status) else None
    peak = usage.ru_maxrss / 1024.0
    reported = read_gnu_time(rusage_path) if GNU_TIME else None
    if reported:
        code, sig, peak = reported
    return Outcome(code, sig, timed_out, wall, usage.ru_utime, usage.ru_stime, peak, out_path, err_path)


NOISE = re.compile(r"error summary|\d+ (errors?|warnings?)\s*$|check the full log|^[\s:\-A-Za-z]*-{5,}\s*$", re.I)
TELLING = re.compile(r"error|abort|terminate|exception|assert|fault|fail|cannot|invalid|killed", re.I)


def log_summary(paths, max_chars=300):
    """The first telling lines of the logs (errors, aborts), else the end of the first non-empty one."""
    found = []
    for path in paths:
        try:
            with open(path, "rb") as f:
                text = f.read(1 << 20).decode("utf-8", "replace")
        except OSError:
            continue
        found += [ln.strip() for ln in text.splitlines() if TELLING.search(ln) and not NOISE.search(ln)]
    if found:
        return " | ".join(dict.fromkeys(found[:3]))[:max_chars]
    return next((t for t in (tail(p, max_chars) for p in paths) if t), "")


def tail(path, max_chars=300):
    """Last lines of a log, on one line, for the results row."""
    try:
        with open(path, "rb") as f:
            f.seek(max(0, os.path.getsize(path) - 4 * max_chars))
            text = f.read().decode("utf-8", "replace")
    except OSError:
        return ""
    lines = [ln.strip() for ln in text.splitlines() if ln.strip()]
    return " | ".join(lines[-3:])[-max_chars:]
