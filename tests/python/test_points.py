# pss.estimate_h, pss.project, pss.render and pss.read_points against the CLI on the bunny.
import threading
import time

import numpy as np
import pytest

import pss
from conftest import BUNNY, cli_error, cli_ok, read_binary_ply, read_png


def test_read_points_matches_an_independent_reading_of_the_ascii_ply(bunny):
    lines = open(BUNNY).read().split("end_header\n")[1].splitlines()
    expected = np.array([line.split()[:3] for line in lines[:35947]], np.float32)
    assert bunny.shape == (35947, 3) and bunny.dtype == np.float32
    assert np.array_equal(bunny, expected)


def test_estimate_h_is_the_h_pss_info_suggests(bunny):
    line = next(l for l in cli_ok("info", BUNNY).splitlines() if l.startswith("suggested h"))
    assert pss.estimate_h(bunny) == pytest.approx(float(line.split()[2]), rel=1e-5)


def test_estimate_h_is_three_times_the_noise_where_that_is_wider_than_the_spacing():
    rng = np.random.default_rng(4)
    directions = rng.normal(size=(8000, 3))
    sphere = directions / np.linalg.norm(directions, axis=1)[:, None]
    sigma = 0.06
    noisy = sphere * (1 + sigma * rng.normal(size=(8000, 1)))
    assert pss.estimate_h(noisy) == pytest.approx(3 * sigma, rel=0.1)
    assert pss.estimate_h(sphere) < 0.7 * 3 * sigma


@pytest.mark.parametrize("method", ["mls", "wls"])
def test_project_gives_the_cli_s_points_normals_and_status(bunny, tmp_path, method):
    out = tmp_path / "projected.ply"
    cli_ok("project", BUNNY, "--h", "0.004", "--method", method, "-o", out)
    cli = read_binary_ply(out)
    points, normals, status = pss.project(bunny, 0.004, method=method)
    assert points.shape == (35947, 3) and points.dtype == np.float32 and status.dtype == np.int32
    assert np.array_equal(points, np.stack([cli["x"], cli["y"], cli["z"]], 1))
    assert np.array_equal(normals, np.stack([cli["nx"], cli["ny"], cli["nz"]], 1))
    assert np.array_equal(status, cli["status"])
    assert np.count_nonzero(status == 0) > 0.9 * len(status)


def stepped_sphere():
    """A unit sphere whose half x < 0 is sampled 64 times sparser (render_test's SphereStep64)."""
    rng = np.random.default_rng(1)
    d = rng.normal(size=(60000, 3))
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    keep = (d[:, 0] >= 0) | (rng.random(len(d)) < 1 / 64)
    return d[keep].astype(np.float32)


@pytest.mark.parametrize("support", ["adaptive", "global"])
def test_support_is_the_cli_s(tmp_path, support):
    points = stepped_sphere()
    cloud = tmp_path / "step.xyz"
    np.savetxt(cloud, points, fmt="%.9g")
    out = tmp_path / "projected.ply"
    cli_ok("project", cloud, "--support", support, "--outliers", "keep", "-o", out)
    cli = read_binary_ply(out)
    projected, _, status = pss.project(np.loadtxt(cloud, dtype=np.float32), support=support, outliers="keep")
    assert np.array_equal(projected, np.stack([cli["x"], cli["y"], cli["z"]], 1))
    assert np.array_equal(status, cli["status"])
    # One global h leaves the sparse half's points with too few neighbours (status 2). (The
    # widths alone: set aside, a sample with only 2 others at the step is not one.)
    assert (np.count_nonzero(status == 2) == 0) == (support == "adaptive")


def test_support_is_adaptive_by_default_and_global_with_h():
    points = stepped_sphere()
    h = pss.estimate_h(points)
    default = pss.project(points)[0]
    assert np.array_equal(default, pss.project(points, support="adaptive")[0])
    assert not np.array_equal(default, pss.project(points, support="global")[0])
    assert np.array_equal(pss.project(points, h)[0], pss.project(points, h, support="global")[0])
    _, _, stats = pss.render(points, size=(32, 32), full_output=True)
    assert stats["params"]["support"] == "adaptive" and stats["params"]["h_largest"] > 3 * h
    _, _, stats = pss.render(points, h, size=(32, 32), full_output=True)
    assert stats["params"]["support"] == "global" and stats["params"]["h_largest"] == pytest.approx(h)


def unit_sphere(count=8000):
    rng = np.random.default_rng(2)
    d = rng.normal(size=(count, 3))
    return (d / np.linalg.norm(d, axis=1, keepdims=True)).astype(np.float32)


@pytest.mark.parametrize("surface", ["mls", "apss", "rimls"])
def test_surface_is_the_cli_s(tmp_path, surface):
    points = unit_sphere()
    cloud = tmp_path / "sphere.xyz"
    np.savetxt(cloud, np.hstack([points, points]), fmt="%.9g")  # with its exact normals
    out = tmp_path / "projected.ply"
    cli_ok("project", cloud, "--surface", surface, "-o", out)
    cli = read_binary_ply(out)
    projected, normals, _ = pss.project(points, normals=points, surface=surface)
    assert np.array_equal(projected, np.stack([cli["x"], cli["y"], cli["z"]], 1))
    assert np.array_equal(normals, np.stack([cli["nx"], cli["ny"], cli["nz"]], 1))
    # APSS's spheres reproduce the sphere to rounding; MLS and RIMLS keep a bias.
    error = np.abs(np.linalg.norm(projected, axis=1) - 1).max()
    assert (error < 2e-6) == (surface == "apss")


def test_outliers_are_the_cli_s_and_set_aside_by_default(tmp_path):
    points = unit_sphere()
    rng = np.random.default_rng(3)
    strays = (points[:50] * (1 + 0.1 + 0.1 * rng.random((50, 1)))).astype(np.float32)  # 1.2h to 2.3h off
    cloud = np.vstack([points, strays])
    np.savetxt(tmp_path / "strays.xyz", cloud, fmt="%.9g")
    for outliers in ["set-aside", "keep"]:
        cli_ok("project", tmp_path / "strays.xyz", "--outliers", outliers, "-o", tmp_path / "p.ply")
        cli = read_binary_ply(tmp_path / "p.ply")
        projected, _, _ = pss.project(cloud, outliers=outliers)
        assert np.array_equal(projected, np.stack([cli["x"], cli["y"], cli["z"]], 1))
    _, _, stats = pss.render(cloud, size=(32, 32), full_output=True)
    assert stats["outliers_set_aside"] >= 50
    _, _, stats = pss.render(cloud, size=(32, 32), outliers="keep", full_output=True)
    assert stats["outliers_set_aside"] == 0


def test_a_noisy_clouds_samples_are_merged_as_by_the_cli(tmp_path):
    rng = np.random.default_rng(5)
    u, v = 2 * np.pi * rng.random((2, 60000))
    normal = np.stack([np.cos(v) * np.cos(u), np.cos(v) * np.sin(u), np.sin(v)], 1)
    centre = np.stack([np.cos(u), np.sin(u), 0 * u], 1)
    torus = (centre + (0.35 + 0.06 * rng.normal(size=len(u)))[:, None] * normal).astype(np.float32)
    _, _, stats = pss.render(torus, size=(16, 16), full_output=True)
    assert stats["points_merged"] > 40000
    _, _, stats = pss.render(torus, size=(16, 16), support="global", full_output=True)
    assert stats["points_merged"] == 0


def test_surface_fits_the_given_normals_or_estimates_them():
    points = unit_sphere()
    wrong = points + np.float32([0.5, 0, 0])  # up to 30 degrees off: they still follow the points
    off = lambda p: np.abs(np.linalg.norm(p, axis=1) - 1).mean()
    bias = 2 * pss.estimate_h(points) ** 4  # MLS's bound on a sphere (tests/projection_test.cpp)
    assert off(pss.project(points, normals=wrong, surface="apss")[0]) > 20 * bias
    assert off(pss.project(points, surface="apss")[0]) < bias  # estimated when none are given
    _, _, stats = pss.render(points, normals=points, surface="rimls", size=(32, 32), full_output=True)
    assert stats["params"]["surface"] == "rimls" and stats["params"]["normals"] == "file"
    _, _, stats = pss.render(points, surface="apss", size=(32, 32), full_output=True)
    assert stats["params"]["surface"] == "apss" and stats["params"]["normals"] == "estimated"
    _, _, stats = pss.render(points, size=(32, 32), full_output=True)  # RIMLS, the default, as the CLI's
    assert stats["params"]["surface"] == "rimls" and stats["params"]["normals"] == "estimated"
    _, _, stats = pss.render(points, surface="mls", size=(32, 32), full_output=True)
    assert stats["params"]["surface"] == "mls" and stats["params"]["normals"] == "none"


def test_a_flipped_half_of_the_given_normals_is_turned():
    points = unit_sphere()
    flipped = np.where(points[:, :1] > 0, -points, points)
    half = int(min((points[:, 0] > 0).sum(), (points[:, 0] <= 0).sum()))
    _, _, stats = pss.render(points, normals=flipped, surface="rimls", size=(32, 32), full_output=True)
    assert stats["normals_turned"] == half > 100
    _, _, stats = pss.render(points, normals=points, surface="rimls", size=(32, 32), full_output=True)
    assert stats["normals_turned"] == 0 and stats["file_normals_off"] == 0


def test_given_normals_that_do_not_follow_the_points_are_left_out():
    points = unit_sphere()
    one_way = np.tile([1.0, 0.0, 0.0], (len(points), 1))  # 45 degrees or more off where |x| <= 0.707: 71 %
    _, _, stats = pss.render(points, normals=one_way, surface="rimls", size=(32, 32), full_output=True)
    off = int((np.abs(points[:, 0]) < 0.7071).sum())
    assert stats["params"]["normals"] == "estimated"
    assert abs(stats["file_normals_off"] - off) <= 0.01 * len(points) and off > len(points) / 2


def test_borders_are_the_cli_s_and_extended_by_default(tmp_path):
    rng = np.random.default_rng(5)
    square = np.column_stack([rng.uniform(-1, 1, (3000, 2)), np.zeros(3000)]).astype(np.float32)
    np.savetxt(tmp_path / "square.xyz", square, fmt="%.9g")
    flags = ["--up", "0,0,1", "--view", "20,50", "--size", "48x48"]
    counts = {}
    for borders in ["extend", "clip"]:
        cli_ok("render", tmp_path / "square.xyz", *flags, "--borders", borders, "-o", tmp_path / "s.png",
               "--hits", tmp_path / "s.ply")
        cli = read_binary_ply(tmp_path / "s.ply")
        _, hits, stats = pss.render(square, up=(0, 0, 1), view=(20, 50), size=(48, 48), borders=borders,
                                    full_output=True)
        assert stats["params"]["borders"] == borders
        counts[borders] = stats["hits"]
        assert counts[borders] == len(cli["x"])
    assert counts["extend"] > counts["clip"] + 20  # the band past the square's edge
    _, _, stats = pss.render(square, up=(0, 0, 1), view=(20, 50), size=(48, 48), full_output=True)
    assert stats["hits"] == counts["extend"]
    # 'auto', as mesh takes it: an array of points is a scan's, extended.
    _, _, stats = pss.render(square, up=(0, 0, 1), view=(20, 50), size=(48, 48), borders="auto", full_output=True)
    assert stats["params"]["borders"] == "extend" and stats["hits"] == counts["extend"]


def test_project_takes_any_array_like_and_hands_back_arrays_it_does_not_copy(bunny):
    as_list = bunny[:2000].astype(np.float64).tolist()
    points, _, _ = pss.project(as_list, 0.004)
    again, _, _ = pss.project(bunny[:2000], 0.004)
    assert np.array_equal(points, again)
    assert not points.flags.owndata and points.base is not None  # the library's vector, kept alive
    assert points.flags.c_contiguous and points.flags.writeable


def render_like_cli(tmp_path, *flags):
    image_path, hits_path, stats_path = tmp_path / "image.png", tmp_path / "hits.ply", tmp_path / "stats.json"
    cli_ok("render", BUNNY, *flags, "-o", image_path, "--hits", hits_path, "--stats", stats_path)
    return read_png(image_path), read_binary_ply(hits_path), stats_path


def test_render_gives_the_cli_s_image_hits_and_counts(bunny, tmp_path):
    # The CLI clips a mesh's vertices at their borders (--borders auto); the module extends.
    cli_image, cli_hits, _ = render_like_cli(tmp_path, "--size", "96x64", "--view", "30,20", "--shadows",
                                             "--reflections", "--iterations", "3", "--borders", "extend")
    image, hits, stats = pss.render(bunny, size=(96, 64), view=(30, 20), shadows=True, reflections=True,
                                    iterations=3, full_output=True)
    assert image.shape == (64, 96, 3) and image.dtype == np.uint8
    assert np.array_equal(image, cli_image)
    mask = hits["mask"]
    assert mask.sum() == len(cli_hits) == stats["hits"] > 500
    assert np.array_equal(hits["points"][cli_hits["py"], cli_hits["px"]],
                          np.stack([cli_hits["x"], cli_hits["y"], cli_hits["z"]], 1))
    assert np.array_equal(hits["normals"][cli_hits["py"], cli_hits["px"]],
                          np.stack([cli_hits["nx"], cli_hits["ny"], cli_hits["nz"]], 1))
    assert np.isinf(hits["depth"][~mask]).all() and np.isnan(hits["points"][~mask]).all()
    eye = np.array(stats["camera"]["eye"], np.float32)
    depth = np.linalg.norm(hits["points"][mask] - eye, axis=1)
    assert np.allclose(hits["depth"][mask], depth, rtol=1e-4)


def test_candidates_limit_a_ray_as_the_cli_s_do(bunny, tmp_path):
    # One candidate a ray: the rays whose first ball intersection is rejected miss, as with the
    # CLI's --candidates 1 (the module had no such argument).
    cli_image, cli_hits, _ = render_like_cli(tmp_path, "--size", "64x48", "--view", "80,10", "--candidates", "1",
                                             "--borders", "extend")
    image, hits, stats = pss.render(bunny, size=(64, 48), view=(80, 10), candidates=1, full_output=True)
    assert np.array_equal(image, cli_image) and stats["params"]["max_candidates"] == 1
    _, every, _ = pss.render(bunny, size=(64, 48), view=(80, 10), full_output=True)
    assert hits["mask"].sum() == len(cli_hits) < every["mask"].sum()
    with pytest.raises(pss.Error, match=r"^candidates: expected an integer from 1 to 1024 \(got 0\)$"):
        pss.render(bunny, candidates=0)


def test_colors_shade_as_the_cli_s_color_does(bunny, tmp_path):
    # Red on top, blue below, in a PLY the CLI reads: the same image from both.
    height = (bunny[:, 1] - bunny[:, 1].min()) / np.ptp(bunny[:, 1])
    colors = np.stack([40 + 200 * height, 60 + 0 * height, 240 - 200 * height], 1).round().astype(np.uint8)
    cloud = tmp_path / "coloured.ply"
    header = ("ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
              "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n" % len(bunny))
    rows = "\n".join("%.9g %.9g %.9g %d %d %d" % (*p, *c) for p, c in zip(bunny.tolist(), colors.tolist()))
    cloud.write_text(header + rows + "\n")
    out = tmp_path / "coloured.png"
    cli_ok("render", cloud, "--color", "--size", "64x48", "-o", out)
    image = pss.render(bunny, colors=colors, size=(64, 48))
    assert np.array_equal(image, read_png(out))
    assert np.array_equal(pss.render(bunny, colors=colors / 255.0, size=(64, 48)), image)
    plain = pss.render(bunny, size=(64, 48))
    assert np.abs(image.astype(int) - plain).max() > 50


def test_a_camera_from_the_stats_renders_the_same_image_as_the_view_did(bunny, tmp_path):
    image, _, stats = pss.render(bunny, size=(48, 40), view=(-40, 10), zoom=1.5, full_output=True)
    assert np.array_equal(pss.render(bunny, size=(48, 40), camera=stats["camera"]), image)
    _, _, stats_path = render_like_cli(tmp_path, "--size", "48x40", "--view", "-40,10", "--zoom", "1.5")
    assert np.array_equal(pss.render(bunny, size=(48, 40), camera=stats_path), image)


def test_transparent_images_have_alpha_where_the_rays_hit(bunny):
    image, hits, _ = pss.render(bunny, size=(40, 30), transparent=True, full_output=True)
    assert image.shape == (30, 40, 4)
    assert np.array_equal(image[..., 3], np.where(hits["mask"], 255, 0))


def test_the_work_runs_without_the_gil(bunny):
    # The main thread keeps running Python while a render runs on another: with the GIL
    # held it would stall for the whole render.
    done = threading.Event()
    seconds = []

    def work():
        start = time.perf_counter()
        pss.render(bunny, size=(256, 256), reflections=True, backend="cpu")
        seconds.append(time.perf_counter() - start)
        done.set()

    thread = threading.Thread(target=work)
    last, longest_gap = time.perf_counter(), 0.0
    thread.start()
    while not done.is_set():
        now = time.perf_counter()
        longest_gap, last = max(longest_gap, now - last), now
    thread.join()
    assert seconds[0] > 0.05
    assert longest_gap < 0.5 * seconds[0]


def test_progress_is_silent_by_default_and_shown_when_asked(bunny, capfd):
    pss.render(bunny, size=(16, 16))
    assert capfd.readouterr().err == ""
    try:
        pss.set_progress("always")
        pss.render(bunny, size=(16, 16))
        err = capfd.readouterr().err
        assert "preprocess: done in" in err and "primary rays: done in" in err
    finally:
        pss.set_progress("never")


def _far_sphere(n=4000, centre=(500123.25, 4000456.5, 310.75), radius=5.0):
    """A Fibonacci sphere at UTM-like coordinates, where float32's step (0.25 m) is about its
    spacing (0.28 m): in float32 it would collapse onto a lattice."""
    i = np.arange(n) + 0.5
    z = 1 - 2 * i / n
    r, a = np.sqrt(1 - z * z), np.pi * (3 - np.sqrt(5)) * np.arange(n)
    return np.array(centre) + radius * np.stack([r * np.cos(a), r * np.sin(a), z], 1), np.array(centre), radius


def test_a_cloud_far_from_zero_keeps_its_digits(tmp_path):
    points, centre, radius = _far_sphere()
    projected, _, status = pss.project(points)
    assert projected.dtype == np.float64 and np.all(status == 0)
    assert np.abs(np.linalg.norm(projected - centre, axis=1) - radius).max() < 1e-3

    np.savetxt(tmp_path / "far.xyz", points, fmt="%.17g")
    read, _, _ = pss.read_points(tmp_path / "far.xyz")
    assert read.dtype == np.float64 and np.abs(read - points).max() < 1e-6

    # The same image as the sphere about zero, and look_at a world point: close up on the top
    # of the silhouette, which 0.1 m (a float's rounding of y here) would move by 5 pixels.
    top = np.array([0.13, 4.9, 0.07])
    near = pss.render(points - centre, size=(96, 96), look_at=tuple(top), zoom=8)
    far = pss.render(points, size=(96, 96), look_at=tuple(centre + top), zoom=8)
    assert np.count_nonzero(np.abs(near.astype(int) - far.astype(int)).max(axis=2) > 2) < 20
    _, hits, stats = pss.render(points, size=(96, 96), look_at=tuple(centre), full_output=True)
    hit = hits["points"][hits["mask"]]
    assert hit.dtype == np.float64 and len(hit) > 1000
    assert np.abs(np.linalg.norm(hit - centre, axis=1) - radius).max() < 1e-3
    assert np.allclose(stats["origin"], centre, atol=8)  # the centre to a multiple of 16 m ≥ its extent


def test_project_and_mesh_give_their_stats_with_full_output():
    points = unit_sphere()
    projected, normals, status, stats = pss.project(points, surface="apss", full_output=True)
    assert stats["params"]["surface"] == "apss" and stats["params"]["normals"] == "estimated"
    assert sum(stats["status"].values()) == len(points)
    assert stats["status"]["converged"] == int((status == 0).sum())
    assert stats["normals_turned"] == 0 and stats["file_normals_off"] == 0
    one_way = np.tile([0.0, 0.0, 1.0], (len(points), 1))
    _, _, _, stats = pss.project(points, normals=one_way, surface="rimls", full_output=True)
    assert stats["file_normals_off"] > len(points) / 2 and stats["params"]["normals"] == "estimated"
    vertices, _, faces, stats = pss.mesh(points, full_output=True)
    shape = stats["mesh"]
    assert shape["vertices"] == len(vertices) and shape["triangles"] == len(faces)
    assert shape["watertight"] and shape["components"] == 1 and shape["euler_characteristic"] == 2
    assert shape["non_manifold_edges"] == 0 and stats["band"]["cubes_meshed"] > 0
    assert stats["params"]["cell"] > 0 and stats["params"]["surface"] == "rimls"
    assert len(pss.project(points)) == 3 and len(pss.mesh(points)) == 3
