#!/usr/bin/python3
"""A cloud whose sampling density steps F:1: the vertices of a mesh, those on one side of the
median along an axis kept at 1/F (issue 26's held-out "one half kept at 1/8 density").

Usage: uneven_cloud.py MESH OUT.xyz [--factor 8] [--axis 0|1|2] [--seed 1]
MESH: an OFF, or a PLY with faces (cloud_quality.py's readers). Measure the result against the
mesh it came from: cloud_quality.py --pss PSS --truth MESH --clouds OUT.xyz
"""
import argparse, os, sys
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cloud_quality import read_mesh


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('mesh'); ap.add_argument('out')
    ap.add_argument('--factor', type=float, default=8); ap.add_argument('--axis', type=int, default=0, choices=(0, 1, 2))
    ap.add_argument('--seed', type=int, default=1)
    a = ap.parse_args()
    if not a.factor >= 1: ap.error('--factor must be at least 1')
    v, _ = read_mesh(a.mesh)
    keep = (v[:, a.axis] < np.median(v[:, a.axis])) | (np.random.default_rng(a.seed).random(len(v)) < 1 / a.factor)
    np.savetxt(a.out, v[keep], fmt='%.7g')
    print(f'wrote {a.out}: {keep.sum()} of {len(v)} vertices, the half above the median along axis {a.axis} at 1/{a.factor:g}')


if __name__ == '__main__':
    main()
