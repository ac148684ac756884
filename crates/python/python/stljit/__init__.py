"""stljit: compile PLC statement-list programs (S7-200/A5 STL, Omron CP mnemonics) to native
code and drive them scan by scan on deterministic virtual time.

    >>> import stljit
    >>> plc = stljit.Plc("motor.stl")          # doctest: +SKIP
    >>> plc["I0.0"] = 1; plc.run(for_="5s")     # doctest: +SKIP
    >>> plc["Q0.0"]                             # doctest: +SKIP
    True

See ``help(stljit.Plc)`` and docs/python.md in the repository.
"""

from ._native import (
    AddressError,
    CompileError,
    Handle,
    Plc,
    PlcValueError,
    RunReport,
    Snapshot,
    SnapshotError,
    StljitError,
    __version__,
)

__all__ = [
    "AddressError",
    "CompileError",
    "Handle",
    "Plc",
    "PlcValueError",
    "RunReport",
    "Snapshot",
    "SnapshotError",
    "StljitError",
    "__version__",
]
