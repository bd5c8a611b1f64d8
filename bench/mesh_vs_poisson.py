#!/usr/bin/python3
"""`pss mesh` beside Open3D's screened Poisson reconstruction, in one run, on a noisy torus
whose surface is known exactly (issue 27's goal).

Usage (Debian python3 with python3-numpy, python3-open3d):
  mesh_vs_poisson.py --pss PSS [--points 60000] [--noise 0.003] [--depth 8] [--out mesh_vs_poisson.json]

The cloud: a torus (R = 1, r = 0.35) sampled uniformly by area, each point moved along the
normal by Gaussian noise of `noise`·R. pss: `pss mesh cloud.ply -o mesh.ply` with default flags
(its process timed whole, reading and writing included). Poisson: Open3D's usual path, normals
from the 16 nearest neighbours, oriented by tangent planes (16), create_from_point_cloud_poisson
at `depth`, then its usual density trim (the vertices below the 1 % quantile of density removed);
the reconstruction step timed alone, and the whole (normals included), each in a process of
its own (peak memory: its maximum resident set). For each mesh: vertices and triangles, the
distance of its vertices to the torus (mean and largest, in R), the angle of its vertex normals
to the torus's (mean, degrees; Poisson's from Open3D's compute_vertex_normals), whether it is
closed (every edge in two triangles) and manifold, edge-manifold, vertex-manifold (Open3D's
checks; self-intersecting too with --self-intersection, Open3D's test of all pairs, which
takes hours on a mesh that has none), and its connected components.
For reference, the same measures of `pss project`'s points. Prints a markdown table, writes JSON.
"""
import argparse, json, os, resource, subprocess, sys, tempfile, time
import numpy as np

from mesh_ply import read_mesh_ply
from noisy_torus import R, r, torus_cloud, write_ply


def torus_truth(p):
    """Distance of each point to the torus and the torus's unit normal at its nearest point."""
    rho = np.hypot(p[:, 0], p[:, 1])
    ring = np.stack([R * p[:, 0] / rho, R * p[:, 1] / rho, 0 * rho], 1)
    d = p - ring
    length = np.linalg.norm(d, axis=1)
    return np.abs(length - r), d / length[:, None]


def errors(points, normals):
    distance, truth = torus_truth(points.astype(float))
    out = {"mean_distance": float(distance.mean()), "max_distance": float(distance.max())}
    if normals is not None:
        n = normals / np.linalg.norm(normals, axis=1, keepdims=True)
        out["mean_normal_deg"] = float(np.degrees(np.arccos(np.clip(np.abs((n * truth).sum(1)), 0, 1))).mean())
        out["normals_inward_pct"] = float(100 * np.mean((n * truth).sum(1) < 0))
    return out


def open3d_checks(vertices, triangles, self_intersection):
    import open3d as o3d
    m = o3d.geometry.TriangleMesh(o3d.utility.Vector3dVector(vertices), o3d.utility.Vector3iVector(triangles))
    clusters = np.asarray(m.cluster_connected_triangles()[0])
    # Open3D's is_watertight includes its self-intersection test; closed and manifold here.
    out = {"watertight": bool(m.is_edge_manifold(allow_boundary_edges=False)) and bool(m.is_vertex_manifold()),
           "edge_manifold": bool(m.is_edge_manifold()), "vertex_manifold": bool(m.is_vertex_manifold()),
           "components": int(len(np.unique(clusters))) if len(clusters) else 0}
    # Open3D tests every pair of triangles: hours for a few 10⁵.
    out["self_intersecting"] = bool(m.is_self_intersecting()) if self_intersection else None
    return out


POISSON = r'''
import json, resource, sys, time
import numpy as np, open3d as o3d
cloud, out, depth = sys.argv[1], sys.argv[2], int(sys.argv[3])
pc = o3d.io.read_point_cloud(cloud)
t0 = time.perf_counter()
pc.estimate_normals(o3d.geometry.KDTreeSearchParamKNN(16))
pc.orient_normals_consistent_tangent_plane(16)
t1 = time.perf_counter()
mesh, density = o3d.geometry.TriangleMesh.create_from_point_cloud_poisson(pc, depth=depth)
density = np.asarray(density)
mesh.remove_vertices_by_mask(density < np.quantile(density, 0.01))
t2 = time.perf_counter()
mesh.compute_vertex_normals()
np.save(out + ".v.npy", np.asarray(mesh.vertices)); np.save(out + ".n.npy", np.asarray(mesh.vertex_normals))
np.save(out + ".t.npy", np.asarray(mesh.triangles))
json.dump({"seconds_reconstruction": t2 - t1, "seconds_total": t2 - t0,
           "peak_memory_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024}, open(out + ".json", "w"))
'''


def main():
    a = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    a.add_argument("--pss", required=True)
    a.add_argument("--points", type=int, default=60000)
    a.add_argument("--noise", type=float, default=0.003)
    a.add_argument("--depth", type=int, default=8)
    a.add_argument("--out", default="mesh_vs_poisson.json")
    a.add_argument("--self-intersection", action="store_true",
                   help="also Open3D's self-intersection test (all pairs of triangles: slow)")
    o = a.parse_args()
    results = {"points": o.points, "noise_R": o.noise, "torus": {"R": R, "r": r}, "poisson_depth": o.depth}
    with tempfile.TemporaryDirectory() as tmp:
        cloud = os.path.join(tmp, "torus.ply")
        write_ply(cloud, torus_cloud(o.points, o.noise))
        results["input_points"] = errors(torus_cloud(o.points, o.noise), None)

        start = time.perf_counter()
        done = subprocess.run([o.pss, "mesh", cloud, "-o", os.path.join(tmp, "pss.ply"), "--progress", "never",
                               "--stats", os.path.join(tmp, "pss.json")], capture_output=True, text=True)
        seconds = time.perf_counter() - start
        if done.returncode:
            sys.exit("pss mesh failed: " + done.stderr)
        v, n, t = read_mesh_ply(os.path.join(tmp, "pss.ply"))
        stats = json.load(open(os.path.join(tmp, "pss.json")))
        results["pss_mesh"] = {"seconds_total": seconds, "phases": stats["seconds"], "vertices": len(v),
                               "triangles": len(t), "cell": stats["params"]["cell"],
                               "peak_memory_mb": resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024,
                               "euler_characteristic": stats["mesh"]["euler_characteristic"],
                               **errors(v, n), **open3d_checks(v, t, o.self_intersection)}

        done = subprocess.run([o.pss, "project", cloud, "-o", os.path.join(tmp, "proj.ply"), "--progress", "never"],
                              capture_output=True, text=True)
        if done.returncode:
            sys.exit("pss project failed: " + done.stderr)
        data = open(os.path.join(tmp, "proj.ply"), "rb").read()
        end = data.index(b"end_header\n") + 11
        rec = np.frombuffer(data, np.dtype([("p", "<f4", 3), ("n", "<f4", 3), ("s", "<i4")]), o.points, end)
        results["pss_project_points"] = errors(rec["p"], rec["n"])

        base = os.path.join(tmp, "poisson")
        done = subprocess.run([sys.executable, "-c", POISSON, cloud, base, str(o.depth)], capture_output=True, text=True)
        if done.returncode:
            sys.exit("Open3D Poisson failed: " + done.stderr)
        timing = json.load(open(base + ".json"))
        v, n, t = np.load(base + ".v.npy"), np.load(base + ".n.npy"), np.load(base + ".t.npy")
        results["poisson"] = {**timing, "vertices": len(v), "triangles": len(t),
                              "euler_characteristic": int(len(v) - len({tuple(sorted(e)) for tri in t.tolist() for e in
                                                                        ((tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0]))}) + len(t)),
                              **errors(v, n), **open3d_checks(v, t, o.self_intersection)}

    p, q = results["pss_mesh"], results["poisson"]
    rows = [("time (s)", "%.2f (whole process)" % p["seconds_total"],
             "%.2f (reconstruction) / %.2f (with normals)" % (q["seconds_reconstruction"], q["seconds_total"])),
            ("peak memory (MB)", "%.0f" % p["peak_memory_mb"], "%.0f" % q["peak_memory_mb"]),
            ("vertices / triangles", "%d / %d" % (p["vertices"], p["triangles"]), "%d / %d" % (q["vertices"], q["triangles"])),
            ("vertex distance mean / max (R)", "%.2e / %.2e" % (p["mean_distance"], p["max_distance"]),
             "%.2e / %.2e" % (q["mean_distance"], q["max_distance"])),
            ("normal error mean (deg)", "%.2f" % p["mean_normal_deg"], "%.2f" % q["mean_normal_deg"]),
            ("watertight / edge-manifold / vertex-manifold", "%s / %s / %s" % (p["watertight"], p["edge_manifold"], p["vertex_manifold"]),
             "%s / %s / %s" % (q["watertight"], q["edge_manifold"], q["vertex_manifold"])),
            ("self-intersecting", str(p["self_intersecting"]), str(q["self_intersecting"])),
            ("components, Euler characteristic", "%d, %d" % (p["components"], p["euler_characteristic"]),
             "%d, %d" % (q["components"], q["euler_characteristic"]))]
    print("noisy torus, %d points, noise %.2g R; pss project's points: distance %.2e R, normals %.2f deg" %
          (o.points, o.noise, results["pss_project_points"]["mean_distance"], results["pss_project_points"]["mean_normal_deg"]))
    print("| | pss mesh | Open3D Poisson, depth %d |\n|---|---|---|" % o.depth)
    for row in rows:
        print("| %s | %s | %s |" % row)
    print("ratios pss/Poisson: distance %.2f, normal error %.2f, time %.2f (vs reconstruction alone)" %
          (p["mean_distance"] / q["mean_distance"], p["mean_normal_deg"] / q["mean_normal_deg"],
           p["seconds_total"] / q["seconds_reconstruction"]))
    json.dump(results, open(o.out, "w"), indent=1)
    print("wrote", o.out)


if __name__ == "__main__":
    main()
