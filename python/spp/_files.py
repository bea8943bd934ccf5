"""Output files are written whole or not at all: a temporary file beside the target, renamed over it."""
import contextlib
import os
import tempfile


@contextlib.contextmanager
def atomic_path(path):
    """Yields a temporary path in path's directory; on success renames it to path with the usual permissions
    (0666 minus the umask, as open() would give), on failure removes it."""
    path = os.fspath(path)
    if os.path.islink(path):  # written through, not replaced (as the C++ writers: spp/io/files.hpp output_file)
        if not os.path.exists(path):
            raise ValueError(f"cannot write {path!r}: it is a symbolic link to a missing file")
        path = os.path.realpath(path)
    if any(p.startswith(("/dev/", "/proc/")) for p in (os.path.abspath(path), os.path.realpath(path))):
        raise ValueError(f"cannot write {path!r}: it is under /dev or /proc (a device or a process's file): expected "
                         "an output file")
    if os.path.exists(path) and not os.path.isfile(path):  # the rename would replace a device or a directory
        raise ValueError(f"cannot write {path!r}: it exists and is not a regular file (a directory or a device)")
    fd, tmp = tempfile.mkstemp(prefix=".tmp.", suffix=os.path.splitext(path)[1],
                               dir=os.path.dirname(os.path.abspath(path)))
    os.close(fd)
    try:
        yield tmp
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)
