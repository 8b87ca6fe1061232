"""Print what the browser test looked at (written by test_site.py: one summary file,
or one per pytest-xdist worker, added up here)."""
import json
import os
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
_started = [time.time()]


def pytest_sessionstart(session):
    _started[0] = time.time()


def pytest_terminal_summary(terminalreporter):
    shots = Path(os.environ.get("WT_SCREENSHOT_DIR", ROOT / "_build" / "screenshots"))
    paths = [p for p in sorted(shots.glob("summary*.json")) if p.stat().st_mtime >= _started[0]]
    if not paths:
        return
    parts = [json.loads(p.read_text(encoding="utf-8")) for p in paths]
    loads = [key for p in parts for key in p["per_page"]]          # "page@width"
    s = {"pages": len({key.rsplit("@", 1)[0] for key in loads}),
         "widths": sorted({w for p in parts for w in p["widths"]}),
         **{k: sum(p[k] for p in parts) for k in ("page_loads", "displays", "inline", "text_outputs")}}
    terminalreporter.write_line(
        f"browser: {s['pages']} pages at {' and '.join(map(str, s['widths']))} px "
        f"({s['page_loads']} page loads): {s['displays']} display and {s['inline']} in-line "
        f"formulas, {s['text_outputs']} text outputs/tables checked; screenshots in {shots}"
    )
