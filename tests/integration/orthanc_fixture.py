"""A real Orthanc archive for the PACS tests: its own configuration, storage
and free loopback ports in a temporary folder, authentication on, Arbor's AE
titles registered in DicomModalities, the DICOMweb plugin loaded.

    with Orthanc(modalities={"ARBOR": 11113}) as pacs:
        pacs.upload(paths)
        ... pacs.dicom_port, pacs.http_port, pacs.user, pacs.password ...

Orthanc runs in the foreground as a child process and is stopped by its PID
(SIGTERM; it needs a few seconds).  Never the system's service: the ports are
chosen free at start.
"""
import base64
import ctypes
import json
import os
import pathlib
import shutil
import signal
import socket
import subprocess
import tempfile
import time
import urllib.error
import urllib.request

ORTHANC = shutil.which("Orthanc") or "/usr/sbin/Orthanc"
DICOMWEB_PLUGIN = pathlib.Path("/usr/share/orthanc/plugins/libOrthancDicomWeb.so")


def _die_with_parent():
    """In the child: SIGTERM when the test process dies, however it dies,
    so a killed test run leaves no archive behind."""
    PR_SET_PDEATHSIG = 1
    ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGTERM)


def free_port():
    """A TCP port nothing listens on now (bound and released)."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class Orthanc:
    AET = "ORTHANC"
    USER = "arbor"
    PASSWORD = "pacs-secret-7361"

    def __init__(self, modalities=None):
        """modalities: {AE title: port on 127.0.0.1} allowed to query and retrieve."""
        self.modalities = dict(modalities or {})
        self.process = None
        self.folder = None

    # -- lifetime -----------------------------------------------------------

    def start(self):
        if not pathlib.Path(ORTHANC).exists():
            raise RuntimeError("Orthanc is not installed (apt-get install orthanc orthanc-dicomweb)")
        self.folder = pathlib.Path(tempfile.mkdtemp(prefix="arbor-orthanc-"))
        self.http_port, self.dicom_port = free_port(), free_port()
        config = {
            "Name": "ArborTestArchive",
            "StorageDirectory": str(self.folder / "storage"),
            "IndexDirectory": str(self.folder / "storage"),
            "HttpPort": self.http_port,
            "DicomPort": self.dicom_port,
            "DicomAet": self.AET,
            "DicomCheckCalledAet": True,
            "RemoteAccessAllowed": False,
            "AuthenticationEnabled": True,
            "RegisteredUsers": {self.USER: self.PASSWORD},
            "DicomAlwaysAllowEcho": True,
            "DicomModalities": {aet.lower(): [aet, "127.0.0.1", port] for aet, port in self.modalities.items()},
            "DicomScpTimeout": 30,
            "StableAge": 1,
            "Plugins": [str(DICOMWEB_PLUGIN)] if DICOMWEB_PLUGIN.exists() else [],
            "DicomWeb": {"Enable": True, "Root": "/dicom-web/", "EnableWado": False},
        }
        (self.folder / "orthanc.json").write_text(json.dumps(config, indent=2))
        self.log = open(self.folder / "orthanc.log", "w")
        self.process = subprocess.Popen([ORTHANC, str(self.folder / "orthanc.json")],
                                        stdout=self.log, stderr=subprocess.STDOUT, preexec_fn=_die_with_parent)
        deadline = time.monotonic() + 20
        while time.monotonic() < deadline:
            if self.process.poll() is not None:
                raise RuntimeError("Orthanc exited at start:\n" + (self.folder / "orthanc.log").read_text())
            try:
                self.rest("GET", "/system")
                socket.create_connection(("127.0.0.1", self.dicom_port), timeout=1).close()
                return self
            except (OSError, urllib.error.URLError):
                time.sleep(0.05)
        self.stop()
        raise RuntimeError("Orthanc did not start within 20 s")

    def stop(self):
        if self.process and self.process.poll() is None:
            self.process.send_signal(signal.SIGTERM)
            try:
                self.process.wait(timeout=30)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        self.process = None
        if getattr(self, "log", None):
            self.log.close()
            self.log = None

    def remove(self):
        self.stop()
        if self.folder:
            shutil.rmtree(self.folder, ignore_errors=True)
            self.folder = None

    def __enter__(self):
        return self.start()

    def __exit__(self, *exc):
        self.remove()

    # -- REST -------------------------------------------------------------

    def rest(self, method, path, body=None, content_type=None):
        request = urllib.request.Request(f"http://127.0.0.1:{self.http_port}{path}", data=body, method=method)
        token = base64.b64encode(f"{self.USER}:{self.PASSWORD}".encode()).decode()
        request.add_header("Authorization", "Basic " + token)
        if content_type:
            request.add_header("Content-Type", content_type)
        with urllib.request.urlopen(request, timeout=30) as r:
            data = r.read()
        return json.loads(data) if data else None

    def upload(self, paths):
        """POSTs each DICOM file; returns the Orthanc instance ids."""
        ids = []
        for p in paths:
            answer = self.rest("POST", "/instances", pathlib.Path(p).read_bytes(), "application/dicom")
            ids.append(answer["ID"])
        return ids

    def log_text(self):
        return (self.folder / "orthanc.log").read_text() if self.folder else ""
