"""A file's version as a cache key: its absolute path and modification time, from one ``stat`` call.

The materials a sweep reads from files (fits, calibrations, bootstrap samples, shift functions) are
cached per file version, so that an edited file is read again; a sweep asks for them at every point,
so the key costs one system call (no symlink resolution, which costs one per path component). The
path is made absolute by joining it to the working folder, not normalised: ``..`` after a symlink
then still names the file that was checked.
"""

from __future__ import annotations

import errno
import os
import stat

__all__ = ["version"]


def version(path) -> tuple[str, int] | None:
    """(absolute path, modification time in ns) of the regular file ``path``; None when there is none
    (missing, a folder, a path through a file, a symlink loop); other errors (permissions) are raised.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from vcor.io.fileversion import version
    >>> with tempfile.TemporaryDirectory() as d:
    ...     f = pathlib.Path(d) / "a.nc"
    ...     _ = f.write_text("x")
    ...     key = version(f)
    ...     key[0] == str(f), isinstance(key[1], int), version(f.with_name("b.nc")), version(d)
    (True, True, None, None)
    """
    try:
        st = os.stat(path)
    except OSError as exc:
        if exc.errno in (errno.ENOENT, errno.ENOTDIR, errno.ELOOP, errno.ENAMETOOLONG):
            return None
        raise
    return (os.path.join(os.getcwd(), os.fspath(path)), st.st_mtime_ns) if stat.S_ISREG(st.st_mode) else None
