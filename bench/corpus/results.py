"""results.jsonl: one JSON line per finished (model, tool), appended as soon as it is known.

A restarted run skips the pairs already in the file, so an interrupted run continues where it
stopped. When a pair appears twice (a --retry), the last line wins.
"""
import json
import math
import os
import threading

STATUSES = ("ok", "crash", "error", "timeout", "oom", "empty", "invalid", "unchecked", "no-input")
FAILURES = STATUSES[1:]

ROW_KEYS = (
    "model", "file", "tags", "input_faces", "input_bytes", "tool", "ours", "task", "out_format", "status", "note",
    "returncode", "signal", "wall_s", "cpu_s", "user_s", "sys_s", "peak_mb", "time_limit_s", "memory_limit_mb",
    "epsilon", "output", "output_bytes", "tool_stats", "finished_at",
)


def read_rows(path):
    """Rows of a results file, the last line of each (model, tool) pair; skips a torn last line."""
    latest = {}
    if not os.path.exists(path):
        return []
    with open(path, encoding="utf-8") as f:
        for line in f:
            try:
                row = json.loads(line)
            except ValueError:
                continue
            if isinstance(row, dict) and "model" in row and "tool" in row:
                latest[(row["model"], row["tool"])] = row
    return list(latest.values())


def _json_safe(value):
    if isinstance(value, float) and not math.isfinite(value):
        return None if math.isnan(value) else ("inf" if value > 0 else "-inf")
    if isinstance(value, dict):
        return {k: _json_safe(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_json_safe(v) for v in value]
    return value


class ResultStore:
    def __init__(self, path):
        self.path = path
        self._lock = threading.Lock()

    def finished(self, retry_statuses=()):
        """(model, tool) pairs that need no new run."""
        return {(r["model"], r["tool"]) for r in read_rows(self.path) if r.get("status") not in retry_statuses}

    def append(self, row):
        line = json.dumps(_json_safe(row), allow_nan=False, default=str) + "\n"
        with self._lock, open(self.path, "a+b") as f:
            if f.tell() > 0:
                f.seek(-1, os.SEEK_END)
                if f.read(1) != b"\n":
                    line = "\n" + line  # close a line torn by an earlier kill
            f.write(line.encode("utf-8"))
            f.flush()
            os.fsync(f.fileno())
