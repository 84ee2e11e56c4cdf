#!/usr/bin/env python3
"""A sixth engine touches only adapters/<name>/ and the one registering line (docs/adding-an-engine.md).

A copy of this tree gets the toy engine of tests/new_engine/toyphys/ as adapters/toyphys/ and its name on
the line `set(impactbench_all_engines ...)`, nothing else. Then, in the copy:
  - the layering and engine-name checks pass (scripts/check_layers.py, scripts/check_engine_names.py);
  - it configures and builds the impactbench command with the toy as its only engine;
  - the catalog lists it, with its descriptor's display name and default time step (engines.json);
  - `all` in a study means the reference and the toy;
  - the toy runs the published free vibration with the injected Hertz law and the shared fixed-step loop
    judges and scores it: its impacts and frame 2's peak displacement (what the impact gave it) agree with the
    reference's within 5 % (the toy's linearised chain has the beam's first frequency within 0.5 %).
Usage: test_new_engine.py BUILD_FOLDER (a scratch folder; the copy and its build go there).
"""
import json
import os
import pathlib
import shutil
import subprocess
import sys

HERE = pathlib.Path(__file__).resolve().parent
REPOSITORY = HERE.parents[1]


def run(command, **kwargs):
    r = subprocess.run(command, capture_output=True, text=True, **kwargs)
    assert r.returncode == 0, f"{' '.join(map(str, command))} exited {r.returncode}:\n{r.stdout}\n{r.stderr}"
    return r.stdout


def add_the_toy(root: pathlib.Path):
    # the tree as a user has it, without this test's own copy of the toy
    shutil.copytree(REPOSITORY, root, ignore=shutil.ignore_patterns("build*", ".git", "__pycache__", "new_engine"))
    shutil.copytree(HERE / "toyphys", root / "adapters" / "toyphys")
    registering = root / "adapters" / "CMakeLists.txt"
    text = registering.read_text()
    line = next(l for l in text.splitlines() if l.startswith("set(impactbench_all_engines "))
    registering.write_text(text.replace(line, line[:-1] + " toyphys)"))


def summary_of(impactbench, scenario, out, *arguments):
    run([impactbench, "run", scenario, "--out", out, *arguments])
    return json.loads((out / "summary.json").read_text())


def main():
    scratch = pathlib.Path(sys.argv[1]).resolve()
    shutil.rmtree(scratch, ignore_errors=True)
    root, build = scratch / "tree", scratch / "build"
    add_the_toy(root)
    for checker in ("check_layers.py", "check_engine_names.py"):
        run([sys.executable, root / "scripts" / checker, root])

    # -O0 without debug information: this build is compiled once and runs for seconds, and compiling is what costs
    run(["cmake", "-S", root, "-B", build, "-G", "Ninja", "-DIMPACTBENCH_ENGINES=toyphys",
         "-DCMAKE_BUILD_TYPE=RelWithDebInfo", "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O0"])
    run(["cmake", "--build", build, "--target", "impactbench", "-j", str(os.cpu_count() or 1)])
    impactbench = build / "cli" / "impactbench"

    assert run([impactbench, "engines", "--names"]).strip() == "reference,toyphys"
    engines = json.loads(run([impactbench, "engines", "--json"]))
    toy = next(e for e in engines["simulators"] if e["name"] == "toyphys")
    assert toy["display_name"] == "ToyPhys", toy
    # its default step, from its descriptor alone: the adapter is compiled with it and engines.json shows it
    assert toy["default_time_step_s"] == 2e-5, toy
    # a study of every engine of the build (the shipped studies also name engines for named configurations)
    study = scratch / "every-engine.toml"
    study.write_text('[[suite]]\nscenarios = ["scenarios/paper/free_vibration.toml"]\nengines = "all"\n')
    plan = run([impactbench, "study", study, "--plan"], cwd=root)
    assert "engines reference,toyphys;" in plan, plan

    scenario = root / "scenarios" / "paper" / "free_vibration.toml"
    window = ["--law", "hertz", "--duration", "0.3", "--window", "0.3"]
    reference = summary_of(impactbench, scenario, scratch / "reference", "--engine", "reference", *window)
    engine = summary_of(impactbench, scenario, scratch / "toyphys", "--engine", "toyphys",
                        "--option", "contact=injected", "--dt", "1e-5", *window)
    assert engine["engine"] == "toyphys" and engine["verdict"] == "ok", engine
    assert engine["impacts"] == reference["impacts"] > 0, (engine["impacts"], reference["impacts"])
    # frame 2 moves by what the impact gave it alone
    peak, peak_reference = engine["frame2_peak_displacement_m"], reference["frame2_peak_displacement_m"]
    assert abs(peak / peak_reference - 1) < 0.05, (peak, peak_reference)
    shutil.rmtree(scratch)
    print("a new engine: its folder and one line; checked, built, listed, in `all`, run and scored")


if __name__ == "__main__":
    main()
