"""The machine a results folder's runs ran on, as the report names it: its provenance.json's "machine" (cpu_model,
logical_cores, memory_bytes, os; written by every suite, sweep, study and run, docs/results.md). A folder older
than provenance.json does not record it: the report then names the machine that draws it, and says so."""

import json
import os
import platform
from dataclasses import dataclass


@dataclass
class Machine:
    description: str  # "AMD EPYC x 2 cores, 23.5 GiB, Linux 6.1.0"
    cores: int  # logical cores, or None where not known
    recorded: bool  # from provenance.json (the machine that ran); False: the machine drawing the report

    @property
    def line(self):
        """The report's machine line (the page's "What ran", summary.json's suite.machine)."""
        if self.recorded:
            return f"{self.description} (the machine the runs ran on, from provenance.json)"
        return (f"{self.description} (the machine that made this report: the results folder has no provenance.json "
                "naming the one the runs ran on)")

    @property
    def stamp(self):
        """The machine as a figure's caption names it."""
        return f"ran on {self.description}" if self.recorded else f"drawn on {self.description} (runs' machine not recorded)"


def describe(machine):
    """'AMD EPYC x 2 cores, 23.5 GiB, Linux 6.1.0' from provenance.json's keys (those present)."""
    parts = [f"{machine.get('cpu_model') or '?'} x {machine.get('logical_cores') or '?'} cores"]
    if isinstance(machine.get("memory_bytes"), (int, float)) and machine["memory_bytes"] > 0:
        parts.append(f"{machine['memory_bytes'] / 2 ** 30:.1f} GiB")
    if machine.get("os"):
        parts.append(str(machine["os"]))
    return ", ".join(parts)


def recorded(folder):
    """provenance.json's "machine" object in folder, or None (no file, not JSON, no machine in it)."""
    try:
        with open(os.path.join(folder, "provenance.json")) as f:
            machine = json.load(f).get("machine")
    except (OSError, ValueError, AttributeError):
        return None
    return machine if isinstance(machine, dict) and machine else None


def this_machine():
    """The machine running this, with provenance.json's keys (its memory not read)."""
    model = ""
    try:
        with open("/proc/cpuinfo") as f:
            model = next((line.split(":", 1)[1].strip() for line in f if line.startswith("model name")), "")
    except OSError:
        pass
    return {"cpu_model": model or platform.processor(), "logical_cores": os.cpu_count(),
            "os": f"{platform.system()} {platform.release()}"}


def of_results(folder):
    """The Machine of a results folder: the one its provenance.json records, else this one (recorded False)."""
    machine = recorded(folder)
    found = machine is not None
    machine = machine if found else this_machine()
    cores = machine.get("logical_cores")
    return Machine(describe(machine), cores if isinstance(cores, int) and cores > 0 else None, found)
