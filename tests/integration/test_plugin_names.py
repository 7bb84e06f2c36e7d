"""Plugin names that do not break, and what users are told when a plugin or a
command line goes wrong (issue 20), through the `arbor` command.

Run by ctest with the environment of test_cli.py.  The fixture plugins
(tests/plugins/fixtures) each lie in a folder of their own, so a test puts
exactly the ones it means on ARBOR_PLUGIN_PATH: fixture-pv-a and fixture-pv-b
are two third-party simplifiers whose ids both end in ".pv" (the volume
squared, or to the power of their parameter "exponent").
"""
import json
import os
import signal
import unittest

from test_cli import DATA, FIXTURES, SCRATCH, arbor

NUCLEON = DATA / "nucleon/nucleon.nrrd"
PV_A, PV_B = FIXTURES / "fixture-pv-a", FIXTURES / "fixture-pv-b"


def path_of(*folders):
    return {"ARBOR_PLUGIN_PATH": os.pathsep.join(map(str, folders))}


def simplify(*args, plugins=(), check=True):
    out = SCRATCH / "names-simplified.json"
    out.unlink(missing_ok=True)
    code, stdout, err = arbor("simplify", NUCLEON, "--no-cache", "--keep", 6, "--json", out, *args,
                              env=path_of(*plugins), check=check)
    return code, (json.loads(out.read_text()) if code == 0 else None), err


class PluginNames(unittest.TestCase):
    def assert_importance_is_volume_to_the(self, j, exponent):
        # The fixture's importance: the relative volume to the power of its
        # parameter; the root's is not the plugin's to say.
        self.assertGreater(len(j["kept_branches"]), 2)
        for b in j["kept_branches"][1:]:
            self.assertAlmostEqual(b["importance"], b["relative_measures"]["volume"] ** exponent, delta=1e-12)

    def test_a_third_partys_short_name_and_flags_work_while_it_is_the_only_one(self):
        code, j, err = simplify("--simplifier", "pv", "--pv.exponent", 3, plugins=[PV_A])
        self.assertEqual(j["simplifier"]["id"], "org.example.simplifier.pv")
        self.assert_importance_is_volume_to_the(j, 3)
        # The full-id flag is the same flag, listed or not.
        _, j, _ = simplify("--simplifier", "pv", "--org.example.simplifier.pv.exponent", 3, plugins=[PV_A])
        self.assert_importance_is_volume_to_the(j, 3)
        code, _, err = simplify("--simplifier", "pv", "--pv.exponent", 3, "--org.example.simplifier.pv.exponent", 2,
                                plugins=[PV_A], check=False)
        self.assertEqual(code, 2, err)
        self.assertIn("--pv.exponent and --org.example.simplifier.pv.exponent set the same parameter", err)

    def test_a_second_plugin_with_the_short_name_makes_it_an_error_naming_both(self):
        code, _, err = simplify("--simplifier", "pv", plugins=[PV_A, PV_B], check=False)
        self.assertEqual(code, 2, err)
        self.assertIn("simplifier 'pv' is ambiguous: org.example.simplifier.pv and org.other.simplifier.pv both have "
                      "the short name 'pv'; write the full id (org.example.simplifier.pv or org.other.simplifier.pv)",
                      err)
        code, _, err = simplify("--simplifier", "org.example.simplifier.pv", "--pv.exponent", 3,
                                plugins=[PV_A, PV_B], check=False)
        self.assertEqual(code, 2, err)
        self.assertIn("--pv.exponent: 'pv' is the short name of org.example.simplifier.pv and "
                      "org.other.simplifier.pv; write the full id: --org.example.simplifier.pv.exponent or "
                      "--org.other.simplifier.pv.exponent", err)

    def test_full_ids_always_work_and_other_plugins_keep_their_names(self):
        _, j, _ = simplify("--simplifier", "org.example.simplifier.pv", "--org.example.simplifier.pv.exponent", 3,
                           plugins=[PV_A, PV_B])
        self.assertEqual(j["simplifier"]["id"], "org.example.simplifier.pv")
        self.assert_importance_is_volume_to_the(j, 3)
        _, j, _ = simplify("--simplifier", "org.other.simplifier.pv", plugins=[PV_B, PV_A])
        self.assertEqual(j["simplifier"]["id"], "org.other.simplifier.pv")
        self.assert_importance_is_volume_to_the(j, 2)
        _, j, _ = simplify("--simplifier", "itri", plugins=[PV_A, PV_B])
        self.assertEqual(j["simplifier"]["id"], "org.arbor.simplifier.itri")
        # The defaults do not go through short names at all.
        _, j, _ = simplify(plugins=[PV_A, PV_B])
        self.assertEqual(j["simplifier"]["id"], "org.arbor.simplifier.itri")

    def test_help_lists_the_plugins_loaded_and_only_full_flags_for_a_shared_name(self):
        _, alone, _ = arbor("simplify", "--help", env=path_of(PV_A))
        simplifier_line = next(l for l in alone.splitlines() if l.strip().startswith("--simplifier"))
        for name in ("itri", "persistence", "n-measure", "pv"):
            self.assertIn(name, simplifier_line)
        self.assertIn("--pv.exponent", alone)
        self.assertNotIn("--org.example.simplifier.pv.exponent", alone)

        _, shared, _ = arbor("simplify", "--help", env=path_of(PV_A, PV_B))
        simplifier_line = next(l for l in shared.splitlines() if l.strip().startswith("--simplifier"))
        self.assertIn("org.example.simplifier.pv", simplifier_line)
        self.assertIn("org.other.simplifier.pv", simplifier_line)
        self.assertIn("--org.example.simplifier.pv.exponent", shared)
        self.assertIn("--org.other.simplifier.pv.exponent", shared)
        self.assertNotIn("--pv.exponent", shared)
        self.assertIn("--n-measure.measures", shared)  # shared by nobody: still short

    def test_plugins_says_which_short_names_are_shared(self):
        j = json.loads(arbor("plugins", "--json", env=path_of(PV_A, PV_B))[1])
        by_id = {p["id"]: p for p in j["plugins"]}
        self.assertEqual(by_id["org.example.simplifier.pv"]["short_name_shared_with"], ["org.other.simplifier.pv"])
        self.assertEqual(by_id["org.arbor.simplifier.itri"]["short_name"], "itri")
        self.assertEqual(by_id["org.arbor.simplifier.itri"]["short_name_shared_with"], [])
        text = arbor("plugins", env=path_of(PV_A, PV_B))[1]
        self.assertIn("(shared)", next(l for l in text.splitlines() if l.startswith("org.other.simplifier.pv")))


class WrongCommandLines(unittest.TestCase):
    """A wrong command line exits 2 with a message, whoever finds it."""

    def expect_usage_error(self, *args, words=(), env=None):
        code, out, err = arbor(*args, env=env, check=False)
        self.assertEqual(code, 2, f"arbor {' '.join(map(str, args))}\nstdout: {out}\nstderr: {err}")
        for w in words:
            self.assertIn(w, err)

    def test_flags_cli11_refuses(self):
        self.expect_usage_error("info", NUCLEON, "--no-such-flag", words=("--no-such-flag",))
        self.expect_usage_error("simplify", NUCLEON, "--keep", 3, "--itri.no-such-parameter", 1)

    def test_plugin_names_that_name_no_plugin(self):
        self.expect_usage_error("simplify", NUCLEON, "--simplifier", "nope", "--keep", 3, "--json",
                                SCRATCH / "x.json", words=("no simplifier 'nope'", "org.arbor.simplifier.itri"))
        self.expect_usage_error("convert", NUCLEON, "-o", SCRATCH / "x.nrrd", "--filter", "nope",
                                words=("no filter 'nope'",))

    def test_values_the_plugin_refuses(self):
        self.expect_usage_error("convert", NUCLEON, "-o", SCRATCH / "x.nrrd", "--filter", "gaussian:sigma=-3",
                                words=("sigma", "-3"))
        self.expect_usage_error("convert", NUCLEON, "-o", SCRATCH / "x.nrrd", "--filter", "gaussian",
                                "--gaussian.sigma", "abc", words=("'abc' is not a number", "--gaussian.sigma"))
        self.expect_usage_error("info", DATA / "walnut/walnut.raw", words=("--raw.dims",))  # a required parameter

    def test_values_and_combinations_the_command_refuses(self):
        self.expect_usage_error("simplify", NUCLEON, "--keep", 0, "--json", SCRATCH / "x.json", words=("--keep 0",))
        self.expect_usage_error("run", NUCLEON, "-o", SCRATCH / "x.jpg", words=(".png or .exr",))
        self.expect_usage_error("tree", NUCLEON, "--json", SCRATCH / "x.json", "--labels", SCRATCH / "l.nrrd",
                                words=("--labels needs --keep",))
        self.expect_usage_error("convert", NUCLEON, "-o", SCRATCH / "x.nrrd", "--filter", ":sigma=1",
                                words=("--filter",))

    def test_a_shared_short_name(self):
        self.expect_usage_error("simplify", NUCLEON, "--simplifier", "pv", "--keep", 3, "--json", SCRATCH / "x.json",
                                env=path_of(PV_A, PV_B), words=("is ambiguous",))


class PluginCrashes(unittest.TestCase):
    """A crash inside a plugin running in-process (--isolate none) names the
    plugin and the call; the process still dies of the signal."""

    def convert_with(self, folder, plugin):
        return arbor("--isolate", "none", "convert", NUCLEON, "-o", SCRATCH / "crash.nrrd", "--filter", plugin,
                     env=path_of(folder), check=False)

    def test_a_segfault(self):
        code, _, err = self.convert_with(FIXTURES, "crash")
        self.assertEqual(code, -signal.SIGSEGV, err)
        self.assertIn("arbor: plugin org.arbor.test.crash crashed (SIGSEGV) in filter.apply\n", err)

    def test_an_abort(self):
        code, _, err = self.convert_with(FIXTURES / "fixture-abort", "abort")
        self.assertEqual(code, -signal.SIGABRT, err)
        self.assertIn("arbor: plugin org.arbor.test.abort crashed (SIGABRT) in filter.apply\n", err)

    def test_a_segfault_on_the_plugins_own_thread(self):
        code, _, err = self.convert_with(FIXTURES / "fixture-crash-thread", "crash-thread")
        self.assertEqual(code, -signal.SIGSEGV, err)
        self.assertIn("while plugin org.arbor.test.crash-thread was in filter.apply", err)


class IsolatedPluginCrashes(unittest.TestCase):
    """The same third-party plugins isolated (the default for libraries
    outside Arbor's plugin folder): the command fails with exit status 1 and
    a message naming the plugin and the call, never dies of the signal."""

    def convert_with(self, folder, plugin, *flags):
        return arbor(*flags, "convert", NUCLEON, "-o", SCRATCH / "crash.nrrd", "--filter", plugin,
                     env=path_of(folder), check=False)

    def test_a_segfault(self):
        code, _, err = self.convert_with(FIXTURES, "crash")
        self.assertEqual(code, 1, err)
        self.assertIn("org.arbor.test.crash: ", err)
        self.assertIn("crashed (SIGSEGV, a segmentation fault) in filter.apply; it runs isolated", err)

    def test_an_abort(self):
        code, _, err = self.convert_with(FIXTURES / "fixture-abort", "abort")
        self.assertEqual(code, 1, err)
        self.assertIn("crashed (SIGABRT, abort()) in filter.apply", err)

    def test_a_hang_is_stopped_after_the_timeout(self):
        code, _, err = self.convert_with(FIXTURES, "hang", "--plugin-timeout", "2")
        self.assertEqual(code, 1, err)
        self.assertIn("org.arbor.test.hang: ", err)
        self.assertIn("did not answer for 2 s", err)
        self.assertIn("in filter.output_type", err)

    def test_a_bad_isolation_value_is_a_usage_error(self):
        code, _, err = arbor("--isolate", "some", "plugins", check=False)
        self.assertEqual(code, 2, err)
        self.assertIn("choose all, third-party or none", err)
        code, _, err = arbor("--plugin-timeout", "0", "plugins", check=False)
        self.assertEqual(code, 2, err)

    def test_a_session_keeps_its_isolation(self):
        session = SCRATCH / "isolated-session.json"
        arbor("--isolate", "all", "--plugin-timeout", "7", "run", "--phantom", "head", "--phantom-size", "48",
              "-o", SCRATCH / "isolated.png", "--save-session", session)
        saved = json.loads(session.read_text())
        self.assertEqual(saved["plugins"], {"isolate": "all", "timeout_s": 7})
        # Opened again without flags, it runs as it was saved.
        again = SCRATCH / "isolated-session-again.json"
        arbor("run", "--session", session, "-o", SCRATCH / "isolated-again.png", "--save-session", again)
        self.assertEqual(json.loads(again.read_text())["plugins"], {"isolate": "all", "timeout_s": 7})
        self.assertEqual((SCRATCH / "isolated.png").read_bytes(), (SCRATCH / "isolated-again.png").read_bytes())

    def test_plugins_says_which_run_isolated(self):
        _, out, _ = arbor("plugins", "--json", env=path_of(FIXTURES / "fixture-abort"))
        listing = json.loads(out)
        self.assertEqual(listing["isolation"]["mode"], "third-party")
        by_id = {p["id"]: p for p in listing["plugins"]}
        self.assertTrue(by_id["org.arbor.test.abort"]["isolated"])
        self.assertFalse(by_id["org.arbor.simplifier.itri"]["isolated"])


class PluginCheck(unittest.TestCase):
    """plugin-check fails plugins it used to pass, each with a useful line."""

    def check(self, folder, library):
        code, out, _ = arbor("plugin-check", FIXTURES / folder / f"{library}.so", check=False)
        self.assertEqual(code, 1, out)
        return out

    def test_an_importance_that_is_nan_for_a_batch_of_one_row(self):
        out = self.check("fixture-simplifier-batch", "fixture-simplifier-batch")
        self.assertIn("    pass  simplifier on host measures\n", out)
        self.assertIn("    FAIL  simplifier on one row: importance of the root's row alone: row 0 got NaN, "
                      "not a finite number >= 0 (last_error: empty)\n", out)
        self.assertIn("    FAIL  simplifier rows are independent: ", out)

    def test_a_generator_deaf_to_cancellation(self):
        out = self.check("fixture-generator-deaf", "fixture-generator-deaf")
        self.assertIn("    pass  tf-generator on a small tree\n", out)
        self.assertIn("    FAIL  tf-generator cancelled mid-call: generate(20000 branches) went on for ", out)

    def test_a_filter_that_refuses_tiny_volumes_without_a_word(self):
        out = self.check("fixture-tiny-mute", "fixture-tiny-mute")
        self.assertIn("    pass  filter on every voxel type\n", out)
        self.assertIn("    FAIL  filter on tiny and thin volumes: apply on 1x1x1 u8 returned invalid argument (-1) "
                      "without a last_error message (last_error: empty)\n", out)

    def test_a_crash_is_a_failure_of_the_check_it_happened_in(self):
        code, out, _ = arbor("plugin-check", FIXTURES / "fixture-crash.so", check=False)
        self.assertEqual(code, 1, out)
        self.assertIn("    FAIL  filter invalid arguments: crashed with signal 11 (Segmentation fault) during "
                      "'filter invalid arguments'\n", out)


if __name__ == "__main__":
    unittest.main()
