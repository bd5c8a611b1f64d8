# The Python module against the `pss` command: both run from the same build (CTest passes
# PSS_CLI, PSS_SOURCE_DIR and PYTHONPATH; tests/CMakeLists.txt).
import os
import subprocess
import zlib

import numpy as np
import pytest

CLI = os.environ["PSS_CLI"]
DATA = os.path.join(os.environ["PSS_SOURCE_DIR"], "data")
BUNNY = os.path.join(DATA, "bun_zipper.ply")
FUEL = os.path.join(DATA, "fuel_64x64x64_uint8.raw")


def run_cli(*args):
    """Runs pss; returns its stderr. A failure's message is the text after 'pss: error: '."""
    done = subprocess.run([CLI, *map(str, args)], capture_output=True, text=True, timeout=300)
    return done


def cli_error(*args):
    done = run_cli(*args)
    assert done.returncode != 0
    line = done.stderr.strip().splitlines()[-1]
    assert line.startswith("pss: error: "), line
    return line[len("pss: error: "):]


def cli_ok(*args):
    done = run_cli(*args)
    assert done.returncode == 0, done.stderr
    return done.stdout


def read_png(path):
    """An 8-bit RGB or RGBA PNG (what pss writes) as an (H, W, C) array, decoded here with
    zlib and the five PNG filters, independently of the library's writer."""
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, idat, header = 8, b"", None
    while pos < len(data):
        length = int.from_bytes(data[pos:pos + 4], "big")
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            header = body
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    width, height = int.from_bytes(header[0:4], "big"), int.from_bytes(header[4:8], "big")
    assert header[8] == 8 and header[12] == 0, "8-bit, not interlaced"
    channels = {2: 3, 6: 4}[header[9]]
    raw = zlib.decompress(idat)
    stride = width * channels
    out = np.zeros((height, stride), np.int32)
    previous = np.zeros(stride, np.int32)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        row = np.frombuffer(raw, np.uint8, stride, y * (stride + 1) + 1).astype(np.int32)
        current = np.zeros(stride, np.int32)
        for x in range(stride):
            a = current[x - channels] if x >= channels else 0
            b = previous[x]
            c = previous[x - channels] if x >= channels else 0
            if kind == 0:
                p = 0
            elif kind == 1:
                p = a
            elif kind == 2:
                p = b
            elif kind == 3:
                p = (a + b) // 2
            else:
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                p = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
            current[x] = (row[x] + p) & 255
        out[y] = current
        previous = current
    return out.reshape(height, width, channels).astype(np.uint8)


def read_binary_ply(path):
    """The vertex properties of a binary little-endian PLY (what pss writes) by name."""
    data = open(path, "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode().splitlines()
    assert header[1] == "format binary_little_endian 1.0"
    types = {"float": "<f4", "double": "<f8", "int": "<i4", "uchar": "u1", "uint": "<u4"}
    count, fields = 0, []
    for line in header:
        words = line.split()
        if words[:2] == ["element", "vertex"]:
            count = int(words[2])
        elif words[0] == "property":
            fields.append((words[2], types[words[1]]))
    return np.frombuffer(data, np.dtype(fields), count, end)


@pytest.fixture(scope="session")
def bunny():
    import pss
    points, normals, colors = pss.read_points(BUNNY)
    assert normals is None and colors is None
    return points
