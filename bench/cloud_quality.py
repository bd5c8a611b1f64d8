#!/usr/bin/python3
"""How well `pss render` shows the surface of real point clouds: holes, extra surface, normal errors.

Usage (Debian python3 with python3-numpy, python3-scipy):
  cloud_quality.py --pss PSS [--out results.json] [--clouds a,b,...] [--label NAME]
                   [--scan-holes scan_holes.py] [--truth MESH] [-- EXTRA_PSS_FLAGS...]
Each cloud is rendered at 384x384 from two views (the default and --view 60,30) with
  pss render CLOUD --size 384x384 [--view 60,30] --hits hits.ply --stats stats.json EXTRA_PSS_FLAGS
in a temporary folder that is removed afterwards. --clouds takes paths or names of the default set
(e.g. blade,radar). It prints a table and writes all numbers as JSON (--out, default
cloud_quality.json).

What the numbers mean (all per view, in pixels of the 384x384 image):
  scans (no mesh; .xyz .las .pwn .ply):
    holes %   holes where the data are, by shared/tools/scan_holes.py: the share of the pixels
              well inside the data's footprint (points drawn as tangent discs) where pss has no hit,
              or only one more than 3 disc radii behind the data.
    floor %   for a PLY scan with faces (the bunny, the dragon: the points are the mesh's vertices),
              the same measure of the mesh itself cast through pss's camera: what the true surface
              scores, since discs tangent near a convex silhouette reach past it.
  meshes (.off: pss renders the vertices; the faces are the ground truth, ray-cast per pixel with
  pss's own camera from the stats JSON, in the same frame, pss's 'origin' taken off both):
    holes %   mesh pixels where pss has no hit, or a hit more than TOL farther along the ray than
              the mesh (the surface seen through a hole), per 100 mesh pixels.
    extra %   pixels where pss hits and the mesh has no surface, per 100 mesh pixels.
    normal °  mean angle between pss's normal and the hit face's normal, up to sign, over the pixels
              where both hit within TOL of each other.
    >10° %    share of those pixels with a normal error over 10 degrees.
  --truth MESH (an OFF, or a PLY with faces) takes that mesh as every cloud's truth: clouds made
  from a mesh's vertices (thinned, made uneven, noisy) measured against the surface they came from.
  (JSON only: 'front_pct', mesh pixels where pss's hit lies more than TOL in front of the mesh.)
  TOL is 1 % of the diagonal of the mesh's bounding box.
  frame s     the frame time pss reports (stats 'frame_seconds'); hits: pss's primary hits.
"""
import argparse, json, os, subprocess, sys, tempfile
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHARED = os.path.join(os.path.dirname(ROOT), 'shared')  # the project's shared/ beside the checkout
CLOUDS = [os.path.join(SHARED, 'data/clouds', c) for c in ('radar.xyz', 'urban.las', 'hippo1.ply', 'cube.pwn')] + \
         [os.path.join(ROOT, 'data/bun_zipper.ply'), os.path.join(SHARED, 'data/dragon_21790.ply')] + \
         [os.path.join(SHARED, 'data/clouds', c) for c in ('cylinder_locally_refined.off', 'blade.off')]
VIEWS = {'default': [], '60,30': ['--view', '60,30']}
SIZE = 384


def read_off(path):
    """Vertices and triangles (polygons split as fans) of an OFF file."""
    tok = ' '.join(l.split('#')[0] for l in open(path)).split()
    assert tok[0].endswith('OFF'), path
    nv, nf = int(tok[1]), int(tok[2]); i = 4
    v = np.array(tok[i:i + 3 * nv], float).reshape(nv, 3); i += 3 * nv
    tris = []
    for _ in range(nf):
        n = int(tok[i]); f = [int(t) for t in tok[i + 1:i + 1 + n]]; i += 1 + n
        tris += [(f[0], f[k], f[k + 1]) for k in range(1, n - 1)]
    return v, np.array(tris, np.int64)


def read_ply_mesh(path):
    """Vertices and triangles (polygons split as fans) of a PLY mesh, ASCII or binary
    little-endian, with any vertex properties (x, y, z taken) and a face list of indices."""
    b = open(path, 'rb').read(); end = b.index(b'end_header') + len(b'end_header')
    end += 2 if b[end:end + 2] == b'\r\n' else 1
    elements = []  # (name, count, [(property, type, list count type or None)])
    for line in b[:end].decode('ascii', 'replace').splitlines():
        w = line.split()
        if w[:1] == ['element']: elements.append((w[1], int(w[2]), []))
        elif w[:2] == ['property', 'list']: elements[-1][2].append((w[4], w[3], w[2]))
        elif w[:1] == ['property']: elements[-1][2].append((w[2], w[1], None))
    tm = {'char': 'i1', 'int8': 'i1', 'uchar': 'u1', 'uint8': 'u1', 'short': 'i2', 'int16': 'i2', 'ushort': 'u2',
          'uint16': 'u2', 'int': 'i4', 'int32': 'i4', 'uint': 'u4', 'uint32': 'u4', 'float': 'f4',
          'float32': 'f4', 'double': 'f8', 'float64': 'f8'}
    ascii = b'format ascii' in b[:end]
    tok = b[end:].split() if ascii else None; at = end; ti = 0; v = None; polys = []
    for name, count, props in elements:
        if not ascii and all(lt is None for _, _, lt in props):  # fixed-size records
            dt = np.dtype([(pn, '<' + tm[t]) for pn, t, _ in props])
            rec = np.frombuffer(b, dt, count, at); at += dt.itemsize * count
            if name == 'vertex': v = np.stack([rec[c].astype(float) for c in 'xyz'], 1)
            continue
        rows = []
        for _ in range(count):
            row = {}
            for pn, t, lt in props:
                if ascii:
                    if lt is None: row[pn] = float(tok[ti]); ti += 1
                    else: n = int(tok[ti]); row[pn] = [int(x) for x in tok[ti + 1:ti + 1 + n]]; ti += 1 + n
                else:
                    if lt is None: row[pn] = np.frombuffer(b, '<' + tm[t], 1, at)[0]; at += int(tm[t][1])
                    else:
                        n = int(np.frombuffer(b, '<' + tm[lt], 1, at)[0]); at += int(tm[lt][1])
                        row[pn] = np.frombuffer(b, '<' + tm[t], n, at).tolist(); at += n * int(tm[t][1])
            rows.append(row)
        if name == 'vertex': v = np.array([[r['x'], r['y'], r['z']] for r in rows], float)
        if name == 'face': polys = [r.get('vertex_indices', r.get('vertex_index')) for r in rows]
    tris = [(f[0], f[k], f[k + 1]) for f in polys for k in range(1, len(f) - 1)]
    assert v is not None and tris, f'{path}: no vertices or no faces'
    return v, np.array(tris, np.int64)


def read_mesh(path):
    return read_ply_mesh(path) if path.lower().endswith('.ply') else read_off(path)


def camera(st):
    """Eye, forward, right, up, tan(fov/2) of the stats JSON's camera."""
    cam = st['camera']; eye, fw, up = (np.array(cam[k], float) for k in ('eye', 'forward', 'up'))
    return eye, fw, np.cross(fw, up), up, cam['tan_half_fov']


def cast_mesh(v, tris, st):
    """Per pixel, the distance along its ray (pss's convention, as scan_holes.py) to the first
    triangle (inf: none) and that triangle's unit normal: Moeller-Trumbore on each triangle's
    box of pixels. (Debian's open3d 0.16 RaycastingScene found no hits at all here.)"""
    W, H = st['width'], st['height']; eye, fw, right, up, th = camera(st)
    yy, xx = np.mgrid[0:H, 0:W]
    sx = (2.0 * (xx + 0.5) / W - 1.0) * th * W / H; sy = (1.0 - 2.0 * (yy + 0.5) / H) * th
    d = fw + sx[..., None] * right + sy[..., None] * up; d /= np.linalg.norm(d, axis=-1, keepdims=True)
    p = v - eye; z = p @ fw
    with np.errstate(divide='ignore', invalid='ignore'):
        px = (p @ right / (z * th) * H / W + 1) * 0.5 * W - 0.5; py = (1 - p @ up / (z * th)) * 0.5 * H - 0.5
    t = np.full((H, W), np.inf); prim = np.zeros((H, W), np.int64)
    for k, tri in enumerate(tris):
        if (z[tri] <= 0).any(): continue  # (none of the test views have the eye inside the mesh's box)
        x0, x1 = max(int(px[tri].min()), 0), min(int(px[tri].max()) + 2, W)
        y0, y1 = max(int(py[tri].min()), 0), min(int(py[tri].max()) + 2, H)
        if x0 >= x1 or y0 >= y1: continue
        a, b, c = p[tri]; e1, e2 = b - a, c - a; r = d[y0:y1, x0:x1]
        pv = np.cross(r, e2); det = pv @ e1; q = np.cross(-a, e1)
        with np.errstate(divide='ignore', invalid='ignore'):
            u = (pv @ -a) / det; w = (r @ q) / det; tt = (e2 @ q) / det
        tb = t[y0:y1, x0:x1]; m = (u >= 0) & (w >= 0) & (u + w <= 1) & (tt > 0) & (tt < tb)
        tb[m] = tt[m]; prim[y0:y1, x0:x1][m] = k
    fn = np.cross(v[tris[:, 1]] - v[tris[:, 0]], v[tris[:, 2]] - v[tris[:, 0]])
    fn /= np.maximum(np.linalg.norm(fn, axis=1, keepdims=True), 1e-300)
    return eye, t, fn[prim]


def read_hits(path, W, H):
    """pss's hits as images: distance-ready positions (H, W, 3), normals, and a mask."""
    b = open(path, 'rb').read(); h = b[:b.index(b'end_header\n') + 11].decode()
    n = int(h.split('element vertex ')[1].split()[0])
    tm = {'float': 'f4', 'double': 'f8', 'int': 'i4', 'uint': 'u4', 'uchar': 'u1', 'short': 'i2'}
    props = [(l.split()[2], tm[l.split()[1]]) for l in h.splitlines() if l.startswith('property')]
    assert 'binary_little_endian' in h, 'pss writes binary little-endian hits'
    rec = np.frombuffer(b, np.dtype([(nm, '<' + t) for nm, t in props]), n, len(h))
    pos = np.zeros((H, W, 3)); nrm = np.zeros((H, W, 3)); mask = np.zeros((H, W), bool)
    px, py = rec['px'].astype(int).clip(0, W - 1), rec['py'].astype(int).clip(0, H - 1)
    pos[py, px] = np.stack([rec[c] for c in 'xyz'], 1); mask[py, px] = True
    nrm[py, px] = np.stack([rec['n' + c] for c in 'xyz'], 1)
    return pos, nrm, mask


def mesh_quality(mesh, st, hits):
    org = np.array(st.get('origin', [0, 0, 0]), float)  # compare in pss's shifted frame
    v, tris = read_mesh(mesh); v = v - org
    st = dict(st, camera=dict(st['camera'], eye=list(np.array(st['camera']['eye']) - org)))
    eye, tm, nm = cast_mesh(v, tris, st)
    pos, npss, hp = read_hits(hits, st['width'], st['height'])
    tol = 0.01 * np.linalg.norm(v.max(0) - v.min(0))
    tp = np.linalg.norm(pos - org - eye, axis=-1)
    mesh = np.isfinite(tm); nmesh = max(1, mesh.sum())
    behind = hp & mesh & (tp > tm + tol); front = hp & mesh & (tp < tm - tol)
    both = hp & mesh & ~behind & ~front
    cosn = np.abs((nm * npss).sum(-1)) / np.maximum(np.linalg.norm(npss, axis=-1), 1e-30)
    ang = np.degrees(np.arccos(np.clip(cosn[both], 0, 1)))
    return dict(holes_pct=100.0 * ((mesh & ~hp) | behind).sum() / nmesh,
                extra_pct=100.0 * (hp & ~mesh).sum() / nmesh, front_pct=100.0 * front.sum() / nmesh,
                normal_mean_deg=float(ang.mean()) if ang.size else None,
                normal_over10_pct=100.0 * (ang > 10).mean() if ang.size else None,
                mesh_pixels=int(mesh.sum()), tolerance=float(tol))


def has_faces(path):
    """Whether a PLY declares faces: a scan kept with the mesh its points are the vertices of."""
    if not path.lower().endswith('.ply'): return False
    head = open(path, 'rb').read(4096).split(b'end_header')[0]
    return any(l.split()[:2] == [b'element', b'face'] and int(l.split()[2]) > 0 for l in head.splitlines())


def write_mesh_hits(mesh, st, path):
    """The mesh's first hit per pixel, through pss's camera, as a hits PLY like pss's (px, py, x, y, z)."""
    org = np.array(st.get('origin', [0, 0, 0]), float)
    v, tris = read_mesh(mesh)
    shifted = dict(st, camera=dict(st['camera'], eye=list(np.array(st['camera']['eye']) - org)))
    eye, t, _ = cast_mesh(v - org, tris, shifted)
    W, H = st['width'], st['height']; _, fw, right, up, th = camera(st)
    yy, xx = np.mgrid[0:H, 0:W]
    sx = (2.0 * (xx + 0.5) / W - 1.0) * th * W / H; sy = (1.0 - 2.0 * (yy + 0.5) / H) * th
    d = fw + sx[..., None] * right + sy[..., None] * up; d /= np.linalg.norm(d, axis=-1, keepdims=True)
    m = np.isfinite(t); p = eye + org + t[m][:, None] * d[m]
    rec = np.zeros(int(m.sum()), [(c, '<f8') for c in ('px', 'py', 'x', 'y', 'z')])
    rec['px'], rec['py'] = xx[m], yy[m]; rec['x'], rec['y'], rec['z'] = p.T
    head = f'ply\nformat binary_little_endian 1.0\nelement vertex {len(rec)}\n' + \
        ''.join(f'property double {c}\n' for c in ('px', 'py', 'x', 'y', 'z')) + 'end_header\n'
    with open(path, 'wb') as f:
        f.write(head.encode()); f.write(rec.tobytes())


def scan_quality(cloud, stats, hits, scan_holes):
    """scan_holes.py's holes where the data are; for a scan kept with its mesh, also the same
    measure of that mesh ('floor_pct'): the true surface's own score, since its silhouettes lie
    inside the discs' union (a disc tangent near a convex silhouette reaches past it)."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(scan_holes)))
    import scan_holes as sh
    share = lambda inner, good: 100.0 * (inner & ~good).sum() / max(1, inner.sum())
    inner, good, _ = sh.splat_holes(cloud, stats, hits)
    row = dict(holes_pct=share(inner, good), data_pixels=int(inner.sum()))
    if has_faces(cloud):
        mesh_hits = os.path.join(os.path.dirname(hits), 'mesh_hits.ply')
        write_mesh_hits(cloud, json.load(open(stats)), mesh_hits)
        row['floor_pct'] = share(*sh.splat_holes(cloud, stats, mesh_hits)[:2])
    return row


def main():
    argv = sys.argv[1:]; extra = argv[argv.index('--') + 1:] if '--' in argv else []
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--pss', required=True); ap.add_argument('--out', default='cloud_quality.json')
    ap.add_argument('--clouds'); ap.add_argument('--label', default=' '.join(extra) or 'default')
    ap.add_argument('--scan-holes', default=os.path.join(SHARED, 'tools/scan_holes.py'))
    ap.add_argument('--truth', help='a mesh (OFF or PLY with faces) that every cloud is compared with')
    a = ap.parse_args(argv[:argv.index('--')] if '--' in argv else argv)
    clouds = CLOUDS
    if a.clouds:
        byname = {os.path.splitext(os.path.basename(c))[0]: c for c in CLOUDS}
        clouds = [c if os.path.exists(c) else byname.get(c) or ap.error(f'no cloud {c}') for c in a.clouds.split(',')]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for cloud in clouds:
            for view, vflags in VIEWS.items():
                stats, hits = os.path.join(tmp, 'stats.json'), os.path.join(tmp, 'hits.ply')
                cmd = [a.pss, 'render', cloud, '-o', os.path.join(tmp, 'img.png'), '--size', f'{SIZE}x{SIZE}',
                       '--hits', hits, '--stats', stats, '--progress', 'never'] + vflags + extra
                r = subprocess.run(cmd, capture_output=True, text=True)
                row = dict(cloud=os.path.basename(cloud), path=cloud, view=view, command=cmd)
                if r.returncode != 0:
                    row['error'] = r.stderr.strip()[-500:]; rows.append(row)
                    print(f'{row["cloud"]} {view}: pss failed: {row["error"]}', file=sys.stderr); continue
                st = json.load(open(stats))
                row.update(frame_seconds=st['frame_seconds'], hits=st['hits'], h=st['params']['h'])
                truth = a.truth or (cloud if cloud.lower().endswith('.off') else None)
                row.update(mesh_quality(truth, st, hits) if truth else scan_quality(cloud, stats, hits, a.scan_holes))
                rows.append(row)
    fmt = lambda x, f: '-' if x is None else format(x, f)
    print(f'# {a.label}: {a.pss} render --size {SIZE}x{SIZE} {" ".join(extra)}')
    print(f'{"cloud":30} {"view":8} {"holes %":>8} {"floor %":>8} {"extra %":>8} {"normal°":>8} {">10° %":>7} '
          f'{"frame s":>8} {"hits":>7}')
    for r in rows:
        if 'error' in r:
            print(f'{r["cloud"]:30} {r["view"]:8} failed'); continue
        print(f'{r["cloud"]:30} {r["view"]:8} {r["holes_pct"]:8.2f} {fmt(r.get("floor_pct"), "8.2f"):>8} '
              f'{fmt(r.get("extra_pct"), "8.2f"):>8} '
              f'{fmt(r.get("normal_mean_deg"), "8.2f"):>8} {fmt(r.get("normal_over10_pct"), "7.2f"):>7} '
              f'{r["frame_seconds"]:8.3f} {r["hits"]:7d}')
    json.dump(dict(label=a.label, pss=a.pss, extra_flags=extra, size=SIZE, rows=rows), open(a.out, 'w'), indent=1)
    print(f'wrote {a.out}')


if __name__ == '__main__':
    main()
