#!/usr/bin/python3
"""Write a LAMMPS/LIGGGHTS data file (atom_style granular) with a loose,
slightly jittered lattice of monodisperse spheres in an open box.

Only meant to test bench/liggghts/in.bed; the real benchmark bed is a settled
bed written by Upgrain in the same format.

Format written (exactly what in.bed expects):

    <comment line>
    <blank>
    N atoms
    1 atom types
    <blank>
    xlo xhi ylo yhi zlo zhi lines
    <blank>
    Atoms
    <blank>
    id type diameter density x y z      (one line per sphere, SI units)

Usage: make_test_bed.py [out.data] [--n 10000] [--lx 0.06] [--ly 0.06]
                        [--d 3e-3] [--rho 2650] [--gap 0.1] [--seed 1]
"""
import argparse
import math

import numpy as np


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out", nargs="?", default="test_bed.data")
    ap.add_argument("--n", type=int, default=10000, help="number of spheres")
    ap.add_argument("--lx", type=float, default=0.06)
    ap.add_argument("--ly", type=float, default=0.06)
    ap.add_argument("--d", type=float, default=3e-3, help="diameter [m]")
    ap.add_argument("--rho", type=float, default=2650.0, help="density [kg/m^3]")
    ap.add_argument("--gap", type=float, default=0.1,
                    help="lattice gap as a fraction of d (spacing = (1+gap) d)")
    ap.add_argument("--jitter", type=float, default=0.02,
                    help="uniform random offset amplitude as a fraction of d")
    ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()

    d, r = a.d, 0.5 * a.d
    s = (1.0 + a.gap) * d
    # lattice sites per row so that every sphere (plus jitter) is inside the walls
    nx = int(math.floor((a.lx - d - 2 * a.jitter * d) / s)) + 1
    ny = int(math.floor((a.ly - d - 2 * a.jitter * d) / s)) + 1
    per_layer = nx * ny
    nz = int(math.ceil(a.n / per_layer))
    # centre the lattice in x,y
    x0 = 0.5 * (a.lx - (nx - 1) * s)
    y0 = 0.5 * (a.ly - (ny - 1) * s)
    z0 = r + a.jitter * d + 0.05 * d          # first layer just above the floor

    k, j, i = np.meshgrid(np.arange(nz), np.arange(ny), np.arange(nx), indexing="ij")
    pos = np.stack([x0 + i.ravel() * s, y0 + j.ravel() * s, z0 + k.ravel() * s], axis=1)
    pos = pos[: a.n]
    rng = np.random.default_rng(a.seed)
    pos += rng.uniform(-a.jitter * d, a.jitter * d, size=pos.shape)

    assert pos[:, 0].min() >= r and pos[:, 0].max() <= a.lx - r
    assert pos[:, 1].min() >= r and pos[:, 1].max() <= a.ly - r
    assert pos[:, 2].min() >= r

    zhi = pos[:, 2].max() + 5 * d              # head room above the top sphere
    n = pos.shape[0]
    with open(a.out, "w") as f:
        f.write("Upgrain test bed: loose jittered lattice (make_test_bed.py)\n\n")
        f.write(f"{n} atoms\n")
        f.write("1 atom types\n\n")
        f.write(f"0.0 {a.lx:.17g} xlo xhi\n")
        f.write(f"0.0 {a.ly:.17g} ylo yhi\n")
        f.write(f"0.0 {zhi:.17g} zlo zhi\n\n")
        f.write("Atoms\n\n")
        for idx, (x, y, z) in enumerate(pos, start=1):
            f.write(f"{idx} 1 {d:.17g} {a.rho:.17g} {x:.17g} {y:.17g} {z:.17g}\n")
    print(f"wrote {a.out}: {n} spheres, {nx}x{ny} per layer, {nz} layers, "
          f"box 0..{a.lx} x 0..{a.ly} x 0..{zhi:.6g} m")


if __name__ == "__main__":
    main()
