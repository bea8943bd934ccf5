"""A progress bar for spp.solve, spp.nearest_spp and spp.root_map(..., progress="bar"): tqdm's (tqdm.auto: a widget in Jupyter, text in a terminal)
when the tqdm package is installed (Debian: python3-tqdm), else a one-line text bar on stderr. It is the callable
given to the C++ run as its progress callback (called every 0.2 s with a SolveProgress or a RootMapProgress)."""
import sys


class Bar:
    """Cells done out of the window's cells, SPP candidates so far (a solve's), elapsed time and tqdm's ETA."""

    def __init__(self, file=None, desc="spp solve"):
        self._file = file if file is not None else sys.stderr
        self._desc = desc
        self._bar = None
        self._plain = False

    def __enter__(self):
        return self

    def __call__(self, p):
        if self._bar is None and not self._plain:
            try:
                from tqdm.auto import tqdm
                self._bar = tqdm(total=p.cells_total, unit="cell", desc=self._desc, file=self._file,
                                 dynamic_ncols=True)
            except ImportError:
                self._plain = True
        if self._bar is not None:
            self._bar.total = p.cells_total
            self._bar.update(p.cells_done - self._bar.n)
            if hasattr(p, "candidates"):
                self._bar.set_postfix(candidates=p.candidates, refresh=False)
        else:
            width = 30
            done = int(width * p.cells_done / p.cells_total) if p.cells_total else width
            found = f"{p.candidates} candidates, " if hasattr(p, "candidates") else ""
            self._file.write(f"\r{self._desc} [{'#' * done}{'.' * (width - done)}] {p.cells_done}/{p.cells_total} "
                             f"cells, {found}{p.seconds:.0f} s ")
            self._file.flush()
        return True

    def __exit__(self, *exc):
        if self._bar is not None:
            self._bar.close()
        elif self._plain:
            self._file.write("\n")
            self._file.flush()
        return False
