#!/usr/bin/env python3
"""The layering rule, checked on every #include of the sources (run by the test command).

    model <- physics <- reference, adapters <- simulators <- harness <- cli
    harness: scoring <- records <- jobs <- suite, sweep <- study <- validation

A folder's files may include their own folder and the folders this table allows, nothing else; the
harness is above the simulators in the chain of commands but links only the model and the physics: it
receives the simulators through a catalog (model/simulator.h). Each engine's library headers (the
"library_headers" pattern of adapters/<engine>/descriptor.json) are included only in its own adapter
folder; the engines are the folders of adapters/, so a new one needs no line here. Includes carry their folder ("model/scenario.h"), so a project header
named without one is an error too. tests/, bench/ and fuzz/ may include anything.

    scripts/check_layers.py [ROOT]     exit 0: every include follows the rule; 1: each breach listed
"""
import json
import pathlib
import re
import sys

BASE = {
    "model": set(),
    "physics": {"model"},
    "reference": {"model", "physics"},
    "adapters/common": {"model", "physics"},
    "cli": {"model", "physics", "reference", "simulators", "harness"},  # the reference for `modes` (its mode options)
}
# The harness's folders, lowest first: each may include the model, the physics and the folders before it.
HARNESS = ["scoring", "records", "jobs", "suite", "sweep", "study", "validation"]
for i, folder in enumerate(HARNESS):
    BASE[f"harness/{folder}"] = {"model", "physics", *(f"harness/{below}" for below in HARNESS[:i])}
    # a suite and a sweep are siblings: neither includes the other
BASE["harness/sweep"].discard("harness/suite")
BASE["cli"] |= {f"harness/{folder}" for folder in HARNESS}


def engines(root: pathlib.Path):
    """The engines of the tree: every folder of adapters/ but common/ (docs/adding-an-engine.md), with the
    pattern of its library's angle-bracket includes from its descriptor.json ("library_headers"; none
    when the folder has no descriptor yet: its includes are then checked for layers only)."""
    found = {}
    for folder in sorted(p for p in (root / "adapters").glob("*") if p.is_dir() and p.name != "common"):
        descriptor = folder / "descriptor.json"
        pattern = ""
        if descriptor.exists():
            try:
                pattern = json.loads(descriptor.read_text()).get("library_headers", "")
            except ValueError as error:
                raise SystemExit(f"check_layers: {descriptor}: not JSON ({error})")
        found[folder.name] = re.compile(pattern) if pattern else None
    return found


def allowed(engine_names):
    """What each layer may include, the engines' folders among them."""
    table = dict(BASE)
    for e in engine_names:
        table[f"adapters/{e}"] = {"model", "physics", "adapters/common"}
    table["simulators"] = {"model", "physics", "reference", "adapters/common", *(f"adapters/{e}" for e in engine_names)}
    return table


INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')


def layer_of(relative: pathlib.PurePosixPath, table):
    parts = relative.parts
    if parts[0] in ("adapters", "harness") and len(parts) > 2:
        return f"{parts[0]}/{parts[1]}"
    return parts[0] if parts[0] in table and len(parts) > 1 else None


def breaches(root: pathlib.Path):
    engine_headers = engines(root)
    table = allowed(engine_headers)
    headers = {p.relative_to(root).as_posix() for p in root.rglob("*.h") if "build" not in p.relative_to(root).parts[0]}
    for path in sorted(root.rglob("*")):
        if path.suffix not in (".h", ".cpp") or path.relative_to(root).parts[0].startswith("build"):
            continue
        relative = pathlib.PurePosixPath(path.relative_to(root).as_posix())
        layer = layer_of(relative, table)
        if layer is None:
            continue
        for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
            m = INCLUDE.match(line)
            if not m:
                continue
            quote, name = m.groups()
            where = f"{relative}:{number}"
            if quote == "<":
                for engine, pattern in engine_headers.items():
                    if pattern and pattern.match(name) and layer != f"adapters/{engine}":
                        yield f"{where}: <{name}> is {engine}'s; only adapters/{engine} may include it"
                continue
            target = layer_of(pathlib.PurePosixPath(name), table)
            if target is None:
                if "/" not in name and any(h.endswith("/" + name) for h in headers):
                    yield f'{where}: "{name}" names no folder; write it with its layer, e.g. "{next(h for h in headers if h.endswith("/" + name))}"'
                continue
            if name not in headers:
                yield f'{where}: "{name}" is not a header of this tree'
            elif target != layer and target not in table[layer]:
                may = ", ".join(sorted(table[layer])) or "nothing below it"
                yield f'{where}: {layer} includes "{name}" ({target}); {layer} may include {may}'


def longest_files(root: pathlib.Path, limit=400):
    """Source files over `limit` lines (the style's "about 400"): listed, not failed."""
    long = []
    for path in root.rglob("*"):
        relative = path.relative_to(root)
        if path.suffix in (".h", ".cpp", ".py") and not relative.parts[0].startswith(("build", ".")):
            lines = sum(1 for _ in path.open(errors="replace"))
            if lines > limit:
                long.append((lines, relative.as_posix()))
    return sorted(long, reverse=True)


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent)
    for lines, name in longest_files(root):
        print(f"check_layers: note: {name} has {lines} lines (the style asks for about 400)")
    found = list(breaches(root))
    for b in found:
        print(b)
    print(f"check_layers: {len(found)} include(s) against the layering rule in {root}" if found
          else f"check_layers: every include in {root} follows model <- physics <- reference, adapters <- simulators <- harness <- cli")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
