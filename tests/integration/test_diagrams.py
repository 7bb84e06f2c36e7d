"""`arbor pairs` formats and plots, and `arbor diagram-distance`, end to end.

Run by ctest with ARBOR, ARBOR_SHARED_DIR and ARBOR_SCRATCH (see test_cli.py).
TTK's reference pair files are the independent oracle: Arbor's diagram of a
volume is at distance 0 from TTK's, and the CSV holds TTK's pairs.
"""
import csv
import gzip
import json
import os
import pathlib
import struct
import subprocess
import unittest
import xml.etree.ElementTree as ET

ARBOR = os.environ["ARBOR"]
SHARED = pathlib.Path(os.environ["ARBOR_SHARED_DIR"])
DATA = SHARED / "data"
TTK = SHARED / "reference" / "ttk"
SCRATCH = pathlib.Path(os.environ["ARBOR_SCRATCH"])


def arbor(*args, check=True):
    env = dict(os.environ)
    env.pop("ARBOR_PLUGIN_PATH", None)
    env["HOME"] = str(SCRATCH / "home")
    p = subprocess.run([ARBOR, *map(str, args)], capture_output=True, text=True, env=env, timeout=600)
    if check and p.returncode != 0:
        raise AssertionError(f"arbor {' '.join(map(str, args))} failed ({p.returncode}):\n{p.stderr}")
    return p.returncode, p.stdout, p.stderr


def ttk_pairs(name):
    """(type, birth vertex, death vertex, birth value, death value) of TTK's file."""
    out = []
    with gzip.open(TTK / f"{name}.pairs.txt.gz", "rt") as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            t, bv, dv, b, d = line.split()[:5]
            out.append((int(t), int(bv), int(dv), float(b), float(d)))
    return out


def png_size(path):
    with open(path, "rb") as f:
        head = f.read(24)
    assert head[:8] == b"\x89PNG\r\n\x1a\n", path
    return struct.unpack(">II", head[16:24])


class Diagrams(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        SCRATCH.mkdir(parents=True, exist_ok=True)

    def test_csv_holds_ttks_pairs_with_dimensions(self):
        out = SCRATCH / "nucleon.csv"
        arbor("pairs", DATA / "nucleon/nucleon.nrrd", "-o", out)
        with open(out, newline="") as f:
            rows = list(csv.DictReader(f))
        want = ttk_pairs("nucleon")
        self.assertEqual(len(rows), len(want))
        got = {(int(r["birth_vertex"]), int(r["death_vertex"])): r for r in rows}
        for t, bv, dv, b, d in want:
            r = got[(bv, dv)]
            self.assertEqual(float(r["birth"]), b)
            self.assertEqual(float(r["death"]), d)
            self.assertEqual(int(r["essential"]), 1 if t == -1 else 0)
            self.assertEqual(int(r["dimension"]), 2 if t == 2 else 0)
            self.assertEqual(float(r["persistence"]), d - b)
            # grid coordinates of the vertices (41^3)
            self.assertEqual(int(r["bx"]) + 41 * (int(r["by"]) + 41 * int(r["bz"])), bv)

    def test_distance_to_ttk_is_zero(self):
        for name, data in [("bucky", "bucky/bucky.nhdr"), ("neghip", "neghip/neghip.nhdr")]:
            ours = SCRATCH / f"{name}.pairs.txt"
            arbor("pairs", DATA / data, "-o", ours)
            for metric in ["bottleneck", "wasserstein"]:
                _, text, _ = arbor("diagram-distance", ours, TTK / f"{name}.pairs.txt.gz", "--metric", metric, "--json")
                r = json.loads(text)
                self.assertEqual(r["total"], 0.0, name)
                self.assertTrue(r["exact"])
                self.assertEqual([d["dimension"] for d in r["dimensions"]], [0, 2])
                self.assertEqual(r["dimensions"][0]["essential_a"], 1)

    def test_distance_between_two_volumes(self):
        """bucky against nucleon, by hand-checkable parts: per dimension, and
        the total as defined; the bottleneck never above W2 nor W1."""
        a, b = TTK / "bucky.pairs.txt.gz", TTK / "nucleon.pairs.txt.gz"
        res = {}
        for metric, p in [("bottleneck", 2), ("wasserstein", 1), ("wasserstein", 2)]:
            _, text, _ = arbor("diagram-distance", a, b, "--metric", metric, "--p", p, "--json")
            res[(metric, p)] = json.loads(text)
        bn, w1, w2 = res[("bottleneck", 2)], res[("wasserstein", 1)], res[("wasserstein", 2)]
        self.assertGreater(bn["total"], 0)
        self.assertEqual(bn["total"], max(d["distance"] for d in bn["dimensions"]))
        self.assertAlmostEqual(w2["total"], sum(d["distance"] ** 2 for d in w2["dimensions"]) ** 0.5, places=9)
        self.assertGreaterEqual(w2["total"], bn["total"])
        self.assertGreaterEqual(w1["total"], w2["total"])
        # Symmetric, and one dimension alone.
        _, text, _ = arbor("diagram-distance", b, a, "--metric", "wasserstein", "--json")
        self.assertEqual(json.loads(text)["total"], w2["total"])
        _, text, _ = arbor("diagram-distance", a, b, "--dimension", "2", "--json")
        only = json.loads(text)
        self.assertEqual(len(only["dimensions"]), 1)
        self.assertEqual(only["total"], w2["dimensions"][1]["distance"])
        # The text form prints the same total.
        _, text, _ = arbor("diagram-distance", a, b)
        self.assertIn("total", text)
        self.assertIn(f"{w2['total']:.10g}", text)

    def test_vtu_is_vtk_xml_with_ttks_arrays(self):
        out = SCRATCH / "bucky.vtu"
        arbor("pairs", DATA / "bucky/bucky.nhdr", "-o", out)
        root = ET.parse(out).getroot()
        self.assertEqual(root.get("type"), "UnstructuredGrid")
        piece = root.find("UnstructuredGrid/Piece")
        n = len(ttk_pairs("bucky"))
        self.assertEqual(int(piece.get("NumberOfPoints")), 2 * n)
        self.assertEqual(int(piece.get("NumberOfCells")), n + 1)
        point_arrays = {a.get("Name"): a.get("type") for a in piece.find("PointData")}
        cell_arrays = {a.get("Name"): a.get("type") for a in piece.find("CellData")}
        self.assertEqual(point_arrays["ttkVertexScalarField"], "Int32")
        self.assertEqual(point_arrays["CriticalType"], "Int32")
        self.assertEqual(point_arrays["Coordinates"], "Float32")
        for name in ["PairIdentifier", "PairType"]:
            self.assertEqual(cell_arrays[name], "Int32")
        for name in ["Persistence", "Birth", "IsFinite"]:
            self.assertIn(name, cell_arrays)

    def test_plots_png_and_svg(self):
        png, svg = SCRATCH / "nucleon-diagram.png", SCRATCH / "nucleon-diagram.svg"
        arbor("pairs", DATA / "nucleon/nucleon.nrrd", "--plot", png, "--plot", svg, "--dpi", "150",
              "--plot-size", "4")
        self.assertEqual(png_size(png), (600, 600))  # 4 in at 150 dpi
        root = ET.parse(svg).getroot()
        self.assertTrue(root.tag.endswith("svg"))
        self.assertEqual(root.get("width"), "288pt")  # 4 in

    def test_bad_command_lines_exit_2(self):
        f = TTK / "bucky.pairs.txt.gz"
        for args in [["diagram-distance", f, f, "--metric", "l2"],
                     ["diagram-distance", f, f, "--p", "0.5"],
                     ["diagram-distance", f, f, "--dimension", "7"],
                     ["diagram-distance", f],
                     ["pairs", DATA / "bucky/bucky.nhdr"],
                     ["pairs", DATA / "bucky/bucky.nhdr", "--plot", SCRATCH / "x.jpg"],
                     ["pairs", DATA / "bucky/bucky.nhdr", "-o", SCRATCH / "x.txt", "--format", "xml"]]:
            code, _, err = arbor(*args, check=False)
            self.assertEqual(code, 2, f"{args}: {err}")

    def test_malformed_diagram_names_file_and_line(self):
        bad = SCRATCH / "bad.pairs.txt"
        bad.write_text("# dims=4 4 4\n0 1 2 3 4\n2 5 6 9 oops 3\n")
        code, _, err = arbor("diagram-distance", bad, TTK / "bucky.pairs.txt.gz", check=False)
        self.assertEqual(code, 1)
        self.assertIn("bad.pairs.txt:3:", err)
        truncated = SCRATCH / "truncated.pairs.txt.gz"
        # Cut in the middle of the deflate data, and a whole stream short of
        # its trailer: both are errors, not a shorter diagram.
        whole = gzip.compress("".join(f"0 {i} {i + 1} {i} {i + 1}\n" for i in range(5000)).encode())
        truncated.write_bytes(whole[:len(whole) // 2])
        code, _, err = arbor("diagram-distance", truncated, TTK / "bucky.pairs.txt.gz", check=False)
        self.assertEqual(code, 1)
        self.assertIn("truncated.pairs.txt.gz: truncated", err)
        truncated.write_bytes(whole[:-4])
        code, _, err = arbor("diagram-distance", truncated, TTK / "bucky.pairs.txt.gz", check=False)
        self.assertEqual(code, 1)
        self.assertIn("truncated.pairs.txt.gz: truncated", err)


if __name__ == "__main__":
    unittest.main()
