#!/usr/bin/python3
"""Sharp creases in `pss mesh` (issue 27): a box's edges, with and without the creases' vertices,
for each surface, in one run.

Usage (Debian python3 with python3-numpy, python3-open3d):
  mesh_creases.py --pss PSS [--points 60000] [--normals file|estimate] [--out mesh_creases.json]

The cloud: the faces of a box (1 x 0.8 x 0.6) turned against the lattice (0.5 rad about
(1, 2, 0.7)), sampled uniformly at random, with its exact normals (or none: --normals estimate).
For each surface (mls, apss, rimls), `pss mesh` at its defaults and with --crease-angle 180. For
each mesh: the distance of the box's edges (points along them, two cubes from the corners) to
the mesh (Open3D's RaycastingScene), mean and largest in cubes; the share of the mesh's area
whose triangle normals are more than 10° from the nearest face's; the vertices on creases and
the time of the whole process. Prints a markdown table, writes JSON.
"""
import argparse, json, os, subprocess, tempfile, time
import numpy as np
import open3d as o3d

from mesh_ply import read_mesh_ply

HALF = np.array([0.5, 0.4, 0.3])


def turn():
    axis = np.array([1.0, 2.0, 0.7])
    axis /= np.linalg.norm(axis)
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + np.sin(0.5) * k + (1 - np.cos(0.5)) * k @ k  # Rodrigues


def box_cloud(n, seed=1):
    rng = np.random.default_rng(seed)
    areas = [HALF[1] * HALF[2], HALF[0] * HALF[2], HALF[0] * HALF[1]]
    points, normals = [], []
    for axis in range(3):
        for side in (-1, 1):
            p = rng.uniform(-1, 1, (int(n * areas[axis] / (2 * sum(areas))), 3)) * HALF
            p[:, axis] = side * HALF[axis]
            q = np.zeros_like(p)
            q[:, axis] = side
            points.append(p)
            normals.append(q)
    t = turn()
    return np.vstack(points) @ t.T, np.vstack(normals) @ t.T


def measures(vertices, faces, cell):
    local = vertices @ turn()  # back to the box's frame
    mesh = o3d.geometry.TriangleMesh(o3d.utility.Vector3dVector(local), o3d.utility.Vector3iVector(faces))
    scene = o3d.t.geometry.RaycastingScene()
    scene.add_triangles(o3d.t.geometry.TriangleMesh.from_legacy(mesh))
    edges = []
    for axis in range(3):
        for corner in range(4):
            p = np.zeros((200, 3))
            p[:, axis] = np.linspace(-HALF[axis] + 2 * cell, HALF[axis] - 2 * cell, 200)
            p[:, (axis + 1) % 3] = (1 if corner & 1 else -1) * HALF[(axis + 1) % 3]
            p[:, (axis + 2) % 3] = (1 if corner & 2 else -1) * HALF[(axis + 2) % 3]
            edges.append(p)
    d = scene.compute_distance(np.vstack(edges).astype(np.float32)).numpy() / cell
    a, b, c = (local[faces[:, k]] for k in range(3))
    n = np.cross(b - a, c - a)
    area = np.linalg.norm(n, axis=1)
    n /= np.maximum(area, 1e-30)[:, None]
    centre = (a + b + c) / 3
    nearest = np.argmax(np.abs(centre) / HALF, axis=1)  # the face whose plane is nearest
    truth = np.zeros_like(n)
    truth[np.arange(len(n)), nearest] = np.sign(centre[np.arange(len(n)), nearest])
    off = np.degrees(np.arccos(np.clip(np.einsum("ij,ij->i", n, truth), -1, 1)))
    return {"edge_mean_cubes": float(d.mean()), "edge_largest_cubes": float(d.max()),
            "area_off_10_degrees": float(area[off > 10].sum() / area.sum())}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pss", required=True)
    parser.add_argument("--points", type=int, default=60000)
    parser.add_argument("--normals", choices=["file", "estimate"], default="file")
    parser.add_argument("--out", default="mesh_creases.json")
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        points, normals = box_cloud(args.points)
        cloud = os.path.join(folder, "box.pwn")
        np.savetxt(cloud, np.hstack([points, normals]), fmt="%.7g")
        for surface in ("mls", "apss", "rimls"):
            for angle in ("30", "180"):
                out, stats = os.path.join(folder, "m.ply"), os.path.join(folder, "s.json")
                start = time.perf_counter()
                subprocess.run([args.pss, "mesh", cloud, "--surface", surface, "--normals", args.normals,
                                "--crease-angle", angle, "-o", out, "--stats", stats, "--progress", "never"],
                               check=True, stdout=subprocess.DEVNULL)
                seconds = time.perf_counter() - start
                s = json.load(open(stats))
                vertices, _, faces = read_mesh_ply(out)
                row = {"surface": surface, "crease_angle": float(angle), "seconds": seconds,
                       "crease_vertices": s["band"]["crease_vertices"], "triangles": len(faces),
                       **measures(vertices.astype(np.float64), faces, s["params"]["cell"])}
                rows.append(row)
    print(f"box of {args.points} points, normals: {args.normals}\n")
    print("| surface | --crease-angle | edges to mesh, mean (cubes) | largest | area > 10° off | crease vertices | s |")
    print("|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['surface']} | {r['crease_angle']:g} | {r['edge_mean_cubes']:.3f} | {r['edge_largest_cubes']:.3f} | "
              f"{100 * r['area_off_10_degrees']:.2f} % | {r['crease_vertices']} | {r['seconds']:.2f} |")
    json.dump({"points": args.points, "normals": args.normals, "rows": rows}, open(args.out, "w"), indent=1)


if __name__ == "__main__":
    main()
