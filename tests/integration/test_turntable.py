"""`arbor render --orbit N`: a turntable as a video, an animated GIF or a
folder of PNGs, at each quality, with its report; clear refusals; and which
renderer `arbor render` takes by default, and why.  Run by ctest like
test_cli.py.
"""
import json
import unittest

from test_cli import SCRATCH, arbor, png_pixels

PHANTOM = ("--phantom", "head", "--width", 64, "--height", 64)


def report(output):
    return json.loads((SCRATCH / f"{output}.report.json").read_text())


class Turntable(unittest.TestCase):
    def test_a_video_of_n_frames_with_seconds_per_frame(self):
        out = SCRATCH / "orbit.mp4"
        _, stdout, _ = arbor("render", *PHANTOM, "--orbit", 8, "-o", out)
        data = out.read_bytes()
        self.assertEqual(data[4:8], b"ftyp", "an MPEG-4 file")
        self.assertGreater(len(data), 1000)
        self.assertFalse(list(SCRATCH.glob(".orbit.partial*")), "the partial file is gone")
        r = report("orbit.mp4")
        self.assertEqual(r["frames"], 8)
        self.assertEqual(r["quality"], "full")
        self.assertEqual([f["frame"] for f in r["per_frame"]], list(range(1, 9)))
        self.assertEqual([f["azimuth"] for f in r["per_frame"]], [45.0 * i for i in range(8)])
        for f in r["per_frame"]:
            self.assertEqual(len(f["pass_seconds"]), 1)
            self.assertGreater(f["seconds"], 0)
        self.assertIn("8 frames", stdout)

    def test_a_folder_of_pngs_turns_and_comes_back(self):
        out = SCRATCH / "orbit-frames"
        arbor("render", *PHANTOM, "--orbit", 4, "-o", out)
        frames = sorted(out.glob("frame-*.png"))
        self.assertEqual([f.name for f in frames], [f"frame-{i:04d}.png" for i in range(1, 5)])
        pixels = [png_pixels(f)[3] for f in frames]
        self.assertNotEqual(pixels[0], pixels[1], "a quarter turn changes the picture")
        # Half a turn mirrors the (left-right symmetric) phantom's silhouette:
        # the covered pixels per row agree closely.
        def covered(rows, bpp=4):
            return [sum(1 for x in range(64) if row[x * bpp + 3] > 0) for row in rows]
        front, back = covered(pixels[0]), covered(pixels[2])
        self.assertLess(sum(abs(a - b) for a, b in zip(front, back)), 0.1 * sum(front))

    def test_each_quality_has_its_passes(self):
        arbor("render", *PHANTOM, "--orbit", 2, "--quality", "coarse", "-o", SCRATCH / "coarse.avi")
        arbor("render", *PHANTOM, "--orbit", 2, "--quality", "supersampled", "--supersamples", 3,
              "-o", SCRATCH / "super.avi")
        coarse, fine = report("coarse.avi"), report("super.avi")
        self.assertEqual(coarse["quality"], "coarse")
        self.assertEqual([len(f["pass_seconds"]) for f in coarse["per_frame"]], [1, 1])
        self.assertEqual([len(f["pass_seconds"]) for f in fine["per_frame"]], [4, 4])
        self.assertEqual((SCRATCH / "coarse.avi").read_bytes()[:4], b"RIFF")

    def test_an_animated_gif_loops_through_every_frame(self):
        from PIL import Image
        arbor("render", *PHANTOM, "--orbit", 3, "--quality", "coarse", "--fps", 10, "-o", SCRATCH / "orbit.gif")
        self.assertEqual((SCRATCH / "orbit.gif").read_bytes()[:6], b"GIF89a")
        with Image.open(SCRATCH / "orbit.gif") as gif:
            self.assertEqual(gif.size, (64, 64))
            self.assertEqual(gif.n_frames, 3)
            self.assertEqual(gif.info.get("loop"), 0)  # forever
            self.assertEqual(gif.info.get("duration"), 100)  # ms: 10 frames per second
            frames = []
            for i in range(3):
                gif.seek(i)
                frames.append(list(gif.convert("RGB").getdata()))
        self.assertNotEqual(frames[0], frames[1])  # the camera turned
        self.assertTrue(any(sum(p) > 60 for p in frames[0]))  # something visible, not a black frame
        self.assertEqual(len(report("orbit.gif")["per_frame"]), 3)

    def test_the_default_renderer_is_chosen_for_this_machine_and_says_why(self):
        _, out, err = arbor("render", *PHANTOM, "-o", SCRATCH / "auto.png")
        line = next(l for l in err.splitlines() if "info: renderer " in l)
        hardware = "graphics hardware" in line
        chosen = "gl-raycast" if hardware else "cpu-raycast"
        self.assertIn(f"renderer {chosen}:", line)
        if not hardware:  # llvmpipe here, or no OpenGL at all
            self.assertTrue("emulated on the CPU" in line or "cannot start" in line, line)
        self.assertIn(f"rendered by org.arbor.renderer.{chosen}", out)
        # Options for one renderer choose it.
        _, out, err = arbor("render", *PHANTOM, "--gl-raycast.jitter", "false", "-o", SCRATCH / "gl.png")
        self.assertIn("renderer gl-raycast: its options were given", err)
        self.assertIn("rendered by org.arbor.renderer.gl-raycast", out)

    def test_what_it_cannot_write_is_refused_clearly(self):
        code, _, err = arbor("render", *PHANTOM, "--orbit", 3, "-o", SCRATCH / "orbit.webm", check=False)
        self.assertNotEqual(code, 0)
        self.assertIn(".gif", err)
        self.assertFalse((SCRATCH / "orbit.webm").exists())
        code, _, err = arbor("render", *PHANTOM, "--orbit", 0, "-o", SCRATCH / "none.mp4", check=False)
        self.assertNotEqual(code, 0)
        code, _, err = arbor("render", "--orbit", 3, "-o", SCRATCH / "novolume.mp4", check=False)
        self.assertNotEqual(code, 0)
        self.assertIn("no volume", err)


if __name__ == "__main__":
    unittest.main()
