"""meshrepair-batch end to end: a folder batch with the real tool, resume after SIGKILL, an existing
scheduler with two workers started by hand, the time limit, bad usage; plus in-process unit tests of
input discovery and result classification. Needs Debian's python3-distributed."""
import json
import os
import signal
import subprocess
import sys
import tempfile
import time
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import batch_support as bs  # noqa: E402

sys.path.insert(0, bs.PACKAGE_DIR)
from meshrepair_batch import inputs, runner, store  # noqa: E402


def read_results(out_dir):
    with open(os.path.join(out_dir, "results.jsonl"), encoding="utf-8") as f:
        return [json.loads(line) for line in f]


def by_key(rows):
    return {r["key"]: r for r in rows}


class Tmp(unittest.TestCase):
    def setUp(self):
        self._tmp = tempfile.TemporaryDirectory(prefix="mr_batch_")
        self.tmp = self._tmp.name

    def tearDown(self):
        self._tmp.cleanup()


@unittest.skipUnless(bs.have_dask(), "python3-distributed is not installed")
class RealToolBatch(Tmp):
    def test_folder_batch_outputs_results_and_rerun(self):
        models = os.path.join(self.tmp, "models")
        bs.copy_examples(models)
        os.makedirs(os.path.join(models, "sub"))
        bs.cube(os.path.join(models, "sub", "cube.obj"))
        bs.open_tetrahedron_off(os.path.join(models, "sub", "open_tet.off"))
        bs.broken_stl(os.path.join(models, "sub", "broken.stl"))
        with open(os.path.join(models, "notes.txt"), "w", encoding="ascii") as f:
            f.write("not a model\n")
        out = os.path.join(self.tmp, "out")
        done = bs.run_batch([models, out, "--to", "glb", "--workers", "2", "--time-limit", "60"])
        self.assertEqual(done.returncode, 1, done.stderr)  # the broken model failed, the others not
        rows = by_key(read_results(out))
        good = ["box_with_hole.stl", "overlapping_boxes.obj", "torus_soup.ply", "sub/cube.obj", "sub/open_tet.off"]
        self.assertEqual(sorted(rows), sorted(good + ["sub/broken.stl"]))
        for key in good:
            row = rows[key]
            self.assertEqual(row["status"], "ok", row)
            expected = os.path.join(out, os.path.splitext(key)[0] + ".glb")
            self.assertEqual(row["output"], expected)
            self.assertTrue(os.path.getsize(expected) > 0)
            self.assertTrue(row["stats"]["output"]["watertight"], row["stats"])
            self.assertGreater(row["peak_rss_mb"], 1)
            self.assertLess(row["peak_rss_mb"], 2000)  # the tool's own, not the worker's
            self.assertTrue(row["worker"].startswith("tcp://"))
            checked = subprocess.run([bs.tool("mesh-check"), expected, "-q", "-j", "1"], check=False)
            self.assertEqual(checked.returncode, 0, expected)
        broken = rows["sub/broken.stl"]
        self.assertEqual(broken["status"], "failed")
        self.assertEqual(broken["exit_code"], 2)
        self.assertIn("broken.stl", broken["stderr_tail"])
        self.assertFalse(os.path.exists(os.path.join(out, "sub", "broken.glb")))
        with open(os.path.join(out, "summary.json"), encoding="utf-8") as f:
            summary = json.load(f)
        self.assertEqual(summary["status_counts"], {"failed": 1, "ok": 5})
        self.assertEqual(summary["failed_models"], ["sub/broken.stl"])

        # A rerun runs nothing; --retry-failed runs the failed model only.
        again = bs.run_batch([models, out, "--to", "glb", "--workers", "2"])
        self.assertEqual(again.returncode, 1)
        self.assertEqual(len(read_results(out)), 6)
        retry = bs.run_batch([models, out, "--to", "glb", "--workers", "1", "--retry-failed"])
        self.assertEqual(retry.returncode, 1)
        rows = read_results(out)
        self.assertEqual(len(rows), 7)
        self.assertEqual(rows[-1]["key"], "sub/broken.stl")


@unittest.skipUnless(bs.have_dask(), "python3-distributed is not installed")
class FakeToolBatch(Tmp):
    def test_resume_after_sigkill(self):
        models = os.path.join(self.tmp, "models")
        os.makedirs(models)
        names = [f"slow_{i}.obj" for i in range(8)]
        for name in names:
            bs.cube(os.path.join(models, name))
        listing = os.path.join(self.tmp, "list.txt")
        with open(listing, "w", encoding="ascii") as f:
            f.write("# every model, by path relative to this file\n\n")
            f.writelines(f"models/{n}\n" for n in names)
        fake = bs.fake_tool(self.tmp)
        out = os.path.join(self.tmp, "out")
        args = [listing, out, "--tool-path", fake, "--workers", "2"]
        env = dict(os.environ, MR_TOOLS_DIR=bs.TOOLS_DIR, FAKE_SLOW_S="0.8")
        batch = subprocess.Popen([bs.BATCH] + args, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env,
                                 start_new_session=True)
        results = os.path.join(out, "results.jsonl")
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and not (os.path.exists(results) and os.path.getsize(results) > 0):
            time.sleep(0.05)
        os.killpg(batch.pid, signal.SIGKILL)  # the batch and its local cluster
        batch.wait()
        first = read_results(out)
        self.assertGreaterEqual(len(first), 1)
        self.assertLess(len(first), len(names), "the batch finished before it was killed")
        time.sleep(1.0)  # the fake tools still running finish (they live in their own sessions)

        done = bs.run_batch(args, env=env)
        self.assertEqual(done.returncode, 0, done.stderr)
        rows = read_results(out)
        keys = [r["key"] for r in rows]
        self.assertEqual(sorted(keys), sorted(f"models/{n}" for n in names))  # each exactly once
        self.assertEqual(rows[:len(first)], first)
        self.assertTrue(all(r["status"] == "ok" for r in rows))
        for name in names:
            self.assertTrue(os.path.exists(os.path.join(out, "models", name)))
        with open(os.path.join(out, "summary.json"), encoding="utf-8") as f:
            summary = json.load(f)
        self.assertEqual(summary["skipped_already_done"], len(first))
        self.assertEqual(summary["run_this_time"], len(names) - len(first))

    def test_time_limit_kills_and_batch_goes_on(self):
        models = os.path.join(self.tmp, "models")
        os.makedirs(models)
        for name in ("hang.stl", "a.obj", "b.obj"):
            bs.cube(os.path.join(models, name))
        out = os.path.join(self.tmp, "out")
        started = time.monotonic()
        done = bs.run_batch([os.path.join(models, "*.*"), out, "--tool-path", bs.fake_tool(self.tmp),
                             "--workers", "2", "--time-limit", "2", "--", "--some-tool-option"])
        self.assertLess(time.monotonic() - started, 40)
        self.assertEqual(done.returncode, 1, done.stderr)
        rows = by_key(read_results(out))
        self.assertEqual(rows["hang.stl"]["status"], "timeout")
        self.assertLess(rows["hang.stl"]["wall_s"], 10)
        self.assertEqual(rows["a.obj"]["status"], "ok")
        self.assertEqual(rows["b.obj"]["status"], "ok")
        self.assertIn("--some-tool-option", rows["a.obj"]["command"])
        self.assertEqual(rows["a.obj"]["stats"], {"faces": 12, "fake": True})
        with open(os.path.join(models, "hang.stl.pid"), encoding="ascii") as f:
            pid = int(f.read())
        deadline = time.monotonic() + 5
        while time.monotonic() < deadline and _running(pid):
            time.sleep(0.1)
        self.assertFalse(_running(pid), "the timed-out tool still runs")


@unittest.skipUnless(bs.have_dask(), "python3-distributed is not installed")
class ExistingScheduler(Tmp):
    def test_two_workers_started_by_hand_take_work(self):
        scheduler_file = os.path.join(self.tmp, "scheduler.json")
        log = open(os.path.join(self.tmp, "dask.log"), "wb")
        self.addCleanup(log.close)
        procs = []

        def start(args):
            proc = subprocess.Popen([bs.python(), "-m"] + args, stdout=log, stderr=log,
                                    start_new_session=True)
            procs.append(proc)
            self.addCleanup(_stop, proc)

        start(["distributed.cli.dask_scheduler", "--host", "127.0.0.1", "--port", "0", "--no-dashboard",
               "--scheduler-file", scheduler_file])
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline and not os.path.exists(scheduler_file):
            time.sleep(0.1)
        for name in ("hand-1", "hand-2"):
            start(["distributed.cli.dask_worker", "--scheduler-file", scheduler_file, "--nthreads", "1",
                   "--no-dashboard", "--name", name, "--host", "127.0.0.1"])
        self._wait_for_workers(scheduler_file, 2)
        with open(scheduler_file, encoding="utf-8") as f:
            address = json.load(f)["address"]

        models = os.path.join(self.tmp, "models")
        os.makedirs(models)
        for i in range(6):
            bs.cube(os.path.join(models, f"slow_{i}.obj"))
        out = os.path.join(self.tmp, "out")
        done = bs.run_batch([models, out, "--tool-path", bs.fake_tool(self.tmp), "--scheduler", address],
                            env=dict(os.environ, FAKE_SLOW_S="0.5"))
        self.assertEqual(done.returncode, 0, done.stderr)
        rows = read_results(out)
        self.assertEqual(len(rows), 6)
        self.assertTrue(all(r["status"] == "ok" for r in rows))
        self.assertEqual(len({r["worker"] for r in rows}), 2, [r["worker"] for r in rows])

    @staticmethod
    def _wait_for_workers(scheduler_file, n):
        from distributed import Client
        with Client(scheduler_file=scheduler_file, timeout="30s") as client:
            client.wait_for_workers(n, timeout=60)


def _running(pid):
    """True while pid exists and is not a zombie waiting for its reaper."""
    try:
        with open(f"/proc/{pid}/stat", encoding="ascii", errors="replace") as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except (OSError, IndexError):
        return False


def _stop(proc):
    try:
        os.killpg(proc.pid, signal.SIGTERM)
        proc.wait(timeout=10)
    except (ProcessLookupError, subprocess.TimeoutExpired):
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait()


class BadUsage(Tmp):
    def test_exit_2_with_a_message(self):
        out = os.path.join(self.tmp, "out")
        listing = os.path.join(self.tmp, "list.txt")
        with open(listing, "w", encoding="ascii") as f:
            f.write("missing.stl\n")
        empty = os.path.join(self.tmp, "empty")
        os.makedirs(empty)
        cases = [([os.path.join(self.tmp, "nope"), out], "no such folder"),
                 ([listing, out], "line 1: missing.stl"),
                 ([empty, out], "no mesh files"),
                 ([bs.EXAMPLES, out, "--to", "msh"], "--to msh"),
                 ([bs.EXAMPLES, out, "--tool-path", os.path.join(self.tmp, "nope")], "no executable"),
                 ([bs.EXAMPLES, out, "--tool", "nonsense"], "invalid choice")]
        for args, message in cases:
            done = bs.run_batch(args)
            self.assertEqual(done.returncode, 2, (args, done.stderr))
            self.assertIn(message, done.stderr)
        self.assertFalse(os.path.exists(os.path.join(out, "results.jsonl")))


class Inputs(Tmp):
    def _tree(self):
        for rel in ("a.stl", "b.OBJ", "sub/c.ply", "sub/deeper/d.off", "sub/notes.txt", "out/old.stl", ".hidden/e.stl"):
            path = os.path.join(self.tmp, *rel.split("/"))
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "w", encoding="ascii") as f:
                f.write("x")

    def test_folder_glob_list_and_outputs(self):
        self._tree()
        out = os.path.join(self.tmp, "out")
        keys = [m.key for m in inputs.discover(self.tmp, out)]
        self.assertEqual(keys, ["a.stl", "b.OBJ", "sub/c.ply", "sub/deeper/d.off"])  # not out/, not hidden
        keys = [m.key for m in inputs.discover(os.path.join(self.tmp, "sub", "**", "*.*"), out)]
        self.assertEqual(keys, ["c.ply", "deeper/d.off"])
        listing = os.path.join(self.tmp, "sub", "list.txt")
        with open(listing, "w", encoding="ascii") as f:
            f.write("# comment\nc.ply\n\ndeeper/d.off\nc.ply\n")
        models = inputs.discover(listing, out)
        self.assertEqual([m.key for m in models], ["c.ply", "deeper/d.off"])
        inputs.plan_outputs(models, out, "tetrahedralize")
        self.assertEqual(models[1].output, os.path.join(out, "deeper", "d.msh"))

    def test_colliding_outputs_keep_their_extension(self):
        models = [inputs.Model("/m/a.stl", "a.stl", 1), inputs.Model("/m/a.obj", "a.obj", 1),
                  inputs.Model("/m/b.ply", "b.ply", 1)]
        inputs.plan_outputs(models, "/o", "meshrepair", "glb")
        self.assertEqual([m.output for m in models], ["/o/a.stl.glb", "/o/a.obj.glb", "/o/b.glb"])
        inputs.plan_outputs(models[2:], "/o", "meshrepair")
        self.assertEqual(models[2].output, "/o/b.ply")


class Classification(Tmp):
    def _classify(self, stderr="", limit=1000, **outcome):
        log = os.path.join(self.tmp, "err.txt")
        with open(log, "w", encoding="utf-8") as f:
            f.write(stderr)
        base = dict(returncode=1, signal=None, timed_out=False, wall_s=1.0, cpu_s=1.0, peak_mb=10.0)
        base.update(outcome)
        task = {"output": os.path.join(self.tmp, "missing.glb"), "stderr_log": log, "memory_limit_mb": limit}
        return runner.classify(base, task)

    def test_statuses(self):
        self.assertEqual(self._classify(timed_out=True, returncode=None, signal=9), "timeout")
        self.assertEqual(self._classify(returncode=0), "failed")  # exit 0 without an output
        self.assertEqual(self._classify("terminate called after throwing an instance of 'std::bad_alloc'"), "memory")
        self.assertEqual(self._classify(peak_mb=950.0), "memory")
        self.assertEqual(self._classify(returncode=None, signal=11), "crashed")
        self.assertEqual(self._classify("tool: error: cannot read"), "failed")

    def test_store_drops_a_line_cut_short(self):
        path = os.path.join(self.tmp, store.RESULTS)
        with open(path, "w", encoding="utf-8") as f:
            f.write(json.dumps({"input": "/a", "tool": "t", "status": "ok"}) + "\n" + '{"input": "/b", "tool"')
        results = store.ResultStore(self.tmp)
        self.assertTrue(results.should_skip(("/a", "t"), retry_failed=True))
        self.assertFalse(results.should_skip(("/b", "t"), retry_failed=False))
        results.append({"input": "/b", "tool": "t", "status": "failed"})
        results.close()
        self.assertEqual(len(read_results(self.tmp)), 2)
        reopened = store.ResultStore(self.tmp)
        self.assertTrue(reopened.should_skip(("/b", "t"), retry_failed=False))
        with self.assertRaises(store.Busy):  # one batch at a time per OUT_DIR
            store.ResultStore(self.tmp)
        reopened.close()


if __name__ == "__main__":
    unittest.main()
