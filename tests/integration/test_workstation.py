"""`arbor view`: the real window (GLFW, Dear ImGui, OpenGL 3.3 under Xvfb)
driven by --script as a person would drive it, on a real CT: open, wait,
move the flow rate, select a branch, drag the threshold, hide a branch,
save the session and screenshots; the screenshots change as they should,
the session reopens to the same picture (in the workstation and in
`arbor run --session`), and no frame took over 100 ms while the contour
tree was computed.  Run by ctest like test_cli.py.
"""
import json
import os
import shutil
import subprocess
import unittest

import numpy
from PIL import Image

from test_cli import ARBOR, DATA, FIXTURES, SCRATCH, arbor

CT = DATA / "dicom_ct_head_0051"


def view(*args, script=None, check=True, plugin_path=None):
    """Runs `arbor view` in its own 24-bit X server; (status, stdout, stderr)."""
    cmd = ["xvfb-run", "-a", "-s", "-screen 0 1600x1000x24", ARBOR, "view", *map(str, args)]
    if script is not None:
        path = SCRATCH / f"steps-{abs(hash(script))}.txt"
        path.write_text(script)
        cmd += ["--script", str(path)]
    env = dict(os.environ, HOME=str(SCRATCH / "home"), ARBOR_STATE_DIR=str(SCRATCH / "state"))
    if plugin_path is not None:
        env["ARBOR_PLUGIN_PATH"] = str(plugin_path)
    p = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=900)
    if check and p.returncode != 0:
        raise AssertionError(f"arbor view failed ({p.returncode}):\n{p.stderr}")
    return p.returncode, p.stdout, p.stderr


def pixels(path):
    return numpy.asarray(Image.open(path).convert("RGB")).astype(int)


def differs(a, b):
    """Mean absolute difference of two pictures, 0..255."""
    return float(numpy.abs(pixels(a) - pixels(b)).mean())


@unittest.skipUnless(shutil.which("xvfb-run"), "needs xvfb-run")
class Workstation(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.out = SCRATCH / "workstation"
        cls.out.mkdir(parents=True, exist_ok=True)
        o = cls.out
        cls.frame_log = o / "frames.txt"
        cls.status, cls.stdout, cls.stderr = view(
            "--no-cache", "--frame-log", cls.frame_log, script=f"""\
# as a radiologist would: open the CT, let it compute, then change things
open {CT}
wait idle 600
screenshot {o}/opened.png
set flow-rate 150
wait idle
screenshot {o}/flow.png
select 2
wait idle
screenshot {o}/selected.png
drag-threshold 0.02
wait idle
screenshot {o}/threshold.png
hide 1
wait idle
screenshot {o}/hidden.png
undo
wait idle
screenshot {o}/undone.png
save-session {o}/session.json
screenshot-window {o}/window.png
export-labels {o}/labels.nrrd
quit
""")

    def test_the_script_ran_to_its_end(self):
        self.assertEqual(self.status, 0, self.stderr)
        for name in ("opened", "flow", "selected", "threshold", "hidden", "undone", "window"):
            self.assertTrue((self.out / f"{name}.png").exists(), name)
        self.assertTrue((self.out / "labels.nrrd").exists())

    def test_each_change_changes_the_picture_and_undo_restores_it(self):
        o = self.out
        self.assertGreater(differs(o / "opened.png", o / "flow.png"), 0.2, "a new flow rate")
        self.assertGreater(differs(o / "flow.png", o / "selected.png"), 0.2, "a selection recolours by relation")
        self.assertGreater(differs(o / "selected.png", o / "threshold.png"), 0.2, "another cut")
        self.assertGreater(differs(o / "threshold.png", o / "hidden.png"), 0.2, "a hidden branch")
        self.assertEqual(differs(o / "threshold.png", o / "undone.png"), 0.0, "undo gives the same picture back")

    def test_the_window_shows_every_view(self):
        w = pixels(self.out / "window.png")
        self.assertEqual(w.shape, (1000, 1600, 3))
        # The 3D view (centre top) and the three slice views (centre bottom)
        # hold pictures, not the empty window colour.
        centre_top = w[60:600, 400:1200]
        slices = w[700:950, 360:1200]
        self.assertGreater(centre_top.std(), 10)
        self.assertGreater(slices.std(), 10)

    def test_the_session_reopens_to_the_same_picture(self):
        o = self.out
        view("--no-cache", o / "session.json", script=f"wait idle 600\nscreenshot {o}/reopened.png\nquit\n")
        self.assertEqual(differs(o / "undone.png", o / "reopened.png"), 0.0)
        arbor("run", "--session", o / "session.json", "--no-cache", "-o", o / "run.png")
        self.assertEqual(differs(o / "undone.png", o / "run.png"), 0.0, "arbor run --session gives the same image")

    def test_frames_stay_short_while_the_tree_is_computed(self):
        lines = self.frame_log.read_text().splitlines()
        self.assertEqual(lines[0], "time_s frame_ms jobs")
        frames = [line.split(" ", 2) for line in lines[1:]]
        # The first frames compile the software OpenGL's shaders: not counted.
        during = [(float(t), float(ms)) for t, ms, jobs in frames[5:] if "contour_tree" in jobs]
        self.assertGreater(len(during), 10, "frames were drawn while the tree was computed")
        # The issue asks for no frame over 100 ms while the tree computes.
        slow = sorted(ms for _, ms in during if ms >= 100)
        # On failure the log's lines of those frames (with the time each
        # phase took, the UI thread's CPU time and page faults) and the
        # frame before each say where the time went.
        around = [line for i, line in enumerate(lines[1:], 1)
                  if any(float(x.split(" ", 2)[1]) >= 100 for x in lines[max(i, 2):i + 2])]
        self.assertEqual(slow, [], "frames over 100 ms while the tree was computed:\n" + "\n".join(around))
        # And a UI that keeps drawing at 30 frames a second while any job
        # runs: 95 % of those frames within 33 ms (the rest is the software
        # OpenGL's swap on a machine whose cores the jobs use).
        busy = sorted(float(ms) for t, ms, jobs in frames[5:] if not jobs.startswith("-"))
        self.assertLessEqual(busy[int(0.95 * (len(busy) - 1))], 33.0, "95th percentile of frames while jobs ran")

    def test_bad_scripts_name_their_line(self):
        status, _, err = view(script="open /no/such/scan.nrrd\nquit\n", check=False)
        self.assertNotEqual(status, 0)
        self.assertIn(":1: open:", err)
        self.assertIn("no such file", err)
        status, _, err = view(script="wait idle\nfly to the moon\n", check=False)
        self.assertNotEqual(status, 0)
        self.assertIn(":2: unknown command 'fly'", err)
        status, _, err = view("--phantom", "head", script="wait idle 300\nset flowrate 3\nquit\n", check=False)
        self.assertNotEqual(status, 0)
        self.assertIn(":2: set: no control named 'flowrate'", err)


@unittest.skipUnless(shutil.which("xvfb-run"), "needs xvfb-run")
class CrashingPlugin(unittest.TestCase):
    """A third-party filter that segfaults inside the workstation: it runs
    isolated, so the job fails with the plugin and the call named, the
    window and the session carry on, and taking the filter away brings the
    same picture back."""

    def test_the_session_carries_on(self):
        o = SCRATCH / "workstation-crash"
        o.mkdir(parents=True, exist_ok=True)
        status, _, err = view("--phantom", "head", "--no-recovery", plugin_path=FIXTURES / "fixture-faulty", script=f"""\
wait idle 300
screenshot {o}/before.png
set filter faulty-filter:fault=segfault,call=second
expect-error SIGSEGV
expect-error org.arbor.test.faulty-filter
expect-error filter.apply
screenshot-window {o}/during.png
set filter none
wait idle 300
screenshot {o}/after.png
save-session {o}/session.json
quit
""")
        self.assertEqual(status, 0, err)  # every expect-error step saw its word in the window's error
        self.assertLess(differs(o / "before.png", o / "after.png"), 0.5)
        self.assertTrue((o / "session.json").is_file())


@unittest.skipUnless(shutil.which("xvfb-run"), "needs xvfb-run")
class OpenGlIn3dView(unittest.TestCase):
    """The OpenGL ray caster drawing the 3D view (what `auto` takes on
    graphics hardware; here Mesa's llvmpipe): chosen from the renderer
    control, it draws the frames into the window's own OpenGL context
    (arbor.renderer-gl/1: a context sharing textures with the window's, no
    read back), they agree with the CPU ray caster's images (the screenshot
    of a GPU frame is its texture read back), a click still picks, switching
    back gives images again, and the session remembers the renderer."""

    def test_the_opengl_ray_caster_draws_the_3d_view(self):
        o = SCRATCH / "workstation-gl"
        o.mkdir(parents=True, exist_ok=True)
        status, _, err = view("--phantom", "head", "--no-recovery", script=f"""\
wait idle 300
expect-frames image
screenshot {o}/cpu.png
set renderer gl-raycast
wait idle 300
expect-frames gpu
screenshot {o}/gl.png
pick 370 278
orbit 90 30
wait idle 300
expect-frames gpu
screenshot {o}/gl-orbit.png
save-session {o}/session.json
set renderer cpu-raycast
wait idle 300
expect-frames image
quit
""")
        self.assertEqual(status, 0, err)
        cpu, gl = pixels(o / "cpu.png"), pixels(o / "gl.png")
        self.assertGreater(cpu.mean(), 5, "the CPU ray caster's 3D view is empty")
        # Another renderer drew it (its bytes differ) ...
        self.assertFalse(numpy.array_equal(cpu, gl), "the picture did not change with the renderer")
        # ... to the same picture (the two agree to 72-90 dB offscreen).
        self.assertLess(differs(o / "cpu.png", o / "gl.png"), 0.5)
        self.assertGreater(differs(o / "gl.png", o / "gl-orbit.png"), 2, "the OpenGL 3D view does not orbit")
        session = json.loads((o / "session.json").read_text())
        self.assertEqual(session["view"]["renderer"]["id"], "org.arbor.renderer.gl-raycast")


if __name__ == "__main__":
    unittest.main()
