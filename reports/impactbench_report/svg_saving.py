"""Saving a figure as SVG without the work matplotlib 3.6 repeats, the file unchanged to the byte.

savefig of a figure with constrained layout draws it twice: once with every drawing call disabled, only so that
the layout runs first, then for real. The first pass walks every tick and text of every panel for nothing but
the layout; `save_svg` runs the layout alone in that pass (matplotlib 3.6, Debian's: another version saves as
savefig does). And each of the three SVG renderers a save makes (the first pass's, the layout's and the file's) measures
every string again in its own cache: an SVG renderer's text metrics depend on the string and the font alone
(text2path measures at a fixed size and 72 dpi), so `install_text_metrics_cache` keeps one for all of them."""

import matplotlib
from matplotlib import text as mtext
from matplotlib.backends.backend_svg import RendererSVG

_METRICS = {}  # (string, font properties' hash, ismath) -> (width, height, descent) in an SVG renderer
_MATPLOTLIB_METRICS = mtext._get_text_metrics_with_cache


def _text_metrics(renderer, text, fontprop, ismath, dpi):
    """matplotlib's text metrics, shared across SVG renderers. A FontProperties is equal to another when their
    hashes are (matplotlib's own rule, which its cache relies on too). A renderer drawing a rasterized part
    (MixedModeRenderer with Agg underneath) measures in pixels: matplotlib's own cache then."""
    if not isinstance(getattr(renderer, "_renderer", renderer), RendererSVG):
        return _MATPLOTLIB_METRICS(renderer, text, fontprop, ismath, dpi)
    key = (text, hash(fontprop), ismath)
    metrics = _METRICS.get(key)
    if metrics is None:
        metrics = _METRICS[key] = renderer.get_text_width_height_descent(text, fontprop, ismath)
    return metrics


def install_text_metrics_cache():
    mtext._get_text_metrics_with_cache = _text_metrics


def _layout_pass(figure):
    """Figure.draw for the pass savefig makes with drawing disabled: what precedes the artists' drawing there
    (the axes' aspect, then the layout), nothing after. A pass that draws for real draws in full."""
    def draw(renderer):
        # savefig switches the drawing calls off on the SVG renderer itself (under the mixed-mode one)
        if "draw_path" not in vars(getattr(renderer, "_renderer", renderer)):
            del figure.draw
            return figure.draw(renderer)
        figure._get_draw_artists(renderer)  # runs each axes' apply_aspect, as Figure.draw does first
        if figure.axes and figure.get_layout_engine() is not None:
            try:
                figure.get_layout_engine().execute(figure)
            except ValueError:
                pass  # as Figure.draw: a layout that cannot be made leaves the positions as they are
        del figure.draw
    return draw


def save_svg(figure, path, metadata):
    if matplotlib.__version__.split(".")[:2] == ["3", "6"] and figure.get_layout_engine() is not None:
        figure.draw = _layout_pass(figure)
    try:
        figure.savefig(path, format="svg", metadata=metadata)
    finally:
        vars(figure).pop("draw", None)
