"""A sweep's report from its tables (impactbench sweep: sweep.csv, poincare.csv): the answer follows the data,
the engines' regime agreement counts and lists the right ratios, and a broken sweep.csv stops the report with a
message naming the file, never a traceback.

    /usr/bin/python3 reports/tests/test_sweep_report.py
"""

import json
import os
import subprocess
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from impactbench_report import sweep, sweep_starts  # noqa: E402

MAKE_REPORT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "make_report.py")
# sweep.csv's header as harness/sweep/sweep_row.cpp writes it (the quantities runs.csv has under runs.csv's names)
COLUMNS = ("id,scenario,engine,engine_version,law,options,contact_path,law_simulated,time_step_s,start,ratio,"
           "ensemble_start,ensemble_starts,initial_displacement_offset_m,"
           "motor_frequency_hz,duration_s,window_s,verdict,reason,timed_out,impacts,impacts_per_cycle,regime,period_n,"
           "impacts_per_period,frame1_sensor_peak_acceleration_g,frame2_sensor_peak_acceleration_g,"
           "frame1_peak_displacement_m,frame2_peak_displacement_m,mean_approach_velocity_m_s,contact_duration_mean_s,"
           "poincare_samples,steps,cpu_time_s,wall_time_s,load_average")


def row(engine, start, ratio, regime, impacts_per_cycle, peak=10.0, verdict="ok", options="", member=0, members=1):
    """A sweep.csv row; member K >= 1 of `members`: the reference's ensemble start K from rest (id ends in /start=K)."""
    prefix = f"resonance/{engine}/hertz" + (f"/{options}" if options else "")
    path = "" if engine == "reference" else (options.partition("contact=")[2] or "matched")
    return (f"{prefix}/{start}/r={ratio:g}{f'/start={member}' if member else ''},resonance,{engine},v1,hertz,{options},{path},"
            f"{'no' if path == 'native' else 'yes'},{1e-4 if engine != 'reference' else 0},"
            f"{start},{ratio},{member},{members},{member * 1e-7},{6.95 * ratio},30,10,{verdict},,false,{round(70 * impacts_per_cycle)},{impacts_per_cycle},"
            f"{regime},,,{peak},{peak},0.001,0.0005,0.1,0.0003,70,1000,1.5,1.5,1.0")


def write_sweep(folder, rows, warnings=None):
    """sweep.csv, poincare.csv, sweep.json, and sweep.jsonl with the rows' warnings ({row id: [text]})."""
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, "sweep.csv"), "w") as f:
        f.write(COLUMNS + "\n" + "\n".join(rows) + "\n")
    with open(os.path.join(folder, "sweep.jsonl"), "w") as f:
        for r in rows:
            f.write(json.dumps({"id": r.split(",")[0], "warnings": (warnings or {}).get(r.split(",")[0], [])}) + "\n")
    with open(os.path.join(folder, "poincare.csv"), "w") as f:
        f.write("id,period_index,time_s,frame1_tip_displacement_m,frame1_tip_velocity_m_s,frame2_tip_displacement_m,"
                "frame2_tip_velocity_m_s\n")
        for r in rows:
            f.write(f"{r.split(',')[0]},1,0.1,0.001,0,0,0\n")
    with open(os.path.join(folder, "sweep.json"), "w") as f:
        json.dump({"scenario": "resonance"}, f)


def reference_rows(last_impacting_up=1.08, impacts_at_117=False):
    rows = []
    for start in ("up", "down"):
        for ratio in (1.0, 1.08, 1.17):
            hit = ratio <= (last_impacting_up if start == "up" else 1.0) or (ratio == 1.17 and impacts_at_117)
            rows.append(row("reference", start, ratio, "period-1" if hit else "no impact", 1.0 if hit else 0.0))
    return rows


class SweepAnswer(unittest.TestCase):
    def read(self, rows):
        folder = tempfile.mkdtemp(prefix="impactbench_sweep_")
        write_sweep(folder, rows)
        return sweep.read(folder)

    def test_the_answer_follows_the_data(self):
        text = " ".join(sweep.answer_sentences(self.read(reference_rows())))
        self.assertIn("keeps impacting up to r = 1.08", text)
        self.assertIn("at 1.17 f_1 (the experiment's post-resonance, about 8 impacts per beat) it has no impact", text)
        self.assertIn("up and down differ at r = 1.08 (period-1 up, no impact down)", text)
        text = " ".join(sweep.answer_sentences(self.read(reference_rows(impacts_at_117=True))))
        self.assertIn("at 1.17 f_1 it impacts, 1.00 impacts per cycle (period-1)", text)

    def test_regime_agreement_counts_and_lists_the_ratios_where_an_engine_differs(self):
        engine = [row("engine_a", "up", 1.0, "period-1", 1.0, peak=11.0, options="contact=matched"),
                  row("engine_a", "up", 1.08, "no impact", 0.0, options="contact=matched"),
                  row("engine_a", "up", 1.17, "", 0.0, verdict="unstable", options="contact=matched")]
        table = sweep.agreement(self.read(reference_rows() + engine))
        self.assertEqual(len(table), 1)  # engine_a, hertz, up (no down rows of the engine)
        t = table[0]
        self.assertEqual(t["ratios"], 3)
        self.assertAlmostEqual(t["agreement"], 1 / 3)
        self.assertEqual(t["differ"], [(1.08, "no impact", "period-1"), (1.17, "unstable", "no impact")])
        self.assertAlmostEqual(t["impacts_per_cycle_mean_abs_error"], 0.5)  # 0 at 1.0, 1 at 1.08; 1.17 not ok
        self.assertAlmostEqual(t["sensor_peak_median_relative_error"], 0.1)  # where both impact: 1.0 only
        self.assertIn("1.08 (no impact vs period-1), 1.17 (unstable vs no impact)", sweep.agreement_rows(table)[0][5])


def ensemble_rows(ratio, regimes):
    """The reference's starts from rest at one ratio, start K reaching regimes[K]."""
    return [row("reference", "rest", ratio, regime, 0.0 if regime == "no impact" else 0.3, member=k, members=len(regimes))
            for k, regime in enumerate(regimes)]


# 0.94: start 0 (the row from rest) has no impact, 3 of the 8 starts impact: multistable. 1.0: every start period-1.
MULTISTABLE = ensemble_rows(0.94, ["no impact"] * 5 + ["irregular"] * 3)
SETTLED = ensemble_rows(1.0, ["period-1"] * 4)


class MultistableRatios(unittest.TestCase):
    def read(self, rows, scenario="resonance"):
        folder = tempfile.mkdtemp(prefix="impactbench_sweep_ensemble_")
        write_sweep(folder, rows)
        return sweep.read(folder)

    def test_the_fractions_count_every_start_and_a_ratio_is_multistable_when_more_than_one_regime_is_reached(self):
        data = self.read(MULTISTABLE + SETTLED)
        table = sweep_starts.start_ensemble_table(data, "hertz")
        self.assertEqual([t["ratio"] for t in table], [0.94, 1.0])
        self.assertEqual(table[0]["regimes"], {"no impact": 5, "irregular": 3})
        self.assertEqual((table[0]["starts"], table[0]["impacting"], table[0]["multistable"]), (8, 3, True))
        self.assertEqual((table[1]["regimes"], table[1]["multistable"]), ({"period-1": 4}, False))
        self.assertEqual(sweep_starts.start_ensemble_rows(table)[0], ["0.94", "8", "no impact 5 of 8, irregular 3 of 8", "3 of 8", "yes"])
        self.assertIn("multistable at r = 0.94 (no impact 5 of 8, irregular 3 of 8)", sweep.summary_sentence(data))
        # the members are one configuration's: the reference is one simulator, its rows from rest one per ratio
        self.assertEqual(len(data.simulators()), 1)
        self.assertEqual([r["ratio"] for r in data.rows_of(data.simulators()[0], "hertz", "rest")], [0.94, 1.0])

    def test_an_engine_agrees_at_a_multistable_ratio_when_any_start_of_the_reference_reaches_its_regime(self):
        # From one start (start 0: no impact) the engine's irregular orbit at 0.94 would disagree: it agrees
        # because 3 of the reference's 8 starts reach it. At 1.0, where every start reaches period-1, period-2
        # disagrees; at 0.94 a regime no start reaches (period-2) disagrees too.
        engine = [row("engine_a", "rest", 0.94, "irregular", 0.3, options="contact=matched"),
                  row("engine_a", "rest", 1.0, "period-2", 1.0, options="contact=matched")]
        t = sweep.agreement(self.read(MULTISTABLE + SETTLED + engine))[0]
        self.assertAlmostEqual(t["agreement"], 1 / 2)
        self.assertEqual(t["differ"], [(1.0, "period-2", "period-1")])
        self.assertEqual(t["multistable"], [(0.94, "irregular", {"no impact": 5, "irregular": 3})])
        self.assertEqual(sweep.agreement_rows([t])[0][6], "0.94 (irregular: 3 of 8)")
        engine[0] = row("engine_a", "rest", 0.94, "period-2", 0.5, options="contact=matched")
        t = sweep.agreement(self.read(MULTISTABLE + SETTLED + engine))[0]
        self.assertAlmostEqual(t["agreement"], 0)

    def test_a_studys_engine_sweep_is_judged_by_the_reference_sweeps_starts(self):
        # the engines' sweep (up) holds one reference row per ratio; the study's reference sweep holds the starts
        engines_sweep = self.read([row("reference", "up", 0.94, "no impact", 0.0),
                                   row("engine_a", "up", 0.94, "irregular", 0.3, options="contact=matched")])
        reference_sweep = self.read(MULTISTABLE)
        self.assertAlmostEqual(sweep.agreement(engines_sweep)[0]["agreement"], 0)  # one start: disagrees
        sweep_starts.share_start_ensembles([("engines", engines_sweep), ("reference", reference_sweep)])
        self.assertEqual(engines_sweep.start_ensembles_from, "sweep reference")
        self.assertAlmostEqual(sweep.agreement(engines_sweep)[0]["agreement"], 1)
        # another reference (5 modes) is another model: its starts do not judge this one's engines
        engines_sweep = self.read([row("reference", "up", 0.94, "no impact", 0.0, options="n=5"),
                                   row("engine_a", "up", 0.94, "irregular", 0.3, options="contact=matched")])
        sweep_starts.share_start_ensembles([("engines", engines_sweep), ("reference", reference_sweep)])
        self.assertEqual(engines_sweep.start_ensembles, {})

    def test_the_report_shows_the_fractions_and_the_multistable_ratios(self):
        folder = tempfile.mkdtemp(prefix="impactbench_sweep_ensemble_report_")
        write_sweep(folder, reference_rows() + MULTISTABLE + SETTLED)
        run = subprocess.run([sys.executable, MAKE_REPORT, folder], capture_output=True, text=True)
        self.assertEqual(run.returncode, 0, run.stderr)
        with open(os.path.join(folder, "report", "summary.md")) as f:
            markdown = f.read()
        self.assertIn("| 0.94 | 8 | no impact 5 of 8, irregular 3 of 8 | 3 of 8 | yes |", markdown)
        self.assertIn("| 1 | 4 | period-1 4 of 4 | 4 of 4 | no |", markdown)
        self.assertIn("multistable at r = 0.94", markdown)


class SweepReport(unittest.TestCase):
    def test_a_sweep_folder_gets_a_report_that_answers_first(self):
        folder = tempfile.mkdtemp(prefix="impactbench_sweep_report_")
        write_sweep(folder, reference_rows())
        run = subprocess.run([sys.executable, MAKE_REPORT, folder], capture_output=True, text=True)
        self.assertEqual(run.returncode, 0, run.stderr)
        with open(os.path.join(folder, "report", "index.html")) as f:
            page = f.read()
        self.assertLess(page.index("keeps impacting up to r = 1.08"), page.index("<figure"))
        self.assertTrue(os.path.exists(os.path.join(folder, "report", "figures", "sweep_Frequency_sweep_hertz_bifurcation.svg")))

    def test_a_rows_warning_is_listed_in_the_html_and_markdown_reports(self):
        folder = tempfile.mkdtemp(prefix="impactbench_sweep_warning_")
        rows = reference_rows()
        warning = "resonance: the scoring window starts at 2 s, before the start-up transient's end (22.9 s"
        write_sweep(folder, rows, {rows[0].split(",")[0]: [warning + ")"]})
        run = subprocess.run([sys.executable, MAKE_REPORT, folder], capture_output=True, text=True)
        self.assertEqual(run.returncode, 0, run.stderr)
        with open(os.path.join(folder, "report", "index.html")) as f:
            page = f.read()
        with open(os.path.join(folder, "report", "summary.md")) as f:
            markdown = f.read()
        self.assertIn("<h2 id='warnings'>Warnings</h2>", page)
        self.assertIn(warning, page.replace("&#x27;", "'"))
        self.assertIn("## Warnings", markdown)
        self.assertIn(f"- {warning}) (1 row)", markdown)
        write_sweep(folder, rows)  # no warning: no list
        run = subprocess.run([sys.executable, MAKE_REPORT, folder], capture_output=True, text=True)
        self.assertEqual(run.returncode, 0, run.stderr)
        with open(os.path.join(folder, "report", "summary.md")) as f:
            self.assertNotIn("Warnings", f.read())

    def test_a_broken_sweep_csv_names_the_file_and_line_never_a_traceback(self):
        folder = tempfile.mkdtemp(prefix="impactbench_sweep_broken_")
        write_sweep(folder, reference_rows())
        path = os.path.join(folder, "sweep.csv")
        with open(path) as f:
            lines = f.read().splitlines()
        lines[2] = lines[2].replace(",1.08,", ",1.08x,", 1)
        with open(path, "w") as f:
            f.write("\n".join(lines) + "\n")
        run = subprocess.run([sys.executable, MAKE_REPORT, folder], capture_output=True, text=True)
        self.assertNotEqual(run.returncode, 0)
        self.assertNotIn("Traceback", run.stderr)
        self.assertIn(f"{path} line 3: column ratio is '1.08x', not a number", run.stderr)
        os.remove(path)
        run = subprocess.run([sys.executable, MAKE_REPORT, folder], capture_output=True, text=True)
        self.assertNotIn("Traceback", run.stderr)
        self.assertIn("sweep.csv: no such file", run.stderr)


if __name__ == "__main__":
    unittest.main()
