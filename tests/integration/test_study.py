"""The study layer end to end: `arbor compare` sweeps against separate
single runs, one-to-one matching against best match, provenance, results
that are byte-identical across runs, figures, and `arbor denoise-study`
with a ground truth.

Run by ctest with ARBOR, ARBOR_SHARED_DIR, ARBOR_SCRATCH (see test_cli.py).
"""
import csv
import hashlib
import json
import os
import pathlib
import struct
import subprocess
import unittest
import xml.etree.ElementTree as ElementTree

ARBOR = os.environ["ARBOR"]
DATA = pathlib.Path(os.environ["ARBOR_SHARED_DIR"]) / "data"
SCRATCH = pathlib.Path(os.environ["ARBOR_SCRATCH"])


def arbor(*args, check=True):
    env = dict(os.environ)
    env.pop("ARBOR_PLUGIN_PATH", None)
    env["HOME"] = str(SCRATCH / "home")
    env["ARBOR_CACHE_DIR"] = str(SCRATCH / "cache")
    p = subprocess.run([ARBOR, *map(str, args)], capture_output=True, text=True, env=env, timeout=600)
    if check and p.returncode != 0:
        raise AssertionError(f"arbor {' '.join(map(str, args))} failed ({p.returncode}):\n{p.stderr}")
    return p.returncode, p.stdout, p.stderr


def png_size(path):
    with open(path, "rb") as f:
        head = f.read(24)
    assert head[:8] == b"\x89PNG\r\n\x1a\n", f"{path} is not a PNG"
    return struct.unpack(">II", head[16:24])


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


class Study(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        SCRATCH.mkdir(parents=True, exist_ok=True)
        cls.phantom, cls.truth = SCRATCH / "study-noisy.nrrd", SCRATCH / "study-truth.nrrd"
        arbor("phantom", "--size", 64, "--noise", 6, "--blobs", 8, "-o", cls.phantom, "--labels", cls.truth)
        cls.names = {int(l.split()[0]): l.split()[1].replace("_", " ")
                     for l in (SCRATCH / "study-truth.ctbl").read_text().splitlines() if not l.startswith("#")}
        cls.sweep = SCRATCH / "study-sweep"
        arbor("compare", cls.phantom, "--truth", cls.truth, "--out", cls.sweep, "--keep", "4,8,16",
              "--simplifiers", "itri,persistence,n-measure:measures=persistence+volume,"
              "n-measure:measures=persistence+hypervolume", "--filter", "none", "--filter", "gaussian:sigma=1")

    def test_a_sweep_equals_its_single_runs(self):
        sweep = {(r["filter"], r["cut"], r["simplifier"], r["truth_label"]): r for r in rows(self.sweep / "study.csv")}
        self.assertEqual(len(sweep), 2 * 3 * 4 * (len(self.names) - 1))  # label 0 of the table is the background
        checked = 0
        for filter_ in ("none", "gaussian:sigma=1"):
            for keep in (4, 16):
                for simplifier in ("itri", "n-measure:measures=persistence+hypervolume"):
                    out = SCRATCH / f"study-single-{checked}"
                    arbor("compare", self.phantom, "--truth", self.truth, "--out", out, "--keep", keep,
                          "--simplifiers", simplifier, "--filter", filter_)
                    for r in rows(out / "study.csv"):
                        s = sweep[(filter_, f"keep {keep}", simplifier, r["truth_label"])]
                        for column in ("kept", "matched_label", "dice", "precision", "recall", "region_voxels",
                                       "best_label", "best_dice"):
                            self.assertEqual(r[column], s[column], (filter_, keep, simplifier, column))
                        checked += 1
        self.assertEqual(checked, 2 * 2 * 2 * (len(self.names) - 1))

    def test_one_plugin_with_two_settings_is_recorded_with_its_parameters(self):
        r = json.loads((self.sweep / "report.json").read_text())
        settings = [s for s in r["study"]["simplifiers"] if s["id"] == "org.arbor.simplifier.n-measure"]
        self.assertEqual([s["parameters"]["measures"] for s in settings],
                         ["persistence+volume", "persistence+hypervolume"])
        plugins = [p for p in r["provenance"]["plugins"] if p["role"] == "simplifier"]
        self.assertEqual(len(plugins), 4)
        for p in plugins:
            self.assertTrue(pathlib.Path(p["library"]).is_file())
            self.assertTrue(p["version"])
        itri = next(p for p in plugins if p["id"] == "org.arbor.simplifier.itri")
        self.assertIn("parameters", itri)
        # The two settings rank differently somewhere, or they would be one setting.
        kept = {s["label"]: [len(c["kept"]) for c in s["cuts"]] for s in r["results"][0]["simplifiers"]}
        self.assertEqual(kept["n-measure:measures=persistence+volume"], [4, 8, 16])

    def test_provenance_names_the_code_the_command_and_the_data(self):
        r = json.loads((self.sweep / "report.json").read_text())
        p = r["provenance"]
        self.assertRegex(p["arbor"]["commit"], r"^([0-9a-f]{40}(-modified)?|unknown)$")
        self.assertTrue(p["arbor"]["version"])
        self.assertEqual(p["command_line"][1], "compare")
        self.assertIn("gaussian:sigma=1", p["command_line"])
        self.assertEqual(p["input"]["path"], str(self.phantom))
        self.assertRegex(p["input"]["checksum"], r"^xxh3-128:[0-9a-f]{32}$")
        self.assertEqual(p["input"]["importer"]["id"], "org.arbor.importer.nrrd")
        filters = [x for x in p["plugins"] if x["role"].startswith("filter")]
        self.assertEqual([x["parameters"]["sigma"] for x in filters], ["1"])
        chains = {f["label"]: f["chain"] for f in r["study"]["filters"]}
        self.assertEqual(chains["none"], [])
        self.assertEqual(chains["gaussian:sigma=1"][0]["id"], "org.arbor.filter.gaussian")

    def test_every_result_json_carries_the_provenance(self):
        small = ("--phantom", "head", "--phantom-size", 32)
        out = SCRATCH / "provenance"
        out.mkdir(exist_ok=True)
        pairs = out / "pairs.txt"
        arbor("run", *small, "-o", out / "run.png", "--keep", 4)
        arbor("tree", *small, "--json", out / "tree.json")
        arbor("simplify", *small, "--keep", 4, "--json", out / "simplify.json")
        arbor("tf", *small, "--keep", 4, "-o", out / "tf.json")
        arbor("render", *small, "--orbit", 2, "-o", out / "orbit.gif")
        arbor("pairs", *small, "-o", pairs)
        _, distance, _ = arbor("diagram-distance", pairs, pairs, "--json")
        results = {name: json.loads((out / name).read_text())
                   for name in ("run.report.json", "tree.json", "simplify.json", "tf.json", "orbit.gif.report.json")}
        results["diagram-distance"] = json.loads(distance)
        for name, result in results.items():
            with self.subTest(result=name):
                p = result["provenance"]
                self.assertTrue(p["arbor"]["version"])
                self.assertRegex(p["arbor"]["commit"], r"^([0-9a-f]{40}(-modified)?|unknown)$")
                self.assertIn(p["command_line"][1], name.replace("run.report", "run").replace("orbit.gif.report",
                                                                                                "render"))
                if name != "diagram-distance":
                    self.assertEqual(p["input"]["phantom"]["size"], 32)
                    self.assertRegex(p["input"]["checksum"], r"^xxh3-128:[0-9a-f]{32}$")
        # Each plugin that took part, with every parameter's value.
        roles = {x["role"]: x for x in results["run.report.json"]["provenance"]["plugins"]}
        self.assertEqual(roles["simplifier"]["id"], "org.arbor.simplifier.itri")
        self.assertIn("flow-rate", roles["generator"]["parameters"])

    def test_the_checksum_is_of_the_voxels_not_the_file(self):
        a, b = SCRATCH / "checksum-a", SCRATCH / "checksum-b"
        copy = SCRATCH / "study-noisy-copy.nhdr"
        arbor("convert", self.phantom, "-o", copy)
        arbor("compare", self.phantom, "--keep", 3, "--simplifiers", "volume", "--out", a)
        arbor("compare", copy, "--keep", 3, "--simplifiers", "volume", "--out", b)
        ca = json.loads((a / "report.json").read_text())["provenance"]["input"]["checksum"]
        cb = json.loads((b / "report.json").read_text())["provenance"]["input"]["checksum"]
        self.assertEqual(ca, cb)
        other = SCRATCH / "checksum-c"
        arbor("compare", "--phantom", "head", "--phantom-size", 64, "--keep", 3, "--simplifiers", "volume",
              "--out", other)
        phantom = json.loads((other / "report.json").read_text())["provenance"]["input"]
        self.assertNotEqual(phantom["checksum"], ca)
        self.assertEqual(phantom["phantom"], {"kind": "head", "size": 64, "noise": 0, "blobs": 0, "seed": 1})

    def test_two_runs_of_a_study_write_the_same_bytes(self):
        again = SCRATCH / "study-sweep-again"
        args = ["compare", self.phantom, "--truth", self.truth, "--keep", "4,8,16", "--simplifiers",
                "itri,persistence,n-measure:measures=persistence+volume,n-measure:measures=persistence+hypervolume",
                "--filter", "none", "--filter", "gaussian:sigma=1"]
        # The first run's command line named its own folder; give the same one.
        arbor(*args, "--out", again)
        first = {f.name: hashlib.sha256(f.read_bytes()).hexdigest() for f in again.iterdir()}
        arbor(*args, "--out", again)
        second = {f.name: hashlib.sha256(f.read_bytes()).hexdigest() for f in again.iterdir()}
        for name in ("report.json", "study.csv", "report.csv", "report.md", "priority-lines.png",
                     "labels-axial.png", "labels-axial.svg"):
            self.assertEqual(first[name], second[name], name)
        self.assertIn("timings.json", first)

    def test_one_to_one_matching_credits_a_region_once(self):
        # Keeping 2 branches leaves one region for several structures: best
        # match credits it for each, one-to-one for one of them only.
        out = SCRATCH / "study-keep-2"
        arbor("compare", self.phantom, "--truth", self.truth, "--out", out, "--keep", 2, "--simplifiers", "volume")
        table = rows(out / "study.csv")
        best = [r["best_label"] for r in table if r["best_label"] not in ("", "0")]
        matched = [r["matched_label"] for r in table if r["matched_label"] not in ("", "0")]
        self.assertGreater(len(best), len(set(best)), "best match credits no region twice here")
        self.assertEqual(len(matched), len(set(matched)))
        for r in table:
            self.assertLessEqual(float(r["dice"]), float(r["best_dice"]) + 1e-12)

    def test_subtree_scoring_scores_a_branch_with_what_hangs_below_it(self):
        out = SCRATCH / "study-subtree"
        arbor("compare", self.phantom, "--truth", self.truth, "--out", out, "--keep", 8, "--simplifiers", "itri",
              "--score", "subtree")
        table = rows(out / "study.csv")
        self.assertEqual({r["scoring"] for r in table}, {"subtree"})
        exclusive = {r["truth_label"]: r for r in rows(self.sweep / "study.csv")
                     if r["filter"] == "none" and r["cut"] == "keep 8" and r["simplifier"] == "itri"}
        # A region grows (or stays) when its kept descendants join it.
        for r in table:
            if r["matched_label"] and r["matched_label"] == exclusive[r["truth_label"]]["matched_label"]:
                self.assertGreaterEqual(int(r["region_voxels"]), int(exclusive[r["truth_label"]]["region_voxels"]))

    def test_figures_come_as_png_and_svg_at_the_dpi_asked(self):
        report = json.loads((self.sweep / "report.json").read_text())
        figures = report["figures"]
        self.assertIn("priority-lines.png", figures)
        self.assertIn("priority-lines-gaussian_sigma-1.png", figures)
        dice = [f for f in figures if f.startswith("dice-") and f.endswith(".png")]
        self.assertEqual(len(dice), len(self.names) - 1)
        self.assertTrue(any("tumour" in f for f in dice))
        for name in figures:
            path = self.sweep / name
            self.assertTrue(path.is_file(), name)
            if name.endswith(".svg"):
                root = ElementTree.parse(path).getroot()
                self.assertTrue(root.tag.endswith("svg"))
                self.assertTrue(path.with_suffix(".png").is_file())
        low, high = SCRATCH / "study-dpi-75", SCRATCH / "study-dpi-300"
        for out, dpi in ((low, 75), (high, 300)):
            arbor("compare", self.phantom, "--truth", self.truth, "--out", out, "--keep", 4, "--simplifiers", "itri",
                  "--dpi", dpi)
        wl, hl = png_size(low / "labels-axial.png")
        wh, hh = png_size(high / "labels-axial.png")
        self.assertAlmostEqual(wh / wl, 4.0, delta=0.05)
        self.assertAlmostEqual(hh / hl, 4.0, delta=0.05)

    def test_panels_follow_the_axis_and_slice_asked(self):
        out = SCRATCH / "study-coronal"
        arbor("compare", self.phantom, "--truth", self.truth, "--out", out, "--keep", 4, "--simplifiers", "itri",
              "--slice-axis", "coronal", "--slice", 20)
        self.assertIn("labels-coronal.png", json.loads((out / "report.json").read_text())["figures"])
        ElementTree.parse(out / "labels-coronal.svg")
        code, _, err = arbor("compare", self.phantom, "--out", out, "--keep", 4, "--simplifiers", "itri",
                             "--slice", 64, check=False)
        self.assertNotEqual(code, 0)
        self.assertIn("slices are 0..63", err)

    def test_bad_study_settings_are_refused_clearly(self):
        cases = (
            (["--keep", "4,x"], "--keep x"),
            (["--threshold", "0.1,2"], "--threshold 2"),
            (["--keep", 4, "--simplifiers", "itri,itri"], "same setting"),
            (["--keep", 4, "--simplifiers", "measures=volume"], "is a parameter"),
            (["--keep", 4, "--filter", "gaussian:sigma=1", "--filter", "gaussian:sigma=1"], "same setting"),
            (["--keep", 4, "--filter", "+gaussian:sigma=1"], "empty filter"),
        )
        cases += (([], "give --keep"), (["--keep", 4, "--truth-colors", "x.ctbl"], "names the labels of a --truth"))
        for extra, message in cases:
            with self.subTest(extra=extra):
                code, _, err = arbor("compare", "--phantom", "head", "--phantom-size", 32, "--out",
                                     SCRATCH / "study-bad", *extra, check=False)
                self.assertEqual(code, 2)  # a wrong command line
                self.assertIn(message, err)

    def test_denoise_study_with_a_truth_plots_dice_and_says_when_no_plateau_is_in_range(self):
        out = SCRATCH / "study-denoise"
        _, stdout, _ = arbor("denoise-study", self.phantom, "--truth", self.truth, "--keep", 8, "--to", 3,
                             "--steps", 4, "--out", out)
        table = rows(out / "study.csv")
        self.assertEqual(len(table), 4)
        dice_columns = [c for c in table[0] if c.startswith("dice_")]
        self.assertEqual(len(dice_columns), len(self.names) - 1)
        for r in table:
            self.assertEqual(r["kept"], "8")
            for c in dice_columns:
                self.assertTrue(0.0 <= float(r[c]) <= 1.0)
        self.assertTrue((out / "study.svg").is_file())
        # Too short a range: the tree is still shrinking fast at its end.
        short = SCRATCH / "study-denoise-short"
        _, stdout, _ = arbor("denoise-study", self.phantom, "--to", 0.3, "--steps", 3, "--out", short)
        self.assertIn("no plateau", stdout)
        self.assertEqual(sum(int(r["plateau"]) for r in rows(short / "study.csv")), 0)


if __name__ == "__main__":
    unittest.main()
