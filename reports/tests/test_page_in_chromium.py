"""The report's page as a reader meets it, rendered in headless Chromium (reports/tests/page_in_chromium.py):
it loads with no console error, every <img> is drawn, every file of report/figures/ is shown on the page, it
opens with the fronts (figures/fronts.svg, the first image, above the answer), and the answer (the element
with id "answer": what to use) lies on the first screen of a 1366 x 768 window. The first screen
is saved as first-screen.png beside index.html, for the closing note. In a 1400 x 1000 window (page_layout.py)
no table or figure is wider than the window, none hides columns by scrolling sideways, and no two texts of any
SVG figure overlap: tick labels included, since a tick label under a step label is as unreadable as any.

    /usr/bin/python3 reports/tests/test_page_in_chromium.py REPORT_FOLDER
    /usr/bin/python3 reports/tests/test_page_in_chromium.py --build IMPACTBENCH SCENARIO_FOLDER OUT_FOLDER
    /usr/bin/python3 reports/tests/test_page_in_chromium.py                 (only the self-tests)

--build makes the page first, from the same small suite as test_report.py, in OUT_FOLDER/suite. The
self-tests open hand-made pages (a broken image, a console error, the answer below the first screen, a table
too wide, a scrolled table, a too wide image, overlapping and rotated labels) and
require that each fault is reported: a check that cannot fail checks nothing.
"""

import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest
import urllib.parse

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from page_in_chromium import Chromium  # noqa: E402
from page_layout import label_problems, look_at_layout, width_problems  # noqa: E402

WIDTH, HEIGHT = 1400, 1000  # a desktop reading window: what "the first screen" means here (issue 46)
REPORT = None

# The answer's place, measured before anything scrolls, with the headings above it to say what pushes it down.
ANSWER = """(() => {
  const answer = document.getElementById("answer");
  if (!answer) return null;
  const box = answer.getBoundingClientRect();
  const blocks = Array.from(document.querySelectorAll("h1, h2, h3, p, ul, ol, table, img, svg, figure, pre"))
    .filter(e => !answer.contains(e) && !e.contains(answer) && e.getBoundingClientRect().top < box.top &&
                 !(e.parentElement && e.parentElement.closest("p, ul, ol, table, svg, figure, pre")));
  const headings = blocks.filter(e => /^H[1-3]$/.test(e.tagName)).map(e => e.textContent.trim().slice(0, 60));
  const first = document.images[0];
  const sentence = document.getElementById("answer-sentence");
  const place = e => { const b = e.getBoundingClientRect(); return {top: b.top, bottom: b.bottom, height: b.height}; };
  const budget = Array.from(document.images).find(i => (i.getAttribute("src") || "").endsWith("figures/budget.svg"));
  return {top: box.top, height: box.height, tag: answer.tagName.toLowerCase(), headings: headings,
          blocks: blocks.length,
          first_image: first ? {src: first.getAttribute("src"), top: first.getBoundingClientRect().top} : null,
          sentence: sentence ? {...place(sentence), text: sentence.textContent.trim()} : null,
          budget: budget ? place(budget) : null};
})()"""

# Every image, once each has loaded or failed; "lazy" images are made eager first, as if the reader scrolled
# to each. Waits at most 20 s, so that a stuck image is reported as such rather than timing out the test.
IMAGES = """(async () => {
  const images = Array.from(document.images);
  images.forEach(i => { i.loading = "eager"; });
  const settled = images.map(i => i.complete ? null : new Promise(r => { i.addEventListener("load", r);
                                                                         i.addEventListener("error", r); }));
  await Promise.race([Promise.all(settled), new Promise(r => setTimeout(r, 20000))]);
  return {images: images.map(i => ({src: i.getAttribute("src"), url: i.src, complete: i.complete,
                                    width: i.naturalWidth})),
          inline_svgs: document.querySelectorAll("svg").length};
})()"""


def look_at(report, screenshot):
    """Everything the checks need from one opening of report/index.html; saves its first screen."""
    with Chromium(WIDTH, HEIGHT) as browser:
        page = browser.open(os.path.join(report, "index.html"))
        answer = page.evaluate(ANSWER)
        page.screenshot(screenshot)
        images = page.evaluate(IMAGES)
        return {"errors": page.errors, "answer": answer, **images}


def console_problems(seen):
    return [f"the page reported: {error}" for error in seen["errors"]]


def image_problems(seen):
    return [f'<img src="{i["src"]}"> is not drawn (complete: {str(i["complete"]).lower()}, naturalWidth: {i["width"]})'
            for i in seen["images"] if not (i["complete"] and i["width"] > 0)]


def figure_problems(seen, report):
    """Files in report/figures/ that no <img> of the page shows."""
    figures = os.path.join(report, "figures")
    files = sorted(os.listdir(figures)) if os.path.isdir(figures) else []
    shown = {os.path.realpath(urllib.parse.unquote(urllib.parse.urlparse(i["url"]).path)) for i in seen["images"]
             if i["url"].startswith("file:")}
    missing = [name for name in files if os.path.realpath(os.path.join(figures, name)) not in shown]
    if not missing:
        return []
    return [f"{len(missing)} of the {len(files)} files in figures/ are shown by no <img> of the page "
            f"(the page has {len(seen['images'])} <img> and {seen['inline_svgs']} inline <svg>): "
            + ", ".join(missing[:8]) + (", ..." if len(missing) > 8 else "")]


def lead_sentence(report):
    """The answer sentence of the report's lead case (summary.json; the resonance with Hertz contact where it
    ran: fronts.lead_case), or None without summary.json."""
    path = os.path.join(report, "summary.json")
    if not os.path.exists(path):
        return None
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
    from impactbench_report import fronts
    with open(path) as f:
        case = fronts.lead_case(json.load(f)["cases"])
    return None if case is None else case["answer"]["sentence"]


def answer_problems(seen, expected_sentence=None):
    """The lead case's answer sentence (id "answer-sentence") whole on the first screen, its text
    `expected_sentence` where given; the table of what to use (id "answer") and the error budget's figure
    (figures/budget.svg) starting on the first two."""
    answer = seen["answer"]
    if answer is None:
        return ['no element with id="answer" on the page: the summary table must carry it']
    if answer["height"] <= 0:
        return [f'the element with id="answer" (<{answer["tag"]}>) is not displayed (height {answer["height"]:g} px)']
    problems = []
    sentence = answer.get("sentence")
    if sentence is None:
        problems.append('no element with id="answer-sentence": the page must open with the answer in a sentence')
    elif sentence["bottom"] > HEIGHT or sentence["height"] <= 0:
        problems.append(f'the answer sentence ends at {sentence["bottom"]:.0f} px, not whole on the first screen '
                        f'({WIDTH} x {HEIGHT} px)')
    elif expected_sentence is not None and sentence["text"] != expected_sentence:
        problems.append(f'the answer sentence is not the lead case\'s ("{expected_sentence[:60]}"): '
                        f'"{sentence["text"][:80]}"')
    if answer["top"] >= 2 * HEIGHT:
        problems.append(f'the element with id="answer" (<{answer["tag"]}>) starts at {answer["top"]:.0f} px, below the '
                        f'first two screens ({WIDTH} x {HEIGHT} px); {answer["blocks"]} blocks come before it, under the '
                        'headings: ' + (" / ".join(answer["headings"]) or "none"))
    budget = answer.get("budget")
    if budget is None:
        problems.append("no error budget figure (figures/budget.svg) on the page")
    elif budget["top"] >= 2 * HEIGHT:
        problems.append(f'the error budget figure starts at {budget["top"]:.0f} px, below the first two screens')
    return problems


def fronts_problems(seen):
    """The page opens with the fronts: its first image is figures/fronts.svg, above the answer."""
    answer = seen["answer"]
    first = answer and answer.get("first_image")
    if not first:
        return ["the page has no image: it must open with the fronts (figures/fronts.svg)"]
    if not first["src"].endswith("figures/fronts.svg"):
        return [f'the first image is {first["src"]}, not the fronts (figures/fronts.svg)']
    if first["top"] >= answer["top"]:
        return [f'the fronts start at {first["top"]:.0f} px, below the answer ({answer["top"]:.0f} px)']
    return []


class ReportPage(unittest.TestCase):
    """The report given on the command line, opened once."""

    def assertNoProblems(self, problems):
        if problems:
            self.fail("\n".join(problems))

    @classmethod
    def setUpClass(cls):
        cls.screenshot = os.path.join(REPORT, "first-screen.png")
        cls.seen = look_at(REPORT, cls.screenshot)
        cls.layout = look_at_layout(REPORT)
        print(f"\nfirst screen: {cls.screenshot}", file=sys.stderr)

    def test_it_loads_without_console_errors(self):
        self.assertNoProblems(console_problems(self.seen))

    def test_every_image_is_drawn(self):
        self.assertNoProblems(image_problems(self.seen))

    def test_every_figure_file_is_on_the_page(self):
        self.assertNoProblems(figure_problems(self.seen, REPORT))

    def test_the_answer_is_on_the_first_screen(self):
        self.assertNoProblems(answer_problems(self.seen, lead_sentence(REPORT)))
        self.assertGreater(os.path.getsize(self.screenshot), 1000)

    def test_it_opens_with_the_fronts_above_the_answer(self):
        self.assertNoProblems(fronts_problems(self.seen))

    def test_no_table_or_figure_is_wider_than_the_reading_window(self):
        self.assertNoProblems(width_problems(self.layout))

    def test_no_two_labels_of_a_figure_overlap(self):
        self.assertGreater(sum(f["texts"] for f in self.layout["labels"].values()), 0)  # texts were measured
        self.assertNoProblems(label_problems(self.layout))


GOOD_IMAGE = '<svg xmlns="http://www.w3.org/2000/svg" width="200" height="100"><rect width="200" height="100"/></svg>'




def labelled_image(*labels):
    """An SVG with a text at each (x, y, text), 6 pt like a step label of the figures."""
    texts = "".join(f'<g id="text_{i}"><text x="{x}" y="{y}" style="font: 6px sans-serif">{t}</text></g>'
                    for i, (x, y, t) in enumerate(labels))
    return f'<svg xmlns="http://www.w3.org/2000/svg" width="300" height="100"><g id="axes_1">{texts}</g></svg>'


def hand_made(folder, body, figures=("drawn.svg",), style=""):
    """A report folder with index.html holding `body` and the given figure files (names, drawn as GOOD_IMAGE,
    or a dict of name: SVG text)."""
    os.makedirs(os.path.join(folder, "figures"))
    for name in figures:
        with open(os.path.join(folder, "figures", name), "w") as f:
            f.write(figures[name] if isinstance(figures, dict) else GOOD_IMAGE)
    with open(os.path.join(folder, "index.html"), "w") as f:
        f.write(f'<!doctype html><html><head><meta charset="utf-8"><title>hand-made</title><style>{style}</style>'
                f'</head><body>{body}</body></html>')
    return folder


WIDE_CELL = "<td style='white-space:nowrap'>" + "a long cell that will not wrap " * 12 + "</td>"


class TheChecksCanFail(unittest.TestCase):
    """Hand-made pages: a good one passes every check, a faulty one has each of its faults named."""

    @classmethod
    def setUpClass(cls):
        cls.folder = tempfile.mkdtemp(prefix="page_in_chromium_test_")

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.folder)

    def test_a_good_page_passes(self):
        report = hand_made(os.path.join(self.folder, "good"), '<h1>Report</h1><p id="answer-sentence">resonance, '
                           'hertz: use engine_a</p><img src="figures/fronts.svg"><img src="figures/budget.svg">'
                           '<table id="answer"><tr><td>engine_a</td></tr>'
                           '</table><img src="figures/drawn.svg" loading="lazy" style="margin-top:3000px">',
                           figures=("fronts.svg", "budget.svg", "drawn.svg"))
        seen = look_at(report, os.path.join(report, "first-screen.png"))
        self.assertEqual(console_problems(seen) + image_problems(seen) + figure_problems(seen, report)
                         + answer_problems(seen) + fronts_problems(seen), [])

    def test_every_fault_is_named(self):
        report = hand_made(os.path.join(self.folder, "faulty"),
                           '<h1>Report</h1><h2>Caveats</h2><img src="figures/drawn.svg"><img src="figures/gone.svg">'
                           '<script>console.error("deliberate", 42); console.log("not an error")</script>'
                           '<div style="height:2500px"></div><p id="answer-sentence">resonance: use x</p>'
                           '<table id="answer"><tr><td>x</td></tr></table>'
                           '<script>noSuchFunction()</script>', figures=("drawn.svg", "unshown.svg"))
        seen = look_at(report, os.path.join(report, "first-screen.png"))
        console = "\n".join(console_problems(seen))
        self.assertIn("console.error: deliberate 42", console)
        self.assertIn("figures/gone.svg", console)  # the failed load, with its file
        self.assertIn("noSuchFunction is not defined", console)
        self.assertNotIn("not an error", console)
        self.assertEqual(image_problems(seen), ['<img src="figures/gone.svg"> is not drawn (complete: true, naturalWidth: 0)'])
        self.assertRegex(" ".join(figure_problems(seen, report)), r"1 of the 2 files .*: unshown\.svg$")
        problems = " ".join(answer_problems(seen))
        self.assertRegex(problems, r"the answer sentence ends at 2\d\d\d px, not whole on the first screen")
        self.assertRegex(problems, r"starts at 2\d\d\d px, below the first two screens.*Report / Caveats")
        self.assertIn("no error budget figure", problems)
        self.assertEqual(fronts_problems(seen), ["the first image is figures/drawn.svg, not the fronts (figures/fronts.svg)"])

    def test_a_page_that_fits_with_labels_apart_passes(self):
        report = hand_made(os.path.join(self.folder, "fits"), '<h2>Case</h2><table><tr><td>short</td></tr></table>'
                           '<figure><img src="figures/apart.svg" style="max-width:100%"></figure>',
                           figures={"apart.svg": labelled_image((10, 20, "5e-5"), (10, 27, "1e-4"), (60, 20, "2e-4"))})
        seen = look_at_layout(report)
        self.assertEqual(width_problems(seen) + label_problems(seen), [])
        self.assertEqual(seen["labels"]["apart.svg"]["texts"], 3)

    def test_too_wide_tables_and_figures_are_named(self):
        report = hand_made(os.path.join(self.folder, "wide"),
                           f'<h2>Resonance</h2><table id="spilling"><tr><th>configuration</th></tr><tr>{WIDE_CELL}</tr>'
                           f'</table><h2>Scrolled</h2><div style="overflow-x:auto"><table id="scrolled"><tr>{WIDE_CELL}'
                           '</tr></table></div><figure><img src="figures/drawn.svg" style="width:1500px"></figure>')
        problems = "\n".join(width_problems(look_at_layout(report)))
        self.assertRegex(problems, r"the page is \d{4} px wide, wider than the 1400 px window")
        self.assertRegex(problems, r'<table id=spilling> \(header: configuration ...\) under "Resonance" spans 8 to '
                                   r'\d{4} px in a 1400 px window')
        self.assertRegex(problems, r'<div> under "Scrolled" spans 8 to 1392 px in a 1400 px window, its content '
                                   r'\d{4} px in a box of 1384 px')
        self.assertRegex(problems, r'<img src=figures/drawn.svg> under "Scrolled" spans \d+ to 15\d\d px')

    def test_the_report_style_fits_a_wide_table_and_figure(self):
        sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
        from impactbench_report import tables
        from impactbench_report.page_style import STYLE
        header = [f"metric {i} [unit]" for i in range(20)]
        rows = [[f"engine_{r} [contact=matched, option=value_{r}]"] + ["+12.5 % ± 0.57 %"] * 18
                + ["inaccurate: frame 1's sensor peak −14.9 % from its own chain, beyond the tolerance"]
                for r in range(3)]
        report = hand_made(os.path.join(self.folder, "styled"), f"<h2>Case</h2><p class='case'>a case</p>"
                           f"{tables.html_table(header, rows)}<figure><img src='figures/broad.svg'></figure>",
                           figures={"broad.svg": GOOD_IMAGE.replace('"200"', '"3000"')}, style=STYLE)
        self.assertEqual(width_problems(look_at_layout(report)), [])

    def test_overlapping_labels_are_named(self):
        report = hand_made(os.path.join(self.folder, "overlapping"), '<img src="figures/crowded.svg">',
                           figures={"crowded.svg": labelled_image((10, 20, "5e-5"), (14, 21, "1e-4"),
                                                                  (100, 20, "2e-4"), (100, 26.5, "4e-4"))})
        problems = label_problems(look_at_layout(report))
        self.assertEqual(len(problems), 1, problems)  # 2e-4 and 4e-4 only touch, within OVERLAP_PX
        self.assertRegex(problems[0], r'^crowded.svg: "5e-5" \(axes_1\) and "1e-4" \(axes_1\) overlap by \d\.\d px$')

    def test_rotated_labels_are_measured_as_drawn_and_lines_of_one_text_are_one_label(self):
        font = 'style="font: 8px sans-serif"'
        svg = ('<svg xmlns="http://www.w3.org/2000/svg" width="300" height="200"><g id="axes_1">'
               f'<g id="text_1"><text x="100" y="100" {font} transform="rotate(45 100 100)">a rotated label</text></g>'
               f'<g id="text_2"><text x="115" y="125" {font}>crossed</text></g>'
               f'<g id="text_3"><text x="96" y="146" {font}>off</text></g>'  # in the rotated one's upright box
               f'<g id="text_4"><text x="40" y="20" {font}>first line</text><text x="40" y="26" {font}>second</text>'
               '</g></g></svg>')
        report = hand_made(os.path.join(self.folder, "rotated"), '<img src="figures/rotated.svg">',
                           figures={"rotated.svg": svg})
        problems = label_problems(look_at_layout(report))
        self.assertEqual(len(problems), 1, problems)
        self.assertRegex(problems[0], r'^rotated.svg: "a rotated label" \(axes_1\) and "crossed" \(axes_1\) overlap')

    def test_a_page_without_the_answer_is_reported(self):
        report = hand_made(os.path.join(self.folder, "no_answer"), '<img src="figures/drawn.svg">')
        self.assertIn('no element with id="answer"', " ".join(answer_problems(look_at(report, os.devnull))))

    def test_a_sentence_of_another_case_is_reported(self):
        report = hand_made(os.path.join(self.folder, "other_case"), '<p id="answer-sentence">free_vibration: use x</p>'
                           '<img src="figures/budget.svg"><table id="answer"><tr><td>x</td></tr></table>',
                           figures=("budget.svg",))
        self.assertEqual(answer_problems(look_at(report, os.devnull), "resonance, hertz: use x"),
                         ['the answer sentence is not the lead case\'s ("resonance, hertz: use x"): "free_vibration: use x"'])

    def test_a_hung_page_fails_instead_of_hanging(self):
        report = hand_made(os.path.join(self.folder, "hung"), "<p>ready</p>")
        with Chromium(WIDTH, HEIGHT, timeout_s=3) as browser:
            page = browser.open(os.path.join(report, "index.html"))
            with self.assertRaisesRegex(TimeoutError, "within 3 s"):
                page.evaluate("while (true) {}")


def build_report(executable, scenarios, out):
    """The small suite of test_report.py (the build's first three engines, `engines --names`), run afresh in
    out/suite, and its report; returns the report folder."""
    names = subprocess.run([executable, "engines", "--names"], capture_output=True, text=True, check=True).stdout
    engines = [n for n in names.strip().split(",") if n and n != "reference"][:3]
    suite = os.path.join(out, "suite")
    shutil.rmtree(suite, ignore_errors=True)  # a suite resumes from what it finds: start clean
    run = subprocess.run([executable, "suite", scenarios, "--engines", ",".join(["reference"] + engines),
                          "--laws", "viscoelastic,newton", "--dt", "1e-4,5e-5", "--jobs", "2", "--out", suite],
                         capture_output=True, text=True)
    assert run.returncode in (0, 1), run.stderr  # 1: some runs unstable, a finding the report shows
    # the report of this checkout's make_report.py, which `impactbench report` runs only from the checkout
    # the executable was built from: the page tested is the one these sources make
    make_report = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "make_report.py")
    report = subprocess.run([sys.executable, make_report, suite], capture_output=True, text=True)
    assert report.returncode == 0, report.stderr
    return os.path.join(suite, "report")


if __name__ == "__main__":
    arguments = sys.argv[1:]
    if arguments[:1] == ["--build"]:
        REPORT = build_report(*arguments[1:4])
    elif arguments:
        REPORT = os.path.abspath(arguments[0])
    cases = unittest.defaultTestLoader.loadTestsFromTestCase(TheChecksCanFail)
    if REPORT:
        cases.addTests(unittest.defaultTestLoader.loadTestsFromTestCase(ReportPage))
    sys.exit(not unittest.TextTestRunner(verbosity=2).run(cases).wasSuccessful())
