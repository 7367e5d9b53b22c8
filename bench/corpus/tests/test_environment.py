"""Under ctest (MR_BUILD_DIR set), the other tests of this folder must not skip: this one fails
when what they need is missing (numpy and matplotlib for the interpreter that runs them, our
tools in the build folder), so a dependency that goes away shows as a failure, not as a skip.
"""
import importlib.util
import os
import unittest

BUILD = os.environ.get("MR_BUILD_DIR")


@unittest.skipIf(BUILD is None, "outside ctest, missing pieces only skip the tests that need them")
class EverythingTheTestsNeedIsThere(unittest.TestCase):
    def test_python_modules(self):
        for module in ("numpy", "matplotlib"):
            self.assertIsNotNone(importlib.util.find_spec(module), f"{module} missing for this interpreter")

    def test_our_tools_are_built(self):
        for tool in ("format-convert", "mesh-check", "meshrepair", "tetrahedralize"):
            path = os.path.join(BUILD, "tools", tool, tool)
            self.assertTrue(os.access(path, os.X_OK), f"{path} not built")


if __name__ == "__main__":
    unittest.main()
