"""Files written through vcor.io.receipts.atomic get the permissions the umask gives any new file (the
temporary file tempfile.mkstemp makes is private, 0600), and a failed write leaves nothing behind."""

import os
import stat

import pytest
import xarray as xr

from vcor.io.netcdf import write_dataset
from vcor.io.receipts import atomic, atomic_text, writable_file


@pytest.fixture(params=[0o022, 0o077, 0o002])
def umask(request):
    old = os.umask(request.param)
    yield request.param
    os.umask(old)


def test_written_files_follow_the_umask(tmp_path, umask):
    plain = tmp_path / "plain.txt"
    plain.touch()
    text = atomic_text(tmp_path / "text.txt", "x")
    nc = write_dataset(xr.Dataset({"a": ("x", [1.0])}, coords={"x": [0.0]}), tmp_path / "d.nc", title="t")
    mode = stat.S_IMODE(plain.stat().st_mode)
    assert mode == 0o666 & ~umask
    assert stat.S_IMODE(text.stat().st_mode) == mode and stat.S_IMODE(nc.stat().st_mode) == mode


def test_a_failed_write_leaves_nothing(tmp_path):
    with pytest.raises(RuntimeError), atomic(tmp_path / "f.txt") as tmp:
        tmp.write_text("half")
        raise RuntimeError("killed")
    assert list(tmp_path.iterdir()) == []


def test_a_folder_a_pipe_or_a_file_as_folder_is_refused_before_writing(tmp_path):
    pipe = tmp_path / "pipe"
    os.mkfifo(pipe)
    (tmp_path / "plain").write_text("x")
    for target, words in [(tmp_path, "is a folder"), (pipe, "not a regular file"),
                          (tmp_path / "plain" / "d.nc", "is a file, not a folder")]:
        with pytest.raises(ValueError, match=words):
            atomic_text(target, "x")
    assert stat.S_ISFIFO(pipe.stat().st_mode) and sorted(p.name for p in tmp_path.iterdir()) == ["pipe", "plain"]
    if os.path.isdir("/proc/self"):
        with pytest.raises(ValueError, match="cannot write in the folder '/proc'"):
            writable_file("/proc/x.nc", "--out")
