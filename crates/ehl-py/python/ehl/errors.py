"""The exceptions of ``ehl``. Every error of the library arrives as one of these."""

from typing import Optional


class EhlError(Exception):
    """Base of the errors that ``ehl`` raises."""

    def __init__(self, message: str, reason: Optional[str] = None):
        super().__init__(message)
        #: what was wrong, in words (the message without the file and key)
        self.reason = reason if reason is not None else message


class CaseError(EhlError, ValueError):
    """A problem with a case: ``.file`` (the case file, ``<string>`` or ``<dict>``), ``.key``
    (the dotted key, e.g. ``load.force`` or ``features[0].depth``; None when the file as a
    whole is wrong, e.g. not valid TOML) and ``.reason`` (what is wrong; for an unknown key it
    names the closest valid key)."""

    def __init__(
        self,
        message: str,
        file: Optional[str] = None,
        key: Optional[str] = None,
        reason: Optional[str] = None,
    ):
        super().__init__(message, reason)
        self.file = file
        self.key = key


class SolverError(EhlError, RuntimeError):
    """A solve that gave no usable result (a case outside the range where the solver's
    arithmetic holds, or an internal error). A solve that merely did not converge is not an
    error: it returns a ``Solution`` with ``converged == False``."""

    def __init__(
        self,
        message: str,
        file: Optional[str] = None,
        key: Optional[str] = None,
        reason: Optional[str] = None,
    ):
        super().__init__(message, reason)


class OutputError(EhlError, OSError):
    """Writing the outputs failed: ``.path`` (the folder or file) and ``.reason``. Nothing is
    left half-written: the output folder is as it was before the write."""

    def __init__(
        self,
        message: str,
        path: Optional[str] = None,
        key: Optional[str] = None,
        reason: Optional[str] = None,
    ):
        EhlError.__init__(self, message, reason)
        self.path = path

    def __str__(self) -> str:
        return str(self.args[0]) if self.args else ""
