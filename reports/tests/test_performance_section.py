"""The report's performance section: every figure it shows is the saved measurement's own (Google
Benchmark's median aggregate where repetitions ran), each table names the machine and versions, a
folder without measurements adds no section, and unreadable JSON names its file.

    /usr/bin/python3 reports/tests/test_performance_section.py
"""

import json
import os
import shutil
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from impactbench_report import performance  # noqa: E402

MACHINE = {"cpu_model": "Test CPU 9000", "cpu_cores": "2", "memory_gib": "23.5", "os": "Debian GNU/Linux 12",
           "libmujoco-dev": "2.2.2-3", "impactbench_commit": "abc1234"}


def benchmark(name, **counters):
    return dict({"name": name, "run_name": name, "run_type": "iteration", "real_time": 12.5, "time_unit": "ms"}, **counters)


class PerformanceSection(unittest.TestCase):
    def setUp(self):
        self.suite = tempfile.mkdtemp(prefix="impactbench_performance_test_")
        self.folder = os.path.join(self.suite, "performance")
        os.makedirs(self.folder)

    def tearDown(self):
        shutil.rmtree(self.suite)

    def write(self, name, document):
        with open(os.path.join(self.folder, name), "w") as f:
            json.dump(document, f)

    def test_no_measurements_no_section(self):
        self.assertIsNone(performance.section(self.suite))
        shutil.rmtree(self.folder)
        self.assertIsNone(performance.section(self.suite))

    def test_the_median_aggregate_is_shown_with_the_machine(self):
        mean = dict(benchmark("engine_a/hertz", us_per_step=9.0, steps=20000.0), run_type="aggregate", aggregate_name="mean")
        median = dict(benchmark("engine_a/hertz", us_per_step=6.25, steps=20000.0), run_type="aggregate", aggregate_name="median")
        self.write("engine_step_benchmark.json", {"context": MACHINE, "benchmarks": [mean, median]})
        markdown, page = performance.section(self.suite)
        self.assertIn("| engine_a/hertz | 6.25 | 2e+04 |", markdown)
        self.assertNotIn("| 9 |", markdown)
        for text in (markdown, page):
            self.assertIn("Test CPU 9000 x 2 cores", text)
            self.assertIn("libmujoco-dev 2.2.2-3", text)
            self.assertIn("abc1234", text)

    def test_overhead_and_scaling_figures_are_the_files_own(self):
        self.write("harness_overhead_benchmark.json", {"context": MACHINE, "benchmarks": [
            benchmark("engine_b/newton", harness_ms=104.0, bare_ms=100.0, overhead_percent=4.0)]})
        self.write("scaling.json", {"suite": "default suite part 1", "duration_option": "--duration 50", "machine": MACHINE,
                                    "rows": [{"workers": 1, "wall_time_s": 1800.0, "jobs": 240, "parallel_efficiency": 1.0},
                                             {"workers": 2, "wall_time_s": 960.0, "jobs": 240, "parallel_efficiency": 0.9375}]})
        markdown, _ = performance.section(self.suite)
        self.assertIn("| engine_b/newton | 104 | 100 | +4.0 % |", markdown)
        self.assertIn("| 2 | 960 | 240 | 93.8 % |", markdown)
        self.assertIn("--duration 50", markdown)

    def test_the_scipy_comparison_is_shown_from_its_own_record(self):
        os.makedirs(os.path.join(self.folder, "reference_vs_scipy"))
        summary = {"case": "resonance", "law": "hertz", "duration_s": 20.0, "reference_wall_time_s": 0.5,
                   "scipy_integration_time_s": 80.0, "speed_ratio": 160.0, "speed_ratio_cpu": 150.0,
                   "largest_relative_difference": 1e-3, "largest_reference_error": 8e-5, "largest_scipy_error": 9e-4}
        self.write("reference_vs_scipy/comparison.json", {
            "machine": dict(MACHINE, **{"python3-scipy": "1.10.1-2"}), "versions": {"scipy": "1.10.1"},
            "settings": {"method": "DOP853", "rtol": 1e-9, "tight_rtol": 1e-12}, "cases": [{"summary": summary}]})
        markdown, _ = performance.section(self.suite)
        self.assertIn("| resonance / hertz | 20 | 0.5 | 80 | 160 | 150 | 0.001 | 8e-05 | 0.0009 |", markdown)
        self.assertIn("Test CPU 9000 x 2 cores", markdown)
        self.assertIn("python3-scipy 1.10.1", markdown)

    def test_the_three_way_comparison_is_shown_from_its_own_record(self):
        os.makedirs(os.path.join(self.folder, "reference_cvode_scipy"))
        summary = {"case": "resonance", "law": "hertz", "duration_s": 5.0, "truth_events": 12,
                   "reference_rtol": 1e-6, "reference_met_criterion": True, "reference_cpu_time_per_simulated_s": 0.0125,
                   "cvode_rtol": 1e-8, "cvode_met_criterion": True, "cvode_cpu_time_per_simulated_s": 0.25,
                   "scipy_rtol": 1e-10, "scipy_met_criterion": False, "scipy_cpu_time_per_simulated_s": 7.5,
                   "cvode_over_reference_cpu": 20.0, "scipy_over_reference_cpu": 600.0}
        self.write("reference_cvode_scipy/comparison.json", {
            "machine": dict(MACHINE, **{"libsundials-dev": "6.4.1+dfsg1-3", "proc_loadavg_at_start": [1.25, 1.0, 0.5],
                                        "proc_loadavg_at_end": [1.5, 1.1, 0.6]}),
            "settings": {"cvode_method": "adams", "scipy_method": "DOP853", "truth_rtol": 1e-12,
                         "time_tolerance_s": 1e-6, "velocity_tolerance": 1e-5},
            "cases": [{"summary": summary}]})
        markdown, page = performance.section(self.suite)
        self.assertIn("| resonance / hertz | 5 | 12 | 0.0125 (rtol 1e-06) | 0.25 (rtol 1e-08) | 7.5 (rtol 1e-10) * "
                      "| 20 | 600 |", markdown)
        for text in (markdown, page):
            self.assertIn("libsundials-dev 6.4.1+dfsg1-3", text)
            self.assertIn("load average 1.25 and 1.50 at the start and at the end", text)
            self.assertIn("within 1e-06 s", text)

    def test_the_second_newton_reference_is_shown_from_its_own_record(self):
        os.makedirs(os.path.join(self.folder, "reference_siconos"))
        case = {"case": "resonance", "duration_s": 5.0, "impacts_compared": 20, "max_impact_time_difference_s": 8.16e-10,
                "max_approach_velocity_relative_difference": 6.88e-08, "max_restitution_difference": 7.77e-16,
                "reference_cpu_time_s": 0.125, "siconos_cpu_time_s": 57.5}
        self.write("reference_siconos/comparison.json", {
            "machine": dict(MACHINE, proc_loadavg_at_start=[1.25, 1.0, 0.5], proc_loadavg_at_end=[1.5, 1.1, 0.6]),
            "comparator": "Comparator 4.4 (event-driven)", "cases": [case]})
        markdown, page = performance.section(self.suite)
        self.assertIn("| resonance | 5 | 20 | 8.2e-10 | 6.9e-08 | 7.8e-16 | 0.125 | 57.5 |", markdown)
        for text in (markdown, page):
            self.assertIn("a second Newton reference, Comparator 4.4 (event-driven)", text)
            self.assertIn("load average 1.25 and 1.50 at the start and at the end", text)
            self.assertIn("Test CPU 9000 x 2 cores", text)

    def test_unreadable_json_names_its_file(self):
        with open(os.path.join(self.folder, "scaling.json"), "w") as f:
            f.write("{not json")
        with self.assertRaises(ValueError) as raised:
            performance.section(self.suite)
        self.assertIn("scaling.json", str(raised.exception))


if __name__ == "__main__":
    unittest.main()
