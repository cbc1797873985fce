"""A headless Chromium driven over the DevTools protocol on a pipe
(--remote-debugging-pipe: messages are JSON separated by NUL bytes on file
descriptors 3 and 4), with the standard library only: open a page, evaluate
JavaScript, click, take a screenshot. For tests/tools/test_viewer.py."""

import base64
import fcntl
import itertools
import json
import os
import shutil
import subprocess
import tempfile
import time

BINARIES = ("chromium-headless-shell", "chromium", "chromium-browser", "google-chrome")


def find():
    """The first headless-capable Chromium on PATH, or None."""
    for name in BINARIES:
        path = shutil.which(name)
        if path:
            return path
    return None


class Browser:
    def __init__(self, binary, width=1100, height=640):
        to_chrome_r, self._to_chrome = os.pipe()
        self._from_chrome, from_chrome_w = os.pipe()
        self.profile = tempfile.mkdtemp(prefix="lagmb-chromium-")
        args = [binary, "--headless", "--no-sandbox", "--enable-unsafe-swiftshader", "--remote-debugging-pipe",
                f"--user-data-dir={self.profile}", f"--window-size={width},{height}", "--hide-scrollbars",
                "--no-first-run", "--disable-extensions", "about:blank"]

        def on_fds_3_and_4():  # in the child: Chromium reads commands on 3 and writes replies on 4
            a = fcntl.fcntl(to_chrome_r, fcntl.F_DUPFD, 10)  # out of the way first: either may be 3 or 4
            b = fcntl.fcntl(from_chrome_w, fcntl.F_DUPFD, 10)
            os.dup2(a, 3)
            os.dup2(b, 4)

        # fds 3 and 4 stay open in the child (dup2 above makes them; close_fds closes the rest after it)
        # not the sanitizer runtimes make test-asan preloads into this process
        # (Chromium under a preloaded ASan spins and never answers)
        env = {k: v for k, v in os.environ.items() if k not in ("LD_PRELOAD", "ASAN_OPTIONS", "UBSAN_OPTIONS")}
        self.proc = subprocess.Popen(args, pass_fds=(3, 4), preexec_fn=on_fds_3_and_4, env=env,
                                     stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(to_chrome_r)
        os.close(from_chrome_w)
        self._ids = itertools.count(1)
        self._buffer = b""

    def _receive(self):
        while b"\0" not in self._buffer:
            chunk = os.read(self._from_chrome, 1 << 16)
            if not chunk:
                raise RuntimeError("Chromium closed its pipe")
            self._buffer += chunk
        message, self._buffer = self._buffer.split(b"\0", 1)
        return json.loads(message)

    def send(self, method, params=None, session=None):
        i = next(self._ids)
        message = {"id": i, "method": method, "params": params or {}}
        if session:
            message["sessionId"] = session
        os.write(self._to_chrome, json.dumps(message).encode() + b"\0")
        while True:
            reply = self._receive()
            if reply.get("id") == i:
                if "error" in reply:
                    raise RuntimeError(f"{method}: {reply['error']}")
                return reply["result"]

    def open(self, url):
        target = self.send("Target.createTarget", {"url": "about:blank"})["targetId"]
        session = self.send("Target.attachToTarget", {"targetId": target, "flatten": True})["sessionId"]
        page = Page(self, session, target)
        page.command("Page.enable")
        page.command("Runtime.enable")
        page.command("Page.navigate", {"url": url})
        return page

    def close(self):
        try:
            self.send("Browser.close")
        except Exception:  # noqa: BLE001 - it may be gone already
            pass
        try:
            self.proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
        for fd in (self._to_chrome, self._from_chrome):
            try:
                os.close(fd)
            except OSError:
                pass
        shutil.rmtree(self.profile, ignore_errors=True)


class Page:
    def __init__(self, browser, session, target):
        self.browser, self.session, self.target = browser, session, target

    def close(self):
        self.browser.send("Target.closeTarget", {"targetId": self.target})

    def command(self, method, params=None):
        return self.browser.send(method, params, self.session)

    def evaluate(self, expression):
        result = self.command("Runtime.evaluate", {"expression": expression, "returnByValue": True,
                                                   "awaitPromise": True})
        if "exceptionDetails" in result:
            raise RuntimeError(result["exceptionDetails"].get("exception", {}).get("description",
                                                                                    result["exceptionDetails"]))
        return result["result"].get("value")

    def wait_for(self, expression, timeout=60.0):
        start = time.monotonic()
        while time.monotonic() - start < timeout:
            try:
                value = self.evaluate(expression)
                if value:
                    return value
            except RuntimeError:
                pass
            time.sleep(0.1)
        raise TimeoutError(f"{expression} still false after {timeout} s")

    def click(self, x, y):
        for kind in ("mousePressed", "mouseReleased"):
            self.command("Input.dispatchMouseEvent", {"type": kind, "x": x, "y": y, "button": "left",
                                                      "clickCount": 1})

    def screenshot(self, path):
        data = self.command("Page.captureScreenshot", {"format": "png"})["data"]
        with open(path, "wb") as f:
            f.write(base64.b64decode(data))
