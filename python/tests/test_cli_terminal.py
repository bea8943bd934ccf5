"""spp solve's progress line on a terminal (a pseudo-terminal here): what stays on screen once the search is over."""
import os
import pty
import select
import signal
import subprocess
import time

import pytest

import spp

CLI = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(spp.__file__)))), "spp")


def screen(text):
    """The lines a terminal shows for `text`: a carriage return moves back to the line's start, later characters
    overwrite earlier ones."""
    lines = []
    for raw in text.replace("\r\n", "\n").split("\n"):
        cells = []
        pos = 0
        for ch in raw:
            if ch == "\r":
                pos = 0
                continue
            if pos < len(cells):
                cells[pos] = ch
            else:
                cells.append(ch)
            pos += 1
        lines.append("".join(cells).rstrip())
    return [line for line in lines if line]


def ctrl_c_once_shown(args, marker):
    """Runs the CLI with `args`, its stderr a pseudo-terminal; once `marker` (bytes) is on it, Ctrl-C. Returns (exit
    code, stdout, everything written to the terminal)."""
    master, slave = pty.openpty()
    p = subprocess.Popen([CLI] + args, stdout=subprocess.PIPE, stderr=slave, stdin=subprocess.DEVNULL)
    os.close(slave)
    err = b""
    start = time.monotonic()
    try:
        # wait for the progress line (shown from 1 s on), then Ctrl-C
        while marker not in err and time.monotonic() - start < 60 and p.poll() is None:
            if select.select([master], [], [], 1.0)[0]:  # never a blocking read: the test must not hang
                err += os.read(master, 4096)
        assert marker in err, ("no progress line within 60 s", err)
        time.sleep(0.5)
        p.send_signal(signal.SIGINT)
        out, _ = p.communicate(timeout=120)
        while select.select([master], [], [], 1.0)[0]:
            try:
                chunk = os.read(master, 4096)
            except OSError:  # the child's end closed
                break
            if not chunk:
                break
            err += chunk
    finally:
        os.close(master)
        if p.poll() is None:
            p.kill()
    return p.returncode, out, err


# Found by an independent attack on issue 13: after Ctrl-C, the progress line "... (stopping)" stayed on screen above
# the result (it was ended with a newline, not cleared).
@pytest.mark.skipif(not os.path.exists(CLI), reason="no spp executable beside the package (build tree)")
def test_ctrl_c_progress_line_does_not_stay_on_screen(tmp_path):
    sys_file = tmp_path / "c20.json"
    subprocess.run([CLI, "generate", "chain", "--n", "20", "--out", str(sys_file)], check=True, capture_output=True)
    # not --quiet: it silences the progress line this test is about
    code, _, err = ctrl_c_once_shown(["solve", str(sys_file), "--box"], b"cells ")
    assert code == 130, (code, err)
    shown = screen(err.decode())
    assert not any("stopping" in line or line.lstrip().startswith("cells ") for line in shown), shown
    assert any(line.startswith("interrupted:") for line in shown), shown


# Issue 15: spp modes ran silently (2-dof --k 1..12: 89 s): it now shows spp solve's progress line on a terminal
# ("tracing k = ..."), and Ctrl-C stops it with the families traced so far (exit 130), the line cleared.
@pytest.mark.skipif(not os.path.exists(CLI), reason="no spp executable beside the package (build tree)")
def test_modes_shows_a_progress_line_and_stops_on_ctrl_c(tmp_path):
    sys_file = tmp_path / "two_dof.json"
    subprocess.run([CLI, "generate", "two-dof", "--out", str(sys_file)], check=True, capture_output=True)
    code, out, err = ctrl_c_once_shown(["modes", str(sys_file), "--k", "1..12", "--energy-max", "20"],
                                       b"tracing k = ")
    assert code == 130, (code, err)
    shown = screen(err.decode())
    assert not any("tracing k = " in line for line in shown), shown
    assert any(line.startswith("interrupted:") for line in shown), shown
    assert b"spp modes: incomplete" in out
