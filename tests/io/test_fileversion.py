"""A file's version as a cache key (vcor.io.fileversion): it names the file it checked."""

import os
from pathlib import Path

from vcor.io.fileversion import version


def test_the_key_names_the_file_that_was_checked_through_a_symlink(tmp_path, monkeypatch):
    (tmp_path / "real" / "sub").mkdir(parents=True)
    (tmp_path / "real" / "m.nc").write_text("a")
    (tmp_path / "proj").mkdir()
    (tmp_path / "proj" / "m.nc").write_text("b")
    (tmp_path / "proj" / "link").symlink_to(tmp_path / "real" / "sub")
    monkeypatch.chdir(tmp_path)
    key = version("proj/link/../m.nc")  # the kernel follows the link first: real/m.nc
    assert key is not None and Path(key[0]).read_text() == "a"
    assert key[1] == os.stat(tmp_path / "real" / "m.nc").st_mtime_ns


def test_no_key_for_what_is_not_a_regular_file(tmp_path):
    assert version(tmp_path / "missing.nc") is None
    assert version(tmp_path) is None  # a folder
    (tmp_path / "f").write_text("x")
    assert version(tmp_path / "f" / "below") is None  # a path through a file
    (tmp_path / "loop").symlink_to(tmp_path / "loop")
    assert version(tmp_path / "loop") is None
