"""The Dask side: a client on a local cluster or an existing scheduler, and the task loop.

Each model is one Dask task that runs runner.run_model on a worker; the worker only starts and
watches the tool's process, so one single-threaded worker process per core keeps every core busy.
Results are stored as they complete, in whatever order.
"""
import logging
import os
import tempfile
import uuid

from . import runner


def open_client(scheduler=None, scheduler_file=None, workers=None):
    """(client, close): a client of an existing scheduler, or of a local cluster of `workers`
    single-threaded worker processes started here; close() shuts down what was started."""
    import cloudpickle
    from distributed import Client, LocalCluster

    # Workers started by hand need no copy of this package: the runner travels by value.
    cloudpickle.register_pickle_by_value(runner)
    if scheduler_file or scheduler:
        client = Client(scheduler_file=scheduler_file, timeout="30s") if scheduler_file else \
            Client(scheduler, timeout="30s")
        return client, client.close
    # Worker scratch space in a temporary folder, not dask-worker-space/ in the caller's folder.
    # No dashboard: with None, Dask 2022.12 still serves its HTTP routes on :8787 of every
    # interface (and warns when a second batch finds that port taken); a free local port instead.
    scratch = tempfile.TemporaryDirectory(prefix="meshrepair-batch-dask-")
    cluster = LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1, processes=True,
                           host="127.0.0.1", dashboard_address="127.0.0.1:0", memory_limit=0,
                           local_directory=scratch.name, silence_logs=logging.ERROR)
    client = Client(cluster)

    def close():
        client.close()
        cluster.close()
        scratch.cleanup()

    return client, close


def worker_count(client):
    """Workers the scheduler knows of now."""
    try:
        return len(client.scheduler_info().get("workers", {}))
    except Exception:  # noqa: BLE001 - informational only
        return None


def run_tasks(client, tasks, on_result):
    """Submits every task (largest input first, so the long ones do not straggle at the end) and
    calls on_result(row) for each as it completes. A task whose worker died or raised still gives a
    row (status crashed)."""
    from distributed import as_completed

    batch = uuid.uuid4().hex[:8]
    ordered = sorted(tasks, key=lambda t: -t["input_bytes"])
    futures = {}
    for rank, task in enumerate(ordered):
        future = client.submit(runner.run_model, task, key=f"meshrepair-batch-{batch}-{rank}", pure=False,
                               priority=len(ordered) - rank)
        futures[future] = task
    try:
        for future in as_completed(futures):
            task = futures[future]
            try:
                row = future.result()
            except Exception as e:  # noqa: BLE001 - a lost worker, an exception in the runner
                row = engine_failure_row(task, e)
            future.release()
            on_result(row)
    finally:
        client.cancel(list(futures))


def engine_failure_row(task, error):
    """The result row of a task that Dask could not complete."""
    return {"input": task["input"], "key": task["key"], "tool": task["tool"], "output": task["output"],
            "status": "crashed", "exit_code": None, "signal": None, "wall_s": None, "cpu_s": None,
            "peak_rss_mb": None, "time_limit_s": task["time_limit_s"], "memory_limit_mb": task["memory_limit_mb"],
            "stats": None, "stderr_tail": f"dask: {type(error).__name__}: {error}"[-runner.STDERR_TAIL_CHARS:],
            "command": task["command"], "worker": None}
