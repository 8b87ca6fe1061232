"""The package as pip installs it: the wheel carries the exercises' answer data, so
that a student who installs it checks an exercise from any folder (issue 32)."""
import shutil
import subprocess
import sys
import textwrap
import venv
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

SCRIPT = textwrap.dedent("""
    import json, whittaker_teach
    from whittaker_teach.exercises import check, answers_path
    right = check("sledge-L-star",
                  "sqrt(2*h - k^2*theta^2)*sqrt(m*sec(theta)^2 + J*theta'^2)", part="L_star")
    wrong = check("sledge-L-star",
                  "sqrt(2*h - k^2*theta^2)*sqrt(m + J*theta'^2)", part="L_star")
    print(json.dumps({"package": whittaker_teach.__file__, "data": str(answers_path("sledge-L-star")),
                      "right": right.ok, "wrong": wrong.ok, "hint": wrong.message}))
""")


pytestmark = pytest.mark.xdist_group("wheel")     # one build, in one worker


@pytest.fixture(scope="module")
def wheel(tmp_path_factory):
    """The wheel, built from a copy of the sources (never in the checkout's build/, where
    another build may be under way)."""
    out = tmp_path_factory.mktemp("wheel")
    src = out / "src"
    src.mkdir()
    for name in ("pyproject.toml", "README.md"):
        shutil.copy2(ROOT / name, src / name)
    shutil.copytree(ROOT / "whittaker_teach", src / "whittaker_teach",
                    ignore=shutil.ignore_patterns("__pycache__", "*.pyc"))
    subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation",
                    "-q", "-w", str(out), str(src)], check=True, cwd=out)
    (w,) = out.glob("whittaker_teach-*.whl")
    return w


def test_the_wheel_carries_every_exercise_s_answer_data(wheel):
    names = set(zipfile.ZipFile(wheel).namelist())
    data = sorted((ROOT / "whittaker_teach" / "exercises" / "data").glob("*.json"))
    assert data
    for p in data:
        assert f"whittaker_teach/exercises/data/{p.name}" in names


def test_an_installed_wheel_checks_from_another_folder(wheel, tmp_path):
    env_dir = tmp_path / "venv"
    venv.create(env_dir, with_pip=False)
    py = env_dir / "bin" / "python"
    site = Path(subprocess.run([str(py), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
                               check=True, capture_output=True, text=True).stdout.strip())
    # the wheel, unpacked as pip installs it (no dependencies); SymPy and mpmath from this
    # interpreter's site-packages, added as a plain path (its .pth files, among them the
    # editable install of this checkout, are not run)
    subprocess.run([sys.executable, "-m", "pip", "install", "-q", "--no-deps", "--target", str(site),
                    str(wheel)], check=True)
    import mpmath
    import sympy
    deps = {str(Path(m.__file__).resolve().parents[1]) for m in (sympy, mpmath)}
    (site / "deps.pth").write_text("".join(d + "\n" for d in sorted(deps)), encoding="utf-8")
    away = tmp_path / "elsewhere"
    away.mkdir()
    env = {"PATH": "/usr/bin:/bin", "HOME": str(tmp_path)}
    run = subprocess.run([str(py), "-I", "-c", SCRIPT], cwd=away, env=env, capture_output=True,
                         text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    import json
    got = json.loads(run.stdout.strip().splitlines()[-1])
    assert Path(got["package"]).is_relative_to(site), got
    assert Path(got["data"]).is_relative_to(site), got
    assert got["right"] is True
    assert got["wrong"] is False and got["hint"], got
