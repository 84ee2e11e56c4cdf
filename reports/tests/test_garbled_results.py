"""A runs.csv that is cut short or garbled (hand-edited, copied half-way) stops the report with a message
naming the file, the line and the column, never a Python traceback.

    /usr/bin/python3 reports/tests/test_garbled_results.py
"""

import os
import subprocess
import sys
import tempfile
import unittest

MAKE_REPORT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "make_report.py")
HEADER = "job_id,scenario,law,engine,time_step_s,options,verdict,reason,duration_s,wall_time_s\n"
GOOD = "s/reference/hertz,s,hertz,reference,0,,ok,,0.3,0.01\n"


class GarbledResults(unittest.TestCase):
    def report(self, text):
        folder = tempfile.mkdtemp(prefix="impactbench_garbled_")
        path = os.path.join(folder, "runs.csv")
        with open(path, "w") as f:
            f.write(text)
        run = subprocess.run([sys.executable, MAKE_REPORT, folder], capture_output=True, text=True)
        self.assertNotEqual(run.returncode, 0, run.stdout)
        self.assertNotIn("Traceback", run.stderr)
        return path, run.stderr

    def test_a_row_cut_short_names_the_line(self):
        path, error = self.report(HEADER + GOOD + "s/engine_a/hertz,s,hertz,eng")
        self.assertIn(f"make_report: {path}:3: not the header's 10 columns", error)
        self.assertIn("--resume", error)

    def test_text_in_a_number_column_names_the_column_and_value(self):
        path, error = self.report(HEADER + GOOD.replace(",0.3,", ",0.3x,"))
        self.assertIn(f"make_report: {path}:2: duration_s = '0.3x': not a number", error)

    def test_an_empty_file_says_it_has_no_header(self):
        path, error = self.report("")
        self.assertIn(f"make_report: {path}:1: no header with job_id", error)


if __name__ == "__main__":
    unittest.main()
