#!/usr/bin/env python3
"""Splits a callgrind profile of the engine's steps into the phases of a step.

Usage: callgrind_phases.py PROFILE BINARY PARTICLES STEPS [--lines]

PROFILE is a callgrind output file written with --dump-instr=yes (and, for the miss
columns, --cache-sim=yes --branch-sim=yes); BINARY the program that wrote it, built with
-g (debug information does not change GCC's code). Prints a Markdown table: every event per
particle-step and each phase's share of the instructions.

The force loop is one function with everything inlined (dem/engine/force_loop_body.h), so
its instructions are split by source line: each instruction's inline chain (addr2line -i)
is followed out to its line in force_loop_body.h, and that line's phase is read from the
markers of MARKS, found in the source itself (`body_line_phases`; a missing marker stops the
script). Every other function goes by its name (`phase_of_function`). The figures and how to
read them: bench/README.md, "Where the sphere step's time goes".
"""
import collections
import re
import subprocess
import sys

BODY = "force_loop_body.h"


def parse(path):
    """Self cost per (object, function, address): a dict of event lists, and the event names."""
    events = []
    names = {"ob": {}, "fl": {}, "fn": {}}
    ob = fl = fn = None
    cost = collections.defaultdict(lambda: None)
    last = [0, 0]
    skip_next = False

    def name(kind, value):
        m = re.match(r"\((\d+)\)(?: (.*))?", value)
        if not m:
            return value
        if m.group(2) is not None:
            names[kind][m.group(1)] = m.group(2)
        return names[kind][m.group(1)]

    with open(path) as f:
        for line in f:
            line = line.rstrip("\n")
            if not line:
                continue
            if line.startswith("events:"):
                events = line.split()[1:]
                continue
            key, sep, value = line.partition("=")
            if sep and key in ("ob", "fl", "fi", "fe", "fn", "cob", "cfi", "cfl", "cfn", "calls", "jump", "jcnd"):
                if key == "ob":
                    ob = name("ob", value)
                elif key in ("fl", "fi", "fe"):
                    fl = name("fl", value)
                elif key == "fn":
                    fn = name("fn", value)
                elif key == "cob":
                    name("ob", value)
                elif key in ("cfi", "cfl"):
                    name("fl", value)
                elif key == "cfn":
                    name("fn", value)
                elif key == "calls":
                    skip_next = True  # the next cost line is the call's inclusive cost
                continue
            if not (line[0].isdigit() or line[0] in "+-*"):
                continue
            parts = line.split()
            pos = []
            for k in range(2):
                t = parts[k]
                if t == "*":
                    v = last[k]
                elif t[0] in "+-":
                    v = last[k] + int(t, 0)
                else:
                    v = int(t, 0)
                pos.append(v)
            last = pos
            if skip_next:
                skip_next = False
                continue
            vals = [int(x) for x in parts[2:]]
            k = (ob, fn, pos[0])
            c = cost[k]
            if c is None:
                cost[k] = vals + [0] * (len(events) - len(vals))
            else:
                for i, x in enumerate(vals):
                    c[i] += x
    return events, cost


# The phases of force_loop_body.h's lines: each marker, found in this order, starts the phase
# of the lines from it on. None: a helper (forget_history, the forget lambdas), whose lines
# take the phase of the line that called them.
SETUP = "force loop: set-up (zeroing, output vectors)"
ROWS = "pair loop: rows (row sums loaded and stored)"
MARKS = [
    ("void compute(const ForceInput& in) {", SETUP),
    ("auto forget_wall = ", None),
    ("auto wall_loop = ", "walls"),
    ("// Particle pairs.", SETUP),
    ("auto forget = ", None),
    ("auto pair_loop = ", ROWS),
    ("out.slot_class.resize(", "shape classes (bounding spheres, batches)"),
    ("std::array<const ShapedPair*, kBatches> batch_data;", ROWS),
    ("for (int k = start[r]; k < start[r + 1]; ++k) {", "pair distance checks"),
    ("const SpherePairArms arms", "contact law"),
    ("fi += cf.on_i;", "force and torque sums"),
    ("if constexpr (kRolling) {", "contact law"),
    ("if constexpr (kEnergyPerParticle) {", "energy work"),
    ("if (!kDeterministic || owned_i) ++pair_contacts;", "overlap guard, contact count"),
    ("if constexpr (kDeterministic) {", ROWS),
    ("if constexpr (kEnergyPerParticle) {", "energy work"),
    ("out.energy = energy;", SETUP),
]


def body_line_phases(path):
    """Phase of each line of force_loop_body.h (MARKS)."""
    phase = {}
    current = None
    m = 0
    for n, text in enumerate(open(path).read().split("\n"), start=1):
        if m < len(MARKS) and text.strip().startswith(MARKS[m][0]):
            current = MARKS[m][1]
            m += 1
        phase[n] = current
    if m != len(MARKS):
        sys.exit("callgrind_phases.py: marker %r not found in %s" % (MARKS[m][0], path))
    return phase


def phase_of_function(fn):
    if fn is None:
        return "other"
    if "Simulation::step" in fn or "rotation_first_half" in fn or "rotation_second_half" in fn:
        return "integration (half kicks, drift, skin check, rotation halves)"
    if "MPI_" in fn or "PMPI" in fn or "ompi" in fn or "opal" in fn or "mca_" in fn:
        return "reductions (MPI_Allreduce)"
    if "check_overlap" in fn:
        return "reductions (MPI_Allreduce)"
    if any(k in fn for k in ("posed_", "warm_", "newton_on_sphere", "curvatures_body", "assemble(", "shaped_pair",
                             "GrainPoses", "PosedEllipsoid", "SupportFunction", "support_function")):
        return "ellipsoid narrow phase (poses, support-function solve)"
    if "Verlet" in fn or "rebuild" in fn or "sort_by_cell" in fn or "neighbor" in fn.lower():
        return "neighbour build"
    if "add_to" in fn or "book" in fn or "ExactSum" in fn or "Energy" in fn:
        return "energy work"
    if "clock_gettime" in fn or "steady_clock" in fn or "vdso" in fn.lower():
        return "timers (steady_clock)"
    if "evaluate_forces" in fn or "Simulation::run" in fn:
        return "force loop: set-up (zeroing, output vectors)"
    return "other"


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    if len(args) != 4:
        sys.exit(__doc__)
    profile, binary, particles, steps = args[0], args[1], int(args[2]), int(args[3])
    events, cost = parse(profile)
    ir = events.index("Ir")
    body = None
    # The force loop's instructions (addresses in the binary) and their inline chains,
    # innermost frame first.
    loop_addrs = sorted({a for (ob, fn, a) in cost if fn and "force_loop_detail::compute<" in fn})
    chains = {}
    batch = 400
    for s in range(0, len(loop_addrs), batch):
        part = loop_addrs[s:s + batch]
        out = subprocess.run(["addr2line", "-i", "-a", "-e", binary] + ["0x%x" % a for a in part],
                             capture_output=True, text=True).stdout.split("\n")
        cur = None
        for line in out:
            if line.startswith("0x"):
                cur = int(line, 16)
                chains[cur] = []
            elif line and cur is not None:
                chains[cur].append(line)
    totals = collections.defaultdict(lambda: [0] * len(events))
    by_line = collections.defaultdict(lambda: [0] * len(events))
    for (ob, fn, a), c in cost.items():
        if fn and "force_loop_detail::compute<" in fn:
            ph = "force loop: unplaced"
            for frame in chains.get(a) or []:
                file, _, ln = frame.rpartition(":")
                ln = ln.split()[0]
                if file.endswith(BODY) and ln.isdigit():
                    if body is None:
                        body = body_line_phases(file)
                    if body.get(int(ln)) is None:
                        continue  # a helper: the phase of its caller
                    ph = body[int(ln)]
                    by_line[int(ln)] = [x + y for x, y in zip(by_line[int(ln)], c)]
                    break
        else:
            ph = phase_of_function(fn)
        t = totals[ph]
        for i, x in enumerate(c):
            t[i] += x
    ps = particles * steps
    all_ir = sum(t[ir] for t in totals.values())
    cols = [e for e in ("Ir", "Dr", "Dw", "D1mr", "D1mw", "DLmr", "DLmw", "Bc", "Bcm", "Bi", "Bim") if e in events]
    print("| phase | share of Ir | " + " | ".join(c + "/ps" for c in cols) + " |")
    print("|---|---|" + "---|" * len(cols))
    for ph, t in sorted(totals.items(), key=lambda kv: -kv[1][ir]):
        print("| %s | %.1f %% | " % (ph, 100.0 * t[ir] / all_ir) +
              " | ".join("%.2f" % (t[events.index(c)] / ps) for c in cols) + " |")
    tot = [sum(t[i] for t in totals.values()) for i in range(len(events))]
    print("| **all** | 100 % | " + " | ".join("%.2f" % (tot[events.index(c)] / ps) for c in cols) + " |")
    if "--lines" in sys.argv:
        # Per line of force_loop_body.h: instructions, conditional branches and their simulated
        # mispredictions per particle-step.
        bc, bcm = events.index("Bc") if "Bc" in events else None, events.index("Bcm") if "Bcm" in events else None
        for ln, v in sorted(by_line.items()):
            if v[ir] == 0:
                continue
            extra = "" if bc is None else " %8.2f %8.2f" % (v[bc] / ps, v[bcm] / ps)
            print("%5d %10.2f%s  %s" % (ln, v[ir] / ps, extra, (body or {}).get(ln, "")))


if __name__ == "__main__":
    main()
