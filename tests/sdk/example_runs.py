#!/usr/bin/python3
"""Each SDK example plugin used by a real `arbor` command, its output checked
against an oracle computed here, independently of the plugin:

  pgm-stack     a stack written here, converted to NRRD: every voxel, the
                geometry and the value mapping as written; a broken stack
                refused naming the file
  window        the windowed phantom spans exactly the window
  persistence-volume
                every kept branch's importance is relative persistence x
                relative volume^e from its own measures; polarity and the
                physical cut keep what they say
  lineage       roles follow the parents; branches off the line of descent
                have their opacity times `fade`, the others none changed
  palette       colours from the palette by depth, opacity by depth, nothing
                below the physical cut; the host applies the lineage
                depiction to it: opacity times fade, CIELAB chroma times the
                saturation factor, the selection's HSV hue
  mip           on a volume of two cubes, the brightest pixel is the volume's
                maximum, the dimmer cube shows at its grey level, nothing else

    example_runs.py <arbor executable> <work folder>   (ARBOR_PLUGIN_PATH set)
"""
import colorsys
import gzip
import json
import os
import pathlib
import random
import subprocess
import sys

import numpy as np
from PIL import Image

arbor, work = sys.argv[1], pathlib.Path(sys.argv[2])
work.mkdir(parents=True, exist_ok=True)
PHANTOM = ["--phantom", "head", "--phantom-size", "40", "--phantom-noise", "6", "--phantom-blobs", "12"]


def run(*args, fail=False):
    r = subprocess.run([arbor, *map(str, args)], capture_output=True, text=True)
    if fail:
        assert r.returncode != 0, f"arbor {' '.join(map(str, args))} should have failed"
        return r.stderr
    assert r.returncode == 0, f"arbor {' '.join(map(str, args))} failed ({r.returncode}):\n{r.stderr}"
    return r.stdout


def read_nrrd(path):
    raw = pathlib.Path(path).read_bytes()
    head, data = raw.split(b"\n\n", 1)
    fields = {}
    for line in head.decode().splitlines()[1:]:
        if ":" in line and not line.startswith("#"):
            k, v = line.split(":", 1)
            fields[k.strip()] = v.strip()
    if fields.get("encoding") == "gzip":
        data = gzip.decompress(data)
    dtype = {"uint8": "u1", "uint16": "u2", "int16": "i2", "float": "f4"}[fields["type"]]
    dtype = np.dtype(dtype).newbyteorder("<" if fields.get("endian", "little") == "little" else ">")
    sizes = [int(s) for s in fields["sizes"].split()]
    return fields, np.frombuffer(data, dtype=dtype).reshape(sizes[::-1])  # [k][j][i]


def write_nrrd(path, volume, spacing=(1.0, 1.0, 1.0)):
    nz, ny, nx = volume.shape
    header = (f"NRRD0004\ntype: uint16\ndimension: 3\nspace: left-posterior-superior\nsizes: {nx} {ny} {nz}\n"
              f"space directions: ({spacing[0]},0,0) (0,{spacing[1]},0) (0,0,{spacing[2]})\n"
              "kinds: domain domain domain\nendian: little\nencoding: raw\nspace origin: (0,0,0)\n\n")
    pathlib.Path(path).write_bytes(header.encode() + volume.astype("<u2").tobytes())


# ---- pgm-stack importer ---------------------------------------------------------------
def write_pgm(path, image, maxval):
    h, w = image.shape
    body = image.astype(">u2").tobytes() if maxval > 255 else image.astype("u1").tobytes()
    pathlib.Path(path).write_bytes(f"P5\n# slice\n{w} {h}\n{maxval}\n".encode() + body)


def check_pgm_stack():
    nx, ny, nz = 20, 16, 12
    k, j, i = np.meshgrid(np.arange(nz), np.arange(ny), np.arange(nx), indexing="ij")
    volume = ((i * 37 + j * 113 + k * 311) % 4001).astype(np.uint16)
    stack = work / "stack"
    stack.mkdir(exist_ok=True)
    order = list(range(nz))
    random.Random(7).shuffle(order)  # written in any order: read in name order
    for z in order:
        write_pgm(stack / f"slice_{z:03d}.pgm", volume[z], 4000)
    (stack / "notes.txt").write_text("not a slice")
    out = work / "stack.nrrd"
    flags = ["--pgm-stack.spacing", "0.5,0.75,2", "--pgm-stack.value-offset", "-1024", "--pgm-stack.unit", "HU"]
    run("convert", stack, "-o", out, *flags)
    fields, read = read_nrrd(out)
    assert fields["type"] == "uint16" and fields["sizes"] == f"{nx} {ny} {nz}", fields
    assert fields["space directions"] == "(0.5,0,0) (0,0.75,0) (0,0,2)", fields["space directions"]
    assert np.array_equal(read, volume), "the converted stack differs from the slices written"
    info = json.loads(run("info", stack, "--json", *flags))
    assert info["stored"]["min"] == volume.min() and info["stored"]["max"] == volume.max(), info["stored"]
    assert info["physical"]["min"] == volume.min() - 1024 and info["physical"]["unit"] == "HU", info["physical"]

    small = work / "stack8"
    small.mkdir(exist_ok=True)
    slices = [np.arange(12, dtype=np.uint8).reshape(3, 4) * (z + 1) for z in range(2)]
    for z, s in enumerate(slices):
        write_pgm(small / f"{z}.pgm", s, 255)
    info = json.loads(run("info", small, "--json"))
    assert info["voxel_type"] == "u8" and info["dims"] == [4, 3, 2] and info["stored"]["max"] == 22, info

    broken = work / "broken-stack"
    broken.mkdir(exist_ok=True)
    write_pgm(broken / "a.pgm", volume[0], 4000)
    (broken / "b.pgm").write_bytes((stack / "slice_001.pgm").read_bytes()[:-10])
    err = run("info", broken, fail=True)
    assert "b.pgm" in err and "bytes of pixels" in err, err
    print(f"pgm-stack: {nx}x{ny}x{nz} read voxel for voxel, geometry and HU mapping as given; a broken slice named")


# ---- window filter ----------------------------------------------------------------------
def check_window():
    out = work / "windowed.nrrd"
    run("convert", "--phantom", "head", "--phantom-size", "32", "--filter", "org.arbor.example.window",
        "--window.low", "100", "--window.high", "500", "-o", out)
    info = json.loads(run("info", out, "--json"))
    assert info["stored"]["min"] == 100 and info["stored"]["max"] == 500, info["stored"]
    print("window: the windowed phantom spans 100..500")


# ---- persistence x volume^e simplifier ---------------------------------------------------
def kept(json_path):
    return json.loads(pathlib.Path(json_path).read_text())["kept_branches"]


def check_simplifier():
    sid = "org.arbor.example.persistence-volume"
    for e in (0.5, 1.0):
        path = work / f"simplified-{e}.json"
        run("simplify", *PHANTOM, "--simplifier", sid, "--persistence-volume.exponent", e, "--keep", 12,
            "--json", path)
        branches = kept(path)
        root = branches[0]["measures"]
        assert len(branches) == 12, len(branches)
        for b in branches[1:]:
            p = b["measures"]["persistence"] / root["persistence"]
            v = b["measures"]["volume"] / root["volume"]
            expected = p * v**e
            assert abs(b["importance"] - expected) <= 1e-12 + 1e-9 * expected, (e, b["importance"], expected)
    peaks = work / "simplified-peaks.json"
    run("simplify", *PHANTOM, "--simplifier", sid, "--persistence-volume.polarity", "peaks", "--keep", 8,
        "--json", peaks)
    assert all(b["kind"] == "maximum" and b["importance"] > 0 for b in kept(peaks)[1:]), kept(peaks)
    above = work / "simplified-above.json"
    run("simplify", *PHANTOM, "--simplifier", sid, "--persistence-volume.min-extremum", 300, "--threshold", 0,
        "--json", above)
    branches = kept(above)[1:]
    assert branches and all(b["extremum"]["value"] >= 300 for b in branches), [b["extremum"] for b in branches]
    print(f"persistence-volume: importances = p * v^e for e = 0.5 and 1; peaks only; {len(branches)} branches "
          "above 300 at threshold 0")


# ---- lineage depictor and palette generator -------------------------------------------------
def branches_of(path):
    return json.loads(pathlib.Path(path).read_text())["branches"]


def expected_roles(parent, s):
    def ancestors(b):
        out = []
        while parent[b] >= 0:
            b = parent[b]
            out.append(b)
        return out

    roles = []
    for b in range(len(parent)):
        if b == s:
            roles.append("selected")
        elif b == parent[s]:
            roles.append("parent")
        elif b in ancestors(s):
            roles.append("ancestor")
        elif parent[b] == s:
            roles.append("child")
        elif s in ancestors(b):
            roles.append("descendant")
        else:
            roles.append("other")
    return roles


def pick_selection(parent):
    """A branch with a child, not the root: every role then occurs."""
    for b in range(1, len(parent)):
        if b in parent:
            return b
    return 1


def check_lineage():
    tf = ["tf", *PHANTOM, "--keep", 10]
    none = work / "residue-none.json"
    run(*tf, "--relation", "none", "-o", none)
    parent = [b["parent"] for b in branches_of(none)]
    s = pick_selection(parent)
    lined = work / "residue-lineage.json"
    legend = work / "lineage-legend.png"
    run(*tf, "--relation", "org.arbor.example.lineage", "--select", s, "--legend", legend, "-o", lined)
    roles = expected_roles(parent, s)
    others = 0
    for b, (a, n) in enumerate(zip(branches_of(lined), branches_of(none))):
        assert a["role"] == roles[b], (b, a["role"], roles[b])
        factor = 0.2 if roles[b] == "other" else 1.0
        others += roles[b] == "other"
        assert abs(a["opacity_range"][1] - factor * n["opacity_range"][1]) <= 2e-6, (b, a["opacity_range"],
                                                                                      n["opacity_range"], factor)
    assert others > 0
    image = np.asarray(Image.open(legend).convert("RGBA"))
    assert image[..., 3].max() == 255, "the legend is empty"
    print(f"lineage: roles of {len(parent)} branches around {s}; {others} off the line at 0.2 of their opacity")


PALETTE = [(0.60, 0.60, 0.60), (0.90, 0.62, 0.00), (0.34, 0.71, 0.91), (0.00, 0.62, 0.45),
           (0.94, 0.89, 0.26), (0.00, 0.45, 0.70), (0.84, 0.37, 0.00), (0.80, 0.47, 0.65)]


def srgb_to_lab(c):
    lin = [x / 12.92 if x <= 0.04045 else ((x + 0.055) / 1.055) ** 2.4 for x in c]
    m = [[0.4124564, 0.3575761, 0.1804375], [0.2126729, 0.7151522, 0.0721750], [0.0193339, 0.1191920, 0.9503041]]
    white = [0.95047, 1.0, 1.08883]
    f = []
    for r in range(3):
        t = sum(m[r][k] * lin[k] for k in range(3)) / white[r]
        f.append(t ** (1 / 3) if t > (6 / 29) ** 3 else t / (3 * (6 / 29) ** 2) + 4 / 29)
    return [116 * f[1] - 16, 500 * (f[0] - f[1]), 200 * (f[1] - f[2])]


def lab_to_srgb(lab):
    fy = (lab[0] + 16) / 116
    fs = [fy + lab[1] / 500, fy, fy - lab[2] / 200]
    white = [0.95047, 1.0, 1.08883]
    xyz = [white[r] * (f**3 if f > 6 / 29 else 3 * (6 / 29) ** 2 * (f - 4 / 29)) for r, f in enumerate(fs)]
    m = [[3.2404542, -1.5371385, -0.4985314], [-0.9692660, 1.8760108, 0.0415560], [0.0556434, -0.2040259, 1.0572252]]
    out = []
    for r in range(3):
        x = sum(m[r][k] * xyz[k] for k in range(3))
        out.append(min(1.0, max(0.0, 12.92 * x if x <= 0.0031308 else 1.055 * x ** (1 / 2.4) - 0.055)))
    return out


def lut_values(branch, size):
    lo, hi = branch["domain"]
    return [lo + (hi - lo) * i / (size - 1) for i in range(size)]


def check_palette():
    gen = ["--generator", "org.arbor.example.palette", "--palette.clear-below", 150, "--keep", 10]
    plain = work / "palette-none.json"
    run("tf", *PHANTOM, *gen, "--relation", "none", "-o", plain)
    doc = json.loads(plain.read_text())
    size = doc["lut_size"]
    branches = doc["branches"]
    depth = max(b["depth"] for b in branches)
    for b in branches:
        colour = PALETTE[b["depth"] % 8]
        top = 0.8 * (b["depth"] + 1) / (depth + 1)
        lo, hi = b["domain"]
        # The ramp rises from the saddle to the extremum: upwards for the root
        # and peaks, downwards for basins; nothing below the cut.
        start, end = (hi, lo) if b["kind"] == "minimum" else (lo, hi)
        for value, entry in zip(lut_values(b, size), b["lut"]):
            assert all(abs(entry[k] - colour[k]) <= 1e-6 for k in range(3)), (b["label"], entry, colour)
            t = 1.0 if end == start else min(1.0, max(0.0, (value - start) / (end - start)))
            expected = 0.0 if value < 150 else top * t
            assert abs(entry[3] - expected) <= 2e-6, (b["label"], value, entry, expected)
        values = [p["value"] for p in b["points"]]
        assert values == sorted(values) and len(values) >= 2, values
        assert values[0] == lo and values[-1] == hi, (values, b["domain"])

    # The lineage depiction, applied by the host.
    parent = [b["parent"] for b in branches]
    s = next((b["label"] for b in branches if b["depth"] % 8 != 0 and b["label"] in parent), None)
    s = s if s is not None else next(b["label"] for b in branches if b["depth"] % 8 != 0)
    lined = work / "palette-lineage.json"
    run("tf", *PHANTOM, *gen, "--relation", "org.arbor.example.lineage", "--select", s, "--lineage.hue", 200,
        "-o", lined)
    roles = expected_roles(parent, s)
    for a, n in zip(json.loads(lined.read_text())["branches"], branches):
        role = roles[a["label"]]
        colour = PALETTE[a["depth"] % 8]
        if role == "other":
            lab = srgb_to_lab(colour)
            expected = lab_to_srgb([lab[0], 0.3 * lab[1], 0.3 * lab[2]])
            factor = 0.2
        else:
            expected, factor = list(colour), 1.0
        for ea, en in zip(a["lut"], n["lut"]):
            assert abs(ea[3] - factor * en[3]) <= 2e-6, (a["label"], role, ea, en)
            if role != "selected":
                assert all(abs(ea[k] - expected[k]) <= 2e-4 for k in range(3)), (a["label"], role, ea, expected)
        if role == "selected":
            h, sat, v = colorsys.rgb_to_hsv(*a["rgba_at_extremum"][:3])
            assert abs(h * 360 - 200) < 0.5, (h * 360, a["rgba_at_extremum"])
            hs, ss, vs = colorsys.rgb_to_hsv(*colour)
            assert abs(sat - ss) < 1e-4 and abs(v - vs) < 1e-4, (sat, ss, v, vs)
    print(f"palette: {len(branches)} branches coloured and ramped by depth, clear below 150; "
          f"the host applied the lineage around {s} (fade 0.2, chroma 0.3, hue 200)")


# ---- MIP renderer ----------------------------------------------------------------------------
def check_mip():
    volume = np.full((24, 24, 24), 100, dtype=np.uint16)
    volume[4:10, 4:10, 4:10] = 500  # dim cube
    volume[14:20, 14:20, 14:20] = 1000  # bright cube
    path = work / "cubes.nrrd"
    write_nrrd(path, volume)
    image = work / "mip.png"
    run("run", path, "--renderer", "org.arbor.example.mip", "--filter", "none", "--balance", "off", "--view", "fixed",
        "--azimuth", 30, "--elevation", 20, "--width", 96, "--height", 96, "--keep", 3, "-o", image)
    grey = np.asarray(Image.open(image).convert("RGB")).astype(int)
    assert (grey[..., 0] == grey[..., 1]).all() and (grey[..., 1] == grey[..., 2]).all(), "not grey"
    levels = set(np.unique(grey[..., 0]).tolist())
    dim = round(255 * (500 - 100) / (1000 - 100))
    assert max(levels) == 255, f"brightest pixel {max(levels)}, not the volume's maximum"
    assert dim in levels and levels <= {0, dim, 255}, (levels, dim)
    print(f"mip: brightest pixel 255 = the maximum, the dim cube at {dim}, levels {sorted(levels)}")


check_pgm_stack()
check_window()
check_simplifier()
check_lineage()
check_palette()
check_mip()
print("every example plugin ran in a real command and its output matched the oracle")
