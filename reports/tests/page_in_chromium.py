"""A page as a reader sees it: opened in Debian's headless Chromium, driven over the Chrome DevTools Protocol.

Chromium is started with --remote-debugging-pipe: it reads commands on its file descriptor 3 and writes its
answers and events on its descriptor 4, each message one JSON object followed by a NUL byte. No websocket
and no library beyond Python's own. Every wait has a deadline: a hung Chromium raises TimeoutError (and is
killed) instead of hanging the test.

    with Chromium(width=1366, height=768) as browser:
        page = browser.open("/path/index.html")       # waits for the load event
        page.errors                                    # console errors, exceptions, failed loads
        page.evaluate("document.title")                # JavaScript's value, as JSON
        page.screenshot("first-screen.png")            # the viewport as the reader sees it first
"""

import base64
import fcntl
import json
import os
import pathlib
import select
import shutil
import subprocess
import tempfile
import time

CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run", "--no-default-browser-check",
         "--disable-background-networking", "--disable-component-update", "--disable-sync", "--disable-quic",
         "--disable-extensions", "--mute-audio", "--hide-scrollbars"]


class Chromium:
    """One headless Chromium process; `timeout_s` bounds every single wait for an answer or an event."""

    def __init__(self, width=1366, height=768, timeout_s=60.0):
        self.width, self.height, self.timeout_s = width, height, timeout_s
        self.process = None
        self.next_id = 0
        self.buffer = b""
        self.events = []  # every event received so far, in order: (sessionId or None, method, params)

    def __enter__(self):
        if not os.path.exists(CHROMIUM):
            raise FileNotFoundError(f"{CHROMIUM} is missing: install Debian's chromium (scripts/test.sh does)")
        self.profile = tempfile.mkdtemp(prefix="page_in_chromium_")
        self.log = tempfile.TemporaryFile()  # Chromium's own output, shown when it dies (a pipe could fill up)
        commands_read, self.commands = os.pipe()
        self.answers, answers_write = os.pipe()
        # Chromium wants its ends at exactly 3 and 4; bash puts them there as it execs Chromium (dash knows no
        # descriptor above 9). They are first moved to 10 and up so that no redirection overwrites the other.
        inner = [fcntl.fcntl(commands_read, fcntl.F_DUPFD_CLOEXEC, 10), fcntl.fcntl(answers_write, fcntl.F_DUPFD_CLOEXEC, 10)]
        os.close(commands_read)
        os.close(answers_write)
        command = [CHROMIUM, *FLAGS, "--remote-debugging-pipe", f"--user-data-dir={self.profile}",
                   f"--window-size={self.width},{self.height}", "about:blank"]
        self.process = subprocess.Popen(["/bin/bash", "-c", f'exec "$@" 3<&{inner[0]} 4>&{inner[1]}', "bash", *command],
                                        pass_fds=inner, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                        stderr=self.log, start_new_session=True)
        for fd in inner:  # our copies: the answer pipe then ends (EOF) when Chromium exits
            os.close(fd)
        return self

    def __exit__(self, *exception):
        self.close()

    def close(self):
        if self.process is None:
            return
        try:  # Chromium and its helper processes: the session that Popen started for it
            os.killpg(self.process.pid, 9)
        except ProcessLookupError:
            pass
        self.process.wait(timeout=30)
        for fd in (self.commands, self.answers):
            os.close(fd)
        self.log.close()
        self.process = None
        shutil.rmtree(self.profile, ignore_errors=True)

    def _receive(self, deadline, what):
        """The next message from Chromium, waiting until `deadline` (time.monotonic())."""
        while b"\0" not in self.buffer:
            left = deadline - time.monotonic()
            if left <= 0 or not select.select([self.answers], [], [], left)[0]:
                self.close()
                raise TimeoutError(f"Chromium gave no answer within {self.timeout_s:g} s while waiting for {what}")
            chunk = os.read(self.answers, 1 << 20)
            if not chunk:
                self._died(what)
            self.buffer += chunk
        message, _, self.buffer = self.buffer.partition(b"\0")
        return json.loads(message)

    def _died(self, what):
        self.log.seek(0)
        output = self.log.read().decode(errors="replace")[-2000:]
        self.close()
        raise RuntimeError(f"Chromium exited while waiting for {what}; its last output:\n{output}")

    def send(self, method, params=None, session=None):
        """Sends one command and returns its result; events arriving meanwhile are kept in self.events."""
        self.next_id += 1
        message = {"id": self.next_id, "method": method, "params": params or {}}
        if session:
            message["sessionId"] = session
        try:
            os.write(self.commands, json.dumps(message).encode() + b"\0")
        except BrokenPipeError:
            self._died(method)
        deadline = time.monotonic() + self.timeout_s
        while True:
            answer = self._receive(deadline, method)
            if "method" in answer:
                self.events.append((answer.get("sessionId"), answer["method"], answer.get("params", {})))
            elif answer.get("id") == self.next_id:
                if "error" in answer:
                    raise RuntimeError(f"{method} failed: {answer['error']}")
                return answer.get("result", {})

    def wait_for(self, method, session, since):
        """Waits for the event `method` of `session`, looking first at the events after index `since`."""
        deadline = time.monotonic() + self.timeout_s
        while True:
            for event in self.events[since:]:
                if event[:2] == (session, method):
                    return event[2]
            since = len(self.events)
            answer = self._receive(deadline, method)
            if "method" in answer:
                self.events.append((answer.get("sessionId"), answer["method"], answer.get("params", {})))

    def open(self, path):
        """Opens a local file in a new tab of the viewport's size and waits until it has loaded."""
        target = self.send("Target.createTarget", {"url": "about:blank"})["targetId"]
        session = self.send("Target.attachToTarget", {"targetId": target, "flatten": True})["sessionId"]
        for domain in ("Page", "Runtime", "Log", "Network"):
            self.send(f"{domain}.enable", session=session)
        self.send("Emulation.setDeviceMetricsOverride",
                  {"width": self.width, "height": self.height, "deviceScaleFactor": 1, "mobile": False}, session)
        since = len(self.events)
        url = pathlib.Path(path).resolve().as_uri()
        navigation = self.send("Page.navigate", {"url": url}, session)
        if navigation.get("errorText"):
            raise RuntimeError(f"Chromium could not open {url}: {navigation['errorText']}")
        self.wait_for("Page.loadEventFired", session, since)
        return Page(self, session, url, since, target)


class Page:
    """A loaded tab: its errors so far, JavaScript evaluated in it, and screenshots of its viewport."""

    def __init__(self, browser, session, url, since, target):
        self.browser, self.session, self.url, self.since, self.target = browser, session, url, since, target

    def close(self):
        """Closes the tab: a test that opens many pages (each figure alone) keeps one Chromium lean."""
        self.browser.send("Target.closeTarget", {"targetId": self.target})

    @property
    def errors(self):
        """Every error the page reported since it was opened, as one readable line each."""
        urls = {}  # requestId -> URL, to name what failed to load
        errors = []
        for session, method, params in self.browser.events[self.since:]:
            if session != self.session:
                continue
            if method == "Network.requestWillBeSent":
                urls[params["requestId"]] = params["request"]["url"]
            elif method == "Network.loadingFailed":
                errors.append(f"failed to load {urls.get(params['requestId'], params['requestId'])}: {params['errorText']}")
            elif method == "Runtime.consoleAPICalled" and params["type"] in ("error", "assert"):
                text = " ".join(str(a.get("value", a.get("description", a.get("type")))) for a in params["args"])
                errors.append(f"console.{params['type']}: {text}{_where(params.get('stackTrace'))}")
            elif method == "Runtime.exceptionThrown":
                details = params["exceptionDetails"]
                text = details.get("exception", {}).get("description") or details.get("text", "")
                errors.append(f"uncaught exception: {text} (line {details.get('lineNumber', 0) + 1})")
            elif method == "Log.entryAdded" and params["entry"]["level"] == "error":
                entry = params["entry"]
                errors.append(f"{entry['source']} error: {entry['text']}" + (f" ({entry['url']})" if entry.get("url") else ""))
        return errors

    def evaluate(self, expression):
        """The value of a JavaScript expression in the page (returned by value, so JSON-like)."""
        result = self.browser.send("Runtime.evaluate", {"expression": expression, "returnByValue": True,
                                                         "awaitPromise": True}, self.session)
        if "exceptionDetails" in result:
            details = result["exceptionDetails"]
            raise RuntimeError(f"JavaScript failed: {details.get('exception', {}).get('description') or details['text']}")
        return result["result"].get("value")

    def screenshot(self, png_path):
        """Saves the viewport (what the reader sees before scrolling) as a PNG."""
        data = self.browser.send("Page.captureScreenshot", {"format": "png"}, self.session)["data"]
        with open(png_path, "wb") as f:
            f.write(base64.b64decode(data))
        return png_path


def _where(stack):
    frames = (stack or {}).get("callFrames") or []
    return f" (line {frames[0]['lineNumber'] + 1})" if frames else ""
