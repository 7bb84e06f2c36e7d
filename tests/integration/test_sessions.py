"""End-to-end tests of what the pipeline gives the `arbor` command: sessions
(save, reproduce pixel for pixel, override, refuse), sweeps (one tree, one
image per combination, stage-run counts), the label map that was rendered,
the on-disk contour-tree cache, and Ctrl-C.

Run by ctest like test_cli.py (same environment variables).
"""
import json
import os
import pathlib
import shutil
import signal
import subprocess
import time
import unittest

from test_cli import ARBOR, DATA, SCRATCH, arbor, info, png_pixels, png_size

SMALL = ("--phantom", "head", "--phantom-size", 48, "--phantom-noise", 4)


def session(path):
    return json.loads(pathlib.Path(path).read_text())


class Sessions(unittest.TestCase):
    def test_a_saved_session_reproduces_the_image_pixel_for_pixel(self):
        a, s, b = SCRATCH / "s1" / "a.png", SCRATCH / "s1" / "s.json", SCRATCH / "s1" / "b.png"
        arbor("run", *SMALL, "--keep", 7, "--flow-rate", 90, "--shape", "hat", "--hues", "X:30", "--azimuth", 30,
              "--elevation", 15, "--width", 96, "--height", 80, "--background", "0.1,0.1,0.2", "-o", a,
              "--save-session", s)
        j = session(s)
        self.assertEqual(j["format"], "arbor-session/1")
        self.assertEqual(j["input"]["phantom"], {"kind": "head", "size": 48, "noise": 4, "blobs": 0, "seed": 1})
        self.assertEqual(j["cut"], {"keep": 7, "keep_background": False})
        self.assertEqual(j["appearance"]["generator"]["parameters"]["shape"], "hat")
        self.assertEqual(j["view"]["camera"]["azimuth"], 30)
        _, out, _ = arbor("run", "--session", s, "-o", b)
        self.assertEqual(png_pixels(a), png_pixels(b))
        report = json.loads((SCRATCH / "s1" / "b.report.json").read_text())
        self.assertEqual(report["camera"]["width"], 96)

    def test_a_real_file_with_a_filter_and_a_relative_path(self):
        folder = SCRATCH / "s2"
        folder.mkdir(exist_ok=True)
        data = folder / "data"
        data.mkdir(exist_ok=True)
        (data / "tooth.nhdr").write_text((DATA / "tooth/tooth.nhdr").read_text().replace(
            "data file: ", f"data file: {DATA / 'tooth'}/"))
        first, s = folder / "study" / "first.png", folder / "study" / "tooth.json"
        arbor("run", data / "tooth.nhdr", "--filter", "gaussian:sigma=1", "--simplifier", "persistence",
              "--width", 64, "--height", 64, "-o", first, "--save-session", s)
        j = session(s)
        self.assertEqual(j["input"]["path"], "../data/tooth.nhdr")
        self.assertEqual(j["input"]["importer"]["id"], "org.arbor.importer.nrrd")
        self.assertEqual(j["filters"][0]["id"], "org.arbor.filter.gaussian")
        self.assertEqual(j["filters"][0]["parameters"]["sigma"], 1)
        self.assertEqual(j["simplifier"]["id"], "org.arbor.simplifier.persistence")
        self.assertIn("knee", j["cut"])
        # Read from another working directory: the path is the session's.
        again = folder / "again.png"
        p = subprocess.run([ARBOR, "run", "--session", str(s), "-o", str(again)], capture_output=True, text=True,
                           cwd="/", timeout=600)
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertEqual(png_pixels(first), png_pixels(again))

    def test_a_dicom_series_is_saved_by_its_uid_not_its_row(self):
        import pydicom
        variants = DATA / "dicom_pydicom_variants"
        uid = pydicom.dcmread(variants / "emri_small.dcm", stop_before_pixels=True).SeriesInstanceUID
        s, a = SCRATCH / "s5" / "d.json", SCRATCH / "s5" / "d.png"
        arbor("run", variants, "--series", 2, "--width", 48, "--height", 48, "-o", a, "--save-session", s)
        importer = session(s)["input"]["importer"]
        self.assertEqual(importer["id"], "org.arbor.importer.dicom")
        self.assertEqual(importer["parameters"]["series"], uid)
        self.assertEqual(importer["parameters"]["missing-slices"], "refuse")
        arbor("run", "--session", s, "-o", SCRATCH / "s5" / "again.png")
        self.assertEqual(png_pixels(a), png_pixels(SCRATCH / "s5" / "again.png"))

    def test_flags_beside_a_session_override_it(self):
        a, s = SCRATCH / "s3" / "a.png", SCRATCH / "s3" / "s.json"
        arbor("run", *SMALL, "--keep", 6, "--flow-rate", 30, "--width", 64, "--height", 64, "-o", a,
              "--save-session", s)
        b, s2 = SCRATCH / "s3" / "b.png", SCRATCH / "s3" / "s2.json"
        arbor("run", "--session", s, "--azimuth", 90, "--keep", 5, "--residue-flow.shape", "box", "-o", b,
              "--save-session", s2)
        j, j2 = session(s), session(s2)
        self.assertEqual(j2["view"]["camera"]["azimuth"], 90)
        self.assertEqual(j2["cut"], {"keep": 5, "keep_background": False})
        self.assertEqual(j2["appearance"]["generator"]["parameters"]["shape"], "box")
        # ... and nothing else changed.
        self.assertEqual(j2["appearance"]["generator"]["parameters"]["flow-rate"], 30)
        self.assertEqual(j2["input"], j["input"])
        self.assertEqual(j2["view"]["image"], j["view"]["image"])
        self.assertNotEqual(png_pixels(a), png_pixels(b))
        # Another input beside the session: the session's own need not exist.
        moved = SCRATCH / "s3" / "moved.json"
        doc = session(s)
        doc["input"] = {"path": "gone.nrrd", "importer": None}
        moved.write_text(json.dumps(doc))
        arbor("run", "--session", moved, "--phantom", "head", "--phantom-size", 32, "-o", SCRATCH / "s3" / "c.png")

    def test_refusals_name_the_problem(self):
        s = SCRATCH / "s4" / "s.json"
        arbor("run", *SMALL, "--keep", 6, "--width", 32, "--height", 32, "-o", SCRATCH / "s4" / "a.png",
              "--save-session", s)
        good = session(s)

        def refused(edit, words):
            doc = json.loads(json.dumps(good))
            edit(doc)
            bad = SCRATCH / "s4" / "bad.json"
            bad.write_text(json.dumps(doc))
            code, _, err = arbor("run", "--session", bad, "-o", SCRATCH / "s4" / "b.png", check=False)
            self.assertEqual(code, 1, err)
            for w in words:
                self.assertIn(w, err)
            self.assertRegex(err, r"(?m)^arbor: error: .*bad\.json")

        refused(lambda d: d.update(format="arbor-session/2"), ["arbor-session/2", "newer"])
        refused(lambda d: d["simplifier"].update(id="org.example.simplifier.magic"),
                ["org.example.simplifier.magic", "not installed"])
        refused(lambda d: d["appearance"]["generator"]["parameters"].update({"flow-rate": 1e9}), ["flow-rate"])
        refused(lambda d: d.update(input={"path": "nowhere/scan.nrrd"}), ["nowhere/scan.nrrd", "does not exist"])
        code, _, err = arbor("run", "--session", SCRATCH / "s4" / "none.json", "-o", SCRATCH / "s4" / "c.png",
                             check=False)
        self.assertEqual(code, 1)
        self.assertIn("none.json", err)


class Sweeps(unittest.TestCase):
    def test_every_combination_from_one_contour_tree(self):
        out = SCRATCH / "sweep" / "sweep.png"
        _, stdout, _ = arbor("run", *SMALL, "--keep", 8, "--flow-rate", "30,120,240", "--shape", "ramp,hat",
                             "--width", 64, "--height", 64, "-o", out)
        names = [f"sweep-q{q}-{s}.png" for q in (30, 120, 240) for s in ("ramp", "hat")]
        for n in names:
            self.assertEqual(png_size(out.parent / n), (64, 64), n)
        w, h = png_size(out)  # the contact sheet: 3 x 2 tiles with captions
        self.assertGreater(w, 3 * 64)
        self.assertGreater(h, 2 * 64)
        r = json.loads((out.parent / "sweep.report.json").read_text())
        self.assertEqual(r["format"], "arbor-sweep-report/1")
        self.assertEqual(r["stage_runs"], {"import": 1, "filter": 1, "contour_tree": 1, "decomposition": 1, "cut": 1,
                                           "labels": 1, "depiction": 6, "transfer_functions": 6, "render": 6,
                                           "legend": 6})
        self.assertEqual([run["output"]["image"] for run in r["runs"]], [str(out.parent / n) for n in names])
        self.assertEqual([run["caption"] for run in r["runs"]][:2], ["Q 30, ramp", "Q 30, hat"])
        # The runs differ in their look only, and do differ.
        pixels = {n: png_pixels(out.parent / n) for n in names}
        self.assertEqual(len({tuple(p[3]) for p in pixels.values()}), len(names))

    def test_simplifiers_and_cuts_share_the_tree(self):
        out = SCRATCH / "sweep2" / "study.png"
        arbor("run", *SMALL, "--simplifier", "itri,persistence", "--keep", "5,9", "--width", 48, "--height", 48,
              "-o", out, "--labels", SCRATCH / "sweep2" / "labels.nrrd")
        r = json.loads((out.parent / "study.report.json").read_text())
        runs = r["stage_runs"]
        self.assertEqual((runs["contour_tree"], runs["decomposition"], runs["cut"], runs["render"]), (1, 2, 4, 4))
        self.assertEqual([run["simplification"]["branches_after"] for run in r["runs"]], [5, 9, 5, 9])
        self.assertEqual(r["runs"][2]["plugins"]["simplifier"]["id"], "org.arbor.simplifier.persistence")
        for name in ("itri-k5", "itri-k9", "persistence-k5", "persistence-k9"):
            self.assertTrue((out.parent / f"study-{name}.png").exists())
            self.assertTrue((out.parent / f"labels-{name}.nrrd").exists())

    def test_lists_are_refused_where_they_make_no_sense(self):
        code, _, err = arbor("tf", *SMALL, "--flow-rate", "30,60", "-o", SCRATCH / "x.json", check=False)
        self.assertEqual(code, 2)  # a wrong command line
        self.assertIn("lists are sweeps of `arbor run`", err)
        code, _, err = arbor("run", *SMALL, "--keep", "6,x", "-o", SCRATCH / "x.png", check=False)
        self.assertEqual(code, 2)
        self.assertIn("--keep x", err)


class Labels(unittest.TestCase):
    def test_the_label_map_that_was_rendered(self):
        out, labels = SCRATCH / "lab" / "run.png", SCRATCH / "lab" / "run-labels.nrrd"
        arbor("run", *SMALL, "--keep", 7, "--width", 32, "--height", 32, "-o", out, "--labels", labels)
        j = info(labels)
        self.assertEqual(j["dims"], [48, 48, 48])
        self.assertEqual(j["stored"]["min"], 0)
        self.assertEqual(j["stored"]["max"], 6)
        table = (SCRATCH / "lab" / "run-labels.ctbl").read_text().splitlines()
        entries = [l for l in table if l and not l.startswith("#")]
        self.assertEqual(len(entries), 7)
        report = json.loads((SCRATCH / "lab" / "run.report.json").read_text())
        self.assertEqual(report["labels"], str(labels))
        self.assertEqual(len(report["branches"]), 7)


class TreeCache(unittest.TestCase):
    def env(self, name):
        shutil.rmtree(SCRATCH / name, ignore_errors=True)  # scratch outlives a test run
        return {"ARBOR_CACHE_DIR": str(SCRATCH / name)}

    def test_a_second_run_reads_the_tree_and_a_damaged_entry_is_rebuilt(self):
        env = self.env("cache1")
        first, second = SCRATCH / "c1.json", SCRATCH / "c2.json"
        _, _, err1 = arbor("tree", DATA / "tooth/tooth.nhdr", "--json", first, "--timings", env=env)
        self.assertIn("join+split trees", err1)
        entries = list((SCRATCH / "cache1").glob("*.tree"))
        self.assertEqual(len(entries), 1)
        _, _, err2 = arbor("tree", DATA / "tooth/tooth.nhdr", "--json", second, "--timings", env=env)
        self.assertIn("cache read", err2)
        self.assertNotIn("join+split trees", err2)
        # Everything but the timings and the provenance (whose command line
        # names the output file). Compared as canonical text: unittest's diff
        # of two 15 MB dicts would take hours if they ever differed.
        def strip(p):
            tree = json.loads(p.read_text())
            self.assertIn("provenance", tree)
            return json.dumps({k: v for k, v in tree.items() if k not in ("timings_seconds", "provenance")},
                              sort_keys=True)
        self.assertTrue(strip(first) == strip(second), "the tree read from the cache differs")
        # A damaged entry is noticed, rebuilt, and the answer is the same.
        data = bytearray(entries[0].read_bytes())
        data[len(data) // 2] ^= 0xFF
        entries[0].write_bytes(bytes(data))
        third = SCRATCH / "c3.json"
        _, _, err3 = arbor("tree", DATA / "tooth/tooth.nhdr", "--json", third, env=env)
        self.assertIn("computing the tree again", err3)
        self.assertTrue(strip(first) == strip(third), "the rebuilt tree differs")
        _, _, err4 = arbor("tree", DATA / "tooth/tooth.nhdr", "--json", third, "--timings", env=env)
        self.assertIn("cache read", err4)

    def test_no_cache_neither_reads_nor_writes(self):
        env = self.env("cache2")
        arbor("pairs", DATA / "nucleon/nucleon.nrrd", "-o", SCRATCH / "n.pairs", "--no-cache", env=env)
        self.assertFalse((SCRATCH / "cache2").exists() and any((SCRATCH / "cache2").iterdir()))
        arbor("pairs", DATA / "nucleon/nucleon.nrrd", "-o", SCRATCH / "n.pairs", env=env)
        self.assertEqual(len(list((SCRATCH / "cache2").glob("*.tree"))), 1)
        _, _, err = arbor("pairs", DATA / "nucleon/nucleon.nrrd", "-o", SCRATCH / "n.pairs", "--no-cache",
                          "--timings", env=env)
        self.assertIn("join+split trees", err)

    def test_the_default_folder_is_the_users_cache(self):
        home = SCRATCH / "home-cache"
        shutil.rmtree(home, ignore_errors=True)
        arbor("pairs", DATA / "bucky/bucky.nhdr", "-o", SCRATCH / "b.pairs", env={"HOME": str(home)})
        self.assertEqual(len(list((home / ".cache/arbor/contour-trees").glob("*.tree"))), 1)


class Interrupt(unittest.TestCase):
    def test_ctrl_c_cancels_the_run_promptly(self):
        env = dict(os.environ, HOME=str(SCRATCH / "home"))
        p = subprocess.Popen([ARBOR, "run", "--phantom", "head", "--phantom-size", "320", "--phantom-noise", "12",
                              "--no-cache", "-o", str(SCRATCH / "never.png")], stderr=subprocess.PIPE, text=True,
                             env=env)
        time.sleep(2.5)
        self.assertIsNone(p.poll(), "the run ended before it could be interrupted")
        sent = time.monotonic()
        p.send_signal(signal.SIGINT)
        _, err = p.communicate(timeout=60)
        self.assertEqual(p.returncode, 130, err)
        self.assertLess(time.monotonic() - sent, 10)
        self.assertIn("cancelled", err)
        self.assertFalse((SCRATCH / "never.png").exists())


if __name__ == "__main__":
    unittest.main()
