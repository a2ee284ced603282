"""``ballcvt explore-ui``: the interactive explorer in the browser (Bokeh server)."""

from __future__ import annotations

from . import options as o
from .network import check_bind_address


def add_parser(subparsers) -> None:
    """Add ``explore-ui`` and its options."""
    p = o.sub(
        subparsers,
        "explore-ui",
        "interactive explorer in the browser: sliders, operating point, efficiency map",
        "Start a local web app (Bokeh server) with sliders for the ratio, output torque, "
        "clamping force, input speed and the main design parameters, showing the operating "
        "point (efficiency, losses, creeps, pressures, films), the efficiency map with the "
        "point on it and the limiting-torque curve. It binds to 127.0.0.1 (this machine "
        "only) unless --address says otherwise; Ctrl-C stops it.",
        "ballcvt explore-ui --design hub --port 5006",
    )
    o.add(p, "arch", *o.FLUID_OPTIONS)
    p.add_argument(
        "--port",
        type=o.count(0, 65535),
        default=5006,
        help="TCP port, 0 for any free one (default: 5006)",
    )
    p.add_argument(
        "--address",
        default="127.0.0.1",
        help="address to bind (default: 127.0.0.1, this machine only)",
    )
    p.add_argument("--show", action="store_true", help="open the page in the browser")


def run(args) -> int:
    """Serve the explorer until interrupted."""
    from ..ui import serve

    address = check_bind_address(args.address)  # bad input: before the server starts
    v = o.variator(args)
    serve(
        v.design,
        v.fluid,
        architecture=v.architecture,
        port=args.port,
        address=address,
        show=args.show,
    )
    return 0
