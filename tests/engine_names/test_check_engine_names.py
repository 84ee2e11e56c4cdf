#!/usr/bin/env python3
"""scripts/check_engine_names.py catches what it is for, on fake trees: an engine named in code outside its
folder fails with the file and line (whatever the case, for a new engine too), while its own folder, the
allow-list and comments pass; a new engine added as its folder and one line passes, in a copy of this tree."""
import json
import pathlib
import shutil
import subprocess
import sys
import tempfile

CHECK = pathlib.Path(__file__).resolve().parents[2] / "scripts" / "check_engine_names.py"

GOOD = {
    "adapters/common/rig.h": "#pragma once\n",
    "adapters/ode/ode_rig.cpp": '#include <ode/ode.h>\nconst char* name = "ode";\n',
    "adapters/toy/toy_simulator.cpp": 'const char* name = "toy";\n',
    "adapters/CMakeLists.txt": "set(impactbench_all_engines ode toy)\n",
    "harness/suite/suite.cpp": "// an engine such as ODE or Toy may stop early\nint jobs = 2;\n",
    "scripts/run.sh": "# every engine, e.g. toy\nengines=$(impactbench engines --names)\n",
    "tests/toy_single_impact_test.cpp": 'auto s = make_simulator("toy");\n',
    "harness/episode.cpp": "int decode = 1;  // a word that holds an engine's name is no name\n",
}


def check(files: dict):
    with tempfile.TemporaryDirectory() as d:
        for name, text in files.items():
            path = pathlib.Path(d) / name
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(text)
        r = subprocess.run([sys.executable, str(CHECK), d], capture_output=True, text=True)
        return r.returncode, r.stdout


def expect_finding(extra: dict, words: list):
    code, out = check({**GOOD, **extra})
    assert code == 1, f"expected a finding for {extra}, got exit {code}:\n{out}"
    for w in words:
        assert w in out, f"'{w}' not in:\n{out}"


def main():
    code, out = check(GOOD)
    assert code == 0, out
    expect_finding({"harness/suite/suite.cpp": 'for (auto e : {"ode", "toy"}) run(e);\n'}, ["harness/suite/suite.cpp:1", "'ode'"])
    expect_finding({"reports/figures.py": 'COLOURS = {"TOY": "#123456"}\n'}, ["reports/figures.py:1", "'TOY'"])
    expect_finding({"scripts/run.sh": "for e in reference ode; do echo $e; done\n"}, ["scripts/run.sh:1"])
    # an engine's tests name their own engine only
    expect_finding({"tests/toy_single_impact_test.cpp": 'auto s = make_simulator("ode");\n'},
                   ["tests/toy_single_impact_test.cpp:1"])
    # an allowed file names engines; a file beside it does not get its allowance
    code, out = check({**GOOD, "scripts/install-deps.sh": "apt-get install libode-dev  # ode\nengine=ode\n"})
    assert code == 0, out
    expect_finding({"scripts/install-deps-extra.sh": "engine=ode\n"}, ["scripts/install-deps-extra.sh:1"])
    toy_engine_in_a_copy_of_the_tree()
    print("check_engine_names: every misplaced name caught, the clean tree passed, a toy engine added cleanly")


def toy_engine_in_a_copy_of_the_tree():
    """A new engine is its folder and one line: a copy of this repository with a toy engine, adapters/tinyphys/ (its
    descriptor, a simulator including its own library's header) and its name on the registering line
    passes both checkers; the same toy named in the harness fails the name check."""
    repository = CHECK.parents[1]
    with tempfile.TemporaryDirectory() as d:
        root = pathlib.Path(d) / "tree"
        shutil.copytree(repository, root, ignore=shutil.ignore_patterns("build*", ".git", "__pycache__"))
        toy = root / "adapters" / "tinyphys"
        toy.mkdir()
        (toy / "descriptor.json").write_text(json.dumps({
            "name": "tinyphys", "display_name": "TinyPhys", "summary": "a scripted toy engine", "packages": ["libtoy-dev"],
            "library_headers": "^tinyphyslib/", "colours": {"matched": "#101010", "injected": "#202020", "native": "#303030"},
            "diagnostics": []}))
        (toy / "tinyphys_simulator.h").write_text('#pragma once\n#include "model/simulator.h"\n')
        (toy / "tinyphys_simulator.cpp").write_text('#include <tinyphyslib/world.h>\n#include "adapters/tinyphys/tinyphys_simulator.h"\n'
                                              '#include "adapters/common/rig.h"\nconst char* kName = "tinyphys";\n')
        registering = root / "adapters" / "CMakeLists.txt"
        text = registering.read_text()
        line = next(l for l in text.splitlines() if l.startswith("set(impactbench_all_engines "))
        registering.write_text(text.replace(line, line[:-1] + " tinyphys)"))
        for checker in ("check_layers.py", "check_engine_names.py"):
            r = subprocess.run([sys.executable, str(root / "scripts" / checker), str(root)], capture_output=True, text=True)
            assert r.returncode == 0, f"{checker} refused the new engine:\n{r.stdout}"
        (root / "harness" / "tinyphys_defaults.cpp").write_text('const char* kEngine = "tinyphys";\n')
        r = subprocess.run([sys.executable, str(root / "scripts" / "check_engine_names.py"), str(root)],
                           capture_output=True, text=True)
        assert r.returncode == 1 and "harness/tinyphys_defaults.cpp:1" in r.stdout, r.stdout


if __name__ == "__main__":
    main()
