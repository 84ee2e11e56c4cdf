#!/usr/bin/env python3
"""scripts/check_layers.py catches what it is for: a tree with one wrong-way include, a project header named
without its folder, or an engine's header outside its adapter fails with the file, the line and the rule; the
same tree without them passes; a new engine's folder is checked with or without its descriptor.json."""
import pathlib
import subprocess
import sys
import tempfile

CHECK = pathlib.Path(__file__).resolve().parents[2] / "scripts" / "check_layers.py"


def tree(root: pathlib.Path, files: dict):
    for name, text in files.items():
        path = root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)


def check(files: dict):
    with tempfile.TemporaryDirectory() as d:
        tree(pathlib.Path(d), files)
        r = subprocess.run([sys.executable, str(CHECK), d], capture_output=True, text=True)
        return r.returncode, r.stdout


GOOD = {
    "model/scenario.h": "#pragma once\n",
    "physics/beam_modes.h": '#include "model/scenario.h"\n',
    "reference/reference_solver.h": '#include "physics/beam_modes.h"\n',
    "adapters/common/rig.h": '#include "physics/beam_modes.h"\n',
    "adapters/ode/ode_rig.h": '#include <ode/ode.h>\n#include "adapters/common/rig.h"\n',
    # the engines' library headers come from their descriptors, as in the real tree
    "adapters/ode/descriptor.json": '{"name": "ode", "library_headers": "^ode/"}\n',
    "adapters/mujoco/descriptor.json": '{"name": "mujoco", "library_headers": "^mujoco/"}\n',
    "simulators/catalog.h": '#include "reference/reference_solver.h"\n#include "adapters/ode/ode_rig.h"\n',
    "harness/scoring/metrics.h": '#include "model/scenario.h"\n#include "physics/beam_modes.h"\n',
    "harness/suite/suite.h": '#include "harness/scoring/metrics.h"\n',
    "cli/main.cpp": '#include "simulators/catalog.h"\n#include "harness/suite/suite.h"\n',
    "tests/anything_test.cpp": '#include "adapters/ode/ode_rig.h"\n',
}


def expect_breach(extra: dict, words: list):
    code, out = check({**GOOD, **extra})
    assert code == 1, f"expected a breach for {extra}, got exit {code}:\n{out}"
    for w in words:
        assert w in out, f"'{w}' not in:\n{out}"


def main():
    code, out = check(GOOD)
    assert code == 0, out
    # the harness is above the simulators but must not include them, nor the reference
    expect_breach({"harness/suite/suite.cpp": '#include "model/scenario.h"\n#include "reference/reference_solver.h"\n'},
                  ["harness/suite/suite.cpp:2", "reference/reference_solver.h", "harness/suite may include harness/jobs"])
    # the harness's own folders: a lower one never includes a higher one, and a sweep never a suite
    expect_breach({"harness/scoring/metrics.cpp": '#include "harness/suite/suite.h"\n'},
                  ["harness/scoring/metrics.cpp:1", "harness/scoring includes", "harness/suite"])
    expect_breach({"harness/sweep/sweep_plan.cpp": '#include "harness/suite/suite.h"\n'}, ["harness/sweep/sweep_plan.cpp:1"])
    expect_breach({"physics/link_chain.cpp": '#include "harness/scoring/metrics.h"\n'}, ["physics/link_chain.cpp:1"])
    expect_breach({"reference/free_flight.cpp": '#include "adapters/common/rig.h"\n'}, ["reference/free_flight.cpp:1"])
    expect_breach({"adapters/ode/ode_contact.cpp": '#include "simulators/catalog.h"\n'}, ["adapters/ode/ode_contact.cpp:1"])
    expect_breach({"adapters/bullet/world.cpp": '#include "adapters/ode/ode_rig.h"\n'}, ["adapters/bullet/world.cpp:1"])
    expect_breach({"harness/jobs/run_job.cpp": '#include "scenario.h"\n'}, ['"scenario.h" names no folder', "model/scenario.h"])
    expect_breach({"harness/jobs/run_job.cpp": "#include <mujoco/mujoco.h>\n"}, ["only adapters/mujoco may include it"])
    # a new engine is its folder: without a descriptor yet its layers are checked (no KeyError) ...
    code, out = check({**GOOD, "adapters/toy/toy_simulator.cpp": '#include "adapters/common/rig.h"\n',
                       "simulators/catalog.cpp": '#include "adapters/toy/toy_simulator.h"\n',
                       "adapters/toy/toy_simulator.h": "#pragma once\n"})
    assert code == 0, out
    expect_breach({"adapters/toy/toy_simulator.cpp": '#include "harness/scoring/metrics.h"\n'}, ["adapters/toy/toy_simulator.cpp:1"])
    # ... and with one, its library's headers belong to its folder alone
    toy = {"adapters/toy/descriptor.json": '{"name": "toy", "library_headers": "^toylib/"}\n',
           "adapters/toy/toy_simulator.cpp": "#include <toylib/world.h>\n"}
    code, out = check({**GOOD, **toy})
    assert code == 0, out
    expect_breach({**toy, "adapters/ode/ode_contact.cpp": "#include <toylib/world.h>\n"}, ["only adapters/toy may include it"])
    print("check_layers: every breach caught, the clean tree passed")


if __name__ == "__main__":
    main()
