"""``console-tui serve``'s access rules and command line, without a server or a browser."""

from __future__ import annotations

import pytest

from console_tui.commands import serve
from console_tui.commands.serve_access import Access, host_name, is_loopback, new_token

TOKEN = "s3cret-token-0123456789"


def refusal(access: Access, host: str = "127.0.0.1:8765", **parts):
    request = {"origin": None, "websocket": False, "query_token": None, "cookie_token": None, **parts}
    return access.refusal(host=host, **request)


@pytest.mark.parametrize("host", ["localhost", "127.0.0.1", "127.1.2.3", "::1", "[::1]", "LOCALHOST"])
def test_loopback_names(host):
    assert is_loopback(host)


@pytest.mark.parametrize(
    "host", ["0.0.0.0", "", "::", "192.168.1.5", "robot", "localhost.attacker.example", "127.0.0.1.nip.io"]
)
def test_names_beyond_loopback(host):
    assert not is_loopback(host)


@pytest.mark.parametrize(
    ("header", "name"),
    [
        ("127.0.0.1:8765", "127.0.0.1"),
        ("localhost", "localhost"),
        ("[::1]:80", "::1"),
        ("[::1]", "::1"),
        ("::1", "::1"),
    ],
)
def test_host_name_drops_the_port(header, name):
    assert host_name(header) == name


def test_on_loopback_without_a_token_only_loopback_host_names_pass():
    access = Access(token=None, port=8765)
    assert refusal(access) is None
    assert refusal(access, host="localhost:9000") is None  # an ssh -L port of another number
    assert refusal(access, host="[::1]:8765") is None
    reason = refusal(access, host="attacker.example:8765")  # a rebound DNS name
    assert reason is not None and "loopback only" in reason
    assert refusal(access, host="") is not None


def test_with_a_token_every_request_needs_it_by_query_or_cookie():
    access = Access(token=TOKEN, port=8765)
    reason = refusal(access, host="robot:8765")
    assert reason is not None and "access token" in reason
    assert refusal(access, host="robot:8765", query_token="wrong") is not None
    assert refusal(access, host="robot:8765", query_token=TOKEN[:-1]) is not None
    assert refusal(access, host="robot:8765", query_token="") is not None
    assert refusal(access, host="robot:8765", query_token=TOKEN) is None
    assert refusal(access, host="robot:8765", cookie_token=TOKEN) is None
    # A token given on loopback is asked for there too.
    assert refusal(access, host="127.0.0.1:8765") is not None


def test_a_websocket_must_come_from_the_page_itself():
    access = Access(token=None, port=8765)
    assert refusal(access, websocket=True, origin="http://127.0.0.1:8765") is None
    assert refusal(access, websocket=True, origin="http://attacker.example") is not None
    assert refusal(access, websocket=True, origin="http://127.0.0.1:9999") is not None
    assert refusal(access, websocket=True, origin="null") is not None
    assert refusal(access, websocket=True) is not None
    with_token = Access(token=TOKEN, port=8765)
    ok = {"websocket": True, "cookie_token": TOKEN}
    assert refusal(with_token, host="robot:8765", origin="http://robot:8765", **ok) is None
    assert refusal(with_token, host="robot:8765", origin="http://evil:8765", **ok) is not None


def test_tokens_are_new_each_time_and_fit_a_url():
    tokens = {new_token() for _ in range(20)}
    assert len(tokens) == 20
    assert all(serve._TOKEN_SHAPE.fullmatch(token) for token in tokens)


def test_the_cookie_is_per_port():
    assert Access(token=TOKEN, port=1).cookie_name != Access(token=TOKEN, port=2).cookie_name


# -- the command line ------------------------------------------------------------------------


def test_serve_options_and_the_console_arguments_are_told_apart():
    parser = serve.build_parser()
    args, rest = serve.split_arguments(parser, ["--port", "9000", "a.csv", "--query", "level>=warn", "--demo"])
    assert args.port == 9000 and args.host == "127.0.0.1" and args.token is None
    assert rest == ["a.csv", "--query", "level>=warn", "--demo"]
    args, rest = serve.split_arguments(parser, ["--host", "0.0.0.0", "--", "--port", "x"])
    assert args.host == "0.0.0.0" and rest == ["--port", "x"]


@pytest.mark.parametrize(
    "argv",
    [
        ["--port", "0"],
        ["--port", "70000"],
        ["--port", "x"],
        ["--token", "short"],
        ["--token", "sixteen chars but spaces"],
    ],
)
def test_bad_serve_options_exit_2(argv, capsys):
    with pytest.raises(SystemExit) as exit_info:
        serve.main(argv)
    assert exit_info.value.code == 2
    assert "console-tui serve" in capsys.readouterr().err


def test_bad_console_arguments_exit_2_before_serving(capsys):
    with pytest.raises(SystemExit) as exit_info:
        serve.check_app_arguments(serve.build_parser(), ["--query", "level>=nonsense("])
    assert exit_info.value.code == 2
    assert "--query" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        serve.check_app_arguments(serve.build_parser(), ["--help"])
    serve.check_app_arguments(serve.build_parser(), ["a.csv", "--utc"])  # good ones pass
    serve.check_app_arguments(serve.build_parser(), ["chdb:///tmp/warehouse", "journal:", "--since", "2h"])


@pytest.mark.parametrize(
    ("argv", "said"),
    [
        (["clickhouse://"], "clickhouse://"),
        (["--since", "1h", "a.csv"], "--since goes with the journal or a log warehouse"),
    ],
)
def test_a_bad_source_argument_exits_2_before_serving(argv, said, capsys):
    with pytest.raises(SystemExit) as exit_info:
        serve.check_app_arguments(serve.build_parser(), argv)
    assert exit_info.value.code == 2
    assert said in capsys.readouterr().err


def test_the_banner_says_where_to_go_and_what_runs():
    text = serve.banner("0.0.0.0", 8765, TOKEN, ["--demo"])
    assert f":8765/?token={TOKEN}" in text
    assert f"http://127.0.0.1:8765/?token={TOKEN}" in text
    assert "refused" in text and "console-tui --demo" in text
    loopback = serve.banner("127.0.0.1", 8765, None, [])
    assert "http://127.0.0.1:8765/\n" in loopback and "token" not in loopback
    assert "[::1]" in serve.banner("::1", 8765, None, [])


def test_the_textual_serve_internals_relied_on_are_checked(monkeypatch):
    """serve_web uses three names textual-serve does not promise: a release without one
    fails at once, saying which, instead of serving something unchecked."""
    pytest.importorskip("textual_serve")
    from textual_serve.server import Server

    from console_tui.commands import serve_web

    serve_web.check_upstream()  # the installed, tested release has them all
    monkeypatch.delattr(Server, "_process_messages")
    with pytest.raises(RuntimeError, match=r"lacks Server\._process_messages.*console-tui\[web\]"):
        serve_web.check_upstream()


def test_a_port_in_use_is_reported_and_exits_1():
    pytest.importorskip("textual_serve")
    import socket
    import subprocess
    import sys

    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        port = taken.getsockname()[1]
        result = subprocess.run(
            [sys.executable, "-m", "console_tui", "serve", "--port", str(port)],
            capture_output=True,
            text=True,
            timeout=120,
        )
    assert result.returncode == 1
    assert f"cannot listen on 127.0.0.1:{port}: Address already in use" in result.stderr
    assert "open the console" not in result.stdout  # no address printed that does not work
