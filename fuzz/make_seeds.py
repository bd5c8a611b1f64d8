#!/usr/bin/env python3
"""Writes the seed corpora fuzz/corpus/<target>/ from data/ and hand-made edge cases.

Run from anywhere: python3 fuzz/make_seeds.py. Seeds are small (each < 64 KiB, cut or
downsampled from data/), named for what they are. Findings are added by hand as
fuzz/corpus/<target>/finding-*, which this script leaves alone; it rewrites the others.
The input layouts are the targets' (fuzz/*.cpp): a mode byte and HEAD + SEP + TAIL for NRRD
and MetaImage, a mode byte for NIfTI, an 18-byte format for raw, arguments split at
newlines for the command line.
"""
import gzip
import math
import pathlib
import struct
import zlib

ROOT = pathlib.Path(__file__).resolve().parent.parent
DATA = ROOT / "data"
CORPUS = ROOT / "fuzz" / "corpus"
SEP = b"\n--pss-fuzz-data--\n"
MAX_SEED = 64 * 1024


def gz(b):
    return gzip.compress(b, compresslevel=9, mtime=0)


def write(target, name, data):
    assert len(data) < MAX_SEED, (target, name, len(data))
    folder = CORPUS / target
    folder.mkdir(parents=True, exist_ok=True)
    (folder / name).write_bytes(data)


def clear():
    for folder in CORPUS.glob("*"):
        for f in folder.glob("*"):
            if not f.name.startswith("finding-"):
                f.unlink()


# ---- volumes from data/ --------------------------------------------------------------

def volume(name, dims):
    raw = (DATA / name).read_bytes()
    assert len(raw) == dims[0] * dims[1] * dims[2]
    return raw, dims


def downsample(raw, dims, step):
    nx, ny, nz = dims
    out = bytearray()
    for k in range(0, nz, step):
        for j in range(0, ny, step):
            for i in range(0, nx, step):
                out.append(raw[(k * ny + j) * nx + i])
    return bytes(out), (len(range(0, nx, step)), len(range(0, ny, step)), len(range(0, nz, step)))


def engine_voxels():
    """The engine CT's voxels (the NRRD's gzip part), downsampled by 16: 16x16x8."""
    text = (DATA / "engine_256x256x128_uint8.nrrd").read_bytes()
    raw = gzip.decompress(text[text.index(b"\n\n") + 2:])
    return downsample(raw, (256, 256, 128), 16)


BUCKY = volume("bucky_32x32x32_uint8.raw", (32, 32, 32))
BUCKY8 = downsample(*BUCKY, 4)        # 8x8x8
FUEL16 = downsample(*volume("fuel_64x64x64_uint8.raw", (64, 64, 64)), 4)  # 16x16x16
TOOTH = downsample(*volume("tooth_103x94x161_uint8.raw", (103, 94, 161)), 8)  # 13x12x21
ENGINE = engine_voxels()


def as_type(raw, fmt):
    """uint8 voxels as another type ('<h', '>f', ...), values scaled a little."""
    return b"".join(struct.pack(fmt, v * 3 - 100 if fmt[1] in "hi" else v / 7.0 if fmt[1] in "fd" else v)
                    for v in raw)


# ---- point clouds from the bunny -----------------------------------------------------

def bunny_points(n):
    lines = (DATA / "bun_zipper.ply").read_text().splitlines()
    start = lines.index("end_header") + 1
    pts = [tuple(float(x) for x in line.split()[:3]) for line in lines[start:start + 35947]]
    return pts[:: max(1, len(pts) // n)][:n]


def normal_of(p):
    cx, cy, cz = -0.027, 0.11, 0.0  # roughly the bunny's centre: outward-ish normals
    d = (p[0] - cx, p[1] - cy, p[2] - cz)
    length = math.sqrt(sum(c * c for c in d)) or 1
    return tuple(c / length for c in d)


def ply_header(fmt, n, props, extra=""):
    return (f"ply\nformat {fmt} 1.0\ncomment pss fuzz seed\n{extra}element vertex {n}\n" +
            "".join(f"property {t} {name}\n" for t, name in props) + "end_header\n").encode()


def ply_seeds():
    pts = bunny_points(400)
    # The bunny's own layout, cut: x y z confidence intensity, then faces.
    body = "".join(f"{x:g} {y:g} {z:g} 0.85 0.5\n" for x, y, z in pts[:300])
    faces = "".join(f"3 {i} {i + 1} {i + 2}\n" for i in range(0, 30))
    head = ply_header("ascii", 300, [("float", "x"), ("float", "y"), ("float", "z"), ("float", "confidence"),
                                     ("float", "intensity")]).replace(b"end_header\n", b"element face 30\nproperty list uchar int vertex_indices\nend_header\n")
    write("ply", "bunny-ascii-faces.ply", head + body.encode() + faces.encode())
    xyzn = [("float", c) for c in ("x", "y", "z", "nx", "ny", "nz")]
    write("ply", "bunny-binary-le-normals.ply", ply_header("binary_little_endian", 400, xyzn) +
          b"".join(struct.pack("<6f", *p, *normal_of(p)) for p in pts))
    write("ply", "bunny-binary-be-double.ply", ply_header("binary_big_endian", 200, [("double", c) for c in "xyz"]) +
          b"".join(struct.pack(">3d", *p) for p in pts[:200]))
    # Faces before the vertices, every scalar type, a per-vertex list.
    props = [("char", "a"), ("uchar", "b"), ("short", "c"), ("ushort", "d"), ("int", "e"), ("uint", "f"),
             ("float", "x"), ("double", "y"), ("int16", "z")]
    head = (b"ply\nformat binary_little_endian 1.0\nelement face 2\nproperty list uint8 int32 vertex_indices\n"
            b"element vertex 3\n" + b"".join(f"property {t} {n}\n".encode() for t, n in props) +
            b"property list uchar float extra\nend_header\n")
    faces = struct.pack("<B3i", 3, 0, 1, 2) + struct.pack("<B4i", 4, 0, 1, 2, 0)
    verts = b"".join(struct.pack("<bBhHiIfdh", -1, 2, -3, 4, -5, 6, 0.5 * i, 1.5 * i, i) + struct.pack("<Bff", 2, 1, 2)
                     for i in range(3))
    write("ply", "types-lists-faces-first.ply", head + faces + verts)
    write("ply", "crlf-header.ply", ply_header("ascii", 3, [("float", c) for c in "xyz"]).replace(b"\n", b"\r\n") +
          b"0 0 0\r\n1 0 0\r\n0 1 0\r\n")
    small = [("float", c) for c in "xyz"]
    write("ply", "lying-count.ply", ply_header("ascii", 1000000, small) + b"0 0 0\n1 0 0\n0 1 0\n")
    write("ply", "huge-count.ply", ply_header("binary_little_endian", 18446744073709551615, small) + b"\0" * 24)
    write("ply", "count-overflow.ply", ply_header("ascii", 18446744073709551616, small) + b"0 0 0\n")
    write("ply", "nan-text.ply", ply_header("ascii", 2, small) + b"nan 0 0\n0 inf -inf\n")
    write("ply", "out-of-float-range.ply", ply_header("ascii", 1, small) + b"1e39 0 0\n")
    write("ply", "double-beyond-float.ply", ply_header("binary_little_endian", 1, [("double", c) for c in "xyz"]) +
          struct.pack("<3d", 1e300, 0, 0))
    write("ply", "normals-zero-nan-huge.ply", ply_header("ascii", 3, xyzn) +
          b"0 0 0 0 0 0\n1 0 0 3e38 3e38 3e38\n0 1 0 1e-45 0 0\n")
    write("ply", "normals-one-nan.ply", ply_header("ascii", 2, xyzn) + b"0 0 0 0 0 1\n1 0 0 nan 0 1\n")
    write("ply", "truncated-header.ply", b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nprop")
    write("ply", "no-format.ply", b"ply\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n")
    write("ply", "no-z.ply", ply_header("ascii", 1, small[:2]) + b"0 0\n")
    write("ply", "no-vertex.ply", b"ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n3 0 1 2\n")
    write("ply", "huge-list-count.ply", b"ply\nformat binary_big_endian 1.0\nelement face 1\nproperty list uint int i\n"
          b"element vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n" +
          struct.pack(">I", 4294967295) + b"\0" * 64)
    write("ply", "negative-list-count.ply", b"ply\nformat ascii 1.0\nelement face 1\nproperty list char int i\n"
          b"element vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n-1 0 0 0\n")
    write("ply", "unknown-type.ply", b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n")
    write("ply", "truncated-binary.ply", ply_header("binary_little_endian", 10, small) + b"\0" * 37)
    write("ply", "ascii-malformed-number.ply", ply_header("ascii", 1, small) + b"0x1p3 +1 --2\n")
    write("ply", "control-bytes.ply", b"ply\nformat \x1b[31m 1.0\n")
    write("ply", "empty.ply", b"")
    write("ply", "magic-only.ply", b"ply\n")


def xyz_seeds():
    pts = bunny_points(600)
    write("xyz", "bunny.xyz", "".join(f"{x:g} {y:g} {z:g}\n" for x, y, z in pts).encode())
    write("xyz", "bunny-normals-commas.xyz",
          ("# x,y,z,nx,ny,nz\n" + "".join("{:g},{:g},{:g},{:g},{:g},{:g}\n".format(*p, *normal_of(p))
                                           for p in pts[:300])).encode())
    write("xyz", "tabs-crlf-comments.xyz", b"# a comment\r\n\r\n1\t2\t3\r\n  +4 5e-3 -6E+2\r\n#\r\n7 8 9")
    write("xyz", "nan-inf.xyz", b"0 0 0\nnan 1 2\n")
    write("xyz", "inf.xyz", b"inf -inf 0\n")
    write("xyz", "out-of-float-range.xyz", b"1e39 0 0\n")
    write("xyz", "denormal.xyz", b"1e-45 1e-46 0\n")
    write("xyz", "columns-change.xyz", b"0 0 0\n1 1 1 0 0 1\n")
    write("xyz", "seven-numbers.xyz", b"1 2 3 4 5 6 7\n")
    write("xyz", "four-numbers.xyz", b"1 2 3 4\n")
    write("xyz", "normals-zero-nan.xyz", b"0 0 0 0 0 0\n1 0 0 nan 0 0\n")
    write("xyz", "malformed.xyz", b"1 2 three\n")
    write("xyz", "hex-and-signs.xyz", b"0x10 +-1 1..2\n")
    write("xyz", "control-bytes.xyz", b"1 2 \x1b[2J\x00\n")
    write("xyz", "comments-only.xyz", b"# nothing\n\n# here\n")
    write("xyz", "empty.xyz", b"")
    write("xyz", "long-token.xyz", b"1 2 " + b"9" * 5000 + b"\n")


def lzf(data):
    """liblzf's format, greedily: literal runs and back-references (long ones included)."""
    out, literal, table, i = bytearray(), bytearray(), {}, 0
    def flush():
        for k in range(0, len(literal), 32):
            out.append(len(literal[k:k + 32]) - 1)
            out.extend(literal[k:k + 32])
        literal.clear()
    while i < len(data):
        key = data[i:i + 3]
        ref = table.get(key) if len(key) == 3 else None
        table[key] = i
        if ref is None or i - ref > 8192:
            literal.append(data[i])
            i += 1
            continue
        length = 3
        while i + length < len(data) and length < 264 and data[ref + length] == data[i + length]:
            length += 1
        flush()
        d, n = i - ref - 1, length - 2
        out += bytes([n << 5 | d >> 8, d & 255]) if n < 7 else bytes([7 << 5 | d >> 8, n - 7, d & 255])
        i += length
    flush()
    return bytes(out)


def las(minor, fmt, record_length, pts, rgb_at=None, scale=1e-6):
    header_size = 375 if minor == 4 else 227
    h = b"LASF" + bytes(20) + bytes([1, minor]) + bytes(64) + struct.pack("<HHHII", 1, 2024, header_size, header_size, 0)
    h += struct.pack("<BHI", fmt, record_length, 0 if fmt >= 6 else len(pts)) + bytes(20)
    h += struct.pack("<6d", scale, scale, scale, 0.5, -0.5, 0) + bytes(48)
    if minor == 4:
        h += bytes(20) + struct.pack("<Q", len(pts)) + bytes(120)
    records = b""
    for i, p in enumerate(pts):
        r = bytearray(struct.pack("<3i", *(round((c - o) / scale) for c, o in zip(p, (0.5, -0.5, 0)))))
        r += bytes(record_length - len(r))
        if rgb_at:
            r[rgb_at:rgb_at + 6] = struct.pack("<3H", i * 257 % 65536, 65535, i * 100 % 65536)
        records += bytes(r)
    return h + records


def point_format_seeds():
    pts = bunny_points(120)
    write("obj", "bunny-colours.obj", b"# bunny\nmtllib a.mtl\no b\n" + "".join(
        f"v {x:g} {y:g} {z:g} {i % 3 / 2} 0.25 1\n" for i, (x, y, z) in enumerate(pts)).encode() + b"f 1 2 3\n")
    write("obj", "face-normals.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0 1\nvt 0 0\nvn 0 0 1\nvn 0 2 0\n"
                                     b"f 1//1 2//2 3//1\nf -1/1/-1 1/1/2 2//1\ng x\ns off\n")
    write("obj", "normals-in-order.obj", b"v 0 0 0\nvn 0 0 1\nv 1 0 0\nvn nan 0 1\nf 1 2 1\n")
    write("obj", "continuation.obj", b"v 1 2 \\\n3\n")
    write("obj", "bad-index.obj", b"v 0 0 0\nvn 0 0 1\nf 1//9223372036854775807 -9223372036854775808//1\n")

    write("off", "bunny.off", b"OFF # bunny\n" + f"{len(pts)} 1 0\n".encode() + "".join(
        f"{x:g} {y:g} {z:g}\n" for x, y, z in pts).encode() + b"3 0 1 2\n")
    write("off", "normals-colours.off", b"STCNOFF 2 0 0\n0 0 0 0 0 2 255 0 51 0.5 0.5\n1 0 0 0 1 0 0.2 1.0 0 1 0 0\n")
    write("off", "counts-lie.off", b"COFF\n\n# counts\n1000000000000 0\n1 2 3 4 5 6\n")
    write("off", "no-keyword.off", b"2 0\n1 2 3\n4 nan 6\n")

    facets = [pts[i:i + 3] for i in range(0, len(pts) - 2, 3)]
    binary = b"solid binary".ljust(80) + struct.pack("<I", len(facets)) + b"".join(
        struct.pack("<3f", 0, 0, 1) + b"".join(struct.pack("<3f", *v) for v in f) + b"\0\0" for f in facets)
    write("stl", "bunny-binary.stl", binary)
    write("stl", "bunny-binary-truncated.stl", binary[:-7])
    write("stl", "lying-count.stl", binary[:80] + struct.pack("<I", 0xFFFFFFFF) + binary[84:])
    write("stl", "bunny-ascii.stl", ("solid bunny\n" + "".join(
        " facet normal 0 0 1\n  outer loop\n" + "".join(f"   vertex {x:g} {y:g} {z:g}\n" for x, y, z in f) +
        "  endloop\n endfacet\n" for f in facets[:20]) + "endsolid bunny\n").encode())
    write("stl", "two-vertices.stl", b"solid\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n")

    fields = "FIELDS x y z normal_x normal_y normal_z rgb hist\nSIZE 4 4 4 4 4 4 4 2\nTYPE F F F F F F U I\n" \
             "COUNT 1 1 1 1 1 1 1 3\nWIDTH {n}\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS {n}\nDATA {data}\n"
    rows = [(*p, *normal_of(p), i * 0x010203 & 0xFFFFFF, i, -i, 7) for i, p in enumerate(pts)]
    rows[5] = (math.nan,) * 6 + rows[5][6:]  # PCL's invalid point
    write("pcd", "bunny-ascii.pcd", fields.format(n=len(rows), data="ascii").encode() + "".join(
        " ".join(f"{v:g}" if isinstance(v, float) else str(v) for v in r) + "\n" for r in rows).encode())
    aos = b"".join(struct.pack("<6fI3h", *r) for r in rows)
    write("pcd", "bunny-binary.pcd", fields.format(n=len(rows), data="binary").encode() + aos)
    soa = b"".join(b"".join(struct.pack("<" + t, *r[a:b]) for r in rows)
                   for t, a, b in [("f", 0, 1), ("f", 1, 2), ("f", 2, 3), ("f", 3, 4), ("f", 4, 5), ("f", 5, 6),
                                   ("I", 6, 7), ("3h", 7, 10)])
    packed = lzf(soa)
    compressed = fields.format(n=len(rows), data="binary_compressed").encode() + struct.pack("<II", len(packed), len(soa))
    write("pcd", "bunny-compressed.pcd", compressed + packed)
    write("pcd", "compressed-lying-size.pcd", compressed[:-4] + struct.pack("<I", 0xFFFFFFF0) + packed)
    write("pcd", "types.pcd", b"FIELDS x y z t\nSIZE 8 1 2 8\nTYPE F I U U\nWIDTH 2\nHEIGHT 1\nDATA binary\n" +
          struct.pack("<dbHQdbHQ", 0.5, -3, 65535, 1, float("nan"), 0, 0, 2))

    write("las", "bunny-12-format-2.las", las(2, 2, 26, pts, rgb_at=20))
    write("las", "bunny-14-format-7-extra-bytes.las", las(4, 7, 40, pts, rgb_at=30))
    write("las", "format-0.las", las(2, 0, 20, pts[:10]))
    write("las", "format-10.las", las(4, 10, 67, pts[:10], rgb_at=30))
    write("las", "truncated.las", las(2, 1, 28, pts[:10])[:-5])
    laz = bytearray(las(2, 2, 26, pts[:3], rgb_at=20))
    laz[104] |= 0x80  # LASzip's compressed flag
    write("las", "laz-bit.las", bytes(laz))


# ---- raw: 18-byte format (type, flags, dims x y z, skip as int32 LE), then the file ----

TYPES = {"int8": 0, "uint8": 1, "int16": 2, "uint16": 3, "int32": 4, "uint32": 5, "float32": 6, "float64": 7}


def raw_format(type_name, dims, big=False, skip=0):
    return struct.pack("<BB3ii", TYPES[type_name], 1 if big else 0, *dims, skip)


def raw_seeds():
    write("raw", "bucky-32-uint8", raw_format("uint8", BUCKY[1]) + BUCKY[0])
    write("raw", "bucky-8-uint8", raw_format("uint8", BUCKY8[1]) + BUCKY8[0])
    write("raw", "fuel-16-int16-be", raw_format("int16", FUEL16[1], big=True) + as_type(FUEL16[0], ">h"))
    write("raw", "tooth-float32", raw_format("float32", TOOTH[1]) + as_type(TOOTH[0], "<f"))
    write("raw", "bucky-8-float64-be", raw_format("float64", BUCKY8[1], big=True) + as_type(BUCKY8[0], ">d"))
    write("raw", "bucky-8-uint32-skip16", raw_format("uint32", BUCKY8[1], skip=16) + b"H" * 16 + as_type(BUCKY8[0], "<I"))
    write("raw", "int8", raw_format("int8", (2, 2, 2)) + b"\x80\x7f\0\1\2\3\4\5")
    write("raw", "float32-nan", raw_format("float32", (2, 1, 1)) + struct.pack("<2f", 1.0, float("nan")))
    write("raw", "float64-beyond-float", raw_format("float64", (1, 1, 1)) + struct.pack("<d", 1e300))
    write("raw", "size-mismatch", raw_format("uint8", (8, 8, 8)) + b"\0" * 100)
    write("raw", "huge-dims", raw_format("uint8", (1 << 30, 1 << 30, 1 << 30)))
    write("raw", "overflow-dims", raw_format("float64", (2147483647, 2147483647, 2147483647)))
    write("raw", "at-the-cap", raw_format("uint8", (1 << 11, 1 << 10, 1 << 10)))
    write("raw", "negative-dims", raw_format("uint8", (-1, 8, 8)))
    write("raw", "zero-dims", raw_format("uint8", (0, 0, 0)))
    write("raw", "negative-skip", raw_format("uint8", (1, 1, 1), skip=-5) + b"\0")
    write("raw", "empty-file", raw_format("uint8", (1, 1, 1)))


# ---- NRRD and MetaImage: mode byte (bit 0 detached, bit 1 target gzips TAIL) + HEAD SEP TAIL

def headed(mode, head, tail=None):
    return bytes([mode]) + head + (SEP + tail if tail is not None else b"")


def nrrd_head(type_name, dims, encoding="raw", extra=b"", endian="little", data_file=None):
    h = (f"NRRD0004\n# pss fuzz seed\ntype: {type_name}\ndimension: 3\nsizes: {dims[0]} {dims[1]} {dims[2]}\n"
         f"spacings: 1 1 1.5\nendian: {endian}\nencoding: {encoding}\n").encode() + extra
    if data_file is not None:
        return h + f"data file: {data_file}\n".encode()
    return h + b"\n"  # attached: the blank line ends the header


def nrrd_seeds():
    ev, ed = ENGINE
    bv, bd = BUCKY8
    write("nrrd", "engine-16-raw-attached", headed(0, nrrd_head("uint8", ed), ev))
    write("nrrd", "engine-16-gzip-attached", headed(0, nrrd_head("uint8", ed, "gzip") + gz(ev)))
    write("nrrd", "engine-16-gzip-by-target", headed(2, nrrd_head("uchar", ed, "gz"), ev))
    write("nrrd", "bucky-8-detached", headed(1, nrrd_head("unsigned char", bd, data_file="data.raw"), bv))
    write("nrrd", "bucky-8-detached-gzip", headed(3, nrrd_head("uint8", bd, "gzip", data_file="data.raw"), bv))
    write("nrrd", "bucky-8-int16-big",
          headed(0, nrrd_head("short", bd, endian="big", extra=b"space directions: (1,0,0) (0,2,0) (0,0,0.5)\n"
                              b"space origin: (10,-3.5,1e3)\nkinds: domain domain domain\n"), as_type(bv, ">h")))
    write("nrrd", "bucky-8-float-keyvalues",
          headed(0, nrrd_head("float", bd, extra=b"key:=value\ncontent: fuzz\nmin: 0\nmax: 255\n"), as_type(bv, "<f")))
    write("nrrd", "bucky-8-double-byteskip",
          headed(0, nrrd_head("double", bd, extra=b"byte skip: 8\n"), b"SKIPPED!" + as_type(bv, "<d")))
    write("nrrd", "byteskip-minus-one", headed(0, nrrd_head("uint16", (2, 2, 2), extra=b"byte skip: -1\n"),
                                               b"junk before" + b"\1\0" * 8))
    write("nrrd", "byteskip-huge", headed(0, nrrd_head("uint8", (1, 1, 1), extra=b"byte skip: 9223372036854775807\n"), b"\0"))
    write("nrrd", "byteskip-huge-gzip", headed(2, nrrd_head("uint8", (1, 1, 1), "gzip", extra=b"byte skip: 9223372036854775807\n"), b"\0"))
    write("nrrd", "int-uint-float-nan", headed(0, nrrd_head("float", (2, 1, 1)), struct.pack("<2f", 0, float("nan"))))
    write("nrrd", "lying-sizes", headed(0, nrrd_head("uint8", (64, 64, 64)), b"\0" * 10))
    write("nrrd", "huge-sizes", headed(0, nrrd_head("uint8", (1073741824, 1073741824, 1073741824))))
    write("nrrd", "sizes-at-cap-gzip", headed(2, nrrd_head("uint8", (2048, 1024, 1024), "gzip"), b"\0" * 1000))
    write("nrrd", "negative-sizes", headed(0, nrrd_head("uint8", (-8, 8, 8)), b"\0"))
    # A gzip bomb: the header promises 1 GiB, the 50 KB stream holds 48 MiB of zeros.
    write("nrrd", "gzip-bomb", headed(0, nrrd_head("uint8", (1024, 1024, 1024), "gzip") + gz(b"\0" * (48 << 20))))
    write("nrrd", "gzip-truncated", headed(0, nrrd_head("uint8", ed, "gzip") + gz(ev)[:300]))
    write("nrrd", "gzip-trailing-data", headed(0, nrrd_head("uint8", ed, "gzip") + gz(ev) + b"trailing"))
    write("nrrd", "gzip-corrupt", headed(0, nrrd_head("uint8", ed, "gzip") + b"\x1f\x8b\x08\0garbage"))
    write("nrrd", "nan-spacings", headed(0, nrrd_head("uint8", (1, 1, 1), extra=b"spacings: nan 1 1\n"), b"\0"))
    write("nrrd", "skewed-directions", headed(0, nrrd_head("uint8", (1, 1, 1), extra=b"space directions: (1,1,0) (0,1,0) (0,0,1)\n"), b"\0"))
    write("nrrd", "dimension-4", headed(0, b"NRRD0004\ntype: uint8\ndimension: 4\nsizes: 1 1 1 1\nencoding: raw\n\n", b"\0"))
    write("nrrd", "unknown-field-long", headed(0, b"NRRD0005\n" + b"x" * 20000 + b": y\n\n"))
    write("nrrd", "control-bytes", headed(0, b"NRRD0004\ntype: \x1b[31mred\x07\n\n"))
    write("nrrd", "malformed-line", headed(0, b"NRRD0004\nno colon here\n\n"))
    write("nrrd", "type-block", headed(0, nrrd_head("block", (1, 1, 1)), b"\0"))
    write("nrrd", "no-magic", headed(0, b"NRRD\ntype: uint8\n"))
    write("nrrd", "truncated-header", headed(0, b"NRRD0004\ntype: uint8\ndimension: 3\nsizes: 8 8"))
    write("nrrd", "empty", headed(0, b""))
    write("nrrd", "crlf", headed(0, nrrd_head("uint8", (2, 1, 1)).replace(b"\n", b"\r\n"), b"\1\2"))
    for name, data_file in [("detached-missing", "data.raw"), ("detached-parent", "../data.raw"),
                            ("detached-absolute-dev-null", "/dev/null"), ("detached-dev-zero", "/dev/zero"),
                            ("detached-folder", "."), ("detached-proc", "/proc/self/status"),
                            ("detached-list", "LIST"), ("detached-pattern", "slice%03d.raw 0 7 1"),
                            ("detached-empty-name", "")]:
        write("nrrd", name, headed(1, nrrd_head("uint8", (2, 2, 2), data_file=data_file)))
    write("nrrd", "detached-empty-file", headed(1, nrrd_head("uint8", (2, 2, 2), data_file="data.raw"), b""))


def mha_head(met_type, dims, data_file="LOCAL", extra=b""):
    return (b"ObjectType = Image\nNDims = 3\n" + f"DimSize = {dims[0]} {dims[1]} {dims[2]}\n".encode() +
            f"ElementType = {met_type}\nElementSpacing = 1 1 2\nOffset = 0 -1 2.5\n".encode() + extra +
            f"ElementDataFile = {data_file}\n".encode())


def metaimage_seeds():
    bv, bd = BUCKY8
    tv, td = TOOTH
    write("metaimage", "bucky-8-mha", headed(0, mha_head("MET_UCHAR", bd), bv))
    write("metaimage", "tooth-mhd", headed(1, mha_head("MET_UCHAR", td, "data.raw"), tv))
    write("metaimage", "bucky-8-short-msb",
          headed(0, mha_head("MET_SHORT", bd, extra=b"BinaryData = True\nBinaryDataByteOrderMSB = True\n"
                             b"TransformMatrix = 1 0 0 0 1 0 0 0 1\nAnatomicalOrientation = RAI\n"), as_type(bv, ">h")))
    write("metaimage", "bucky-8-float-compressed-by-target",
          headed(2, mha_head("MET_FLOAT", bd, extra=b"CompressedData = True\n"), as_type(bv, "<f")))
    write("metaimage", "bucky-8-double-mhd-compressed",
          headed(3, mha_head("MET_DOUBLE", bd, "data.raw", extra=b"CompressedData = True\nElementByteOrderMSB = False\n"),
                 as_type(bv, "<d")))
    zl = zlib.compress(bv, 9)
    write("metaimage", "bucky-8-zlib-size",
          headed(0, mha_head("MET_UCHAR", bd, extra=f"CompressedData = True\nCompressedDataSize = {len(zl)}\n".encode()) + zl))
    write("metaimage", "compressed-size-lies",
          headed(0, mha_head("MET_UCHAR", bd, extra=b"CompressedData = True\nCompressedDataSize = 5\n") + zl))
    write("metaimage", "int-uint-long",
          headed(0, mha_head("MET_ULONG", (2, 1, 1), extra=b"ElementSize = 1 1 1\nElementNumberOfChannels = 1\n"),
                 struct.pack("<2I", 1, 4294967295)))
    write("metaimage", "headersize-16", headed(1, mha_head("MET_CHAR", (2, 2, 2), "data.raw", extra=b"HeaderSize = 16\n"),
                                               b"H" * 16 + b"\x80\x7f\0\1\2\3\4\5"))
    write("metaimage", "headersize-minus-one", headed(1, mha_head("MET_CHAR", (2, 2, 2), "data.raw", extra=b"HeaderSize = -1\n"),
                                                      b"junk" + b"\0" * 8))
    write("metaimage", "headersize-huge", headed(0, mha_head("MET_UCHAR", (1, 1, 1), extra=b"HeaderSize = 9223372036854775807\n"), b"\0"))
    write("metaimage", "float-nan", headed(0, mha_head("MET_FLOAT", (2, 1, 1)), struct.pack("<2f", 0, float("inf"))))
    write("metaimage", "lying-dims", headed(0, mha_head("MET_UCHAR", (64, 64, 64)), b"\0" * 10))
    write("metaimage", "huge-dims", headed(0, mha_head("MET_UCHAR", (1073741824, 1073741824, 1073741824))))
    write("metaimage", "zlib-bomb", headed(0, mha_head("MET_UCHAR", (1024, 1024, 1024), extra=b"CompressedData = True\n") +
                                           zlib.compress(b"\0" * (48 << 20), 9)))
    write("metaimage", "rotated", headed(0, mha_head("MET_UCHAR", (1, 1, 1), extra=b"TransformMatrix = 0 1 0 1 0 0 0 0 1\n"), b"\0"))
    write("metaimage", "ndims-2", headed(0, b"NDims = 2\nDimSize = 2 2\nElementType = MET_UCHAR\nElementDataFile = LOCAL\n", b"\0" * 4))
    write("metaimage", "channels-3", headed(0, mha_head("MET_UCHAR", (1, 1, 1), extra=b"ElementNumberOfChannels = 3\n"), b"\0" * 3))
    write("metaimage", "ascii-data", headed(0, mha_head("MET_UCHAR", (1, 1, 1), extra=b"BinaryData = False\n"), b"0"))
    write("metaimage", "nan-spacing", headed(0, mha_head("MET_UCHAR", (1, 1, 1), extra=b"ElementSpacing = nan 1 1\n"), b"\0"))
    write("metaimage", "no-equals", headed(0, b"ObjectType Image\n"))
    write("metaimage", "control-bytes", headed(0, b"Element\x1bType = \x07MET_\x00UCHAR\n"))
    write("metaimage", "empty", headed(0, b""))
    for name, data_file in [("mhd-missing", "data.raw"), ("mhd-parent", "../data.raw"), ("mhd-dev-null", "/dev/null"),
                            ("mhd-folder", "."), ("mhd-list", "LIST"), ("mhd-pattern", "slice%03d.raw 1 8 1"),
                            ("mhd-list-2d", "LIST 2D")]:
        write("metaimage", name, headed(1, mha_head("MET_UCHAR", (2, 2, 2), data_file)))


# ---- NIfTI-1: mode byte (bit 0 named .nii.gz, bit 1 target gzips) + the file ------------

NIFTI_DT = {"int8": (256, 8), "uint8": (2, 8), "int16": (4, 16), "uint16": (512, 16), "int32": (8, 32),
            "uint32": (768, 32), "float32": (16, 32), "float64": (64, 64), "rgb": (128, 24)}


def nifti(dims, dtype, voxels, big=False, ndim=3, dim4=1, pixdim=(1, 1, 1), vox_offset=352.0, slope=0.0,
          inter=0.0, qform=0, sform=0, srow_t=(0, 0, 0), magic=b"n+1\0", sizeof_hdr=348, extension=b"",
          bitpix=None):
    e = ">" if big else "<"
    code, bits = NIFTI_DT[dtype]
    h = bytearray(348)
    struct.pack_into(e + "i", h, 0, sizeof_hdr)
    struct.pack_into(e + "8h", h, 40, ndim, dims[0], dims[1], dims[2], dim4, 1, 1, 1)
    struct.pack_into(e + "hh", h, 70, code, bits if bitpix is None else bitpix)
    struct.pack_into(e + "8f", h, 76, 1.0, *pixdim, 1, 0, 0, 0)
    struct.pack_into(e + "f", h, 108, vox_offset)
    struct.pack_into(e + "ff", h, 112, slope, inter)
    struct.pack_into(e + "hh", h, 252, qform, sform)
    struct.pack_into(e + "3f", h, 256, 0.0, 0.0, 0.0)  # quatern b c d
    struct.pack_into(e + "3f", h, 268, 5.0, -5.0, 7.5)  # qoffset x y z
    struct.pack_into(e + "4f", h, 280, 1, 0, 0, srow_t[0])
    struct.pack_into(e + "4f", h, 296, 0, 1, 0, srow_t[1])
    struct.pack_into(e + "4f", h, 312, 0, 0, 1, srow_t[2])
    h[344:348] = magic
    ext = (b"\1\0\0\0" + extension) if extension else b"\0\0\0\0"
    return bytes(h) + ext + voxels


def nifti_seeds():
    bv, bd = BUCKY8
    fv, fd = FUEL16
    write("nifti", "bucky-8-uint8.nii", b"\0" + nifti(bd, "uint8", bv))
    write("nifti", "fuel-16-int16-big.nii", b"\0" + nifti(fd, "int16", as_type(fv, ">h"), big=True, pixdim=(1, 1, -2),
                                                           qform=1))
    write("nifti", "bucky-8-float-scaled-sform.nii", b"\0" + nifti(bd, "float32", as_type(bv, "<f"), slope=2, inter=-1,
                                                                    sform=2, srow_t=(10, 20, 30)))
    write("nifti", "bucky-8-double-4d.nii", b"\0" + nifti(bd, "float64", as_type(bv, "<d"), ndim=4))
    write("nifti", "bucky-8-gz-by-target", b"\3" + nifti(bd, "uint16", as_type(bv, "<H")))
    write("nifti", "bucky-8-gz-stream", b"\1" + gz(nifti(bd, "int8", bv)))
    write("nifti", "gz-named-nii", b"\2" + nifti(bd, "uint8", bv))
    write("nifti", "plain-named-nii-gz", b"\1" + nifti(bd, "uint8", bv))
    write("nifti", "uint32-int32", b"\0" + nifti((2, 1, 1), "uint32", struct.pack("<2I", 0, 4294967295)))
    write("nifti", "extension", b"\0" + nifti((2, 1, 1), "uint8", b"\1\2", vox_offset=368.0,
                                               extension=struct.pack("<ii", 16, 6) + b"comment!"))
    write("nifti", "extension-lying-size", b"\0" + nifti((2, 1, 1), "uint8", b"\1\2", vox_offset=368.0,
                                                          extension=struct.pack("<ii", 1 << 30, 6) + b"comment!"))
    write("nifti", "extension-negative-size", b"\0" + nifti((2, 1, 1), "uint8", b"\1\2", vox_offset=368.0,
                                                             extension=struct.pack("<ii", -16, 6) + b"comment!"))
    write("nifti", "series-dim4", b"\0" + nifti((2, 1, 1), "uint8", b"\0" * 4, ndim=4, dim4=2))
    write("nifti", "rgb", b"\0" + nifti((1, 1, 1), "rgb", b"\0\0\0"))
    write("nifti", "bitpix-lies", b"\0" + nifti((1, 1, 1), "uint8", b"\0", bitpix=16))
    write("nifti", "vox-offset-huge", b"\0" + nifti((1, 1, 1), "uint8", b"\0", vox_offset=1e30))
    write("nifti", "vox-offset-nan", b"\0" + nifti((1, 1, 1), "uint8", b"\0", vox_offset=float("nan")))
    write("nifti", "vox-offset-fraction", b"\0" + nifti((1, 1, 1), "uint8", b"\0", vox_offset=352.5))
    write("nifti", "pixdim-zero-nan", b"\0" + nifti((1, 1, 1), "uint8", b"\0", pixdim=(0, float("nan"), 1)))
    write("nifti", "slope-overflow", b"\0" + nifti((1, 1, 1), "float32", struct.pack("<f", 3e38), slope=1e10))
    write("nifti", "slope-nan", b"\0" + nifti((1, 1, 1), "uint8", b"\5", slope=float("nan"), inter=float("inf")))
    write("nifti", "float-nan", b"\0" + nifti((2, 1, 1), "float32", struct.pack("<2f", 0, float("nan"))))
    write("nifti", "sform-nan-origin", b"\0" + nifti((1, 1, 1), "uint8", b"\0", sform=1, srow_t=(float("nan"), 0, 0)))
    write("nifti", "lying-dims", b"\0" + nifti((64, 64, 64), "uint8", b"\0" * 10))
    write("nifti", "max-dims", b"\0" + nifti((32767, 32767, 32767), "float64", b""))
    write("nifti", "negative-dims", b"\0" + nifti((-1, 1, 1), "uint8", b"\0"))
    write("nifti", "ndim-2", b"\0" + nifti((1, 1, 1), "uint8", b"\0", ndim=2))
    write("nifti", "ndim-7", b"\0" + nifti((1, 1, 1), "uint8", b"\0", ndim=7))
    write("nifti", "magic-ni1", b"\0" + nifti((1, 1, 1), "uint8", b"\0", magic=b"ni1\0"))
    write("nifti", "nifti2", b"\0" + nifti((1, 1, 1), "uint8", b"\0", sizeof_hdr=540))
    write("nifti", "gzip-bomb", b"\1" + gz(nifti((1024, 1024, 1024), "uint8", b"\0" * (48 << 20))))
    write("nifti", "gzip-truncated", b"\1" + gz(nifti(bd, "uint8", bv))[:200])
    write("nifti", "gzip-corrupt", b"\1\x1f\x8b\x08\0garbage")
    write("nifti", "short-header", b"\0" + nifti(bd, "uint8", bv)[:200])
    write("nifti", "empty", b"\0")


# ---- the command line: arguments after "pss", one per line ------------------------------

def cli_seeds():
    commands = {
        "info-cloud": ["info", "data/bun_zipper.ply"],
        "info-raw": ["info", "data/tooth_103x94x161_uint8.raw", "--dims", "103x94x161", "--type", "uint8"],
        "info-raw-all-flags": ["info", "v.raw", "--dims", "4X4X4", "--type", "float64", "--spacing", "1,1,2.5",
                               "--endian", "big", "--skip", "16"],
        "project-all-flags": ["project", "in.ply", "-o", "out.ply", "--h", "0.004", "--rho", "0.008", "--method",
                              "wls", "--iterations", "3", "--backend", "cpu", "--threads", "2", "--stats", "s.json"],
        "render-all-flags": ["render", "in.xyz", "-o", "o.png", "--size", "640x480", "--view", "30,-20", "--fov",
                             "35", "--hits", "h.ply", "--shadows", "--reflections", "--reflectivity", "0.5",
                             "--iterations", "auto", "--secondary", "paper", "--h", "0.01", "--rho", "0.02",
                             "--b", "0.01", "--epsilon", "1e-5", "--backend", "auto", "--stats", "s.json"],
        "volume-iso": ["volume", "data/bucky_32x32x32_uint8.raw", "--dims", "32x32x32", "--type", "uint8",
                       "--iso", "100", "--method", "predictor", "--h", "2", "--k", "0.75", "--radius", "1.5",
                       "--alpha", "0.9", "--smoothing", "1.25", "--error", "0.1", "--debug-projection", "-o", "d.png"],
        "volume-gradient": ["volume", "e.nrrd", "--gradient", "--threshold", "0.15", "--view", "30,30", "-o", "e.png"],
        "extract": ["extract", "e.nrrd", "--iso=75", "-o", "s.ply", "--stats=s.json", "--threads=1"],
        "help": ["volume", "--help"],
        "version": ["--version"],
        # What issue 8 reported, and neighbours.
        "fov-nan": ["volume", "b.raw", "--dims", "32x32x32", "--iso", "100", "--fov", "nan", "-o", "o.png"],
        "threads-huge": ["project", "in.ply", "-o", "o.ply", "--threads", "100000"],
        "dims-overflow": ["volume", "e.raw", "--dims", "1048576x1048576x1073741824", "--iso", "1", "-o", "o.png"],
        "dims-bad": ["info", "e.raw", "--dims", "-1x2x3"],
        "iso-inf": ["extract", "e.nrrd", "--iso", "inf", "-o", "o.ply"],
        "h-nan": ["volume", "e.nrrd", "--iso", "1", "--h", "nan", "-o", "o.png"],
        "h-huge": ["project", "in.ply", "-o", "o.ply", "--h", "1e39"],
        "size-zero": ["render", "in.ply", "-o", "o.png", "--size", "0x0"],
        "size-huge": ["render", "in.ply", "-o", "o.png", "--size", "99999999999x1"],
        "view-nan": ["render", "in.ply", "-o", "o.png", "--view", "nan,0"],
        "iterations-bad": ["render", "in.ply", "-o", "o.png", "--iterations", "0x10"],
        "skip-negative": ["info", "e.raw", "--dims", "2x2x2", "--skip", "-1"],
        "spacing-nan": ["info", "e.raw", "--dims", "2x2x2", "--spacing", "nan,1,1"],
        "iso-and-gradient": ["volume", "e.nrrd", "--iso", "1", "--gradient", "-o", "o.png"],
        "no-surface": ["extract", "e.nrrd", "-o", "o.ply"],
        "threshold-with-iso": ["volume", "e.nrrd", "--iso", "1", "--threshold", "0.2", "-o", "o.png"],
        "raw-without-dims": ["volume", "e.raw", "--type", "int16", "--iso", "1", "-o", "o.png"],
        "unknown-command": ["frobnicate"],
        "unknown-flag": ["render", "in.ply", "-o", "o.png", "--\x1b[31mred"],
        "missing-value": ["project", "in.ply", "-o"],
        "empty": [],
    }
    for name, args in commands.items():
        write("cli", name, "\n".join(args).encode())
    write("cli", "nul-separated", b"\0".join([b"info", b"x.raw", b"--dims", b"2x2x2"]))


if __name__ == "__main__":
    clear()
    ply_seeds()
    xyz_seeds()
    point_format_seeds()
    raw_seeds()
    nrrd_seeds()
    metaimage_seeds()
    nifti_seeds()
    cli_seeds()
    total = sum(f.stat().st_size for f in CORPUS.rglob("*") if f.is_file())
    print(f"{sum(1 for f in CORPUS.rglob('*') if f.is_file())} seeds, {total} bytes in {CORPUS}")
