"""Re-take docs/report.md's picture of the HTML report (docs/report-screenshot.png):
    python scripts/report-screenshot.py out/report.html
Headless Chromium (scripts/browser-deps.sh) through playwright, as in tests/output/test_report_browser.py;
shows case 1's mode-shape player (paused on mode 2) and its cycle map."""

import io
import sys
import tempfile
from pathlib import Path

from PIL import Image
from playwright.sync_api import sync_playwright

FLAGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync"]
TARGET = Path(__file__).resolve().parent.parent / "docs" / "report-screenshot.png"

with sync_playwright() as p, tempfile.TemporaryDirectory() as profile:
    context = p.chromium.launch_persistent_context(
        profile, executable_path="/usr/bin/chromium", headless=True, args=FLAGS,
        viewport={"width": 1280, "height": 800})
    page = context.new_page()
    page.goto(Path(sys.argv[1]).resolve().as_uri())
    page.wait_for_function("window.flexlinkReport !== undefined")
    page.select_option("#player-case1 select", "1")
    page.locator("#player-case1").scroll_into_view_if_needed()
    page.wait_for_timeout(400)
    page.click("#player-case1 button.play")
    top = page.evaluate("document.querySelector('#player-case1').getBoundingClientRect().top"
                        " + scrollY")
    png = page.screenshot(full_page=True, clip={"x": 100, "y": top - 50, "width": 1080,
                                                "height": 960})
    context.close()
picture = Image.open(io.BytesIO(png)).convert("RGB")
picture = picture.resize((picture.width * 3 // 4, picture.height * 3 // 4), Image.LANCZOS)
picture.quantize(128).save(TARGET, optimize=True)
print(f"wrote {TARGET} ({TARGET.stat().st_size} bytes)")
