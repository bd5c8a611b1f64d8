"""The binary PLY meshes `pss mesh` writes, read for the benchmarks: positions (float or,
for a georeferenced cloud, double), vertex normals and triangles."""
import numpy as np


def read_mesh_ply(path):
    data = open(path, "rb").read()
    end = data.index(b"end_header\n") + 11
    header = data[:end].decode()
    nv = int(header.split("element vertex ")[1].split()[0])
    nf = int(header.split("element face ")[1].split()[0])
    vt = np.dtype([("p", "<f8" if "double x" in header else "<f4", 3), ("n", "<f4", 3)])
    v = np.frombuffer(data, vt, nv, end)
    f = np.frombuffer(data, np.dtype([("c", "u1"), ("i", "<i4", 3)]), nf, end + nv * vt.itemsize)
    return v["p"].astype(float), v["n"].astype(float), f["i"]
