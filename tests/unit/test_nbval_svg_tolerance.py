"""The root conftest's SVG comparison for nbval: tolerant to 1e-6 pt, not to a moved line."""
import importlib.util
from pathlib import Path

spec = importlib.util.spec_from_file_location(
    "wt_root_conftest", Path(__file__).resolve().parents[2] / "conftest.py")
root_conftest = importlib.util.module_from_spec(spec)
spec.loader.exec_module(root_conftest)
SVGOutput = root_conftest.SVGOutput

STORED = ('<svg width="712.004302pt"><clipPath id="p7703bf79f0"/>'
          '<path d="M 57.6 307.584 L 169.395665 174.136153" clip-path="url(#p7703bf79f0)"/></svg>')


def test_roundoff_and_hash_ids_are_equal():
    fresh = STORED.replace("169.395665", "169.395664").replace("712.004302", "712.005452")
    fresh = fresh.replace("p7703bf79f0", "pb9ab0e5a86")
    assert SVGOutput(STORED) == fresh
    assert not SVGOutput(STORED) != fresh


def test_a_moved_point_differs():
    assert SVGOutput(STORED) != STORED.replace("169.395665", "169.5")


def test_other_text_or_structure_differs():
    assert SVGOutput(STORED) != STORED.replace("L 169", "C 169")
    assert SVGOutput(STORED) != STORED.replace(" 174.136153", "")
    two_ids = STORED.replace('clip-path="url(#p7703bf79f0)"', 'clip-path="url(#p0000000000)"')
    assert SVGOutput(STORED) != two_ids
