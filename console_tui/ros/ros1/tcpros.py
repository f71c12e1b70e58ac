"""TCPROS: connection headers, opening a topic connection, calling a service.

A connection header is a uint32 total length, then fields, each a uint32 length and
``key=value`` bytes. A subscriber sends ``callerid, topic, type, md5sum``; the publisher
answers with its own header (or one holding ``error=``) and then sends messages, each a
uint32 length and the message's bytes. A service client sends ``callerid, service,
md5sum, persistent=0``, gets a header back, sends the request (length-prefixed) and reads
one ok byte and a length-prefixed body (the error text when ok is 0).

Every exchange has one deadline for all its steps (connect, send, the whole reply); failures raise ``TcprosError`` with a text to show.
"""

from __future__ import annotations

import socket
import struct
import time
from collections.abc import Callable, Mapping
from urllib.parse import urlsplit

CONNECT_TIMEOUT_S = 2.0
#: A header longer than this is not one (a wrong port, garbage).
MAX_HEADER_BYTES = 1 << 20
#: A service reply longer than this is refused.
MAX_REPLY_BYTES = 64 << 20
_U32 = struct.Struct("<I")


class TcprosError(Exception):
    """A TCPROS exchange failed; ``str()`` says what went wrong."""

    def __init__(self, message: str, *, refused_by_peer: bool = False) -> None:
        super().__init__(message)
        #: The peer answered with an ``error=`` header (wrong type or md5sum, unknown service).
        self.refused_by_peer = refused_by_peer


def prefixed(data: bytes) -> bytes:
    """``data`` after its uint32 length: how TCPROS writes header fields, bodies and strings."""
    return _U32.pack(len(data)) + data


def read_prefixed(
    body: bytes, pos: int, what: str, item: str, error: Callable[[str], Exception] = TcprosError
) -> tuple[bytes, int]:
    """The length-prefixed bytes at ``pos`` in ``body`` and the position after them; raises
    ``error("<what> cut short")`` or ``error("<what>: a <item> runs past the end")``."""
    if pos + 4 > len(body):
        raise error(f"{what} cut short")
    (length,) = _U32.unpack_from(body, pos)
    pos += 4
    if pos + length > len(body):
        raise error(f"{what}: a {item} runs past the end")
    return body[pos : pos + length], pos + length


def encode_header(fields: Mapping[str, str]) -> bytes:
    return prefixed(b"".join(prefixed(f"{k}={v}".encode()) for k, v in fields.items()))


def decode_header(body: bytes) -> dict[str, str]:
    """The fields of a header's body (without its total length); ``TcprosError`` if malformed."""
    fields: dict[str, str] = {}
    pos = 0
    while pos < len(body):
        field, pos = read_prefixed(body, pos, "connection header", "field")
        key, sep, value = field.decode("utf-8", "replace").partition("=")
        if not sep:
            raise TcprosError(f"connection header field without '=': {key[:40]!r}")
        fields[key] = value
    return fields


def read_exact(sock: socket.socket, count: int, deadline: float) -> bytes:
    """``count`` bytes from a blocking socket before ``deadline`` (monotonic)."""
    chunks: list[bytes] = []
    left = count
    while left:
        remaining = deadline - time.monotonic()
        if remaining <= 0:
            raise TcprosError("no answer in time")
        sock.settimeout(remaining)
        try:
            chunk = sock.recv(min(left, 1 << 20))
        except TimeoutError:
            raise TcprosError("no answer in time") from None
        if not chunk:
            raise TcprosError("the connection was closed")
        chunks.append(chunk)
        left -= len(chunk)
    return b"".join(chunks)


def _send(sock: socket.socket, deadline: float, data: bytes) -> None:
    """All of ``data`` before ``deadline`` (monotonic)."""
    remaining = deadline - time.monotonic()
    if remaining <= 0:
        raise TcprosError("no answer in time")
    sock.settimeout(remaining)
    try:
        sock.sendall(data)
    except TimeoutError:
        raise TcprosError("no answer in time") from None


def read_header(sock: socket.socket, deadline: float) -> dict[str, str]:
    (length,) = _U32.unpack(read_exact(sock, 4, deadline))
    if length > MAX_HEADER_BYTES:
        raise TcprosError(f"a connection header of {length:,} bytes: not a TCPROS peer")
    return decode_header(read_exact(sock, length, deadline))


def _connect(host: str, port: int, timeout: float) -> socket.socket:
    try:
        sock = socket.create_connection((host, port), timeout=timeout)
    except TimeoutError:
        raise TcprosError(f"{host}:{port} did not accept a connection within {timeout:g} s") from None
    except ConnectionRefusedError:
        raise TcprosError(f"{host}:{port} refused the connection") from None
    except OSError as error:
        raise TcprosError(f"cannot connect to {host}:{port}: {error.strerror or error}") from None
    return sock


def open_subscription(
    host: str,
    port: int,
    *,
    caller_id: str,
    topic: str,
    msg_type: str,
    md5sum: str,
    timeout: float = CONNECT_TIMEOUT_S,
) -> tuple[socket.socket, dict[str, str]]:
    """Connect to a publisher and exchange headers; returns the socket (blocking, no
    timeout left set) and the publisher's header. ``TcprosError`` when refused."""
    deadline = time.monotonic() + timeout
    sock = _connect(host, port, timeout)
    try:
        _send(
            sock, deadline, encode_header({"callerid": caller_id, "topic": topic, "type": msg_type, "md5sum": md5sum})
        )
        fields = read_header(sock, deadline)
    except (OSError, TcprosError) as error:
        sock.close()
        if isinstance(error, TcprosError):
            raise
        raise TcprosError(f"{host}:{port}: {error}") from None
    if "error" in fields:
        sock.close()
        raise TcprosError(fields["error"] or "refused without a reason", refused_by_peer=True)
    sock.settimeout(None)
    return sock, fields


def call_service(
    uri: str,
    service: str,
    md5sum: str,
    request: bytes,
    *,
    caller_id: str,
    timeout: float = CONNECT_TIMEOUT_S,
) -> bytes:
    """Call ``service`` at ``rosrpc://host:port`` with a serialized request; the response's
    bytes. ``TcprosError`` if it fails; ``ServiceFailed`` when the service answers ok=0."""
    parts = urlsplit(uri)
    if parts.scheme != "rosrpc" or not parts.hostname or not parts.port:
        raise TcprosError(f"not a service address: {uri!r}")
    deadline = time.monotonic() + timeout
    sock = _connect(parts.hostname, parts.port, timeout)
    try:
        _send(
            sock,
            deadline,
            encode_header({"callerid": caller_id, "service": service, "md5sum": md5sum, "persistent": "0"}),
        )
        fields = read_header(sock, deadline)
        if "error" in fields:
            raise TcprosError(fields["error"] or "refused without a reason", refused_by_peer=True)
        _send(sock, deadline, prefixed(request))
        ok = read_exact(sock, 1, deadline)[0]
        (length,) = _U32.unpack(read_exact(sock, 4, deadline))
        if length > MAX_REPLY_BYTES:
            raise TcprosError(f"a reply of {length:,} bytes announced")
        body = read_exact(sock, length, deadline)
    except OSError as error:
        raise TcprosError(f"{service}: {error.strerror or error}") from None
    finally:
        sock.close()
    if not ok:
        raise ServiceFailed(body.decode("utf-8", "replace"))
    return body


class ServiceFailed(TcprosError):
    """The service answered, with ok=0; the text is its error message (maybe empty)."""
