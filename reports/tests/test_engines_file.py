"""A result folder's engines.json drives the report's names, colours and settings, and an old folder without
it still reports (each engine under its catalog name, in a spare colour); the descriptors the repository
ships are complete (each with its default time step, null for the adaptive reference), each documented diagnostics key is one its adapter writes, and `impactbench engines
--json` (what a suite writes) carries them with each library's version.

    /usr/bin/python3 reports/tests/test_engines_file.py [IMPACTBENCH_EXECUTABLE]
"""

import glob
import json
import os
import re
import subprocess
import sys
import tempfile
import unittest

REPOSITORY = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(REPOSITORY, "reports"))
from impactbench_report import engines, figures, settings  # noqa: E402

EXECUTABLE = None
TOY = {"name": "toy", "display_name": "ToyPhysics", "summary": "a fake engine", "version": "0.1", "packages": ["libtoy-dev"],
       "colours": {"matched": "#010203", "native": "#040506", "injected": "#070809"},
       "diagnostics": [{"key": "toy_solver_flag", "label": "solver", "meaning": "m", "unit": "", "values": {"1": "Toy's LCP"}},
                       {"key": "toy_stiffness_n_per_m", "label": "toy stiffness", "meaning": "m", "unit": "N/m"}]}


def shipped():
    found = {}
    for path in sorted(glob.glob(os.path.join(REPOSITORY, "adapters", "*", "descriptor.json"))) + \
            [os.path.join(REPOSITORY, "reference", "descriptor.json")]:
        with open(path) as f:
            found[path] = json.load(f)
    return found


class FromTheFolder(unittest.TestCase):
    def setUp(self):
        self.folder = tempfile.mkdtemp(prefix="impactbench_engines_test_")

    def use(self, document):
        if document is not None:
            with open(os.path.join(self.folder, "engines.json"), "w") as f:
                f.write(document if isinstance(document, str) else json.dumps(document))
        engines.use(self.folder)

    def test_names_colours_and_settings_come_from_engines_json(self):
        self.use({"simulators": [TOY]})
        self.assertEqual(engines.display_name("toy"), "ToyPhysics")
        self.assertEqual(figures.colour_of("toy [contact=native]", ["toy [contact=native]"]), "#040506")
        items = dict(settings.describe("toy", "matched", {"toy_solver_flag": 1.0, "toy_stiffness_n_per_m": 2.5e6,
                                                          "undocumented_key": 7.0}))
        self.assertEqual(items["solver"], "Toy's LCP")
        self.assertEqual(items["toy stiffness"], "2.5e+06 N/m")
        self.assertNotIn("undocumented_key", " ".join(items) + " ".join(items.values()))

    def test_an_old_folder_without_the_file_falls_back_to_names_and_spare_colours(self):
        for document in (None, "{not json", {"simulators": "garbled"}):
            self.use(document)
            self.assertEqual(engines.display_name("toy"), "toy")
            colour = figures.colour_of("toy [contact=native]", ["toy [contact=native]"])
            self.assertIn(colour, figures.SPARE_COLOURS)
            items = settings.describe("toy", "matched", {"toy_solver_flag": 1.0})
            self.assertEqual([name for name, _ in items], ["contact path"])


class TheShippedDescriptors(unittest.TestCase):
    VERDICT = {c.lower() for c in figures.VERDICT_COLOURS.values()}

    def test_every_descriptor_is_complete_and_its_colours_are_its_own(self):
        seen = {}
        for path, d in shipped().items():
            folder = os.path.basename(os.path.dirname(path))
            self.assertEqual(d["name"], folder if folder != "reference" else "reference", path)
            self.assertTrue(d.get("display_name") and d.get("summary"), path)
            for key in d["diagnostics"]:
                self.assertTrue(key.get("key") and key.get("label") and key.get("meaning"), f"{path}: {key}")
                self.assertIn("unit", key, f"{path}: {key['key']} has no unit field ('' for none)")
            self.assertIn("default_time_step_s", d, path)
            if d["name"] == "reference":
                self.assertIsNone(d["default_time_step_s"], f"{path}: the reference is adaptive")
                self.assertIn("adaptive", d["default_time_step_note"], path)
                continue
            self.assertGreater(d["default_time_step_s"], 0, f"{path}: the step of a run without --dt [s]")
            self.assertTrue(d["packages"], f"{path}: no Debian package")
            self.assertEqual(set(d["colours"]), {"matched", "injected", "native"}, path)
            for path_name, colour in d["colours"].items():
                self.assertRegex(colour, r"^#[0-9a-fA-F]{6}$")
                self.assertNotIn(colour.lower(), self.VERDICT, f"{path}: {path_name} has a verdict's colour")
                self.assertNotIn(colour.lower(), seen, f"{path}: {colour} is {seen.get(colour.lower())}'s too")
                seen[colour.lower()] = f"{d['name']} {path_name}"

    def test_every_recommended_setting_names_its_source(self):
        """An engine's recommended configuration (descriptor "recommended"): a configuration per law with a
        contact path and a time step; each option it sets, and its step, is a setting listed with why and a
        source (a link, or a repository file), or said to have no value from the authors."""
        laws = {"hertz", "viscoelastic", "newton"}
        checked = 0
        for path, d in shipped().items():
            if "recommended" not in d:
                continue
            recommended = d["recommended"]
            self.assertEqual(set(recommended["laws"]), laws, path)
            settings = recommended["settings"]
            for entry in settings:
                self.assertTrue(entry["setting"] and entry["why"] and entry["value_is"], f"{path}: {entry}")
                if not entry["value_is"].startswith("no value"):
                    self.assertRegex(entry["source"], r"^(https://|adapters/)", f"{path}: {entry['setting']}")
            texts = " | ".join(entry["setting"] for entry in settings)
            for law, configuration in recommended["laws"].items():
                self.assertIn("contact", configuration["options"], f"{path}: {law}")
                self.assertGreater(configuration["time_step_s"], 0, f"{path}: {law}")
                for name, value in configuration["options"].items():
                    self.assertIn(f"{name}={value}", texts, f"{path}: {law} sets {name}={value} without a source")
                mantissa, exponent = f"{configuration['time_step_s']:e}".split("e")
                step = f"{mantissa.rstrip('0').rstrip('.')}e{int(exponent)}"  # 2.5e-5, as the settings write it
                self.assertRegex(texts, rf"time step[^|]*{re.escape(step)} s", f"{path}: {law}'s time step without a source")
                checked += 1
            with open(os.path.join(REPOSITORY, "docs", "engines.md")) as f:
                documented = f.read()
            for entry in settings:  # docs/engines.md lists them as the descriptor has them
                self.assertIn(f"**{entry['setting']}** ({entry['value_is']}): {entry['why']}.", documented, path)
                self.assertIn(entry["source"], documented, f"{path}: {entry['setting']}")
        self.assertGreater(checked, 0)

    def test_each_documented_key_is_written_by_its_simulator(self):
        """A key the descriptor documents but the adapter never writes is a renamed or removed one."""
        for path, d in shipped().items():
            folder = os.path.dirname(path)
            text = "".join(open(p, errors="replace").read() for p in glob.glob(os.path.join(folder, "*.cpp")))
            for key in d["diagnostics"]:
                # keys are written whole ("integrator_rk4"), from a stem ("integrator_" + name) or per frame
                # (frame + "_hinge_stop_erp")
                stems = [key["key"]] + [key["key"][:i + 1] for i, c in enumerate(key["key"]) if c == "_"]
                stems += [m.group(1) for m in [re.match(r"^frame[12](_.+)$", key["key"])] if m]
                self.assertTrue(any(f'"{stem}"' in text for stem in stems),
                                f"{path}: {key['key']} is not written by {folder}/*.cpp")


@unittest.skipIf(EXECUTABLE is None and len(sys.argv) < 2, "no impactbench executable given")
class TheCommand(unittest.TestCase):
    def test_engines_json_is_the_descriptors_with_versions(self):
        run = subprocess.run([EXECUTABLE, "engines", "--json"], capture_output=True, text=True)
        self.assertEqual(run.returncode, 0, run.stderr)
        printed = {d["name"]: d for d in json.loads(run.stdout)["simulators"]}
        self.assertEqual(next(iter(printed)), "reference")
        for path, d in shipped().items():
            if d["name"] not in printed:
                continue  # an engine left out of this build (-DIMPACTBENCH_ENGINES)
            p = printed[d["name"]]
            self.assertTrue(p["version"], d["name"])
            for field in ("display_name", "packages", "colours"):
                self.assertEqual(p[field], d[field], f"{d['name']}: {field}")
            self.assertEqual([k["key"] for k in p["diagnostics"]], [k["key"] for k in d["diagnostics"]])
            self.assertEqual(p.get("recommended"), d.get("recommended"), f"{d['name']}: recommended")
            for field in ("default_time_step_s", "default_time_step_note"):  # null: adaptive (the reference)
                self.assertEqual(p.get(field), d.get(field), f"{d['name']}: {field}")
        names = subprocess.run([EXECUTABLE, "engines", "--names"], capture_output=True, text=True)
        self.assertEqual(names.stdout.strip().split(","), list(printed))
        human = subprocess.run([EXECUTABLE, "engines"], capture_output=True, text=True)
        for d in printed.values():
            self.assertIn(f"{d['name']} ({d['display_name']})", human.stdout)
        both = subprocess.run([EXECUTABLE, "engines", "--json", "--names"], capture_output=True, text=True)
        self.assertEqual(both.returncode, 2, both.stdout)


if __name__ == "__main__":
    if len(sys.argv) > 1:
        EXECUTABLE = sys.argv.pop(1)
    unittest.main(verbosity=2)
