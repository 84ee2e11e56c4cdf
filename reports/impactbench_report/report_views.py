"""The report's views besides its cases: each a function from what the report has read (ViewInputs) to its section
(title, Markdown text, HTML text, [figure paths]), or None when it has nothing to show. The page shows BEFORE_CASES
first, then the cases and each law's stability map, then AFTER_CASES, in list order, then a study's sweeps. A new
view is one function (in its own module when it computes something) and its line in one of the two lists
(docs/layout.md, "A new report view"); page_writer.py writes it into index.html and summary.md."""

from dataclasses import dataclass

from . import ablation, convergence_table, performance, validation_page


@dataclass(frozen=True)
class ViewInputs:
    suite_folder: str  # the results folder the report is made from
    document: dict     # summary.json, as the report wrote it
    out: str           # the report's folder (its figures go to out/figures)


def chain_resolution(inputs):
    """How the chain's error changes with its number of links, where the reference ran on several chains."""
    section = convergence_table.section(inputs.document)
    return (*section, []) if section else None


def ablation_view(inputs):
    """Which setting moved an engine's error or cost."""
    rows = inputs.document["ablation"]
    return ablation.section(rows) if rows else None


def performance_view(inputs):
    """bench/'s timings saved in SUITE/performance/, if any; ValueError for a file that is not their JSON."""
    measured = performance.section(inputs.suite_folder)
    return ("Performance", measured[0], measured[1], []) if measured else None


def validation_view(inputs):
    """The reference against the experiment, where the study sampled the rig's uncertain inputs ([[validation]]):
    after the laws' comparisons with the experiment, which show single runs at the nominal inputs."""
    return validation_page.section(inputs.document, inputs.suite_folder, inputs.out)


BEFORE_CASES = [chain_resolution]
AFTER_CASES = [validation_view, ablation_view, performance_view]


def sections(views, inputs):
    """The sections of those views that have something to show, in the views' order."""
    return [section for section in (view(inputs) for view in views) if section]
