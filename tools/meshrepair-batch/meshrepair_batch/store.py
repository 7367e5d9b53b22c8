"""OUT_DIR/results.jsonl (one JSON line per model run, appended as results arrive) and summary.json.

Each line is flushed and fsynced before the next result is taken, so a batch killed at any moment
loses none of the results it had written. A line cut short by such a kill is dropped when the file
is opened again. The latest line of a model is its result; a rerun skips models that have one.
"""
import collections
import fcntl
import json
import os

RESULTS = "results.jsonl"
SUMMARY = "summary.json"


def resume_key(row):
    """A model's identity across runs: its input file and the tool run on it."""
    return row.get("input"), row.get("tool")


class Busy(Exception):
    """OUT_DIR is in use by another batch."""


class ResultStore:
    """Append-only results file of one OUT_DIR."""

    def __init__(self, out_dir):
        self.path = os.path.join(out_dir, RESULTS)
        self.latest = {}  # resume_key -> latest row
        os.makedirs(out_dir, exist_ok=True)
        self._lock = self._take_lock(out_dir)
        self._drop_partial_line()
        for row in self._read():
            self.latest[resume_key(row)] = row
        self._file = open(self.path, "a", encoding="utf-8")

    @staticmethod
    def _take_lock(out_dir):
        """An exclusive lock on OUT_DIR/.lock for the life of this process: two batches writing the
        same results.jsonl would run models twice. The kernel drops it when the process dies."""
        handle = open(os.path.join(out_dir, ".lock"), "a", encoding="utf-8")
        try:
            fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            handle.close()
            raise Busy(f"{out_dir}: another meshrepair-batch is writing there") from None
        return handle

    def _read(self):
        try:
            with open(self.path, encoding="utf-8", errors="replace") as f:
                lines = f.readlines()
        except FileNotFoundError:
            return []
        rows = []
        for line in lines:
            try:
                row = json.loads(line)
            except ValueError:
                continue
            if isinstance(row, dict):
                rows.append(row)
        return rows

    def _drop_partial_line(self):
        """Truncates a last line without its newline (written by a batch killed mid-write)."""
        try:
            with open(self.path, "rb+") as f:
                data = f.read()
                if data and not data.endswith(b"\n"):
                    f.truncate(data.rfind(b"\n") + 1)
        except FileNotFoundError:
            pass

    def should_skip(self, row_key, retry_failed):
        """True when the model already has a result that this run keeps."""
        row = self.latest.get(row_key)
        if row is None:
            return False
        return row.get("status") == "ok" or not retry_failed

    def append(self, row):
        """Writes one result line and makes it durable before returning."""
        self._file.write(json.dumps(row, sort_keys=True) + "\n")
        self._file.flush()
        os.fsync(self._file.fileno())
        self.latest[resume_key(row)] = row

    def close(self):
        self._file.close()
        self._lock.close()


def summarize(rows, run_rows, skipped, wall_s, workers):
    """The batch's summary: counts per status over all its models, and this run's times."""
    counts = collections.Counter(r.get("status", "unknown") for r in rows)
    return {
        "models": len(rows),
        "status_counts": dict(sorted(counts.items())),
        "ok": counts.get("ok", 0),
        "not_ok": len(rows) - counts.get("ok", 0),
        "failed_models": sorted(r.get("key") or r.get("input") for r in rows if r.get("status") != "ok"),
        "run_this_time": len(run_rows),
        "skipped_already_done": skipped,
        "wall_s": round(wall_s, 2),
        "tool_wall_s_sum": round(sum(r.get("wall_s") or 0 for r in run_rows), 2),
        "tool_cpu_s_sum": round(sum(r.get("cpu_s") or 0 for r in run_rows), 2),
        "peak_rss_mb_max": max((r.get("peak_rss_mb") or 0 for r in run_rows), default=None),
        "workers": workers,
    }


def write_summary(out_dir, summary):
    """summary.json, written atomically."""
    path = os.path.join(out_dir, SUMMARY)
    with open(path + ".tmp", "w", encoding="utf-8") as f:
        json.dump(summary, f, indent=2, sort_keys=True)
        f.write("\n")
    os.replace(path + ".tmp", path)


def format_summary(summary):
    """A few lines for the terminal."""
    counts = ", ".join(f"{n} {s}" for s, n in summary["status_counts"].items())
    lines = [f"{summary['models']} models: {counts} "
             f"({summary['run_this_time']} run now, {summary['skipped_already_done']} done before)",
             f"wall {summary['wall_s']:.1f} s" + (f" on {summary['workers']} worker(s)" if summary["workers"] else "")
             + f"; tool cpu {summary['tool_cpu_s_sum']:.1f} s"]
    failed = summary["failed_models"]
    if failed:
        lines.append("not ok: " + ", ".join(failed[:10]) + (f" and {len(failed) - 10} more" if len(failed) > 10 else ""))
    return "\n".join(lines)
