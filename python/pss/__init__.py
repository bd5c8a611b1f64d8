"""pss: point set surfaces of point clouds and volumes, on the CPU or the GPU.

The moving-least-squares surface of a point cloud or a volume (Schmitt et al.,
"Hardware-accelerated extraction and rendering of point set surfaces"), from NumPy:

    points, normals, status = pss.project(points)          # every point onto the surface
    vertices, normals, faces = pss.mesh(points)            # a triangle mesh of the surface
    image = pss.render(points, view=(30, 20))              # (H, W, 3) uint8, ray traced
    volume = pss.Volume(values, spacing=(1, 1, 1))         # values indexed [z, y, x]
    image = volume.render(iso=100)
    points, normals = volume.extract(iso=100)

Arrays come in as any array-like of numbers and are converted once to float32 (the
surface's grid reorders them anyway); results are NumPy arrays that own the library's
memory, without a copy. Points far from zero for their extent (a georeferenced scan at
4e6 m) are taken about an origin near their centre, in double, so that float32 keeps
their detail: positions then come back as float64 world coordinates. The work runs
without the GIL. Every problem raises pss.Error (a ValueError) with the one-line message
the `pss` command prints. Units are the data's:
h, rho, b and epsilon of point clouds in its coordinates; the volume's h and error in voxels.
"""

import json as _json
import numbers as _numbers
import os as _os

from . import _pss
from ._pss import Error, Volume

__all__ = ["Error", "Volume", "estimate_h", "mesh", "project", "read_points", "read_volume", "render", "set_progress",
           "set_threads"]
__version__ = "0.1.0"



def _path(value, name):
    """A file name (str, bytes or os.PathLike) as a str; pss.Error for anything else."""
    if not isinstance(value, (str, bytes, _os.PathLike)):
        raise Error("%s: expected a file name (got %r)" % (name, value))
    return _os.fsdecode(value)


def set_progress(mode):
    """Whether the work shows its progress on stderr, as `pss --progress`: 'never' (the
    default: a library call prints nothing), 'auto' (a bar while stderr is a terminal) or
    'always' (and lines a log can read elsewhere)."""
    if not isinstance(mode, str):
        raise Error("progress: expected 'auto', 'always' or 'never' (got %r)" % (mode,))
    _pss.set_progress(mode)

def _plain(value):
    """NumPy arrays and scalars in a camera dict, as JSON lists and numbers."""
    if hasattr(value, "tolist"):
        return value.tolist()
    raise Error("camera: %r is not a number or a list of numbers" % (value,))


def set_threads(count):
    """The CPU backend's threads, as `pss --threads`: 0 (the default) uses every core,
    as OpenMP's OMP_NUM_THREADS says."""
    if isinstance(count, bool) or not isinstance(count, _numbers.Integral):
        raise Error("threads: expected a count from 0 (every core) to 1024 (got %r)" % (count,))
    _pss.set_threads(int(count))


_CAMERA_ARGS = ("view", "fov", "look_at", "up", "distance", "zoom", "roll")


def _frame_options(size, view, fov, look_at, up, distance, zoom, roll, camera, shadows, reflections,
                   reflectivity, transparent, backend, full_output):
    given = [name for name, value in zip(_CAMERA_ARGS, (view, fov, look_at, up, distance, zoom, roll))
             if value is not None]
    if camera is not None and given:
        raise Error("camera excludes " + ", ".join(given) + ": the camera says where the eye is")
    options = {
        "size": size, "view": view, "fov": fov, "look_at": look_at, "up": up, "distance": distance,
        "zoom": zoom, "roll": roll, "camera_json": None, "camera_file": None, "shadows": shadows, "reflections": reflections,
        "reflectivity": reflectivity, "transparent": transparent, "backend": backend, "full_output": full_output,
    }
    if isinstance(camera, (str, bytes, _os.PathLike)):
        options["camera_file"] = _path(camera, "camera")
    elif camera is not None:
        try:
            options["camera_json"] = _json.dumps(camera, default=_plain, allow_nan=False)
        except ValueError:  # JSON has no NaN: said here, not as "not a JSON object" after
            raise Error("camera: holds a number that is not finite (NaN or infinity)") from None
    return options


_FRAME_DOC = """
    Camera (as `pss render`'s flags; each left at None keeps the default view, which frames
    the object's bounding sphere):
      size=(width, height) in pixels (default {size});
      view=(azimuth, elevation) in degrees about the look-at point (default (0, 0): from +z
        with the default up; with another up, from the side across it, -y for up = +z);
      fov: the vertical field of view in degrees (default {fov:g});
      look_at=(x, y, z): the point orbited (default: the centre of the object's box);
      up=(x, y, z): the world's up (default (0, 1, 0)); distance: of the eye (then fov zooms);
      zoom: divides the distance; roll: degrees about the view direction;
      camera: instead of those, a camera dict (the 'camera' of a full_output's stats, or of a
        --stats file) or the path of a camera JSON file.
    Shading: shadows, reflections (one mirror bounce), reflectivity (default {reflectivity:g}),
      transparent (an (H, W, 4) image with alpha 0 where the ray missed).
    backend: 'auto' (the GPU when this build has one and a device is present), 'cpu' or 'cuda'.
    Returns the (H, W, 3) uint8 sRGB image, row 0 at the top; with full_output=True the tuple
    (image, hits, stats): hits a dict of per-pixel arrays 'mask' (bool), 'depth' (the primary
    ray's distance, inf where it missed), 'iterations', 'points' (NaN where missed; float64
    world coordinates for a cloud far from zero) and
    'normals' (facing the camera, 0 where missed); stats the counts, times and camera that
    `pss ... --stats` writes.
""".format(**_pss.frame_defaults)


def estimate_h(points):
    """The Gaussian width h that `pss info` suggests for these (N, 3) points: the median
    distance to the 15th nearest sample (a ball of radius 2h then holds about 60), or three
    times the samples' noise about their surface where that is larger."""
    return _pss.estimate_h(points)


def project(points, h=None, *, normals=None, surface="rimls", outliers="set-aside", method="mls", rho=None, support=None,
            iterations=None, backend="auto", full_output=False):
    """Move every point onto the point set surface, as `pss project`.

    points: (N, 3). h: the Gaussian width (default: estimate_h(points)); rho: the
    neighbourhood radius (default 2h); support: 'adaptive' (each sample's width h, or wider
    where the distance to its 15th nearest neighbour is over 4/3 of the median, and at least
    3 times the samples' noise where they are noisy; lengths given at h scale with it) or 'global' (h for every sample, as the paper); default adaptive,
    global when h is given; method: 'mls' (the paper's Eq. 2) or 'wls' (Eq. 1);
    iterations: the most MLS alternations (default 4; apss, rimls: 8 fits); normals: (N, 3) hints of the side each point's
    normal faces (without them the normals are oriented consistently over the cloud).
    surface: 'rimls' (robust implicit MLS: keeps sharp creases; the default), 'mls' (the
    paper's) or 'apss' (algebraic spheres fitted to the points and their normals), as the CLI's
    --surface; apss and rimls fit the given normals, or estimate them when none are given
    (the CLI's --normals estimate); with them, iterations counts the fits moved to the point.
    outliers: 'set-aside' (points off their neighbours' plane by more than the cloud's noise
    allows, or with fewer than 3 neighbours, are not samples of the surface, though projected
    onto it like the rest) or 'keep', as the CLI's --outliers.

    Returns (points, normals, status): (N, 3) float32 (float64 for points far from zero, see
    above), (N, 3) float32 unit normals, and (N,)
    int32 status: 0 converged, 1 not converged within `iterations`, 2 too few neighbours
    within rho (point and normal unchanged), 3 degenerate normal (neighbours on a line).
    With full_output=True a fourth, the stats dict: the parameters used ('params': h, rho,
    support, surface, normals 'file'/'estimated'/'none'), 'status' counts, 'outliers_set_aside',
    'points_merged', 'normals_turned', 'file_normals_off' and the phases' times, as
    `pss project --stats` writes them.
    """
    return _pss.project(points, {"normals": normals, "surface": surface, "outliers": outliers, "h": h, "method": method,
                                 "rho": rho,
                                 "support": support, "iterations": iterations, "backend": backend,
                                 "full_output": full_output})


def mesh(points, h=None, *, normals=None, surface="rimls", outliers="set-aside", rho=None, support=None, cell=None,
         borders="auto", iterations=None, crease_angle=30, backend="auto", full_output=False):
    """A triangle mesh of the point set surface, as `pss mesh`: marching tetrahedra over the
    cubes near the points, every vertex on the surface with its normal.

    points, h, normals, surface, outliers, rho, support, iterations: as for project (the
    normals given, or estimated and oriented, say which side is out). cell: the cubes' side
    and the size the triangles grow to (default: cubes of the least h/2, triangles grown to
    each place's h/2, the local spacing; smaller gives more, smaller triangles).
    borders: 'clip' (the mesh ends at the points' hull), 'extend' (on as far as the projection
    reaches, about rho past the last points) or 'auto' (extend: an array of points is a scan's,
    as the CLI's auto for files without faces). crease_angle: degrees; where the normals within
    a cube differ by more than this and the surface has a sharp crease there (rimls keeps a
    box's edges), a vertex is put on the crease instead of cutting it off; 180: never.

    Returns (vertices, normals, faces): (V, 3) float32 (float64 for points far from zero,
    see above), (V, 3) float32 unit normals of the surface, and (T, 3) int32 vertex indices,
    counter-clockwise seen from outside. Closed where the surface is closed, manifold always.
    With full_output=True a fourth, the stats dict: project's, with the cell, the mesh's shape
    ('mesh': vertices, triangles, edges, components, boundary_edges, non-manifold edges and
    vertices, euler_characteristic, watertight, manifold), the march's counts ('band') and
    'turned_outward', as `pss mesh --stats` writes them.
    """
    return _pss.mesh(points, {"normals": normals, "surface": surface, "outliers": outliers, "h": h, "rho": rho,
                              "support": support, "cell": cell, "borders": borders, "iterations": iterations,
                              "crease_angle": crease_angle, "backend": backend, "full_output": full_output})


def render(points, h=None, *, normals=None, colors=None, surface="rimls", outliers="set-aside", rho=None, support=None,
           b=None, epsilon=None, ball_spacing=None,
           iterations=2, candidates=32, secondary="full", borders="extend",
           size=None, view=None, fov=None, look_at=None, up=None, distance=None,
           zoom=None, roll=None, camera=None, shadows=False, reflections=False, reflectivity=None,
           transparent=False, backend="auto", full_output=False):
    """Ray trace the point set surface of (N, 3) points (the paper's section 5.2), as `pss render`.

    Surface: h (default: estimated from the spacing), rho (default 2h), support ('adaptive' or
    'global', as for project), b: the radius of the balls around the local polynomials
    (default h, at most rho), epsilon: a hit's tolerance (default 1e-3 h),
    ball_spacing (0 to b, default b/2; 0 keeps one polynomial per sample, as the paper),
    iterations: projections per ray candidate, 1 to 32 or 'auto' (default 2, the paper's),
    candidates: ball intersections a ray tries before it is a miss, 1 to 1024 (default 32),
    secondary: 'full' or 'paper' (the paper's rough secondary hits); normals: optional hints.
    borders: 'extend' (the surface runs on past the last points, as the paper's and as `pss
    render` does for scans), 'clip' (it ends at them: what `pss render --borders auto` does
    for a mesh's vertices, whose faces the points cannot tell) or 'auto' (extend, as for mesh).
    surface: 'mls', 'apss' or 'rimls', as for project (the given normals fitted, or estimated);
    outliers: 'set-aside' or 'keep', as for project (full_output's stats: outliers_set_aside).
    Where noise widens the supports their samples are merged (full_output's stats:
    points_merged; none with support='global').
    colors: (N, 3) sRGB colours of the points (uint8 0..255, or floats 0..1) to shade with, as
    `pss render --color`: averaged at each hit with the projection's weights, in linear light.
    """
    options = _frame_options(size, view, fov, look_at, up, distance, zoom, roll, camera, shadows, reflections,
                             reflectivity, transparent, backend, full_output)
    options.update({"normals": normals, "colors": colors, "surface": surface, "outliers": outliers, "h": h, "rho": rho,
                    "support": support,
                    "b": b,
                    "epsilon": epsilon, "ball_spacing": ball_spacing, "iterations": iterations, "candidates": candidates,
                    "secondary": secondary, "borders": borders})
    return _pss.render(points, options)


render.__doc__ += _FRAME_DOC


def read_points(path):
    """The point cloud of a file (.ply, .xyz/.txt/.pts/.pwn, .obj, .off, .stl, .pcd, .las), as
    the CLI reads it: (points, normals, colors) with (N, 3) float32 points (float64 world
    coordinates for a cloud far from zero, see above), (N, 3) float32 normals or None, (N, 3)
    uint8 colours or None."""
    return _pss.read_points(_path(path, "path"))


def read_volume(path, *, dims=None, type="uint8", spacing=None, endian="little", skip=0):
    """A pss.Volume from a file: .nrrd/.nhdr, .mhd/.mha, .nii/.nii.gz (whose header gives the
    spacing and origin), or a raw file described by dims=(nx, ny, nz) (x fastest in the file),
    type ('int8', 'uint8', 'int16', 'uint16', 'int32', 'uint32', 'float32', 'float64'),
    spacing (default (1, 1, 1)), endian ('little' or 'big') and skip (header bytes), as
    `pss volume`'s raw flags. Errors about its data then name the file."""
    if dims is None and spacing is not None:
        raise Error("spacing describes a raw file, with dims; a file with a header gives its own")
    return _pss.read_volume(_path(path, "path"), {"dims": dims, "type": type, "spacing": spacing,
                                                 "endian": endian, "skip": skip})


_SURFACE_DOC = """
    The surface (paper section 4): iso=V (the iso-surface, theta1 weights) or gradient=True
    (high gradient magnitude, theta2; threshold: (|grad f|/max)^2 above it is projected,
    default 0.5). In voxels u = (sx sy sz)^(1/3): h (default {h:g}), k: the marching step
    b = k h (default {k:g}), radius: the neighbourhood in units of h (default {radius:g}),
    error: epsilon (default {error:g}), smoothing: theta1's width (default {smoothing:g});
    alpha: alpha1 of the corrector (default {alpha:g}).
""".format(**_pss.volume_defaults)


def _surface_options(iso, gradient, method, h, k, radius, alpha, error, smoothing, threshold, backend):
    return {"iso": iso, "gradient": gradient, "method": method, "h": h, "k": k, "radius": radius, "alpha": alpha,
            "error": error, "smoothing": smoothing, "threshold": threshold, "backend": backend}


def _volume_render(self, iso=None, *, gradient=False, method="predictor-corrector", h=None, k=None, radius=None,
                   alpha=None, error=None, smoothing=None, threshold=None, size=None, view=None, fov=None,
                   look_at=None, up=None, distance=None, zoom=None, roll=None, camera=None, shadows=False,
                   reflections=False, reflectivity=None, transparent=False, backend="auto", full_output=False):
    options = _frame_options(size, view, fov, look_at, up, distance, zoom, roll, camera, shadows, reflections,
                             reflectivity, transparent, backend, full_output)
    options.update(_surface_options(iso, gradient, method, h, k, radius, alpha, error, smoothing, threshold, backend))
    return self._render(options)


def _volume_extract(self, iso=None, *, gradient=False, h=None, k=None, radius=None, alpha=None, error=None,
                    smoothing=None, threshold=None, backend="auto", full_output=False):
    options = _surface_options(iso, gradient, "predictor-corrector", h, k, radius, alpha, error, smoothing,
                               threshold, backend)
    options["full_output"] = full_output
    return self._extract(options)


def _volume_mesh(self, iso=None, *, gradient=False, method="predictor-corrector", h=None, radius=None, alpha=None,
                 error=None, smoothing=None, threshold=None, cell=None, backend="auto"):
    options = _surface_options(iso, gradient, method, h, None, radius, alpha, error, smoothing, threshold, backend)
    options["cell"] = cell
    return self._mesh(options)


_volume_render.__name__ = "render"
_volume_render.__doc__ = """Extract and render the volume's point set surface along every
    primary ray (the paper's section 5.1), as `pss volume`. method: 'predictor-corrector'
    (the default) or 'predictor'.
    """ + _SURFACE_DOC + _FRAME_DOC
_volume_extract.__name__ = "extract"
_volume_extract.__doc__ = """The volume's point set surface as an oriented point set, about
    one point per step b (predictor-corrector), as `pss extract`: (points, normals), both
    (N, 3) float32, normals along the gradient (toward higher values: inward where the
    object is brighter than its surroundings); with full_output=True also the stats dict.
    """ + _SURFACE_DOC
_volume_mesh.__name__ = "mesh"
_volume_mesh.__doc__ = """A triangle mesh of the volume's point set surface, as `pss mesh` of a
    volume: marching tetrahedra over the cubes near the cells the surface crosses, every
    vertex a root of the distance to the surface's projection on its edge. method:
    'predictor-corrector' (the default) or 'predictor'; cell: the cubes' side in world units
    (default the voxel u). Returns (vertices, normals, faces): (V, 3) float32, (V, 3) float32
    unit normals of the surface, and (T, 3) int32 vertex indices, counter-clockwise seen
    from outside, outside being towards lower values (the brighter material is inside).
    Closed where the surface is, open where the volume's box cuts it; manifold always.
    """ + _SURFACE_DOC.replace(" k: the marching step\n    b = k h (default {:g}),".format(_pss.volume_defaults["k"]), "")
Volume.render = _volume_render
Volume.mesh = _volume_mesh
Volume.extract = _volume_extract
Volume.__doc__ = """Volume(values, spacing=(1, 1, 1), origin=(0, 0, 0)): a scalar volume on a
    uniform grid. values: a 3-D array indexed [z, y, x] (x fastest, as SimpleITK and VTK give
    them), copied once as float32; values[k, j, i] sits at origin + (i sx, j sy, k sz).
    Properties: values (read-only float32 view), spacing, origin, source (the file it was
    read from, or ''). A render or extract prepares the volume for its surface settings
    (gradients, weights and gradient directions: about eight times the values' memory) and
    keeps that preparation for the next call with the same settings, so that views after the
    first cost only their rays."""
