"""Messages to the user, shown literally and without anything of the server's.

Streamlit renders the text of ``st.error`` as Markdown: a value the user typed or uploaded,
echoed in a message, would become a link (``[click me](http://example.com)``), bold text
(``__import__`` shown as "import") or an emoji. Every message the app shows goes through
:func:`show_error`, which

* removes what looks like a path on the server (the temporary folder, any absolute path): a
  second line of defence behind the readers, which name uploaded files by their base name
  only;
* escapes every Markdown character, so that the text reads exactly as written;
* breaks what GitHub-flavoured Markdown would turn into a link by itself (``http://...``,
  ``www.``, an e-mail address: Streamlit links them even when escaped) with an invisible
  word joiner (U+2060) after the scheme, ``www`` or ``@``.
"""

from __future__ import annotations

import re
import tempfile
from typing import Any

#: What replaces a server path in a message.
PATH_PLACEHOLDER = "<path>"

#: Characters with a meaning in Streamlit's Markdown (CommonMark, GitHub tables and
#: strikethrough, LaTeX ``$``, colour and emoji ``:...:``): each is backslash-escaped.
_MARKDOWN = re.compile(r"([\\`*_{}\[\]()#+\-.!|<>~$:&\"'=^%@;/,?])")
#: Where GitHub-flavoured Markdown starts a link of its own: after "http:", "www", "@".
_AUTOLINK = re.compile(r"(?i)(\bhttps?:|\bwww(?=\.)|@)")
#: The invisible character that keeps them text.
WORD_JOINER = "\u2060"
#: A POSIX absolute path (two segments at least: "/etc/shadow", not a unit's "/s") or a
#: Windows one ("C:\\...", "\\\\server\\share"), not preceded by a word character ("N*s/m").
_ABSOLUTE_PATH = re.compile(
    r"(?<![\w.:/])/(?:[\w.\-~@+]+/)+[\w.\-~@+]*"
    r"|\b[A-Za-z]:\\[^\s'\"]*"
    r"|\\\\[^\s'\"]+"
)


#: Longest message shown, in characters: an upload's 100,000 unknown tables or 500,000 record
#: columns made one-line refusals of up to 4.5 MB (an independent audit). A longer message
#: keeps its start and its end (where the reason and the allowed values are) around a count.
MAX_MESSAGE = 600
#: Characters kept from the end of a shortened message.
MESSAGE_TAIL = 200


def shortened(text: str) -> str:
    """``text`` if it has at most :data:`MAX_MESSAGE` characters, else its start and end
    around ``[... N characters ...]``.

    Parameters
    ----------
    text : str
        A one-line message.

    Returns
    -------
    str
        At most about :data:`MAX_MESSAGE` characters.
    """
    if len(text) <= MAX_MESSAGE:
        return text
    head = MAX_MESSAGE - MESSAGE_TAIL
    left = len(text) - head - MESSAGE_TAIL
    return f"{text[:head]} [... {left:,} characters ...] {text[-MESSAGE_TAIL:]}"


def sanitised(message: str) -> str:
    """``message`` on one line, with the server's temporary folder and absolute paths removed.

    Parameters
    ----------
    message : str
        The text of an exception or of a refusal.

    Returns
    -------
    str
        The same words, every path replaced by :data:`PATH_PLACEHOLDER`, shortened to
        :data:`MAX_MESSAGE` characters (:func:`shortened`).
    """
    text = " ".join(str(message).split())
    for folder in {tempfile.gettempdir(), "/tmp", "/var/tmp"}:
        text = text.replace(folder, PATH_PLACEHOLDER)
    text = _ABSOLUTE_PATH.sub(PATH_PLACEHOLDER, text)
    # "<path>/stickslip-abc/x.csv" -> "<path>"
    return shortened(re.sub(re.escape(PATH_PLACEHOLDER) + r"[^\s'\"()\[\];,]*", PATH_PLACEHOLDER, text))


def literal_markdown(text: str) -> str:
    """``text`` escaped so that Markdown shows it character for character (and unlinked)."""
    return _MARKDOWN.sub(r"\\\1", _AUTOLINK.sub(r"\1" + WORD_JOINER, text))


def show_error(message: str, where: Any = None) -> None:
    """Show ``message`` in a red box, sanitised (:func:`sanitised`) and literally.

    Parameters
    ----------
    message : str
        The message (one line; whitespace is collapsed).
    where : Streamlit container, optional
        Where to show it (default: the page, ``st``).
    """
    import streamlit as st

    (where or st).error(literal_markdown(sanitised(message)))


def show_warning(message: str, where: Any = None) -> None:
    """Show ``message`` in a yellow box, as :func:`show_error` does (sanitised, literal)."""
    import streamlit as st

    (where or st).warning(literal_markdown(sanitised(message)))


def show_info(message: str, where: Any = None) -> None:
    """Show ``message`` in a blue box, as :func:`show_error` does (sanitised, literal)."""
    import streamlit as st

    (where or st).info(literal_markdown(sanitised(message)))


def show_unexpected(exc: BaseException, what: str, where: Any = None) -> None:
    """An error nobody foresaw: its traceback goes to the server's log, one line to the page.

    Parameters
    ----------
    exc : BaseException
        The exception caught.
    what : str
        What failed, e.g. "The design of this machine".
    where : Streamlit container, optional
        Where to show it (default: the page).
    """
    import logging

    logging.getLogger("stickslip.app").error("%s failed", what, exc_info=exc)
    show_error(f"{what} failed unexpectedly ({type(exc).__name__}: {exc}); the server's log "
               "has the details", where)


def show_failure(exc: BaseException, what: str) -> None:
    """A computation of the page failed: say so in the form its kind calls for.

    Every worker busy (:class:`stickslip.app.workers.Busy`): a warning to try again; an input
    the model refuses or a computation over its time limit (``ValueError``,
    ``TimeoutError``): its one-line message; anything else: :func:`show_unexpected`.

    Parameters
    ----------
    exc : BaseException
        The exception caught.
    what : str
        What failed, e.g. "The fit of this record".
    """
    from stickslip.app.workers import Busy

    if isinstance(exc, Busy):
        show_warning(str(exc))
    elif isinstance(exc, (ValueError, TimeoutError)):
        show_error(str(exc))
    else:  # no traceback on the page (it names the server's files)
        show_unexpected(exc, what)
