#!/usr/bin/python3
"""Time and peak resident memory of each phase of `pss project` against the cloud's size
(issue 28): the cost curve, bytes per point and whole-process throughput.

Usage (Debian python3 with python3-numpy):
  project_memory.py --pss PSS [--points 100000,1000000] [--noise 0.003] [--threads 0]
                    [--out project_memory.json]

For each size, a noisy torus (bench/noisy_torus.py) written as binary PLY, then
`pss project cloud.ply -o out.ply --stats` at its defaults, timed whole by this script. From
--stats: each phase's seconds and peak resident bytes (the kernel's high-water mark, reset
when the phase begins) and the run's peak ("total"). Prints a markdown table per size and
one of the curve; writes JSON.
"""
import argparse, json, os, subprocess, sys, tempfile, time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from noisy_torus import torus_cloud, write_ply

MIB = 1 << 20


def run(pss, cloud, n, threads, tmp):
    stats = os.path.join(tmp, "stats.json")
    command = [pss, "project", cloud, "-o", os.path.join(tmp, "out.ply"), "--progress", "never", "--stats", stats]
    if threads:
        command += ["--threads", str(threads)]
    start = time.perf_counter()
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    seconds = time.perf_counter() - start
    s = json.load(open(stats))
    peak = s["peak_bytes"]
    return {"points": n, "process_seconds": seconds, "points_per_second": n / seconds,
            "peak_bytes": peak["total"], "bytes_per_point": peak["total"] / n,
            "phases": {p: {"seconds": t, "peak_bytes": peak.get(p)} for p, t in s["seconds"].items()},
            "threads": s.get("threads")}


def main():
    a = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    a.add_argument("--pss", required=True)
    a.add_argument("--points", default="100000,1000000")
    a.add_argument("--noise", type=float, default=0.003)
    a.add_argument("--threads", type=int, default=0, help="0: pss's default (every core)")
    a.add_argument("--out", default="project_memory.json")
    o = a.parse_args()
    results = []
    for n in [int(x) for x in o.points.split(",")]:
        with tempfile.TemporaryDirectory() as tmp:
            cloud = os.path.join(tmp, "torus.ply")
            write_ply(cloud, torus_cloud(n, o.noise))
            r = run(o.pss, cloud, n, o.threads, tmp)
        results.append(r)
        print("\n%d points, %s threads: %.2f s whole process, %.0f points/s, peak %.0f MiB (%.0f bytes/point)\n" %
              (n, r["threads"], r["process_seconds"], r["points_per_second"], r["peak_bytes"] / MIB,
               r["bytes_per_point"]))
        print("| phase | s | peak MiB |\n|---|---|---|")
        for p, v in r["phases"].items():
            peak = "" if v["peak_bytes"] is None else "%.0f" % (v["peak_bytes"] / MIB)
            print("| %s | %.2f | %s |" % (p, v["seconds"], peak))
    print("\n| points | s | points/s | peak MiB | bytes/point |\n|---|---|---|---|---|")
    for r in results:
        print("| %d | %.2f | %.0f | %.0f | %.0f |" % (r["points"], r["process_seconds"], r["points_per_second"],
                                                    r["peak_bytes"] / MIB, r["bytes_per_point"]))
    json.dump({"noise_R": o.noise, "runs": results}, open(o.out, "w"), indent=2)


if __name__ == "__main__":
    main()
