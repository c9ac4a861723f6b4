#!/usr/bin/python3
"""Side-by-side dense-bed benchmark: Upgrain vs LIGGGHTS 3.8.

For each bed size: Upgrain settles a bed once (bench_dense_bed settle) and writes a data
file; then both codes run 2,000 steps from that same file, on 1 rank, alternately,
`--repeat` times each. Reported: best particle-steps/s of each code, their ratio,
contacts per particle (to show the two scenes match) and peak memory per particle.

Usage: bench/compare_liggghts.py [--build build] [--sizes 10000 50000] [--repeat 3]
LIGGGHTS comes from the Debian package `liggghts` (apt-get install liggghts); its deck
and settings are documented in bench/liggghts/README.md.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))


def run_measured(cmd, cwd=None):
    """Runs cmd, returns (stdout, peak RSS in bytes) of that program alone.

    The peak is VmHWM of /proc/<pid>/status, polled while the program runs: it belongs to
    the program's own address space after exec. (The rusage of the child would also count
    the Python image the child was forked from.)"""
    proc = subprocess.Popen(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    peak = 0
    chunks = []
    reader = threading.Thread(target=lambda: chunks.append(proc.stdout.read()))
    reader.start()
    while proc.poll() is None:
        try:
            with open(f"/proc/{proc.pid}/status") as status:
                for line in status:
                    if line.startswith("VmHWM:"):
                        peak = max(peak, int(line.split()[1]) * 1024)
        except (FileNotFoundError, ProcessLookupError, ValueError):
            pass
        time.sleep(0.02)
    reader.join()
    out = "".join(chunks)
    if proc.returncode != 0:
        sys.exit(f"failed ({proc.returncode}): {' '.join(cmd)}\n{out[-3000:]}")
    return out, peak


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(HERE, "..", "build"))
    ap.add_argument("--sizes", type=int, nargs="+", default=[10000, 50000])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--steps", type=int, default=2000)
    ap.add_argument("--results", default=os.path.join(HERE, "results"))
    ap.add_argument("--summation", default="deterministic", choices=["deterministic", "fast"],
                    help="the engine's summation (docs/architecture.md)")
    a = ap.parse_args()
    bench = os.path.join(a.build, "bench", "bench_dense_bed")
    liggghts = shutil.which("liggghts")
    if not os.path.exists(bench):
        sys.exit(f"{bench} not built: cmake --build {a.build}")
    if liggghts is None:
        sys.exit("liggghts not found: apt-get install --no-install-recommends liggghts")
    os.makedirs(a.results, exist_ok=True)
    rows = []
    for n in a.sizes:
        data = os.path.join(a.results, f"bed_{n}.data")
        if not os.path.exists(data):
            print(f"settling {n} spheres (once; kept in {data}) ...", flush=True)
            run_measured([bench, "settle", str(n), data])
        side = next(float(l.split()[1]) for l in open(data) if "xlo xhi" in l)
        best_u = best_l = None
        for rep in range(a.repeat):
            out, rss_u = run_measured([bench, "run", data, str(a.steps), a.summation])
            m = dict(zip(*[iter(out.split()[1:])] * 2))
            u = {k: float(v) for k, v in m.items() if k != "summation"}
            u["rss"] = rss_u
            if best_u is None or u["particle_steps_per_second"] > best_u["particle_steps_per_second"]:
                best_u = u
            out, rss_l = run_measured([liggghts, "-in", "in.bed", "-var", "datafile", data, "-var", "lx", repr(side),
                                       "-var", "ly", repr(side), "-var", "nsteps", str(a.steps), "-log", "none",
                                       "-echo", "none"], cwd=os.path.join(HERE, "liggghts"))
            loop = re.search(r"Loop time of ([0-9.eE+-]+) on 1 procs for (\d+) steps with (\d+) atoms", out)
            cont = re.search(r"CONTACTS: .*mean_pp_contacts_per_particle ([0-9.eE+-]+)", out)
            pw = re.search(r"pw_contacts ([0-9.eE+-]+)", out)
            lg = {"seconds": float(loop.group(1)), "rss": rss_l,
                  "particle_steps_per_second": int(loop.group(3)) * int(loop.group(2)) / float(loop.group(1)),
                  "contacts_per_particle": float(cont.group(1)), "wall_contacts": float(pw.group(1))}
            if best_l is None or lg["particle_steps_per_second"] > best_l["particle_steps_per_second"]:
                best_l = lg
            print(f"  N={n} rep {rep + 1}: upgrain {u['particle_steps_per_second']:.3e}, "
                  f"liggghts {lg['particle_steps_per_second']:.3e} particle-steps/s", flush=True)
        rows.append((n, best_u, best_l))
    print("\n| spheres | Upgrain particle-steps/s | LIGGGHTS particle-steps/s | ratio | contacts/particle U / L "
          "| wall contacts U / L | peak bytes/particle U / L |")
    print("|---|---|---|---|---|---|---|")
    for n, u, lg in rows:
        print(f"| {n} | {u['particle_steps_per_second']:.3e} | {lg['particle_steps_per_second']:.3e} | "
              f"{u['particle_steps_per_second'] / lg['particle_steps_per_second']:.2f} | "
              f"{u['contacts_per_particle']:.3f} / {lg['contacts_per_particle']:.3f} | "
              f"{u['wall_contacts']:.0f} / {lg['wall_contacts']:.0f} | {u['rss'] / n:.0f} / {lg['rss'] / n:.0f} |")


if __name__ == "__main__":
    main()
