#!/usr/bin/env python3
"""fuzz/make_corpus.py OUT_DIR: writes the seed corpora of the fuzz targets into OUT_DIR/<target>/,
and their dictionaries as OUT_DIR/<target>.dict: for the loaders, tiny valid files made here from
the formats' descriptions (FORMATS.md); for fuzz_scene, the shipped scenes/*.json and small scenes
made here. Nothing is copied from third-party data. The inputs are laid out as each target reads
them (fuzz_tfx: a version byte then the file from byte 4; fuzz_cyhair: the file after "HAIR")."""
import glob
import json
import os
import struct
import sys

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")


def point(s, v):
    return (0.5 * s, 1.0 + 0.25 * v, -0.125 * (s + v))


def tfx2(strands, per, header="", newline="\n", bom=False):
    lines = [l for l in header.split("\n") if l] + [f"numStrands {strands}", "is sorted 1"]
    for s in range(strands):
        lines.append(f"strand {s} numVerts {per} texcoord 0.000000 000000")
        lines += ["%g %g %g" % point(s, v) for v in range(per)]
    text = newline.join(lines) + newline
    return (b"\xef\xbb\xbf" if bom else b"") + text.encode()


def tfx3(strands, per, both_ends=0):
    b = struct.pack("<fIIII", 3.0, strands, per, 4, both_ends) + bytes(31 * 4)
    b += struct.pack("<I", 296) + bytes(5 * 4 + 32 * 4)
    assert len(b) == 296
    for s in range(strands):
        for v in range(per):
            b += struct.pack("<3f", *point(s, v))
    return b


def tfx4(strands, per, pinned=1):
    b = struct.pack("<fIII", 4.0, strands, per, 160) + bytes(4 * 4 + 32 * 4)
    assert len(b) == 160
    for s in range(strands):
        for v in range(per):
            b += struct.pack("<4f", *point(s, v), 0.0 if v < pinned else 1.0)
    return b


def cyhair(segments, array=True, extra=False):
    points = sum(s + 1 for s in segments)
    arrays = (1 if array else 0) | 2 | ((4 | 16) if extra else 0)
    b = b"HAIR" + struct.pack("<IIII", len(segments), points, arrays, segments[0])
    b += struct.pack("<5f", 0.01, 1.0, 0.5, 0.4, 0.3) + bytes(88)
    assert len(b) == 128
    if array:
        b += b"".join(struct.pack("<H", s) for s in segments)
    for s, n in enumerate(segments):
        for v in range(n + 1):
            b += struct.pack("<3f", *point(s, v))
    if extra:
        b += struct.pack(f"<{points}f", *([0.02] * points))
        b += struct.pack(f"<{3 * points}f", *([0.1, 0.2, 0.3] * points))
    return b


OBJ_TRIANGLE = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"
OBJ_QUAD = (b"# a quad with texture coordinates and normals\no quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
            b"vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\ng front\nusemtl grey\ns 1\n"
            b"f 1/1/1 2/2/1 3/3/1 4/4/1\n")
OBJ_NEGATIVE = b"v 0 0 0\r\nv 2 0 0\r\nv 0 2 0\r\nvn 0 0 -1\r\nf -3//1 -1//1 -2//1\r\n"
OBJ_PENTAGON = b"v 0 0 0\nv 1 0 0\nv 1.5 1 0\nv 0.5 1.6 0\nv -0.5 1 0\nf 1 2 3 4 5\nl 1 2\n"

def scene(**values):
    return json.dumps(values, indent=1).encode()


SCENE_KEY = {"time": 0.5, "camera": {"yaw": -30, "pitch": 12.5, "distance": 1.5, "target": [0, 0.1, 0]},
             "sphere": [0.1, 0.2, 0.3, 0.05], "light": {"azimuth": 40, "elevation": -10, "intensity": 2},
             "wind": [1, 0, -2], "head_yaw": 20}
SCENE_SEEDS = {
    "empty.json": b"{}",
    "version.json": scene(version=1, description="nothing else"),
    "grown.json": scene(head="heads/bust.json", hair={"guides": 40, "vertices": 8, "hair_length": 0.3,
                                                      "length_variation": 0.2, "curl": 0.01, "poisson": True,
                                                      "seed": 7, "global_stiffness": 0.2, "drag": 3}),
    "loaded.json": scene(hair={"files": ["shared:a/b.tfx", {"file": "c.tfx", "local_stiffness": 0.4, "damping": 0.9}],
                               "scale": 0.01, "offset": [0, -0.02, 0.01], "z_up": True, "mirror_z": False}),
    "colliders.json": scene(colliders=[{"name": "cranium", "center": [0, 0.1, 0], "radii": [0.09, 0.11, 0.12],
                                        "rotation_deg": [10, 0, -5]}, {"center": [0, 0, 0], "radii": [1, 1, 1]}]),
    "physics.json": scene(physics={"wind": [0, 0, 1], "sphere": [0, 0, 0, 0], "repulsion": 0.25,
                                   "grid_atomics": "float"}),
    "settings.json": scene(settings={"strands_per_guide": 8, "lod": False, "hair_preset": "auburn",
                                     "hair_color": [0.3, 0.2, 0.1], "width": 0.0004, "transparency": "oit"}),
    "keys.json": scene(interpolation="linear", duration=4, keys=[{"time": 0, "head_yaw": 0}, SCENE_KEY,
                                                                 {"time": 3.25, "camera": {"yaw": 390}}]),
}
for path in sorted(glob.glob(os.path.join(ROOT, "scenes", "*.json"))):
    with open(path, "rb") as f:
        SCENE_SEEDS["shipped-" + os.path.basename(path)] = f.read()

SEEDS = {
    "fuzz_tfx2": {
        "plain.tfx": tfx2(2, 3, "version 2.0"),
        "transform.tfx": tfx2(3, 4, "version 2.0\nscale 0.5\nrotation 0 90 0\ntranslation 1 2 3\n"
                                    "bothEndsImmovable 1\nmaxNumVerticesInStrand 4\nnumFollowHairsPerGuideHair 0\n"
                                    "maxRadiusAroundGuideHair 0.5"),
        "crlf_bom.tfx": tfx2(1, 2, "# exported\nscale 1 2 3", newline="\r\n", bom=True),
    },
    # fuzz_tfx reads a version byte (odd: 4.0, even: 3.0), then the file from byte 4.
    "fuzz_tfx": {
        "v3.bin": b"\x00" + tfx3(2, 3)[4:],
        "v3_both_ends.bin": b"\x00" + tfx3(1, 4, both_ends=1)[4:],
        "v4.bin": b"\x01" + tfx4(2, 3)[4:],
        "v4_pinned.bin": b"\x01" + tfx4(2, 4, pinned=2)[4:],
    },
    # fuzz_cyhair reads the file after its "HAIR" magic.
    "fuzz_cyhair": {
        "segments.bin": cyhair([2, 1, 3])[4:],
        "default_segments.bin": cyhair([2, 2], array=False)[4:],
        "extra_arrays.bin": cyhair([1, 2], extra=True)[4:],
    },
    "fuzz_obj": {
        "triangle.obj": OBJ_TRIANGLE,
        "quad.obj": OBJ_QUAD,
        "negative.obj": OBJ_NEGATIVE,
        "pentagon.obj": OBJ_PENTAGON,
    },
    "fuzz_scene": SCENE_SEEDS,
}

SCENE_NAMES = ["version", "description", "head", "hair", "colliders", "physics", "settings", "interpolation",
               "duration", "keys", "guides", "vertices", "vertices_per_strand", "hair_length", "length_variation",
               "curl", "poisson", "seed", "files", "file", "scale", "offset", "z_up", "mirror_z", "half_turn",
               "global_stiffness", "local_stiffness", "damping", "drag", "name", "center", "radii", "rotation_deg",
               "wind", "sphere", "repulsion", "grid_atomics", "time", "camera", "yaw", "pitch", "distance",
               "target", "light", "azimuth", "elevation", "intensity", "head_yaw", "strands_per_guide", "divisions",
               "width", "lod", "hair_preset", "hair_color", "shading", "transparency", "step_hz", "substeps",
               "grid", "friction", "samples", "shadow_size", "oit_nodes_per_pixel"]

DICTIONARIES = {
    "fuzz_tfx2": ["version", "scale", "rotation", "translation", "bothEndsImmovable", "maxNumVerticesInStrand",
                  "numFollowHairsPerGuideHair", "maxRadiusAroundGuideHair", "numStrands", "is sorted", "strand",
                  "numVerts", "texcoord", "#", "\r\n", "1e38", "1e30", "-0", "nan", "inf"],
    "fuzz_obj": ["v ", "vn ", "vt ", "vp ", "f ", "l ", "p ", "o ", "g ", "s ", "usemtl ", "mtllib ", "/", "//", "-1",
                 "#", "\r\n", "\\\n", "1e38", "nan", "inf"],
    "fuzz_scene": ['"%s":' % n for n in SCENE_NAMES] +
                  ["{", "}", "[", "]", ",", ":", "true", "false", "null", '"shared:', '"linear"', '"smooth"',
                   '"fixed"', '"float"', '"on"', '"off"', "\\u0000", "\\ud800", "1e308", "1e400", "-0", "0.1",
                   "3600", "4294967295", "4294967296", "2000000", "1e-320"],
}


def escape(c):
    """A character as libFuzzer's dictionaries write it: printable, else \\xNN."""
    if c in '\\"' or not c.isprintable():
        return "\\x%02X" % ord(c)
    return c


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: make_corpus.py OUT_DIR")
    out = sys.argv[1]
    for target, files in SEEDS.items():
        folder = os.path.join(out, target)
        os.makedirs(folder, exist_ok=True)
        for name, data in files.items():
            with open(os.path.join(folder, name), "wb") as f:
                f.write(data)
    for target, words in DICTIONARIES.items():
        with open(os.path.join(out, target + ".dict"), "w") as f:
            f.writelines('"' + "".join(escape(c) for c in w) + '"\n' for w in words)


if __name__ == "__main__":
    main()
