"""FMI 2.0 co-simulation FMUs made by `stljit fmu`, checked with FMPy (a third-party FMI
library): the FMU validates, simulates with an input signal exactly as `stljit run` runs the same
stimulus, couples with a plant model in a master loop exactly as the Python API does, and saves
and restores its state.

The `stljit` executable is $STLJIT_BIN, else the one on PATH, else the workspace's
target/release/stljit.
"""

import csv
import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
from fmpy import extract, read_model_description, simulate_fmu
from fmpy.fmi2 import FMU2Slave
from fmpy.validation import validate_fmu

import stljit
from conftest import EXAMPLES, PROGRAMS, REPO
from test_closed_loop import COUNTS_PER_MM, Tank

TRAFFIC = EXAMPLES / "traffic_light"


def stljit_bin() -> str:
    found = os.environ.get("STLJIT_BIN") or shutil.which("stljit")
    if found:
        return found
    local = REPO / "target" / "release" / "stljit"
    assert local.exists(), "no stljit executable: set STLJIT_BIN, put stljit on PATH or build it"
    return str(local)


def stljit_cli(*args: str, check: bool = True) -> subprocess.CompletedProcess:
    return subprocess.run(
        [stljit_bin(), *args], capture_output=True, text=True, check=check
    )


@pytest.fixture(scope="module")
def traffic_fmu(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("fmu") / "traffic_light.fmu"
    stljit_cli(
        "fmu", str(TRAFFIC / "traffic_light.awl"), "--symbols", str(TRAFFIC / "symbols.txt"),
        "--local", "Walk_Total,T37:i", "-o", str(out),
    )
    return out


@pytest.fixture(scope="module")
def level_fmu(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("fmu") / "level.fmu"
    stljit_cli(
        "fmu", str(PROGRAMS / "level.stl"), "--symbols", str(PROGRAMS / "level_symbols.txt"),
        "--scan-time", "100ms", "--local", "Openings", "-o", str(out),
    )
    return out


def test_fmpy_validates_the_fmus(traffic_fmu, level_fmu, tmp_path):
    omron = tmp_path / "floats.fmu"
    stljit_cli("fmu", str(PROGRAMS / "floats.omr"), "--local", "D0", "-o", str(omron))
    for fmu in (traffic_fmu, level_fmu, omron):
        assert validate_fmu(str(fmu)) == [], fmu
    md = read_model_description(str(traffic_fmu))
    assert md.fmiVersion == "2.0" and md.coSimulation.modelIdentifier == "traffic_light"
    by_name = {v.name: v for v in md.modelVariables}
    assert by_name["Ped_Button"].causality == "input" and by_name["Ped_Button"].type == "Boolean"
    assert by_name["Car_Red"].causality == "output"
    assert by_name["T37:i"].causality == "local" and by_name["T37:i"].type == "Integer"
    assert md.defaultExperiment.stepSize == "0.01"
    md = read_model_description(str(omron))
    names = {v.name: v.causality for v in md.modelVariables}
    assert names == {"0.00": "input", "0.01": "input", "100.00": "output", "D0": "local"}


def test_simulation_with_an_input_signal_matches_stljit_run(traffic_fmu, tmp_path):
    # The example's stimulus as an FMPy input signal (t_ms,Ped_Button,Night_Mode,Count_Reset).
    rows = [(0, 0, 0, 0), (5000, 1, 0, 0), (5300, 0, 0, 0), (60000, 1, 0, 0), (60200, 0, 0, 0),
            (90000, 0, 1, 0), (110000, 0, 0, 0)]
    signal = np.array(
        [(t / 1000.0, bool(p), bool(n), bool(c)) for t, p, n, c in rows],
        dtype=[("time", np.double), ("Ped_Button", np.bool_), ("Night_Mode", np.bool_),
               ("Count_Reset", np.bool_)],
    )
    outputs = ["Car_Red", "Car_Yellow", "Car_Green", "Ped_Red", "Ped_Green", "Walk_Total"]
    result = simulate_fmu(
        str(traffic_fmu), stop_time=120.0, step_size=0.01, output_interval=0.01,
        input=signal, output=outputs,
    )
    trace = tmp_path / "trace.csv"
    stljit_cli(
        "run", str(TRAFFIC / "traffic_light.awl"), "--symbols", str(TRAFFIC / "symbols.txt"),
        "--inputs", str(TRAFFIC / "stimulus.csv"), "--for", "2m",
        "--watch", ",".join(outputs), "--trace", str(trace),
    )
    with open(trace) as f:
        runs = list(csv.DictReader(f))
    assert len(runs) == 12000 and len(result) == 12001
    # FMPy samples at t = k * 10 ms after the step [t - 10 ms, t): that is the image after scan
    # k - 1, the trace's row k - 1.
    for name in outputs:
        fmu_values = result[name][1:].astype(int)
        run_values = np.array([int(r[name]) for r in runs])
        np.testing.assert_array_equal(fmu_values, run_values, err_msg=name)
    assert result["Ped_Green"].any() and result["Walk_Total"][-1] == 2


def master(fmu_path: Path, tmp_path: Path):
    md = read_model_description(str(fmu_path))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    unzipped = extract(str(fmu_path), unzipdir=str(tmp_path / "unzipped"))
    fmu = FMU2Slave(
        guid=md.guid, unzipDirectory=unzipped,
        modelIdentifier=md.coSimulation.modelIdentifier, instanceName="plc",
    )
    fmu.instantiate()
    fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    return fmu, vr


def test_master_loop_with_a_plant_model_matches_the_python_api(level_fmu, tmp_path):
    fmu, vr = master(level_fmu, tmp_path)
    plc = stljit.Plc(PROGRAMS / "level.stl", symbols=PROGRAMS / "level_symbols.txt",
                     scan_time="100ms")
    dt = 0.1
    tank_fmu, tank_api = Tank(500.0), Tank(500.0)
    t = 0.0
    for k in range(36_000):  # one hour, one scan per communication step
        fmu.setInteger([vr["Level"]], [int(tank_fmu.level * COUNTS_PER_MM)])
        fmu.doStep(currentCommunicationPoint=t, communicationStepSize=dt)
        valve_fmu = fmu.getBoolean([vr["Inlet_Valve"]])[0]
        plc["Level"] = int(tank_api.level * COUNTS_PER_MM)
        plc.scan()
        valve_api = plc["Inlet_Valve"]
        assert bool(valve_fmu) == valve_api, f"step {k}"
        tank_fmu.step(bool(valve_fmu), t, dt)
        tank_api.step(valve_api, t, dt)
        t = (k + 1) * dt
    assert fmu.getInteger([vr["Openings"]])[0] == plc["Openings"] > 10
    # Steps longer than a scan run every scan that starts in them.
    fmu.doStep(currentCommunicationPoint=t, communicationStepSize=0.35)
    plc.run(until_ms=round((t + 0.35) * 1000))
    assert fmu.getInteger([vr["Openings"]])[0] == plc["Openings"]
    fmu.terminate()
    fmu.freeInstance()


def test_fmu_state_save_restore_and_serialize(level_fmu, tmp_path):
    fmu, vr = master(level_fmu, tmp_path)
    level = vr["Level"]
    fmu.setInteger([level], [8000])
    t = 0.0
    for _ in range(50):
        fmu.doStep(currentCommunicationPoint=t, communicationStepSize=0.1)
        t += 0.1
    state = fmu.getFMUstate()
    serialized = fmu.serializeFMUstate(state)

    def branch(level_counts):
        fmu.setInteger([level], [level_counts])
        tt = t
        out = []
        for _ in range(20):
            fmu.doStep(currentCommunicationPoint=tt, communicationStepSize=0.1)
            tt += 0.1
            out.append(fmu.getBoolean([vr["Inlet_Valve"]])[0])
        return out

    high = branch(20000)  # above the band: the valve closes
    fmu.setFMUstate(state)
    assert branch(20000) == high
    fmu.setFMUstate(fmu.deSerializeFMUstate(serialized))
    low = branch(8000)
    assert high[-1] == 0 and low[-1] == 1
    fmu.freeFMUstate(state)
    # A step from the wrong time is refused (FMI status Error raises in FMPy).
    with pytest.raises(Exception):
        fmu.doStep(currentCommunicationPoint=0.0, communicationStepSize=0.1)
    fmu.freeInstance()


def test_export_errors_name_the_cause(tmp_path):
    r = stljit_cli("fmu", str(TRAFFIC / "traffic_light.awl"), "-o", str(tmp_path / "x.fmu"),
                   check=False)
    assert r.returncode == 1 and "error[E009]" in r.stderr
    r = stljit_cli("fmu", str(PROGRAMS / "level.stl"), "--local", "Nope", "-o",
                   str(tmp_path / "x.fmu"), check=False)
    assert r.returncode == 2 and "Nope" in r.stderr
    assert not (tmp_path / "x.fmu").exists()
