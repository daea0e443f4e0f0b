"""Packages that are also functions: ``rollaway.hold(...)`` and ``rollaway.sweep(...)``.

``rollaway.hold`` is both the package of the hold check (``from rollaway.hold import
required_torque`` keeps working) and the public function :func:`rollaway.api.hold`.  Python sets
``rollaway.hold`` to the package whenever it is imported, so the package itself is made
callable: calling it calls the API function.  Nothing else is changed.
"""
from __future__ import annotations

import importlib
import sys
import types


class CallableModule(types.ModuleType):
    """A module whose call forwards to the function named by ``__call_target__`` (``"module:function"``)."""

    def __call__(self, *args, **kwargs):
        module, name = self.__call_target__.split(":")
        return getattr(importlib.import_module(module), name)(*args, **kwargs)


def make_callable(module_name: str, target: str) -> None:
    """Make the module *module_name* callable as *target* (``"rollaway.api:hold"``)."""
    module = sys.modules[module_name]
    module.__class__ = CallableModule
    module.__call_target__ = target
