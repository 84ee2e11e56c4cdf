"""A new report view is one function and its line in report_views.py (docs/layout.md, "A new report view"): a toy
view, impacts counted from runs.csv, added to AFTER_CASES shows on both pages (index.html with its anchor, and
summary.md) after the views already there, with the number its folder's runs.csv gives; a view with nothing to
show adds no section.

    /usr/bin/python3 reports/tests/test_toy_report_view.py
"""

import csv
import os
import shutil
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from impactbench_report import page_writer, report_views  # noqa: E402

RUNS = ("job_id,engine,impacts\n"
        "s/reference/hertz,reference,12\n"
        "s/engine_a/hertz,engine_a,15\n"
        "s/engine_b/hertz,engine_b,\n")


def impacts_recorded(inputs):
    """The toy view: the impacts every run of the folder recorded, from runs.csv; None without runs."""
    with open(os.path.join(inputs.suite_folder, "runs.csv")) as f:
        counted = [int(row["impacts"]) for row in csv.DictReader(f) if row["impacts"]]
    if not counted:
        return None
    text = f"{sum(counted)} impacts in {len(counted)} runs."
    return "Impacts recorded", text, f"<p>{text}</p>", []


class ToyReportView(unittest.TestCase):
    def setUp(self):
        self.folder = tempfile.mkdtemp(prefix="impactbench_toy_view_")
        with open(os.path.join(self.folder, "runs.csv"), "w") as f:
            f.write(RUNS)
        self.inputs = report_views.ViewInputs(self.folder, {"cases": [], "ablation": []}, self.folder)

    def tearDown(self):
        shutil.rmtree(self.folder)

    def test_the_toy_view_shows_on_both_pages_with_its_folders_numbers(self):
        views = report_views.AFTER_CASES + [impacts_recorded]  # its one line, as report_views.py would hold it
        sections = report_views.sections(views, self.inputs)
        self.assertEqual([s[0] for s in sections], ["Impacts recorded"], "the other views have nothing to show here")
        page = "\n".join(page_writer.sections_html(sections, self.folder))
        markdown = "\n".join(page_writer.sections_markdown(sections, self.folder))
        self.assertIn("<h2 id='impacts-recorded'>Impacts recorded</h2><p>27 impacts in 2 runs.</p>", page)
        self.assertIn("## Impacts recorded\n\n27 impacts in 2 runs.", markdown)

    def test_a_view_with_nothing_to_show_adds_no_section(self):
        with open(os.path.join(self.folder, "runs.csv"), "w") as f:
            f.write(RUNS.splitlines()[0] + "\n")
        self.assertEqual(report_views.sections([impacts_recorded], self.inputs), [])

    def test_the_views_are_in_page_order_and_each_is_named_once(self):
        views = report_views.BEFORE_CASES + report_views.AFTER_CASES
        self.assertEqual(len(set(views)), len(views))
        self.assertEqual(report_views.BEFORE_CASES[0], report_views.chain_resolution)


if __name__ == "__main__":
    unittest.main()
