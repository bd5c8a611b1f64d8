# pss.mesh against `pss mesh`: the same vertices, normals and faces, and the same errors.
import numpy as np
import pytest

import pss
from conftest import BUNNY, FUEL, cli_error, cli_ok


def read_mesh_ply(path):
    """Vertices (x y z as float32 or float64), normals and faces of a binary PLY mesh as pss
    writes it, read here independently of the library."""
    data = open(path, "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode()
    vertices = int(header.split("element vertex ")[1].split()[0])
    faces = int(header.split("element face ")[1].split()[0])
    real = "<f8" if "property double x" in header else "<f4"
    vt = np.dtype([("p", real, 3), ("n", "<f4", 3)])
    v = np.frombuffer(data, vt, vertices, end)
    f = np.frombuffer(data, np.dtype([("count", "u1"), ("i", "<i4", 3)]), faces, end + vertices * vt.itemsize)
    assert np.all(f["count"] == 3)
    return v["p"], v["n"], f["i"]


def sphere(count=3000, seed=1):
    rng = np.random.default_rng(seed)
    d = rng.normal(size=(count, 3))
    return (d / np.linalg.norm(d, axis=1, keepdims=True)).astype(np.float32)


@pytest.mark.parametrize("surface", ["mls", "rimls"])
def test_mesh_gives_the_cli_s_vertices_normals_and_faces(tmp_path, surface):
    out = tmp_path / "bunny.ply"
    # The bunny's file has faces: the CLI's auto clips its vertices; an array is a scan's.
    cli_ok("mesh", BUNNY, "--surface", surface, "--borders", "extend", "-o", out)
    points, _, _ = pss.read_points(BUNNY)
    vertices, normals, faces = pss.mesh(points, surface=surface)
    assert vertices.dtype == np.float32 and normals.dtype == np.float32 and faces.dtype == np.int32
    v, n, f = read_mesh_ply(out)
    assert np.array_equal(vertices, v) and np.array_equal(normals, n) and np.array_equal(faces, f)
    assert faces.min() == 0 and faces.max() == len(vertices) - 1


def test_mesh_of_a_sphere_is_closed_on_the_sphere_and_faces_out():
    vertices, normals, faces = pss.mesh(sphere())
    assert np.abs(np.linalg.norm(vertices, axis=1) - 1).max() < 0.01
    assert np.all(np.einsum("ij,ij->i", normals, vertices) > 0.98)
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    assert np.all(np.einsum("ij,ij->i", np.cross(b - a, c - a), a + b + c) > 0)
    # Closed: every edge in exactly two faces, once each way.
    edges = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    directed = {tuple(e) for e in edges.tolist()}
    assert len(directed) == len(edges)
    assert all((b, a) in directed for a, b in directed)
    assert len(vertices) - len(directed) // 2 + len(faces) == 2  # Euler characteristic


def test_cell_borders_and_h_are_the_cli_s(tmp_path):
    points = sphere()
    coarse = pss.mesh(points, cell=0.1)[2]
    fine = pss.mesh(points, cell=0.05)[2]
    assert 3.5 < len(fine) / len(coarse) < 4.5
    out = tmp_path / "m.ply"
    np.savetxt(tmp_path / "s.xyz", points)
    cli_ok("mesh", tmp_path / "s.xyz", "--h", "0.1", "--cell", "0.06", "--borders", "extend", "-o", out)
    v, n, f = read_mesh_ply(out)
    vertices, normals, faces = pss.mesh(np.loadtxt(tmp_path / "s.xyz"), 0.1, cell=0.06, borders="extend")
    assert np.array_equal(f, faces) and np.allclose(v, vertices, atol=0)


def test_borders_clip_an_open_sheet_at_its_points_and_extend_it_by_default():
    rng = np.random.default_rng(5)
    square = np.column_stack([rng.uniform(-1, 1, (3000, 2)), np.zeros(3000)]).astype(np.float32)
    reach = {b: np.abs(pss.mesh(square, borders=b)[0][:, :2]).max() for b in ["extend", "clip", "auto"]}
    assert reach["clip"] < 1.0 < 1.05 < reach["extend"]  # the band past the square's edge
    assert reach["auto"] == reach["extend"]  # an array of points is a scan's


BOX_HALF = np.array([0.5, 0.4, 0.3])
BOX_TURN = (np.array([[np.cos(0.5), -np.sin(0.5), 0], [np.sin(0.5), np.cos(0.5), 0], [0, 0, 1]])
            @ np.array([[1, 0, 0], [0, np.cos(0.5), -np.sin(0.5)], [0, np.sin(0.5), np.cos(0.5)]]))


def turned_box_samples(count=20000, seed=3):
    """Points on the faces of a box (1 x 0.8 x 0.6) turned against the axes, with their normals."""
    rng = np.random.default_rng(seed)
    half = BOX_HALF
    points, normals = [], []
    for axis in range(3):
        for side in (-1, 1):
            p = rng.uniform(-1, 1, (count // 6, 3)) * half
            p[:, axis] = side * half[axis]
            n = np.zeros_like(p)
            n[:, axis] = side
            points.append(p)
            normals.append(n)
    return np.vstack(points) @ BOX_TURN.T, np.vstack(normals) @ BOX_TURN.T


def on_the_box_edges(vertices, within=1e-3):
    """How many of a mesh's vertices lie on the edges of turned_box_samples' box (within
    `within` of two of its faces' planes): 601 creased and 291 chamfered, measured."""
    local = np.abs(vertices @ BOX_TURN)
    return int(((np.abs(local - BOX_HALF) < within).sum(1) >= 2).sum())


def test_crease_angle_is_the_cli_s(tmp_path):
    points, normals = turned_box_samples()
    np.savetxt(tmp_path / "box.pwn", np.hstack([points, normals]), fmt="%.7g")
    for flags, kwargs in (((), {}), (("--crease-angle", "180"), {"crease_angle": 180})):
        out = tmp_path / "m.ply"
        cli_ok("mesh", tmp_path / "box.pwn", "--surface", "rimls", *flags, "-o", out)
        v, n, f = read_mesh_ply(out)
        vertices, _, faces = pss.mesh(np.loadtxt(tmp_path / "box.pwn")[:, :3], surface="rimls",
                                      normals=np.loadtxt(tmp_path / "box.pwn")[:, 3:], borders="extend", **kwargs)
        assert np.array_equal(f, faces) and np.array_equal(v, vertices)
    creased = pss.mesh(points, surface="rimls", normals=normals)
    chamfered = pss.mesh(points, surface="rimls", normals=normals, crease_angle=180)
    # a vertex on the crease in each of its cubes
    assert on_the_box_edges(creased[0]) > 1.5 * on_the_box_edges(chamfered[0])
    with pytest.raises(pss.Error, match="crease_angle"):
        pss.mesh(points, crease_angle=0)
    with pytest.raises(pss.Error, match="crease_angle"):
        pss.mesh(points, crease_angle=float("nan"))


def test_bad_arguments_say_what_the_cli_says(tmp_path):
    with pytest.raises(pss.Error, match="at least 3"):
        pss.mesh(np.zeros((2, 3)))
    with pytest.raises(pss.Error, match="cell"):
        pss.mesh(sphere(), cell=-1)
    with pytest.raises(pss.Error, match="borders"):
        pss.mesh(sphere(), borders="none")
    with pytest.raises(pss.Error, match="too small"):
        pss.mesh(sphere(), cell=1e-9)


@pytest.mark.parametrize("flags, kwargs", [(("--iso", "60"), {"iso": 60}),
                                           (("--iso", "60", "--method", "predictor", "--h", "1.5", "--cell", "0.75"),
                                            {"iso": 60, "method": "predictor", "h": 1.5, "cell": 0.75}),
                                           (("--gradient",), {"gradient": True})])
def test_volume_mesh_gives_the_cli_s_vertices_normals_and_faces(tmp_path, flags, kwargs):
    out = tmp_path / "fuel.ply"
    cli_ok("mesh", FUEL, "--dims", "64x64x64", *flags, "-o", out)
    vertices, normals, faces = pss.read_volume(FUEL, dims=(64, 64, 64)).mesh(**kwargs)
    assert vertices.dtype == np.float32 and normals.dtype == np.float32 and faces.dtype == np.int32
    assert len(faces) > 100
    v, n, f = read_mesh_ply(out)
    assert np.array_equal(vertices, v) and np.array_equal(normals, n) and np.array_equal(faces, f)


def test_a_volume_s_mesh_is_its_sphere_in_world_units_facing_lower_values():
    # f = |x - c| on an anisotropic grid, indexed [z, y, x]: the iso-surface f = 9 is the
    # sphere of radius 9 about c; outward is towards lower values, here the centre.
    spacing, origin, centre = np.array([0.8, 1.0, 1.25]), np.array([-3.0, 2.0, 5.0]), np.array([12.0, 14.0, 18.0])
    z, y, x = np.meshgrid(*(o + s * np.arange(n) for o, s, n in zip(origin[::-1], spacing[::-1], (26, 30, 36))),
                          indexing="ij")
    values = np.sqrt((x - centre[0]) ** 2 + (y - centre[1]) ** 2 + (z - centre[2]) ** 2)
    volume = pss.Volume(values, spacing=tuple(spacing), origin=tuple(origin))
    vertices, normals, faces = volume.mesh(iso=9)
    radii = np.linalg.norm(vertices - centre, axis=1)
    assert np.max(np.abs(radii - 9)) < 0.05
    assert np.all(np.sum(normals * (vertices - centre), axis=1) < 0)
    coarse = volume.mesh(iso=9, cell=2.0)[2]
    assert 2.5 * len(coarse) < len(faces) < 6 * len(coarse)  # the default cell: u = 1


def test_volume_mesh_errors_are_the_cli_s(tmp_path):
    fuel = pss.read_volume(FUEL, dims=(64, 64, 64))
    expected = cli_error("mesh", FUEL, "--dims", "64x64x64", "--iso", "60", "--cell", "1e-3", "-o", tmp_path / "m.ply")
    with pytest.raises(pss.Error) as caught:
        fuel.mesh(iso=60, cell=1e-3)
    assert str(caught.value) == expected
    with pytest.raises(pss.Error, match="choose the surface"):
        fuel.mesh()
    with pytest.raises(pss.Error, match="cell"):
        fuel.mesh(iso=60, cell=-1)
