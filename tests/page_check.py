"""A report page as a reader's browser lays it out: headless Chromium (Debian's, as the X_ITE
harness drives it) opens the page at each width at once, every <details> open, and says what
runs off the page or scrolls inside it, and which images did not load.

One browser start for every width: an outer page holds the page under test in an iframe of
each width, and a script appended to a copy of it (beside it, so its relative links resolve)
measures it after its load event and posts what it found to the outer page, whose DOM
--dump-dom prints. --virtual-time-budget lets the posts arrive before the dump: virtual
time passes only when the page is idle, so no wall-clock wait decides the result.
"""

from __future__ import annotations

import html
import json
import os
import re
import subprocess
import sys

CHROMIUM = os.environ.get("X3DRBP_CHROMIUM", "/usr/bin/chromium")
FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-background-networking",
         "--disable-component-update", "--disable-sync", "--virtual-time-budget=10000"]
SLACK_PX = 0.5  # layout rounds to fractions of a pixel: an edge this far past the viewport is on it

_MEASURE = """
<script>
window.addEventListener("load", () => {
  for (const d of document.querySelectorAll("details")) d.open = true;
  const width = document.documentElement.clientWidth;
  const name = e => e.tagName.toLowerCase() + (e.id ? "#" + e.id : "") + (e.className ? "." + e.className : "")
    + ": " + (e.textContent || e.getAttribute("src") || "").trim().replace(/\\s+/g, " ").slice(0, 60);
  const past = e => { const r = e.getBoundingClientRect(); return r.width > 0 && (r.right > width + SLACK || r.left < -SLACK); };
  const all = [...document.body.querySelectorAll("*")];
  // the outermost of what runs off the page: its children are off with it
  const off = all.filter(e => past(e) && !(e.parentElement && e.parentElement !== document.body && past(e.parentElement)));
  const scrolls = all.filter(e => e.scrollWidth > e.clientWidth + 1 && getComputedStyle(e).overflowX !== "visible");
  // each table and the plot beside it (reports/report_page.py's .side): side by side, or one above the other
  const sides = [...document.querySelectorAll(".side")].map(s => {
    const [a, b] = [...s.children].map(e => e.getBoundingClientRect());
    return b.left >= a.right ? "beside" : "below"; });
  parent.postMessage(JSON.stringify({
    viewport: window.innerWidth, width, page_width: document.documentElement.scrollWidth,
    off_page: off.map(name), scrolls: scrolls.map(name), sides,
    images: [...document.images].map(i => ({src: i.getAttribute("src"), loaded: i.complete && i.naturalWidth > 0,
                                            shown_px: Math.round(i.getBoundingClientRect().width)})),
  }), "*");
});
</script>
""".replace("SLACK", str(SLACK_PX))

_OUTER = """<!DOCTYPE html><html><body><pre id="found"></pre>
<script>
const found = [];
addEventListener("message", e => { found.push(JSON.parse(e.data));
  document.getElementById("found").textContent = JSON.stringify(found); });
</script>
{frames}
</body></html>
"""


def unavailable() -> str | None:
    """Why the page cannot be laid out here, or None."""
    if not os.access(CHROMIUM, os.X_OK):
        return f"no Chromium at {CHROMIUM} (Debian: apt-get install chromium; or set X3DRBP_CHROMIUM)"
    return None


def layout(page: str, widths: tuple[int, ...] = (1400, 900), height: int = 900) -> dict[int, dict]:
    """Per viewport width (CSS px): the width left beside the scroll bar, the page's width as
    laid out, the outermost elements that run off it, the boxes that scroll or clip their
    content sideways, whether each plot stands beside its table or below it, and each image
    (loaded or not, its width on the page). Writes two files beside the page (their names
    start with '.')."""
    folder, name = os.path.split(os.path.abspath(page))
    with open(page, encoding="utf-8") as f:
        text = f.read()
    probe = os.path.join(folder, ".measured-" + name)
    with open(probe, "w", encoding="utf-8") as f:
        f.write(text.replace("</body>", _MEASURE + "</body>", 1))
    outer = os.path.join(folder, ".widths.html")
    frames = "\n".join(f'<iframe src="{os.path.basename(probe)}" width="{w}" height="{height}"></iframe>'
                       for w in widths)
    with open(outer, "w", encoding="utf-8") as f:
        f.write(_OUTER.replace("{frames}", frames))
    done = subprocess.run([CHROMIUM, *FLAGS, f"--window-size={max(widths)},{height}", "--dump-dom",
                           "file://" + outer], capture_output=True, text=True, timeout=300)
    m = re.search(r'<pre id="found">(.*?)</pre>', done.stdout, re.S)
    if done.returncode != 0 or m is None:
        raise RuntimeError(f"chromium exited with {done.returncode}: {done.stderr.strip().splitlines()[-1:]}")
    found = json.loads(html.unescape(m.group(1)) or "[]")
    return {d["viewport"]: d for d in found}


if __name__ == "__main__":  # python tests/page_check.py DIR/index.html: what a reader's browser shows
    print(json.dumps(layout(sys.argv[1]), indent=1))
