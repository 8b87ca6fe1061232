"""Rendering (Unicode, LaTeX) and the command line."""

import subprocess
import sys

from whittaker_teach.__main__ import main


def test_unicode_has_paper_numbers(sledge_red):
    text = sledge_red.steps.to_unicode()
    for lab in ("(1.6)", "(1.16)", "(1.26)", "(2.4)"):
        assert lab in text
    assert "✓" in text and "✗" not in text
    assert "θ′" in text


def test_latex_tags(sledge_red):
    tex = sledge_red.steps.to_latex()
    assert r"\tag{1.16}" in tex and r"\tag{2.4}" in tex
    assert r"L^{*}" in tex
    assert sledge_red.steps["1.16"]._repr_latex_().startswith("$$")


def test_show_in_terminal(capsys, sledge_red):
    sledge_red.show()
    out = capsys.readouterr().out
    assert "(1.12)" in out and "sign q̇_ε = +1" in out


def test_cli_list(capsys):
    assert main(["list"]) == 0
    out = capsys.readouterr().out
    for name in ("sledge", "projectile", "kepler", "offset_sleigh", "rolling_disk",
                 "cone_particle"):
        assert name in out


def test_cli_derive_sledge(capsys):
    assert main(["derive", "sledge"]) == 0
    out = capsys.readouterr().out
    for lab in ("(1.4)", "(1.26)", "(2.4)", "(3.10)", "(3.15)"):
        assert lab in out
    assert "0 did not" in out.splitlines()[-1]


def test_cli_derive_latex_and_errors(capsys):
    assert main(["derive", "kepler", "--latex"]) == 0
    assert r"\tag{1.27}" in capsys.readouterr().out
    assert main(["derive", "nosuch"]) == 2
    assert "no built-in example" in capsys.readouterr().err


def test_import_is_light():
    code = "import sys, whittaker_teach; print('sympy' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.strip()
    assert out == "False"
