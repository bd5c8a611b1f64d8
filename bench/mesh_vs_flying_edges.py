#!/usr/bin/python3
"""`pss mesh` of a volume beside VTK's Flying Edges, in one run, on CT-like volumes whose
surface is known exactly, and on the shipped CT scans (issue 27's goal).

Usage (Debian python3 with python3-numpy, python3-vtk9):
  mesh_vs_flying_edges.py --pss PSS [--noise 0,0.02,0.05] [--data DIR] [--out mesh_vs_flying_edges.json]

The analytic volumes: a ball (R = 20 voxels) and a torus (R = 18, r = 7) in a 64³ float32
volume, each a CT-like step: 100 inside, 0 outside, a logistic edge 100/(1 + exp(d/0.4))
(10-90 % over 1.8 voxels, as a CT's blur and partial volume make it) of the signed distance d
to the true surface, so that its iso-value 50 lies exactly on it; plus Gaussian noise of
`noise` times the contrast. pss: `pss mesh VOLUME --iso 50` with default flags, its process
timed whole (reading, gradients, mesh, writing); Flying Edges: vtkFlyingEdges3D at 50 with
its gradient normals, the filter timed alone. Each runs in a process of its own (peak
memory: its maximum resident set; VTK's includes Python's and NumPy's, about 110 MB). For each mesh: triangles, the
distance of its vertices to the true surface (mean and largest, voxels), the angle of its
normals to the true normals (mean, degrees), and whether it is closed and manifold, with its
components. The shipped scans (engine, tooth) have no truth: time, triangles, shape, and
the mean distance from pss's vertices to Flying Edges' surface. Prints markdown, writes JSON.
"""
import argparse, gzip, json, os, subprocess, sys, tempfile
import numpy as np

from mesh_ply import read_mesh_ply

N = 64
BALL = {"centre": np.array([31.7, 32.2, 31.4]), "R": 20.0}
TORUS = {"centre": np.array([32.3, 31.6, 31.8]), "R": 18.0, "r": 7.0}


def grid():
    z, y, x = np.meshgrid(*(np.arange(N, dtype=float),) * 3, indexing="ij")
    return np.stack([x, y, z], -1)


def ball_distance(p):
    d = p - BALL["centre"]
    length = np.linalg.norm(d, axis=-1)
    return length - BALL["R"], d / length[..., None]


def torus_distance(p):
    d = p - TORUS["centre"]
    rho = np.hypot(d[..., 0], d[..., 1])
    ring = np.stack([TORUS["R"] * d[..., 0] / rho, TORUS["R"] * d[..., 1] / rho, 0 * rho], -1)
    e = d - ring
    length = np.linalg.norm(e, axis=-1)
    return length - TORUS["r"], e / length[..., None]


def ct_step(distance, noise, seed=1):
    d = distance(grid())[0]
    values = 100.0 / (1.0 + np.exp(np.clip(d / 0.4, -50, 50)))
    return (values + np.random.default_rng(seed).normal(0, 100 * noise, values.shape)).astype(np.float32)


def errors(distance, vertices, normals):
    d, truth = distance(vertices)
    n = normals / np.linalg.norm(normals, axis=1, keepdims=True)
    cosine = (n * truth).sum(1)
    return {"mean_distance": float(np.abs(d).mean()), "max_distance": float(np.abs(d).max()),
            "mean_normal_deg": float(np.degrees(np.arccos(np.clip(np.abs(cosine), 0, 1))).mean()),
            "normals_outward_pct": float(100 * np.mean(cosine > 0))}


def shape(vertices, triangles):
    edges = np.sort(np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]]), axis=1)
    _, uses = np.unique(edges, axis=0, return_counts=True)
    # Components by union-find over the triangles' vertices.
    parent = np.arange(len(vertices))

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i
    for a, b, c in triangles.tolist():
        ra, rb, rc = find(a), find(b), find(c)
        parent[rb] = ra
        parent[find(rc)] = ra
    used = np.unique(triangles)
    return {"triangles": int(len(triangles)), "closed": bool(np.all(uses == 2)),
            "edge_manifold": bool(np.all(uses <= 2)), "boundary_edges": int(np.sum(uses == 1)),
            "components": int(len({find(i) for i in used.tolist()})),
            "euler_characteristic": int(len(used) - len(uses) + len(triangles))}


# A process of its own: VTK's Flying Edges at the iso-value, the filter timed alone.
FLYING_EDGES = r'''
import json, sys, time
import numpy as np, vtk
from vtk.util import numpy_support
values, out, iso = np.load(sys.argv[1]), sys.argv[2], float(sys.argv[3])
spacing = [float(s) for s in sys.argv[4].split(",")]
image = vtk.vtkImageData()
image.SetDimensions(values.shape[2], values.shape[1], values.shape[0])
image.SetSpacing(*spacing)
image.GetPointData().SetScalars(numpy_support.numpy_to_vtk(values.ravel(), deep=1))
start = time.perf_counter()
fe = vtk.vtkFlyingEdges3D()
fe.SetInputData(image)
fe.SetValue(0, iso)
fe.ComputeNormalsOn()
fe.Update()
seconds = time.perf_counter() - start
mesh = fe.GetOutput()
np.save(out + ".v.npy", numpy_support.vtk_to_numpy(mesh.GetPoints().GetData()).astype(float))
np.save(out + ".n.npy", numpy_support.vtk_to_numpy(mesh.GetPointData().GetNormals()).astype(float))
np.save(out + ".t.npy", numpy_support.vtk_to_numpy(mesh.GetPolys().GetConnectivityArray()).reshape(-1, 3))
json.dump({"seconds": seconds}, open(out + ".json", "w"))
'''

# A process that runs a command and reports its time and peak memory. (A child's own
# maximum resident set counts its parent's at the fork: the command is this small
# process's child, not the benchmark's.)
PEAK = "import resource, subprocess, sys, time; t = time.perf_counter(); r = subprocess.run(sys.argv[1:]); " \
       "print(time.perf_counter() - t, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024); sys.exit(r.returncode)"


def run_pss(pss, args, tmp):
    out = os.path.join(tmp, "pss.ply")
    done = subprocess.run([sys.executable, "-c", PEAK, pss, "mesh", *args, "-o", out, "--progress", "never",
                           "--stats", os.path.join(tmp, "pss.json")], capture_output=True, text=True)
    if done.returncode:
        sys.exit("pss mesh failed: " + done.stderr)
    seconds, peak = (float(x) for x in done.stdout.split()[-2:])
    v, n, t = read_mesh_ply(out)
    return v, n, t, {"seconds": seconds, "peak_memory_mb": peak}


def run_flying_edges(values, iso, spacing, tmp):
    base = os.path.join(tmp, "fe")
    np.save(base + ".npy", values)
    done = subprocess.run([sys.executable, "-c", PEAK, sys.executable, "-c", FLYING_EDGES, base + ".npy", base,
                           str(iso), spacing], capture_output=True, text=True)
    if done.returncode:
        sys.exit("Flying Edges failed: " + done.stderr)
    timing = {**json.load(open(base + ".json")), "peak_memory_mb": float(done.stdout.split()[-1])}
    return np.load(base + ".v.npy"), np.load(base + ".n.npy"), np.load(base + ".t.npy").astype(np.int64), timing


def uint8_voxels(path):
    """A raw file's bytes, or a NRRD's (raw or gzip) after its header."""
    data = open(path, "rb").read()
    if path.endswith(".nrrd"):
        header, data = data.split(b"\n\n", 1)
        if b"encoding: gzip" in header:
            data = gzip.decompress(data)
    return np.frombuffer(data, np.uint8)


def nearest_surface_distance(points, vertices, triangles):
    """Mean distance from points to a triangle mesh, by its vertices and triangle centroids
    (dense meshes: within a fraction of a triangle's size)."""
    from scipy.spatial import cKDTree
    samples = np.concatenate([vertices, vertices[triangles].mean(1)])
    return float(cKDTree(samples).query(points)[0].mean())


def main():
    a = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    a.add_argument("--pss", required=True)
    a.add_argument("--noise", default="0,0.02,0.05", help="noise levels, fractions of the contrast")
    a.add_argument("--data", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data"))
    a.add_argument("--out", default="mesh_vs_flying_edges.json")
    o = a.parse_args()
    results = {"analytic": [], "scans": []}
    print("| volume | noise | mesh | time (s) | peak MB | triangles | distance mean / max (voxels) | normal error (deg) "
          "| closed, components, Euler |\n|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for name, distance in (("ball", ball_distance), ("torus", torus_distance)):
            for noise in (float(x) for x in o.noise.split(",")):
                values = ct_step(distance, noise)
                raw = os.path.join(tmp, "v.raw")
                values.tofile(raw)
                v, n, t, timing = run_pss(o.pss, [raw, "--dims", "%dx%dx%d" % (N, N, N), "--type", "float32",
                                                  "--iso", "50"], tmp)
                row = {"volume": name, "noise": noise,
                       "pss": {**timing, **shape(v, t), **errors(distance, v, n)}}
                v, n, t, timing = run_flying_edges(values, 50, "1,1,1", tmp)
                row["flying_edges"] = {**timing, **shape(v, t), **errors(distance, v, n)}
                results["analytic"].append(row)
                for key, label in (("pss", "pss mesh"), ("flying_edges", "Flying Edges")):
                    m = row[key]
                    print("| %s | %.0f %% | %s | %.3f | %.0f | %d | %.4f / %.3f | %.2f | %s, %d, %d |" % (
                        name, 100 * noise, label, m["seconds"], m["peak_memory_mb"], m["triangles"],
                        m["mean_distance"], m["max_distance"], m["mean_normal_deg"], m["closed"], m["components"],
                        m["euler_characteristic"]))
                p, q = row["pss"], row["flying_edges"]
                print("| | | ratio pss / FE | %.1f | | | %.2f | %.2f | |" % (
                    p["seconds"] / q["seconds"], p["mean_distance"] / q["mean_distance"],
                    p["mean_normal_deg"] / q["mean_normal_deg"]))
        scans = [("engine", "engine_256x256x128_uint8.nrrd", [], (256, 256, 128), 75),
                 ("tooth", "tooth_103x94x161_uint8.raw", ["--dims", "103x94x161", "--type", "uint8"], (103, 94, 161), 125)]
        print("\n| scan | iso | mesh | time (s) | peak MB | triangles | closed, boundary edges, components |\n"
              "|---|---|---|---|---|---|---|")
        for name, file, flags, dims, iso in scans:
            path = os.path.join(o.data, file)
            if not os.path.exists(path):
                print("skipped", name, "(no %s)" % path)
                continue
            v, n, t, timing = run_pss(o.pss, [path, *flags, "--iso", str(iso)], tmp)
            row = {"scan": name, "iso": iso, "pss": {**timing, **shape(v, t)}}
            voxels = uint8_voxels(path).reshape(dims[::-1]).astype(np.float32)
            fv, fn, ft, timing = run_flying_edges(voxels, iso, "1,1,1", tmp)
            row["flying_edges"] = {**timing, **shape(fv, ft)}
            row["pss"]["mean_distance_to_flying_edges"] = nearest_surface_distance(v, fv, ft)
            results["scans"].append(row)
            for key, label in (("pss", "pss mesh"), ("flying_edges", "Flying Edges")):
                m = row[key]
                print("| %s | %g | %s | %.2f | %.0f | %d | %s, %d, %d |" % (
                    name, iso, label, m["seconds"], m["peak_memory_mb"], m["triangles"], m["closed"],
                    m["boundary_edges"], m["components"]))
            print("| | | pss's vertices from FE's surface: %.3f voxels (mean) | | | | |" %
                  row["pss"]["mean_distance_to_flying_edges"])
    json.dump(results, open(o.out, "w"), indent=1)
    print("wrote", o.out)


if __name__ == "__main__":
    main()
