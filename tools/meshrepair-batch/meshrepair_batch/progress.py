"""The progress line on stderr: done/failed/remaining and an ETA.

On a terminal the line is rewritten in place every second; otherwise (a log file, CI) a plain line
is printed every `interval` seconds and at the end. Models that fail are named as they arrive.
"""
import sys
import threading
import time


def format_duration(seconds):
    """1h02m, 3m07s or 12s."""
    seconds = int(round(seconds))
    if seconds >= 3600:
        return f"{seconds // 3600}h{seconds % 3600 // 60:02d}m"
    if seconds >= 60:
        return f"{seconds // 60}m{seconds % 60:02d}s"
    return f"{seconds}s"


class Progress:
    """Counts results as they arrive and reports them; a context manager that ticks while open."""

    def __init__(self, to_run, already_done, stream=None, interval=15.0, enabled=True):
        self.to_run = to_run
        self.already_done = already_done
        self.done = 0
        self.failed = 0
        self.stream = stream or sys.stderr
        self.tty = self.stream.isatty()
        self.interval = 1.0 if self.tty else interval
        self.enabled = enabled
        self.start = time.monotonic()
        self.last_print = -1e9
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._ticker = None

    def __enter__(self):
        if self.enabled:
            self._ticker = threading.Thread(target=self._tick, daemon=True)
            self._ticker.start()
        return self

    def __exit__(self, *exc):
        self._stop.set()
        if self._ticker:
            self._ticker.join()
        if self.enabled and self.tty and self.done < self.to_run:
            self._write("\n")  # interrupted: keep the last line

    def line(self):
        """done/failed/remaining, elapsed time and ETA on one line."""
        elapsed = time.monotonic() - self.start
        remaining = self.to_run - self.done
        eta = format_duration(elapsed / self.done * remaining) if self.done else "?"
        before = f" ({self.already_done} done before)" if self.already_done else ""
        return (f"done {self.done}/{self.to_run}, failed {self.failed}, remaining {remaining}{before};"
                f" elapsed {format_duration(elapsed)}, ETA {eta}")

    def update(self, row):
        """Counts one result and reports when due."""
        with self._lock:
            self.done += 1
            ok = row.get("status") == "ok"
            self.failed += not ok
            if not ok and self.enabled:
                self._write(("\r\x1b[K" if self.tty else "") + f"{row.get('status')}: {row.get('key')}\n")
            self._show(force=self.tty or self.done == self.to_run)

    def _tick(self):
        while not self._stop.wait(min(self.interval, 1.0)):
            with self._lock:
                self._show(force=False)

    def _show(self, force):
        if not self.enabled:
            return
        now = time.monotonic()
        if not force and now - self.last_print < self.interval:
            return
        self.last_print = now
        if self.tty:
            self._write("\r\x1b[K" + self.line() + ("\n" if self.done == self.to_run else ""))
        else:
            self._write(self.line() + "\n")

    def _write(self, text):
        self.stream.write(text)
        self.stream.flush()
