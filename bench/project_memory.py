#!/usr/bin/python3
"""Time and peak resident memory of each phase of `pss project` against the cloud's size
(issue 28): the cost curve, bytes per point and whole-process throughput.

Usage (Debian python3 with python3-numpy):
  project_memory.py --pss PSS [--points 100000,1000000] [--noise 0.003] [--threads 0]
                    [--memory 64M,512M] [--ranks 2,3] [--out project_memory.json]

For each size, a noisy torus (bench/noisy_torus.py) written as binary PLY, then
`pss project cloud.ply -o out.ply --stats` at its defaults, timed whole by this script, and
once more with each --memory budget (tile by tile where the cloud needs more). From --stats:
each phase's seconds and peak resident bytes (the kernel's high-water mark, reset when the
phase begins) and the run's peak ("total"). A budget's output is compared with the in-core
one: the farthest a point lies from its in-core projection, how many statuses differ and how
many normals face the other way. With --ranks, each budget again under `mpirun -np N` (pss
built with Open MPI; the ranks on this machine share its cores): its time, the points each
rank projected, and whether its output is byte for byte the one process's. Prints a markdown
table per run and one of the curve; writes JSON.
"""
import argparse, json, os, subprocess, sys, tempfile, time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from noisy_torus import torus_cloud, write_ply

MIB = 1 << 20


def read_projected(path):
    """x y z nx ny nz (float) and status (int) of pss project's binary PLY of a float cloud."""
    data = open(path, "rb").read()
    body = data[data.index(b"end_header\n") + len(b"end_header\n"):]
    rows = np.frombuffer(body, dtype=np.dtype([("p", "<f4", 3), ("n", "<f4", 3), ("status", "<i4")]))
    return rows["p"].astype(np.float64), rows["n"].astype(np.float64), rows["status"]


def compare(core, tiled):
    (p, n, s), (q, m, t) = read_projected(core), read_projected(tiled)
    return {"farthest": float(np.max(np.linalg.norm(p - q, axis=1))), "statuses_differ": int(np.sum(s != t)),
            "normals_facing_apart": int(np.sum(np.sum(n * m, axis=1) < 0))}


def run(pss, cloud, n, threads, tmp, memory=None, ranks=1):
    stats = os.path.join(tmp, "stats.json")
    out = os.path.join(tmp, "out-%s-%d.ply" % (memory or "core", ranks))
    command = [pss, "project", cloud, "-o", out, "--progress", "never", "--stats", stats]
    if ranks > 1:
        command = ["mpirun", "--oversubscribe", "-np", str(ranks)] + command
    if threads:
        command += ["--threads", str(threads)]
    if memory:
        command += ["--memory", memory]
    start = time.perf_counter()
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    seconds = time.perf_counter() - start
    s = json.load(open(stats))
    peak = s["peak_bytes"]
    return {"points": n, "memory": memory or "in core", "tiled": s["memory"]["tiled"], "ranks": ranks,
            "points_per_rank": s.get("points_per_rank"),
            "points_per_tile": s["memory"].get("points_per_tile"), "output": out,
            "process_seconds": seconds, "points_per_second": n / seconds,
            "peak_bytes": peak["total"], "bytes_per_point": peak["total"] / n,
            "phases": {p: {"seconds": t, "peak_bytes": peak.get(p)} for p, t in s["seconds"].items()},
            "threads": s.get("threads")}


def main():
    a = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    a.add_argument("--pss", required=True)
    a.add_argument("--points", default="100000,1000000")
    a.add_argument("--noise", type=float, default=0.003)
    a.add_argument("--threads", type=int, default=0, help="0: pss's default (every core)")
    a.add_argument("--memory", default="", help="budgets to run beside in core, such as 64M,512M")
    a.add_argument("--ranks", default="", help="MPI ranks to run each budget on beside one process, such as 2,3")
    a.add_argument("--out", default="project_memory.json")
    o = a.parse_args()
    results = []
    for n in [int(x) for x in o.points.split(",")]:
        with tempfile.TemporaryDirectory() as tmp:
            cloud = os.path.join(tmp, "torus.ply")
            write_ply(cloud, torus_cloud(n, o.noise))
            runs = [run(o.pss, cloud, n, o.threads, tmp)]
            for budget in [b for b in o.memory.split(",") if b]:
                runs.append(run(o.pss, cloud, n, o.threads, tmp, budget))
                runs[-1]["against_in_core"] = compare(runs[0]["output"], runs[-1]["output"])
                one = runs[-1]
                for ranks in [int(r) for r in o.ranks.split(",") if r]:
                    runs.append(run(o.pss, cloud, n, o.threads, tmp, budget, ranks))
                    runs[-1]["same_bytes_as_one_process"] = open(one["output"], "rb").read() == open(
                        runs[-1]["output"], "rb").read()
        for r in runs:
            results.append(r)
            print("\n%d points, %s (%s), %s threads: %.2f s whole process, %.0f points/s, peak %.0f MiB "
                  "(%.0f bytes/point)" % (n, r["memory"], "tiles of at most %d points" % r["points_per_tile"]
                                          if r["tiled"] else "in core", r["threads"],
                                          r["process_seconds"], r["points_per_second"], r["peak_bytes"] / MIB,
                                          r["bytes_per_point"]))
            if "against_in_core" in r:
                print("against in core: %s" % r["against_in_core"])
            if r["ranks"] > 1:
                print("%d ranks, points per rank %s, the same bytes as one process: %s"
                      % (r["ranks"], r["points_per_rank"], r["same_bytes_as_one_process"]))
            print("\n| phase | s | peak MiB |\n|---|---|---|")
            for p, v in r["phases"].items():
                peak = "" if v["peak_bytes"] is None else "%.0f" % (v["peak_bytes"] / MIB)
                print("| %s | %.2f | %s |" % (p, v["seconds"], peak))
    print("\n| points | run | ranks | s | points/s | peak MiB (rank 0) | bytes/point |\n|---|---|---|---|---|---|---|")
    for r in results:
        print("| %d | %s | %d | %.2f | %.0f | %.0f | %.0f |" % (r["points"], r["memory"], r["ranks"],
                                                              r["process_seconds"], r["points_per_second"],
                                                              r["peak_bytes"] / MIB, r["bytes_per_point"]))
    json.dump({"noise_R": o.noise, "runs": results}, open(o.out, "w"), indent=2)


if __name__ == "__main__":
    main()
