"""Labels beside points (a run's time step, an impulse, a bar's error) that overlap nothing: no other label,
no tick label, title or legend text, and where possible no marker. A 6 pt label at a fixed offset overlaps its
neighbour wherever two runs lie within a label's width of each other (issue 46: the error-against-cost panels'
step labels did, by about 6 px). So a figure's point labels are placed once its layout is known, just before
it is saved (figures.save calls place_labels): each label, in the order they were made, takes the first of a
few positions around its point (right, left, above, below, then a little further out) where its box meets no
text and stays inside its panel; a label with no such place is left out. Every figure that labels points says
in its legend or caption that the labels are drawn where they fit, and the table beside the figure lists every
value, so a label left out hides nothing.

test_page_in_chromium.py checks the saved SVGs in Chromium: no two texts of a figure overlap."""

import weakref

from matplotlib.text import Text
from matplotlib.transforms import Bbox

# Offsets from the point [pt] with the alignment that puts the label on that side of it, nearest first.
POSITIONS = [(4, 2, "left", "bottom"), (4, -2, "left", "top"), (-4, 2, "right", "bottom"), (-4, -2, "right", "top"),
             (0, 5, "center", "bottom"), (0, -5, "center", "top"), (6, 0, "left", "center"), (-6, 0, "right", "center"),
             (9, 7, "left", "bottom"), (9, -7, "left", "top"), (-9, 7, "right", "bottom"), (-9, -7, "right", "top"),
             (0, 11, "center", "bottom"), (0, -11, "center", "top")]
GAP_PT = 1.0  # the space kept between a label and any other text (Chromium's font metrics differ slightly)

_LABELS = weakref.WeakKeyDictionary()  # figure -> [(annotation, positions)] still to be placed


def label_point(ax, text, xy, positions=POSITIONS, **style):
    """A label for the point xy (data coordinates of ax), placed when the figure is saved; returns it. The
    label takes no part in the layout: where it goes depends on the layout, not the other way round."""
    label = ax.annotate(text, xy, xytext=positions[0][:2], textcoords="offset points", ha=positions[0][2],
                        va=positions[0][3], **style)
    label.set_in_layout(False)
    _LABELS.setdefault(ax.figure, []).append((label, positions))
    return label


def place_labels(figure):
    """Places the figure's point labels (label_point), leaving out those that fit nowhere; returns how many
    it left out. A no-op for a figure without them."""
    labels = _LABELS.pop(figure, [])
    if not labels:
        return 0
    figure.draw_without_rendering()  # the layout, and every tick label's text and place
    renderer = figure.canvas.get_renderer()
    gap = GAP_PT * figure.dpi / 72
    mine = {id(label) for label, _ in labels}
    taken = [box.padded(gap) for box in fixed_text_boxes(figure, renderer, mine)]
    markers = marker_boxes(figure, renderer)
    left_out = 0
    for label, positions in labels:
        panel = label.axes.get_window_extent(renderer)
        fits = []
        for x, y, ha, va in positions:
            label.set_position((x, y))
            label.set_ha(ha)
            label.set_va(va)
            box = label.get_window_extent(renderer)
            if inside(box, panel) and not any(box.overlaps(t) for t in taken):
                fits.append(((x, y, ha, va), box))
                if not any(box.overlaps(m) for m in markers):
                    break  # free of text and markers: the best there is
        if not fits:
            label.set_visible(False)
            left_out += 1
            continue
        (x, y, ha, va), box = next(((p, b) for p, b in fits if not any(b.overlaps(m) for m in markers)), fits[0])
        label.set_position((x, y))
        label.set_ha(ha)
        label.set_va(va)
        taken.append(box.padded(gap))
    return left_out


def inside(box, panel):
    return box.x0 >= panel.x0 and box.x1 <= panel.x1 and box.y0 >= panel.y0 and box.y1 <= panel.y1


def fixed_text_boxes(figure, renderer, labels):
    """The window boxes of every text the figure draws but the point labels: titles, axis labels, legends,
    notes and the labels of the ticks the axes draw (a tick outside the view keeps a label, drawn nowhere)."""
    every_tick, drawn = set(), set()
    for ax in figure.axes:
        for axis in (ax.xaxis, ax.yaxis):
            every_tick.update(id(t.label1) for t in axis.majorTicks + axis.minorTicks)
            drawn.update(id(t.label1) for t in axis._update_ticks())  # the ticks matplotlib draws
    return [text.get_window_extent(renderer) for text in figure.findobj(Text)
            if id(text) not in labels and text.get_visible() and text.get_text().strip()
            and (id(text) not in every_tick or id(text) in drawn)]


def marker_boxes(figure, renderer):
    """A box around every marker of every line and scatter (a point the labels should rather not cover)."""
    boxes = []
    for ax in figure.axes:
        for line in ax.get_lines():
            if line.get_marker() in (None, "None", "", " ") or not line.get_visible():
                continue
            half = line.get_markersize() * figure.dpi / 72 / 2
            boxes += [Bbox([[x - half, y - half], [x + half, y + half]])
                      for x, y in line.get_transform().transform(line.get_xydata())]
        for collection in ax.collections:
            sizes = getattr(collection, "get_sizes", lambda: [])()
            if len(sizes) == 0 or not collection.get_visible():
                continue
            half = max(sizes) ** 0.5 * figure.dpi / 72 / 2
            boxes += [Bbox([[x - half, y - half], [x + half, y + half]])
                      for x, y in collection.get_offset_transform().transform(collection.get_offsets())]
    return boxes
