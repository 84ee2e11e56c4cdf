"""The engines that made a result folder, from its engines.json (written by the suite and the sweep from
each simulator's descriptor, docs/adding-an-engine.md): names for people, colours per contact path,
Debian packages and the documented diagnostics keys. Nothing here names an engine: a folder from before
engines.json existed shows each engine under its catalog name, in a spare colour, with no engine settings."""

import glob
import json
import os

REPOSITORY = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
_descriptors = {}  # name -> descriptor of the folder being reported


def read(folder):
    """{name: descriptor} from folder/engines.json; {} when the folder has none or it is unreadable (an
    old folder: the report falls back to the names, a wrong file must not stop the report)."""
    path = os.path.join(folder, "engines.json")
    try:
        with open(path) as f:
            document = json.load(f)
        return {d["name"]: d for d in document.get("simulators", []) if isinstance(d, dict) and "name" in d}
    except (OSError, ValueError, AttributeError):
        return {}


def use(folder):
    """Makes folder's engines the ones every later call describes (the report reads one folder)."""
    _descriptors.clear()
    _descriptors.update(read(folder))


def descriptor(engine):
    return _descriptors.get(engine, {})


def display_name(engine):
    return descriptor(engine).get("display_name") or engine


def colour(engine, path):
    """The engine's own colour for a contact path, or None (the caller picks a spare one)."""
    return descriptor(engine).get("colours", {}).get(path)


def recommended(engine):
    """The engine's authors' recommended configuration (engines.json "recommended": per law its options and
    time step, and every setting with its source), or {} when the folder's engines.json has none."""
    return descriptor(engine).get("recommended") or {}


def repository_packages():
    """The Debian packages of every engine of this checkout (adapters/*/descriptor.json), in folder order:
    what bench/machine.sh records and the performance section shows."""
    packages = []
    for path in sorted(glob.glob(os.path.join(REPOSITORY, "adapters", "*", "descriptor.json"))):
        with open(path) as f:
            packages += [p for p in json.load(f).get("packages", []) if p not in packages]
    return packages
