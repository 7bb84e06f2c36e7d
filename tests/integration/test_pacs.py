"""`arbor pacs` and pacs:// inputs against a real archive: Orthanc (Debian's
orthanc and orthanc-dicomweb packages), started by orthanc_fixture with its
own storage, free loopback ports and authentication on.  The shared CT head
and MR tumour series and a JPEG 2000 CT image are uploaded through its REST
API; what comes back is checked against the source files with pydicom
(every SOP Instance UID arrives) and against arbor's reading of the source
folder (the same volume, voxel for voxel).

Failures are provoked for real: a wrong called AE title, an unknown caller,
a stopped Orthanc, a wrong password, a server that accepts and never
answers (timeouts), and an HTTP proxy that cuts a WADO-RS answer half way.
"""
import base64
import http.server
import json
import os
import pathlib
import shutil
import socket
import stat
import subprocess
import threading
import time
import unittest
import urllib.request

import numpy as np
import pydicom
from PIL import Image

from orthanc_fixture import Orthanc, free_port
from test_cli import DATA, SCRATCH, arbor
from test_dicom import read_nrrd

CT_HEAD = DATA / "dicom_ct_head_0051"
MR_TUMOR = DATA / "dicom_mr_brain_vs_tumor"
J2K = DATA / "dicom_compressed_wg04" / "CT1_J2KR.dcm"   # JPEG 2000 lossless
J2K_REFERENCE = DATA / "dicom_compressed_wg04" / "CT1_UNC.dcm"


def sop_uids(folder):
    """{SOP Instance UID} of the DICOM files in a folder, by pydicom."""
    uids = set()
    for p in pathlib.Path(folder).iterdir():
        if p.suffix == ".dcm":
            uids.add(str(pydicom.dcmread(p, stop_before_pixels=True).SOPInstanceUID))
    return uids


def series_uid(folder):
    first = sorted(pathlib.Path(folder).glob("*.dcm"))[0]
    return str(pydicom.dcmread(first, stop_before_pixels=True).SeriesInstanceUID)


class SilentServer:
    """Accepts TCP connections and never answers: what a hung archive does."""

    def __init__(self):
        self.sock = socket.socket()
        self.sock.bind(("127.0.0.1", 0))
        self.sock.listen(8)
        self.port = self.sock.getsockname()[1]
        self.held = []
        self.thread = threading.Thread(target=self._accept, daemon=True)
        self.thread.start()

    def _accept(self):
        while True:
            try:
                conn, _ = self.sock.accept()
            except OSError:
                return
            self.held.append(conn)

    def close(self):
        self.sock.close()
        for c in self.held:
            c.close()


class CuttingProxy:
    """A TCP proxy to a port of Orthanc that closes each connection once
    `limit` bytes of the answer went through: a retrieve that fails half way
    (DICOM association or HTTP alike)."""

    def __init__(self, target_port, limit):
        self.target_port, self.limit = target_port, limit
        self.sock = socket.socket()
        self.sock.bind(("127.0.0.1", 0))
        self.sock.listen(8)
        self.port = self.sock.getsockname()[1]
        threading.Thread(target=self._serve, daemon=True).start()

    def _serve(self):
        while True:
            try:
                client, _ = self.sock.accept()
            except OSError:
                return
            upstream = socket.create_connection(("127.0.0.1", self.target_port))
            threading.Thread(target=self._copy, args=(client, upstream, None), daemon=True).start()
            threading.Thread(target=self._copy, args=(upstream, client, self.limit), daemon=True).start()

    @staticmethod
    def _copy(source, target, limit):
        sent = 0
        try:
            while limit is None or sent < limit:
                chunk = source.recv(65536)
                if not chunk:
                    break
                if limit is not None:
                    chunk = chunk[: limit - sent]
                target.sendall(chunk)
                sent += len(chunk)
        except OSError:
            pass
        for s in (source, target):
            try:
                s.shutdown(socket.SHUT_RDWR)
            except OSError:
                pass
            s.close()

    def close(self):
        self.sock.close()


class BearerGateway:
    """An HTTP gateway in front of Orthanc's DICOMweb that wants a bearer
    token (as archives behind OAuth do) and passes requests on with
    Orthanc's own basic credentials."""

    def __init__(self, orthanc, token):
        gateway = self

        class Handler(http.server.BaseHTTPRequestHandler):
            def do_GET(self):
                if self.headers.get("Authorization") != f"Bearer {token}":
                    self.send_response(401)
                    self.send_header("WWW-Authenticate", "Bearer")
                    self.send_header("Content-Length", "0")
                    self.end_headers()
                    return
                request = urllib.request.Request(f"http://127.0.0.1:{orthanc.http_port}{self.path}")
                request.add_header("Accept", self.headers.get("Accept", "*/*"))
                request.add_header("Authorization", "Basic " + base64.b64encode(
                    f"{Orthanc.USER}:{Orthanc.PASSWORD}".encode()).decode())
                with urllib.request.urlopen(request, timeout=30) as answer:
                    body = answer.read()
                    self.send_response(answer.status)
                    self.send_header("Content-Type", answer.headers["Content-Type"])
                    self.send_header("Content-Length", str(len(body)))
                    self.end_headers()
                    self.wfile.write(body)

            def log_message(self, *args):
                pass

        self.server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), Handler)
        self.port = self.server.server_address[1]
        threading.Thread(target=self.server.serve_forever, daemon=True).start()

    def close(self):
        self.server.shutdown()
        self.server.server_close()


class Pacs(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.get_port, cls.move_port = free_port(), free_port()
        cls.orthanc = Orthanc({"ARBOR": cls.get_port, "ARBORMOVE": cls.move_port}).start()
        cls.orthanc.upload(sorted(CT_HEAD.glob("*.dcm")))
        cls.orthanc.upload(sorted(MR_TUMOR.glob("*.dcm")))
        cls.orthanc.upload([J2K])
        cls.node = f"{Orthanc.AET}@127.0.0.1:{cls.orthanc.dicom_port}"
        cls.web = f"http://127.0.0.1:{cls.orthanc.http_port}/dicom-web"
        cls.ct_series, cls.mr_series, cls.j2k_series = series_uid(CT_HEAD), series_uid(MR_TUMOR), str(
            pydicom.dcmread(J2K, stop_before_pixels=True).SeriesInstanceUID)
        cls.out = SCRATCH / "pacs"
        shutil.rmtree(cls.out, ignore_errors=True)
        cls.out.mkdir(parents=True)
        cls.config = cls.out / "config"
        cls.cache = cls.out / "cache"

    @classmethod
    def tearDownClass(cls):
        cls.orthanc.remove()

    def pacs(self, *args, check=True, env=None, password=Orthanc.PASSWORD):
        e = {"ARBOR_CONFIG_DIR": str(self.config), "ARBOR_PACS_CACHE_DIR": str(self.cache),
             "ARBOR_PACS_USER": Orthanc.USER, "ARBOR_PACS_PASSWORD": password}
        e.update(env or {})
        return arbor(*args, check=check, env=e)

    def assert_no_secret(self, *texts):
        for t in texts:
            self.assertNotIn(Orthanc.PASSWORD, t)

    # -- echo and find ------------------------------------------------------

    def test_echo(self):
        _, out, _ = self.pacs("pacs", "echo", self.node)
        self.assertIn("answered C-ECHO", out)
        _, out, _ = self.pacs("pacs", "echo", self.web)
        self.assertIn("answered a QIDO-RS search", out)

    def test_find_studies_with_filters(self):
        everything = json.loads(self.pacs("pacs", "find", self.node, "--level", "study", "--json")[1])
        self.assertEqual(len(everything), 3)
        ct = json.loads(self.pacs("pacs", "find", self.node, "--level", "study", "--json",
                                  "--patient", "CT 0051*")[1])
        self.assertEqual(len(ct), 1)
        self.assertEqual(ct[0]["images"], 108)
        self.assertEqual(ct[0]["study_uid"], str(pydicom.dcmread(sorted(CT_HEAD.glob("*.dcm"))[0]).StudyInstanceUID))
        self.assertEqual(ct[0]["study_date"], "20020604")
        mr = json.loads(self.pacs("pacs", "find", self.node, "--level", "study", "--json", "--modality", "MR")[1])
        self.assertEqual([s["images"] for s in mr], [120])
        dated = json.loads(self.pacs("pacs", "find", self.node, "--level", "study", "--json",
                                     "--study-date", "20020601-20020610")[1])
        self.assertEqual([s["study_uid"] for s in dated], [ct[0]["study_uid"]])
        none = self.pacs("pacs", "find", self.node, "--level", "study", "--patient", "NOBODY*")[1]
        self.assertIn("no studies match", none)
        for node in (self.node, self.web):
            self.assertEqual(json.loads(self.pacs("pacs", "find", node, "--json", "--accession", "NO-SUCH-1")[1]), [])

    def test_find_series_over_dimse_and_dicomweb_agree(self):
        for node in (self.node, self.web):
            with self.subTest(node=node):
                rows = json.loads(self.pacs("pacs", "find", node, "--json")[1])
                by_uid = {r["series_uid"]: r for r in rows}
                self.assertEqual(set(by_uid), {self.ct_series, self.mr_series, self.j2k_series})
                self.assertEqual(by_uid[self.ct_series]["images"], 108)
                self.assertEqual(by_uid[self.mr_series]["images"], 120)
                self.assertEqual(by_uid[self.mr_series]["modality"], "MR")
                ct_only = json.loads(self.pacs("pacs", "find", node, "--json", "--modality", "CT")[1])
                self.assertEqual({r["series_uid"] for r in ct_only}, {self.ct_series, self.j2k_series})
        _, table, _ = self.pacs("pacs", "find", self.node)
        self.assertIn("series UID " + self.ct_series, table)

    def test_a_bad_date_is_refused(self):
        status, _, err = self.pacs("pacs", "find", self.node, "--study-date", "2002-06-04", check=False)
        self.assertEqual(status, 2)  # a value the flag refuses: a wrong command line
        self.assertIn("YYYYMMDD", err)

    # -- retrieve -----------------------------------------------------------

    def same_volume(self, received, source, name):
        arbor("convert", received, "-o", self.out / f"{name}-received.nrrd")
        arbor("convert", source, "-o", self.out / f"{name}-source.nrrd")
        (fr, vr), (fs, vs) = read_nrrd(self.out / f"{name}-received.nrrd"), read_nrrd(self.out / f"{name}-source.nrrd")
        self.assertEqual(vr.shape, vs.shape)
        self.assertTrue(np.array_equal(vr, vs), f"{name}: the retrieved volume differs from the source folder's")
        self.assertEqual(fr["space directions"], fs["space directions"])

    def test_get_a_whole_series(self):
        folder = self.out / "get-ct"
        _, out, err = self.pacs("-v", "pacs", "get", self.node, "--series", self.ct_series, "-o", folder)
        self.assertIn("retrieved 108 image(s)", out)
        self.assertIn("received image 108 of 108", err)  # progress per image
        self.assertEqual(sop_uids(folder), sop_uids(CT_HEAD))
        manifest = json.loads((folder / ".arbor-retrieve.json").read_text())
        self.assertEqual((manifest["state"], manifest["received"], manifest["expected"]), ("complete", 108, 108))
        self.same_volume(folder, CT_HEAD, "get-ct")

    def test_move_a_whole_series(self):
        folder = self.out / "move-mr"
        _, out, _ = self.pacs("pacs", "move", self.node, "--series", self.mr_series, "-o", folder,
                              "--our-aet", "ARBORMOVE", "--our-port", str(self.move_port))
        self.assertIn("retrieved 120 image(s)", out)
        self.assertEqual(sop_uids(folder), sop_uids(MR_TUMOR))
        self.same_volume(folder, MR_TUMOR, "move-mr")

    def test_move_to_an_unknown_destination_says_so(self):
        status, _, err = self.pacs("pacs", "move", self.node, "--series", self.ct_series, "-o", self.out / "move-x",
                                   "--our-aet", "ARBOR", "--our-port", str(free_port()), check=False)
        self.assertEqual(status, 1)
        self.assertIn("C-MOVE ended with status", err)
        self.assertIn("Nothing arrived", err)

    def test_jpeg_2000_arrives_as_held_and_decodes(self):
        for method, node in (("get", self.node), ("get", self.web), ("move", self.node)):
            with self.subTest(method=method, node=node):
                folder = self.out / f"j2k-{method}-{'web' if node == self.web else 'dimse'}"
                extra = ["--our-aet", "ARBORMOVE", "--our-port", str(self.move_port)] if method == "move" else []
                self.pacs("pacs", method, node, "--series", self.j2k_series, "-o", folder, *extra)
                files = [p for p in folder.iterdir() if p.suffix == ".dcm"]
                self.assertEqual(len(files), 1)
                syntax = str(pydicom.dcmread(files[0], stop_before_pixels=True).file_meta.TransferSyntaxUID)
                self.assertEqual(syntax, "1.2.840.10008.1.2.4.90", "not transcoded: the archive sent what it holds")
                self.same_volume(folder, J2K_REFERENCE, f"j2k-{method}")

    def test_dicomweb_retrieve(self):
        folder = self.out / "web-mr"
        _, out, _ = self.pacs("pacs", "get", self.web, "--series", self.mr_series, "-o", folder)
        self.assertIn("by WADO-RS", out)
        self.assertEqual(sop_uids(folder), sop_uids(MR_TUMOR))
        self.same_volume(folder, MR_TUMOR, "web-mr")
        self.assert_no_secret((folder / ".arbor-retrieve.json").read_text(), out)

    def test_bearer_token(self):
        gateway = BearerGateway(self.orthanc, "token-5309")
        try:
            node = f"http://127.0.0.1:{gateway.port}/dicom-web"
            no_basic = {"ARBOR_PACS_USER": "", "ARBOR_PACS_PASSWORD": ""}
            rows = json.loads(self.pacs("pacs", "find", node, "--json", "--modality", "MR",
                                        env={**no_basic, "ARBOR_PACS_TOKEN": "token-5309"})[1])
            self.assertEqual([r["series_uid"] for r in rows], [self.mr_series])
            folder = self.out / "bearer"
            self.pacs("pacs", "get", node, "--series", self.j2k_series, "-o", folder,
                      env={**no_basic, "ARBOR_PACS_TOKEN": "token-5309"})
            self.assertEqual(sop_uids(folder), {str(pydicom.dcmread(J2K, stop_before_pixels=True).SOPInstanceUID)})
            status, _, err = self.pacs("pacs", "echo", node, check=False, env={**no_basic, "ARBOR_PACS_TOKEN": "wrong"})
            self.assertEqual(status, 1)
            self.assertIn("refused our credentials (HTTP 401)", err)
        finally:
            gateway.close()

    def test_a_folder_with_other_files_is_refused(self):
        folder = self.out / "occupied"
        folder.mkdir(exist_ok=True)
        (folder / "notes.txt").write_text("mine")
        status, _, err = self.pacs("pacs", "get", self.node, "--series", self.ct_series, "-o", folder, check=False)
        self.assertEqual(status, 1)
        self.assertIn("already holds other files", err)
        self.assertEqual((folder / "notes.txt").read_text(), "mine")

    def test_an_unknown_series(self):
        status, _, err = self.pacs("pacs", "get", self.node, "--series", "1.2.3.4.5", "-o", self.out / "none",
                                   check=False)
        self.assertEqual(status, 1)
        self.assertIn("has no series 1.2.3.4.5", err)

    # -- failures -----------------------------------------------------------

    def test_a_wrong_called_ae_title_is_rejected(self):
        status, _, err = self.pacs("pacs", "echo", f"WRONG@127.0.0.1:{self.orthanc.dicom_port}", check=False)
        self.assertEqual(status, 1)
        self.assertIn("rejected the association", err)

    def test_an_unknown_caller_is_told_why(self):
        status, _, err = self.pacs("pacs", "find", self.node, "--our-aet", "STRANGER", check=False)
        self.assertEqual(status, 1)
        self.assertIn("may not know our AE title STRANGER", err)

    def test_a_stopped_server(self):
        stopped = Orthanc().start()
        port, http = stopped.dicom_port, stopped.http_port
        stopped.remove()
        for node in (f"ORTHANC@127.0.0.1:{port}", f"http://127.0.0.1:{http}/dicom-web"):
            with self.subTest(node=node):
                status, _, err = self.pacs("pacs", "echo", node, check=False)
                self.assertEqual(status, 1)
                self.assertIn("connection refused", err)

    def test_an_unknown_host(self):
        status, _, err = self.pacs("pacs", "echo", "ORTHANC@no-such-host.invalid:104", check=False)
        self.assertEqual(status, 1)
        self.assertIn("unknown host", err)

    def test_a_wrong_password(self):
        status, _, err = self.pacs("pacs", "find", self.web, check=False, password="not-the-password")
        self.assertEqual(status, 1)
        self.assertIn("refused our credentials (HTTP 401)", err)
        self.assertNotIn("not-the-password", err)

    def test_a_silent_server_times_out(self):
        silent = SilentServer()
        try:
            for node in (f"ORTHANC@127.0.0.1:{silent.port}", f"http://127.0.0.1:{silent.port}/dicom-web"):
                with self.subTest(node=node):
                    start = time.monotonic()
                    status, _, err = self.pacs("pacs", "echo", node, "--timeout", "2", check=False)
                    elapsed = time.monotonic() - start
                    self.assertEqual(status, 1)
                    self.assertIn("2 s (--timeout)", err)
                    self.assertLess(elapsed, 10)
        finally:
            silent.close()

    def test_a_retrieve_cut_half_way_keeps_what_arrived_marked_incomplete(self):
        dimse = CuttingProxy(self.orthanc.dicom_port, limit=20 << 20)  # of ~63 MB
        web = CuttingProxy(self.orthanc.http_port, limit=20 << 20)
        try:
            for node in (f"{Orthanc.AET}@127.0.0.1:{dimse.port}", f"http://127.0.0.1:{web.port}/dicom-web"):
                with self.subTest(node=node):
                    folder = self.out / f"cut-{'web' if node.startswith('http') else 'dimse'}"
                    status, _, err = self.pacs("pacs", "get", node, "--series", self.mr_series, "-o", folder,
                                               "--timeout", "5", check=False)
                    self.assertEqual(status, 1)
                    manifest = json.loads((folder / ".arbor-retrieve.json").read_text())
                    self.assertEqual(manifest["state"], "incomplete")
                    arrived = sop_uids(folder)
                    self.assertGreater(len(arrived), 10)
                    self.assertLess(len(arrived), 120)
                    self.assertEqual(manifest["received"], len(arrived))
                    self.assertIn(f"The {len(arrived)} image(s) that arrived are in {folder}", err)
                    self.assertTrue("was lost during the C-GET" in err or "ended before its last part" in err, err)
                    self.assertFalse((folder / ".incoming").exists(), "nothing half-written is left")
                    self.assertTrue(arrived <= sop_uids(MR_TUMOR))
                    # pacs:// does not take an incomplete retrieve for the series.
                    status, _, err = self.pacs("info", f"pacs://{node}/{self.mr_series}", "--no-cache", check=False,
                                               env={"ARBOR_PACS_CACHE_DIR": str(self.out / "cut-cache")})
                    self.assertEqual(status, 1)
                    self.assertIn("incomplete", err)
        finally:
            dimse.close()
            web.close()

    # -- nodes and pacs:// --------------------------------------------------

    def test_nodes_file(self):
        env = {"ARBOR_CONFIG_DIR": str(self.out / "nodes-config"), "ORTHANC_PASSWORD": Orthanc.PASSWORD}
        self.pacs("pacs", "nodes", "add", "archive", self.node, "--our-aet", "ARBOR", env=env)
        self.pacs("pacs", "nodes", "add", "web", self.web, "--user", Orthanc.USER, "--password-env",
                  "ORTHANC_PASSWORD", env=env)
        listed = json.loads(self.pacs("pacs", "nodes", "--json", env=env)[1])
        self.assertEqual([n["name"] for n in listed["nodes"]], ["archive", "web"])
        self.assertEqual(listed["nodes"][1]["authentication"], f"basic (user {Orthanc.USER})")
        file = pathlib.Path(listed["file"])
        self.assertEqual(stat.S_IMODE(file.stat().st_mode), 0o600)
        self.assert_no_secret(file.read_text(), json.dumps(listed))
        self.assertIn("answered C-ECHO", self.pacs("pacs", "echo", "archive", env=env)[1])
        self.assertIn("answered a QIDO-RS", self.pacs("pacs", "echo", "web", env=env)[1])
        status, _, err = self.pacs("pacs", "echo", "nowhere", check=False, env=env)
        self.assertEqual(status, 1)
        self.assertIn("configured: archive, web", err)
        self.pacs("pacs", "nodes", "remove", "web", env=env)
        listed = json.loads(self.pacs("pacs", "nodes", "--json", env=env)[1])
        self.assertEqual([n["name"] for n in listed["nodes"]], ["archive"])

    def test_pacs_uri_as_the_input_of_run(self):
        cache = self.out / "uri-cache"
        env = {"ARBOR_PACS_CACHE_DIR": str(cache)}
        uri = f"pacs://{self.node}/{self.ct_series}"
        session = self.out / "uri-session.json"
        self.pacs("run", uri, "-o", self.out / "uri.png", "--save-session", session, "--no-cache", env=env)
        folder = cache / self.node.replace(":", "_") / self.ct_series
        self.assertTrue(retrieval_complete(folder))
        self.assertEqual(sop_uids(folder), sop_uids(CT_HEAD))
        self.assertEqual(json.loads(session.read_text())["input"]["path"], uri)
        self.pacs("run", "--session", session, "-o", self.out / "uri-again.png", "--no-cache", env=env)
        first, again = (np.asarray(Image.open(self.out / n)) for n in ("uri.png", "uri-again.png"))
        self.assertTrue(np.array_equal(first, again), "the session reopens the pacs:// input to the same image")
        # Once cached, the archive is not asked again: a stopped node still reads.
        j = json.loads(self.pacs("info", uri, "--json", env=env)[1])
        self.assertEqual(j["dims"][:2], [512, 512])
        reference = json.loads(self.pacs("info", CT_HEAD, "--json")[1])
        self.assertEqual(j["dims"], reference["dims"])

    def test_pacs_uri_over_dicomweb_and_a_cached_series_needs_no_archive(self):
        cache = self.out / "uri-web-cache"
        self.pacs("info", f"pacs://{self.web}/{self.j2k_series}", env={"ARBOR_PACS_CACHE_DIR": str(cache)})
        # The same series through a node name whose archive is down: the cache answers.
        config = self.out / "uri-web-config"
        config.mkdir(exist_ok=True)
        env = {"ARBOR_PACS_CACHE_DIR": str(cache), "ARBOR_CONFIG_DIR": str(config)}
        (config / "pacs-nodes.json").write_text(json.dumps({"format": "arbor-pacs-nodes/1", "nodes": [
            {"name": "down", "kind": "dimse", "aet": "X", "host": "127.0.0.1", "port": free_port()}]}))
        shutil.copytree(cache / next(cache.iterdir()).name, cache / "down")
        j = json.loads(self.pacs("info", f"pacs://down/{self.j2k_series}", "--json", env=env)[1])
        self.assertEqual(j["dims"], [512, 512, 1])
        status, _, err = self.pacs("info", "pacs://down/1.2.3", check=False, env=env)
        self.assertEqual(status, 1)
        self.assertIn("connection refused", err)
        status, _, err = self.pacs("info", "pacs://down", check=False, env=env)
        self.assertEqual(status, 1)
        self.assertIn("pacs://NODE/SERIES_UID", err)


@unittest.skipUnless(shutil.which("xvfb-run"), "needs xvfb-run")
class PacsInTheWorkstation(unittest.TestCase):
    """The DICOM browser's PACS tab, driven by `arbor view --script` in a real
    window: search the archive, open a series, let it compute, save."""

    def test_search_open_and_save(self):
        out = SCRATCH / "pacs-view"
        shutil.rmtree(out, ignore_errors=True)
        out.mkdir(parents=True)
        with Orthanc({"ARBOR": free_port()}) as orthanc:
            orthanc.upload(sorted(MR_TUMOR.glob("*.dcm")))
            orthanc.upload([J2K])
            node = f"{Orthanc.AET}@127.0.0.1:{orthanc.dicom_port}"
            script = out / "steps.txt"
            script.write_text(f"""\
pacs-search {node} modality=MR
wait idle 60
pacs-open 1
wait idle 600
screenshot {out}/opened.png
screenshot-window {out}/window.png
save-session {out}/session.json
pacs-search {node} modality=XA
wait idle 60
pacs-open 1
""")
            env = dict(os.environ, HOME=str(out / "home"), ARBOR_STATE_DIR=str(out / "state"),
                       ARBOR_PACS_CACHE_DIR=str(out / "cache"))
            p = subprocess.run(["xvfb-run", "-a", "-s", "-screen 0 1600x1000x24", os.environ["ARBOR"], "view",
                                "--no-cache", "--no-recovery", "--script", str(script)],
                               capture_output=True, text=True, env=env, timeout=900)
        # The last step opens row 1 of a search that found nothing: the script stops there, naming it.
        self.assertNotEqual(p.returncode, 0)
        self.assertIn("steps.txt:10: pacs-open: the search found 0 series", p.stderr)
        mr = series_uid(MR_TUMOR)
        session = json.loads((out / "session.json").read_text())
        self.assertEqual(session["input"]["path"], f"pacs://{node}/{mr}")
        folder = out / "cache" / node.replace(":", "_") / mr
        self.assertTrue(retrieval_complete(folder))
        self.assertEqual(sop_uids(folder), sop_uids(MR_TUMOR))
        picture = np.asarray(Image.open(out / "opened.png").convert("L"), dtype=float)
        self.assertGreater(picture.std(), 5, "the 3D view shows the retrieved MR")


def retrieval_complete(folder):
    m = pathlib.Path(folder) / ".arbor-retrieve.json"
    return m.exists() and json.loads(m.read_text())["state"] == "complete"


if __name__ == "__main__":
    unittest.main()
