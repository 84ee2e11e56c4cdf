"""A result folder as compare reads it: its runs (impactbench_report.data: one run per configuration, with
its ensemble's statistics) and its sweeps' rows (a study's sweeps/NAME/, or a sweep's own folder), what made
them (provenance.json, engines.json) and the scenario files it ran (the digests in suite.jsonl). Anything it
cannot read is a CompareInputError naming the file."""

import glob
import json
import os
from dataclasses import dataclass, field

from impactbench_report import data, sweep


class CompareInputError(ValueError):
    """A folder compare cannot read: the message names the folder or file, the line where there is one,
    and what was expected."""


@dataclass
class ResultFolder:
    path: str
    suite: data.Suite  # None for a sweep's folder
    sweeps: dict = field(default_factory=dict)  # {job id prefix ("sweeps/NAME/", "" for a sweep's folder): sweep.Sweep}
    provenance: dict = field(default_factory=dict)  # provenance.json, {} for a folder made before it existed
    engine_versions: dict = field(default_factory=dict)  # engines.json: {engine: its library's version}
    # provenance.json's engine_builds: {engine: {library_path, library_size_bytes, library_sha256, install_prefix,
    # header_version}}; None for a folder made before they were recorded
    engine_builds: dict = None
    scenario_digests: dict = field(default_factory=dict)  # {scenario file as the suite named it: digest}

    @property
    def configurations(self):
        """{job id: its run (member 0 of an ensemble), or a sweep's row under its prefix}, built once."""
        if self._configurations is None:
            self._configurations = {r["job_id"]: r for r in self.suite.runs} if self.suite else {}
            for prefix, s in self.sweeps.items():
                self._configurations.update({prefix + r["id"]: r for r in s.rows})
        return self._configurations

    _configurations: dict = None


def read_json(path):
    try:
        with open(path) as f:
            return json.load(f)
    except json.JSONDecodeError as e:
        raise CompareInputError(f"{path}:{e.lineno}: not JSON ({e.msg}); the folder is damaged") from None


def read_scenario_digests(path):
    """{scenario file: digest} over every suite.jsonl line (a study runs several suites into one folder).
    A line cut short by a kill (the last, without its line break) is skipped, as the suite does."""
    digests = {}
    if not os.path.exists(path):
        return digests
    with open(path) as f:
        text = f.read()
    lines = text.split("\n")
    for number, line in enumerate(lines[:-1], start=1):  # the part after the last line break is cut short
        try:
            record = json.loads(line)
        except json.JSONDecodeError as e:
            raise CompareInputError(f"{path}:{number}: not a suite's settings record ({e.msg}); the folder is damaged") from None
        files = record.get("settings", {}).get("scenario_files", {}) if isinstance(record, dict) else {}
        digests.update(files if isinstance(files, dict) else {})
    return digests


def read_engine_builds(path, provenance):
    """provenance.json's engine_builds ({engine: {key: value}}), None when the file predates them; a value of
    another shape is a CompareInputError naming the file."""
    builds = provenance.get("engine_builds") if isinstance(provenance, dict) else None
    if builds is None:
        return None
    if not isinstance(builds, dict) or not all(isinstance(b, dict) for b in builds.values()):
        raise CompareInputError(f"{path}: \"engine_builds\" is not an object of one object per engine "
                                "({engine: {library_path, library_size_bytes, library_sha256, ...}}); the folder is damaged")
    return builds


def read_folder(path):
    """The folder at `path`, or CompareInputError: not a folder, no runs.csv, a damaged record."""
    if not os.path.isdir(path):
        what = "not a folder" if os.path.exists(path) else "no such folder"
        raise CompareInputError(f"{path}: {what}; expected a result folder (a suite's or a study's, with runs.csv)")
    has_runs = os.path.exists(os.path.join(path, "runs.csv"))
    if not has_runs and not sweep.is_sweep(path):
        raise CompareInputError(f"{path}: not a result folder: it has no runs.csv (a suite's or a study's folder has "
                                "one) nor sweep.json (a sweep's)")
    try:
        folder = ResultFolder(path, data.read_runs(path) if has_runs else None)
        sweep_folders = {"": path} if not has_runs else {
            os.path.relpath(s, path) + "/": s for s in sorted(glob.glob(os.path.join(path, "sweeps", "*"))) if sweep.is_sweep(s)}
        folder.sweeps = {prefix: sweep.read(s) for prefix, s in sweep_folders.items()}
    except data.ResultsError as e:
        raise CompareInputError(str(e)) from None
    provenance = os.path.join(path, "provenance.json")
    if os.path.exists(provenance):
        folder.provenance = read_json(provenance)
        folder.engine_builds = read_engine_builds(provenance, folder.provenance)
    engines = os.path.join(path, "engines.json")
    if os.path.exists(engines):
        folder.engine_versions = {s.get("name", ""): s.get("version", "") for s in read_json(engines).get("simulators", [])}
    folder.scenario_digests = read_scenario_digests(os.path.join(path, "suite.jsonl"))
    for s in folder.sweeps.values():  # a sweep's settings (sweep.json) name its scenario file and its digest
        if s.settings.get("scenario_file") and s.settings.get("scenario_digest"):
            folder.scenario_digests[s.settings["scenario_file"]] = s.settings["scenario_digest"]
    return folder


def differences(base, new):
    """What differs between what made two folders, before what moved: [(what, base's, new's)], scenario
    files first (a file of the same name with other content makes every comparison of its runs moot)."""
    found = []
    for name in sorted(set(base.scenario_digests) & set(new.scenario_digests)):
        if base.scenario_digests[name] != new.scenario_digests[name]:
            found.append((f"scenario file {name}: its content differs", base.scenario_digests[name],
                          new.scenario_digests[name]))
    for name in sorted(set(base.engine_versions) | set(new.engine_versions)):
        a, b = base.engine_versions.get(name), new.engine_versions.get(name)
        if a != b:
            found.append((f"{name}'s library version", a or "not in the build", b or "not in the build"))
    found += build_differences(base, new)
    if not base.provenance or not new.provenance:
        if base.provenance or new.provenance:
            found.append(("provenance.json", "present" if base.provenance else "missing (an older folder)",
                          "present" if new.provenance else "missing (an older folder)"))
        return found
    for part in ("build", "machine"):
        a, b = base.provenance.get(part, {}), new.provenance.get(part, {})
        for key in sorted(set(a) | set(b)):
            if a.get(key) != b.get(key):
                found.append((f"{part} {key}", a.get(key), b.get(key)))
    return found


def library_file_text(build):
    """"sha256 ab12cd34ef56… (1234567 bytes)": a library file as a difference names it."""
    sha = build.get("library_sha256") or "unknown"
    return f"sha256 {sha[:12]}{'…' if len(sha) > 12 else ''} ({build.get('library_size_bytes')} bytes)"


def build_differences(base, new):
    """Which build of each engine's library ran, where both folders record it (provenance.json's engine_builds):
    a library file of other content, size or path even under the same version string (a rebuilt or patched
    library), the install prefix and the headers' version the adapter was built against."""
    if base.engine_builds is None or new.engine_builds is None:
        if (base.engine_builds is None) != (new.engine_builds is None) and base.provenance and new.provenance:
            said = {True: "not recorded (an older folder)", False: "recorded"}
            return [("each engine's library file", said[base.engine_builds is None], said[new.engine_builds is None])]
        return []
    found = []
    for name in sorted(set(base.engine_builds) & set(new.engine_builds)):
        a, b = base.engine_builds[name], new.engine_builds[name]
        if any(a.get(k) != b.get(k) for k in ("library_sha256", "library_size_bytes", "library_path")):
            a_text, b_text = library_file_text(a), library_file_text(b)
            if a.get("library_path") != b.get("library_path"):
                a_text, b_text = f"{a_text} at {a.get('library_path')}", f"{b_text} at {b.get('library_path')}"
            found.append((f"{name}'s library file", a_text, b_text))
        for key, what in (("install_prefix", "install prefix"), ("header_version", "headers' version")):
            if a.get(key) != b.get(key):
                found.append((f"{name}'s {what}", a.get(key), b.get(key)))
    return found


def same_machine(base, new):
    """Whether the two folders' runs were timed on machines alike (CPU model and cores); False when either
    folder does not say."""
    a, b = base.provenance.get("machine"), new.provenance.get("machine")
    if not a or not b:
        return False
    return all(a.get(k) == b.get(k) for k in ("cpu_model", "logical_cores"))
