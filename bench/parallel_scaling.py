#!/usr/bin/python3
"""MPI scaling of the dense-bed benchmark, for both summations of the engine.

Runs `mpiexec -n K bench_parallel_bed bed.data STEPS --summation S` for each rank count K in
--ranks and each summation S in --summations, alternating all of them within each of
--repeat rounds, and reports the best run of each: speedup and parallel efficiency against
one rank of the same summation, the cost of the deterministic summation over the fast one on
the same rank count, the share of time in communication and the load imbalance. With
--baseline BUILD, the bench_parallel_bed of another build (an earlier version of Upgrain,
which may print other keys) runs in the same rounds, so that its figures are measured beside
these. The load average is read before and after every run; the spread of the repeats shows
how noisy the machine was. Creates the settled bed with `bench_dense_bed settle N` if it is
missing.

    python3 bench/parallel_scaling.py --build build --size 50000 --steps 1000 --repeat 3
"""
import argparse
import os
import pathlib
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent


def loadavg():
    return float(pathlib.Path("/proc/loadavg").read_text().split()[0])


def parse(line):
    words = line.split()
    assert words[0] == "parallel", line
    out = {}
    for k, v in zip(words[1::2], words[2::2]):
        try:
            out[k] = float(v)
        except ValueError:
            out[k] = v
    return out


def mpiexec(args, k):
    cmd = ["mpiexec", "-n", str(k), "--bind-to", args.bind]
    if os.geteuid() == 0:
        cmd.append("--allow-run-as-root")
    if k > (os.cpu_count() or 1):
        cmd.append("--oversubscribe")
    return cmd


def run_once(args, bench, bed, k, extra):
    cmd = mpiexec(args, k) + [str(bench), str(bed), str(args.steps)] + extra
    if k in args.blocks:
        cmd += ["--blocks", args.blocks[k]]
    before = loadavg()
    r = subprocess.run(cmd, capture_output=True, text=True, check=False)
    after = loadavg()
    if r.returncode != 0:
        sys.exit(f"failed: {' '.join(cmd)}\n{r.stdout}\n{r.stderr}")
    line = next(l for l in r.stdout.splitlines() if l.startswith("parallel "))
    result = parse(line)
    result["load_before"], result["load_after"] = before, after
    result["rank_lines"] = [l for l in r.stderr.splitlines() if l.startswith("rank ")]
    return result, " ".join(cmd)


def running():
    """Runnable tasks now (this script included), from /proc/stat."""
    for line in pathlib.Path("/proc/stat").read_text().splitlines():
        if line.startswith("procs_running"):
            return int(line.split()[1])
    return 0


def wait_idle(limit):
    """Until no other task has wanted a CPU for 5 checks in a row (2 s apart), or `limit` s."""
    start, quiet = time.time(), 0
    while quiet < 5 and time.time() - start < limit:
        quiet = quiet + 1 if running() <= 1 else 0
        time.sleep(2)
    return time.time() - start


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=str(ROOT / "build"), help="build folder with bench/")
    ap.add_argument("--baseline", help="another build folder whose bench_parallel_bed runs beside (no --summation)")
    ap.add_argument("--size", type=int, default=50000, help="spheres in the bed")
    ap.add_argument("--bed", help="bed file (default bench/results/bed_SIZE.data)")
    ap.add_argument("--steps", type=int, default=1000)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--summations", nargs="+", default=["deterministic", "fast"],
                    choices=["deterministic", "fast"])
    ap.add_argument("--bind", default="none", help="mpiexec --bind-to (none, core)")
    ap.add_argument("--blocks", nargs="*", default=[], metavar="K:PXxPYxPZ",
                    help="explicit blocks for a rank count, e.g. 2:2x1x1 (default: the decomposition rule)")
    ap.add_argument("--wait-idle", type=float, default=0.0, metavar="SECONDS",
                    help="before each run, wait up to SECONDS until no other task is runnable for 10 s")
    ap.add_argument("--verbose", action="store_true", help="print every run and its per-rank lines")
    args = ap.parse_args()
    args.blocks = {int(b.split(":")[0]): b.split(":")[1] for b in args.blocks}

    build = pathlib.Path(args.build)
    bench = build / "bench" / "bench_parallel_bed"
    bed = pathlib.Path(args.bed) if args.bed else ROOT / "bench" / "results" / f"bed_{args.size}.data"
    if not bench.exists():
        sys.exit(f"{bench} not built (ninja -C {build} bench_parallel_bed)")
    if not bed.exists():
        bed.parent.mkdir(parents=True, exist_ok=True)
        print(f"creating {bed} (bench_dense_bed settle {args.size}) ...", flush=True)
        subprocess.run([str(build / "bench" / "bench_dense_bed"), "settle", str(args.size), str(bed)], check=True)
    os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
    os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")

    # Each configuration: (label, bench binary, extra arguments).
    configs = [(s, bench, ["--summation", s]) for s in args.summations]
    if args.baseline:
        configs.append(("baseline", pathlib.Path(args.baseline) / "bench" / "bench_parallel_bed", []))
    runs = {(c[0], k): [] for c in configs for k in args.ranks}
    commands = {}
    for rep in range(args.repeat):
        for label, binary, extra in configs:
            for k in args.ranks:
                if args.wait_idle > 0:
                    wait_idle(args.wait_idle)
                res, commands[(label, k)] = run_once(args, binary, bed, k, extra)
                runs[(label, k)].append(res)
                print(f"round {rep + 1} {label} ranks {k}: {res['seconds']:.3f} s, comm {100 * res['comm_share']:.1f} %, "
                      f"load {res['load_before']:.2f} -> {res['load_after']:.2f}", flush=True)
                if args.verbose:
                    for l in res["rank_lines"]:
                        print("   ", l)

    best = {key: min(v, key=lambda r: r["seconds"]) for key, v in runs.items()}
    print()
    for key, cmd in commands.items():
        print(f"command ({key[0]}, K = {key[1]}): {cmd}")
    any_run = next(iter(best.values()))
    print(f"bed {bed}: {int(any_run['particles'])} spheres, {args.steps} steps per run, best of {args.repeat}, "
          f"mpiexec --bind-to {args.bind}")
    for label, _, _ in configs:
        hashes = {r["state_hash"] for k in args.ranks for r in runs[(label, k)]}
        print(f"{label}: final states bitwise identical on all rank counts: "
              + ("yes" if len(hashes) == 1 else f"no ({len(hashes)} states)"))
    loads = [r[x] for v in runs.values() for r in v for x in ("load_before", "load_after")]
    print(f"load average (1 min) during the runs: {min(loads):.2f} - {max(loads):.2f} on {os.cpu_count()} cores")
    print()
    print("| summation | ranks | blocks | best s | spread | particle-steps/s | speedup | efficiency | comm share "
          "(reduction / ghost refresh) | imbalance owned / pairs / compute | rebuilds |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    k0 = args.ranks[0]
    for label, _, _ in configs:
        t0 = best[(label, k0)]["seconds"]
        for k in args.ranks:
            b = best[(label, k)]
            times = [r["seconds"] for r in runs[(label, k)]]
            spread = max(times) / min(times) - 1.0
            speedup = t0 / b["seconds"]
            print(f"| {label} | {k} | {b['blocks']} | {b['seconds']:.3f} | {100 * spread:.0f} % | "
                  f"{b['particle_steps_per_second']:.3e} | {speedup:.2f} | {100 * speedup / (k / k0):.0f} % | "
                  f"{100 * b['comm_share']:.1f} % ({100 * b['reduction_share']:.1f} / "
                  f"{100 * b['ghost_refresh_share']:.1f}) | {b['owned_imbalance']:.3f} / {b['pairs_imbalance']:.3f} / "
                  f"{b['compute_imbalance']:.3f} | {int(b['rebuilds'])} |")
    print()
    if "deterministic" in args.summations and "fast" in args.summations:
        for k in args.ranks:
            ratio = best[("deterministic", k)]["seconds"] / best[("fast", k)]["seconds"]
            print(f"{k} rank(s): deterministic / fast = {ratio:.3f}")
    if args.baseline:
        base = [r for r in runs[("baseline", 1)] if "serial_seconds" in r] if 1 in args.ranks else []
        if base:
            s = min(r["serial_seconds"] for r in base)
            print(f"baseline serial engine (same rounds), best: {s:.3f} s")
            for label in args.summations:
                for k in args.ranks:
                    print(f"{label} on {k} rank(s) / baseline serial engine = {best[(label, k)]['seconds'] / s:.3f}")
    for key in best:
        print(f"per rank, best run of {key[0]}, K = {key[1]}:")
        for l in best[key]["rank_lines"]:
            print("   ", l)


if __name__ == "__main__":
    main()
