"""Griffe extension of the docs build: Sphinx roles in docstrings (``:class:`~a.b.C```) read as code.

The source's docstrings cite other objects the Sphinx way (``:func:`rollaway.hold```), which reads
well in ``help()``; on the site (Markdown) the role itself would show.  This turns each role into
inline code: the target's last name with ``~``, else the name as written.
"""
from __future__ import annotations

import re

import griffe

ROLE = re.compile(r":(?:py:)?(?:class|func|meth|mod|data|attr|obj|exc):`(~?)([^`]+)`")


def plain(text: str) -> str:
    """*text* with every Sphinx role as inline code (``:class:`~a.b.C``` → ```C```)."""
    return ROLE.sub(lambda m: "`" + (m.group(2).rsplit(".", 1)[-1] if m.group(1) else m.group(2)) + "`", text)


class RstRoles(griffe.Extension):
    def on_instance(self, *, obj: griffe.Object, **kwargs) -> None:
        if obj.docstring is not None:
            obj.docstring.value = plain(obj.docstring.value)
