# pss.Volume and pss.read_volume against the CLI, and the layout of a NumPy volume against
# an analytic sphere.
import numpy as np
import pytest

import pss
from conftest import FUEL, cli_error, cli_ok, read_binary_ply, read_png

RAW = ("--dims", "64x64x64")


@pytest.fixture(scope="module")
def fuel():
    return pss.read_volume(FUEL, dims=(64, 64, 64))


def test_read_volume_gives_the_file_s_voxels_indexed_z_y_x(fuel):
    expected = np.fromfile(FUEL, np.uint8).reshape(64, 64, 64).astype(np.float32)
    assert np.array_equal(fuel.values, expected)
    assert fuel.spacing == (1, 1, 1) and fuel.origin == (0, 0, 0) and fuel.source == FUEL
    assert repr(fuel) == "pss.Volume(shape=(64, 64, 64), spacing=(1.0, 1.0, 1.0), origin=(0.0, 0.0, 0.0), " \
        "source=%r)" % FUEL
    assert not fuel.values.flags.writeable  # a view of the volume's own values


def test_a_volume_says_its_shape_spacing_and_origin():
    v = pss.Volume(np.zeros((4, 5, 6)), spacing=(1, 2, 0.5), origin=(-1, 0, 3))
    assert repr(v) == "pss.Volume(shape=(4, 5, 6), spacing=(1.0, 2.0, 0.5), origin=(-1.0, 0.0, 3.0))"


@pytest.mark.parametrize("method", ["predictor", "predictor-corrector"])
def test_render_gives_the_cli_s_image_from_the_file_and_from_an_array(fuel, tmp_path, method):
    out = tmp_path / "fuel.png"
    cli_ok("volume", FUEL, *RAW, "--iso", "60", "--method", method, "--size", "64x48", "--view", "20,30", "-o", out)
    expected = read_png(out)
    assert np.array_equal(fuel.render(iso=60, method=method, size=(64, 48), view=(20, 30)), expected)
    from_array = pss.Volume(np.fromfile(FUEL, np.uint8).reshape(64, 64, 64))
    assert from_array.source == ""
    assert np.array_equal(from_array.render(iso=60, method=method, size=(64, 48), view=(20, 30)), expected)


def test_extract_gives_the_cli_s_points(fuel, tmp_path):
    out = tmp_path / "fuel.ply"
    cli_ok("extract", FUEL, *RAW, "--iso", "60", "--h", "1.5", "-o", out)
    cli = read_binary_ply(out)
    points, normals, stats = fuel.extract(iso=60, h=1.5, full_output=True)
    assert len(points) == len(cli) == stats["points"] > 100
    assert np.array_equal(points, np.stack([cli["x"], cli["y"], cli["z"]], 1))
    assert np.array_equal(normals, np.stack([cli["nx"], cli["ny"], cli["nz"]], 1))


def test_an_array_s_axes_spacing_and_origin_place_a_sphere_where_it_is():
    # f = |x - c| sampled on an anisotropic grid: the iso-surface f = 9 is the sphere of
    # radius 9 about c, in world units, only if values are indexed [z, y, x] and voxel
    # (i, j, k) sits at origin + (i sx, j sy, k sz).
    spacing, origin, centre = np.array([0.8, 1.0, 1.25]), np.array([-3.0, 2.0, 5.0]), np.array([12.0, 14.0, 18.0])
    nx, ny, nz = 36, 30, 26
    x = origin[0] + spacing[0] * np.arange(nx)
    y = origin[1] + spacing[1] * np.arange(ny)
    z = origin[2] + spacing[2] * np.arange(nz)
    zz, yy, xx = np.meshgrid(z, y, x, indexing="ij")
    values = np.sqrt((xx - centre[0]) ** 2 + (yy - centre[1]) ** 2 + (zz - centre[2]) ** 2)
    volume = pss.Volume(values, spacing=tuple(spacing), origin=tuple(origin))
    points, normals = volume.extract(iso=9)
    radius = np.linalg.norm(points - centre, axis=1)
    assert len(points) > 500
    assert np.abs(radius - 9).max() < 0.05
    outward = (points - centre) / radius[:, None]
    assert (np.sum(normals * outward, axis=1) > 0.99).all()  # along the gradient


def test_render_frames_the_surface_the_cli_frames(fuel, tmp_path):
    image, hits, stats = fuel.render(gradient=True, size=(32, 32), full_output=True)
    out = tmp_path / "fuel.png"
    cli_ok("volume", FUEL, *RAW, "--gradient", "--size", "32x32", "-o", out)
    assert np.array_equal(image, read_png(out))
    assert stats["hits"] == hits["mask"].sum() > 10


def test_a_volume_is_prepared_once_for_many_views_and_again_for_other_settings():
    volume = pss.Volume(np.fromfile(FUEL, np.uint8).reshape(64, 64, 64))
    first, _, stats = volume.render(iso=60, size=(32, 32), full_output=True)
    assert "gradients" in stats["seconds"]
    turned, _, stats = volume.render(iso=60, size=(32, 32), view=(90, 0), full_output=True)
    assert "gradients" not in stats["seconds"] and not np.array_equal(turned, first)
    _, _, stats = volume.extract(iso=60, full_output=True)
    assert "gradients" not in stats["seconds"]
    again, _, stats = volume.render(iso=61, size=(32, 32), full_output=True)
    assert "gradients" in stats["seconds"] and not np.array_equal(again, first)
    assert np.array_equal(volume.render(iso=60, size=(32, 32)), first)


def test_errors_about_the_data_name_the_file_as_the_cli_s_do(fuel, tmp_path):
    expected = cli_error("volume", FUEL, *RAW, "--iso", "1000", "-o", tmp_path / "x.png")
    with pytest.raises(pss.Error) as caught:
        fuel.render(iso=1000)
    assert str(caught.value) == expected
    with pytest.raises(pss.Error, match=r"^the iso-value 1000 lies outside the volume's values \[0, 255\]$"):
        pss.Volume(fuel.values).extract(iso=1000)


def test_read_volume_errors_are_the_cli_s(tmp_path):
    short = tmp_path / "short.raw"
    short.write_bytes(bytes(100))
    expected = cli_error("volume", short, "--dims", "8x8x8", "--iso", "1", "-o", tmp_path / "x.png")
    with pytest.raises(pss.Error) as caught:
        pss.read_volume(short, dims=(8, 8, 8))
    assert str(caught.value) == expected
