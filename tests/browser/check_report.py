#!/usr/bin/env python3
"""The HTML report (`radchain report`, docs/report.md) in a real browser.

Builds the report of a folder of sensor files, then opens every page in Debian's headless Chromium at 1280 px wide,
driven over the DevTools protocol on a pipe (--remote-debugging-pipe: no port, no third-party Python package), and
checks what a reader would see:

  * no console error, no uncaught exception, no failed load, no broken image, no link to a missing file;
  * every number on a page that names its place in report.json (data-json, a JSON pointer) equals the number there,
    to the digits shown;
  * every curve of every plot has as many points as report.json's series has values;
  * the page fits 1280 px (document scrollWidth <= 1280): nothing to scroll sideways;
  * on the index, a click on a column header sorts the table by that column, as a user clicks it.

Screenshots of every page (1280 px wide, the whole page) are kept in ARTEFACTS/screenshots/ and the report itself in
ARTEFACTS/report/. Exit 0 when every check holds, 1 with one line per failure, 2 when it cannot run.

Usage: check_report.py --radchain BIN --sensors DIR --artefacts DIR [--chromium BIN]
"""
import argparse
import base64
import json
import math
import os
import re
import select
import shutil
import subprocess
import sys
import tempfile
import time
import urllib.parse

WIDTH = 1280
HEIGHT = 900
MAX_SHOT_HEIGHT = 6000  # a taller page is captured to this height (the rasterising is what costs)


class Browser:
    """Chromium driven over --remote-debugging-pipe: requests on fd 3, replies and events on fd 4, NUL-separated JSON."""

    def __init__(self, binary, profile):
        to_browser_r, self.to_browser = os.pipe()
        self.from_browser, from_browser_w = os.pipe()

        def wire():  # in the child: the protocol's two descriptors at 3 and 4, inherited through exec
            reading, writing = os.dup(to_browser_r), os.dup(from_browser_w)  # copies first: a pipe may sit at 3 or 4
            os.dup2(reading, 3)
            os.dup2(writing, 4)
            os.set_inheritable(3, True)  # dup2 onto itself keeps close-on-exec
            os.set_inheritable(4, True)

        args = [binary, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                "--disable-background-networking", "--disable-component-update", "--disable-sync",
                "--disable-default-apps", "--disable-extensions", "--mute-audio", "--hide-scrollbars",
                "--allow-file-access-from-files", f"--user-data-dir={profile}", "--remote-debugging-pipe",
                f"--window-size={WIDTH},{HEIGHT}", "about:blank"]
        self.log = open(os.path.join(profile, "chromium.log"), "wb")
        self.process = subprocess.Popen(args, preexec_fn=wire, close_fds=False, stdin=subprocess.DEVNULL,
                                        stdout=self.log, stderr=self.log)
        os.close(to_browser_r)
        os.close(from_browser_w)
        self.buffer = b""
        self.next_id = 0
        self.events = []

    def _read_message(self, deadline):
        while b"\0" not in self.buffer:
            left = deadline - time.monotonic()
            if left <= 0:
                raise TimeoutError("no answer from chromium")
            ready, _, _ = select.select([self.from_browser], [], [], left)
            if ready:
                chunk = os.read(self.from_browser, 1 << 20)
                if not chunk:
                    raise RuntimeError("chromium closed the pipe (see chromium.log)")
                self.buffer += chunk
        message, self.buffer = self.buffer.split(b"\0", 1)
        return json.loads(message)

    def call(self, method, params=None, session=None, timeout=30):
        self.next_id += 1
        request = {"id": self.next_id, "method": method, "params": params or {}}
        if session:
            request["sessionId"] = session
        os.write(self.to_browser, json.dumps(request).encode() + b"\0")
        deadline = time.monotonic() + timeout
        while True:
            message = self._read_message(deadline)
            if message.get("id") == self.next_id:
                if "error" in message:
                    raise RuntimeError(f"{method}: {message['error']}")
                return message.get("result", {})
            self.events.append(message)

    def wait_event(self, method, session, timeout=30):
        deadline = time.monotonic() + timeout
        while True:
            for i, event in enumerate(self.events):
                if event.get("method") == method and event.get("sessionId") == session:
                    return self.events.pop(i)
            self.events.append(self._read_message(deadline))

    def close(self):
        try:
            self.call("Browser.close", timeout=5)
        except Exception:
            pass
        try:
            self.process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.process.kill()
            self.process.wait()
        self.log.close()


def resolve(document, pointer):
    """A JSON pointer (RFC 6901) into report.json."""
    value = document
    for part in pointer.lstrip("/").split("/"):
        part = part.replace("~1", "/").replace("~0", "~")
        value = value[int(part)] if isinstance(value, list) else value[part]
    return value


def shown_equals(text, value):
    """The number shown equals `value` to the digits it shows (half a unit in the last place)."""
    match = re.fullmatch(r"\s*([+-]?)(\d*)(?:\.(\d*))?(?:[eE]([+-]?\d+))?\s*", text)
    if not match or value is None:
        return False
    shown = float(text)
    decimals = len(match.group(3) or "")
    exponent = int(match.group(4) or 0)
    half_ulp = 0.5 * 10.0 ** (exponent - decimals)
    return abs(shown - value) <= half_ulp * (1 + 1e-9) + 1e-300


PAGE_PROBE = r"""
(() => {
  const numbers = Array.from(document.querySelectorAll('[data-json]')).map(e => [e.getAttribute('data-json'), e.textContent]);
  const curves = Array.from(document.querySelectorAll('svg.plot')).map(svg => [svg.id,
      Array.from(svg.querySelectorAll('path.curve')).map(p => [p.getAttribute('data-series'), Number(p.getAttribute('data-points')),
          (p.getAttribute('d').match(/[ML]/g) || []).length])]);
  const brokenImages = Array.from(document.images).filter(i => !i.complete || i.naturalWidth === 0).map(i => i.src);
  const links = Array.from(document.querySelectorAll('a[href]')).map(a => a.getAttribute('href'));
  const external = Array.from(document.querySelectorAll('[src],link[href]')).map(e => e.getAttribute('src') || e.getAttribute('href'))
      .filter(u => /^(https?:)?\/\//.test(u));
  // Text drawn outside its SVG (a label cut at the edge): every text element's box inside the viewBox.
  // (Boxes on the screen, so that a rotated label counts as drawn.)
  const clipped = [];
  document.querySelectorAll('svg.plot').forEach(svg => {
    const s = svg.getBoundingClientRect();
    svg.querySelectorAll('text').forEach(t => {
      const b = t.getBoundingClientRect();
      if (b.left < s.left - 1 || b.top < s.top - 1 || b.right > s.right + 1 || b.bottom > s.bottom + 1)
        clipped.push(svg.id + ': ' + t.textContent);
    });
  });
  return JSON.stringify({numbers, curves, brokenImages, links, external, clipped,
      scrollWidth: document.documentElement.scrollWidth, scrollHeight: document.documentElement.scrollHeight,
      title: document.title});
})()
"""


def check_page(browser, session, path, report, artefacts, failures):
    started = time.monotonic()
    url = "file://" + urllib.parse.quote(os.path.abspath(path))
    browser.events = [e for e in browser.events if e.get("sessionId") != session]
    browser.call("Page.navigate", {"url": url}, session)
    browser.wait_event("Page.loadEventFired", session)
    probe = json.loads(browser.call("Runtime.evaluate", {"expression": PAGE_PROBE, "returnByValue": True}, session)["result"]["value"])
    name = os.path.relpath(path, os.path.join(artefacts, "report"))

    def fail(what):
        failures.append(f"{name}: {what}")

    for event in browser.events:
        if event.get("sessionId") != session:
            continue
        method, params = event.get("method"), event.get("params", {})
        if method == "Runtime.consoleAPICalled" and params.get("type") in ("error", "assert", "warning"):
            fail("console " + params["type"] + ": " + " ".join(str(a.get("value", a.get("description", ""))) for a in params.get("args", [])))
        elif method == "Runtime.exceptionThrown":
            fail("uncaught exception: " + params.get("exceptionDetails", {}).get("text", ""))
        elif method == "Log.entryAdded" and params.get("entry", {}).get("level") == "error":
            fail("console error: " + params["entry"].get("text", "") + " " + params["entry"].get("url", ""))
        elif method == "Network.loadingFailed":
            fail("failed to load: " + params.get("errorText", ""))

    if probe["brokenImages"]:
        fail(f"broken images: {probe['brokenImages']}")
    if probe["external"]:
        fail(f"fetches from the network: {probe['external']}")
    for href in probe["links"]:
        target = href.split("#")[0]
        if target and not re.match(r"^[a-z]+:", target) and not os.path.exists(os.path.join(os.path.dirname(path), target)):
            fail(f"link to a missing file: {href}")
    if probe["scrollWidth"] > WIDTH:
        fail(f"wider than {WIDTH} px: scrollWidth {probe['scrollWidth']}")
    if probe["clipped"]:
        fail(f"text outside its plot: {probe['clipped'][:3]}")

    if not probe["numbers"]:
        fail("no number names its place in report.json")
    for pointer, text in probe["numbers"]:
        try:
            value = resolve(report, pointer)
        except (KeyError, IndexError, ValueError, TypeError):
            fail(f"{pointer}: no such place in report.json")
            continue
        if not shown_equals(text, value):
            fail(f"{pointer}: the page shows {text!r}, report.json has {value!r}")

    sensor = next((s for s in report["sensors"] if os.path.normpath(s["page"]) == os.path.normpath(name)), None)
    plots = sensor.get("plots", {}) if sensor else {}
    for svg_id, curves in probe["curves"]:
        key = svg_id[len("plot-"):] if svg_id.startswith("plot-") else svg_id
        if key.startswith("tornado"):
            continue
        series = plots.get(key, {}).get("series")
        if series is None:
            fail(f"{svg_id}: no plot \"{key}\" in report.json")
            continue
        if len(series) != len(curves):
            fail(f"{svg_id}: {len(curves)} curves, report.json has {len(series)}")
            continue
        for (label, points, commands), s in zip(curves, series):
            finite = sum(1 for x, y in zip(s["x"], s["y"]) if x is not None and y is not None and
                         (not plots[key].get("y_log") or y > 0) and (not plots[key].get("x_log") or x > 0))
            if label != s["label"] or points != finite or commands != finite:
                fail(f"{svg_id}: curve {label!r} draws {points} points ({commands} in its path), report.json has {finite}")

    probe["seconds_checking"] = time.monotonic() - started
    started = time.monotonic()
    height = min(probe["scrollHeight"], MAX_SHOT_HEIGHT)
    shot = browser.call("Page.captureScreenshot", {"format": "png", "captureBeyondViewport": True, "optimizeForSpeed": True,
                                                   "clip": {"x": 0, "y": 0, "width": WIDTH, "height": height, "scale": 1}},
                        session, timeout=60)
    shot_path = os.path.join(artefacts, "screenshots", name.replace(os.sep, "_").replace(".html", ".png"))
    with open(shot_path, "wb") as f:
        f.write(base64.b64decode(shot["data"]))
    probe["seconds_screenshot"] = time.monotonic() - started
    return probe


SORT_PROBE = r"""
(() => {
  const table = document.getElementById('instruments');
  const th = Array.from(table.tHead.rows[0].cells).find(c => c.textContent.startsWith(%s));
  const r = th.getBoundingClientRect();
  return JSON.stringify({x: r.left + r.width / 2, y: r.top + r.height / 2, column: th.cellIndex});
})()
"""

COLUMN_PROBE = r"""
JSON.stringify(Array.from(document.getElementById('instruments').tBodies[0].rows).map(r => {
  const c = r.cells[%d]; return c.hasAttribute('data-sort') ? c.getAttribute('data-sort') : c.textContent.trim(); }))
"""


def click_sorts(browser, session, header, numeric, failures):
    """A click on the header (a real mouse event at its place) sorts the column ascending, a second descending."""
    browser.call("Runtime.evaluate", {"expression": "window.scrollTo(0, 0)"}, session)
    where = json.loads(browser.call("Runtime.evaluate", {"expression": SORT_PROBE % json.dumps(header), "returnByValue": True},
                                    session)["result"]["value"])
    for direction in ("ascending", "descending"):
        for kind in ("mousePressed", "mouseReleased"):
            browser.call("Input.dispatchMouseEvent", {"type": kind, "x": where["x"], "y": where["y"], "button": "left",
                                                      "clickCount": 1}, session)
        values = json.loads(browser.call("Runtime.evaluate", {"expression": COLUMN_PROBE % where["column"], "returnByValue": True},
                                         session)["result"]["value"])
        keys = [float(v) for v in values] if numeric else [v.lower() for v in values]
        expected = sorted(keys, reverse=direction == "descending")
        if keys != expected:
            failures.append(f"index.html: a click on \"{header}\" does not sort it {direction}: {values[:6]}...")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--radchain", required=True)
    parser.add_argument("--sensors", required=True)
    parser.add_argument("--artefacts", required=True)
    parser.add_argument("--chromium", default=shutil.which("chromium") or shutil.which("chromium-browser"))
    args = parser.parse_args()
    if not args.chromium:
        print("check_report: Debian's chromium is not installed (scripts/setup-debian.sh installs it)", file=sys.stderr)
        return 2
    started = time.monotonic()
    artefacts = os.path.abspath(args.artefacts)
    os.makedirs(os.path.join(artefacts, "screenshots"), exist_ok=True)
    for old in os.listdir(os.path.join(artefacts, "screenshots")):
        os.remove(os.path.join(artefacts, "screenshots", old))
    out = os.path.join(artefacts, "report")
    run = subprocess.run([args.radchain, "report", args.sensors, "--out", out], capture_output=True, text=True)
    if run.returncode != 0:
        print(f"check_report: radchain report exited {run.returncode}:\n{run.stdout}{run.stderr}", file=sys.stderr)
        return 1
    built = time.monotonic()
    with open(os.path.join(out, "report.json")) as f:
        report = json.load(f)
    pages = [os.path.join(out, "index.html")] + [os.path.join(out, s["page"]) for s in report["sensors"]]
    toml = sorted(f for f in os.listdir(args.sensors) if f.endswith(".toml"))
    failures = []
    if len(report["sensors"]) != len(toml):
        failures.append(f"report.json lists {len(report['sensors'])} sensors, {args.sensors} holds {len(toml)} files")

    profile = tempfile.mkdtemp(prefix="radchain-chromium-")
    browser = Browser(args.chromium, profile)
    numbers, checking, shooting = 0, 0.0, 0.0
    try:
        target = browser.call("Target.createTarget", {"url": "about:blank"})["targetId"]
        session = browser.call("Target.attachToTarget", {"targetId": target, "flatten": True})["sessionId"]
        for domain in ("Page", "Runtime", "Log", "Network"):
            browser.call(f"{domain}.enable", {}, session)
        browser.call("Emulation.setDeviceMetricsOverride", {"width": WIDTH, "height": HEIGHT, "deviceScaleFactor": 1,
                                                            "mobile": False}, session)
        for path in pages:
            probe = check_page(browser, session, path, report, artefacts, failures)
            numbers += len(probe["numbers"])
            checking += probe["seconds_checking"]
            shooting += probe["seconds_screenshot"]
        # The index as a user sorts it: by name (text) and by the share of checks that pass (numbers).
        browser.call("Page.navigate", {"url": "file://" + urllib.parse.quote(pages[0])}, session)
        browser.wait_event("Page.loadEventFired", session)
        click_sorts(browser, session, "Instrument", False, failures)
        click_sorts(browser, session, "Checks ok", True, failures)
    finally:
        browser.close()
        shutil.rmtree(profile, ignore_errors=True)

    elapsed = time.monotonic() - started
    for f in failures:
        print("FAIL " + f)
    print(f"check_report: {len(pages)} pages, {numbers} numbers compared with report.json, screenshots in "
          f"{os.path.join(artefacts, 'screenshots')}; report {built - started:.1f} s, browser {elapsed - (built - started):.1f} s, "
          f"total {elapsed:.1f} s (pages checked in {checking:.1f} s, screenshots {shooting:.1f} s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
