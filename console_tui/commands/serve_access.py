"""Who may use ``console-tui serve``: the access token, the Host and Origin checks.

A console in a browser shows a robot's logs and sets its logger levels, so a request is
refused (HTTP and websocket alike) unless:

- the server listens on loopback only and no token was asked for: the request names a
  loopback host (``localhost``, ``127.x.x.x``, ``[::1]``; any port, for ``ssh -L``), which
  keeps out a web page that points its own host name at 127.0.0.1 (DNS rebinding);
- otherwise: it carries the access token, in the ``token`` query parameter (the URL the
  server prints) or in the cookie the first page sets, so the page's own requests (its
  script, the websocket) carry it without the token in every URL.

A websocket is refused too unless its ``Origin`` is the page's own (host and port as the
browser addressed the server): another site open in the same browser cannot drive a
console (websockets are not bound by the browser's same-origin rule).

No aiohttp here: the rules are plain functions of the request's parts, tested alone.
"""

from __future__ import annotations

import hmac
import ipaddress
import secrets
from dataclasses import dataclass
from urllib.parse import urlsplit

#: The query parameter that carries the token in the printed URL.
TOKEN_PARAMETER = "token"


def is_loopback(host: str) -> bool:
    """``localhost``, ``127.0.0.1`` (any 127.x), ``::1``: a name or address of this machine only."""
    host = host.strip().lower().strip("[]")
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False


def new_token() -> str:
    """A fresh access token: 192 random bits, URL-safe."""
    return secrets.token_urlsafe(24)


def host_name(header: str) -> str:
    """The host of a ``Host`` header or a URL's netloc, without the port: ``[::1]:80`` -> ``::1``."""
    header = header.strip()
    if header.startswith("["):
        return header[1 : header.find("]")] if "]" in header else header[1:]
    return header.rsplit(":", 1)[0] if header.count(":") == 1 else header


@dataclass(frozen=True)
class Access:
    """The access rule of one server: ``token`` None means loopback, no token."""

    token: str | None
    port: int

    @property
    def cookie_name(self) -> str:
        """Per port: cookies are shared by every port of a host."""
        return f"console_tui_token_{self.port}"

    def token_ok(self, given: str | None) -> bool:
        if self.token is None or not given:
            return False
        return hmac.compare_digest(given.encode(), self.token.encode())

    def refusal(
        self,
        *,
        host: str,
        origin: str | None,
        websocket: bool,
        query_token: str | None,
        cookie_token: str | None,
    ) -> str | None:
        """Why the request is refused, or None when it may go on. ``host`` is its Host
        header, ``origin`` its Origin header (None when absent)."""
        if self.token is None:
            if not is_loopback(host_name(host)):
                return (
                    "refused: this console serves loopback only, and this request names another host "
                    f"({host!r}); open it as http://127.0.0.1:{self.port}/"
                )
        elif not (self.token_ok(query_token) or self.token_ok(cookie_token)):
            return (
                "refused: this console needs its access token; open the URL that 'console-tui serve' "
                f"printed when it started (it ends in ?{TOKEN_PARAMETER}=...)"
            )
        if websocket and (origin is None or urlsplit(origin).netloc.lower() != host.strip().lower()):
            return "refused: a console's websocket is opened only by its own page"
        return None
