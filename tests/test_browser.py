"""A real browser opens a handout's index.html: headless Chromium driven over the DevTools
protocol through a pipe (``--remote-debugging-pipe``: JSON messages ending in NUL on file
descriptors 3 and 4), with the standard library only.

Checked: every <img> sheet loads (complete, its natural size the SVG's millimetres at 96 px an
inch) and draws ink (drawn onto a canvas, some pixels are dark); nothing is reported as an
error (console errors, uncaught exceptions, failed loads in the browser's log); printing to
PDF with the page's CSS page sizes gives one page per assignment (A4 landscape, first), then
per variant one page of values and one per answer-key sheet. A screenshot is saved in the
test's tmp_path.

Chromium is looked for as $PLANS_CHROMIUM, chromium, chromium-browser, google-chrome; without
one the test is skipped, saying so (.ci/run installs Debian's chromium where apt-get works).
"""

from __future__ import annotations

import base64
import json
import os
import re
import select
import shutil
import subprocess
import time
from pathlib import Path

import pytest

from plans.cli import main
from plans.export import sheet_size_mm

from conftest import press_without_cycle

#: Longest wait for one answer or event from the browser, s.
TIMEOUT = 60.0
#: CSS pixels per millimetre (96 px an inch).
PX_PER_MM = 96 / 25.4
#: A4 in PDF points (Chromium writes 841.92 × 594.96).
A4_PT = (841.92, 594.96)
PT_PER_MM = 72 / 25.4


def _sheet_order(path: Path) -> tuple[int, str]:
    """``…-assignment.svg`` before its answer sheets ``…-assignment-2.svg``, ``-3`` …"""
    tail = path.stem.rsplit("-", 1)[-1]
    return (int(tail), path.name) if tail.isdigit() else (1, path.name)


def _chromium() -> str | None:
    for name in (os.environ.get("PLANS_CHROMIUM"), "chromium", "chromium-browser", "google-chrome"):
        found = name and shutil.which(name)
        if found:
            return found
    return None


class Browser:
    """Headless Chromium and a DevTools-protocol session on one page, over a pipe."""

    def __init__(self, exe: str, profile: Path):
        to_r, to_w = os.pipe()        # we write commands, Chromium reads them on fd 3
        from_r, from_w = os.pipe()    # Chromium writes answers and events on fd 4

        def onto_3_and_4() -> None:   # in the child, before exec
            a, b = os.dup(to_r), os.dup(from_w)
            os.dup2(a, 3)
            os.dup2(b, 4)
            os.set_inheritable(3, True)
            os.set_inheritable(4, True)

        args = [exe, "--headless", "--no-sandbox", "--disable-gpu", "--remote-debugging-pipe",
                f"--user-data-dir={profile}", "--no-first-run", "--disable-background-networking",
                "--disable-component-update", "--disable-sync", "--disable-quic", "--disable-extensions",
                "--allow-file-access-from-files", "about:blank"]
        self.proc = subprocess.Popen(args, preexec_fn=onto_3_and_4, close_fds=False, stdin=subprocess.DEVNULL,
                                     stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(to_r)
        os.close(from_w)
        self._w, self._r = to_w, from_r
        self._buf = b""
        self._id = 0
        self.events: list[dict] = []
        self.session: str | None = None

    def _message(self, deadline: float) -> dict:
        while b"\0" not in self._buf:
            left = deadline - time.monotonic()
            if left <= 0 or not select.select([self._r], [], [], left)[0]:
                raise TimeoutError("Chromium did not answer in time")
            chunk = os.read(self._r, 1 << 16)
            if not chunk:
                raise RuntimeError("Chromium closed the DevTools pipe")
            self._buf += chunk
        raw, self._buf = self._buf.split(b"\0", 1)
        return json.loads(raw)

    def send(self, method: str, params: dict | None = None, *, page: bool = True) -> dict:
        """Send a command (to the page's session unless ``page`` is False) and return its result;
        events that arrive meanwhile are kept in ``events``."""
        self._id += 1
        msg = {"id": self._id, "method": method, "params": params or {}}
        if page and self.session:
            msg["sessionId"] = self.session
        data = json.dumps(msg).encode() + b"\0"
        while data:
            data = data[os.write(self._w, data):]
        deadline = time.monotonic() + TIMEOUT
        while True:
            m = self._message(deadline)
            if m.get("id") == self._id:
                if "error" in m:
                    raise RuntimeError(f"{method}: {m['error']}")
                return m.get("result", {})
            self.events.append(m)

    def wait(self, method: str) -> dict:
        deadline = time.monotonic() + TIMEOUT
        while True:
            for k, e in enumerate(self.events):
                if e.get("method") == method:
                    return self.events.pop(k)
            self.events.append(self._message(deadline))

    def open(self, url: str) -> None:
        target = self.send("Target.createTarget", {"url": "about:blank"}, page=False)["targetId"]
        self.session = self.send("Target.attachToTarget", {"targetId": target, "flatten": True},
                                 page=False)["sessionId"]
        for domain in ("Page", "Runtime", "Log"):
            self.send(f"{domain}.enable")
        self.send("Emulation.setDeviceMetricsOverride", {"width": 1280, "height": 1000, "deviceScaleFactor": 1,
                                                          "mobile": False})
        self.send("Page.navigate", {"url": url})
        self.wait("Page.loadEventFired")

    def errors(self) -> list[str]:
        """Console errors, uncaught exceptions and error entries of the browser's log so far."""
        out = []
        for e in self.events:
            p = e.get("params", {})
            if e.get("method") == "Runtime.consoleAPICalled" and p.get("type") in ("error", "assert"):
                out.append("console: " + " ".join(str(a.get("value", a.get("description"))) for a in p["args"]))
            elif e.get("method") == "Runtime.exceptionThrown":
                out.append("exception: " + p["exceptionDetails"].get("text", ""))
            elif e.get("method") == "Log.entryAdded" and p["entry"]["level"] == "error":
                out.append(f"log: {p['entry']['text']} {p['entry'].get('url', '')}")
        return out

    def close(self) -> None:
        try:
            self.send("Browser.close", page=False)
        except (RuntimeError, TimeoutError, OSError):
            pass
        try:
            self.proc.wait(10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
        for fd in (self._w, self._r):
            os.close(fd)


#: For every <img>: its src, whether it loaded, its natural size (CSS px) and how many dark
#: pixels it draws on a canvas a quarter of its size.
_IMAGES = """JSON.stringify([...document.images].map(i => {
  if (!i.complete || i.naturalWidth === 0) return [i.getAttribute('src'), i.complete, i.naturalWidth, i.naturalHeight, 0];
  const c = document.createElement('canvas');
  c.width = Math.max(1, Math.round(i.naturalWidth / 4)); c.height = Math.max(1, Math.round(i.naturalHeight / 4));
  const g = c.getContext('2d'); g.drawImage(i, 0, 0, c.width, c.height);
  const d = g.getImageData(0, 0, c.width, c.height).data; let dark = 0;
  for (let k = 0; k < d.length; k += 4) if (d[k + 3] > 0 && d[k] + d[k + 1] + d[k + 2] < 384) dark++;
  return [i.getAttribute('src'), i.complete, i.naturalWidth, i.naturalHeight, dark];
}))"""


def _pages(pdf: bytes) -> list[tuple[float, float]]:
    """Each page's size (points) in a PDF as Chromium writes it (one /MediaBox per page object)."""
    pages = re.findall(rb"/Type\s*/Page\b(?!s)", pdf)
    boxes = [tuple(float(x) for x in m.split()[2:4])
             for m in re.findall(rb"/MediaBox\s*\[\s*([-0-9. ]+)\]", pdf)]
    assert len(boxes) == len(pages), "a page without its own /MediaBox"
    return boxes


def test_index_in_headless_chromium(tmp_path):
    exe = _chromium()
    if exe is None:
        pytest.skip("Chromium not found (looked for $PLANS_CHROMIUM, chromium, chromium-browser, google-chrome): "
                    "install it, e.g. apt-get install -y chromium, to run the browser test")
    out = tmp_path / "handout"
    press = press_without_cycle(tmp_path)        # two positions, three sheets: one page each
    assert main(["handout", str(press), "--random", "2", "--seed", "11", "-o", str(out), "-q"]) == 0
    variants = sorted(p for p in out.iterdir() if p.is_dir())
    keys = {v.name: sorted(p for p in v.glob("*.svg") if "-assignment" not in p.name) for v in variants}

    browser = Browser(exe, tmp_path / "profile")
    try:
        browser.open((out / "index.html").as_uri())
        answer = browser.send("Runtime.evaluate", {"expression": _IMAGES, "returnByValue": True})
        assert "exceptionDetails" not in answer, answer["exceptionDetails"]
        images = json.loads(answer["result"]["value"])
        pdf = base64.b64decode(browser.send("Page.printToPDF", {"preferCSSPageSize": True})["data"])
        shot = base64.b64decode(browser.send("Page.captureScreenshot", {"format": "png"})["data"])
        errors = browser.errors()
    finally:
        browser.close()
    (tmp_path / "index.png").write_bytes(shot)
    (tmp_path / "index.pdf").write_bytes(pdf)
    assert shot.startswith(b"\x89PNG")

    assert errors == []
    expected = sorted(str(p.relative_to(out)) for p in out.glob("variant-*/*.svg"))
    assert sorted(src for src, *_ in images) == expected
    for src, complete, w, h, dark in images:
        mm = sheet_size_mm((out / src).read_text(encoding="utf-8"))
        assert complete and w > 0 and h > 0, src
        assert abs(w - mm[0] * PX_PER_MM) <= 1 and abs(h - mm[1] * PX_PER_MM) <= 1, src
        assert dark > 100, f"{src} draws nothing"

    # every sheet on a page of its own size (printed at 100 %): the assignments' sheets first,
    # then, variant by variant, an A4 portrait page of the key's values and the key's sheets
    pt = lambda svg: tuple(round(x * PT_PER_MM) for x in sheet_size_mm(svg.read_text(encoding="utf-8")))  # noqa: E731
    assigned = [pt(p) for v in variants for p in sorted(v.glob("*-assignment*.svg"), key=_sheet_order)]
    portrait = (round(A4_PT[1]), round(A4_PT[0]))
    pages = [(round(w), round(h)) for w, h in _pages(pdf)]
    assert pages[:len(assigned)] == assigned
    assert sorted(pages[len(assigned):]) == sorted([portrait] * len(variants) + [pt(p) for k in keys.values() for p in k])
