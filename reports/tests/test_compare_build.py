"""`impactbench compare` names a changed build of an engine's library (docs/compare.md): every result folder
records which library file each engine loaded (provenance.json's engine_builds: its path, size and SHA-256, the
install prefix and the headers' version); a copy of a folder in which one engine's file has other content or
size under the same version string (a rebuilt or patched library) must be reported as that engine's changed
build, as must a file at another path, while the folder compared with itself reports none.

    /usr/bin/python3 reports/tests/test_compare_build.py IMPACTBENCH_EXECUTABLE SCENARIO_FOLDER
"""

import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

EXECUTABLE = SCENARIOS = None
EXIT_NOTHING_MOVED, EXIT_BAD_INPUT = 0, 2


def engines():
    names = subprocess.run([EXECUTABLE, "engines", "--names"], capture_output=True, text=True, check=True).stdout
    return [n for n in names.strip().split(",") if n != "reference"]


def compare(base, new, *options):
    return subprocess.run([EXECUTABLE, "compare", base, new, *options], capture_output=True, text=True)


def edit_provenance(folder, edit):
    """provenance.json of `folder` changed in place by edit(provenance)."""
    path = os.path.join(folder, "provenance.json")
    with open(path) as f:
        provenance = json.load(f)
    edit(provenance)
    with open(path, "w") as f:
        json.dump(provenance, f, indent=2)


class CompareBuild(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.folder = tempfile.mkdtemp(prefix="impactbench_compare_build_test_")
        scenarios = os.path.join(cls.folder, "scenarios")
        os.makedirs(scenarios)
        shutil.copy(os.path.join(SCENARIOS, "short_free_vibration.toml"), scenarios)
        cls.engines = engines()
        cls.engine = cls.engines[-1]  # any engine: the last, so that the first is not the only one ever checked
        cls.base = os.path.join(cls.folder, "base")
        run = subprocess.run([EXECUTABLE, "suite", scenarios, "--engines", f"reference,{cls.engine}", "--laws", "hertz",
                              "--dt", "1e-5", "--jobs", "2", "--out", cls.base], capture_output=True, text=True)
        assert run.returncode in (0, 1), run.stderr  # an unstable run (exit 1) is compared like any other
        with open(os.path.join(cls.base, "provenance.json")) as f:
            cls.builds = json.load(f)["engine_builds"]

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.folder)

    def copy(self, name, edit):
        changed = os.path.join(self.folder, name)
        shutil.copytree(self.base, changed)
        edit_provenance(changed, edit)
        return changed

    def test_every_engine_of_the_build_has_its_library_file_recorded(self):
        self.assertEqual(set(self.builds), set(self.engines))
        for name, build in self.builds.items():
            self.assertRegex(build["library_sha256"], r"^[0-9a-f]{64}$", name)
            self.assertGreater(build["library_size_bytes"], 0, name)
            self.assertTrue(os.path.isabs(build["library_path"]), name)
            self.assertTrue(build["install_prefix"] and build["header_version"], name)

    def test_a_folder_compared_with_itself_names_no_build(self):
        result = compare(self.base, self.base)
        self.assertEqual(result.returncode, EXIT_NOTHING_MOVED, result.stdout + result.stderr)
        self.assertNotIn("library file", result.stdout)

    def test_a_library_file_of_other_content_under_the_same_version_is_that_engines_changed_build(self):
        build = self.builds[self.engine]
        other_sha = hashlib.sha256(b"another build of the same version").hexdigest()
        other_size = build["library_size_bytes"] + 4096

        def rebuilt(provenance):
            provenance["engine_builds"][self.engine].update(library_sha256=other_sha, library_size_bytes=other_size)

        changed = self.copy("rebuilt", rebuilt)
        out = os.path.join(self.folder, "rebuilt.json")
        result = compare(self.base, changed, "--json", out)
        self.assertEqual(result.returncode, EXIT_NOTHING_MOVED, result.stdout + result.stderr)  # no number moved
        self.assertIn(f"  {self.engine}'s library file: sha256 {build['library_sha256'][:12]}… "
                      f"({build['library_size_bytes']} bytes) -> sha256 {other_sha[:12]}… ({other_size} bytes)",
                      result.stdout.splitlines())
        self.assertNotIn("library version", result.stdout)  # the version strings are the same: the file alone differs
        with open(out) as f:
            differences = json.load(f)["differences"]
        self.assertEqual([d["what"] for d in differences], [f"{self.engine}'s library file"])

    def test_a_library_file_at_another_path_is_named_with_both_paths(self):
        build = self.builds[self.engine]
        other_path = "/opt/own-build/lib/" + os.path.basename(build["library_path"])

        def moved(provenance):
            provenance["engine_builds"][self.engine]["library_path"] = other_path

        result = compare(self.base, self.copy("moved", moved))
        line = [l for l in result.stdout.splitlines() if l.startswith(f"  {self.engine}'s library file: ")]
        self.assertEqual(len(line), 1, result.stdout)
        self.assertTrue(re.search(f"at {re.escape(build['library_path'])} -> .* at {re.escape(other_path)}$", line[0]), line[0])

    def test_a_folder_made_before_the_builds_were_recorded_says_so(self):
        result = compare(self.base, self.copy("older", lambda provenance: provenance.pop("engine_builds")))
        self.assertIn("  each engine's library file: recorded -> not recorded (an older folder)", result.stdout.splitlines())

    def test_damaged_engine_builds_are_named_with_exit_2(self):
        def damaged(provenance):
            provenance["engine_builds"] = ["not", "an", "object"]

        result = compare(self.base, self.copy("damaged", damaged))
        self.assertEqual(result.returncode, EXIT_BAD_INPUT, result.stdout + result.stderr)
        self.assertIn("provenance.json: \"engine_builds\"", result.stderr)


if __name__ == "__main__":
    EXECUTABLE, SCENARIOS = sys.argv[1], sys.argv[2]
    unittest.main(argv=sys.argv[:1], verbosity=2)
