"""The report's "Input kept" section: medians over all outputs and split by whether the defects are local."""
import os
import sys
import unittest

BENCH = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, BENCH)

from corpus import report  # noqa: E402


def row(model, share, local, status="ok"):
    stats = {"path": "tetrahedralize",
             "provenance": {"kept_area_share": share, "input_triangles_kept": 1, "recut_faces": 0, "filled_faces": 0}}
    if local is not None:
        stats["defects_cut"] = {"local": local}
    return {"model": model, "status": status, "input_faces": 10, "tool_stats": stats}


class KeptInputSectionTest(unittest.TestCase):
    def test_medians_split_by_locality(self):
        rows = [row("a", 1.0, True), row("b", 0.9, True), row("c", 0.2, False), row("d", 0.4, None),
                row("e", 0.0, False, status="timeout")]
        text = report.kept_input_section(["meshrepair"], {"meshrepair": rows})
        self.assertIn("median 65.0% over 4 outputs", text)
        self.assertIn("95.0% over 2 inputs whose defects are local", text)
        self.assertIn("20.0% over 1 others", text)
        lines = {ln.split("|")[1].strip(): ln for ln in text.splitlines() if ln.startswith("| `")}
        self.assertEqual(sorted(lines), ["`a`", "`b`", "`c`", "`d`"])  # the timeout has no output
        self.assertIn("| yes |", lines["`a`"])
        self.assertIn("| no |", lines["`c`"])
        self.assertIn("| – |", lines["`d`"])

    def test_no_locality_reported(self):
        text = report.kept_input_section(["meshrepair"], {"meshrepair": [row("a", 0.5, None)]})
        self.assertIn("no inputs whose defects are local", text)


if __name__ == "__main__":
    unittest.main()
