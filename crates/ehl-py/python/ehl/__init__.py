"""ehl: contact and elastohydrodynamic lubrication (EHL) of finite rollers and balls.

The Python face of the ``ehl`` solver (a Rust library), with the case-file model of the
``ehl`` program: a :class:`Case` is a case file (TOML) with overrides, :func:`solve` gives a
:class:`Solution` with NumPy arrays. Everything is SI: m, Pa, N, s, Pa s, kg/m^3, rad.

>>> import ehl
>>> case = ehl.Case.from_file("examples/ehl_thesis_ch2_roller.toml")
>>> case.set("load.force", 5000)            # the CLI's --set load.force=5000
>>> case.check()["hertz_pressure_pa"]       # what `ehl check` prints, as a dict
>>> sol = ehl.solve(case)                   # GIL released; Ctrl-C stops it
>>> sol.summary["min_film_m"], sol.pressure.shape   # summary.json, (ny, nx) arrays
>>> sol.write("out/roller")                 # the outputs of `ehl run`

Ctrl-C reaches the main thread only. Solves running in worker threads (a
``ThreadPoolExecutor``) are stopped with :func:`cancel_all`::

    with ThreadPoolExecutor() as ex:
        try:
            solutions = list(ex.map(ehl.solve, cases))
        except KeyboardInterrupt:
            ehl.cancel_all()  # every running solve stops within a solver iteration
            raise

The case-file format: docs/case-file.md of the repository.
"""

import os
import sys
from typing import Callable, Union

from . import errors
from ._ehl import Case, Solution, __version__, _solve, cancel_all
from .errors import CaseError, EhlError, OutputError, SolverError

__all__ = [
    "Case",
    "Solution",
    "solve",
    "cancel_all",
    "EhlError",
    "CaseError",
    "SolverError",
    "OutputError",
    "errors",
    "__version__",
]

ProgressArg = Union[bool, None, Callable[[float, str], None]]


def _interactive() -> bool:
    """True in a Jupyter notebook (an IPython kernel: Jupyter, VS Code, Colab, ...) or when
    stderr is a terminal."""
    shell = sys.modules.get("IPython")
    if shell is not None:
        try:
            ip = shell.get_ipython()  # type: ignore[attr-defined]
            # every kernel runs under an IPKernelApp, whatever the shell class is called
            if ip is not None and "IPKernelApp" in ip.config:
                return True
        except Exception:
            pass
    try:
        return sys.stderr is not None and sys.stderr.isatty()
    except Exception:
        return False


class _Bar:
    """A tqdm bar over [0, 1] fed by the solver's progress reports."""

    def __init__(self, title: str):
        import warnings

        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            from tqdm.auto import tqdm
        self.bar = tqdm(
            total=1000,
            desc=(title[:30] + "...") if len(title) > 33 else title,
            leave=False,
            bar_format="{desc}: {percentage:3.0f}%|{bar}| [{elapsed}<{remaining}]{postfix}",
        )
        self.at = 0

    def __call__(self, fraction: float, message: str) -> None:
        if fraction == fraction:  # not NaN
            n = int(round(min(max(fraction, 0.0), 1.0) * 1000))
            if n > self.at:
                self.bar.update(n - self.at)
                self.at = n
        self.bar.set_postfix_str(message, refresh=True)

    def close(self) -> None:
        self.bar.close()


def _progress_callback(progress: ProgressArg, case: Case):
    """(callback, closer) for the `progress` argument of :func:`solve`."""
    if callable(progress):
        return progress, None
    if progress and _interactive():
        try:
            bar = _Bar(case.title or "ehl")
        except ImportError:
            return None, None
        return bar, bar.close
    return None, None


def solve(
    case: Union[Case, str, "os.PathLike[str]"], progress: ProgressArg = True
) -> Solution:
    """Solves a case (a :class:`Case`, or the path of a case file) and returns its
    :class:`Solution`, as ``ehl run`` does without writing files (``Solution.write`` does).

    The GIL is released while solving, so threads (``concurrent.futures.ThreadPoolExecutor``)
    solve several cases at once. Ctrl-C (KeyboardInterrupt, also the notebook's interrupt
    button) stops the solve within a solver iteration and raises KeyboardInterrupt; nothing is
    written. Python delivers Ctrl-C to the main thread only: a solve in another thread is
    stopped by :func:`cancel_all` (and raises KeyboardInterrupt in its thread). A solve that does not converge returns normally with ``converged == False`` (as
    the CLI writes its outputs with exit status 3).

    progress: True (default) shows a tqdm progress bar when tqdm is installed and the output
    is a notebook or a terminal (it disappears when done); False or None shows nothing; a
    callable ``f(fraction, message)`` receives the reports (fraction in [0, 1], or NaN).

    Raises :class:`CaseError` (a bad case file), :class:`SolverError` (no usable result),
    KeyboardInterrupt.
    """
    if not isinstance(case, Case):
        case = Case.from_file(os.fspath(case))
    callback, close = _progress_callback(progress, case)
    try:
        return _solve(case, callback)
    finally:
        if close is not None:
            close()
