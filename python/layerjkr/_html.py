"""Notebook views (``_repr_html_``): one small table builder that every result shares, so each
view says what its object holds - values with units, counts, warnings - escaped, in the same
look."""
from __future__ import annotations

import html
import math
from typing import Any, Iterable, Sequence


def number(value: Any, digits: int = 6) -> str:
    """A value as a table cell: numbers to `digits` significant digits, NaN or None as "-"."""
    if value is None:
        return "-"
    if isinstance(value, float) and not math.isfinite(value):
        return "-"
    if isinstance(value, (int, float)):
        return "%.*g" % (digits, value)
    return html.escape(str(value))


def table(caption: str, header: Sequence[str], rows: Iterable[Sequence[Any]], notes: Iterable[str] = ()) -> str:
    """A captioned table (cells already text, or numbers formatted by :func:`number`) and, under
    it, a list of notes (warnings, escaped)."""
    head = "".join("<th>%s</th>" % html.escape(h) for h in header)
    body = "".join("<tr>%s</tr>" % "".join("<td>%s</td>" % (c if isinstance(c, str) else number(c)) for c in row)
                   for row in rows)
    items = "".join("<li>%s</li>" % html.escape(n) for n in notes)
    return "<table><caption>%s</caption><tr>%s</tr>%s</table>%s" % (
        html.escape(caption), head, body, "<ul>%s</ul>" % items if items else "")
