"""The Python API of stljit.Plc: names, symbols and handles, values and their types, time,
forcing, snapshots, traces and errors, on both engines and both dialects."""

import pickle

import numpy as np
import pytest

import stljit
from conftest import EXAMPLES, PROGRAMS

TRAFFIC = EXAMPLES / "traffic_light"
CONVEYOR = EXAMPLES / "omron_conveyor"


def traffic(engine: str) -> stljit.Plc:
    return stljit.Plc(
        [TRAFFIC / "traffic_light.awl"], symbols=TRAFFIC / "symbols.txt", engine=engine
    )


def level(engine: str, scan_time="100ms") -> stljit.Plc:
    return stljit.Plc(
        str(PROGRAMS / "level.stl"),
        symbols=str(PROGRAMS / "level_symbols.txt"),
        engine=engine,
        scan_time=scan_time,
    )


def test_time_is_virtual_and_runs_are_counted(engine):
    plc = level(engine)
    assert (plc.scan_no, plc.time_ms, plc.scan_ms) == (0, 0, 100)
    assert plc.engine == engine and plc.dialect == "s7" and plc.cpu == "a5"
    assert plc.scan() is None
    r = plc.run(scans=9)
    assert (r.scans, r.outcome, r.time_ms) == (9, "completed", 1000)
    r = plc.run(for_="2m")
    assert r.scans == 1200 and plc.time_ms == 121_000
    r = plc.run(for_=500)
    assert r.scans == 5
    r = plc.run(until_ms=121_750)  # scans at 121.5 s and 121.6 s, 121.7 s
    assert r.scans == 3 and plc.time_ms == 121_800
    with pytest.raises(ValueError):
        plc.run(scans=1, for_="1s")
    with pytest.raises(ValueError):
        plc.run(for_="3 parsecs")
    plc.reset()
    assert plc.scan_no == 0


def test_values_by_address_symbol_and_handle(engine):
    plc = level(engine)
    plc["Level"] = 16000  # 1000 mm: in the band
    plc.scan()
    assert plc["Inlet_Valve"] is False
    plc["Level"] = 8000  # 500 mm: below the low limit
    assert plc["AIW0"] == 8000
    plc.scan()
    assert plc["Inlet_Valve"] is True and plc["Q0.0"] is True
    assert plc["Openings"] == 1 and plc["C0:i"] == 1
    h = plc.handle("VD200:real")
    assert (h.name, h.type) == ("VD200:real", "real")
    plc[h] = 2.5
    assert plc[h] == 2.5 and isinstance(plc[h], float)
    plc["VW10"] = -1
    assert plc["VW10"] == -1 and plc["VW10:u"] == 65535
    plc.set("VB3", np.int64(7))
    assert plc.get("VB3") == 7
    plc["M0.0"] = True
    assert plc["M0.0"] is True
    plc["M0.0"] = np.bool_(False)
    assert plc["M0.0"] is False


def test_errors_carry_the_place_and_the_cause(engine):
    plc = level(engine)
    with pytest.raises(stljit.AddressError, match="Nope"):
        plc["Nope"]
    with pytest.raises(stljit.AddressError, match="VW99999"):
        plc["VW99999"] = 1
    with pytest.raises(stljit.AddressError, match="not writable"):
        plc["SM0.1"] = 1
    with pytest.raises(stljit.PlcValueError, match="70000"):
        plc["VW10"] = 70000
    with pytest.raises(stljit.PlcValueError):
        plc["VW10"] = 1.5
    with pytest.raises(stljit.PlcValueError):
        plc["Q0.0"] = 2
    with pytest.raises(TypeError):
        plc["Q0.0"] = "on"
    with pytest.raises(TypeError):
        plc[3]
    with pytest.raises(stljit.CompileError) as e:
        stljit.Plc(TRAFFIC / "traffic_light.awl", engine=engine)  # no symbols: E009 everywhere
    text = str(e.value)
    assert "error[E009]" in text and "traffic_light.awl:6:3" in text
    assert issubclass(stljit.CompileError, stljit.StljitError)
    with pytest.raises(stljit.StljitError, match="cannot read"):
        stljit.Plc("no/such/file.stl")
    with pytest.raises(stljit.StljitError, match="unknown cpu"):
        stljit.Plc(PROGRAMS / "level.stl", cpu="cp1h")
    with pytest.raises(stljit.StljitError, match="at least 1 ms"):
        stljit.Plc(PROGRAMS / "level.stl", scan_time=0)
    with pytest.raises(ValueError):
        stljit.Plc(PROGRAMS / "level.stl", engine="gpu")


def test_forcing_holds_inputs_and_outputs(engine):
    plc = level(engine)
    plc["Level"] = 8000
    plc.force("Inlet_Valve", False)  # the program sets it, the force wins
    plc.run(scans=10)
    assert plc["Inlet_Valve"] is False
    assert plc.forced == {"Inlet_Valve": False}
    plc.force("I0.0", 1)  # the reset button held by force, though nothing presses it
    plc["Level"] = 2000  # 125 mm: low-low
    plc.scan()
    assert plc["Low_Low"] is False, "the forced reset wins, it runs after the alarm network"
    assert plc.unforce("I0.0") is True and plc.unforce("I0.0") is False
    plc.scan()
    assert plc["Low_Low"] is True and plc["I0.0"] is False
    plc.unforce_all()
    plc.scan()
    assert plc["Inlet_Valve"] is True and plc.forced == {}


def test_snapshot_branches_continue_identically_across_engines(engine):
    plc = traffic(engine)
    plc.scan()  # edges sit out the first scan (spec TC7): press the button after it
    plc["Ped_Button"] = 1
    plc.run(for_="7s")
    snap = plc.snapshot()
    a = plc.trace(["Car_Green", "Car_Yellow", "Ped_Green", "T37:i"], for_="30s")
    other = traffic("interp" if engine == "jit" else "jit")
    other.restore(pickle.loads(pickle.dumps(snap)))
    assert other.time_ms == 7010
    b = other.trace(["Car_Green", "Car_Yellow", "Ped_Green", "T37:i"], for_="30s")
    for key in a:
        np.testing.assert_array_equal(a[key], b[key], err_msg=key)
    assert a["Ped_Green"].any(), "the walk phase happens in the branch"
    with pytest.raises(stljit.SnapshotError):
        level(engine).restore(snap)
    with pytest.raises(stljit.SnapshotError):
        stljit.Snapshot.from_bytes(b"garbage")
    assert stljit.Snapshot.from_bytes(snap.to_bytes()).to_bytes() == snap.to_bytes()


def test_traces_are_numpy_arrays_of_the_right_types(engine):
    plc = level(engine)
    plc["Level"] = 16000
    plc.scan()
    plc["Level"] = 8000
    t = plc.trace(["Inlet_Valve", "Openings", "VD200:real"], scans=20)
    assert t["scan"].dtype == np.uint64 and list(t["scan"][:3]) == [1, 2, 3]
    assert list(t["t_ms"][:3]) == [100, 200, 300]
    assert t["Inlet_Valve"].dtype == np.bool_ and t["Inlet_Valve"].all()
    assert t["Openings"].dtype == np.int64 and t["Openings"][-1] == 1
    assert t["VD200:real"].dtype == np.float64 and len(t["VD200:real"]) == 20


def test_omron_programs_by_symbol(engine):
    plc = stljit.Plc(
        CONVEYOR / "conveyor.omr", symbols=CONVEYOR / "symbols.txt", engine=engine
    )
    assert plc.dialect == "omron" and plc.cpu == "cp1h"
    plc["Stop_PB"] = 1
    plc["Start_PB"] = 1
    plc.scan()
    plc["Start_PB"] = 0
    assert plc["Run_Request"] is True and plc["Horn"] is True
    plc.run(for_="3s")
    assert plc["Motor"] is True and plc["Horn"] is False
    assert plc["Batch_Left"] == plc["D0"]
    with pytest.raises(stljit.AddressError):
        plc["100.16"]
