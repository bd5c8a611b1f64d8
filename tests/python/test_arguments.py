# Bad arguments: a pss.Error (a ValueError) with one line naming the argument, before any
# work, as the CLI's flags are refused.
import warnings

import numpy as np
import pytest

import pss
from conftest import BUNNY, cli_error

SOME = np.random.default_rng(1).random((300, 3), np.float32)


def test_errors_are_value_errors():
    assert issubclass(pss.Error, ValueError)


@pytest.mark.parametrize("points, message", [
    (np.zeros((5, 2)), r"^points: expected an array of shape \(N, 3\) \(got shape \(5, 2\)\)$"),
    (np.zeros(6), r"^points: expected an array of shape \(N, 3\) \(got shape \(6,\)\)$"),
    ([["a", "b", "c"]], r"^points: expected an array of real numbers$"),
    (np.array([[0, 0, 0], [1, np.nan, 0]]), r"^points: row 1 is not three finite numbers \(that fit a float\)$"),
    (np.array([[0, 0, 1e300]]), r"^points: row 0 is not three finite numbers \(that fit a float\)$"),
])
def test_points_that_are_not_finite_rows_of_three_are_refused(points, message):
    for call in (pss.estimate_h, pss.project, pss.render):
        with pytest.raises(pss.Error, match=message):
            call(points)


@pytest.mark.parametrize("arguments, message", [
    ({"h": float("nan")}, r"^h: expected a finite number > 0 \(got nan\)$"),
    ({"h": -1}, r"^h: expected a finite number > 0 \(got -1\)$"),
    ({"h": 1e-50}, r"^h: expected a finite number > 0 \(got 1e-50\)$"),
    ({"h": 1e-45}, r"^h: expected a finite number > 0 \(got 1e-45\)$"),
    ({"h": "0.1"}, r"^h: expected a finite number > 0 \(got '0.1'\)$"),
    ({"fov": 200}, r"^fov: expected a finite number from 1 to 170 \(got 200\)$"),
    ({"zoom": 0}, r"^zoom: expected a finite number from 0.001 to 1000 \(got 0\)$"),
    ({"size": (0, 10)}, r"^size: expected \(width, height\), two integers from 1 to 16384 \(got \(0, 10\)\)$"),
    ({"size": (10.5, 10)}, r"^size: expected \(width, height\)"),
    ({"size": (16384, 16384)}, r"at most 67108864 pixels"),
    ({"view": (0, 91)}, r"^the elevation must be from -90 to 90 \(got 91\)$"),
    ({"view": (float("inf"), 0)}, r"^view: expected \(azimuth, elevation\)"),
    ({"up": (0, 0, 0)}, r"^up must be a non-zero direction"),
    ({"iterations": 0}, r"^iterations: expected an integer from 1 to 32 \(got 0\)$"),
    ({"iterations": "many"}, r"^iterations: expected an integer from 1 to 32"),
    ({"secondary": "some"}, r"^secondary: expected one of 'full', 'paper' \(got 'some'\)$"),
    ({"support": "wide"}, r"^support: expected one of 'adaptive', 'global' \(got 'wide'\)$"),
    ({"surface": "rbf"}, r"^surface: expected one of 'mls', 'apss', 'rimls' \(got 'rbf'\)$"),
    ({"outliers": "drop"}, r"^outliers: expected one of 'set-aside', 'keep' \(got 'drop'\)$"),
    ({"borders": "none"}, r"^borders: expected one of 'auto', 'clip', 'extend' \(got 'none'\)$"),
    ({"backend": "tpu"}, r"^backend: expected one of 'auto', 'cpu', 'cuda' \(got 'tpu'\)$"),
    ({"shadows": 1}, r"^shadows: expected True or False \(got 1\)$"),
    ({"camera": {"eye": [0, 0, 1]}}, r"^camera: camera field \"forward\" is missing$"),
    ({"camera": {"eye": [0, 0, 1]}, "fov": 20}, r"^camera excludes fov"),
    ({"camera": {"eye": [0, float("nan"), 1]}}, r"^camera: holds a number that is not finite \(NaN or infinity\)$"),
    ({"normals": np.zeros((3, 3))}, r"^normals: expected one per point \(300\), got 3$"),
    ({"colors": np.zeros((3, 3))}, r"^colors: expected one per point \(300\), got 3$"),
    ({"colors": np.full((300, 3), 256)}, r"^colors: row 0 is not a colour \(integers from 0 to 255\)$"),
    ({"colors": np.full((300, 3), 1.5)}, r"^colors: row 0 is not a colour \(floats from 0 to 1\)$"),
])
def test_render_arguments_out_of_range_are_refused_naming_them(arguments, message):
    with pytest.raises(pss.Error, match=message):
        pss.render(SOME, **arguments)


def test_a_missing_or_malformed_file_gives_the_cli_s_message(tmp_path):
    for path in (tmp_path / "missing.ply", tmp_path / "cloud.laz"):
        expected = cli_error("render", path, "-o", tmp_path / "x.png")
        with pytest.raises(pss.Error) as caught:
            pss.read_points(path)
        assert str(caught.value) == expected
    bad = tmp_path / "camera.json"
    bad.write_text("{}")
    expected = cli_error("render", BUNNY, "--camera", bad, "-o", tmp_path / "x.png")
    with pytest.raises(pss.Error) as caught:
        pss.render(SOME, camera=bad)
    assert str(caught.value) == expected


def test_an_image_of_background_alone_comes_with_a_warning():
    _, _, stats = pss.render(SOME, size=(8, 8), full_output=True)
    away = dict(stats["camera"])  # the surface behind the camera
    away["forward"] = [-c for c in away["forward"]]
    away["right"] = [-c for c in away["right"]]
    with pytest.warns(RuntimeWarning, match=r"^no ray hit the surface"):
        _, hits, _ = pss.render(SOME, size=(8, 8), camera=away, full_output=True)
    assert not hits["mask"].any()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        pss.render(SOME, size=(8, 8))


def test_a_cloud_with_no_surface_anywhere_is_an_error_not_an_empty_image():
    for h in (1e-6, 1e-30):
        with pytest.raises(pss.Error, match=r"^no surface with h = .*h is likely too small"):
            pss.render(SOME, h=h, size=(8, 8))


def test_a_cloud_projected_nowhere_is_an_error_not_the_input_unmoved():
    for h in (1e-6, 1e-8, 1e-30):  # 1e-8 once sized the grid from an overflowed cell count
        with pytest.raises(pss.Error, match=r"^no point was projected with h = "):
            pss.project(SOME, h)


@pytest.mark.parametrize("arguments, message", [
    ({}, r"^choose the surface: iso=V or gradient=True$"),
    ({"iso": 1, "gradient": True}, r"^choose the surface: iso=V or gradient=True$"),
    ({"iso": 1, "threshold": 0.5}, r"^threshold applies to gradient surfaces only$"),
    ({"iso": 1, "h": 0.1}, r"^h: expected a finite number >= 0.5 \(got 0.1\)$"),
    ({"iso": 1, "k": 2}, r"^k: expected a finite number from 0.05 to 1 \(got 2\)$"),
    ({"iso": 1, "method": "corrector"}, r"^method: expected one of 'predictor', 'predictor-corrector'"),
])
def test_volume_arguments_out_of_range_are_refused_naming_them(arguments, message):
    volume = pss.Volume(np.zeros((4, 4, 4)))
    with pytest.raises(pss.Error, match=message):
        volume.render(**arguments)


def test_a_raw_volume_s_arguments_are_checked_and_named_as_python_names_them(tmp_path):
    raw = tmp_path / "v.raw"
    raw.write_bytes(bytes(8))
    for spacing in ((-1, 1, 1), (0, 1, 1)):  # a negative spacing once crashed the render
        with pytest.raises(pss.Error, match=r"^spacing: expected three positive numbers"):
            pss.read_volume(raw, dims=(2, 2, 2), spacing=spacing)
    with pytest.raises(pss.Error, match=r"^dims '-2x2x2': expected XxYxZ"):
        pss.read_volume(raw, dims=(-2, 2, 2))
    with pytest.raises(pss.Error, match=r"^type 'u1': "):
        pss.read_volume(raw, dims=(2, 2, 2), type="u1")
    with pytest.raises(pss.Error, match=r"needs dims"):
        pss.read_volume(raw)
    with pytest.raises(pss.Error, match=r"^spacing describes a raw file"):
        pss.read_volume(raw, spacing=(2, 2, 2))


def test_threads_are_a_count():
    with pytest.raises(pss.Error, match=r"^threads: expected a count from 0 \(every core\) to 1024$"):
        pss.set_threads(-1)
    pss.set_threads(1)
    one = pss.render(SOME, size=(16, 16))
    pss.set_threads(0)
    assert np.array_equal(pss.render(SOME, size=(16, 16)), one)


def test_progress_is_one_of_three_words():
    for bad in [None, 3, "loud"]:
        with pytest.raises(pss.Error, match=r"^progress: expected 'auto', 'always' or 'never'"):
            pss.set_progress(bad)
    pss.set_progress("never")


def test_a_camera_dict_may_hold_numpy_arrays():
    _, _, stats = pss.render(SOME, size=(16, 16), view=(20, 10), full_output=True)
    camera = {key: np.array(value) for key, value in stats["camera"].items()}
    assert np.array_equal(pss.render(SOME, size=(16, 16), camera=camera), pss.render(SOME, size=(16, 16), view=(20, 10)))


@pytest.mark.parametrize("values, spacing, message", [
    (np.zeros((4, 4)), (1, 1, 1), r"^values: expected a 3-D array of real numbers indexed \[z, y, x\] \(got 2-D float64\)$"),
    (np.zeros((2, 2, 2), complex), (1, 1, 1),
     r"^values: expected a 3-D array of real numbers indexed \[z, y, x\] \(got 3-D complex128\)$"),
    (np.full((2, 2, 2), np.nan), (1, 1, 1), r"^values\[0, 0, 0\] is not a finite number$"),
    (np.pad(np.full((1, 1, 1), np.inf), ((2, 0), (1, 2), (3, 0))), (1, 1, 1), r"^values\[2, 1, 3\] is not a finite number$"),
    (np.zeros((0, 2, 2)), (1, 1, 1), r"^values: the array is empty$"),
    (np.zeros((2, 2, 2)), (1, 0, 1), r"^spacing: expected three positive numbers"),
    (np.zeros((2, 2, 2)), (1, 1), r"^spacing: expected three numbers"),
])
def test_volumes_that_are_not_finite_3d_arrays_are_refused(values, spacing, message):
    with pytest.raises(pss.Error, match=message):
        pss.Volume(values, spacing=spacing)


def test_arguments_of_the_wrong_type_raise_pss_errors():
    # A new user's trial: these raised TypeError, or took complex numbers' real parts with a
    # warning, where the module promises pss.Error for every problem.
    for bad in (2.5, "a", None):
        with pytest.raises(pss.Error, match=r"^threads: expected a count from 0 \(every core\) to 1024 \(got "):
            pss.set_threads(bad)
    pss.set_threads(0)
    for call in (pss.read_points, pss.read_volume):
        with pytest.raises(pss.Error, match=r"^path: expected a file name \(got 5\)$"):
            call(5)
    with pytest.raises(pss.Error, match=r"^points: expected an array of real numbers$"):
        pss.project(SOME.astype(np.complex64))
