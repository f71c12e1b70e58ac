"""``console-tui serve``: the same console in a browser tab (textual-serve, the ``[web]`` extra).

Each tab runs its own ``console-tui APP ARGUMENTS…`` process (a live source, files,
``--demo``), ended when the tab closes. The server listens on 127.0.0.1 unless told
otherwise; any other address needs the access token (``serve_access``), generated and
printed in the URL unless ``--token`` gives it. The page loads nothing from the internet
(``serve_web``). Ctrl-C or SIGTERM ends every console, then the server.
"""

from __future__ import annotations

import argparse
import re
import shlex
import socket
import subprocess
import sys
from collections.abc import Sequence

from .arguments import command_parser, positive_int
from .serve_access import TOKEN_PARAMETER, is_loopback, new_token

EXIT_OK = 0
EXIT_FAILED = 1
EXIT_USAGE = 2

DEFAULT_HOST = "127.0.0.1"
DEFAULT_PORT = 8765
#: Each console is a process (with its own demo nodes): a browser left opening tabs is bounded.
DEFAULT_MAX_CONSOLES = 8
#: A token given with --token goes into URLs unchanged, and is long enough not to be guessed.
_TOKEN_SHAPE = re.compile(r"[A-Za-z0-9._~-]{16,}")
#: How long checking the console's arguments may take (one Python start).
CHECK_TIMEOUT_S = 60.0
#: Checks the console's arguments as ``console-tui`` itself does, in a process of its own.
_CHECK = (
    "import sys\n"
    "from console_tui.cli import build_parser\n"
    "from console_tui.commands.arguments import check_rule_arguments\n"
    "from console_tui.commands.location_options import apply_location_arguments\n"
    "parser = build_parser()\n"
    "parser.prog = 'console-tui'\n"
    "args = parser.parse_args(sys.argv[1:])\n"
    "apply_location_arguments(parser, args, follow=True)\n"
    "check_rule_arguments(parser, args)\n"
)


def port_number(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a port number: {text!r}") from None
    if not 1 <= value <= 65535:
        raise argparse.ArgumentTypeError("a port is 1 to 65535")
    return value


def build_parser() -> argparse.ArgumentParser:
    parser = command_parser(
        "serve",
        "Serve the console to web browsers: each browser tab runs its own console-tui with the APP "
        "ARGUMENTS (files, --demo, --ros1, --query ...: as for console-tui itself; put them after -- "
        "if one looks like these options). Closing the tab ends its console. Listening on anything "
        "but loopback needs the access token: one is generated and printed in the URL to open, "
        "unless --token gives it; requests without it are refused. Needs the [web] extra: "
        "pip install 'console-tui[web]'.",
        f"""a robot's console from a laptop: keep the default address on the robot and forward the port,
  ssh -N -L {DEFAULT_PORT}:127.0.0.1:{DEFAULT_PORT} robot   (then open http://127.0.0.1:{DEFAULT_PORT}/)

exit status:
  {EXIT_OK}  stopped by Ctrl-C, SIGTERM or SIGHUP
  {EXIT_FAILED}  cannot listen, or textual-serve is missing
  {EXIT_USAGE}  bad command line (serve's options or the console's arguments)""",
    )
    parser.usage = (
        "console-tui serve [-h] [--host HOST] [--port PORT] [--token TOKEN] [--max-consoles N] [APP ARGUMENTS ...]"
    )
    parser.add_argument(
        "--host",
        default=DEFAULT_HOST,
        help=f"address to listen on (default {DEFAULT_HOST}: this machine only); 0.0.0.0 listens on every "
        "address, and then the access token is required",
    )
    parser.add_argument(
        "--port", type=port_number, default=DEFAULT_PORT, help=f"port to listen on (default {DEFAULT_PORT})"
    )
    parser.add_argument(
        "--token",
        metavar="TOKEN",
        help="the access token (at least 16 of A-Z a-z 0-9 . _ ~ -); required on every address when given "
        "(default: generated when --host is not loopback). Other users of this machine can read a command "
        "line: prefer the generated one there",
    )
    parser.add_argument(
        "--max-consoles",
        type=positive_int,
        default=DEFAULT_MAX_CONSOLES,
        metavar="N",
        help=f"consoles (browser tabs) running at once, at most; a tab beyond it is refused (default "
        f"{DEFAULT_MAX_CONSOLES})",
    )
    return parser


def split_arguments(parser: argparse.ArgumentParser, argv: Sequence[str]) -> tuple[argparse.Namespace, list[str]]:
    """Serve's own options, and the console's arguments (everything else, or all after ``--``)."""
    argv = list(argv)
    if "--" in argv:
        cut = argv.index("--")
        return parser.parse_args(argv[:cut]), argv[cut + 1 :]
    args, app_arguments = parser.parse_known_args(argv)
    return args, app_arguments


def check_app_arguments(parser: argparse.ArgumentParser, app_arguments: list[str]) -> None:
    """Bad console arguments exit 2 now, not in every tab."""
    for word in ("-h", "--help", "--version"):
        if word in app_arguments:
            parser.error(f"{word} is not an argument for the console in a browser (see console-tui {word})")
    try:
        result = subprocess.run(
            [sys.executable, "-c", _CHECK, *app_arguments],
            stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
            text=True,
            errors="replace",
            timeout=CHECK_TIMEOUT_S,
        )
    except subprocess.TimeoutExpired:
        return  # the check is a courtesy: the tabs will say what is wrong
    if result.returncode != 0:
        sys.stderr.write(result.stderr[-4000:])
        sys.exit(EXIT_USAGE)


def cannot_listen(host: str, port: int) -> str | None:
    """Why the server could not listen on ``host:port`` (tried at once, before anything is
    printed), or None."""
    try:
        addresses = socket.getaddrinfo(host or None, port, type=socket.SOCK_STREAM, flags=socket.AI_PASSIVE)
    except OSError as error:
        return str(error.strerror or error)
    for family, kind, protocol, _, address in addresses:
        try:
            with socket.socket(family, kind, protocol) as probe:
                probe.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)  # as aiohttp does
                probe.bind(address)
        except OSError as error:
            return str(error.strerror or error)
    return None


def url_host(host: str) -> str:
    """The host to print in a URL: this machine's name for every address, IPv6 in brackets."""
    if host in ("", "0.0.0.0", "::"):
        host = socket.gethostname()
    return f"[{host}]" if ":" in host else host


def banner(host: str, port: int, token: str | None, app_arguments: list[str]) -> str:
    query = f"?{TOKEN_PARAMETER}={token}" if token else ""
    lines = ["console-tui serve: open the console in a browser at", f"  http://{url_host(host)}:{port}/{query}"]
    if host in ("", "0.0.0.0", "::"):
        lines.append(f"  or, on this machine, http://127.0.0.1:{port}/{query}")
    if token:
        lines.append("Requests without this token are refused.")
    command = shlex.join(["console-tui", *app_arguments])
    lines.append(f"Each tab runs its own console: {command}")
    lines.append("Ctrl-C stops the server and every console.")
    return "\n".join(lines)


def main(argv: Sequence[str]) -> int:
    parser = build_parser()
    args, app_arguments = split_arguments(parser, argv)
    if args.token is not None and not _TOKEN_SHAPE.fullmatch(args.token):
        parser.error("--token: at least 16 characters, each one of A-Z a-z 0-9 . _ ~ -")
    try:
        from .serve_web import ConsoleServer
    except ImportError as error:
        print(
            f"console-tui serve needs textual-serve ({error}): pip install 'console-tui[web]'",
            file=sys.stderr,
        )
        return EXIT_FAILED
    check_app_arguments(parser, app_arguments)
    problem = cannot_listen(args.host, args.port)
    if problem is not None:
        print(f"console-tui serve: cannot listen on {args.host}:{args.port}: {problem}", file=sys.stderr)
        return EXIT_FAILED
    token = args.token or (None if is_loopback(args.host) else new_token())
    from .serve_access import Access

    server = ConsoleServer(
        "exec " + shlex.join([sys.executable, "-m", "console_tui", *app_arguments]),
        host=args.host,
        port=args.port,
        access=Access(token=token, port=args.port),
        banner=banner(args.host, args.port, token, app_arguments),
        max_consoles=args.max_consoles,
    )
    try:
        server.serve()
    except OSError as error:
        print(
            f"console-tui serve: cannot listen on {args.host}:{args.port}: {error.strerror or error}", file=sys.stderr
        )
        return EXIT_FAILED
    return EXIT_OK
