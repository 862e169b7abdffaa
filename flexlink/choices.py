"""A choice given as text (a command-line option, a scene key, a Python argument) turned into
its enum member at the edge, so that the stages inside compare members, never strings."""

from __future__ import annotations

import enum
from typing import TypeVar

from flexlink.errors import InputError

Choice = TypeVar("Choice", bound=enum.StrEnum)


def spelled(kind: type[enum.StrEnum]) -> str:
    """The choices of ``kind`` as text: "auto, dense or sparse"."""
    values = [member.value for member in kind]
    return values[0] if len(values) == 1 else ", ".join(values[:-1]) + " or " + values[-1]


def parse_choice(kind: type[Choice], value, field: str) -> Choice:
    """``value`` (a member of ``kind`` or its text) as a member of ``kind``; InputError naming
    ``field`` and the choices when it is none of them."""
    try:
        return kind(value)
    except ValueError:
        raise InputError(f"{value!r} is not a choice", field=field,
                         expected=spelled(kind)) from None
