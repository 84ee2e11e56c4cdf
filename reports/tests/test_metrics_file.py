"""The report's one fallback catalog, for a folder made before metrics.json (metric_catalog.py's
CATALOG_OF_FOLDERS_WITHOUT_METRICS_JSON), is the metrics.json the current binary writes (`impactbench metrics
--json`, what every suite and sweep writes into its folder): the same references and note, and the same metrics,
first and in order, each with the same name, column, unit, error column, kind, tolerance key and default,
references and step search. A metric added since then comes after them and is in no older folder, so the fallback
does not list it; a metric changed in place fails here (an older folder holds the old one: give it a new name).

    /usr/bin/python3 reports/tests/test_metrics_file.py IMPACTBENCH_EXECUTABLE
"""

import json
import os
import subprocess
import sys
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))
from impactbench_report import metric_catalog  # noqa: E402

EXECUTABLE = None


class TheFallbackIsWhatTheBinaryWrites(unittest.TestCase):
    def test_the_fallback_is_the_binarys_metrics_json(self):
        written = json.loads(subprocess.run([EXECUTABLE, "metrics", "--json"], capture_output=True, text=True,
                                            check=True).stdout)
        fallback = metric_catalog.CATALOG_OF_FOLDERS_WITHOUT_METRICS_JSON
        self.assertEqual(list(written), list(fallback))
        for key in fallback:
            if key != "metrics":
                self.assertEqual(written[key], fallback[key], key)
        listed = len(fallback["metrics"])
        self.assertEqual(written["metrics"][:listed], fallback["metrics"])
        self.assertEqual(metric_catalog.metrics_of(written)[:listed], metric_catalog.metrics_of(fallback))


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit("usage: test_metrics_file.py IMPACTBENCH_EXECUTABLE")
    EXECUTABLE = sys.argv.pop(1)
    unittest.main()
