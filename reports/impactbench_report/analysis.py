"""What the tables and figures pick from the runs: each configuration's best and largest stable time
step, and which engine wins at equal run time."""

import math

# The headline errors against the continuous-beam reference (the whole error a user would see) and
# their names in runs.csv. Impacts per cycle is a difference, the others relative errors.
HEADLINE = [
    ("sensor peak, frame 1", "frame1_sensor_peak_relative_error", "relative"),
    ("contact duration", "contact_duration_relative_error", "relative"),
    ("impacts per cycle", "impacts_per_cycle_difference", "difference"),
]


def error(run, column, against="vs_reference_"):
    return abs(run.number(against + column))


def score(run, against="vs_reference_"):
    """The largest headline error of a run (NaN-free errors only); inf when it has none."""
    errors = [error(run, column, against) for _, column, _ in HEADLINE]
    errors = [e for e in errors if not math.isnan(e)]
    return max(errors) if errors else math.inf


def configurations(runs):
    """Engine configurations (engine + options) other than the references, in first-seen order."""
    seen = []
    for r in runs:
        if r["engine"] != "reference" and r.config not in seen:
            seen.append(r.config)
    return seen


def runs_of_config(runs, config):
    return sorted((r for r in runs if r.config == config), key=lambda r: r.number("time_step_s"))


def best_step(runs, config):
    """The stable run with the smallest headline error (then the cheapest)."""
    stable = [r for r in runs_of_config(runs, config) if r.stable]
    if not stable:
        return None
    return min(stable, key=lambda r: (score(r), r.number("wall_time_s")))


def largest_stable_step(runs, config):
    stable = [r for r in runs_of_config(runs, config) if r.stable]
    return max(stable, key=lambda r: r.number("time_step_s")) if stable else None


def winner_at_equal_cost(runs):
    """(budget [s], config, score) for the engine with the smallest headline error among runs that cost at
    most the budget, the budget being the largest of the configurations' cheapest stable runs, so that
    every configuration has a run within it. None when there is nothing to compare."""
    configs = configurations(runs)
    cheapest = []
    for config in configs:
        stable = [r for r in runs_of_config(runs, config) if r.stable and not math.isinf(score(r))]
        if stable:
            cheapest.append(min(r.number("wall_time_s") for r in stable))
    if len(cheapest) < 2:
        return None
    budget = max(cheapest)
    best = None
    for config in configs:
        within = [r for r in runs_of_config(runs, config)
                  if r.stable and r.number("wall_time_s") <= budget and not math.isinf(score(r))]
        if within:
            run = min(within, key=score)
            if best is None or score(run) < best[2]:
                best = (budget, config, score(run))
    return best
