#!/usr/bin/env python3
"""An engine is its folder and one line: no source or script outside adapters/<engine>/ names an engine,
so that adding one (docs/adding-an-engine.md) touches no list elsewhere. The engines are the folders of
adapters/ (but common/); a name counts as a whole word, in any case, in code: comments (C++ `//`, `#` in
Python, shell, CMake and TOML) may explain an engine's behaviour and are not read.

    scripts/check_engine_names.py [ROOT]    exit 0: no engine named out of place; 1: each place listed

ALLOWED are the places that must name engines, each with why. TO_REWRITE are files that named engines
when this check came and are yet to read them from the catalog (simulator_names(), `impactbench engines
--names`, engines.json); the list only shrinks: a listed file that no longer names an engine fails the
check until it leaves the list.
"""
import fnmatch
import pathlib
import re
import sys

ALLOWED = {
    "adapters/CMakeLists.txt": "the one line that registers the engines",
    "scripts/install-deps.sh": "the Debian packages to install, engine by engine",
    "studies/*.toml": "a study's named configurations and the engines a part leaves out, with why (data, not code)",
    "tests/{engine}_*_test.cpp": "an engine's own tests (label engine:<engine>)",
    "tests/agreement_table.h": "the agreement test's data: each engine's step and tolerances, with why",
    "tests/ctest-cost-data.txt": "ctest's measured cost of each test, engine tests among them",
    "tests/layering/test_check_layers.py": "check_layers' own test, on fake trees with engine folders",
    "tests/engine_names/test_check_engine_names.py": "this check's own test, on fake trees",
}
TO_REWRITE = [
    "bench/harness_overhead_benchmark.cpp", "bench/timing_check.sh", "cli/main.cpp",
    "reports/impactbench_report/first_screen.py", "reports/tests/test_garbled_results.py",
    "reports/tests/test_page_in_chromium.py", "reports/tests/test_performance_section.py", "reports/tests/test_report.py",
    "reports/tests/test_sweep_report.py", "scripts/check-mutations.sh",
    "tests/contact_law_fit_test.cpp",
    "tests/output_errors_test.cpp", "tests/progress_estimate_test.cpp", "tests/recorded_run_test.cpp",
    "tests/resume_repair_test.cpp", "tests/run_command_test.cpp", "tests/slurm/test_slurm_cluster.sh",
    "tests/suite_interruption_test.cpp", "tests/suite_records_test.cpp", "tests/suite_sharding_test.cpp",
]
SUFFIXES = (".h", ".cpp", ".py", ".sh", ".sbatch", ".cmake", ".toml")
HASH_COMMENT = re.compile(r"(^|\s)#(?!include|define|undef|if|endif|else|elif|pragma).*")


def engines(root: pathlib.Path):
    return sorted(p.name for p in (root / "adapters").glob("*") if p.is_dir() and p.name != "common")


def allowed(relative: str, named: str):
    """Whether `relative` may name the engine `named`: a pattern with {engine} allows that engine alone."""
    return any(fnmatch.fnmatchcase(relative, pattern.format(engine=named.lower())) for pattern in ALLOWED)


def code_of(line: str, cpp: bool):
    return line.split("//", 1)[0] if cpp else HASH_COMMENT.sub("", line)


def sources(root: pathlib.Path):
    for path in sorted(root.rglob("*")):
        relative = path.relative_to(root)
        if relative.parts[0].startswith(("build", ".")) or not path.is_file():
            continue
        if path.suffix in SUFFIXES or path.name == "CMakeLists.txt":
            yield relative.as_posix(), path


def findings(root: pathlib.Path):
    names = engines(root)
    if not names:
        return [f"{root}/adapters: no engine folder (is this the repository?)"]
    word = re.compile(r"\b(" + "|".join(map(re.escape, names)) + r")\b", re.IGNORECASE)
    found, naming = [], set()
    for relative, path in sources(root):
        parts = relative.split("/")
        if parts[0] == "adapters" and len(parts) > 2 and parts[1] in names:
            continue  # an engine's own folder
        cpp = path.suffix in (".h", ".cpp")
        for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
            misplaced = [m for m in word.finditer(code_of(line, cpp)) if not allowed(relative, m.group(1))]
            if word.search(code_of(line, cpp)):
                naming.add(relative)
            if misplaced and relative not in TO_REWRITE:
                m = misplaced[0]
                found.append(f"{relative}:{number}: names the engine '{m.group(1)}' outside adapters/{m.group(1).lower()}/; "
                             "read the engines from the catalog (docs/adding-an-engine.md)")
    for relative in TO_REWRITE:
        if (root / relative).exists() and relative not in naming:
            found.append(f"{relative}: names no engine any more; remove it from TO_REWRITE in scripts/check_engine_names.py")
    return found


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent)
    found = findings(root)
    for f in found:
        print(f)
    print(f"check_engine_names: {len(found)} place(s) to fix in {root}" if found else
          f"check_engine_names: no engine named outside its folder in {root} ({len(TO_REWRITE)} files still to rewrite)")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
