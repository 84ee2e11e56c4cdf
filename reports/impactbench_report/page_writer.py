"""The pages a report writes (index.html beside summary.md): the skeleton of an HTML page, a section's heading,
text and figures in either format, and a figure as a separate file. The suite's report (suite_report.py) and a
sweep's (sweep_report.py) are written with it."""

import html
import os

from .page_style import STYLE


def anchor(title):
    return "".join(c if c.isalnum() else "-" for c in title.lower())


def figure_html(path, out):
    """A figure as a separate file (index.html stays small and opens at once), its caption, the SVG's
    title, as the image's text for a reader without images."""
    caption = ""
    with open(path) as f:
        head = f.read(4000)
    start = head.find("<dc:title>")
    if start >= 0:
        caption = head[start + len("<dc:title>"):head.find("</dc:title>")]
    relative = os.path.relpath(path, out)
    return (f"<figure><a href='{html.escape(relative)}'><img src='{html.escape(relative)}' loading='lazy' "
            f"alt='{html.escape(caption)}'></a></figure>")



def markdown_figure(path, out):
    return f"![{os.path.basename(path)}]({os.path.relpath(path, out)})"


def html_head(title, viewport=True):
    """An HTML page's start, its style inside (the page is self-contained but for its figures)."""
    return ("<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'>"
            + ("<meta name='viewport' content='width=device-width, initial-scale=1'>" if viewport else "")
            + f"<title>{html.escape(title)}</title><style>{STYLE}</style></head><body>")


def sections_markdown(sections, out):
    """Each section (title, markdown text, html text, figure paths) as Markdown lines."""
    lines = []
    for title, text, _, paths in sections:
        lines += ["", f"## {title}", ""]
        if text:
            lines += [text, ""]
        lines += [markdown_figure(p, out) for p in paths]
    return lines


def sections_html(sections, out):
    """Each section as its heading (with its anchor), its HTML text and its figures."""
    parts = []
    for title, _, table_html, paths in sections:
        parts.append(f"<h2 id='{anchor(title)}'>{html.escape(title)}</h2>{table_html}")
        parts += [figure_html(p, out) for p in paths]
    return parts


def write_pages(out, markdown_lines, html_parts):
    """OUT/summary.md and OUT/index.html."""
    with open(os.path.join(out, "summary.md"), "w") as f:
        f.write("\n".join(markdown_lines) + "\n")
    with open(os.path.join(out, "index.html"), "w") as f:
        f.write("\n".join(html_parts))
