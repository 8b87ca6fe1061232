"""The grader (often root) writes feedback pages only into a private folder and never
through a link (issue 37, item 5: a symlink planted in a shared --feedback folder made
root overwrite a root-owned file)."""
import os

import pytest

from whittaker_teach.grading import run
from whittaker_teach.grading.rows import Row


def rows(name):
    return {name: [Row(name, "kepler-orbit", "h", True, "right", 1, 1)]}


def test_a_missing_folder_is_made_private(tmp_path):
    folder = tmp_path / "feedback"
    run.write_feedback(folder, ["a.ipynb"], rows("a.ipynb"))
    assert oct(os.stat(folder).st_mode & 0o777) == "0o700"
    pages = [p for p in folder.iterdir()]
    assert len(pages) == 1 and pages[0].suffix == ".html" and not pages[0].is_symlink()


def test_a_folder_others_can_write_is_refused(tmp_path):
    folder = tmp_path / "shared"
    folder.mkdir()
    os.chmod(folder, 0o777)
    with pytest.raises(run.UnsafeFolder, match="other accounts"):
        run.write_feedback(folder, ["a.ipynb"], rows("a.ipynb"))


def test_a_link_as_the_folder_is_refused(tmp_path):
    (tmp_path / "real").mkdir(mode=0o700)
    (tmp_path / "link").symlink_to(tmp_path / "real")
    with pytest.raises(run.UnsafeFolder, match="not a folder"):
        run.write_feedback(tmp_path / "link", ["a.ipynb"], rows("a.ipynb"))


def test_a_link_in_place_of_a_page_is_replaced_not_followed(tmp_path):
    folder = tmp_path / "feedback"
    folder.mkdir(mode=0o700)
    victim = tmp_path / "victim.txt"
    victim.write_text("keep me")
    page = folder / run.page_name("a.ipynb")
    page.symlink_to(victim)
    run.write_feedback(folder, ["a.ipynb"], rows("a.ipynb"))
    assert victim.read_text() == "keep me"
    assert not page.is_symlink() and "Feedback" in page.read_text()


def test_the_command_line_refuses_before_grading(tmp_path, capsys):
    folder = tmp_path / "shared"
    folder.mkdir()
    os.chmod(folder, 0o777)
    nb = tmp_path / "a.ipynb"
    nb.write_text("{}")
    from whittaker_teach import __main__ as cli
    code = cli.main(["grade", "--out", str(tmp_path / "g.csv"), "--feedback", str(folder),
                     "--unsafe", str(nb)])
    assert code == 2 and "other accounts" in capsys.readouterr().err
    assert not (tmp_path / "g.csv").exists()
