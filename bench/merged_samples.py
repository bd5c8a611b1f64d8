#!/usr/bin/python3
"""What a noisy cloud's fits need of its samples (issue 26): where the noise widens h, each
support holds thousands of samples, and the fits' time grows with them. This measures, on a
noisy torus (bench/noisy_torus.py) at one h, the distance to the true torus of `pss project`'s
points, and the time, for the samples:
  all         every point (today);
  random      a random share of them;
  merged      one sample per cell of side CELL·h, at the mean of the points in it;
  merged+mass the same, each with the weight of the points it stands for: written as that
              many coincident copies, so its time is that of all points, and its error what a
              fit that weighs a merged sample by its count would give at the time of `merged`.
The errors are the projected samples' (each variant projects its own samples).

Usage: merged_samples.py PSS [--points 300000] [--noise 0.03] [--h 0.0867] [--share 0.2]
                             [--cell 0.5] [--json OUT.json]
"""
import argparse, json, os, subprocess, sys, tempfile, time
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from noisy_torus import R, r, torus_cloud, write_ply


def read_projected(path):
    b = open(path, 'rb').read()
    end = b.index(b'end_header') + 11
    head = b[:end].decode()
    n = int(head.split('element vertex ')[1].split()[0])
    kinds = {'float': '<f4', 'double': '<f8', 'int': '<i4', 'uchar': 'u1'}
    props = [l.split() for l in head.splitlines() if l.startswith('property')]
    rec = np.frombuffer(b, np.dtype([(q[2], kinds[q[1]]) for q in props]), n, end)
    return np.stack([rec['x'], rec['y'], rec['z']], 1).astype(float), rec['status']


def torus_distance(p):
    return np.hypot(np.hypot(p[:, 0], p[:, 1]) - R, p[:, 2]) - r


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('pss')
    ap.add_argument('--points', type=int, default=300000)
    ap.add_argument('--noise', type=float, default=0.03, help='sigma over R')
    ap.add_argument('--h', type=float, default=0.0867, help="one h for all (pss info's for the default torus)")
    ap.add_argument('--share', type=float, default=0.2)
    ap.add_argument('--cell', type=float, default=0.5, help='the cells of the merged samples, in h')
    ap.add_argument('--json')
    a = ap.parse_args()
    p = torus_cloud(a.points, a.noise)
    cell = a.cell * a.h
    key = np.floor(p / cell).astype(np.int64)
    _, inverse, count = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    merged = np.zeros((len(count), 3))
    np.add.at(merged, inverse.ravel(), p)
    merged /= count[:, None]
    variants = [('all', p), (f'random {a.share:g}', p[np.random.default_rng(3).random(len(p)) < a.share]),
                (f'merged {a.cell:g}h', merged), (f'merged {a.cell:g}h + mass', np.repeat(merged, count, axis=0))]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        cloud, out = os.path.join(tmp, 'cloud.ply'), os.path.join(tmp, 'out.ply')
        for name, samples in variants:
            write_ply(cloud, samples)
            start = time.perf_counter()
            subprocess.run([a.pss, 'project', cloud, '-o', out, '--h', str(a.h), '--outliers', 'keep'], check=True,
                           capture_output=True)
            seconds = time.perf_counter() - start
            q, status = read_projected(out)
            e = np.abs(torus_distance(q[status == 0]))
            rows.append({'samples': name, 'count': len(samples), 'unique': len(np.unique(samples, axis=0)),
                         'seconds': seconds, 'rms': float(np.sqrt((e ** 2).mean())), 'p99': float(np.percentile(e, 99))})
            x = rows[-1]
            print(f"{name:22s} {x['count']:8d} samples ({x['unique']:7d} distinct) {seconds:7.1f} s  "
                  f"rms {x['rms'] / R:.5f} R  p99 {x['p99'] / R:.5f} R", flush=True)
    if a.json:
        json.dump({'points': a.points, 'noise': a.noise, 'h': a.h, 'rows': rows}, open(a.json, 'w'), indent=1)


if __name__ == '__main__':
    main()
