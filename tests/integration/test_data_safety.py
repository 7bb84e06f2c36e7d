"""Nothing the user saved is lost: every file `arbor` writes goes to a
temporary file beside it and replaces the target only when whole.  Provoked
for real: a full disk (RLIMIT_FSIZE, with SIGXFSZ ignored, so each write
past the limit fails with EFBIG as on a full file system) and a read-only
folder (arbor run as the unprivileged user nobody, since root ignores
permissions).  Each failure must exit 1 with a message naming the file,
leave the previous file byte for byte, and leave no temporary files.
"""
import os
import pathlib
import resource
import shutil
import signal
import subprocess
import unittest

from test_cli import ARBOR, DATA, SCRATCH, arbor

RUN = ["run", "--phantom", "head", "--phantom-size", "40", "--no-cache"]


def run_limited(args, max_file_bytes):
    def limit():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (max_file_bytes, max_file_bytes))
    env = dict(os.environ, HOME=str(SCRATCH / "home"))
    return subprocess.run([ARBOR, *map(str, args)], preexec_fn=limit, capture_output=True, text=True, env=env,
                          timeout=600)


def snapshot(folder):
    return {p.name: p.read_bytes() for p in folder.iterdir() if p.is_file()}


class DataSafety(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.out = SCRATCH / "data-safety"
        shutil.rmtree(cls.out, ignore_errors=True)
        cls.out.mkdir(parents=True)

    def assert_kept(self, folder, before, result, what):
        self.assertEqual(result.returncode, 1, result.stderr)
        self.assertIn("cannot write", result.stderr)
        self.assertIn(what, result.stderr)
        after = snapshot(folder)
        for name, data in before.items():
            self.assertEqual(after.get(name), data, f"{name} changed although the write failed")
        self.assertEqual(sorted(after), sorted(before), "no temporary or partial file is left")

    def test_a_full_disk_keeps_the_previous_files(self):
        folder = self.out / "full"
        folder.mkdir()
        arbor(*RUN, "-o", folder / "head.png", "--save-session", folder / "head.json", "--labels", folder / "labels.nrrd")
        arbor("convert", DATA / "tooth/tooth.nhdr", "-o", folder / "tooth.nrrd")
        before = snapshot(folder)
        # A change that rewrites every file, on a disk with room for 2 KB a file.
        r = run_limited([*RUN, "--flow-rate", "150", "-o", folder / "head.png", "--save-session", folder / "head.json",
                         "--labels", folder / "labels.nrrd"], 2000)
        self.assert_kept(folder, before, r, str(folder))
        r = run_limited(["convert", DATA / "tooth/tooth.nhdr", "--filter", "gaussian:sigma=1", "-o",
                         folder / "tooth.nrrd"], 2000)
        self.assert_kept(folder, before, r, "tooth.nrrd")

    @unittest.skipUnless(os.geteuid() == 0 and shutil.which("setpriv"), "needs root to become nobody")
    def test_a_read_only_folder_is_refused_clearly(self):
        folder = self.out / "read-only"
        folder.mkdir()
        arbor(*RUN, "-o", folder / "head.png")
        home = self.out / "nobody-home"
        home.mkdir()
        os.chmod(home, 0o777)
        os.chmod(folder, 0o555)
        before = snapshot(folder)
        try:
            r = subprocess.run(["setpriv", "--reuid=65534", "--regid=65534", "--clear-groups", ARBOR, *RUN,
                                "--flow-rate", "150", "-o", folder / "head.png"],
                               capture_output=True, text=True, env=dict(os.environ, HOME=str(home)), timeout=600)
        finally:
            os.chmod(folder, 0o755)
        if "Permission denied" in r.stderr and "head.png" not in r.stderr:
            self.skipTest("nobody cannot run the build here: " + r.stderr[-200:])
        self.assert_kept(folder, before, r, "head.png")
        self.assertIn("Permission denied", r.stderr)


if __name__ == "__main__":
    unittest.main()
