"""Closed loop: a tank-level plant model in Python coupled to PLC level controllers for hours
of virtual time. The bounds asserted are derived from the plant model and the controller's
limits, not read off a run.

Plant: a tank whose level h (mm) rises at Q_IN mm/s while the inlet valve is open and falls at
the demand d(t) = 1.5 + 1.0 sin(2 pi t / 40 min) mm/s (0.5 ... 2.5 mm/s) all the time. The PLC reads
the level at the start of scan k (time t_k) and its valve output holds until the next scan.
"""

import math

import pytest

import stljit
from conftest import PROGRAMS

Q_IN = 4.0  # mm/s with the valve open
LOW, HIGH = 900.0, 1100.0  # the controllers' switching levels (mm)
COUNTS_PER_MM = 16


def demand(t_s: float) -> float:
    return 1.5 + 1.0 * math.sin(2 * math.pi * t_s / 2400.0)


def expected_fills(t0: float, t1: float, dt: float) -> float:
    """Fill cycles the plant model predicts between t0 and t1: a cycle takes
    (HIGH - LOW) / (Q_IN - d) to fill and (HIGH - LOW) / d to drain, d varying slowly."""
    n, t = 0.0, t0
    while t < t1:
        d = demand(t)
        n += dt / ((HIGH - LOW) / (Q_IN - d) + (HIGH - LOW) / d)
        t += dt
    return n


class Tank:
    def __init__(self, level: float) -> None:
        self.level = level

    def step(self, valve: bool, t_s: float, dt: float) -> None:
        self.level += ((Q_IN if valve else 0.0) - demand(t_s)) * dt


@pytest.mark.parametrize("hours", [4])
def test_s7_level_controller_keeps_the_tank_in_band_for_hours(engine, hours):
    plc = stljit.Plc(
        PROGRAMS / "level.stl",
        symbols=PROGRAMS / "level_symbols.txt",
        engine=engine,
        scan_time="100ms",
    )
    dt = plc.scan_ms / 1000.0
    sensor, valve = plc.handle("Level"), plc.handle("Inlet_Valve")
    tank = Tank(level=500.0)  # starts low: the first fill brings it into the band
    openings, was_open, in_band_since = 0, False, None
    lo_seen, hi_seen = math.inf, -math.inf
    # One scan's worst move (plus one count of quantisation) past a limit before the PLC acts.
    slack_low = 2.5 * dt + 1.0 / COUNTS_PER_MM
    slack_high = (Q_IN - 0.5) * dt + 1.0 / COUNTS_PER_MM
    for _ in range(int(hours * 3600 / dt)):
        t_s = plc.time_ms / 1000.0
        plc[sensor] = int(tank.level * COUNTS_PER_MM)
        plc.scan()
        is_open = plc[valve]
        openings += is_open and not was_open
        was_open = is_open
        tank.step(is_open, t_s, dt)
        if in_band_since is None and tank.level >= LOW:
            in_band_since = t_s
        if in_band_since is not None:
            lo_seen, hi_seen = min(lo_seen, tank.level), max(hi_seen, tank.level)
    assert plc.time_ms == hours * 3_600_000
    assert in_band_since is not None and in_band_since < 200, "the first fill takes ~150 s"
    assert LOW - slack_low <= lo_seen < LOW + 1.0, lo_seen
    assert HIGH - 1.0 < hi_seen <= HIGH + slack_high, hi_seen
    # The PLC counts every opening but the one in scan 0: edges sit out the first scan (spec TC7).
    assert plc["Openings"] == openings - 1
    predicted = expected_fills(in_band_since, hours * 3600.0, 1.0)
    assert abs(openings - predicted) <= 0.03 * predicted + 2, (openings, predicted)
    assert not plc["High_High"] and not plc["Low_Low"]

    # What if the valve sticks shut? Force it: the level drains, and the low-low alarm latches
    # in the first scan that reads a level below 200 mm, although the program wants the valve open.
    plc.force(valve, False)
    alarm_at = None
    while alarm_at is None:
        plc[sensor] = int(tank.level * COUNTS_PER_MM)
        below = tank.level * COUNTS_PER_MM < 3200
        plc.scan()
        assert plc[valve] is False
        assert plc["Low_Low"] == below, tank.level
        if below:
            alarm_at = tank.level
        tank.step(False, plc.time_ms / 1000.0, dt)
        assert plc.time_ms < (hours * 3600 + 1800) * 1000, "drains within 30 min at >= 0.5 mm/s"
    assert 200.0 - 2.5 * dt - 0.1 < alarm_at < 200.0
    # Released, the controller opens the valve at once; the alarm stays latched until reset.
    plc.unforce(valve)
    plc[sensor] = int(tank.level * COUNTS_PER_MM)
    plc.scan()
    assert plc[valve] is True and plc["Low_Low"] is True
    while tank.level < 300:
        tank.step(True, plc.time_ms / 1000.0, dt)
        plc[sensor] = int(tank.level * COUNTS_PER_MM)
        plc.scan()
    plc["Alarm_Reset"] = 1
    plc.scan()
    plc["Alarm_Reset"] = 0
    plc.scan()
    assert plc["Low_Low"] is False


def run_floats(engine: str, hours: float):
    """The Omron float-switch controller for `hours`; returns the valve switching times."""
    plc = stljit.Plc(PROGRAMS / "floats.omr", engine=engine, scan_time="50ms")
    assert plc.dialect == "omron"
    dt = plc.scan_ms / 1000.0
    low_float, high_float, valve = (plc.handle(n) for n in ("0.00", "0.01", "100.00"))
    tank = Tank(level=1000.0)
    switches, was_open, levels = [], False, []
    for _ in range(int(hours * 3600 / dt)):
        t_s = plc.time_ms / 1000.0
        plc[low_float] = tank.level > LOW
        plc[high_float] = tank.level >= HIGH
        plc.scan()
        is_open = plc[valve]
        if is_open != was_open:
            switches.append((plc.scan_no, is_open))
        was_open = is_open
        tank.step(is_open, t_s, dt)
        levels.append(tank.level)
    return plc, switches, levels


def test_omron_float_switch_controller_on_both_engines_agrees():
    runs = {e: run_floats(e, hours=1.0) for e in ("jit", "interp")}
    (plc, switches, levels), (_, switches_interp, _) = runs["jit"], runs["interp"]
    assert switches == switches_interp, "both engines switch the valve at the same scans"
    dt = plc.scan_ms / 1000.0
    assert LOW - 2.5 * dt <= min(levels) and max(levels) <= HIGH + (Q_IN - 0.5) * dt
    fills = sum(1 for _, opened in switches if opened)
    assert plc["D0"] == fills, "the PLC counts each opening once (@+ is up-differentiated)"
    predicted = expected_fills(0.0, 3600.0, 1.0)
    assert abs(fills - predicted) <= 0.05 * predicted + 2, (fills, predicted)
