#!/usr/bin/python3
"""Puts two result folders side by side (what `impactbench compare` runs):

    reports/compare.py BASE NEW [MORE ...] [--json FILE] [--markdown FILE] [--html DIR] [--cost-across-machines]
                       [--cost-noise FRACTION]

prints what differs between what made the folders (provenance.json, engine versions, scenario files) and
how they were run (alike.py), then what moved beyond the noise, by job (impactbench_compare/changes.py says
which noise), each judged improved, regressed or neither (judgement.py); writes the JSON, the Markdown, and
an HTML page with a figure per moved configuration (DIR/compare.html, DIR/compare.md).
With more than two folders (a history: one per engine version, say), each folder is compared with the next,
and --html draws each configuration that moved along them (DIR/history.html; impactbench_compare/history.py).
Exit 0: nothing moved; 1: something moved beyond the noise and nothing regressed (improved, or moves that
are neither: an appeared configuration, a per-impact distribution, an error as large); 2: bad input (a
folder that is not a result folder, a damaged record, folders of different kinds, or folders whose every
shared configuration was run otherwise: named); 3: a file could not be written; 4: something regressed (a
CI job gates on 4); 70: this script failed."""

import argparse
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from impactbench_compare import alike, changes, folders, judgement, writers  # noqa: E402
from impactbench_report import metric_catalog  # noqa: E402

# a failure of this script itself exits otherwise (an uncaught exception: 1 would read as "moved")
EXIT_NOTHING_MOVED, EXIT_MOVED, EXIT_BAD_INPUT, EXIT_OUTPUT_ERROR, EXIT_REGRESSED, EXIT_FAILED = 0, 1, 2, 3, 4, 70


def exit_code(found, refused=()):
    """found: every configuration judged (changes.compare), of one comparison or of each step of a history;
    refused: the (base, new) pairs of folders whose configurations were all run otherwise (alike.py)."""
    for base, new in refused:
        print(f"impactbench: {base.path} and {new.path} were run otherwise (listed above: not comparable): no "
              "configuration of both was run alike, nothing was compared", file=sys.stderr)
    if refused:
        return EXIT_BAD_INPUT
    if judgement.regressed(found):
        return EXIT_REGRESSED
    return EXIT_MOVED if any(c.moved for c in found) else EXIT_NOTHING_MOVED


def compare_pair(arguments, base, new):
    """(what differs between what made the folders and how they were run, the configurations judged)."""
    comparable = arguments.cost_across_machines or folders.same_machine(base, new)
    found = changes.compare(base, new, comparable, arguments.cost_noise)
    return folders.differences(base, new) + alike.folder_differences(found), found


def cost_noise(text):
    try:
        value = float(text)
    except ValueError:
        value = float("nan")
    if not 0 <= value <= 10:
        raise argparse.ArgumentTypeError(f"--cost-noise {text}: allowed: 0 <= x <= 10 (the relative drift of a run's "
                                         "CPU time between identical runs)")
    return value


def main(argv):
    parser = argparse.ArgumentParser(prog="impactbench compare", description=__doc__.split("\n\n")[0])
    parser.add_argument("folders", nargs="+", metavar="FOLDER", help="BASE NEW, or several folders in order")
    parser.add_argument("--json", help="write the comparison as JSON to this file")
    parser.add_argument("--markdown", help="write the comparison as Markdown to this file")
    parser.add_argument("--html", help="write compare.html and compare.md into this folder")
    parser.add_argument("--cost-across-machines", action="store_true",
                        help="judge costs timed on other machines too (not comparable by default)")
    parser.add_argument("--cost-noise", type=cost_noise, default=changes.COST_NOISE_FLOOR,
                        help=f"the least relative change of CPU time told apart from the machine's drift "
                             f"(default {changes.COST_NOISE_FLOOR:g})")
    try:
        arguments = parser.parse_args(argv)
    except SystemExit as e:
        return EXIT_BAD_INPUT if e.code else 0
    if len(arguments.folders) < 2:
        print(f"impactbench: compare {' '.join(arguments.folders)}: allowed: two result folders or more", file=sys.stderr)
        return EXIT_BAD_INPUT
    try:
        read = [folders.read_folder(path) for path in arguments.folders]
        metric_catalog.use(*arguments.folders)  # the metrics every folder was scored on (metrics.json)
        for base, new in zip(read, read[1:]):
            alike.refuse(base, new)
    except (folders.CompareInputError, metric_catalog.MetricsFileError) as e:
        print(f"impactbench: {e}", file=sys.stderr)
        return EXIT_BAD_INPUT
    if len(read) > 2:
        return compare_history(arguments, read)
    base, new = read
    differences, found = compare_pair(arguments, base, new)
    print("\n".join(writers.summary_lines(base, new, differences, found)), flush=True)
    try:
        write_files(arguments, base, new, differences, found)
    except OSError as e:
        print(f"impactbench: {e.filename}: could not write the comparison ({e.strerror})", file=sys.stderr)
        return EXIT_OUTPUT_ERROR
    return exit_code(found, [(base, new)] if alike.nothing_alike(found) else [])


def compare_history(arguments, read):
    """Each folder with the next; the JSON holds the steps, the page each configuration along them."""
    from impactbench_compare import history
    steps = []
    for base, new in zip(read, read[1:]):
        steps.append((base, new, *compare_pair(arguments, base, new)))
    print("\n".join(history.summary_lines(read, steps)), flush=True)
    try:
        if arguments.json:
            with open(arguments.json, "w") as f:
                json.dump({"folders": [r.path for r in read],
                           "steps": [writers.json_object(*step) for step in steps]}, f, indent=1)
                f.write("\n")
        if arguments.markdown:
            with open(arguments.markdown, "w") as f:
                f.write("\n".join(writers.markdown(*step) for step in steps))
        if arguments.html:
            history.write_page(arguments.html, read, steps)
    except OSError as e:
        print(f"impactbench: {e.filename}: could not write the comparison ({e.strerror})", file=sys.stderr)
        return EXIT_OUTPUT_ERROR
    return exit_code([c for *_, found in steps for c in found],
                     [(base, new) for base, new, _, found in steps if alike.nothing_alike(found)])


def write_files(arguments, base, new, differences, found):
    if arguments.json:
        with open(arguments.json, "w") as f:
            json.dump(writers.json_object(base, new, differences, found), f, indent=1)
            f.write("\n")
    if arguments.markdown:
        with open(arguments.markdown, "w") as f:
            f.write(writers.markdown(base, new, differences, found))
    if arguments.html:
        from impactbench_compare import page  # matplotlib only when a page is asked for
        page.write_page(arguments.html, base, new, differences, found)


if __name__ == "__main__":
    try:
        code = main(sys.argv[1:])
    except Exception:
        import traceback
        traceback.print_exc()
        code = EXIT_FAILED
    sys.exit(code)
