"""A real OpenTelemetry collector for tests: rotel's ``rotel-agent`` (the ``rotel`` package),
taking OTLP/HTTP on a loopback port and sending it on to a receiver; stopped and started
again as a collector that goes away."""

from __future__ import annotations

import importlib.util
import os
import socket
import subprocess
import time
from pathlib import Path

from support.otlp_receiver import free_port

ROTEL_AGENT = (
    Path(importlib.util.find_spec("rotel").origin).parent / "rotel-agent" if importlib.util.find_spec("rotel") else None
)
ROTEL_MISSING = "" if ROTEL_AGENT is not None and ROTEL_AGENT.exists() else "rotel (pip install --pre rotel) is missing"


class Rotel:
    def __init__(self, forward_to: str, directory: Path) -> None:
        self.port = free_port()
        self.grpc_port = free_port()
        self.forward_to = forward_to
        self.directory = directory
        self.process: subprocess.Popen | None = None
        self.start()

    @property
    def url(self) -> str:
        return f"http://127.0.0.1:{self.port}"

    def start(self, timeout: float = 30.0) -> None:
        log = open(self.directory / f"rotel-{self.port}.log", "ab")
        self.process = subprocess.Popen(
            [
                str(ROTEL_AGENT),
                "start",
                "--otlp-http-endpoint",
                f"127.0.0.1:{self.port}",
                "--otlp-grpc-endpoint",
                f"127.0.0.1:{self.grpc_port}",
                "--exporter",
                "otlp",
                "--otlp-exporter-endpoint",
                self.forward_to,
                "--otlp-exporter-protocol",
                "http",
                "--pid-file",
                str(self.directory / f"rotel-{self.port}.pid"),
                "--batch-timeout",
                "200ms",
            ],
            stdout=log,
            stderr=log,
            env={**os.environ},
        )
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            if self.process.poll() is not None:
                raise RuntimeError(
                    f"rotel-agent ended: {(self.directory / f'rotel-{self.port}.log').read_text()[-2000:]}"
                )
            try:
                with socket.create_connection(("127.0.0.1", self.port), timeout=0.5):
                    return
            except OSError:
                time.sleep(0.1)
        raise RuntimeError("rotel-agent did not listen")

    def stop(self) -> None:
        if self.process is not None and self.process.poll() is None:
            self.process.terminate()
            try:
                self.process.wait(10)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        self.process = None
