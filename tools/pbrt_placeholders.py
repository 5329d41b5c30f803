"""Small valid stand-ins for the files a pbrt-v4 scene names: meshes, images, spectra, gzipped includes.

The public pbrt-v4 scene collection's text is readable, its meshes, images and volume data are not. A stand-in
lets a renderer read a scene through to its end: a PLY tetrahedron (normals and uv on every vertex), a 4x4
image of one value (square, so that it can also be an equal-area environment map; a flat normal map where
the scene names it as one), a flat spectrum, an empty gzipped include, a grey tabulated BSDF (Material "measured"). Every writer here is a minimal
uncompressed writer of its format, written for this purpose (no image library is needed).

A stand-in is made only where a valid one can be written without the original data; `stand_in` returns
(None, reason) for the rest (NanoVDB grids, JPEG, lens data), which the caller reports.
"""

from __future__ import annotations

import gzip
import struct
import zlib

GREY = 0.5  # every channel of every image stand-in, linear (188 in 8-bit files, which are sRGB-encoded)
GREY_8BIT = 188  # the sRGB encoding of 0.5: 0.7354 * 255
SIZE = 4  # image stand-ins are SIZE x SIZE
IMAGE_EXTENSIONS = (".png", ".exr", ".pfm", ".tga", ".hdr")
SPECTRUM_EXTENSIONS = (".spd", ".txt", ".csv")
NO_STAND_IN = {
    ".nvdb": "a NanoVDB grid (written only by NanoVDB's builder: bench_scene_census.py --nvdb-writer)",
    ".jpg": "a JPEG image (no JPEG encoder here)",
    ".jpeg": "a JPEG image (no JPEG encoder here)",
    ".dat": "lens data of a realistic camera (not generated)",
    ".vdb": "an OpenVDB grid (no valid grid can be written without an OpenVDB library)",
}


def ply_tetrahedron() -> bytes:
    """A binary little-endian PLY tetrahedron of edge about 1.6, flat-shaded: 12 vertices with x y z,
    nx ny nz, u v (three per face, the face's normal on each) and 4 triangles."""
    corners = [(1.0, 1.0, 1.0), (1.0, -1.0, -1.0), (-1.0, 1.0, -1.0), (-1.0, -1.0, 1.0)]
    faces = [(0, 1, 2), (0, 3, 1), (0, 2, 3), (1, 3, 2)]  # counter-clockwise seen from outside
    uvs = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)]
    head = ("ply\nformat binary_little_endian 1.0\ncomment placeholder: a stand-in for a mesh of the pbrt-v4 "
            "scene collection\nelement vertex 12\nproperty float x\nproperty float y\nproperty float z\n"
            "property float nx\nproperty float ny\nproperty float nz\nproperty float u\nproperty float v\n"
            "element face 4\nproperty list uchar int vertex_indices\nend_header\n").encode()
    body = bytearray()
    for f in faces:
        a, b, c = (corners[i] for i in f)
        e1 = [b[k] - a[k] for k in range(3)]
        e2 = [c[k] - a[k] for k in range(3)]
        n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]]
        length = sum(x * x for x in n) ** 0.5
        n = [x / length for x in n]
        for p, uv in zip((a, b, c), uvs):
            body += struct.pack("<8f", *(0.8 * x for x in p), *n, *uv)
    for i in range(4):
        body += struct.pack("<B3i", 3, 3 * i, 3 * i + 1, 3 * i + 2)
    return head + bytes(body)


def _pixels(normal_map: bool) -> tuple[float, float, float]:
    return (0.5, 0.5, 1.0) if normal_map else (GREY, GREY, GREY)


def _bytes8(normal_map: bool) -> bytes:
    return bytes((128, 128, 255)) if normal_map else bytes((GREY_8BIT,) * 3)


def png(normal_map: bool = False) -> bytes:
    """An 8-bit RGB PNG, SIZE x SIZE, of one colour: GREY sRGB-encoded, or the flat normal (128, 128, 255)
    where the image is a normal map (normal maps are read without the sRGB curve)."""
    rgb = _bytes8(normal_map)
    raw = b"".join(b"\x00" + rgb * SIZE for _ in range(SIZE))  # filter byte 0 on every row

    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", SIZE, SIZE, 8, 2, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def exr(normal_map: bool = False) -> bytes:
    """A scanline OpenEXR file without compression, SIZE x SIZE, float RGB of one colour."""
    def attr(name: str, kind: str, value: bytes) -> bytes:
        return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(value)) + value

    channels = b"".join(c + b"\0" + struct.pack("<iB3xii", 2, 0, 1, 1) for c in (b"B", b"G", b"R")) + b"\0"
    window = struct.pack("<4i", 0, 0, SIZE - 1, SIZE - 1)
    header = (b"\x76\x2f\x31\x01" + struct.pack("<i", 2) + attr("channels", "chlist", channels)
              + attr("compression", "compression", b"\0") + attr("dataWindow", "box2i", window)
              + attr("displayWindow", "box2i", window) + attr("lineOrder", "lineOrder", b"\0")
              + attr("pixelAspectRatio", "float", struct.pack("<f", 1.0))
              + attr("screenWindowCenter", "v2f", struct.pack("<2f", 0.0, 0.0))
              + attr("screenWindowWidth", "float", struct.pack("<f", 1.0)) + b"\0")
    r, g, b = _pixels(normal_map)
    line = b"".join(struct.pack(f"<{SIZE}f", *([c] * SIZE)) for c in (b, g, r))  # channels in name order
    chunks, offsets = b"", []
    first = len(header) + 8 * SIZE
    for y in range(SIZE):
        offsets.append(first + len(chunks))
        chunks += struct.pack("<ii", y, len(line)) + line
    return header + struct.pack(f"<{SIZE}Q", *offsets) + chunks


def pfm(normal_map: bool = False) -> bytes:
    """A little-endian colour PFM, SIZE x SIZE, float RGB of one colour."""
    values = _pixels(normal_map) * (SIZE * SIZE)
    return f"PF\n{SIZE} {SIZE}\n-1.0\n".encode() + struct.pack(f"<{3 * SIZE * SIZE}f", *values)


def tga(normal_map: bool = False) -> bytes:
    """An uncompressed 24-bit true-colour TGA, SIZE x SIZE, of one colour (BGR order)."""
    r, g, b = _bytes8(normal_map)
    return struct.pack("<BBBHHBHHHHBB", 0, 0, 2, 0, 0, 0, 0, 0, SIZE, SIZE, 24, 0) + bytes((b, g, r)) * (SIZE * SIZE)


def hdr(normal_map: bool = False) -> bytes:
    """A Radiance RGBE file with flat (not run-length encoded) scanlines, SIZE x SIZE, of one colour."""
    colour = _pixels(normal_map)
    exponent = 1 if max(colour) >= 1 else 0  # shared by the three mantissas; stored with a bias of 128
    pixel = bytes([round(c / 2 ** exponent * 256) for c in colour] + [128 + exponent])
    return f"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y {SIZE} +X {SIZE}\n".encode() + pixel * (SIZE * SIZE)


def spectrum() -> bytes:
    """A flat spectrum of value 1 over 300-900 nm, as (wavelength, value) pairs."""
    return b"# placeholder: a flat stand-in for a spectrum of the pbrt-v4 scene collection\n300 1\n900 1\n"


def tabulated_bsdf() -> bytes:
    """A tensor file of pbrt-v4's measured BSDF (apps/scene/tabulated_bsdf.h), isotropic, each table 2 x 2: normals
    of uniform density (ndf 1 / pi), their projected area (1 + cos theta) / 2, uniform visible normals and
    luminance, and a spectral factor of 0.5 at 360 and 830 nm."""
    half_pi = 1.5707963267948966
    fields = [("description", "B", [1], b"placeholder"), ("jacobian", "B", [1], [1]),
              ("theta_i", "f", [2], [0.0, half_pi]), ("phi_i", "f", [1], [0.0]), ("wavelengths", "f", [2], [360.0, 830.0]),
              ("ndf", "f", [2, 2], [0.3183099] * 4), ("sigma", "f", [2, 2], [1.0, 0.5, 1.0, 0.5]),
              ("vndf", "f", [1, 2, 2, 2], [1.0] * 8), ("luminance", "f", [1, 2, 2, 2], [1.0] * 8),
              ("spectra", "f", [1, 2, 2, 2, 2], [0.5] * 16)]
    fields[0] = ("description", "B", [len(fields[0][3])], fields[0][3])
    head = b"tensor_file\0" + bytes((1, 0)) + struct.pack("<I", len(fields))
    offset = len(head) + sum(2 + len(name) + 2 + 1 + 8 + 8 * len(shape) for name, _, shape, _ in fields)
    records, data = b"", b""
    for name, kind, shape, values in fields:
        records += struct.pack("<H", len(name)) + name.encode() + struct.pack("<HBQ", len(shape), 1 if kind == "B" else 10,
                                                                            offset + len(data))
        records += b"".join(struct.pack("<Q", n) for n in shape)
        data += bytes(values) if kind == "B" else struct.pack(f"<{len(values)}f", *values)
    return head + records + data


def empty_include() -> bytes:
    """An include that holds nothing but a comment (for gzipped includes whose text is not readable)."""
    return b"# placeholder: this include's text is not available; it holds nothing here\n"


def stand_in(name: str, normal_map: bool = False) -> tuple[bytes | None, str]:
    """The stand-in for a file named `name` (by its extension; `.gz` compresses the inner format), with a
    one-line description; (None, reason) where no valid stand-in can be written."""
    lower = name.lower()
    gz = lower.endswith(".gz")
    inner = lower[:-3] if gz else lower
    dot = inner.rfind(".")
    ext = inner[dot:] if dot >= 0 else ""
    writers = {".ply": (ply_tetrahedron, "a PLY tetrahedron"), ".png": (png, "a 4x4 PNG"), ".exr": (exr, "a 4x4 EXR"),
               ".pfm": (pfm, "a 4x4 PFM"), ".tga": (tga, "a 4x4 TGA"), ".hdr": (hdr, "a 4x4 RGBE image"),
               ".pbrt": (empty_include, "an empty include"), ".bsdf": (tabulated_bsdf, "a grey tabulated BSDF")}
    for e in SPECTRUM_EXTENSIONS:
        writers[e] = (spectrum, "a flat spectrum")
    if ext in writers:
        make, what = writers[ext]
        data = make(normal_map) if ext in IMAGE_EXTENSIONS else make()
        if normal_map and ext in IMAGE_EXTENSIONS:
            what += " (flat normal map)"
        if gz:
            data, what = gzip.compress(data, mtime=0), what + ", gzipped"
        return data, what
    return None, NO_STAND_IN.get(ext, f"a '{ext or name}' file (no stand-in for this kind)")
