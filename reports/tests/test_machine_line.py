"""The report's machine line (reports/impactbench_report/machine.py) names the machine the runs ran on, from the
results folder's provenance.json; without one (or with a damaged one) it names the machine drawing the report and
says so.

    /usr/bin/python3 reports/tests/test_machine_line.py
"""

import json
import os
import shutil
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from impactbench_report import machine  # noqa: E402

RECORDED = {"cpu_model": "Test CPU 9000", "logical_cores": 48, "memory_bytes": 25276063744, "os": "Linux 9.9.9-test"}


class MachineLine(unittest.TestCase):
    def setUp(self):
        self.folder = tempfile.mkdtemp(prefix="impactbench_machine_")

    def tearDown(self):
        shutil.rmtree(self.folder)

    def write(self, text):
        with open(os.path.join(self.folder, "provenance.json"), "w") as f:
            f.write(text)

    def test_the_recorded_machine_is_named(self):
        self.write(json.dumps({"build": {}, "machine": RECORDED, "engines": {}}))
        found = machine.of_results(self.folder)
        self.assertTrue(found.recorded)
        self.assertEqual(found.cores, 48)
        self.assertEqual(found.description, "Test CPU 9000 x 48 cores, 23.5 GiB, Linux 9.9.9-test")
        self.assertIn("the machine the runs ran on, from provenance.json", found.line)
        self.assertEqual(found.stamp, "ran on Test CPU 9000 x 48 cores, 23.5 GiB, Linux 9.9.9-test")

    def test_without_a_record_the_drawing_machine_is_named_as_such(self):
        for text in (None, "{not json", json.dumps({"build": {}}), json.dumps([1, 2])):
            if text is not None:
                self.write(text)
            found = machine.of_results(self.folder)
            self.assertFalse(found.recorded, text)
            self.assertEqual(found.cores, os.cpu_count())
            self.assertNotIn("Test CPU", found.line)
            self.assertIn("the machine that made this report", found.line)
            self.assertIn("no provenance.json", found.line)
            self.assertTrue(found.stamp.startswith("drawn on "), found.stamp)

    def test_missing_keys_are_left_out_or_marked(self):
        self.assertEqual(machine.describe({"cpu_model": "X"}), "X x ? cores")
        self.assertEqual(machine.describe({"logical_cores": 2, "os": "Linux"}), "? x 2 cores, Linux")


if __name__ == "__main__":
    unittest.main()
