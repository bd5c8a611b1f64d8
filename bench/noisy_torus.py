"""The noisy torus of the benchmarks (issues 27 and 28): R = 1, r = 0.35, sampled uniformly by
area, each point moved along the normal by Gaussian noise of `noise`·R; and a binary PLY of
points."""
import numpy as np

R, r = 1.0, 0.35


def torus_cloud(n, noise, seed=1):
    rng = np.random.default_rng(seed)
    out = []
    while sum(len(o) for o in out) < n:  # area element ∝ R + r cos v: rejection for uniform density
        u, v, w = rng.random((3, 2 * n))
        u, v = 2 * np.pi * u, 2 * np.pi * v
        keep = w * (R + r) < R + r * np.cos(v)
        u, v = u[keep], v[keep]
        normal = np.stack([np.cos(v) * np.cos(u), np.cos(v) * np.sin(u), np.sin(v)], 1)
        centre = np.stack([R * np.cos(u), R * np.sin(u), 0 * u], 1)
        out.append(centre + (r + noise * R * rng.normal(size=len(u)))[:, None] * normal)
    return np.concatenate(out)[:n]


def write_ply(path, p):
    with open(path, "wb") as f:
        f.write(b"ply\nformat binary_little_endian 1.0\nelement vertex %d\n" % len(p))
        f.write(b"property float x\nproperty float y\nproperty float z\nend_header\n")
        f.write(p.astype("<f4").tobytes())
