"""The report's page as a reader meets it, rendered in headless Chromium (reports/tests/page_in_chromium.py):
it loads with no console error, every <img> is drawn, every file of report/figures/ is shown on the page, it
opens with the fronts (figures/fronts.svg, the first image, above the answer), and the answer (the element
with id "answer": what to use) lies on the first screen of a 1366 x 768 window. The first screen
is saved as first-screen.png beside index.html, for the closing note.

    /usr/bin/python3 reports/tests/test_page_in_chromium.py REPORT_FOLDER
    /usr/bin/python3 reports/tests/test_page_in_chromium.py --build IMPACTBENCH SCENARIO_FOLDER OUT_FOLDER
    /usr/bin/python3 reports/tests/test_page_in_chromium.py                 (only the self-tests)

--build makes the page first, from the same small suite as test_report.py, in OUT_FOLDER/suite. The
self-tests open hand-made pages (a broken image, a console error, the answer below the first screen) and
require that each fault is reported: a check that cannot fail checks nothing.
"""

import os
import shutil
import subprocess
import sys
import tempfile
import unittest
import urllib.parse

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from page_in_chromium import Chromium  # noqa: E402

WIDTH, HEIGHT = 1366, 768  # a common laptop screen: what "the first screen" means here
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
  return {top: box.top, height: box.height, tag: answer.tagName.toLowerCase(), headings: headings,
          blocks: blocks.length,
          first_image: first ? {src: first.getAttribute("src"), top: first.getBoundingClientRect().top} : null};
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


def answer_problems(seen):
    answer = seen["answer"]
    if answer is None:
        return ['no element with id="answer" on the page: the summary table must carry it']
    if answer["height"] <= 0:
        return [f'the element with id="answer" (<{answer["tag"]}>) is not displayed (height {answer["height"]:g} px)']
    if answer["top"] >= HEIGHT:
        return [f'the element with id="answer" (<{answer["tag"]}>) starts at {answer["top"]:.0f} px, below the first '
                f'screen ({WIDTH} x {HEIGHT} px); {answer["blocks"]} blocks come before it, under the headings: '
                + (" / ".join(answer["headings"]) or "none")]
    return []


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
        print(f"\nfirst screen: {cls.screenshot}", file=sys.stderr)

    def test_it_loads_without_console_errors(self):
        self.assertNoProblems(console_problems(self.seen))

    def test_every_image_is_drawn(self):
        self.assertNoProblems(image_problems(self.seen))

    def test_every_figure_file_is_on_the_page(self):
        self.assertNoProblems(figure_problems(self.seen, REPORT))

    def test_the_answer_is_on_the_first_screen(self):
        self.assertNoProblems(answer_problems(self.seen))
        self.assertGreater(os.path.getsize(self.screenshot), 1000)

    def test_it_opens_with_the_fronts_above_the_answer(self):
        self.assertNoProblems(fronts_problems(self.seen))


GOOD_IMAGE = '<svg xmlns="http://www.w3.org/2000/svg" width="200" height="100"><rect width="200" height="100"/></svg>'


def hand_made(folder, body, figures=("drawn.svg",)):
    """A report folder with index.html holding `body` and the given figure files."""
    os.makedirs(os.path.join(folder, "figures"))
    for name in figures:
        with open(os.path.join(folder, "figures", name), "w") as f:
            f.write(GOOD_IMAGE)
    with open(os.path.join(folder, "index.html"), "w") as f:
        f.write(f'<!doctype html><html><head><meta charset="utf-8"><title>hand-made</title></head><body>{body}</body></html>')
    return folder


class TheChecksCanFail(unittest.TestCase):
    """Hand-made pages: a good one passes every check, a faulty one has each of its faults named."""

    @classmethod
    def setUpClass(cls):
        cls.folder = tempfile.mkdtemp(prefix="page_in_chromium_test_")

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.folder)

    def test_a_good_page_passes(self):
        report = hand_made(os.path.join(self.folder, "good"), '<h1>Report</h1><img src="figures/fronts.svg">'
                           '<table id="answer"><tr><td>engine_a</td></tr>'
                           '</table><img src="figures/drawn.svg" loading="lazy" style="margin-top:3000px">',
                           figures=("fronts.svg", "drawn.svg"))
        seen = look_at(report, os.path.join(report, "first-screen.png"))
        self.assertEqual(console_problems(seen) + image_problems(seen) + figure_problems(seen, report)
                         + answer_problems(seen) + fronts_problems(seen), [])

    def test_every_fault_is_named(self):
        report = hand_made(os.path.join(self.folder, "faulty"),
                           '<h1>Report</h1><h2>Caveats</h2><img src="figures/drawn.svg"><img src="figures/gone.svg">'
                           '<script>console.error("deliberate", 42); console.log("not an error")</script>'
                           '<div style="height:1500px"></div><table id="answer"><tr><td>x</td></tr></table>'
                           '<script>noSuchFunction()</script>', figures=("drawn.svg", "unshown.svg"))
        seen = look_at(report, os.path.join(report, "first-screen.png"))
        console = "\n".join(console_problems(seen))
        self.assertIn("console.error: deliberate 42", console)
        self.assertIn("figures/gone.svg", console)  # the failed load, with its file
        self.assertIn("noSuchFunction is not defined", console)
        self.assertNotIn("not an error", console)
        self.assertEqual(image_problems(seen), ['<img src="figures/gone.svg"> is not drawn (complete: true, naturalWidth: 0)'])
        self.assertRegex(" ".join(figure_problems(seen, report)), r"1 of the 2 files .*: unshown\.svg$")
        self.assertRegex(" ".join(answer_problems(seen)), r"starts at 1\d\d\d px, below the first screen.*Report / Caveats")
        self.assertEqual(fronts_problems(seen), ["the first image is figures/drawn.svg, not the fronts (figures/fronts.svg)"])

    def test_a_page_without_the_answer_is_reported(self):
        report = hand_made(os.path.join(self.folder, "no_answer"), '<img src="figures/drawn.svg">')
        self.assertIn('no element with id="answer"', " ".join(answer_problems(look_at(report, os.devnull))))

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
    report = subprocess.run([executable, "report", suite], capture_output=True, text=True)
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
