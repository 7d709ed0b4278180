"""The checks every request passes before the app sees it (a plain ASGI middleware):

* the access token, when the server has one: `Authorization: Bearer T`, the `arise_token`
  cookie, or `?token=T` (which sets the cookie, so the page, its stream, the replay frame
  and the downloads all carry it);
* on a loopback server, a Host header naming this machine (a web page elsewhere cannot
  reach the server by pointing a DNS name at 127.0.0.1);
* on a request that changes something (POST, PUT, PATCH, DELETE), no sign of another
  site: `Sec-Fetch-Site` must be `same-origin` or `none` when a browser sends it, and
  `Origin`, when sent, must name the host the request was sent to (403 otherwise). A
  client that sends neither (curl, a script) is no browser and passes;
* a request body no larger than the limit (413 before the app reads it);
* headers that keep browsers from sniffing types or sending the page's address on.
"""

from __future__ import annotations

import hmac
import json
from collections.abc import Awaitable, Callable, MutableMapping
from http.cookies import SimpleCookie
from typing import Any
from urllib.parse import parse_qs, urlsplit

from arise.serve.config import is_loopback

Scope = MutableMapping[str, Any]
Message = MutableMapping[str, Any]
Receive = Callable[[], Awaitable[Message]]
Send = Callable[[Message], Awaitable[None]]
ASGIApp = Callable[[Scope, Receive, Send], Awaitable[None]]

COOKIE = "arise_token"
LOOPBACK_NAMES = frozenset({"127.0.0.1", "localhost", "::1"})
BODY_METHODS = frozenset({"POST", "PUT", "PATCH"})
CHANGING_METHODS = frozenset({"POST", "PUT", "PATCH", "DELETE"})
#: Sec-Fetch-Site values of a request the page itself (or the user, typing) made.
OWN_SITE = frozenset({"same-origin", "none"})
COMMON_HEADERS = [
    (b"x-content-type-options", b"nosniff"),
    (b"referrer-policy", b"no-referrer"),
]


def host_name(host: str) -> str:
    """`[::1]:8765` -> `::1`, `localhost:8765` -> `localhost`."""
    if host.startswith("["):
        return host[1:].split("]", 1)[0]
    return host.rsplit(":", 1)[0] if host.count(":") == 1 else host


def cross_site(headers: dict[str, str]) -> str | None:
    """Why a state-changing request comes from another site, or None when it does not."""
    site = headers.get("sec-fetch-site")
    if site is not None and site.strip().lower() not in OWN_SITE:
        return f"the browser says it comes from another site (Sec-Fetch-Site: {site[:40]})"
    origin = headers.get("origin")
    if origin is None:
        return None
    host = headers.get("host", "").strip().lower()
    try:
        parts = urlsplit(origin.strip())
        netloc = parts.netloc.lower()
    except ValueError:
        parts, netloc = None, ""
    if parts is None or parts.scheme not in ("http", "https") or not host or netloc != host:
        return f"its Origin ({origin[:80]}) is not this server ({host[:80] or 'no Host'})"
    return None


async def _refuse(send: Send, status: int, message: str) -> None:
    body = json.dumps({"error": message}).encode()
    await send(
        {
            "type": "http.response.start",
            "status": status,
            "headers": [
                (b"content-type", b"application/json"),
                (b"content-length", str(len(body)).encode()),
                *COMMON_HEADERS,
            ],
        }
    )
    await send({"type": "http.response.body", "body": body})


def _loopback_name(name: str) -> bool:
    """`localhost`, or a loopback address written as one (127.0.0.1, 127.1.2.3, ::1)."""
    return name.lower() in LOOPBACK_NAMES or (name != "" and is_loopback(name))


class Guard:
    def __init__(self, app: ASGIApp, *, token: str | None, loopback: bool, max_body: int):
        self.app = app
        self.token = token
        self.loopback = loopback
        self.max_body = max_body

    def _token_of(self, scope: Scope, headers: dict[str, str]) -> tuple[str | None, bool]:
        """The token the request carries, and whether it came in the query string."""
        authorization = headers.get("authorization", "")
        if authorization.lower().startswith("bearer "):
            return authorization[7:].strip(), False
        cookie = SimpleCookie()
        try:
            cookie.load(headers.get("cookie", ""))
        except Exception:  # noqa: BLE001  (a malformed cookie header is no token)
            cookie = SimpleCookie()
        if COOKIE in cookie:
            return cookie[COOKIE].value, False
        query = parse_qs(scope.get("query_string", b"").decode("latin-1"))
        if query.get("token"):
            return query["token"][0], True
        return None, False

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        headers = {k.decode("latin-1").lower(): v.decode("latin-1") for k, v in scope["headers"]}
        if self.loopback and not _loopback_name(host_name(headers.get("host", ""))):
            await _refuse(send, 421, "this server answers only to 127.0.0.1 or localhost")
            return
        if scope["method"] in CHANGING_METHODS:
            reason = cross_site(headers)
            if reason is not None:
                await _refuse(
                    send,
                    403,
                    f"cross-site request refused: {reason}; this server takes changes "
                    "only from its own page",
                )
                return
        set_cookie = False
        if self.token is not None:
            given, from_query = self._token_of(scope, headers)
            if given is None or not hmac.compare_digest(given.encode(), self.token.encode()):
                await _refuse(
                    send,
                    401,
                    "this server needs its access token: open the address `arise serve` "
                    "printed (it ends in ?token=...)",
                )
                return
            set_cookie = from_query
        if scope["method"] in BODY_METHODS:
            declared = headers.get("content-length")
            if declared is not None and declared.isdigit() and int(declared) > self.max_body:
                await _refuse(send, 413, self._too_large())
                return
            body = await self._read_body(receive)
            if body is None:
                await _refuse(send, 413, self._too_large())
                return
            receive = self._replay(body, receive)
        extra = list(COMMON_HEADERS)
        if set_cookie and self.token is not None:
            cookie = f"{COOKIE}={self.token}; HttpOnly; SameSite=Strict; Path=/"
            extra.append((b"set-cookie", cookie.encode("latin-1")))

        async def send_with_headers(message: Message) -> None:
            if message["type"] == "http.response.start":
                message["headers"] = list(message.get("headers", [])) + extra
            await send(message)

        await self.app(scope, receive, send_with_headers)

    def _too_large(self) -> str:
        return f"the request is larger than {self.max_body // 1024} KiB"

    async def _read_body(self, receive: Receive) -> bytes | None:
        """The whole body, or None as soon as it passes the limit."""
        chunks: list[bytes] = []
        size = 0
        while True:
            message = await receive()
            if message["type"] != "http.request":
                break
            chunk = message.get("body", b"")
            size += len(chunk)
            if size > self.max_body:
                return None
            chunks.append(chunk)
            if not message.get("more_body", False):
                break
        return b"".join(chunks)

    @staticmethod
    def _replay(body: bytes, receive: Receive) -> Receive:
        sent = False

        async def replay() -> Message:
            nonlocal sent
            if not sent:
                sent = True
                return {"type": "http.request", "body": body, "more_body": False}
            return await receive()

        return replay
