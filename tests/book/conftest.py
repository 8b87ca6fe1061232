"""Print what the browser test looked at (written by test_site.py)."""
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
    path = shots / "summary.json"
    if not path.is_file() or path.stat().st_mtime < _started[0]:
        return
    s = json.loads(path.read_text(encoding="utf-8"))
    terminalreporter.write_line(
        f"browser: {s['pages']} pages at {' and '.join(map(str, s['widths']))} px "
        f"({s['page_loads']} page loads): {s['displays']} display and {s['inline']} in-line "
        f"formulas, {s['text_outputs']} text outputs/tables checked; screenshots in {shots}"
    )
