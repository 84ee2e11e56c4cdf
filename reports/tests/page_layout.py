"""The report's page in the window it must read in (issue 46: 1400 x 1000), measured in headless Chromium
(page_in_chromium.py) for test_page_in_chromium.py: which tables and figures are wider than the window, and
which texts of each SVG figure overlap another.

    seen = look_at_layout(REPORT_FOLDER)
    width_problems(seen), label_problems(seen)     # one readable line per fault, [] when there is none
"""

import os

from page_in_chromium import Chromium

READING_WIDTH, READING_HEIGHT = 1400, 1000  # the window the whole page must read in: nothing wider
OVERLAP_PX = 1.0  # two texts overlapping by more than this overlap (less is antialiasing and font rounding)

# Every image, made eager, once each has loaded or failed (at most 20 s): an image's size moves the layout.
IMAGES_LOADED = """(async () => {
  const images = Array.from(document.images);
  images.forEach(i => { i.loading = "eager"; });
  await Promise.race([Promise.all(images.map(i => i.complete ? null : new Promise(r => {
    i.addEventListener("load", r); i.addEventListener("error", r); }))), new Promise(r => setTimeout(r, 20000))]);
})()"""

# Every table and figure whose box leaves the viewport, or whose content is wider than its box (a table that
# scrolls sideways or spills hides its columns just the same), and any other element that scrolls sideways;
# measured after every image has loaded, since an image's size moves the layout.
WIDE = """(() => {
  const width = window.innerWidth;
  const heading = e => { let h = null; for (const c of document.querySelectorAll("h1, h2, h3"))
    if (c.compareDocumentPosition(e) & Node.DOCUMENT_POSITION_FOLLOWING) h = c; return h ? h.textContent.trim() : ""; };
  const name = e => { const head = e.tagName === "TABLE" ? Array.from(e.querySelectorAll("th")).slice(0, 3)
                        .map(c => c.textContent.trim()).join(" | ") : "";
    return `<${e.tagName.toLowerCase()}${e.id ? " id=" + e.id : ""}${e.getAttribute("src") ? " src=" +
           e.getAttribute("src") : ""}>` + (head ? ` (header: ${head} ...)` : "") + ` under "${heading(e)}"`; };
  const elements = Array.from(document.querySelectorAll("table, figure, img, svg, object, pre"))
    .filter(e => !(e.parentElement && e.parentElement.closest("svg")));
  const scrolling = Array.from(document.body.querySelectorAll("*")).filter(e =>
    getComputedStyle(e).overflowX !== "visible" && !elements.includes(e));
  const wide = elements.concat(scrolling).map(e => { const box = e.getBoundingClientRect();
      return {name: name(e), left: box.left, right: box.right, content: e.scrollWidth, box: e.clientWidth}; })
    .filter(e => e.right > width + 0.5 || e.left < -0.5 || e.content > e.box + 1);
  return {width: width, page: document.scrollingElement.scrollWidth, wide: wide};
})()"""

# Every <text> of an SVG opened as its own page, as the four corners of its box where it is drawn (rotated
# labels too: a box around a rotated label would claim the space beside it), and the pairs of texts whose boxes
# overlap by more than OVERLAP_PX (the depth on the separating axis theorem's shallowest axis). Each line of a
# matplotlib text is its own <text> in that text's group (text_N): lines of one text are not two labels, and
# matplotlib spaces them by its own line spacing, which Chromium's taller font boxes overlap by a pixel.
# Its groups' ids (axes_2, xtick_3, legend_1) say where a text is.
TEXT_OVERLAPS = """(() => {
  const texts = Array.from(document.querySelectorAll("text")).map(t => { const b = t.getBBox(), m = t.getScreenCTM();
      const corners = [[b.x, b.y], [b.x + b.width, b.y], [b.x + b.width, b.y + b.height], [b.x, b.y + b.height]]
        .map(([x, y]) => new DOMPoint(x, y).matrixTransform(m));
      const where = []; for (let g = t.parentElement; g; g = g.parentElement)
        if (/^(axes|legend|xtick|ytick)_/.test(g.id || "")) where.unshift(g.id);
      return {text: t.textContent.trim(), where: where.join("/"), group: t.parentElement, corners: corners,
              empty: b.width <= 0 || b.height <= 0}; })
    .filter(t => t.text && !t.empty);
  const depth = (a, b) => { let least = Infinity;  // overlap along each edge's normal; 0 once they are apart
    for (const c of [a, b]) for (let k = 0; k < 4; k++) {
      const p = c[k], q = c[(k + 1) % 4], nx = p.y - q.y, ny = q.x - p.x, n = Math.hypot(nx, ny);
      if (n === 0) continue;
      const along = pts => pts.map(r => (r.x * nx + r.y * ny) / n);
      const u = along(a), v = along(b);
      least = Math.min(least, Math.min(Math.max(...u), Math.max(...v)) - Math.max(Math.min(...u), Math.min(...v)));
    } return least; };
  const overlaps = [];
  for (let i = 0; i < texts.length; i++) for (let j = i + 1; j < texts.length; j++) {
    const a = texts[i], b = texts[j];
    if (a.group === b.group && /^text_/.test(a.group.id || "")) continue;
    const d = depth(a.corners, b.corners);
    if (d > LIMIT) overlaps.push({a: {text: a.text, where: a.where}, b: {text: b.text, where: b.where}, depth: d});
  }
  return {texts: texts.length, overlaps: overlaps};
})()""".replace("LIMIT", str(OVERLAP_PX))


def look_at_layout(report):
    """The page in the reading window once its images are drawn, and the text overlaps of each SVG figure
    (figures/*.svg, each opened alone at its own size, as the link under the page's image opens it)."""
    with Chromium(READING_WIDTH, READING_HEIGHT) as browser:
        page = browser.open(os.path.join(report, "index.html"))
        page.evaluate(IMAGES_LOADED)
        layout = page.evaluate(WIDE)
        figures = os.path.join(report, "figures")
        labels = {}
        for name in sorted(os.listdir(figures)) if os.path.isdir(figures) else []:
            if name.endswith(".svg"):
                figure = browser.open(os.path.join(figures, name))
                labels[name] = figure.evaluate(TEXT_OVERLAPS)
                figure.close()
        return {**layout, "labels": labels}


def width_problems(seen):
    problems = [f"the page is {seen['page']} px wide, wider than the {seen['width']} px window"
                ] if seen["page"] > seen["width"] else []
    for e in seen["wide"]:
        hidden = f", its content {e['content']} px in a box of {e['box']} px" if e["content"] > e["box"] + 1 else ""
        problems.append(f"{e['name']} spans {e['left']:.0f} to {e['right']:.0f} px in a {seen['width']} px "
                        f"window{hidden}")
    return problems


def label_problems(seen):
    problems = []
    for name, found in seen["labels"].items():
        for o in found["overlaps"][:10]:
            a, b = o["a"], o["b"]
            problems.append(f'{name}: "{a["text"]}" ({a["where"] or "figure"}) and "{b["text"]}" '
                            f'({b["where"] or "figure"}) overlap by {o["depth"]:.1f} px')
        if len(found["overlaps"]) > 10:
            problems.append(f"{name}: and {len(found['overlaps']) - 10} more overlapping pairs")
    return problems
