"""A progress bar for spp.solve(..., progress="bar"): tqdm's (tqdm.auto: a widget in Jupyter, text in a terminal)
when the tqdm package is installed (Debian: python3-tqdm), else a one-line text bar on stderr. It is the callable
given to the C++ solve as its progress callback (called every 0.2 s with a SolveProgress)."""
import sys


class Bar:
    """Cells traced out of the window's cells, SPP candidates so far, elapsed time and tqdm's ETA."""

    def __init__(self, file=None):
        self._file = file if file is not None else sys.stderr
        self._bar = None
        self._plain = False

    def __enter__(self):
        return self

    def __call__(self, p):
        if self._bar is None and not self._plain:
            try:
                from tqdm.auto import tqdm
                self._bar = tqdm(total=p.cells_total, unit="cell", desc="spp solve", file=self._file,
                                 dynamic_ncols=True)
            except ImportError:
                self._plain = True
        if self._bar is not None:
            self._bar.total = p.cells_total
            self._bar.update(p.cells_done - self._bar.n)
            self._bar.set_postfix(candidates=p.candidates, refresh=False)
        else:
            width = 30
            done = int(width * p.cells_done / p.cells_total) if p.cells_total else width
            self._file.write(f"\rspp solve [{'#' * done}{'.' * (width - done)}] {p.cells_done}/{p.cells_total} "
                             f"cells, {p.candidates} candidates, {p.seconds:.0f} s ")
            self._file.flush()
        return True

    def __exit__(self, *exc):
        if self._bar is not None:
            self._bar.close()
        elif self._plain:
            self._file.write("\n")
            self._file.flush()
        return False
