#!/usr/bin/python3
"""How far the seams' turn mends a file's normals flipped on one half, as noise grows (issue 26:
"input normals that contradict the points are repaired"). For each noise level (in median
spacings), the mesh's vertices moved by Gaussian noise, with their faces' area-weighted normals
as the file's, once as they are and once flipped on the half above the median x; `pss project`
at its defaults; the normals it turned and its normals against the truth's.

Usage: flipped_normals.py --pss PSS MESH [MESH ...] [--noise 0 0.5 1 2] [--seed 3] [--ranks N] [--json OUT]
MESH: a PLY with faces or an OFF (cloud_quality.py's readers), e.g. data/bun_zipper.ply.
--ranks N runs `mpirun -np N pss project` (tile by tile) instead of one process (in core).
"""
import argparse, json, os, subprocess, sys, tempfile
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cloud_quality import read_mesh


def vertex_normals(v, tris):
    n = np.zeros_like(v)
    face = np.cross(v[tris[:, 1]] - v[tris[:, 0]], v[tris[:, 2]] - v[tris[:, 0]])
    for k in range(3): np.add.at(n, tris[:, k], face)
    return n


def mesh_truth(mesh):
    """A mesh's vertices that its faces give a normal, with those unit normals."""
    v, tris = read_mesh(mesh)
    n = vertex_normals(v, np.asarray(tris))
    keep = (n * n).sum(1) > 0
    return v[keep], n[keep] / np.linalg.norm(n[keep], axis=1)[:, None]


def median_spacing(v, rng):
    pick = v[rng.choice(len(v), min(len(v), 2000), replace=False)]
    d2 = ((pick[:, None, :] - v[None, :, :]) ** 2).sum(2)
    d2.sort(1)
    return float(np.median(np.sqrt(d2[:, 1])))


def pss_command(pss, ranks):
    """pss in one process, or over `ranks` MPI processes (tile by tile)."""
    return (['mpirun', '--oversubscribe', '--bind-to', 'none', '-np', str(ranks)] if ranks > 1 else []) + [pss]


def projected_normals(ply):
    with open(ply, 'rb') as f:
        names, count = [], 0
        while (line := f.readline().strip()) != b'end_header':
            w = line.split()
            if w[:2] == [b'element', b'vertex']: count = int(w[2])
            types = {b'float': '<f4', b'double': '<f8', b'int': '<i4'}
            if w[0] == b'property': names.append((w[2].decode(), types[w[1]]))
        rows = np.frombuffer(f.read(count * np.dtype(names).itemsize), np.dtype(names))
    return np.stack([rows['nx'], rows['ny'], rows['nz']], 1).astype(float)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('meshes', nargs='+'); ap.add_argument('--pss', required=True)
    ap.add_argument('--noise', type=float, nargs='+', default=[0, 0.5, 1, 2])
    ap.add_argument('--seed', type=int, default=3)
    ap.add_argument('--ranks', type=int, default=1)
    ap.add_argument('--json')
    a = ap.parse_args()
    rng = np.random.default_rng(a.seed)
    rows = []
    print(f"{'mesh':<20} {'noise':>6} {'flipped':>8} {'turned':>8} {'against %':>10}")
    with tempfile.TemporaryDirectory() as tmp:
        for mesh in a.meshes:
            v, n = mesh_truth(mesh)
            spacing = median_spacing(v, rng)
            for noise in a.noise:
                moved = v + rng.normal(size=v.shape) * noise * spacing
                for flipped in (False, True):
                    given = np.where((v[:, 0] > np.median(v[:, 0]))[:, None] & flipped, -n, n)
                    cloud, out, stats = (os.path.join(tmp, x) for x in ('c.xyz', 'o.ply', 's.json'))
                    np.savetxt(cloud, np.hstack([moved, given]), fmt='%.7g')
                    subprocess.run(pss_command(a.pss, a.ranks) + ['project', cloud, '-o', out, '--stats', stats], check=True,
                                   capture_output=True)
                    turned = json.load(open(stats))['normals_turned']
                    against = float(((projected_normals(out) * n).sum(1) < 0).mean() * 100)
                    rows.append({'mesh': os.path.basename(mesh), 'noise_spacings': noise, 'flipped_half': flipped,
                                 'turned': turned, 'against_percent': against})
                    print(f"{os.path.basename(mesh):<20} {noise:>6g} {str(flipped):>8} {turned:>8} {against:>10.1f}")
    if a.json:
        json.dump({'seed': a.seed, 'ranks': a.ranks, 'rows': rows}, open(a.json, 'w'), indent=1)


if __name__ == '__main__':
    main()
