"""Network addresses of ``explore --scheduler`` and ``explore-ui --address``, checked before
anything starts: a malformed address is bad input (exit 2), an unreachable scheduler an
environment failure (exit 1), each in one line and within seconds."""

from __future__ import annotations

import errno
import ipaddress
import re
import socket

from ...errors import InputError

__all__ = ["CONNECT_TIMEOUT", "check_bind_address", "check_scheduler"]

#: Seconds to wait for a Dask scheduler to accept a connection [s].
CONNECT_TIMEOUT = 5.0
#: Schemes whose scheduler is reached over TCP (others, e.g. ``inproc``, are not probed).
_TCP_SCHEMES = ("tcp", "tls")
#: A host name (RFC 1123 labels).
_LABEL = r"[A-Za-z0-9]([A-Za-z0-9-]{0,61}[A-Za-z0-9])?"
_HOSTNAME = re.compile(rf"^(?=.{{1,253}}$){_LABEL}(\.{_LABEL})*$")


def _host(text: str, flag: str, example: str) -> str:
    """``text`` if it is an IP address or a well-formed host name, else `InputError`."""
    try:
        return str(ipaddress.ip_address(text.strip("[]")))
    except ValueError:
        pass
    if re.fullmatch(r"[0-9.]+", text) or not _HOSTNAME.match(text):
        # all digits and dots but not an IPv4 address (999.999.1.1): never a host name
        raise InputError(
            flag,
            text,
            example,
            message=f"{flag} {text!r} is not a valid "
            f"address: allowed an IP address or a host name, e.g. {example}",
        )
    return text


def check_bind_address(address: str) -> str:
    """The ``--address`` of ``explore-ui``, checked: an IP address or a host name that
    resolves (`InputError` otherwise, before the server starts)."""
    host = _host(address, "--address", "127.0.0.1")
    try:
        socket.getaddrinfo(host, None)
    except (socket.gaierror, UnicodeError):
        raise InputError(
            "--address",
            address,
            "a host name that resolves",
            message=f"--address {address!r}: no such host",
        ) from None
    return host


def check_scheduler(address: str, timeout: float = CONNECT_TIMEOUT) -> None:
    """Check that the Dask scheduler at ``address`` (``tcp://HOST:PORT``) accepts a
    connection within ``timeout`` [s].

    Raises
    ------
    InputError
        The address is malformed (exit status 2).
    OSError
        The scheduler cannot be reached (exit status 1), naming the address and the cause.
    """
    scheme, sep, rest = address.partition("://")
    if not sep:
        scheme, rest = "tcp", address
    if scheme not in _TCP_SCHEMES:
        return  # another transport: left to Dask
    host, colon, port = rest.rpartition(":")
    if not colon:
        host, port = rest, "8786"
    if not port.isdigit() or not 0 < int(port) < 65536:
        raise InputError(
            "--scheduler",
            address,
            "tcp://HOST:PORT",
            message=f"--scheduler {address!r} is not a valid address: allowed "
            "tcp://HOST:PORT with a port 1-65535",
        )
    host = _host(host, "--scheduler", "tcp://10.0.0.1:8786")
    try:
        with socket.create_connection((host, int(port)), timeout=timeout):
            pass
    except OSError as exc:
        cause = "timed out" if isinstance(exc, TimeoutError) else (exc.strerror or str(exc))
        raise OSError(
            exc.errno or errno.ETIMEDOUT, f"cannot reach the Dask scheduler at {address}: {cause}"
        ) from None
