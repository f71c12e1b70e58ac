"""Reading rule fields from plain values (rules files), with errors that name the field."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from .rule import RuleError


def _wrong(key: str, wanted: str, value: Any) -> RuleError:
    return RuleError(f"{key}: expected {wanted}, got {type(value).__name__} {value!r}")


def read_str(fields: Mapping[str, Any], key: str, default: str = "") -> str:
    value = fields.get(key, default)
    if not isinstance(value, str):
        raise _wrong(key, "text", value)
    return value


def read_bool(fields: Mapping[str, Any], key: str, default: bool = False) -> bool:
    value = fields.get(key, default)
    if not isinstance(value, bool):
        raise _wrong(key, "true or false", value)
    return value


def read_int(fields: Mapping[str, Any], key: str) -> int | None:
    value = fields.get(key)
    if value is not None and (isinstance(value, bool) or not isinstance(value, int)):
        raise _wrong(key, "a whole number", value)
    return value


def read_str_list(fields: Mapping[str, Any], key: str) -> tuple[str, ...]:
    value = fields.get(key, [])
    if isinstance(value, str):
        value = [value]
    if not isinstance(value, list) or not all(isinstance(item, str) for item in value):
        raise _wrong(key, "a list of text", value)
    return tuple(value)
