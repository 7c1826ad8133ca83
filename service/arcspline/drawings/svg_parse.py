"""An SVG document's XML read into a tree of :class:`Node` (docs/drawings.md §3).

Parsing is defusedxml's: entity declarations and external entities are refused (they can
expand without bound or read files); a plain DOCTYPE is allowed, as Illustrator and Inkscape
write one. The document is fed in chunks to a tree builder that keeps each element's line,
counts elements and depth as they arrive (XML 1.0 §3, "element"), and refuses a document over
its :class:`DocumentLimits` before building more of it. Text content is dropped: the reader
draws no text. A declared encoding the parser cannot decode (unknown, multi-byte other than
UTF-8 and UTF-16, or not a text codec) is refused by name.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import Final
from xml.etree.ElementTree import ParseError

from defusedxml import EntitiesForbidden, ExternalReferenceForbidden
from defusedxml.ElementTree import DefusedXMLParser

from .model import DocumentError, DocumentLimits

__all__ = ["SVG_NS", "Node", "parse_svg"]

SVG_NS: Final = "http://www.w3.org/2000/svg"
#: Bytes (or characters) fed to the parser at a time: the limits are checked between them.
CHUNK_BYTES: Final = 1 << 16
#: Characters read for the XML declaration's encoding (XML 1.0 §4.3.3), for error messages.
_DECLARATION_CHARS: Final = 200
_ENCODING: Final = re.compile(r"""<\?xml[^>]*?\bencoding\s*=\s*["']([^"']{1,40})["']""")


class Node:
    """An element: local ``tag``, whether it is SVG's (or in no namespace), its attributes
    (namespaced ones as ``{uri}name``), line and children."""

    __slots__ = ("attrib", "children", "line", "svg", "tag")

    def __init__(self, tag: str, svg: bool, attrib: dict[str, str], line: int) -> None:
        self.tag, self.svg, self.attrib, self.line = tag, svg, attrib, line
        self.children: list[Node] = []

    @property
    def name(self) -> str:
        return self.tag if self.svg else f"a foreign {self.tag}"

    @property
    def source(self) -> str:
        """``tag#id`` when the element has an id, else ``tag (line N)``."""
        ident = self.attrib.get("id")
        return f"{self.tag}#{ident}" if ident else f"{self.tag} (line {self.line})"


def parse_svg(document: bytes | str, limits: DocumentLimits) -> Node:
    """The document's root element (module docstring), or a :class:`DocumentError` naming
    ``"document"`` or the element that crosses a limit."""
    _check_size(document, limits)
    builder = _Builder(limits)
    parser = DefusedXMLParser(target=builder, forbid_dtd=False)
    expat = parser.parser
    builder.line = lambda: int(expat.CurrentLineNumber)
    try:
        for i in range(0, len(document), CHUNK_BYTES):
            parser.feed(document[i : i + CHUNK_BYTES])
        root = parser.close()
    except DocumentError:
        raise
    except EntitiesForbidden as error:
        raise DocumentError(
            "document",
            f"entities are not allowed (the declaration of {error.name!r} at line "
            f"{expat.CurrentLineNumber}): they can expand without bound or read files",
        ) from None
    except ExternalReferenceForbidden as error:
        raise DocumentError(
            "document",
            f"external entities are not allowed (a reference to {error.sysid!r} at line "
            f"{expat.CurrentLineNumber})",
        ) from None
    except ParseError as error:
        line, column = error.position
        reason = str(error).split(":")[0]
        raise DocumentError(
            "document", f"not well-formed XML at line {line}, column {column + 1}: {reason}"
        ) from None
    except (LookupError, ValueError) as error:
        # Raised by pyexpat's handler of a declared encoding it does not know itself
        # (LookupError for an unknown or a bytes-to-bytes codec, ValueError for a multi-byte
        # one, UnicodeError for a codec that refuses to decode): the builder raises only
        # DocumentError and defusedxml's refusals are caught above.
        raise DocumentError("document", _encoding_reason(document, error)) from None
    if not isinstance(root, Node):  # pragma: no cover - expat refuses a document without one
        raise DocumentError("document", "no root element")
    return root


def _encoding_reason(document: bytes | str, error: Exception) -> str:
    """Why the parser could not decode the document, naming the encoding it declares."""
    head = document[:_DECLARATION_CHARS]
    text = head if isinstance(head, str) else head.decode("latin-1")
    match = _ENCODING.search(text)
    name = f"encoding {match.group(1)!r}" if match else "declared encoding"
    return f"the {name} cannot be read ({error}): declare UTF-8, UTF-16 or a single-byte encoding"


def _check_size(document: bytes | str, limits: DocumentLimits) -> None:
    """Refuses a document over ``limits.max_bytes`` (a text one counted in UTF-8, which is
    what the parser reads it as) and a text one that no encoding can hold (a lone
    surrogate, which the parser would fail on with an error of another kind)."""
    size = len(document)
    if isinstance(document, str) and size <= limits.max_bytes:
        try:
            size = len(document.encode("utf-8"))
        except UnicodeEncodeError as error:
            line = document.count("\n", 0, error.start) + 1
            raise DocumentError(
                "document",
                f"not text: a lone surrogate at line {line} (character {error.start})",
            ) from None
    if size > limits.max_bytes:
        raise DocumentError("document", f"larger than {limits.max_bytes} bytes")


class _Builder:
    """The parser's target: builds :class:`Node` trees, refusing a document over the
    limits as soon as the element that crosses them starts."""

    def __init__(self, limits: DocumentLimits) -> None:
        self.limits = limits
        self.stack: list[Node] = []
        self.root: Node | None = None
        self.count = 0
        self.line: Callable[[], int] = lambda: 0

    def start(self, tag: str, attrib: dict[str, str]) -> None:
        namespace, _, local = tag[1:].partition("}") if tag.startswith("{") else ("", "", tag)
        node = Node(local, namespace in ("", SVG_NS), dict(attrib), self.line())
        self.count += 1
        if self.count > self.limits.max_elements:
            raise DocumentError(
                node.source, f"the document has more than {self.limits.max_elements} elements"
            )
        if len(self.stack) >= self.limits.max_depth:
            raise DocumentError(
                node.source, f"elements are nested deeper than {self.limits.max_depth}"
            )
        if self.stack:
            self.stack[-1].children.append(node)
        else:
            self.root = node
        self.stack.append(node)

    def end(self, tag: str) -> None:
        self.stack.pop()

    def data(self, text: str) -> None:
        pass  # text is not drawn (text elements are warned about, not read)

    def close(self) -> Node | None:
        return self.root
