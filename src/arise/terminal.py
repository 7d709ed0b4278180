"""Printing text arise did not write: one place that makes it harmless on a terminal.

A diagnostic, a worker's result, a trace, a run folder, a model's answer or a file name may
hold anything. Printed raw, an escape sequence in it reaches the terminal: OSC 52 writes
the clipboard, `ESC [2J` clears the screen and a carriage return overwrites a line, so a
failed check can be made to look like an "OK"; bidi overrides reorder what is read. rich
adds two more hazards: markup such as `[/x]` in the text raises an error (a crash that
loses a batch's results), and its highlighter is quadratic on a long line.

So every such text is printed through this module: `text` assembles output that rich
never parses as markup, `markup_name` escapes a short name for an f-string of markup, and
both pass it through `shown`, which spells out control characters as visible escapes
(`\\x1b`, `\\u202e`) and caps the length with a note of what was cut. The consoles of the
CLIs come from `console()`: no highlighting, no emoji codes.
"""

from __future__ import annotations

from rich.console import Console
from rich.text import Text

#: Characters of untrusted text printed per message; the rest is counted, not shown.
MAX_SHOWN = 4096
#: For names (a file, an agent, a map): one line, and short.
MAX_NAME_SHOWN = 256
#: A whole script shown on request (`--show-scripts`, `arise kb show`).
MAX_SCRIPT_SHOWN = 256 * 1024

# Bidirectional controls (embeddings, overrides, isolates, marks) and line separators:
# not C0/C1 controls, but they reorder or break what the reader sees.
_FORMAT_CONTROLS = (
    [0x061C, 0x200E, 0x200F, 0x2028, 0x2029]
    + list(range(0x202A, 0x202F))
    + list(range(0x2066, 0x206A))
)


def _escape(code: int) -> str:
    return f"\\x{code:02x}" if code < 0x100 else f"\\u{code:04x}"


def _table(keep: str) -> dict[int, str]:
    codes = [*range(0x20), 0x7F, *range(0x80, 0xA0), *_FORMAT_CONTROLS]
    table = {code: _escape(code) for code in codes if chr(code) not in keep}
    if "\n" not in keep:
        table.update({ord("\n"): "\\n", ord("\t"): "\\t"})
    return table


_MULTI_LINE = _table(keep="\n\t")
_ONE_LINE = _table(keep="")


_TAG_START = frozenset("abcdefghijklmnopqrstuvwxyz#/@")


def escape_markup(text: str) -> str:
    """`text` for use inside rich markup: it prints exactly as written.

    What `rich.markup.escape` means to do, in linear time (rich's own backtracks
    quadratically on a run of backslashes: half a second for 4,096). rich reads `[` + a
    lower-case letter, `#`, `/` or `@` up to the next `]` with no `[` between as a tag,
    halves the backslashes before a tag (an odd run escapes it), and in other text reads
    `\\[` as `[`. So before a tag-like `[` a run of k backslashes becomes 2k+1, before any
    other `[` a run of k >= 1 becomes k+1, and a trailing run is doubled so that it cannot
    escape the markup that follows it in an f-string."""
    out: list[str] = []
    position = 0
    close = -1  # the first "]" at or after the current "[" + 2
    opening = text.find("[")
    while opening >= 0:
        following = text.find("[", opening + 1)
        if close != len(text) and close < opening + 2:
            found = text.find("]", opening + 2)
            close = len(text) if found < 0 else found
        tag = (
            text[opening + 1 : opening + 2] in _TAG_START
            and close < len(text)
            and (following < 0 or following > close)
        )
        run = opening
        while run > position and text[run - 1] == "\\":
            run -= 1
        backslashes = opening - run
        if tag or backslashes:
            out += [text[position:opening], "\\" * (backslashes + 1 if tag else 1)]
            position = opening
        opening = following
    out.append(text[position:])
    escaped = "".join(out)
    return escaped + "\\" * (len(escaped) - len(escaped.rstrip("\\")))


def shown(text: object, limit: int = MAX_SHOWN, *, one_line: bool = False) -> str:
    """`text` as plain text safe for a terminal: control characters (C0 except newline and
    tab, DEL, C1, bidi controls) spelled out as escapes, at most `limit` characters of it
    shown. `one_line` also spells out newlines and tabs (a name, a table cell)."""
    value = text if isinstance(text, str) else str(text)
    cut = len(value) - limit
    if cut > 0:
        value = value[:limit]
    value = value.translate(_ONE_LINE if one_line else _MULTI_LINE)
    if cut > 0:
        value += f"... ({cut} more characters)"
    return value


def name(text: object) -> str:
    """A name (a file, an agent, a map) as plain text: one line, at most MAX_NAME_SHOWN
    characters."""
    return shown(text, MAX_NAME_SHOWN, one_line=True)


def markup_name(text: object) -> str:
    """`name(text)` to put inside rich markup (a progress bar's or a status's description),
    brackets escaped. Longer text belongs in `text`, which rich never parses: rich's
    markup parser is itself quadratic on a long run of backslashes."""
    return escape_markup(name(text))


def text(*parts: object, limit: int = MAX_SHOWN) -> Text:
    """A line (or block) of output from our own words and untrusted values, never parsed as
    markup: every part, or (part, style) pair, passes through `shown`; a Text is kept as
    it is (build it with `text` too)."""
    out = Text()
    for part in parts:
        if isinstance(part, Text):
            out.append_text(part)
        elif isinstance(part, tuple) and len(part) == 2 and isinstance(part[1], str):
            out.append(shown(part[0], limit), style=part[1])
        else:
            out.append(shown(part, limit))
    return out


def console(*, stderr: bool = False) -> Console:
    """The console every CLI prints with: no highlighter (it colours numbers and paths by
    regular expressions, and takes minutes on a long line), no `:emoji:` codes."""
    return Console(stderr=stderr, soft_wrap=True, highlight=False, emoji=False)
