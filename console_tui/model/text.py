"""Making untrusted message text safe to put on a terminal.

Messages come from any node and may hold escape sequences, control characters, bidi
overrides, or megabytes of text. Everything here maps such characters to visible
stand-ins (so they read as what they are) and never drops text silently.
"""

from __future__ import annotations

import re

# C0 controls become the Unicode "control pictures" (U+2400..U+241F): ESC shows as ␛.
_C0 = {code: chr(0x2400 + code) for code in range(0x20)}
_C0[0x7F] = "\u2421"  # DEL -> ␡
# C1 controls and the bidi/format characters that reorder or hide text: shown as <U+XXXX>.
_INVISIBLE = [*range(0x80, 0xA0), 0x061C, 0x200E, 0x200F, *range(0x202A, 0x202F), *range(0x2066, 0x206A)]
_OTHERS = {code: f"<U+{code:04X}>" for code in _INVISIBLE}

#: Table for one-line display (a table cell): newlines and tabs are shown too.
ONE_LINE = str.maketrans({**_C0, **_OTHERS, 0x0A: "\u21b5", 0x09: "\u2192"})
#: Table for multi-line display (the detail view): newlines and tabs kept.
MULTI_LINE = str.maketrans({**_C0, **_OTHERS, 0x0A: "\n", 0x09: "\t"})

_NEEDS_WORK = re.compile(r"[\x00-\x1f\x7f-\x9f\u061c\u200e\u200f\u202a-\u202e\u2066-\u2069]")
_SURROGATE = re.compile(r"[\ud800-\udfff]")


def _replace_surrogates(text: str) -> str:
    """Lone surrogates (from bad UTF-8 decoded with 'surrogateescape') as U+FFFD."""
    return _SURROGATE.sub("\ufffd", text)


def one_line(text: str, limit: int | None = None) -> str:
    """Text for a single table cell: inert, on one line, cut to ``limit`` characters.

    Cutting happens before translating, so a 1 MB message costs only ``limit`` work.
    """
    if limit is not None and len(text) > limit:
        text = text[:limit]
    if _NEEDS_WORK.search(text):
        text = text.translate(ONE_LINE)
    return _replace_surrogates(text)


def multi_line(text: str) -> str:
    """Text for the detail view: inert, with its own line breaks kept."""
    text = text.replace("\r\n", "\n")
    if _NEEDS_WORK.search(text):
        text = text.translate(MULTI_LINE)
    return _replace_surrogates(text)


#: What JSON text may hold raw that a terminal acts on or hides (JSON escapes C0 itself).
_JSON_RAW = re.compile(r"[\x7f-\x9f\u061c\u200e\u200f\u202a-\u202e\u2066-\u2069\u2028\u2029]")


def inert_json(text: str) -> str:
    """JSON text with DEL, C1 controls, bidi and line-separator characters written as
    ``\\uXXXX`` escapes: the same JSON value, nothing a terminal acts on."""
    if _JSON_RAW.search(text) is None:
        return text
    return _JSON_RAW.sub(lambda match: f"\\u{ord(match.group()):04x}", text)


def first_line(text: str, limit: int) -> tuple[str, bool]:
    """The first line of ``text`` (at most ``limit`` characters) and whether more follows."""
    head = text[: limit + 1]
    newline = head.find("\n")
    if newline != -1:
        return head[:newline], True
    return head[:limit], len(text) > limit


def plural(count: int, word: str, words: str | None = None) -> str:
    """``count`` and the noun in agreement, the count with thousands separators:
    ``plural(1, "line")`` is ``1 line``, ``plural(1200, "line")`` is ``1,200 lines``;
    ``words`` is the plural when it is not ``word + "s"`` (``plural(2, "entry", "entries")``)."""
    return f"{count:,} {word if count == 1 else (words or word + 's')}"
