"""`make sysdeps` (scripts/system_deps.sh): what it finds present it leaves alone, what
is missing it names; it runs before anything else in `make test` and `make book`."""
import os
import re
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def fake_bin(tmp_path, present, fonts_lines=20000):
    b = tmp_path / "bin"
    b.mkdir()
    for name in present:
        p = b / name
        p.write_text("#!/bin/sh\nexit 0\n")
        p.chmod(0o755)
    # a long font list with the CJK font first: `fc-list | grep -q` would kill
    # fc-list with SIGPIPE (a false "missing" under pipefail)
    fc = b / "fc-list"
    fc.write_text("#!/bin/sh\necho '/usr/share/fonts/wqy-zenhei.ttc: WenQuanYi Zen Hei'\n"
                  f"i=0; while [ $i -lt {fonts_lines} ]; do echo /usr/share/fonts/f$i.ttf: F; "
                  "i=$((i+1)); done\n")
    fc.chmod(0o755)
    for tool in ("grep", "id", "cat"):         # the few programs the script itself uses
        (b / tool).symlink_to(subprocess.run(["sh", "-c", f"command -v {tool}"],
                                             capture_output=True, text=True).stdout.strip())
    for name in ("apt-get", "sudo"):          # record any call instead of installing
        p = b / name
        p.write_text(f"#!/bin/sh\necho {name} \"$@\" >> {tmp_path}/calls\n")
        p.chmod(0o755)
    return b


def run(tmp_path, b, chromium):
    env = {"PATH": str(b), "CHROMIUM": chromium}
    return subprocess.run(["/bin/bash", str(ROOT / "scripts" / "system_deps.sh")], env=env,
                          capture_output=True, text=True)


def test_nothing_is_installed_when_everything_is_there(tmp_path):
    b = fake_bin(tmp_path, ["pdftotext", "pdfimages", "bwrap", "node", "npm"])
    r = run(tmp_path, b, str(b / "pdftotext"))
    assert r.returncode == 0, r.stderr
    assert not (tmp_path / "calls").exists()


def test_what_is_missing_is_named(tmp_path):
    b = fake_bin(tmp_path, ["pdftotext", "pdfimages", "node", "npm"])
    r = run(tmp_path, b, str(b / "pdftotext"))
    if os.geteuid() == 0:       # root: apt-get is called for exactly the missing one
        assert r.returncode == 0, r.stderr
        calls = (tmp_path / "calls").read_text()
        assert re.search(r"apt-get install -y -q bubblewrap$", calls, re.M), calls
    else:
        assert r.returncode == 1
        assert "missing bubblewrap" in r.stderr


def test_make_test_and_make_book_install_the_system_packages_first():
    text = (ROOT / "Makefile").read_text()
    for target in ("test", "book", "unit"):
        prereqs = re.search(rf"^{target}:(.*)$", text, re.M).group(1).split()
        assert prereqs[0] == "sysdeps", (target, prereqs)
    ci = (ROOT / ".ci" / "run").read_text()
    assert "apt-get" not in ci and "make test" in ci
