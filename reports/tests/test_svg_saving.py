"""The report's SVG saving (impactbench_report/svg_saving.py) writes the file matplotlib's own savefig writes, to
the byte: figures with constrained layout (shared axes, titles, a legend below, log axes, a rasterized line, a
colour bar) and without, saved both ways with matplotlib's hashed ids made reproducible.

    /usr/bin/python3 reports/tests/test_svg_saving.py
"""

import io
import os
import sys
import unittest

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib import text as mtext  # noqa: E402

from impactbench_report import svg_saving  # noqa: E402

plt.rcParams["svg.fonttype"] = "none"
plt.rcParams["svg.hashsalt"] = "test"  # ids from the content alone: the two files comparable
METADATA = {"Title": "a caption", "Date": None}


def panels(constrained):
    """A figure like the report's: a grid of shared panels with titles and tick labels, a log panel, a
    rasterized dense line, an image with a colour bar, a legend in its own axes below."""
    figure = plt.figure(figsize=(9, 6), constrained_layout=constrained)
    grid = figure.add_gridspec(3, 2, height_ratios=[1, 1, 0.3])
    first = figure.add_subplot(grid[0, 0])
    axes = [first, figure.add_subplot(grid[0, 1])] + [figure.add_subplot(grid[1, k], sharex=first) for k in (0, 1)]
    t = np.linspace(0, 1, 20000)
    axes[0].plot(t, np.sin(40 * t) * np.exp(-t), linewidth=0.5, rasterized=True)
    axes[0].set_title("a rasterized dense line, frame 1", fontsize=8)
    axes[1].loglog(t[1:], 1e-3 + t[1:] ** 2, "o-", markersize=2)
    axes[1].set_title("log axes: $u_1$ [m]", fontsize=8)
    image = axes[2].imshow(np.outer(np.arange(30), np.arange(40)), aspect="auto",
                           extent=(0, 1, 0, 3))
    figure.colorbar(image, ax=axes[2], label="amplitude [g]")
    axes[3].plot(t, t ** 2, label="a curve")
    axes[3].set_xlabel("time [s]")
    axes[2].set_ylabel("0.5", fontsize=20)  # a tick label's text in another font: its own size in the layout
    legend = figure.add_subplot(grid[2, :])
    legend.axis("off")
    legend.legend(*axes[3].get_legend_handles_labels(), loc="center")
    figure.suptitle("a caption over the panels, long enough to wrap at the figure's width " * 2, fontsize=7)
    return figure


def svg_bytes(figure, save):
    buffer = io.StringIO()
    save(figure, buffer)
    plt.close(figure)
    return buffer.getvalue()


class SvgSaving(unittest.TestCase):
    def setUp(self):
        svg_saving.install_text_metrics_cache()

    def test_the_file_is_savefigs_with_and_without_constrained_layout(self):
        for constrained in (True, False):
            with self.subTest(constrained=constrained):
                ours = svg_bytes(panels(constrained), lambda f, out: svg_saving.save_svg(f, out, METADATA))
                mtext._get_text_metrics_with_cache = svg_saving._MATPLOTLIB_METRICS  # matplotlib's own, alone
                try:
                    theirs = svg_bytes(panels(constrained),
                                       lambda f, out: f.savefig(out, format="svg", metadata=METADATA))
                finally:
                    svg_saving.install_text_metrics_cache()
                self.assertIn("<image", ours)  # the rasterized line and the image are in the file
                self.assertEqual(ours, theirs)

    def test_a_figure_saved_twice_is_savefigs_both_times(self):
        """(matplotlib's second file of a figure is not its first: the layout starts from the first's)"""
        files = {}
        for name, save in (("ours", lambda f, out: svg_saving.save_svg(f, out, METADATA)),
                           ("theirs", lambda f, out: f.savefig(out, format="svg", metadata=METADATA))):
            figure = panels(True)
            files[name] = [io.StringIO(), io.StringIO()]
            for out in files[name]:
                save(figure, out)
                self.assertNotIn("draw", vars(figure))  # the layout pass's stand-in is gone
            plt.close(figure)
        self.assertEqual([f.getvalue() for f in files["ours"]], [f.getvalue() for f in files["theirs"]])

if __name__ == "__main__":
    unittest.main()
