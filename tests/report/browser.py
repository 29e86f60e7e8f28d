"""Headless Chromium driven over the DevTools protocol on a pipe (--remote-debugging-pipe).

A pipe rather than chromedriver or a debugging port: no port to pick or race for, no driver whose
version must match the browser, and the browser is our own child, so it cannot outlive us. The
browser runs in a process group of its own and with a parent-death signal; closing it (also on an
exception, SIGTERM, SIGINT or the caller's deadline) kills that group and any orphan that was
reparented to us (we are a child subreaper), so no Chromium process is left behind even when a test
fails halfway.

Python 3 standard library only.
"""
import base64
import ctypes
import fcntl
import json
import os
import select
import shutil
import signal
import subprocess
import tempfile
import time

# Without the background-networking flags Chromium keeps trying to reach Google on a closed network
# and logs those failures; --disable-gpu because there is no GPU; --no-sandbox because we run as root.
FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--disable-default-apps", "--disable-extensions", "--mute-audio", "--hide-scrollbars",
         "--remote-debugging-pipe"]
PR_SET_PDEATHSIG = 1
PR_SET_CHILD_SUBREAPER = 36


class BrowserError(RuntimeError):
    pass


def find_chromium():
    """The Chromium executable (BSPBENCH_CHROMIUM, else chromium on PATH), or None."""
    return os.environ.get("BSPBENCH_CHROMIUM") or shutil.which("chromium") or shutil.which("chromium-browser")


def _prctl(option, arg):
    try:
        ctypes.CDLL(None, use_errno=True).prctl(option, arg, 0, 0, 0)
    except (AttributeError, OSError):
        pass  # not Linux: the process-group kill still runs


def _children(pid):
    """Direct children of pid, from /proc."""
    kids = []
    for child in _pids():
        try:
            with open(f"/proc/{child}/stat") as f:
                stat = f.read()
        except OSError:
            continue
        # The command name in parentheses may hold spaces; the fields after it do not.
        if int(stat[stat.rindex(")") + 2:].split()[1]) == pid:
            kids.append(child)
    return kids


def _pids():
    return [int(entry) for entry in os.listdir("/proc") if entry.isdigit()]


def _pgid(pid):
    try:
        return os.getpgid(pid)
    except ProcessLookupError:
        return None


def _raise_on_signal(signum, _frame):
    raise SystemExit(f"killed by signal {signum}")


class Browser:
    """with Browser(log_path) as b: page = b.open(url, width, height) ..."""

    def __init__(self, log_path, executable=None, timeout=60):
        self.executable = executable or find_chromium()
        if not self.executable:
            raise BrowserError("chromium is not installed (apt-get install chromium)")
        self.log_path = log_path
        self.timeout = timeout
        self.proc = None
        self._buf = b""
        self._next_id = 0
        self.events = []
        self.leftover = []  # processes of the browser's group still there after close (should be none)

    def __enter__(self):
        # SIGTERM and SIGHUP (ctest, a closed terminal) unwind through __exit__ like an exception.
        for sig in (signal.SIGTERM, signal.SIGHUP):
            signal.signal(sig, _raise_on_signal)
        _prctl(PR_SET_CHILD_SUBREAPER, 1)
        self._known_children = set(_children(os.getpid()))
        self._profile = tempfile.mkdtemp(prefix="bspbench-chromium-")
        to_browser_r, self._to_browser = os.pipe()
        self._from_browser, from_browser_w = os.pipe()
        # Chromium reads commands on fd 3 and writes on fd 4. bash (dash takes single-digit fds
        # only) moves our ends there; they are first moved to 10 and above so that neither can
        # already be 3 or 4 and be overwritten by the other's move.
        child_r = fcntl.fcntl(to_browser_r, fcntl.F_DUPFD, 10)
        child_w = fcntl.fcntl(from_browser_w, fcntl.F_DUPFD, 10)
        os.close(to_browser_r)
        os.close(from_browser_w)
        self._log = open(self.log_path, "wb")
        try:
            self.proc = subprocess.Popen(
                ["/bin/bash", "-c", f'exec "$@" 3<&{child_r} 4>&{child_w} {child_r}<&- {child_w}>&-', "bash",
                 self.executable, *FLAGS, f"--user-data-dir={self._profile}", "about:blank"],
                pass_fds=(child_r, child_w), stdin=subprocess.DEVNULL, stdout=self._log, stderr=self._log,
                start_new_session=True, preexec_fn=lambda: _prctl(PR_SET_PDEATHSIG, signal.SIGKILL))
        finally:
            os.close(child_r)
            os.close(child_w)
        try:
            self.send("Browser.getVersion")
        except BaseException:
            self.close()
            raise
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    # The protocol: JSON messages separated by NUL bytes.

    def _read_message(self, deadline):
        while b"\0" not in self._buf:
            left = deadline - time.monotonic()
            if left <= 0:
                raise BrowserError("Chromium did not answer in time")
            ready, _, _ = select.select([self._from_browser], [], [], left)
            if ready:
                data = os.read(self._from_browser, 1 << 20)
                if not data:
                    raise BrowserError(f"Chromium exited (its log: {self.log_path}): {self.log_tail()}")
                self._buf += data
        message, self._buf = self._buf.split(b"\0", 1)
        return json.loads(message)

    def send(self, method, params=None, session=None, timeout=None):
        """Sends a command and returns its result; events read meanwhile go to self.events."""
        self._next_id += 1
        message = {"id": self._next_id, "method": method, "params": params or {}}
        if session:
            message["sessionId"] = session
        os.write(self._to_browser, json.dumps(message).encode() + b"\0")
        deadline = time.monotonic() + (timeout or self.timeout)
        while True:
            reply = self._read_message(deadline)
            if reply.get("id") == self._next_id:
                if "error" in reply:
                    raise BrowserError(f"{method}: {reply['error'].get('message')}")
                return reply.get("result", {})
            if "method" in reply:
                self.events.append(reply)

    def wait_event(self, method, session, timeout=None):
        deadline = time.monotonic() + (timeout or self.timeout)
        seen = 0
        while True:
            for event in self.events[seen:]:
                if event["method"] == method and event.get("sessionId") == session:
                    return event
            seen = len(self.events)
            self.events.append(self._read_message(deadline))

    def log_tail(self, lines=15):
        try:
            with open(self.log_path, errors="replace") as f:
                return "".join(f.readlines()[-lines:])
        except OSError:
            return ""

    def open(self, url, width, height):
        """A new tab of width x height CSS pixels with url loaded (its load event fired)."""
        target = self.send("Target.createTarget", {"url": "about:blank"})
        session = self.send("Target.attachToTarget", {"targetId": target["targetId"], "flatten": True})["sessionId"]
        page = Page(self, session)
        # Every domain whose messages we judge is enabled before the page starts loading.
        for domain in ("Page", "Runtime", "Log", "Network"):
            self.send(domain + ".enable", session=session)
        self.send("Emulation.setDeviceMetricsOverride",
                  {"width": width, "height": height, "deviceScaleFactor": 1, "mobile": False}, session)
        nav = self.send("Page.navigate", {"url": url}, session)
        if nav.get("errorText"):
            raise BrowserError(f"cannot open {url}: {nav['errorText']}")
        self.wait_event("Page.loadEventFired", session)
        # Let timers and the first frame after load run, so late console messages are caught too.
        page.evaluate("new Promise(r => requestAnimationFrame(() => setTimeout(r, 300)))")
        return page

    def close(self):
        """Ends the browser and everything it started; safe to call twice."""
        if self.proc is None:
            return
        proc, self.proc = self.proc, None
        # A deadline, ^C or SIGTERM arriving now must not cut the cleanup short; they are
        # delivered when it is done.
        held = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGALRM, signal.SIGINT, signal.SIGTERM, signal.SIGHUP})
        try:
            self._end(proc)
        finally:
            signal.pthread_sigmask(signal.SIG_SETMASK, held)

    def _end(self, proc):
        if proc.poll() is None:
            try:
                self.send("Browser.close", timeout=5)
            except (BrowserError, OSError):
                pass
            try:
                proc.wait(timeout=5)
            except subprocess.TimeoutExpired:
                pass
        try:
            os.killpg(proc.pid, signal.SIGKILL)  # whatever of its group is still running
        except (ProcessLookupError, PermissionError):
            pass
        proc.wait()
        # Processes that left the group (Chromium's crash handler starts its own session) and were
        # orphaned came to us, the subreaper: end and reap them.
        for _ in range(20):
            strays = [pid for pid in _children(os.getpid()) if pid not in self._known_children]
            if not strays:
                break
            for pid in strays:
                try:
                    os.kill(pid, signal.SIGKILL)
                    os.waitpid(pid, 0)
                except (ProcessLookupError, ChildProcessError):
                    pass
        for fd in (self._to_browser, self._from_browser):
            try:
                os.close(fd)
            except OSError:
                pass
        self._log.close()
        shutil.rmtree(self._profile, ignore_errors=True)
        self.leftover = [pid for pid in _pids() if _pgid(pid) == proc.pid]


class Page:
    def __init__(self, browser, session):
        self.browser = browser
        self.session = session

    def evaluate(self, expression):
        """The value of a JavaScript expression (awaited when it is a promise)."""
        result = self.browser.send("Runtime.evaluate", {"expression": expression, "returnByValue": True,
                                                        "awaitPromise": True}, self.session)
        if "exceptionDetails" in result:
            raise BrowserError(f"{expression}: {result['exceptionDetails'].get('text')}")
        return result["result"].get("value")

    def screenshot(self, path, height=None, scale=1):
        """Saves a PNG of the page from its top: height CSS pixels of it, or all of it when None."""
        size = self.browser.send("Page.getLayoutMetrics", session=self.session)["cssContentSize"]
        clip = {"x": 0, "y": 0, "width": size["width"], "height": min(height or size["height"], size["height"]),
                "scale": scale}
        shot = self.browser.send("Page.captureScreenshot", {"format": "png", "clip": clip,
                                                            "captureBeyondViewport": True}, self.session)
        with open(path, "wb") as f:
            f.write(base64.b64decode(shot["data"]))
        return clip

    def problems(self):
        """What the page logged as an error or a warning, and every failed load, one line each."""
        mine = [e for e in self.browser.events if e.get("sessionId") == self.session]
        urls = {e["params"]["requestId"]: e["params"]["request"]["url"]
                for e in mine if e["method"] == "Network.requestWillBeSent"}
        echoed = {e["params"]["entry"].get("networkRequestId") for e in mine if e["method"] == "Log.entryAdded"}
        found = []
        for event in mine:
            method, params = event["method"], event["params"]
            if method == "Runtime.consoleAPICalled" and params["type"] in ("error", "warning", "assert"):
                text = " ".join(str(a.get("value", a.get("description", ""))) for a in params["args"])
                found.append(f"console.{params['type']}: {text}")
            elif method == "Runtime.exceptionThrown":
                details = params["exceptionDetails"]
                found.append(f"uncaught exception: {details.get('exception', {}).get('description') or details['text']}")
            elif method == "Log.entryAdded" and params["entry"]["level"] in ("error", "warning"):
                entry = params["entry"]
                found.append(f"{entry['level']} ({entry['source']}): {entry['text']} {entry.get('url', '')}".rstrip())
            elif method == "Network.loadingFailed" and not params.get("canceled") and params["requestId"] not in echoed:
                # A failed load counts even if Chromium stops echoing it to the console.
                found.append(f"error (network): failed to load {urls.get(params['requestId'], '?')}: "
                             f"{params['errorText']}")
            elif method == "Network.responseReceived" and params["response"].get("status", 200) >= 400:
                found.append(f"error (network): HTTP {params['response']['status']} for {params['response']['url']}")
        return found
