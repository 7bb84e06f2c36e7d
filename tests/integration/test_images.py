"""The default image, end to end: measured visibility, framing, the clear
background, automatic denoising, automatic shapes per structure and the
automatic viewpoint, on the phantom (whose structures are known) and a real
CT.  Run by ctest like test_cli.py.
"""
import json
import unittest

from test_cli import DATA, SCRATCH, arbor, png_pixels

# The phantom's structures (resources/phantoms/head.json): centres in mm.
TUMOUR, VENTRICLE = (-27, 47, 10), (24, -5, 10)
LEFT, RIGHT = (27, 0, 2), (-27, 0, 2)


def report(name):
    return json.loads((SCRATCH / f"{name}.report.json").read_text())


def run(name, *args):
    _, out, err = arbor("run", *args, "-o", SCRATCH / f"{name}.png")
    return report(name), out, err


def near(branch, centre, mm):
    return sum((a - c) ** 2 for a, c in zip(branch["extremum_position_mm"], centre)) < mm ** 2


def content_fraction(png):
    """The extent of the pixels where something is seen (unlike the background
    in the corner), over the shorter side."""
    w, h, bpp, rows = png_pixels(png)
    background = rows[0][:bpp]
    xs, ys = [], []
    for y, row in enumerate(rows):
        for x in range(w):
            if sum(abs(row[x * bpp + c] - background[c]) for c in range(3)) > 12:
                xs.append(x)
                ys.append(y)
    return max(max(xs) - min(xs) + 1, max(ys) - min(ys) + 1) / min(w, h)


class DefaultImage(unittest.TestCase):
    def test_the_phantom_frames_measures_and_shapes_its_structures(self):
        r, out, _ = run("phantom", "--phantom", "head", "--width", 160, "--height", 160)
        # Visibility: every branch's share, adding up to 1, printed per branch.
        shares = [b["visibility"] for b in r["branches"]]
        self.assertAlmostEqual(sum(shares), 1.0, places=6)
        self.assertIn("visibility", out)
        # Framing: the content fills about 85 % of the shorter side.
        self.assertGreater(r["framing"]["scale"], 1.2)
        self.assertAlmostEqual(content_fraction(SCRATCH / "phantom.png"), 0.85, delta=0.07)
        # Balance: the root and the kept structures within their bounds.
        # Labels resolved per sample draw a structure at its isosurface's
        # size, not its voxels' cubes: the phantom's smallest kept one, the
        # tumour (a 5 mm core at depth 4, fully opaque, its ancestors
        # peeled), holds 0.96 % of a 160-pixel image, its cubes held 1.5 %.
        self.assertLessEqual(shares[0], 0.40)
        for b in r["branches"][1:]:
            self.assertGreaterEqual(b["visibility"], 0.008, b)
        by_place = lambda centre: [b for b in r["branches"] if near(b, centre, 10)]
        tumour, ventricle = by_place(TUMOUR), by_place(VENTRICLE)
        self.assertTrue(tumour and ventricle, "the tumour and the ventricle are kept")
        self.assertGreaterEqual(tumour[0]["visibility"], 0.008)  # the core above
        self.assertGreaterEqual(ventricle[0]["visibility"], 0.01)
        # Automatic shapes: the body a ramp, the skull (a dark shell) a hat,
        # the solid structures a box or a ramp, each saying why.
        shape = lambda b: b["generator_note"].split(":")[0]
        self.assertEqual(shape(r["branches"][0]), "ramp")
        skull = [b for b in r["branches"] if b["kind"] == "minimum" and b["depth"] == 1]
        self.assertEqual([shape(b) for b in skull], ["hat"], skull)
        self.assertIn("thin", skull[0]["generator_note"])
        self.assertEqual(shape(ventricle[0]), "box")
        self.assertIn(shape(tumour[0]), ("ramp", "box"))
        for hemisphere in by_place(LEFT)[:1] + by_place(RIGHT)[:1]:
            self.assertIn(shape(hemisphere), ("ramp", "box"), hemisphere["generator_note"])

    def test_the_automatic_view_shows_the_tumour_better_than_the_front(self):
        front, _, _ = run("front", "--phantom", "head", "--width", 96, "--height", 96)
        auto, _, _ = run("auto-view", "--phantom", "head", "--view", "auto", "--width", 96, "--height", 96)
        self.assertIn("viewpoint", auto)
        self.assertGreater(auto["viewpoint"]["score"], auto["viewpoint"]["anterior_score"])
        self.assertNotEqual((auto["camera"]["azimuth"], auto["camera"]["elevation"]), (0, 0))
        share = lambda r: next(b["visibility"] for b in r["branches"] if near(b, TUMOUR, 10))
        self.assertGreater(share(auto), share(front))

    def test_noise_is_studied_and_smoothed_unless_told_not_to(self):
        noisy = ("--phantom", "head", "--phantom-noise", 8, "--width", 64, "--height", 64)
        r, _, err = run("noisy", *noisy)
        self.assertIn("(automatic)", r["input"]["source"])
        self.assertIn("automatic denoising", err)
        self.assertEqual(r["plugins"]["filter"]["id"], "org.arbor.filter.gaussian")
        self.assertTrue(any(near(b, TUMOUR, 10) for b in r["branches"]), "smoothing kept the tumour")
        plain, _, _ = run("plain", *noisy, "--filter", "none")
        self.assertNotIn("gaussian", plain["input"]["source"])
        self.assertGreater(plain["simplification"]["branches_before"], 5 * r["simplification"]["branches_before"])
        clean, _, err = run("clean", "--phantom", "head", "--width", 64, "--height", 64)
        self.assertNotIn("gaussian", clean["input"]["source"])
        self.assertIn("not dominated by noise", err)

    def test_a_real_ct_keeps_its_air_clear_and_names_its_tissues(self):
        r, out, _ = run("ct", DATA / "dicom_ct_head_0051", "--width", 128, "--height", 128)
        for b in r["branches"][1:]:
            self.assertGreater(b["hu_range"][1], -900, b)  # no basin of the air is a structure
        self.assertLessEqual(r["branches"][0]["visibility"], 0.40)
        # Every structure gets its share; the headrest, outside the body, is
        # faint context instead (at most 2 %, no floor).
        for b in r["branches"][1:]:
            if b.get("context"):
                self.assertLessEqual(b["visibility"], 0.03, b)
            else:
                self.assertGreaterEqual(b["visibility"], 0.01, b)
        self.assertEqual(sum(1 for b in r["branches"] if b.get("context") == "outside the body"), 2)
        # What the headrest gave up is not all forced onto the one structure
        # left free by the caps (the nasal cavity: 32 % without the limit).
        cavity = [b for b in r["branches"] if b["kind"] == "minimum"]
        self.assertEqual(len(cavity), 1)
        self.assertLess(cavity[0]["visibility"], 0.2)
        # The skull (a sheet over its cap) takes the rest: bone leads.
        self.assertGreaterEqual(max(r["branches"], key=lambda b: b["visibility"])["hu_range"][0], 300)
        bone = [b for b in r["branches"] if b["hu_range"][0] >= 300]
        self.assertTrue(bone)
        top3 = sorted(r["branches"], key=lambda b: -b["visibility"])[:3]
        self.assertTrue(any(b in bone for b in top3), "a bone branch is among the three most visible")
        self.assertIn("HU range", out)
        self.assertIn("bone", out)

    def test_a_real_mr_gives_every_structure_its_share(self):
        # Colin27: a brain MR with a dozen kept structures, several of them
        # thin and nested (cortex, ventricles): none is lost, none takes over.
        r, _, _ = run("mr", DATA / "mr_brain_colin27/ch2.nii.gz", "--width", 128, "--height", 128)
        shares = [b["visibility"] for b in r["branches"]]
        self.assertGreater(len(shares), 5)
        self.assertAlmostEqual(sum(shares), 1.0, places=6)
        self.assertLessEqual(shares[0], 0.40)
        for b in r["branches"][1:]:
            self.assertGreaterEqual(b["visibility"], 0.01, b)
        self.assertLess(max(shares), 0.5)
        self.assertAlmostEqual(content_fraction(SCRATCH / "mr.png"), 0.85, delta=0.08)


if __name__ == "__main__":
    unittest.main()
