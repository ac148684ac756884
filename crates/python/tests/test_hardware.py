"""The simulated hardware's stimulus from Python, on both engines: high-speed counter steps
(``plc.set_hsc_steps``, s7-200-more §8.4) and bytes received on a serial port (``plc.queue_rx``,
§10.4), and the errors for a counter or port the CPU does not have."""

import pytest

import stljit
from conftest import EXAMPLES, PROGRAMS

CUT = EXAMPLES / "cut_to_length"
CONVEYOR = EXAMPLES / "omron_conveyor"


def cutter(engine: str) -> stljit.Plc:
    return stljit.Plc(CUT / "cut_to_length.stl", symbols=CUT / "symbols.txt", engine=engine)


def test_encoder_steps_cut_pieces(engine):
    # examples/cut_to_length: HSC0 in mode 0 (counting up), PV 500; the CV = PV routine counts a
    # piece, writes CV = 0 and requests one scan of the cutter.
    plc = cutter(engine)
    plc.set_hsc_steps(0, 10)  # held: 10 steps in every interval from scan 1 on (§8.4)
    plc.run(scans=50)  # scan 0 has no interval; scans 1..49 count 49 * 10
    assert (plc["Length"], plc["Pieces"], plc["Cutter"]) == (490, 0, False)
    plc.scan()  # scan 50: the 10th step, at T_50, reaches 500 = PV: piece 1, CV := 0
    assert (plc["Length"], plc["Pieces"], plc["Cutter"]) == (0, 1, True)
    plc.set_hsc_steps(0, 0)  # the feed stops
    plc.run(scans=10)
    assert (plc["Length"], plc["Pieces"], plc["Cutter"]) == (0, 1, False)


def test_bytes_received_on_port_0(engine):
    plc = stljit.Plc(PROGRAMS / "receive.stl", engine=engine)
    plc.scan()  # scan 0: the RCV starts an any-response message, SMB86 = 0 (§10.3)
    assert plc["SMB86"] == 0
    # Before scan 1: "OK\r" arrives back to back from T_0, one character per 1 042 us at 9 600
    # baud 8N1 (§10.1, §10.4); the CR ends the message: SMB86 = 16#20 (end character).
    plc.queue_rx(0, b"OK\r")
    plc.scan()
    assert [plc[f"VB{b}"] for b in range(200, 204)] == [3, 0x4F, 0x4B, 0x0D]
    assert (plc["SMB86"], plc["SMB2"]) == (0x20, 0x0D)
    plc.queue_rx(0, bytearray(b"x"))  # a bytearray too; the receive is over, VB200 stays 3
    plc.run(scans=2)
    assert plc["VB200"] == 3 and plc["SMB2"] == ord("x")


def test_a_counter_or_port_the_cpu_lacks_raises(engine):
    plc = cutter(engine)  # the a5: HSC0 and HSC1 (§8.2), ports 0 and 1
    with pytest.raises(stljit.StljitError, match=r"the A5 has no high-speed counter 2 \(it has: HSC0, HSC1\)"):
        plc.set_hsc_steps(2, 1)
    with pytest.raises(stljit.StljitError, match=r"the A5 has no serial port 2 \(it has: PORT0, PORT1\)"):
        plc.queue_rx(2, b"x")
    omron = stljit.Plc(CONVEYOR / "conveyor.omr", symbols=CONVEYOR / "symbols.txt", engine=engine)
    with pytest.raises(stljit.StljitError, match=r"the CP1H has no serial port 0 \(it has: none\)"):
        omron.queue_rx(0, b"x")
    with pytest.raises(stljit.StljitError, match="the CP1H has no high-speed counter 0"):
        omron.set_hsc_steps(0, 1)
    with pytest.raises(ValueError, match="counter -1"):
        plc.set_hsc_steps(-1, 1)
    with pytest.raises(ValueError, match="steps 2147483648"):
        plc.set_hsc_steps(0, 2**31)
    with pytest.raises(TypeError, match="bytes or bytearray"):
        plc.queue_rx(0, "OK")
