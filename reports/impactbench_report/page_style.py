"""The report page's style sheet. The page must read in a 1400 x 1000 window (issue 46): no table or figure
wider than the page, checked in Chromium by reports/tests/test_page_in_chromium.py. So nothing here keeps a
cell from wrapping or lets a table scroll sideways (a scrolled table hides its last columns, the verdicts and
costs, from a reader who does not know to scroll): every table is at most the page's width, its cells wrap at
spaces (a word longer than the whole table can be is broken inside); a dense table (tables.DENSE_COLUMNS columns or
more, class "dense") is set smaller; every image scales down to the page's width."""

STYLE = """
body { font-family: sans-serif; margin: 1.5em auto; max-width: 1340px; padding: 0 1em; color: #222; }
h1 { font-size: 1.35em; margin: 0.3em 0; } .lede { font-size: 0.85em; margin: 0.3em 0; }
#answer, #cases { font-size: 0.8em; } #answer td, #cases td { padding: 0.15em 0.4em; }
#answer th, #cases th { font-size: 0.9em; } #answer td { min-width: 4em; }
#answer td:nth-child(3n+2) { text-align: left; }
#cases td:nth-child(2), #cases td:nth-child(6) { text-align: left; min-width: 9em; }  /* ties wrap */
.notes { font-size: 0.75em; color: #444; margin: 0.2em 0; } .engines { font-size: 0.8em; margin: 0.4em 0; } .convention { font-size: 0.8em; color: #444; }
p.case + table td:last-child { min-width: 12em; }  /* the reason: prose, wraps */
nav { font-size: 0.85em; margin: 1em 0; } h2 { font-size: 1.2em; border-bottom: 1px solid #ccc; margin-top: 2em; }
table { border-collapse: collapse; font-size: 0.85em; margin: 0.8em 0; max-width: 100%; }
th, td { border: 1px solid #ccc; padding: 0.25em 0.5em; text-align: right; overflow-wrap: break-word; }
th { background: #f2f2f2; } td:first-child, th:first-child { text-align: left; }
table.dense { font-size: 0.72em; } table.dense th, table.dense td { padding: 0.15em 0.3em; }
#answer table.dense { font-size: 1em; }  /* already set smaller by #answer */
figure { margin: 1em 0; } figure img, figure svg { width: 100%; height: auto; }
img, svg, object, video { max-width: 100%; height: auto; }
pre { white-space: pre-wrap; overflow-wrap: anywhere; }
dl { display: grid; grid-template-columns: max-content minmax(0, 1fr); gap: 0.2em 1em; font-size: 0.9em; }
dd { overflow-wrap: anywhere; margin: 0; }
dt { font-weight: bold; } .caveats li { margin: 0.3em 0; }
"""
