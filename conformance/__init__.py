"""Conformance harness: drive implementations with identical scenarios, compare pair by pair."""

from conformance.protocol import (
    MODEL,
    Backend,
    Command,
    ErrorInfo,
    ErrorKind,
    LocationState,
    Observation,
    Result,
)

__all__ = [
    "MODEL",
    "Backend",
    "Command",
    "ErrorInfo",
    "ErrorKind",
    "LocationState",
    "Observation",
    "Result",
]
