"""Nothing blind (reports/impactbench_compare/impacts.py and instability.py, docs/compare.md): a suite of the
short resonance (the reference and the first engine of the build, single runs, a dozen impacts each)
compared with itself moves nothing, per-impact distributions included; a copy whose engine run's
restitution changed in events.csv alone (runs.csv, its aggregates, as they were) moves that distribution;
copies in which the engine's run was unstable in both folders at other times are moved (earlier: regressed,
exit 4; later: improved, exit 1), at the same time and for the same reason not.

    /usr/bin/python3 reports/tests/test_compare_impacts.py IMPACTBENCH_EXECUTABLE SCENARIO_FOLDER
"""

import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import test_compare  # noqa: E402
from test_compare import compare, first_engine, rewrite_csv  # noqa: E402

EXECUTABLE = SCENARIOS = None
EXIT_NOTHING_MOVED, EXIT_MOVED, EXIT_REGRESSED = 0, 1, 4


class Impacts(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.folder = tempfile.mkdtemp(prefix="impactbench_compare_impacts_")
        cls.engine = first_engine()
        cls.base = os.path.join(cls.folder, "base")
        run = subprocess.run([EXECUTABLE, "suite", os.path.join(SCENARIOS, "short_resonance.toml"), "--engines",
                              f"reference,{cls.engine}", "--laws", "hertz", "--dt", "5e-5", "--jobs", "2", "--out",
                              cls.base], capture_output=True, text=True)
        assert run.returncode in (0, 1), run.stderr
        cls.job = f"short_resonance/{cls.engine}/hertz/dt=5e-05"

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.folder)

    def copy(self, name):
        path = os.path.join(self.folder, name)
        shutil.copytree(self.base, path)
        return path

    def test_a_folder_compared_with_itself_moves_nothing_per_impact_either(self):
        out = os.path.join(self.folder, "itself.json")
        result = compare(self.base, self.base, "--json", out)
        self.assertEqual(result.returncode, EXIT_NOTHING_MOVED, result.stdout + result.stderr)
        with open(out) as f:
            tested = [i for c in json.load(f)["configurations"] for i in c["impacts"]]
        self.assertTrue(tested)  # the distributions were compared, and none moved
        self.assertFalse(any(i["moved"] for i in tested))

    def test_a_restitution_changed_in_events_alone_is_found(self):
        changed = self.copy("restitution")

        def lower(rows):
            for row in rows:
                row["restitution"] = repr(float(row["restitution"]) * 0.8) if row["restitution"] else ""
        rewrite_csv(os.path.join(changed, "runs", self.job, "events.csv"), lower)
        result = compare(self.base, changed)
        self.assertEqual(result.returncode, EXIT_MOVED, result.stdout + result.stderr)
        line = next(line for line in result.stdout.splitlines() if line.startswith(f"  {self.job}:"))
        self.assertIn(f"  {self.job}: moved: per-impact restitution: median ", line)
        self.assertNotIn("per-impact contact duration", line)

    def unstable_copy(self, name, at_s, why="energy grew without input from 0.003 J to 0.0041 J"):
        path = self.copy(name)

        def unstable(rows):
            for row in rows:
                if row["engine"] == self.engine:
                    row["verdict"], row["reason"] = "unstable", f"{why} at t = {at_s} s"
        rewrite_csv(os.path.join(path, "runs.csv"), unstable)
        return path

    def test_unstable_in_both_folders_is_compared_by_when(self):
        late, early = self.unstable_copy("late", 2.5), self.unstable_copy("early", 1.5)
        result = compare(late, early)
        self.assertEqual(result.returncode, EXIT_REGRESSED, result.stdout + result.stderr)
        self.assertIn(f"  {self.job}: regressed: unstable at t = 2.5 s -> 1.5 s", result.stdout)
        result = compare(early, late)
        self.assertEqual(result.returncode, EXIT_MOVED, result.stdout + result.stderr)
        self.assertIn(f"  {self.job}: improved: unstable at t = 1.5 s -> 2.5 s", result.stdout)
        result = compare(late, self.unstable_copy("late_again", 2.5))
        self.assertEqual(result.returncode, EXIT_NOTHING_MOVED, result.stdout + result.stderr)

    def test_unstable_in_both_folders_for_another_reason_is_a_move(self):
        energy = self.unstable_copy("energy", 2.5)
        penetration = self.unstable_copy("penetration", 2.5, "penetration = 0.002 m, beyond the bound 0.001 m")
        result = compare(energy, penetration)
        self.assertEqual(result.returncode, EXIT_MOVED, result.stdout + result.stderr)
        self.assertIn(f"  {self.job}: moved: unstable at t = 2.5 s -> 2.5 s; why: 'energy grew", result.stdout)


if __name__ == "__main__":
    EXECUTABLE, SCENARIOS = sys.argv[1], sys.argv[2]
    test_compare.EXECUTABLE, test_compare.SCENARIOS = EXECUTABLE, SCENARIOS  # its helpers run the same binary
    unittest.main(argv=sys.argv[:1], verbosity=2)
