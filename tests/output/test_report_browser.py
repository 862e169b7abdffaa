"""The HTML report as a person sees it: Debian's Chromium, headless, driven by playwright.

Chromium comes from scripts/browser-deps.sh (run here when it is missing; scripts/test.sh runs
it too); the test skips only when Chromium cannot be installed (no root, no apt). playwright's
own browser download is never used: it launches /usr/bin/chromium. Asserted: no console
errors and no network requests, the animation changes pixels between two frames (and stops
when paused), the mode selector and the amplitude slider change the picture, a screenshot is
not blank, and the page is readable at 1280x800 and at a phone's 390 px width."""

import io
import json
import subprocess
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from flexlink.cli import main

from conftest import ROOT
CHROMIUM = "/usr/bin/chromium"
# Without the background-networking flags Chromium reaches for its update and sync services,
# which a closed network answers with errors.
FLAGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync"]
DESKTOP = {"width": 1280, "height": 800}
PHONE = {"width": 390, "height": 844}


def chromium() -> str:
    if not Path(CHROMIUM).exists():
        subprocess.run(["bash", str(ROOT / "scripts" / "browser-deps.sh")], check=False)
    if not Path(CHROMIUM).exists():
        pytest.skip("Chromium is not installed and scripts/browser-deps.sh could not install it")
    return CHROMIUM


@pytest.fixture(scope="module")
def report(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("report")
    result = CliRunner().invoke(main, ["report", str(ROOT / "cases" / "case1.toml"),
                                       str(ROOT / "cases" / "case3.toml"), "-e", "8",
                                       "--cycle-poses", "24", "--json", "--out", str(out)])
    assert result.exit_code == 0, result.output
    return Path(json.loads(result.stdout)["report"])


@pytest.fixture(scope="module")
def browser(tmp_path_factory):
    executable = chromium()
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        pytest.fail("playwright is missing: install the test extra (pip install -e '.[test]')")
    profile = tmp_path_factory.mktemp("chromium-profile")  # a fresh --user-data-dir
    with sync_playwright() as p:
        context = p.chromium.launch_persistent_context(
            str(profile), executable_path=executable, headless=True, args=FLAGS,
            viewport=DESKTOP)
        yield context
        context.close()


class Visit:
    """A page opened in ``browser`` at ``viewport``, recording console errors, uncaught
    exceptions and every request."""

    def __init__(self, browser, report: Path, viewport: dict):
        self.errors, self.requests = [], []
        self.page = browser.new_page()
        self.page.set_viewport_size(viewport)
        self.page.on("console", lambda m: m.type == "error" and self.errors.append(m.text))
        self.page.on("pageerror", lambda e: self.errors.append(str(e)))
        self.page.on("request", lambda r: self.requests.append(r.url))
        self.url = report.as_uri()
        self.page.goto(self.url)
        self.page.wait_for_function("window.flexlinkReport !== undefined")

    def pixels(self, selector: str) -> np.ndarray:
        from PIL import Image

        png = self.page.locator(selector).screenshot()
        return np.asarray(Image.open(io.BytesIO(png)).convert("RGB"), dtype=int)

    def frames(self, player: str) -> int:
        return self.page.evaluate(f"window.flexlinkReport.players[{player!r}].frames")


def changed(a: np.ndarray, b: np.ndarray) -> int:
    """Pixels that differ between two pictures of the same element."""
    assert a.shape == b.shape
    return int((np.abs(a - b).sum(axis=2) > 30).sum())


def not_blank(picture: np.ndarray) -> None:
    """More than one colour in quantity, and a good share of the picture not background."""
    colours = {tuple(c) for c in picture.reshape(-1, 3)[::7] // 16}
    background = np.bincount(np.ravel_multi_index((picture // 16).reshape(-1, 3).T,
                                                  (16, 16, 16))).max()
    assert len(colours) > 8, f"only {len(colours)} colours"
    assert background < 0.97 * picture.shape[0] * picture.shape[1]


def most_changed(visit, page, plot, first, enough: int, looks: int = 6) -> int:
    """The most pixels of ``plot`` changed from ``first`` over up to ``looks`` looks 150 ms
    apart (a fifth of the drawn period and more), stopping at the first look that changes more
    than ``enough``: on a busy machine one look may land on a frame close to the first."""
    best = 0
    for _ in range(looks):
        page.wait_for_timeout(150)
        best = max(best, changed(first, visit.pixels(plot)))
        if best > enough:
            break
    return best


def drawn(visit, page, plot, looks: int = 20) -> np.ndarray:
    """The picture of ``plot`` once something is drawn in it, looking up to ``looks`` times 150
    ms apart: on a busy machine a screenshot can land on a redraw and catch it blank."""
    for _ in range(looks):
        picture = visit.pixels(plot)
        if (picture.sum(axis=2) < 3 * 255 - 30).sum() > 200:
            break
        page.wait_for_timeout(150)
    return picture


def test_desktop_page_animates_and_reacts_without_errors_or_network(browser, report, tmp_path):
    visit = Visit(browser, report, DESKTOP)
    page = visit.page
    plot = "#modeplot-case1"
    page.locator(plot).scroll_into_view_if_needed()
    page.wait_for_function("window.flexlinkReport.players.case1.frames > 3")
    first = visit.pixels(plot)
    assert most_changed(visit, page, plot, first, 200) > 200, "the animation did not move"

    page.click("#player-case1 button.play")  # pause: the picture holds still
    assert page.inner_text("#player-case1 button.play") == "Play"
    # held at the largest displacement, where another mode or no amplitude must show (paused
    # near a zero crossing every mode would look like the undeformed pose)
    page.evaluate("(() => { const p = window.flexlinkReport.players.case1;"
                  " p.phase = Math.PI / 2; p.draw(); })()")
    page.wait_for_timeout(100)
    held = drawn(visit, page, plot)
    count = visit.frames("case1")
    page.wait_for_timeout(300)
    assert visit.frames("case1") == count and changed(held, drawn(visit, page, plot)) == 0

    page.select_option("#player-case1 select", "2")  # another mode, another picture
    assert most_changed(visit, page, plot, held, 200) > 200
    other_mode = drawn(visit, page, plot)
    page.fill("#player-case1 input[type=range]", "0")  # no amplitude: the undeformed pose
    assert page.inner_text("#player-case1 .amp-value") == "0 %"
    assert most_changed(visit, page, plot, other_mode, 200) > 200

    page.evaluate("window.scrollTo(0, 0)")
    shot = tmp_path / "desktop.png"
    page.screenshot(path=str(shot))
    from PIL import Image

    not_blank(np.asarray(Image.open(shot).convert("RGB"), dtype=int))
    # the figures are drawn: plotly made an SVG for the pose, the cycle map and the player
    for name in ("fig-case1-pose", "fig-case1-cycle", "modeplot-case1", "fig-case3-cycle"):
        assert page.locator(f"#{name} svg.main-svg").count() >= 1, name
    assert visit.errors == []
    assert visit.requests == [visit.url]  # the page itself, nothing else
    page.close()


def test_phone_width_page_fits_and_reads(browser, report, tmp_path):
    visit = Visit(browser, report, PHONE)
    page = visit.page
    # nothing wider than the screen: no sideways scrolling of the page (wide tables scroll
    # inside their own box)
    assert page.evaluate("document.documentElement.scrollWidth") <= PHONE["width"]
    for selector in ("#fig-case1-pose", "#modeplot-case1", "#player-case1 .controls"):
        box = page.locator(selector).bounding_box()
        assert box["x"] >= 0 and box["x"] + box["width"] <= PHONE["width"], selector
    # text stays readable: no body text below 12 px
    smallest = page.evaluate("""Math.min(...Array.from(document.querySelectorAll('p, td, th, li'))
        .map(e => parseFloat(getComputedStyle(e).fontSize)))""")
    assert smallest >= 12
    page.locator("#modeplot-case1").scroll_into_view_if_needed()
    page.wait_for_function("window.flexlinkReport.players.case1.frames > 3")
    first = visit.pixels("#modeplot-case1")
    assert most_changed(visit, page, "#modeplot-case1", first, 100) > 100, \
        "the animation did not move"
    shot = tmp_path / "phone.png"
    page.screenshot(path=str(shot))
    from PIL import Image

    not_blank(np.asarray(Image.open(shot).convert("RGB"), dtype=int))
    assert visit.errors == [] and visit.requests == [visit.url]
    page.close()


def test_blank_picture_is_caught():
    """The blank check itself can fail: a white screenshot does not pass it."""
    with pytest.raises(AssertionError):
        not_blank(np.full((800, 1280, 3), 255))


def test_tables_read_as_text_and_fit_the_page(browser, report):
    """No table cell shows a raw Python dict, no table is wider than the desktop page, energy
    shares name their two largest parts (all of them in the tooltip), effective masses are in
    g, the mode selector and the cycle map's legend carry mode labels, and the top of the page
    has one line per scene with its mean |error| against each reference."""
    visit = Visit(browser, report, DESKTOP)
    page = visit.page
    cells = page.evaluate("Array.from(document.querySelectorAll('td, th')).map(c => c.innerText)")
    assert cells and not [c for c in cells if "{" in c]
    # each table within the page's column (its scroll box never has to scroll at 1280 px)
    overflow = page.evaluate("Array.from(document.querySelectorAll('table'))"
                             ".map(t => t.scrollWidth - t.parentElement.clientWidth)")
    assert overflow and max(overflow) <= 0, overflow
    headers = page.evaluate("Array.from(document.querySelectorAll('#scene-case3 th'))"
                            ".map(c => c.innerText)")
    assert "mx [g]" in headers and "my [g]" in headers and "strain energy" in headers
    shares = page.locator("#scene-case3 .shares").first
    shown, tooltip = shares.inner_text(), shares.get_attribute("title")
    assert shown.count("%") == 2 and tooltip.count("%") > 2, (shown, tooltip)
    options = page.evaluate("Array.from(document.querySelectorAll('#player-case3 option'))"
                            ".map(o => o.innerText)")
    assert all("bending" in o or "spring" in o or "axial" in o for o in options), options
    legend = page.evaluate("Array.from(document.querySelectorAll('#fig-case3-cycle .legendtext'))"
                           ".map(t => t.textContent)")
    assert legend and all("at the pose" in t for t in legend), legend
    lines = page.evaluate("Array.from(document.querySelectorAll('header nav li'))"
                          ".map(l => l.innerText)")
    assert len(lines) == 2 and all("mean |error| vs Ex" in x and "vs FE" in x for x in lines)
    assert visit.errors == []
    page.close()
