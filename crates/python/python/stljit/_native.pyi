"""Type hints of stljit's native module (the classes re-exported by ``stljit``)."""

from os import PathLike
from typing import Dict, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

_Path = Union[str, "PathLike[str]"]
_Duration = Union[str, int]
_Value = Union[bool, int, float]
_Key = Union[str, "Handle"]

class StljitError(Exception):
    """Base class of every error stljit raises."""

class CompileError(StljitError):
    """The program has errors; the message is every diagnostic as ``stljit check`` prints it."""

class AddressError(StljitError):
    """A name is no address or symbol of the program, or may not be written or forced."""

class PlcValueError(StljitError):
    """A value does not fit the address."""

class SnapshotError(StljitError):
    """A snapshot belongs to another program, or bytes are not a snapshot."""

class Handle:
    """A name resolved once: reads and writes through it skip the lookup."""

    @property
    def name(self) -> str: ...
    @property
    def type(self) -> str:
        """``bool``, ``byte``, ``int16``, ``uint16``, ``int32``, ``uint32`` or ``real``."""

class Snapshot:
    """The whole state of a PLC: image, timers, counters, edges, time, forces."""

    def to_bytes(self) -> bytes: ...
    @staticmethod
    def from_bytes(data: bytes) -> "Snapshot": ...
    def __reduce__(self) -> Tuple[object, Tuple[bytes]]: ...

class RunReport:
    """What a run did."""

    @property
    def scans(self) -> int: ...
    @property
    def outcome(self) -> str:
        """``completed``, ``stopped``, ``fatal`` or ``cancelled``."""
    @property
    def message(self) -> str: ...
    @property
    def time_ms(self) -> int: ...

class Plc:
    """A compiled PLC program on an engine, driven scan by scan on virtual time.

    Names: addresses of the program's dialect (``"I0.0"``, ``"VW10"``, ``"100.01"``, ``"D10"``),
    symbols of the symbol table, with an optional type suffix (``":i"``, ``":u"``, ``":real"``);
    ``"T37"`` is a timer's bit and ``"T37:i"`` its value. Bits read as ``bool``, integers as
    ``int``, reals as ``float``. An input written now reaches the program at the next scan's
    input refresh; anything else is written at once.
    """

    def __init__(
        self,
        files: Union[_Path, Sequence[_Path]],
        dialect: Optional[str] = None,
        cpu: Optional[str] = None,
        symbols: Optional[_Path] = None,
        engine: str = "jit",
        scan_time: Optional[_Duration] = "10ms",
    ) -> None: ...
    def handle(self, name: str) -> Handle: ...
    def __getitem__(self, key: _Key) -> _Value: ...
    def __setitem__(self, key: _Key, value: _Value) -> None: ...
    def get(self, key: _Key) -> _Value: ...
    def set(self, key: _Key, value: _Value) -> None: ...
    def scan(self) -> None:
        """Runs one scan."""
    def run(
        self,
        scans: Optional[int] = None,
        for_: Optional[_Duration] = None,
        until_ms: Optional[int] = None,
    ) -> RunReport:
        """Runs ``scans`` scans, ``for_`` virtual time, or every scan starting before ``until_ms``."""
    def trace(
        self,
        names: Sequence[str],
        scans: Optional[int] = None,
        for_: Optional[_Duration] = None,
        until_ms: Optional[int] = None,
    ) -> Dict[str, npt.NDArray[np.generic]]:
        """Runs like ``run``; returns ``scan``, ``t_ms`` and one array per name, one row per scan."""
    def set_hsc_steps(self, counter: int, steps: int) -> None:
        """Gives high-speed counter ``counter`` ``steps`` signed unit steps in every scan
        interval from the next scan on, held until set again (S7 only; a counter the CPU lacks
        raises ``StljitError``)."""
    def queue_rx(self, port: int, data: Union[bytes, bytearray]) -> None:
        """Queues ``data`` to be received on serial port ``port`` in the interval before the
        next scan (S7 only; a port the CPU lacks raises ``StljitError``)."""
    def force(self, key: _Key, value: _Value) -> None: ...
    def unforce(self, key: _Key) -> bool: ...
    def unforce_all(self) -> None: ...
    @property
    def forced(self) -> Dict[str, _Value]: ...
    def snapshot(self) -> Snapshot: ...
    def restore(self, snapshot: Snapshot) -> None: ...
    def reset(self) -> None: ...
    @property
    def time_ms(self) -> int: ...
    @property
    def scan_no(self) -> int: ...
    @property
    def scan_ms(self) -> int: ...
    @property
    def engine(self) -> str: ...
    @property
    def dialect(self) -> str: ...
    @property
    def cpu(self) -> str: ...
    @property
    def is_stopped(self) -> bool: ...
