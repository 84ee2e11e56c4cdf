#!/usr/bin/env python3
"""An engine is its folder and one line: no source or script outside adapters/<engine>/ names an engine,
so that adding one (docs/adding-an-engine.md) touches no list elsewhere. The engines are the folders of
adapters/ (but common/); a name counts as a whole word, in any case, in code: comments (C++ `//`, `#` in
Python, shell, CMake and TOML) may explain an engine's behaviour and are not read.

    scripts/check_engine_names.py [ROOT]    exit 0: no engine named out of place; 1: each place listed

ALLOWED are the places that must name engines, each with why; everything else reads the engines from the
catalog (simulator_names() and the descriptors in C++, tests/catalog_engines.h in tests, `impactbench
engines --names` in scripts, engines.json in the report).
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
    "bench/harness_overhead_benchmark.cpp": "the bare loops the harness is timed against, each written in one engine's "
                                            "own library (an engine without one is simply not in this benchmark)",
    "bench/siconos_*": "the second Newton reference is written in that engine's own library, as "
                       "harness_overhead_benchmark names engines (issue 49; its CMake in siconos_reference.cmake)",
    "bench/reference_siconos.py": "the second Newton reference's comparison: it runs bench/siconos_reference",
    "bench/tests/test_siconos_reference.py": "the second Newton reference's test",
    "bench/run-benchmarks.sh": "runs the second Newton reference's comparison (bench/reference_siconos.py) beside "
                               "the Google Benchmarks, for the report's performance section",
    "scripts/check-mutations.sh": "issue 20's mutations, each a line of source: one is in an engine's contact mapping",
}
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
    found = []
    for relative, path in sources(root):
        parts = relative.split("/")
        if parts[0] == "adapters" and len(parts) > 2 and parts[1] in names:
            continue  # an engine's own folder
        cpp = path.suffix in (".h", ".cpp")
        for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
            misplaced = [m for m in word.finditer(code_of(line, cpp)) if not allowed(relative, m.group(1))]
            if misplaced:
                m = misplaced[0]
                found.append(f"{relative}:{number}: names the engine '{m.group(1)}' outside adapters/{m.group(1).lower()}/; "
                             "read the engines from the catalog (docs/adding-an-engine.md)")
    return found


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent)
    found = findings(root)
    for f in found:
        print(f)
    print(f"check_engine_names: {len(found)} place(s) to fix in {root}" if found else
          f"check_engine_names: no engine named outside its folder in {root}")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
