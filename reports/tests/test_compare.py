"""`impactbench compare BASE NEW` as an engine's author meets it (reports/compare.py, docs/compare.md): a small
study (a suite with an ensemble, so that the noise bands are the ensembles' intervals, and a sweep) run twice,
then compared with itself, with its rerun, with a copy in which one engine's contact durations were raised by
30 % in every file that holds them, with a suite run against a scenario file of the same name and other
content, and with a damaged copy; a sweep's folder alone; several folders in order.

    /usr/bin/python3 reports/tests/test_compare.py IMPACTBENCH_EXECUTABLE SCENARIO_FOLDER

The binary makes the folders; the comparison is this tree's reports/compare.py, what `impactbench compare`
runs from its own source tree with its exit code passed through (a binary built from another tree would run
that tree's).
"""

import csv
import glob
import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

EXECUTABLE = SCENARIOS = None
EXIT_NOTHING_MOVED, EXIT_MOVED, EXIT_BAD_INPUT, EXIT_REGRESSED = 0, 1, 2, 4
COMPARE = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "compare.py")
RAISE = 1.3


def first_engine():
    names = subprocess.run([EXECUTABLE, "engines", "--names"], capture_output=True, text=True, check=True).stdout
    return [n for n in names.strip().split(",") if n != "reference"][0]


def run_suite(scenarios, out, engine):
    # the short free vibration as an ensemble of 3 starts (its reference too: the cases' noise is measured), at a
    # step that resolves its one contact (23 steps: 3 starts at 5e-5 s gave 4 and 5 steps, whose scatter is a
    # noise band wider than 30 %)
    run = subprocess.run([EXECUTABLE, "suite", scenarios, "--engines", f"reference,{engine}", "--laws", "hertz",
                          "--dt", "1e-5", "--ensemble", "3", "--jobs", "2", "--out", out], capture_output=True, text=True)
    assert run.returncode in (0, 1), run.stderr  # an unstable run (exit 1) is a finding, compared like any other


def run_study(folder, scenarios, out, engine):
    """The suite of run_suite and a coarse sweep of the short resonance (reference only), as one study."""
    study = os.path.join(folder, "study.toml")
    with open(study, "w") as f:
        f.write(f"""[[suite]]
scenarios = ["{scenarios}"]
engines = ["reference", "{engine}"]
laws = ["hertz"]
dt_s = [1e-5]
ensemble_starts = 3

[[sweep]]
name = "coarse"
scenario = "{os.path.join(SCENARIOS, 'short_resonance.toml')}"
ratios = "0.95:1.00:0.05"
starts = ["up"]
engines = ["reference"]
laws = ["hertz"]
rest_duration_s = 3
duration_s = 3
window_s = 2
""")
    run = subprocess.run([EXECUTABLE, "study", study, "--no-report", "--jobs", "2", "--out", out], capture_output=True, text=True)
    assert run.returncode in (0, 1), run.stdout + run.stderr


def compare(base, new, *options):
    return subprocess.run([sys.executable, COMPARE, base, new, *options], capture_output=True, text=True)


def rewrite_csv(path, edit):
    """The CSV file at path with its rows (dicts) changed in place by edit(rows), header and order kept."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        return rows
    edit(rows)
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    return rows


def raise_contact_durations(folder, engine):
    """Every contact duration of `engine`'s runs times RAISE, in every file of the folder that holds one:
    runs.csv, runs.jsonl, each run's summary.json and events.csv."""
    jobs = set()

    def raise_runs(rows):
        columns = [c for c in rows[0] if c.startswith("contact_duration_") and c.endswith("_s")]
        for row in rows:
            if row["engine"] == engine:
                jobs.add(row["job_id"])
                for c in columns:
                    if row[c]:
                        row[c] = repr(float(row[c]) * RAISE)

    def raise_events(rows):
        for e in rows:
            for c in (c for c in rows[0] if c.startswith("duration")):
                e[c] = repr(float(e[c]) * RAISE) if e[c] else e[c]

    rewrite_csv(os.path.join(folder, "runs.csv"), raise_runs)

    def raised(record):
        for key, value in record.items():
            if key.startswith("contact_duration_") and key.endswith("_s") and isinstance(value, (int, float)):
                record[key] = value * RAISE
            elif isinstance(value, dict):
                raised(value)
        return record

    path = os.path.join(folder, "runs.jsonl")
    with open(path) as f:
        records = [json.loads(line) for line in f]
    with open(path, "w") as f:
        for r in records:
            f.write(json.dumps(raised(r) if r.get("job_id") in jobs else r) + "\n")
    for job in jobs:
        summary = os.path.join(folder, "runs", job, "summary.json")
        if os.path.exists(summary):
            with open(summary) as f:
                record = json.load(f)
            with open(summary, "w") as f:
                json.dump(raised(record), f)
        events = os.path.join(folder, "runs", job, "events.csv")
        if os.path.exists(events):
            rewrite_csv(events, raise_events)
    return jobs


class Compare(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.folder = tempfile.mkdtemp(prefix="impactbench_compare_test_")
        cls.scenarios = os.path.join(cls.folder, "scenarios")
        os.makedirs(cls.scenarios)
        shutil.copy(os.path.join(SCENARIOS, "short_free_vibration.toml"), cls.scenarios)
        cls.engine = first_engine()
        cls.base, cls.rerun = os.path.join(cls.folder, "base"), os.path.join(cls.folder, "rerun")
        run_study(cls.folder, cls.scenarios, cls.base, cls.engine)
        run_study(cls.folder, cls.scenarios, cls.rerun, cls.engine)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.folder)

    def test_every_result_folder_says_what_made_it(self):
        with open(os.path.join(self.base, "provenance.json")) as f:
            provenance = json.load(f)
        self.assertEqual(set(provenance), {"build", "machine", "engines", "engine_builds"})
        self.assertIn(self.engine, provenance["engines"])

    def test_a_folder_compared_with_itself_moves_nothing(self):
        result = compare(self.base, self.base)
        self.assertEqual(result.returncode, EXIT_NOTHING_MOVED, result.stdout + result.stderr)
        self.assertIn("made alike", result.stdout)
        self.assertIn("nothing moved beyond the noise", result.stdout)

    def test_the_same_study_run_twice_moves_nothing_beyond_the_noise(self):
        out = os.path.join(self.folder, "rerun.json")
        result = compare(self.base, self.rerun, "--json", out)
        self.assertEqual(result.returncode, EXIT_NOTHING_MOVED, result.stdout + result.stderr)
        with open(out) as f:
            comparison = json.load(f)
        # the ensembles' intervals are what the metrics were judged against (the noise bands at work)
        methods = {m["noise"] for c in comparison["configurations"] for m in c["metrics"]}
        self.assertTrue(any("ensembles" in m for m in methods), methods)
        self.assertTrue(all(c["presence"] == "both" for c in comparison["configurations"]))
        # the study's sweep rows are compared too
        self.assertTrue(any(c["job_id"].startswith("sweeps/coarse/") for c in comparison["configurations"]))

    def test_one_engines_contact_durations_raised_30_percent_are_named(self):
        changed = os.path.join(self.folder, "changed")
        shutil.copytree(self.base, changed)
        jobs = raise_contact_durations(changed, self.engine)
        self.assertTrue(jobs)
        page = os.path.join(self.folder, "page")
        result = compare(self.base, changed, "--html", page)
        # better or worse is the error's doing (against the engine's own chain): either way it moved
        self.assertIn(result.returncode, (EXIT_MOVED, EXIT_REGRESSED), result.stdout + result.stderr)
        moved = [line.strip() for line in result.stdout.splitlines() if line.startswith("  ")]
        self.assertTrue(moved, result.stdout)
        for line in moved:  # that engine's contact duration (its mean, and its impacts' distribution), nothing else
            job = line.split(":")[0]
            self.assertIn(job, jobs, line)
            self.assertIn("contact duration +30 %: error vs own chain", line)
            for part in line.split("; ")[1:]:
                self.assertTrue(part.startswith("per-impact contact duration"), line)
        with open(os.path.join(page, "compare.html")) as f:
            self.assertEqual(f.read().count("<svg"), len(moved))  # a figure per moved configuration
        self.assertTrue(os.path.exists(os.path.join(page, "compare.md")))

    def test_several_folders_in_order_are_a_history_of_each_configuration(self):
        changed = os.path.join(self.folder, "history_changed")
        shutil.copytree(self.base, changed)
        jobs = raise_contact_durations(changed, self.engine)
        page = os.path.join(self.folder, "history")
        result = compare(self.base, self.rerun, changed, "--html", page)
        self.assertIn(result.returncode, (EXIT_MOVED, EXIT_REGRESSED), result.stdout + result.stderr)
        lines = result.stdout.splitlines()
        self.assertIn(f"{self.base} -> {self.rerun}: nothing moved beyond the noise", lines)
        configurations = {job for job in jobs if "/start=" not in job}  # an ensemble is one configuration
        self.assertIn(f"{self.rerun} -> {changed}: {len(configurations)} configurations moved beyond the noise", lines)
        with open(os.path.join(page, "history.html")) as f:
            self.assertEqual(f.read().count("<svg"), len(configurations))  # each moved one along the folders

    def test_a_sweeps_rows_are_compared_and_a_changed_regime_is_named(self):
        sweep = os.path.join(self.folder, "sweep")
        run = subprocess.run([EXECUTABLE, "sweep", os.path.join(SCENARIOS, "short_resonance.toml"), "--engines", "reference",
                              "--laws", "hertz", "--ratios", "0.95:1.0:0.05", "--start", "up", "--duration", "3",
                              "--window", "2", "--out", sweep], capture_output=True, text=True)
        self.assertIn(run.returncode, (0, 1), run.stderr)
        result = compare(sweep, sweep)
        self.assertEqual(result.returncode, EXIT_NOTHING_MOVED, result.stdout + result.stderr)
        result = compare(sweep, self.base)  # a sweep's folder against a study's: of other kinds, refused
        self.assertEqual(result.returncode, EXIT_BAD_INPUT, result.stdout + result.stderr)
        self.assertIn(f"{sweep} is a sweep's folder (sweep.json), {self.base} is a suite's or a study's folder", result.stderr)
        changed = os.path.join(self.folder, "sweep_changed")
        shutil.copytree(sweep, changed)

        def change_last_regime(rows):
            rows[-1]["regime"] = "period-9" if rows[-1]["regime"] != "period-9" else "period-8"

        rows = rewrite_csv(os.path.join(changed, "sweep.csv"), change_last_regime)
        result = compare(sweep, changed)
        self.assertEqual(result.returncode, EXIT_MOVED, result.stdout + result.stderr)
        self.assertIn(f"  {rows[-1]['id']}: moved: verdict ", result.stdout)  # a regime is neither better nor worse
        self.assertIn(f", {rows[-1]['regime']}", result.stdout)
        page = os.path.join(self.folder, "sweep_history")  # a history of sweeps: the moved row drawn along them
        result = compare(sweep, changed, sweep, "--html", page)  # a regime changed and back: moves, neither worse
        self.assertEqual(result.returncode, EXIT_MOVED, result.stdout + result.stderr)
        with open(os.path.join(page, "history.html")) as f:
            self.assertEqual(f.read().count("<svg"), 1)

    def test_a_scenario_file_of_the_same_name_and_other_content_is_said_first(self):
        other = os.path.join(self.folder, "other_scenarios")
        shutil.copytree(self.scenarios, other)
        path = os.path.join(other, "short_free_vibration.toml")
        with open(path) as f:
            text = f.read()
        with open(path, "w") as f:
            f.write(text.replace("damping_ratio = 0.003", "damping_ratio = 0.004", 1))
        # the same name as the base's file: the folder itself is moved into place for the run
        shutil.move(self.scenarios, self.scenarios + ".kept")
        shutil.move(other, self.scenarios)
        try:
            changed = os.path.join(self.folder, "other_content")
            run_suite(self.scenarios, changed, self.engine)
        finally:
            shutil.move(self.scenarios, other)
            shutil.move(self.scenarios + ".kept", self.scenarios)
        result = compare(self.base, changed)
        lines = result.stdout.splitlines()
        self.assertEqual(lines[1], "what differs between the folders (before what moved):", result.stdout)
        self.assertIn("short_free_vibration.toml: its content differs", lines[2])

    def test_a_damaged_folder_is_named_with_exit_2(self):
        damaged = os.path.join(self.folder, "damaged")
        shutil.copytree(self.base, damaged)
        path = os.path.join(damaged, "runs.csv")
        with open(path) as f:
            lines = f.readlines()
        lines[2] = lines[2][: len(lines[2]) // 2] + "\n"  # a row cut short
        with open(path, "w") as f:
            f.writelines(lines)
        result = compare(self.base, damaged)
        self.assertEqual(result.returncode, EXIT_BAD_INPUT, result.stdout + result.stderr)
        self.assertIn(f"{path}:3", result.stderr)
        empty = os.path.join(self.folder, "empty")
        os.makedirs(empty)
        result = compare(empty, self.base)
        self.assertEqual(result.returncode, EXIT_BAD_INPUT)
        self.assertIn(f"{empty}: not a result folder", result.stderr)
        for name in glob.glob(os.path.join(damaged, "provenance.json")):
            with open(name, "w") as f:
                f.write("{ cut")
        with open(path, "w") as f:  # runs.csv whole again: the provenance alone is damaged
            with open(os.path.join(self.base, "runs.csv")) as whole:
                f.write(whole.read())
        result = compare(self.base, damaged)
        self.assertEqual(result.returncode, EXIT_BAD_INPUT, result.stdout + result.stderr)
        self.assertIn("provenance.json:1: not JSON", result.stderr)


if __name__ == "__main__":
    EXECUTABLE, SCENARIOS = sys.argv[1], sys.argv[2]
    unittest.main(argv=sys.argv[:1], verbosity=2)
