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
# C1 controls, the bidi/format characters that reorder text, and the characters that take
# no room or break lines where a terminal shows nothing (so text can hide in them, or look
# like other text): shown as <U+XXXX>. Not here: the zero-width joiners (U+200C, U+200D) and
# variation selectors, which emoji and several scripts need, and which hide nothing.
_INVISIBLE = [
    *range(0x80, 0xA0),  # C1 controls
    0x00AD,  # soft hyphen
    0x034F,  # combining grapheme joiner
    0x061C,  # Arabic letter mark
    0x115F,  # Hangul choseong filler
    0x1160,  # Hangul jungseong filler
    0x17B4,  # Khmer vowel inherent aq
    0x17B5,  # Khmer vowel inherent aa
    0x180E,  # Mongolian vowel separator
    0x200B,  # zero width space
    0x200E,  # left-to-right mark
    0x200F,  # right-to-left mark
    0x2028,  # line separator
    0x2029,  # paragraph separator
    *range(0x202A, 0x202F),  # bidi embeddings and overrides
    *range(0x2060, 0x2065),  # word joiner, invisible operators
    *range(0x2066, 0x2070),  # bidi isolates, deprecated format characters
    0x3164,  # Hangul filler
    0xFEFF,  # zero width no-break space (byte order mark)
    0xFFA0,  # halfwidth Hangul filler
    *range(0xFFF9, 0xFFFC),  # interlinear annotation
    *range(0x1D173, 0x1D17B),  # musical symbol format characters
    *range(0xE0000, 0xE0080),  # tags (invisible copies of ASCII)
]
_OTHERS = {code: f"<U+{code:04X}>" for code in _INVISIBLE}

#: Table for one-line display (a table cell): newlines and tabs are shown too.
ONE_LINE = str.maketrans({**_C0, **_OTHERS, 0x0A: "\u21b5", 0x09: "\u2192"})
#: Table for multi-line display (the detail view): newlines and tabs kept.
MULTI_LINE = str.maketrans({**_C0, **_OTHERS, 0x0A: "\n", 0x09: "\t"})


def _char_class(codes: list[int]) -> str:
    """A regex character class of ``codes``, consecutive ones as ranges (much faster to
    match than a long list of single characters)."""
    runs: list[list[int]] = []
    for code in sorted(codes):
        if runs and code == runs[-1][1] + 1:
            runs[-1][1] = code
        else:
            runs.append([code, code])
    return "[" + "".join(re.escape(chr(a)) + (f"-{re.escape(chr(b))}" if b > a else "") for a, b in runs) + "]"


_NEEDS_WORK = re.compile(_char_class([*range(0x20), 0x7F, *_INVISIBLE]))
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
_JSON_RAW = re.compile(_char_class([0x7F, *_INVISIBLE]))


def _json_escape(match: re.Match[str]) -> str:
    code = ord(match.group())
    if code <= 0xFFFF:
        return f"\\u{code:04x}"
    code -= 0x10000  # a UTF-16 surrogate pair, as JSON writes characters past U+FFFF
    return f"\\u{0xD800 + (code >> 10):04x}\\u{0xDC00 + (code & 0x3FF):04x}"


def inert_json(text: str) -> str:
    """JSON text with DEL and the characters ``one_line`` shows as ``<U+XXXX>`` (C1
    controls, bidi, zero-width and line-separator characters) written as ``\\u`` escapes:
    the same JSON value, nothing a terminal acts on or hides."""
    if _JSON_RAW.search(text) is None:
        return text
    return _JSON_RAW.sub(_json_escape, text)


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


def shorten_name(name: str, width: int) -> str:
    """A dotted name (a logger name) in ``width`` characters, keeping what tells names apart,
    their end: the leading segments shrink to their first letter, from the left
    (``navigation.planner.costmap`` → ``n.planner.costmap`` → ``n.p.costmap``), and when that
    is not enough the middle gives way to ``…`` (``p.batt…monitor``)."""
    if len(name) <= width:
        return name
    if width <= 1:
        return "…"[:width]
    parts = name.split(".")
    for index in range(len(parts) - 1):
        parts[index] = parts[index][:1]
        shortened = ".".join(parts)
        if len(shortened) <= width:
            return shortened
    shortened = ".".join(parts)
    head = (width - 1) // 3
    return shortened[:head] + "…" + shortened[len(shortened) - (width - 1 - head) :]


_COLOUR = re.compile(r"\x1b\[[0-9;]*m")


def strip_colour(text: str) -> str:
    """Text without the colour codes (``ESC [ ... m``) a terminal logger adds: style, not
    content. Any other escape sequence stays (``one_line`` makes it visible)."""
    return _COLOUR.sub("", text) if "\x1b" in text else text
