"""The browser explorer (issue 12): a real headless Chromium loads the page, moves a slider,
and the efficiency shown is the one `Variator.solve` gives at the slider's new value.

Chromium comes from the Debian packages (``.ci/run`` installs it) and is driven through
Playwright's Python API pointed at that browser: nothing is downloaded. Without Chromium or
Playwright the test is skipped, and says why.
"""

import html
import json
import shutil
import subprocess
import sys
import time

import pytest

from ballcvt import Variator

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")


@pytest.fixture(scope="module")
def server():
    proc = subprocess.Popen(
        [sys.executable, "-m", "ballcvt.interfaces.cli.main", "explore-ui", "--port", "0"],
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
    )
    try:
        line = proc.stdout.readline()
        assert "explorer at http://127.0.0.1:" in line, line
        yield line.split(" at ")[1].split()[0]
    finally:
        proc.terminate()
        proc.wait(timeout=10)


@pytest.fixture(scope="module")
def browser():
    if CHROMIUM is None:
        pytest.skip("Chromium is not installed (Debian package 'chromium'; .ci/run installs "
                    "it with apt-get): the browser test cannot run")
    sync_api = pytest.importorskip("playwright.sync_api",
                                   reason="Playwright's Python package is not installed")
    with sync_api.sync_playwright() as p:
        b = p.chromium.launch(executable_path=CHROMIUM, headless=True, args=["--no-sandbox"])
        yield b
        b.close()


def _state(page):
    return json.loads(page.locator(".bcvt-state .bcvt-json").text_content())


def _wait(page, test, timeout=15.0):
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        state = _state(page)
        if test(state):
            return state
        time.sleep(0.05)
    raise AssertionError(f"the page did not update: {state}")


def test_slider_moves_the_efficiency_to_the_solvers_value(server, browser):
    page = browser.new_page(viewport={"width": 1500, "height": 1000})
    page.goto(server)
    page.wait_for_selector(".bcvt-eta .bcvt-value", timeout=30000)
    before = _state(page)
    assert before["inputs"]["ratio"] == 1.0 and before["eta"] is not None
    page.locator(".bcvt-slider-ratio .noUi-handle").focus()
    start = time.monotonic()
    for _ in range(10):                                   # 10 steps of 0.01
        page.keyboard.press("ArrowRight")
    after = _wait(page, lambda s: abs(s["inputs"]["ratio"] - 1.1) < 1e-9)
    latency = time.monotonic() - start
    shown = float(page.locator(".bcvt-eta .bcvt-value").text_content())
    i = after["inputs"]
    expected = Variator().solve(ratio=i["ratio"], output_torque=i["output_torque"],
                                clamp_force=i["clamp_force"],
                                input_speed_rpm=i["input_speed_rpm"]).eta
    assert after["eta"] == pytest.approx(expected, rel=1e-12)
    assert shown == pytest.approx(expected, abs=5e-5)          # as displayed, 4 decimals
    assert shown != float(f"{before['eta']:.4f}")
    assert latency < 10.0                                 # ten moves, each re-solved
    # a design slider: the number of balls, one step down
    page.locator(".bcvt-slider-n_rollers .noUi-handle").focus()
    page.keyboard.press("ArrowLeft")
    after = _wait(page, lambda s: s["design"]["n_rollers"] == 7)
    v = Variator(Variator().design.replace(n_rollers=7))
    assert after["eta"] == pytest.approx(
        v.solve(ratio=1.1, output_torque=40.0, clamp_force=2000.0, input_speed_rpm=2000).eta,
        rel=1e-12)
    page.close()


def _document():
    from bokeh.document import Document

    from ballcvt.interfaces.ui import make_document

    doc = Document()
    v = Variator()
    make_document(doc, v.design, v.fluid)
    return doc


def _div(doc, css):
    return next(m for m in doc.models if css in (getattr(m, "css_classes", None) or []))


def test_document_without_a_browser_shows_the_solvers_point_and_map():
    """The page as built in Python (no browser needed): the point shown is
    `Variator.solve`'s, the map holds the grid, and a slider moved re-solves the point."""
    pytest.importorskip("bokeh")
    from ballcvt.interfaces.ui import MAP_GRID

    doc = _document()
    text = _div(doc, "bcvt-state").text
    state = json.loads(html.unescape(text.split(">", 1)[1].rsplit("<", 1)[0]))
    expected = Variator().solve(ratio=1.0, output_torque=40.0, clamp_force=2000.0,
                                input_speed_rpm=2000.0)
    assert state["eta"] == pytest.approx(expected.eta, rel=1e-12)
    image = next(m for m in doc.models if "image" in getattr(m, "data", {}))
    assert image.data["image"][0].shape == (MAP_GRID[1], MAP_GRID[0])
    slider = next(m for m in doc.models if getattr(m, "name", None) == "ratio")
    slider.value = 1.2
    eta = float(_div(doc, "bcvt-eta").text.split(">")[1].split("<")[0])
    assert eta == pytest.approx(Variator().solve(ratio=1.2, output_torque=40.0,
                                                 clamp_force=2000.0,
                                                 input_speed_rpm=2000.0).eta, abs=5e-5)
