"""The package's errors: UDM1Error, and check(), which turns a failing C status into it."""

from __future__ import annotations

from . import _native
from ._native import lib


class UDM1Error(ValueError):
    """A udm1 call failed. ``status`` is the C status code, ``status_name``
    its enum name, and the message is the library's one-line description."""

    def __init__(self, status: int, message: str):
        self.status = status
        self.status_name = _native.STATUS_NAMES.get(status, f"status {status}")
        super().__init__(message)


def check(status: int) -> None:
    """Raise UDM1Error for a failing status code."""
    if status != 0:
        detail = lib.udm1_last_error().decode("utf-8", "replace")
        if status == 8:
            raise MemoryError(detail)
        raise UDM1Error(status, detail or lib.udm1_status_string(status).decode())
