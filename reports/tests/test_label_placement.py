"""Point labels (impactbench_report/label_placement.py): placed once the figure's layout is known, none over
another or over a tick label, title or legend, each inside its panel, and left out where no place is free.

    /usr/bin/python3 reports/tests/test_label_placement.py

The Chromium test (test_page_in_chromium.py) checks the saved figures of a real report the same way, with the
browser's own text boxes."""

import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from impactbench_report import figures  # noqa: E402  (sets matplotlib's backend and the SVG text)
from impactbench_report.label_placement import label_point, place_labels  # noqa: E402
from matplotlib.text import Text  # noqa: E402

plt = figures.plt


def crowded_panel(points):
    """A log-log panel like an error-against-cost one, a step label at each point, its legend beside it."""
    figure = plt.figure(figsize=(5, 3), constrained_layout=True)
    ax = figure.add_subplot(1, 2, 1)
    figures.log_axis(ax, "x", 1e-2, 1.0)
    figures.log_axis(ax, "y", 0.1, 100.0)
    ax.plot([x for x, _ in points], [y for _, y in points], "-o", markersize=5)
    ax.set_title("a crowded panel", fontsize=9)
    labels = [label_point(ax, f"{k + 1}e-5", xy, fontsize=6) for k, xy in enumerate(points)]
    figures.legend_axis(figure.add_subplot(1, 2, 2), [figures.proxy("a run", marker="o")])
    return figure, ax, labels


class PointLabels(unittest.TestCase):

    def test_labels_of_nearby_points_do_not_overlap_and_stay_in_their_panel(self):
        points = [(0.1 * 1.03 ** k, 5.0 * 1.05 ** k) for k in range(6)]  # six runs within a label's width
        figure, ax, labels = crowded_panel(points)
        left_out = place_labels(figure)
        figure.draw_without_rendering()
        renderer = figure.canvas.get_renderer()
        shown = [(label.get_text(), label.get_window_extent(renderer)) for label in labels if label.get_visible()]
        self.assertEqual(len(shown) + left_out, 6)
        self.assertGreaterEqual(len(shown), 3)  # room around the cluster for at least half of them
        others = [t.get_window_extent(renderer) for t in figure.findobj(Text)
                  if t.get_visible() and t.get_text().strip() and t not in labels and t.axes is not None
                  and t in ax.get_xticklabels() + ax.get_yticklabels() + [ax.title]]
        panel = ax.get_window_extent(renderer)
        for i, (text, box) in enumerate(shown):
            self.assertTrue(panel.x0 <= box.x0 and box.x1 <= panel.x1 and panel.y0 <= box.y0 and box.y1 <= panel.y1,
                            f"{text} leaves its panel")
            for other_text, other in shown[i + 1:]:
                self.assertFalse(box.overlaps(other), f"{text} overlaps {other_text}")
            for other in others:
                self.assertFalse(box.overlaps(other), f"{text} overlaps a tick label or the title")
        plt.close(figure)

    def test_a_label_with_no_free_place_is_left_out_and_counted(self):
        figure, ax, labels = crowded_panel([(0.1, 5.0)] * 40)  # forty labels on one point: no room for all
        left_out = place_labels(figure)
        self.assertGreater(left_out, 0)
        self.assertEqual(left_out, sum(not label.get_visible() for label in labels))
        plt.close(figure)

    def test_the_saved_file_holds_the_placed_labels_only(self):
        figure, _, labels = crowded_panel([(0.1, 5.0)] * 40)
        with tempfile.TemporaryDirectory() as folder:
            path = figures.save(figure, folder, "crowded", "a caption")
            with open(path) as f:
                svg = f.read()
        shown = [label.get_text() for label in labels if label.get_visible()]
        self.assertTrue(0 < len(shown) < 40)
        self.assertEqual([k for k in range(1, 41) if f">{k}e-5<" in svg], [int(t[:-3]) for t in shown])

    def test_a_figure_without_point_labels_is_left_alone(self):
        figure = plt.figure(figsize=(3, 2))
        figure.add_subplot().plot([1, 2], [3, 4])
        self.assertEqual(place_labels(figure), 0)
        plt.close(figure)


if __name__ == "__main__":
    unittest.main(verbosity=2)
