#!/usr/bin/python3
"""Convert a LIGGGHTS `write_data` file (atom_style granular) into the plain
format that Upgrain writes and in.bed reads:

    N atoms / 1 atom types / xlo xhi / ylo yhi / zlo zhi / Atoms
    id type diameter density x y z

Image flags and the Velocities section are dropped (the bed starts at rest,
as an Upgrain bed does).  Testing helper only.

Usage: strip_data.py in.data out.data
"""
import sys


def main():
    src, dst = sys.argv[1], sys.argv[2]
    lines = open(src).read().splitlines()
    n = None
    box = {}
    atoms = []
    i = 0
    while i < len(lines):
        t = lines[i].split()
        if len(t) == 2 and t[1] == "atoms":
            n = int(t[0])
        elif len(t) == 4 and t[2:] in (["xlo", "xhi"], ["ylo", "yhi"], ["zlo", "zhi"]):
            box[t[2]] = (float(t[0]), float(t[1]))
        elif t and t[0] == "Atoms":
            i += 1
            while i < len(lines) and not lines[i].strip():
                i += 1
            while i < len(lines) and lines[i].strip():
                c = lines[i].split()
                atoms.append((int(c[0]), int(c[1])) + tuple(float(v) for v in c[2:7]))
                i += 1
            continue
        i += 1
    assert n == len(atoms), (n, len(atoms))
    atoms.sort()
    with open(dst, "w") as f:
        f.write(f"settled test bed converted from {src}\n\n")
        f.write(f"{n} atoms\n1 atom types\n\n")
        for k in ("xlo", "ylo", "zlo"):
            lo, hi = box[k]
            f.write(f"{lo:.17g} {hi:.17g} {k} {k[0]}hi\n")
        f.write("\nAtoms\n\n")
        for a in atoms:
            f.write("%d %d %.17g %.17g %.17g %.17g %.17g\n" % a)
    print(f"wrote {dst}: {n} atoms")


if __name__ == "__main__":
    main()
