"""A configuration unstable in both folders, compared by when and why it went unstable: the verdict alone
("unstable -> unstable") would hide a run that now blows up in the first second instead of the tenth.

Where it is recorded: runs.csv's `reason` says what and when ("energy grew without input from 0.003 J to
0.0041 J at t = 2.3 s", harness/scoring/verdict.cpp and adapters/common/fixed_step_loop.cpp), and a
fixed-step run stopped early has simulated_time_s = steps x step short of duration_s. The time is the
reason's "at t = ", else the simulated time where the run stopped early. Why is the reason with its numbers
masked ("energy grew without input from # J to # J"), a frame's number kept.

Members are paired by ensemble start. A time that differs by more than TIME_SLACK_SAMPLES of the run's step
or sample interval, whichever is longer, or another reason, moved: earlier is regressed, later improved,
another reason at the same time neutral."""

import math
import re
from dataclasses import dataclass

from impactbench_report import ensemble_groups

# Two runs of one configuration that go unstable "at the same time" may still be a step or a sample apart
# (the check runs on samples; a rounding moves the step that crosses a bound).
TIME_SLACK_SAMPLES = 2
AT_TIME = re.compile(r"at t = ([-+0-9.eE]+) s")
NUMBER = re.compile(r"(?<!frame )[-+]?\d+(\.\d*)?([eE][-+]?\d+)?")


@dataclass
class InstabilityChange:
    start: int  # the ensemble start of the pair that moved (0: the run itself)
    base_time_s: float
    new_time_s: float
    base_reason: str
    new_reason: str
    slack_s: float
    judgement: str  # "regressed" (earlier), "improved" (later), "moved" (another reason), "unchanged"

    @property
    def moved(self):
        return self.judgement != "unchanged"

    def text(self):
        when = f"unstable at t = {self.base_time_s:.4g} s -> {self.new_time_s:.4g} s"
        why = "" if kind(self.base_reason) == kind(self.new_reason) else \
            f"; why: '{self.base_reason}' -> '{self.new_reason}'"
        member = f" (start {self.start})" if self.start else ""
        return f"{when}{why}{member}: {self.judgement} (a step or sample: ±{self.slack_s:.2g} s)"


def unstable_at(run):
    """When the run went unstable: the reason's time, else where a fixed-step run stopped; NaN if neither."""
    match = AT_TIME.search(run["reason"] or "")
    if match:
        try:
            return float(match.group(1))
        except ValueError:
            pass
    simulated, duration = run.number("simulated_time_s"), run.number("duration_s")
    return simulated if simulated < duration else math.nan


def kind(reason):
    """A reason without its numbers: what went wrong, not by how much."""
    return NUMBER.sub("#", AT_TIME.sub("", reason or "")).strip()


def slack_s(run):
    step, rate = run.number("time_step_s"), run.number("output_rate_hz")
    longest = max(x for x in (step if step > 0 else 0.0, 1 / rate if rate > 0 else 0.0, 0.0))
    return TIME_SLACK_SAMPLES * longest


def judge_pair(start, a, b):
    ta, tb = unstable_at(a), unstable_at(b)
    slack = max(slack_s(a), slack_s(b))
    if not (math.isnan(ta) or math.isnan(tb)) and abs(tb - ta) > slack:
        judgement = "regressed" if tb < ta else "improved"
    elif kind(a["reason"]) != kind(b["reason"]):
        judgement = "moved"
    else:
        judgement = "unchanged"
    return InstabilityChange(start, ta, tb, a["reason"], b["reason"], slack, judgement)


def compare(base_members, new_members):
    """The InstabilityChange of the first pair of members (by start) unstable in both folders that moved,
    earlier ones first; else that of the first pair unstable in both; None when no pair is."""
    new_by_start = {ensemble_groups.start_of(m): m for m in new_members}
    pairs = [(ensemble_groups.start_of(a), a, new_by_start.get(ensemble_groups.start_of(a))) for a in base_members]
    found = [judge_pair(s, a, b) for s, a, b in pairs if b is not None and a["verdict"] == b["verdict"] == "unstable"]
    if not found:
        return None
    order = {"regressed": 0, "improved": 1, "moved": 2, "unchanged": 3}
    return min(found, key=lambda c: (order[c.judgement], c.start))
