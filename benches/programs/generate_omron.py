#!/usr/bin/env python3
"""Deterministic generator of the Omron CP benchmark program (bit logic plus timers, counters,
moves, compares and arithmetic), in CX-Programmer mnemonic form.

Run from the repository root: `python3 benches/programs/generate_omron.py`. The output file is
committed; rerunning reproduces it byte for byte (fixed seed, no clock). Every generated program
passes the Omron front end's checks: each timer and counter number is used once, TR bits only
with OUT/LD, jumps forward to a JME of their own, IL regions closed, END at the end.
"""
import random


def contact(r):
    k = r.random()
    if k < 0.3:
        return f"{r.randrange(2)}.{r.randrange(16):02d}"          # input words CIO 0-1
    if k < 0.45:
        return f"{100 + r.randrange(2)}.{r.randrange(16):02d}"    # output words
    if k < 0.8:
        return f"W{r.randrange(100)}.{r.randrange(16):02d}"
    return f"H{r.randrange(50)}.{r.randrange(16):02d}"


def pools(r):
    """Every coil bit and destination word once, shuffled: each is written by one instruction
    (no duplicate coils, OMR-W020)."""
    bits = [f"{w}.{b:02d}" for w in (100, 101) for b in range(16)]
    bits += [f"W{w}.{b:02d}" for w in range(100) for b in range(16)]
    bits += [f"H{w}.{b:02d}" for w in range(50) for b in range(16)]
    words = [f"D{w}" for w in range(1000, 3000)]
    r.shuffle(bits)
    r.shuffle(words)
    return bits, words


def dm(r):
    return f"D{r.randrange(1000)}"


class Gen:
    def __init__(self, seed):
        self.r = random.Random(seed)
        self.coils, self.dsts = pools(self.r)
        self.doubles = 0
        self.lines = []
        self.timers = 0
        self.counters = 0
        self.jumps = 0

    def coil(self):
        return self.coils.pop()

    def dst(self):
        return self.dsts.pop()

    def double_dst(self):
        """A fresh double word (D5000 upwards, two words each)."""
        self.doubles += 2
        return f"D{5000 + self.doubles}"

    def emit(self, s):
        self.lines.append(s)

    def block(self):
        """LD with a few serial/parallel contacts."""
        r = self.r
        self.emit(f"{r.choice(['LD', 'LD NOT'])} {contact(r)}")
        for _ in range(r.randint(0, 3)):
            self.emit(f"{r.choice(['AND', 'AND NOT', 'OR', 'OR NOT'])} {contact(r)}")

    def condition(self):
        """A whole execution condition: blocks joined by AND LD / OR LD."""
        r = self.r
        self.block()
        for _ in range(r.randint(0, 2)):
            self.block()
            self.emit(r.choice(["AND LD", "OR LD"]))

    def rung(self):
        r = self.r
        self.condition()
        k = r.random()
        if k < 0.55:
            self.emit(f"OUT {self.coil()}")
            if r.random() < 0.3:
                self.emit(f"AND {contact(r)}")
                self.emit(f"OUT {self.coil()}")
        elif k < 0.65:
            self.emit(f"OUT NOT {self.coil()}")
        elif k < 0.75:
            self.emit(f"{r.choice(['SET', 'RSET'])} {self.coil()}")
        elif k < 0.82:
            self.emit(f"{r.choice(['DIFU(013)', 'DIFD(014)'])} {self.coil()}")
        elif k < 0.9:
            self.block()
            self.emit(f"KEEP(011) {self.coil()}")
        else:
            self.emit("OUT TR0")
            self.emit(f"AND {contact(r)}")
            self.emit(f"OUT {self.coil()}")
            self.emit("LD TR0")
            self.emit(f"AND NOT {contact(r)}")
            self.emit(f"OUT {self.coil()}")

    def network(self):
        r = self.r
        k = r.random()
        if k < 0.5:
            self.rung()
        elif k < 0.58 and self.timers < 4000:
            self.condition()
            kind = r.choice(["TIM", "TIMH(015)", "TIMX(550)"])
            sv = f"&{r.randint(1, 50)}" if "X" in kind else f"#{r.randint(1, 50):04d}"
            self.emit(f"{kind} {self.timers:04d} {sv}")
            self.timers += 1
        elif k < 0.63 and self.counters < 4000:
            self.block()
            self.block()
            self.emit(f"CNT {self.counters:04d} #{r.randint(1, 20):04d}")
            self.counters += 1
        elif k < 0.73:
            self.block()
            k2 = r.random()
            if k2 < 0.4:
                self.emit(f"MOV(021) {dm(r)} {self.dst()}")
            elif k2 < 0.8:
                self.emit(f"MOV(021) #{r.randrange(65536):04X} {self.dst()}")
            else:
                self.emit(f"MOVL(498) D{2 * r.randrange(400)} {self.double_dst()}")
            self.emit("AND P_EQ")
            self.emit(f"OUT {self.coil()}")
        elif k < 0.83:
            rel = r.choice(["=", "<>", "<", "<=", ">", ">="])
            suffix = r.choice(["", "S"])
            self.emit(f"LD{rel}{suffix} {dm(r)} &{r.randint(0, 200)}")
            self.emit(f"AND {contact(r)}")
            self.emit(f"OUT {self.coil()}")
        elif k < 0.93:
            self.block()
            op = r.choice(["+(400)", "-(410)", "+B(404)", "-B(414)", "+L(401)"])
            if op == "+L(401)":
                self.emit(f"{op} D{2 * r.randrange(400)} D{2 * r.randrange(400)} {self.double_dst()}")
            elif "B" in op:
                self.emit(f"{op} {dm(r)} #{r.randint(0, 99):04d} {self.dst()}")
            else:
                self.emit(f"{op} {dm(r)} &{r.randint(1, 9)} {self.dst()}")
            self.emit(r.choice(["AND P_CY", "AND NOT P_EQ", "AND P_ER"]))
            self.emit(f"OUT {self.coil()}")
        elif k < 0.96 and self.jumps < 250:
            n = self.jumps
            self.jumps += 1
            self.block()
            self.emit(f"JMP(004) &{n}")
            for _ in range(r.randint(1, 3)):
                self.rung()
            self.emit(f"JME(005) &{n}")
        else:
            self.block()
            self.emit("IL(002)")
            for _ in range(r.randint(1, 3)):
                self.rung()
            self.emit("ILC(003)")


def mixed(n, seed):
    g = Gen(seed)
    while len(g.lines) < n - 1:
        g.network()
    g.emit("END(001)")
    return g


if __name__ == "__main__":
    import os
    here = os.path.dirname(os.path.abspath(__file__))
    name = "omron_mixed_10k"
    g = mixed(10000, 5)
    with open(os.path.join(here, name + ".omr"), "w") as f:
        f.write(f"; {name}: {len(g.lines)} instructions, {g.timers} timers, {g.counters} counters\n")
        f.write("; Generated by benches/programs/generate_omron.py; do not edit by hand.\n")
        for l in g.lines:
            f.write(l + "\n")
    print(name, len(g.lines), "instructions")
