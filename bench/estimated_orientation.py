#!/usr/bin/python3
"""How well `pss project` orients a cloud's estimated normals as noise grows (issue 26: the
orientation's tree turns a part inward across a thin part that noise merges into one sheet;
points/visibility.hpp). For each noise level (in median spacings) and seed, the mesh's vertices
moved by Gaussian noise, written without normals; `pss project` at its defaults; the share of its
normals against the mesh's faces' (area-weighted, at each vertex).

Usage: estimated_orientation.py --pss PSS MESH [MESH ...] [--noise 0 0.5 0.75 1] [--seeds 1 2 4 5]
                                [--ranks N] [--json OUT]
MESH: a PLY with faces or an OFF (cloud_quality.py's readers), e.g. ../shared/data/dragon_21790.ply.
--ranks N runs `mpirun -np N pss project` (tile by tile) instead of one process (in core).
"""
import argparse, json, os, subprocess, sys, tempfile
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from flipped_normals import median_spacing, mesh_truth, projected_normals, pss_command


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('meshes', nargs='+'); ap.add_argument('--pss', required=True)
    ap.add_argument('--noise', type=float, nargs='+', default=[0, 0.5, 0.75, 1])
    ap.add_argument('--seeds', type=int, nargs='+', default=[1, 2, 4, 5])
    ap.add_argument('--ranks', type=int, default=1)
    ap.add_argument('--json')
    a = ap.parse_args()
    rows = []
    print(f"{'mesh':<20} {'noise':>6} {'seed':>5} {'against %':>10}")
    with tempfile.TemporaryDirectory() as tmp:
        for mesh in a.meshes:
            v, n = mesh_truth(mesh)
            spacing = median_spacing(v, np.random.default_rng(0))
            for noise in a.noise:
                for seed in a.seeds:
                    moved = v + np.random.default_rng(seed).normal(size=v.shape) * noise * spacing
                    cloud, out = os.path.join(tmp, 'c.xyz'), os.path.join(tmp, 'o.ply')
                    np.savetxt(cloud, moved, fmt='%.7g')
                    subprocess.run(pss_command(a.pss, a.ranks) + ['project', cloud, '-o', out], check=True, capture_output=True)
                    against = float(((projected_normals(out) * n).sum(1) < 0).mean() * 100)
                    rows.append({'mesh': os.path.basename(mesh), 'noise_spacings': noise, 'seed': seed,
                                 'against_percent': against})
                    print(f"{os.path.basename(mesh):<20} {noise:>6g} {seed:>5} {against:>10.1f}", flush=True)
    if a.json:
        json.dump({'ranks': a.ranks, 'rows': rows}, open(a.json, 'w'), indent=1)


if __name__ == '__main__':
    main()
