"""One XML-RPC call to a ROS 1 peer, bounded in time and size, whatever the peer does.

Every ROS 1 API call answers ``[code, status message, value]``; code 1 is success. A call
that fails in any way (no whole answer in time, connection refused, garbage, a reply too
large, a code other than 1) raises ``Ros1CallError`` whose text names the URI and says what
went wrong. A fresh connection is made per call, so calls may come from any thread.

The timeout is for the whole call: connecting, sending, and reading the whole reply. A peer
that answers one byte a second is cut off at the deadline like a silent one (each socket
operation waits only for what is left of it). The reply is read up to ``MAX_REPLY_BYTES``
and refused beyond: a master's ``getSystemState`` for 5,000 nodes, each with 20 topics and
services, is about 5 MB of XML (some 50 bytes per node name listed), so 64 MB is more than
ten times what a very large real graph sends, and parsing that much stays within a few
hundred MB.
"""

from __future__ import annotations

import http.client
import socket
import time
import xmlrpc.client
from typing import Any
from xml.parsers.expat import ExpatError

CALL_TIMEOUT_S = 2.0
#: A reply longer than this is refused (see the module's text for the figure).
MAX_REPLY_BYTES = 64 << 20
_READ_BYTES = 1 << 16


class Ros1CallError(Exception):
    """An XML-RPC call failed; ``str()`` says which URI and why, ``reason`` just why."""

    def __init__(self, uri: str, reason: str, *, unreachable: bool = False, gone: bool = False) -> None:
        super().__init__(f"{uri}: {reason}")
        self.uri = uri
        self.reason = reason
        #: No answer at all (refused, timed out, not XML-RPC), rather than an answer saying no.
        self.unreachable = unreachable or gone
        #: Nothing listens there any more (a killed node's registration, say).
        self.gone = gone


class ReplyTooLarge(Exception):
    """The reply went past the size limit; it was not read further."""


class _DeadlineSocket(socket.socket):
    """A socket whose every wait ends at one ``deadline`` (monotonic) for the whole call."""

    deadline = 0.0

    def _left(self) -> None:
        left = self.deadline - time.monotonic()
        if left <= 0:
            raise TimeoutError("the call's time is up")
        self.settimeout(left)

    def recv(self, *args: Any) -> bytes:
        self._left()
        return super().recv(*args)

    def recv_into(self, *args: Any) -> int:
        self._left()
        return super().recv_into(*args)

    def send(self, *args: Any) -> int:
        self._left()
        return super().send(*args)

    def sendall(self, *args: Any) -> None:
        self._left()
        super().sendall(*args)


class _DeadlineConnection(http.client.HTTPConnection):
    def __init__(self, host: str, deadline: float) -> None:
        super().__init__(host, timeout=max(deadline - time.monotonic(), 0.001))
        self.deadline = deadline

    def connect(self) -> None:
        super().connect()
        plain = self.sock
        bounded = _DeadlineSocket(fileno=plain.detach())
        bounded.deadline = self.deadline
        self.sock = bounded


class _BoundedTransport(xmlrpc.client.Transport):
    #: Replies uncompressed: the size limit is of what is parsed (no gzip bomb), and rosmaster
    #: (Python's XML-RPC server) would otherwise gzip every reply over 1,400 bytes.
    accept_gzip_encoding = False

    def __init__(self, deadline: float, max_bytes: int) -> None:
        super().__init__()
        self._deadline = deadline
        self._max_bytes = max_bytes
        #: The ``Server`` header of the answer: the software behind the API.
        self.server = ""

    def make_connection(self, host: Any) -> http.client.HTTPConnection:
        chost, self._extra_headers, _x509 = self.get_host_info(host)
        self._connection = host, _DeadlineConnection(chost, self._deadline)
        return self._connection[1]

    def parse_response(self, response: http.client.HTTPResponse) -> Any:
        self.server = response.getheader("Server") or ""
        length = response.getheader("Content-Length")
        if length is not None and length.isdigit() and int(length) > self._max_bytes:
            raise ReplyTooLarge(int(length))
        body = bytearray()
        while data := response.read1(_READ_BYTES):
            body += data
            if len(body) > self._max_bytes:
                raise ReplyTooLarge(len(body))  # refused before any of it is parsed
        response.close()
        parser, unmarshaller = self.getparser()
        parser.feed(body)
        del body
        parser.close()
        return unmarshaller.close()


def xmlrpc_call(
    uri: str,
    method: str,
    *args: Any,
    timeout: float = CALL_TIMEOUT_S,
    max_bytes: int = MAX_REPLY_BYTES,
    answered_by: list[str] | None = None,
) -> Any:
    """``method(*args)`` at ``uri``, all of it within ``timeout``; the value of a code-1
    answer, else ``Ros1CallError``. ``answered_by`` gets the answer's ``Server`` header."""
    transport = _BoundedTransport(time.monotonic() + timeout, max_bytes)
    proxy = xmlrpc.client.ServerProxy(uri, transport=transport)
    try:
        answer = getattr(proxy, method)(*args)
    except TimeoutError:
        raise Ros1CallError(uri, f"no answer within {timeout:g} s", unreachable=True) from None
    except ConnectionRefusedError:
        raise Ros1CallError(uri, "connection refused (nothing listens there)", gone=True) from None
    except ReplyTooLarge:
        reason = f"{method}: a reply over {max_bytes >> 20} MB refused (not read further)"
        raise Ros1CallError(uri, reason) from None
    except (OSError, http.client.HTTPException, xmlrpc.client.ProtocolError, ExpatError, ValueError) as error:
        raise Ros1CallError(uri, f"{method} failed: {_reason(error)}", unreachable=True) from None
    except xmlrpc.client.Fault as fault:
        raise Ros1CallError(uri, f"{method} failed: {shown(fault.faultString)}") from None
    finally:
        transport.close()
    if answered_by is not None:
        answered_by.append(transport.server)
    if not isinstance(answer, (list, tuple)) or len(answer) != 3:
        raise Ros1CallError(uri, f"{method} gave an answer that is not [code, message, value]")
    code, message, value = answer
    if code != 1:
        raise Ros1CallError(uri, f"{method}: {shown(message) or 'failed'} (code {shown(code)})")
    return value


def malformed(uri: str, method: str, value: Any) -> Ros1CallError:
    """The error for an answer of the wrong shape: a problem of this call, tried again."""
    return Ros1CallError(uri, f"{method} gave a malformed answer: {shown(value)}")


def shown(value: Any, limit: int = 80) -> str:
    """A peer's value as a short text for a status line."""
    text = value if isinstance(value, str) else repr(value)
    return text if len(text) <= limit else text[: limit - 1] + "…"


def _reason(error: BaseException) -> str:
    text = str(error) or type(error).__name__
    if isinstance(error, OSError) and error.strerror:
        text = error.strerror
    return text
