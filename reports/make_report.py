#!/usr/bin/python3
"""Makes a suite's report from its saved results, without rerunning anything:

    reports/make_report.py SUITE_FOLDER [--out REPORT_FOLDER]

writes REPORT_FOLDER (default SUITE_FOLDER/report): index.html (self-contained: the SVG figures are
inside it), summary.md, figures/*.svg, and the runs.csv and runs.jsonl it was made from; with a
performance section when SUITE_FOLDER/performance/ holds bench/ measurements (impactbench_report/performance.py). A
sweep's folder gets the sweep's report. Needs Debian's python3-matplotlib (run with /usr/bin/python3). The pages are
made by impactbench_report (suite_report.py, sweep_report.py, page_writer.py)."""

import argparse
import csv
import os
import sys
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from impactbench_report import data, suite_report, sweep, sweep_report  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("suite", help="a suite's output folder (holds runs.csv)")
    parser.add_argument("--out", help="report folder (default: SUITE/report)")
    args = parser.parse_args()
    out = args.out or os.path.join(args.suite, "report")
    if sweep.is_sweep(args.suite) and not os.path.exists(os.path.join(args.suite, "runs.csv")):
        return sweep_report.make(args.suite, out)
    return suite_report.make(args.suite, out)


def guarded_main():
    """main(), with every failure said in one line naming the folder and what went wrong, never a traceback
    (IMPACTBENCH_TRACEBACK=1 shows it, for a developer)."""
    try:
        main()
    except (data.ResultsError, OSError, ValueError, KeyError, IndexError, TypeError, csv.Error, EOFError,
            zlib.error, UnicodeDecodeError) as error:
        if os.environ.get("IMPACTBENCH_TRACEBACK"):
            raise
        what = f"{type(error).__name__}: {error}" if not isinstance(error, data.ResultsError) else str(error)
        sys.exit(f"make_report: cannot make the report of {sys.argv[1] if len(sys.argv) > 1 else '?'}: {what} "
                 "(a damaged or incomplete results folder? `impactbench suite ... --resume` repairs a suite's)")



if __name__ == "__main__":
    guarded_main()
